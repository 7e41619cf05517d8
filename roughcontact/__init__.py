"""roughcontact — multiscale electrostatic contact of rough surfaces.

Submodules are imported lazily (PEP 562), so ``import roughcontact`` and the pure-numpy modules
``roughcontact.electrostatics`` and ``roughcontact.macro`` never load numba or an FFT library.
"""
from __future__ import annotations

import importlib

from ._version import __version__

# public name -> submodule that defines it
_LAZY = {
    "DielectricStack": "electrostatics",
    "PowerLawContact": "macro",
    "SlidingFrictionModel": "macro",
    "ElasticHalfSpace": "elastic",
    "solve_contact": "contact",
    "load_path": "contact",
    "ContactResult": "contact",
}

__all__ = sorted(_LAZY) + ["__version__"]


def __getattr__(name):
    if name in _LAZY:
        value = getattr(importlib.import_module(f".{_LAZY[name]}", __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'roughcontact' has no attribute {name!r}")


def __dir__():
    return __all__
