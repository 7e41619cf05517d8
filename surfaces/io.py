"""Self-describing ``.npz`` files: named arrays plus a JSON metadata record (tuples come back as tuples).

One writer and one reader serve every saved object of the project (height fields here, contact and
sweep results in ``roughcontact``), so provenance is stored the same way everywhere.
"""
from __future__ import annotations

import io
import json
import zipfile
import zlib
from pathlib import Path

import numpy as np

from .validation import check_integer, check_real

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
    """Write ``arrays`` and the JSON-serialisable ``metadata`` to a compressed ``.npz`` file; return its path
    (``.npz`` is appended to a path without it). A path that is a directory is refused (``IsADirectoryError``)."""
    path = Path(path)
    if path.is_dir():
        raise IsADirectoryError(f"{path} is a directory; give the file to write, e.g. {path / 'result.npz'}")
    if path.suffix != ".npz":
        path = path.with_suffix(path.suffix + ".npz") if path.suffix else path.with_suffix(".npz")
    if _METADATA_KEY in arrays:
        raise ValueError(f"array name {_METADATA_KEY!r} is reserved")
    encoded = np.frombuffer(json.dumps(_jsonable(metadata), sort_keys=True).encode("utf-8"), dtype=np.uint8)
    np.savez_compressed(path, **arrays, **{_METADATA_KEY: encoded})
    return path


def _restore_tuple(record: dict):
    return tuple(record[_TUPLE_TAG]) if record.keys() == {_TUPLE_TAG} else record


class UnreadableFile(ValueError):
    """A file that is not what :func:`load_npz` reads: ``"<path>: <reason>"``."""

    def __init__(self, path, reason: str):
        super().__init__(f"{path}: {reason}")
        self.path, self.reason = path, reason


def load_npz(path) -> tuple:
    """Read a file written by :func:`save_npz`; return ``(arrays, metadata)``. A file that is not one (empty,
    truncated, another format, no metadata record) raises :class:`UnreadableFile` (a ``ValueError``) naming it;
    a missing or unreadable one the ``OSError``, which names it."""
    try:        # (the file opened here, so that it is closed when numpy fails on it)
        with open(Path(path), "rb") as handle, np.load(handle, allow_pickle=False) as data:
            if _METADATA_KEY not in data:
                raise UnreadableFile(path, "has no metadata record; it was not written by save_npz")
            metadata = json.loads(data[_METADATA_KEY].tobytes().decode("utf-8"), object_hook=_restore_tuple)
            arrays = {name: data[name] for name in data.files if name != _METADATA_KEY}
    except (zipfile.BadZipFile, zlib.error, EOFError) as error:
        raise UnreadableFile(path, f"not a readable .npz archive (empty, truncated or of another format: {error})"
                             ) from None
    except (json.JSONDecodeError, UnicodeDecodeError) as error:
        raise UnreadableFile(path, f"its metadata record is not valid JSON ({error})") from None
    except UnreadableFile:
        raise
    except ValueError as error:             # numpy takes what is not a zip for a pickle, and advises allow_pickle
        if "pickle" not in str(error):
            raise
        raise UnreadableFile(path, "not an .npz archive") from None
    return arrays, metadata


# -- plain-text height maps and unit names ------------------------------------------------------------------
#: Length units accepted by name at the file boundary, in metres (the micro sign and the Greek mu both work).
LENGTH_UNITS = {"m": 1.0, "mm": 1e-3, "um": 1e-6, "\u00b5m": 1e-6, "\u03bcm": 1e-6, "nm": 1e-9, "pm": 1e-12,
                "\u00c5": 1e-10}

# First bytes of the binary containers that instruments write (zip: x3p, plux, datx-in-zip; HDF5; NetCDF 3)
_BINARY_MAGIC = {b"PK\x03\x04": "a zip container (x3p, plux, ...)", b"\x89HDF": "an HDF5 file (datx, NetCDF 4, ...)",
                 b"CDF\x01": "a NetCDF file", b"CDF\x02": "a NetCDF file"}


def length_unit(name: str, unit) -> float:
    """Metres per stored number: ``unit`` is a positive factor or one of :data:`LENGTH_UNITS`' names."""
    if isinstance(unit, str):
        if unit not in LENGTH_UNITS:
            raise ValueError(f"{name} = {unit!r} is not a known length unit; valid: a positive factor to metres "
                             f"or one of {', '.join(repr(u) for u in LENGTH_UNITS)}")
        return LENGTH_UNITS[unit]
    return check_real(name, unit, low=0.0, low_open=True)


def read_npy(path) -> np.ndarray:
    """The array of the ``.npy`` file ``path``; ``ValueError`` naming it if it is not one (empty, truncated,
    pickled objects)."""
    try:
        with open(Path(path), "rb") as handle:
            return np.load(handle, allow_pickle=False)
    except (ValueError, EOFError) as error:
        reason = "it holds pickled objects" if "pickle" in str(error) else str(error)
        raise ValueError(f"{path} is not a readable .npy array ({reason})") from None


