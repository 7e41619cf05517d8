"""Saving and loading of result objects (frozen dataclasses) with their parameters and library version.

A result class inherits :class:`SavableResult`; ``result.save(path)`` writes a ``.npz`` file in which every
array field is stored as an array and every other field (numbers, strings, dicts, tuples, a
``surfaces.Grid``, an interaction law) in the JSON metadata record, together with the class name and
``roughcontact`` version; a result held in a field (a path's results, a pull-off's last equilibrium) is stored
the same way, its arrays named ``field.name`` (``field.index.name`` in a tuple), and the shape and dtype of
every array are recorded. ``ResultClass.load(path)`` gives back an equal object, with read-only arrays (as a
pickled result does); a file that is not such a result, or whose arrays differ from their record, is a
``ValueError`` naming the file. A dataclass held in a field is rebuilt from its registered class
(:func:`savable_field`) or, failing that, from its class if that derives from a registered class's base (a
user's own interaction law) and its module is imported in this session; otherwise it loads as a dict of its
fields, with a warning naming the class.
"""
from __future__ import annotations

import dataclasses
import os
import sys
import warnings
from pathlib import Path

import numpy as np

from surfaces import Grid
from surfaces.io import UnreadableFile, load_npz, save_npz

from .._version import __version__

_GRID_TAG = "__surfaces.Grid__"


