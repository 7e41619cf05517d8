"""The electrostatics of the layered stack: stratum corneum | air gap | insulator (Heß & Forsbach 2020).

:mod:`~roughcontact.electrostatics.stack` holds the seed's parallel-plate capacitor (Eqs. 18–25), pure numpy:
importing this package loads neither numba nor an FFT library.
"""
from __future__ import annotations

from .stack import EPSILON_0, DielectricStack, ElectricFields

__all__ = ["EPSILON_0", "DielectricStack", "ElectricFields"]
