"""The electrostatics of the layered stack: stratum corneum | air gap | insulator (Heß & Forsbach 2020).

:mod:`~roughcontact.electrostatics.stack` holds the seed's parallel-plate capacitor (Eqs. 18–25), pure numpy:
importing this package loads neither numba nor an FFT library. :mod:`~roughcontact.electrostatics.field` solves
the layered stack's field over a gap field (``solve_field``), :mod:`~roughcontact.electrostatics.ac` the same under an
AC or DC drive with a leaky stratum corneum and, for a :class:`LeakyStack`, a leak across the skin–screen interface
(``solve_ac_field``), both loaded on first use; :mod:`~roughcontact.electrostatics.contact_line` the models of the
contact line that give the layered field a finite strength there (``AirBreakdown``, ``RoughnessFilm``).
"""
from __future__ import annotations

from surfaces.lazy import lazy_attributes

from .contact_line import AIR_BREAKDOWN_FIELD, AirBreakdown, RoughnessFilm
from .stack import EPSILON_0, DielectricStack, ElectricFields, LeakyStack

# the field model loads the FFT backends: imported on first use
_LAZY = {"solve_field": "field", "FieldSolution": "field", "StackField": "field",
         "solve_ac_field": "ac", "ACFieldSolution": "ac", "ACStackField": "ac", "crossover_frequency": "ac",
         "circuit_thickness": "ac"}

__getattr__, __dir__, __all__ = lazy_attributes(__name__, _LAZY, ["EPSILON_0", "DielectricStack", "ElectricFields",
                                                                    "LeakyStack", "AIR_BREAKDOWN_FIELD", "AirBreakdown",
                                                                    "RoughnessFilm"])
