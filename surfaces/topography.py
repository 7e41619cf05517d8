"""Measured topographies through SurfaceTopography (optional: ``pip install "roughcontact[topography]"``).

SurfaceTopography (MIT, the reader behind contact.engineering) reads about forty instrument formats (x3p,
sur, plu/plux, datx, opd, di, Gwyddion, NetCDF, text exports, ...) with their units, physical sizes and
undefined-data masks. This module converts its topographies to and from :class:`~surfaces.HeightField`:

* :func:`read_topography` ``(path, ...)``: one channel of a file as a HeightField in metres;
* :func:`from_topography` / :func:`to_topography`: the two directions in memory.

Axes: SurfaceTopography's ``heights()[i, j]`` is the height at ``(i dx, j dy)``, the layout of
:attr:`HeightField.heights`, so arrays pass through untransposed (its x3p reader, for instance, transposes
the file's x-fastest point order). Missing data (undefined points) and tilt are handled only on request:
``missing="refuse"`` (default), ``"harmonic"`` (:func:`surfaces.heightfield.harmonic_fill`) or ``"crop"``
(:func:`surfaces.heightfield.measured_window`), ``detrend=None`` (default), ``"mean"`` or ``"plane"``.
SurfaceTopography is imported on first use only.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from .grid import Grid
from .heightfield import MISSING, HeightField, missing_handled, physical_size
from .io import LENGTH_UNITS, length_unit
from .validation import check_bool, check_choice, check_real


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
    when the topography has none. ``missing``: undefined points are refused (``"refuse"``), filled by
    harmonic interpolation (``"harmonic"``, warned with a :class:`~surfaces.heightfield.MissingDataWarning`
    above 5 % of the map) or cropped away (``"crop"``: the largest fully measured rectangle); the metadata
    records ``missing_points``, ``filled_fraction`` and, cropped, the ``crop`` kept (as
    :meth:`HeightField.read` does). ``detrend``: ``None`` keeps the heights, ``"mean"`` or ``"plane"`` applies
    :meth:`HeightField.detrended` after the filling. ``metadata`` is added to the field's record.
    """
    check_choice("missing", missing, MISSING)
    check_choice("detrend", detrend, (None, "mean", "plane"))
    if not getattr(topography, "is_uniform", False):
        raise ValueError(f"{type(topography).__name__} is not on a uniform grid; a HeightField needs a uniform "
                         "map or line scan (interpolate a nonuniform line scan with its to_uniform first)")
    name = metadata.get("source", "the topography")
    if topography.unit is not None:
        if unit is not None:
            raise ValueError(f"unit = {unit!r} given, but {name} carries its unit ({topography.unit!r}); pass "
                             "unit=None")
        factor = _metres_per(topography.unit)
    elif unit is None:
        raise ValueError(f"{name} has no unit; pass unit= (a name such as 'um', or metres per number)")
    else:
        factor = length_unit("unit", unit)
    heights = np.ma.getdata(topography.heights()).astype(np.float64)
    if heights.size == 0:
        raise ValueError(f"{name} holds no heights (shape {heights.shape})")
    heights[np.ma.getmaskarray(topography.heights())] = np.nan
    if topography.dim == 1:
        heights = heights[:, None]
        length = float(topography.physical_sizes[0]) * factor
        lengths = (length, length / heights.shape[0])
    else:
        lengths = tuple(float(size) * factor for size in topography.physical_sizes)
    heights, lengths, periodic, fill = missing_handled(heights * factor, lengths, bool(topography.is_periodic),
                                                        missing, name)
    record = {"generator": "SurfaceTopography", "unit": topography.unit or str(unit), **metadata, **fill}
    field = HeightField(Grid(heights.shape, lengths, periodic), heights, record)
    if detrend is None:
        return field
    levelled = field.detrended(detrend)                         # the record of missing data stays on top
    return HeightField(levelled.grid, levelled.heights, {**levelled.metadata, **fill})


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


