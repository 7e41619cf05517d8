"""Self-describing ``.npz`` files: named arrays plus a JSON metadata record.

One writer and one reader serve every saved object of the project (height fields here, contact and
sweep results in ``roughcontact``), so provenance is stored the same way everywhere.
"""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np

_METADATA_KEY = "__metadata_json__"


def _jsonable(value):
    if isinstance(value, dict):
        return {str(k): _jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
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


def load_npz(path) -> tuple:
    """Read a file written by :func:`save_npz`; return ``(arrays, metadata)``."""
    with np.load(Path(path), allow_pickle=False) as data:
        if _METADATA_KEY not in data:
            raise ValueError(f"{path} has no metadata record; it was not written by save_npz")
        metadata = json.loads(data[_METADATA_KEY].tobytes().decode("utf-8"))
        arrays = {name: data[name] for name in data.files if name != _METADATA_KEY}
    return arrays, metadata
