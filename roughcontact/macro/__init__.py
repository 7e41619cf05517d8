"""The seed paper's macroscopic model (Heß & Forsbach 2020): adhesive power-law contacts (Eqs. 1–14), peeling
(Eqs. 29–33), equivalent-gap models (Eq. 46), a tabulated ridge area (the role of Eq. 9) and sliding friction
under electroadhesion (Eqs. 35–45).

Pure numpy: importing it loads neither numba nor an FFT library. Equation map: ``docs/guide/friction_model.md``.
"""
from .area import TabulatedArea
from .friction import SlidingFrictionModel, SlidingState
from .gap import ConstantGap, LinearGap, PowerLawGap, TabulatedGap
from .peeling import SavkoorBriggsPeeling, hutchinson_suo_toughness
from .power_law import PowerLawContact, PullOff

__all__ = ["ConstantGap", "LinearGap", "PowerLawContact", "PowerLawGap", "PullOff", "SavkoorBriggsPeeling",
           "SlidingFrictionModel", "SlidingState", "TabulatedArea", "TabulatedGap", "hutchinson_suo_toughness"]
