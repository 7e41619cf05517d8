"""Saving and loading of result objects (frozen dataclasses) with their parameters and library version.

A result class inherits :class:`SavableResult`; ``result.save(path)`` writes a ``.npz`` file in which every
array field is stored as an array and every other field (numbers, strings, dicts, tuples, a
``surfaces.Grid``) in the JSON metadata record, together with the class name and ``roughcontact`` version.
``ResultClass.load(path)`` gives back an equal object, with read-only arrays.
"""
from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np

from surfaces import Grid
from surfaces.io import load_npz, save_npz

from ._version import __version__

_GRID_TAG = "__surfaces.Grid__"


def _encode(value):
    if isinstance(value, Grid):
        return {_GRID_TAG: value.to_dict()}
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return {"__dataclass__": type(value).__qualname__,
                **{f.name: _encode(getattr(value, f.name)) for f in dataclasses.fields(value)}}
    if isinstance(value, dict):
        return {k: _encode(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return type(value)(_encode(v) for v in value)      # save_npz keeps a tuple apart from a list
    return value


def _dataclass_types() -> dict:
    """The dataclasses a result may hold as a field, by name (the interaction laws and the dielectric stack)."""
    from .electrostatics import DielectricStack
    from .interactions import LAWS
    return {**LAWS, "DielectricStack": DielectricStack}


def _decode(value):
    if isinstance(value, dict) and _GRID_TAG in value:
        return Grid.from_dict(value[_GRID_TAG])
    if isinstance(value, dict) and value.get("__dataclass__") in _dataclass_types():
        kind = _dataclass_types()[value["__dataclass__"]]
        return kind(**{k: _decode(v) for k, v in value.items() if k != "__dataclass__"})
    if isinstance(value, dict):
        return {k: _decode(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return type(value)(_decode(v) for v in value)
    return value


class SavableResult:
    """Mixin giving frozen dataclasses ``save``/``load`` to ``.npz`` (see module docstring)."""

    def save(self, path) -> Path:
        arrays, fields = {}, {}
        for f in dataclasses.fields(self):
            value = getattr(self, f.name)
            if isinstance(value, np.ndarray):
                arrays[f.name] = value
            else:
                fields[f.name] = _encode(value)
        metadata = {"kind": type(self).__qualname__, "version": __version__, "fields": fields}
        return save_npz(path, arrays, metadata)

    @classmethod
    def load(cls, path):
        arrays, metadata = load_npz(path)
        if metadata.get("kind") != cls.__qualname__:
            raise ValueError(f"{path} holds a {metadata.get('kind')!r}, not a {cls.__qualname__}")
        kwargs = {name: _decode(value) for name, value in metadata["fields"].items()}
        for array in arrays.values():         # results are immutable: read-only as when they were made
            array.flags.writeable = False
        kwargs.update(arrays)
        for f in dataclasses.fields(cls):     # files written before save_npz kept tuples stored them as lists
            if isinstance(kwargs.get(f.name), list) and "tuple" in str(f.type):
                kwargs[f.name] = tuple(kwargs[f.name])
        return cls(**kwargs)


class ConvergenceWarning(UserWarning):
    """An iterative solver stopped before meeting its tolerance; the result says so (``converged=False``)."""
