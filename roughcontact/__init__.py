"""roughcontact — multiscale electrostatic contact of rough surfaces.

Submodules are imported lazily (PEP 562), so ``import roughcontact`` and the pure-numpy modules
``roughcontact.electrostatics`` and ``roughcontact.macro`` never load numba or an FFT library.
"""
from __future__ import annotations

from surfaces.lazy import lazy_attributes

from ._version import __version__

# public name -> submodule that defines it
_LAZY = {
    "DielectricStack": "electrostatics",
    "LeakyStack": "electrostatics",
    "AirBreakdown": "electrostatics",
    "RoughnessFilm": "electrostatics",
    "PowerLawContact": "macro",
    "SlidingFrictionModel": "macro",
    "ElasticHalfSpace": "body",
    "solve_contact": "solvers",
    "load_path": "solvers",
    "voltage_path": "solvers",
    "ContactResult": "solvers",
    "ContactProblem": "solvers",
    "HardWall": "interactions",
    "ElectrostaticInteraction": "interactions",
    "ExponentialAdhesion": "interactions",
    "MaugisDugdale": "interactions",
    "load_scene": "study.scene",
    "run_study": "study.run",
}

__getattr__, __dir__, __all__ = lazy_attributes(__name__, _LAZY, ["__version__"])
