"""Saving and loading of result objects (frozen dataclasses) with their parameters and library version.

A result class inherits :class:`SavableResult`; ``result.save(path)`` writes a ``.npz`` file in which every
array field is stored as an array and every other field (numbers, strings, dicts, tuples, a
``surfaces.Grid``, an interaction law) in the JSON metadata record, together with the class name and
``roughcontact`` version; a result held in a field (a path's results, a pull-off's last equilibrium) is stored
the same way, its arrays named ``field.name`` (``field.index.name`` in a tuple). ``ResultClass.load(path)``
gives back an equal object, with read-only arrays.
"""
from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np

from surfaces import Grid
from surfaces.io import load_npz, save_npz

from .._version import __version__

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


#: The dataclasses a result may hold as a field, by qualified name: registered by the module that defines the
#: result's field types (:mod:`roughcontact.interactions` registers its laws and the dielectric stack), so that
#: this module imports nothing above it.
FIELD_TYPES: dict = {}


def savable_field(kind: type) -> type:
    """Register the dataclass ``kind`` as one a result may hold as a field (saved by its qualified name)."""
    FIELD_TYPES[kind.__qualname__] = kind
    return kind


def _decode(value):
    if isinstance(value, dict) and _GRID_TAG in value:
        return Grid.from_dict(value[_GRID_TAG])
    if isinstance(value, dict) and (kind := FIELD_TYPES.get(value.get("__dataclass__"))) is not None:
        return kind(**{k: _decode(v) for k, v in value.items() if k != "__dataclass__"})
    if isinstance(value, dict):
        return {k: _decode(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return type(value)(_decode(v) for v in value)
    return value


_RESULT_TAG = "__result__"


def _result_types() -> dict:
    """Every :class:`SavableResult` subclass defined so far, by qualified name (for nested results)."""
    found, pending = {}, list(SavableResult.__subclasses__())
    while pending:
        kind = pending.pop()
        found[kind.__qualname__] = kind
        pending.extend(kind.__subclasses__())
    return found


def _split(result, prefix, arrays) -> dict:
    """The metadata record of ``result``'s fields; its arrays, and those of results nested in it (a field, or a
    tuple of them), go into ``arrays`` under ``prefix`` + the field's name (+ ``.index``)."""
    fields = {}
    for f in dataclasses.fields(result):
        value, key = getattr(result, f.name), prefix + f.name
        if isinstance(value, np.ndarray):
            arrays[key] = value
        elif isinstance(value, SavableResult):
            fields[f.name] = {_RESULT_TAG: type(value).__qualname__, "fields": _split(value, key + ".", arrays)}
        elif isinstance(value, tuple) and value and all(isinstance(v, SavableResult) for v in value):
            fields[f.name] = tuple({_RESULT_TAG: type(v).__qualname__, "fields": _split(v, f"{key}.{i}.", arrays)}
                                   for i, v in enumerate(value))
        else:
            fields[f.name] = _encode(value)
    return fields


def _join(kind, fields, arrays, prefix):
    """The ``kind`` result from its metadata record and the arrays stored under ``prefix`` (inverse of _split)."""
    def rebuilt(value, key):
        if isinstance(value, dict) and _RESULT_TAG in value:
            return _join(_result_types()[value[_RESULT_TAG]], value["fields"], arrays, key + ".")
        if isinstance(value, tuple) and value and all(isinstance(v, dict) and _RESULT_TAG in v for v in value):
            return tuple(rebuilt(v, f"{key}.{i}") for i, v in enumerate(value))
        return _decode(value)

    kwargs = {name: rebuilt(value, prefix + name) for name, value in fields.items()}
    for key, array in arrays.items():
        name = key[len(prefix):]
        if key.startswith(prefix) and "." not in name:
            array.flags.writeable = False     # results are immutable: read-only as when they were made
            kwargs[name] = array
    for f in dataclasses.fields(kind):        # files written before save_npz kept tuples stored them as lists
        if isinstance(kwargs.get(f.name), list) and "tuple" in str(f.type):
            kwargs[f.name] = tuple(kwargs[f.name])
    return kind(**kwargs)


class SavableResult:
    """Mixin giving frozen dataclasses ``save``/``load`` to ``.npz`` (see module docstring); a result held in a
    field (or a tuple of them) is saved and loaded with it."""

    def save(self, path) -> Path:
        arrays = {}
        fields = _split(self, "", arrays)
        metadata = {"kind": type(self).__qualname__, "version": __version__, "fields": fields}
        return save_npz(path, arrays, metadata)

    @classmethod
    def load(cls, path):
        arrays, metadata = load_npz(path)
        if metadata.get("kind") != cls.__qualname__:
            raise ValueError(f"{path} holds a {metadata.get('kind')!r}, not a {cls.__qualname__}")
        return _join(cls, metadata["fields"], arrays, "")


class ConvergenceWarning(UserWarning):
    """An iterative solver stopped before meeting its tolerance; the result says so (``converged=False``)."""