def read_topography(path, *, channel: int = 0, format: str | None = None, lengths=None, pixel_size=None,
                    unit=None, periodic: bool | None = None, missing: str = "refuse",
                    detrend: str | None = None) -> HeightField:
    """Channel ``channel`` of the topography file ``path`` (any format SurfaceTopography reads, detected from
    the contents unless ``format`` is given) as a HeightField in metres.

    For files that do not store them (refused where the file fixes them): the physical size as ``lengths``
    [m] or ``pixel_size`` [m] (one number, or (dx, dy)), and ``unit``, the unit of the file's numbers (a name
    such as ``"um"`` or metres per number). ``periodic`` overrides the file's flag (most instruments record a
    non-periodic window). ``missing`` and ``detrend`` as in :func:`from_topography`.
    """
    st = _surface_topography()
    from SurfaceTopography.Exceptions import CannotDetectFileFormat, ReadFileError, UnknownFileFormat
    path = Path(path)
    if not path.is_file():
        raise ValueError(f"cannot read the topography {path}: no such file")
    if path.stat().st_size == 0:
        raise ValueError(f"{path} is empty (0 bytes), not a topography file")
    try:           # opened here and closed: SurfaceTopography's NPY reader would leave a file it opens open
        stream = open(path, "rb")
    except OSError as error:
        raise ValueError(f"cannot read the topography {path}: {error.strerror}") from None
    with stream:
        try:
            reader = st.open_topography(stream, format=format)
        except (UnknownFileFormat, CannotDetectFileFormat) as error:
            reason = "no reader recognises its contents" if format is None else str(error).splitlines()[0]
            raise ValueError(f"{path} is not a topography file SurfaceTopography can read ({reason}); "
                             "pass format= if the format is known") from None
        except (ReadFileError, ValueError) as error:
            raise ValueError(f"{path} is not a topography file SurfaceTopography can read: {error}") from None
        channels = reader.channels
        if (isinstance(channel, bool) or not isinstance(channel, (int, np.integer))
                or not 0 <= channel < len(channels)):
            raise ValueError(f"channel = {channel!r} is out of range; {path.name} has channels "
                             f"0..{len(channels) - 1}: " + ", ".join(repr(info.name) for info in channels))
        info = channels[channel]
        options, factor = _unit_and_size(path, info, unit, lengths, pixel_size)
        if periodic is not None:
            options["periodic"] = check_bool("periodic", periodic)          # as Grid: a truthy string is refused
        try:
            topography = reader.topography(channel_index=channel, **options)
        except (ReadFileError, ValueError) as error:
            raise ValueError(f"{path}: {error}") from None
    return from_topography(topography, unit=factor, missing=missing, detrend=detrend, source=str(path),
                           channel=channel, format=reader.format())


def _unit_and_size(path, info, unit, lengths, pixel_size) -> tuple:
    """``(options, factor)``: the unit and physical size to give SurfaceTopography's reader for the channel
    ``info`` of ``path``, from what the file stores and :func:`read_topography`'s ``unit``, ``lengths`` and
    ``pixel_size``; ``factor`` (metres per number) for :func:`from_topography` when the unit is a factor
    (SurfaceTopography then reads the numbers without a unit), else None."""
    options, factor = {}, None
    if info.unit is not None:
        if unit is not None:
            raise ValueError(f"unit = {unit!r} given, but {path.name} stores its unit ({info.unit!r}); pass "
                             "unit=None")
        metres = _metres_per(info.unit)
    elif unit is None:
        raise ValueError(f"{path} stores no length unit; pass unit= (e.g. 'um' or metres per number), the unit "
                         "of its numbers")
    elif isinstance(unit, str):
        metres = LENGTH_UNITS.get(unit) or _metres_per(unit)            # (refused if neither knows it)
        options["unit"] = unit
    else:
        metres = factor = length_unit("unit", unit)
    if info.physical_sizes is not None:
        if lengths is not None or pixel_size is not None:
            given = f"lengths = {lengths!r}" if lengths is not None else f"pixel_size = {pixel_size!r}"
            raise ValueError(f"{given} given, but {path.name} stores its physical size ({info.physical_sizes} "
                             f"{info.unit}); pass lengths=None and pixel_size=None")
        return options, factor
    counts = tuple(info.nb_grid_pts)
    if len(counts) == 1 and pixel_size is not None and np.ndim(pixel_size) > 0:
        raise ValueError(f"pixel_size = {pixel_size!r} given for a line scan; give one number (m)")
    if len(counts) == 1 and lengths is not None and np.ndim(lengths) > 0 and len(lengths) != 1:
        raise ValueError(f"lengths = {lengths!r} given for a line scan; give its length (one number, m)")
    if lengths is None and pixel_size is None:
        raise ValueError(f"{path} stores no physical size; pass lengths=(Lx, Ly) or pixel_size (dx or (dx, dy)) "
                         "in m")
    shape = counts if len(counts) == 2 else (counts[0], 1)
    size = physical_size(shape, lengths, pixel_size)[:len(counts)]
    options["physical_sizes"] = tuple(check_real(f"lengths[{axis}]", length, low=0.0, low_open=True) / metres
                                      for axis, length in enumerate(size))
    return options, factor
