"""Self-describing ``.npz`` files: named arrays plus a JSON metadata record (tuples come back as tuples).

One writer and one reader serve every saved object of the project (height fields here, contact and
sweep results in ``roughcontact``), so provenance is stored the same way everywhere.
"""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np

_METADATA_KEY = "__metadata_json__"
_TUPLE_TAG = "__tuple__"          # JSON has no tuple: {"__tuple__": [...]} keeps one apart from a list


def _jsonable(value):
    if isinstance(value, dict):
        return {str(k): _jsonable(v) for k, v in value.items()}
    if isinstance(value, tuple):
        return {_TUPLE_TAG: [_jsonable(v) for v in value]}
    if isinstance(value, list):
        return [_jsonable(v) for v in value]
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.tolist()
    return value


def save_npz(path, arrays: dict, metadata: dict) -> Path:
    """Write ``arrays`` and the JSON-serialisable ``metadata`` to a compressed ``.npz`` file; return its path."""
    path = Path(path)
    if path.suffix != ".npz":
        path = path.with_suffix(path.suffix + ".npz") if path.suffix else path.with_suffix(".npz")
    if _METADATA_KEY in arrays:
        raise ValueError(f"array name {_METADATA_KEY!r} is reserved")
    encoded = np.frombuffer(json.dumps(_jsonable(metadata), sort_keys=True).encode("utf-8"), dtype=np.uint8)
    np.savez_compressed(path, **arrays, **{_METADATA_KEY: encoded})
    return path


def _restore_tuple(record: dict):
    return tuple(record[_TUPLE_TAG]) if record.keys() == {_TUPLE_TAG} else record


def load_npz(path) -> tuple:
    """Read a file written by :func:`save_npz`; return ``(arrays, metadata)``."""
    with np.load(Path(path), allow_pickle=False) as data:
        if _METADATA_KEY not in data:
            raise ValueError(f"{path} has no metadata record; it was not written by save_npz")
        metadata = json.loads(data[_METADATA_KEY].tobytes().decode("utf-8"), object_hook=_restore_tuple)
        arrays = {name: data[name] for name in data.files if name != _METADATA_KEY}
    return arrays, metadata
