"""Measured topographies through SurfaceTopography (optional: ``pip install "roughcontact[topography]"``).

SurfaceTopography (MIT, the reader behind contact.engineering) reads about forty instrument formats (x3p,
sur, plu/plux, datx, opd, di, Gwyddion, NetCDF, text exports, ...) with their units, physical sizes and
undefined-data masks. This module converts its topographies to and from :class:`~surfaces.HeightField`:

* :func:`read_topography` ``(path, ...)``: one channel of a file as a HeightField in metres;
* :func:`from_topography` / :func:`to_topography`: the two directions in memory.

Axes: SurfaceTopography's ``heights()[i, j]`` is the height at ``(i dx, j dy)``, the layout of
:attr:`HeightField.heights`, so arrays pass through untransposed (its x3p reader, for instance, transposes
the file's x-fastest point order). Missing data (undefined points) and tilt are handled only on request:
``missing="refuse"`` (default) or ``"harmonic"`` (:func:`surfaces.heightfield.harmonic_fill`), ``detrend=None``
(default), ``"mean"`` or ``"plane"``. SurfaceTopography is imported on first use only.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from .grid import Grid
from .heightfield import HeightField, harmonic_fill
from .io import length_unit
from .validation import check_choice


def _surface_topography():
    """The SurfaceTopography package, or an ImportError that says how to install it."""
    try:
        import SurfaceTopography
    except ImportError:
        raise ModuleNotFoundError("reading measured topographies needs the optional SurfaceTopography package: "
                                  "pip install 'roughcontact[topography]' (or 'SurfaceTopography>=1.3')",
                                  name="SurfaceTopography") from None
    return SurfaceTopography


def from_topography(topography, *, unit=None, missing: str = "refuse", detrend: str | None = None,
                    **metadata) -> HeightField:
    """The SurfaceTopography ``topography`` (a uniform 2-D map or line scan) as a HeightField in metres.

    Its unit, physical size and periodicity carry over; ``unit`` (a name or metres per number) is needed only
    when the topography has none. ``missing``: undefined points are refused (``"refuse"``) or filled by
    harmonic interpolation (``"harmonic"``; their count goes into the metadata as ``missing_points``).
    ``detrend``: ``None`` keeps the heights, ``"mean"`` or ``"plane"`` applies :meth:`HeightField.detrended`
    after the filling. ``metadata`` is added to the field's record.
    """
    check_choice("missing", missing, ("refuse", "harmonic"))
    check_choice("detrend", detrend, (None, "mean", "plane"))
    if not getattr(topography, "is_uniform", False):
        raise ValueError(f"{type(topography).__name__} is not on a uniform grid; a HeightField needs a uniform "
                         "map or line scan (interpolate a nonuniform line scan with its to_uniform first)")
    if topography.unit is not None:
        if unit is not None:
            raise ValueError(f"unit = {unit!r} given, but the topography carries its unit "
                             f"({topography.unit!r}); pass unit=None")
        factor = _metres_per(topography.unit)
    elif unit is None:
        raise ValueError("the topography has no unit; pass unit= (a name such as 'um', or metres per number)")
    else:
        factor = length_unit("unit", unit)
    heights = np.ma.getdata(topography.heights()).astype(np.float64)
    holes = np.ma.getmaskarray(topography.heights()) | np.isnan(heights)
    if topography.dim == 1:
        heights, holes = heights[:, None], holes[:, None]
        length = float(topography.physical_sizes[0]) * factor
        lengths = (length, length / heights.shape[0])
    else:
        lengths = tuple(float(size) * factor for size in topography.physical_sizes)
    grid = Grid(heights.shape, lengths, bool(topography.is_periodic))
    record = {"generator": "SurfaceTopography", "unit": topography.unit or str(unit), **metadata}
    if holes.any():
        if missing == "refuse":
            raise ValueError(f"the topography has {int(holes.sum())} undefined points of {holes.size}, the first "
                             f"at index {np.argwhere(holes)[0].tolist()}; pass missing='harmonic' to fill them "
                             "from their neighbours")
        heights = harmonic_fill(heights, holes, grid.spacing, grid.periodic)
        record["missing_points"] = int(holes.sum())
    field = HeightField(grid, heights * factor, record)
    return field if detrend is None else field.detrended(detrend)


def _metres_per(unit: str) -> float:
    """Metres per number of a SurfaceTopography unit name (it knows more names than :data:`LENGTH_UNITS`)."""
    from SurfaceTopography.Support.UnitConversion import get_unit_conversion_factor
    try:
        return float(get_unit_conversion_factor(unit, "m"))
    except (KeyError, ValueError):
        raise ValueError(f"unit {unit!r} is not a length unit SurfaceTopography knows") from None


def to_topography(field: HeightField):
    """``field`` as a SurfaceTopography ``Topography`` (a ``UniformLineScan`` for a profile), unit ``"m"``.

    SurfaceTopography has one periodicity flag per topography, so a grid periodic along one axis only is
    refused."""
    st = _surface_topography()
    if not isinstance(field, HeightField):
        raise TypeError(f"field must be a surfaces.HeightField, got {type(field).__name__}")
    grid = field.grid
    if grid.is_profile:
        return st.UniformLineScan(np.array(field.heights[:, 0]), grid.lengths[0], periodic=grid.periodic[0],
                                  unit="m")
    if grid.periodic[0] != grid.periodic[1]:
        raise ValueError(f"grid.periodic = {grid.periodic}: SurfaceTopography holds one periodicity flag per "
                         "topography; make both axes periodic or neither")
    return st.Topography(np.array(field.heights), grid.lengths, periodic=grid.periodic[0], unit="m")


def read_topography(path, *, channel: int = 0, format: str | None = None, lengths=None, unit=None,
                    periodic: bool | None = None, missing: str = "refuse",
                    detrend: str | None = None) -> HeightField:
    """Channel ``channel`` of the topography file ``path`` (any format SurfaceTopography reads, detected from
    the contents unless ``format`` is given) as a HeightField in metres.

    ``lengths`` [m] and ``unit`` are for files that do not store the physical size or the unit (refused
    where the file fixes them); ``periodic`` overrides the file's flag (most instruments record a
    non-periodic window). ``missing`` and ``detrend`` as in :func:`from_topography`.
    """
    st = _surface_topography()
    from SurfaceTopography.Exceptions import CannotDetectFileFormat, ReadFileError, UnknownFileFormat
    path = Path(path)
    if not path.is_file():
        raise ValueError(f"cannot read the topography {path}: no such file")
    try:
        reader = st.open_topography(str(path), format=format)
    except (UnknownFileFormat, CannotDetectFileFormat) as error:
        reason = "no reader recognises its contents" if format is None else str(error).splitlines()[0]
        raise ValueError(f"{path} is not a topography file SurfaceTopography can read ({reason}); "
                         "pass format= if the format is known") from None
    except (ReadFileError, ValueError) as error:
        raise ValueError(f"{path} is not a topography file SurfaceTopography can read: {error}") from None
    channels = reader.channels
    if not 0 <= channel < len(channels) or isinstance(channel, bool):
        raise ValueError(f"channel = {channel!r} is out of range; {path.name} has channels 0..{len(channels) - 1}: "
                         + ", ".join(repr(info.name) for info in channels))
    info = channels[channel]
    options = {}
    if unit is not None and not isinstance(unit, str):
        raise TypeError(f"unit must be a unit name such as 'um' (the unit of the file's numbers), got {unit!r}")
    if info.unit is None:
        if unit is None:
            raise ValueError(f"{path} stores no length unit; pass unit= (e.g. 'um'), the unit of its numbers")
        options["unit"] = unit
    elif unit is not None:
        raise ValueError(f"unit = {unit!r} given, but {path.name} stores its unit ({info.unit!r}); pass unit=None")
    if info.physical_sizes is None:
        if lengths is None:
            raise ValueError(f"{path} stores no physical size; pass lengths=(Lx, Ly) in m")
        options["physical_sizes"] = tuple(float(length) / _metres_per(info.unit or unit)
                                          for length in np.atleast_1d(lengths))
    elif lengths is not None:
        raise ValueError(f"lengths = {lengths!r} given, but {path.name} stores its physical size "
                         f"({info.physical_sizes} {info.unit}); pass lengths=None")
    if periodic is not None:
        options["periodic"] = periodic
    try:
        topography = reader.topography(channel_index=channel, **options)
    except (ReadFileError, ValueError) as error:
        raise ValueError(f"{path}: {error}") from None
    return from_topography(topography, missing=missing, detrend=detrend, source=str(path), channel=channel,
                           format=reader.format())