def read_text_table(path, delimiter=None, skiprows: int = 0) -> np.ndarray:
    """The numbers of the text file ``path`` as a 2-D array (one row per line; ``#`` starts a comment).

    ``delimiter=None`` takes it from the first data line: ``;`` if present, else ``,``, else white space.
    Binary files and lines that are not numbers raise ``ValueError`` naming the file (and the line).
    """
    path = Path(path)
    skiprows = check_integer("skiprows", skiprows, low=0)
    raw = path.read_bytes()
    for magic, kind in _BINARY_MAGIC.items():
        if raw.startswith(magic):
            raise ValueError(f"{path} is {kind}, not a text height map; read instrument formats with "
                             "surfaces.topography.read_topography (optional SurfaceTopography: "
                             "pip install 'roughcontact[topography]')")
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as error:
        raise ValueError(f"{path} is not UTF-8 text (byte {error.start}: {raw[error.start:error.start + 1]!r}), so "
                         "not a text height map; read instrument formats with "
                         "surfaces.topography.read_topography (optional SurfaceTopography)") from None
    lines = text.splitlines()
    data_lines = [line for line in lines[skiprows:] if line.split("#", 1)[0].strip()]
    if not data_lines:
        raise ValueError(f"{path} holds no numbers (after skiprows = {skiprows} lines and '#' comments)")
    if delimiter is None:
        first = data_lines[0].split("#", 1)[0]
        delimiter = ";" if ";" in first else "," if "," in first else None
    try:
        return np.loadtxt(io.StringIO(text), delimiter=delimiter, skiprows=skiprows, ndmin=2, dtype=np.float64)
    except ValueError:
        raise ValueError(_first_unreadable_line(path, lines, skiprows, delimiter)) from None


def _first_unreadable_line(path, lines, skiprows: int, delimiter) -> str:
    """The message naming the first line of ``lines`` that is not a row of numbers like the first data row."""
    separator = "white space" if delimiter is None else repr(delimiter)
    width = None
    for number, line in enumerate(lines[skiprows:], start=skiprows + 1):
        content = line.split("#", 1)[0].strip()
        if not content:
            continue
        try:
            row = [float(value) for value in content.split(delimiter)]
        except ValueError:
            return (f"{path}, line {number}: {content[:60]!r} is not a row of numbers separated by "
                    f"{separator}; pass delimiter= or skiprows= "
                    "(header lines), or start comment lines with '#'")
        width = len(row) if width is None else width
        if len(row) != width:
            return f"{path}, line {number}: {len(row)} columns, but the first data row has {width}"
    return f"{path} is not a table of numbers separated by {separator}"


def _lattice_indices(name: str, values: np.ndarray) -> tuple:
    """``(index, step, count)`` of coordinates ``values`` on a regular lattice ``values.min() + index*step``;
    ``ValueError`` if they are not on one (to 1 % of a step). Printing noise below a quarter step is merged."""
    levels = np.unique(values)
    if levels.size == 1:
        return np.zeros(values.size, dtype=np.intp), None, 1
    gaps = np.diff(levels)
    levels = levels[np.concatenate([[True], gaps > 0.25 * gaps.max()])]
    step = (levels[-1] - levels[0]) / (levels.size - 1)
    position = (values - levels[0]) / step
    index = np.rint(position).astype(np.intp)
    worst = np.abs(position - index).max()
    if worst > 0.01:
        raise ValueError(f"the {name} column is not on a regular lattice: a value lies {worst:.2g} steps off the "
                         f"lattice of {levels.size} values spaced {step:g}; regrid the scan before reading it")
    return index, step, levels.size


def _in_raster_order(x_index: np.ndarray, y_index: np.ndarray) -> bool:
    """Whether lattice points come line by line: one axis outer (monotone), the other inner (strictly monotone
    within each line, in the same direction on every line), ascending or descending; points may be left out."""
    for outer, inner in ((x_index, y_index), (y_index, x_index)):
        step = np.diff(outer)
        if (step >= 0).all() or (step <= 0).all():
            inner_step = np.diff(inner)[step == 0]
            if (inner_step > 0).all() or (inner_step < 0).all():
                return True
    return False


def grid_from_columns(columns: np.ndarray, raster_order: bool = False) -> tuple:
    """``(heights, spacing)`` of an x-z or x-y-z column export on a regular lattice: ``heights[i, j]`` at
    ``(x0 + i dx, y0 + j dy)``, NaN where the export has no point; ``spacing`` (dx, dy) in the file's unit
    (dy None for a profile). ``ValueError`` if the points are off a lattice, a point is given twice or, with
    ``raster_order``, the points do not come line by line (x or y outer, each ascending or descending)."""
    if columns.ndim != 2 or columns.shape[1] not in (2, 3):
        raise ValueError(f"a column export has 2 (x z) or 3 (x y z) columns, got shape {columns.shape}")
    coordinates = columns[:, :-1]
    if not np.isfinite(coordinates).all():
        row, column = np.argwhere(~np.isfinite(coordinates))[0]
        raise ValueError(f"the {'xy'[column]} column holds {float(coordinates[row, column])!r} in data row "
                         f"{row + 1}; coordinates must be finite (a missing height goes in the z column as NaN)")
    x_index, dx, nx = _lattice_indices("x", columns[:, 0])
    y_index, dy, ny = (_lattice_indices("y", columns[:, 1]) if columns.shape[1] == 3
                       else (np.zeros(len(columns), dtype=np.intp), None, 1))
    if dx is None:
        raise ValueError(f"the x column holds a single value ({float(columns[0, 0])!r}); a column export needs x "
                         "to vary")
    heights = np.full((nx, ny), np.nan)
    counts = np.zeros((nx, ny), dtype=np.intp)
    np.add.at(counts, (x_index, y_index), 1)
    if counts.max() > 1:
        i, j = np.argwhere(counts > 1)[0]
        raise ValueError(f"the point (x index {i}, y index {j}) is given {counts[i, j]} times; a column export "
                         "holds each lattice point once")
    if raster_order and not _in_raster_order(x_index, y_index):
        raise ValueError("its points are not in raster order (line by line, x or y outer, each ascending or "
                         "descending)")
    heights[x_index, y_index] = columns[:, -1]
    return heights, (dx, dy)