def _encode(value):
    if isinstance(value, Grid):
        return {_GRID_TAG: value.to_dict()}
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return {"__dataclass__": type(value).__qualname__, "__module__": type(value).__module__,
                **{f.name: _encode(getattr(value, f.name)) for f in dataclasses.fields(value)}}
    if isinstance(value, dict):
        return {k: _encode(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return type(value)(_encode(v) for v in value)      # save_npz keeps a tuple apart from a list
    if value is None or isinstance(value, (str, int, float, np.generic, np.ndarray)):   # (an array in a dict: a list)
        return value
    raise TypeError(f"a {type(value).__qualname__} cannot be saved: a field holds arrays, numbers, strings, "
                    "dicts, lists, tuples, a surfaces.Grid or dataclasses of these (a user's interaction law must "
                    "be a frozen dataclass)")


#: The dataclasses a result may hold as a field, by qualified name: registered by the module that defines the
#: result's field types (:mod:`roughcontact.interactions` registers its laws and the dielectric stack), so that
#: this module imports nothing above it.
FIELD_TYPES: dict = {}


def savable_field(kind: type) -> type:
    """Register the dataclass ``kind`` as one a result may hold as a field (saved by its qualified name)."""
    FIELD_TYPES[kind.__qualname__] = kind
    return kind


def _field_type(record: dict, unknown: set):
    """The class of a stored dataclass ``record``: registered, or a subclass of a registered class's base (a
    user's own interaction law) defined in a module imported in this session (never imported here: loading a
    file runs no module's code); None, with its name added to ``unknown``."""
    name, module = record["__dataclass__"], record.get("__module__")
    kind = FIELD_TYPES.get(name)
    if kind is None and module in sys.modules:
        kind = sys.modules[module]
        for part in name.split("."):
            kind = getattr(kind, part, None)
        bases = tuple({base for registered in FIELD_TYPES.values() for base in registered.__mro__[:-1]})
        if not (isinstance(kind, type) and dataclasses.is_dataclass(kind) and issubclass(kind, bases)):
            kind = None
    if kind is None:
        unknown.add(name if module is None else f"{module}.{name}")
    return kind


def _decode(value, unknown: set):
    if isinstance(value, dict) and _GRID_TAG in value:
        return Grid.from_dict(value[_GRID_TAG])
    if isinstance(value, dict) and "__dataclass__" in value:
        fields = {k: _decode(v, unknown) for k, v in value.items() if k not in ("__dataclass__", "__module__")}
        kind = _field_type(value, unknown)
        return fields if kind is None else kind(**fields)
    if isinstance(value, dict):
        return {k: _decode(v, unknown) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return type(value)(_decode(v, unknown) for v in value)
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
            try:
                fields[f.name] = _encode(value)
            except TypeError as error:
                raise TypeError(f"{type(result).__qualname__}.{f.name}: {error}") from None
    return fields


def _join(kind, fields, arrays, prefix, unknown: set):
    """The ``kind`` result from its metadata record and the arrays stored under ``prefix`` (inverse of _split);
    ``unknown`` collects the stored dataclasses whose class is not found (loaded as dicts)."""
    def rebuilt(value, key):
        if isinstance(value, dict) and _RESULT_TAG in value:
            nested = _result_types().get(value[_RESULT_TAG])
            if nested is None:
                raise ValueError(f"its field {key} holds a {value[_RESULT_TAG]!r}, a result class not defined now")
            return _join(nested, value["fields"], arrays, key + ".", unknown)
        if isinstance(value, tuple) and value and all(isinstance(v, dict) and _RESULT_TAG in v for v in value):
            return tuple(rebuilt(v, f"{key}.{i}") for i, v in enumerate(value))
        return _decode(value, unknown)

    kwargs = {name: rebuilt(value, prefix + name) for name, value in fields.items()}
    for key, array in arrays.items():
        name = key[len(prefix):]
        if key.startswith(prefix) and "." not in name:
            array.flags.writeable = False     # results are immutable: read-only as when they were made
            kwargs[name] = array
    names = {f.name for f in dataclasses.fields(kind)}
    required = {f.name for f in dataclasses.fields(kind)
                if f.default is dataclasses.MISSING and f.default_factory is dataclasses.MISSING}
    extra, missing = sorted(set(kwargs) - names), sorted(required - set(kwargs))
    if extra or missing:
        problems = [f"the fields {', '.join(extra)} that a {kind.__qualname__} does not have"] if extra else []
        raise ValueError(f"its {kind.__qualname__} record has " + " and ".join(
            problems + ([f"no {', '.join(missing)}"] if missing else [])))
    return kind(**kwargs)


def _array_record(arrays: dict) -> dict:
    """``{name: [shape, dtype]}`` of the arrays of a saved result."""
    return {name: [list(array.shape), array.dtype.str] for name, array in arrays.items()}


def _read(path) -> tuple:
    """``(arrays, metadata)`` of a saved result; a ValueError naming ``path`` if it is not one (the file's absence
    or permissions stay an OSError, which names it)."""
    if not isinstance(path, (str, os.PathLike)):
        raise TypeError(f"path must be a str or os.PathLike, got {type(path).__name__}")
    try:
        arrays, metadata = load_npz(path)
    except UnreadableFile as error:
        raise ValueError(f"{path} is not a saved result: {error.reason}") from None
    except TypeError as error:
        raise ValueError(f"{path} is not a saved result: not a readable .npz archive ({error})") from None
    if not isinstance(metadata, dict) or not isinstance(metadata.get("fields"), dict):
        raise ValueError(f"{path} is not a saved result: its metadata record has no fields")
    stored, expected = _array_record(arrays), metadata.get("arrays")
    if expected is None:
        raise ValueError(f"{path} is not a saved result: its metadata has no record of its arrays")
    if not isinstance(expected, dict):
        raise ValueError(f"{path} is not a saved result: its record of arrays is not a table")
    if stored != expected:
        def described(record, name):
            return "missing" if name not in record else f"{tuple(record[name][0])} {record[name][1]}"

        changed = [f"{name}: {described(expected, name)} -> {described(stored, name)}"
                   for name in sorted({*stored, *expected}) if stored.get(name) != expected.get(name)]
        raise ValueError(f"{path}: its arrays differ from the shapes and dtypes recorded when it was saved (the file "
                         f"was altered): {'; '.join(changed)}")
    return arrays, metadata


class SavableResult:
    """Mixin giving frozen dataclasses ``save``/``load`` to ``.npz`` (see module docstring); a result held in a
    field (or a tuple of them) is saved and loaded with it."""

    def save(self, path) -> Path:
        arrays = {}
        fields = _split(self, "", arrays)
        metadata = {"kind": type(self).__qualname__, "version": __version__, "fields": fields,
                    "arrays": _array_record(arrays)}
        return save_npz(path, arrays, metadata)

    @classmethod
    def load(cls, path):
        arrays, metadata = _read(path)
        if metadata.get("kind") != cls.__qualname__:
            raise ValueError(f"{path} holds a {metadata.get('kind')!r}, not a {cls.__qualname__}")
        unknown = set()
        try:
            result = _join(cls, metadata["fields"], arrays, "", unknown)
        except (TypeError, ValueError) as error:
            raise ValueError(f"{path}: {error}") from None
        if unknown:
            warnings.warn(f"{path}: cannot rebuild {', '.join(sorted(unknown))}: not registered with "
                          "roughcontact.io.savable_field, nor a subclass of a registered class's base (a user's "
                          "interaction law) in a module imported now; loaded as a dict of its fields (import its "
                          "module, or register the class, before loading to rebuild it)", stacklevel=2)
        return result

    def __setstate__(self, state: dict):
        """Unpickling: the arrays read-only, as when the result was made."""
        for value in state.values():
            for array in value if isinstance(value, tuple) else (value,):
                if isinstance(array, np.ndarray):
                    array.flags.writeable = False
        self.__dict__.update(state)


class ConvergenceWarning(UserWarning):
    """An iterative solver stopped before meeting its tolerance; the result says so (``converged=False``)."""
