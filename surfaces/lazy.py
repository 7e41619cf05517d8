"""Lazy package attributes (PEP 562), shared by ``surfaces`` and ``roughcontact``.

Heavy submodules (scipy.fft, numba, pyFFTW users) load on first attribute access, so importing a package
stays cheap for code that only needs its light parts.
"""
import importlib


def lazy_attributes(package: str, lazy: dict, eager: list) -> tuple:
    """Return ``(__getattr__, __dir__, __all__)`` for ``package``.

    ``lazy`` maps each public name to the submodule (relative to ``package``) that defines it; ``eager`` lists
    the names the package imports itself.
    """
    names = list(eager) + list(lazy)
    namespace = importlib.import_module(package).__dict__

    def __getattr__(name):
        if name in lazy:
            value = getattr(importlib.import_module(f".{lazy[name]}", package), name)
            namespace[name] = value
            return value
        raise AttributeError(f"module {package!r} has no attribute {name!r}")

    def __dir__():
        return names

    return __getattr__, __dir__, names
