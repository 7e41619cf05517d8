"""Height fields: heights in metres on a :class:`~surfaces.Grid`, with the recipe that made them."""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

import warnings

from .validation import check_choice, check_finite_array, check_integer, check_real, plain
from .grid import Grid
from .io import grid_from_columns, length_unit, load_npz, read_npy, read_text_table, save_npz

#: Ways of handling the missing (undefined) heights of a measured map: refuse the map, fill them by harmonic
#: interpolation (:func:`harmonic_fill`), or keep the largest fully measured rectangle (:func:`measured_window`).
MISSING = ("refuse", "harmonic", "crop")

#: A harmonic fill of more than this fraction of a map's pixels warns (:class:`MissingDataWarning`): those heights
#: are invented, and a contact solve treats them as measured.
FILL_WARNING_FRACTION = 0.05

#: Most missing points :func:`harmonic_fill` solves for. Its sparse LU factors (minimum-degree ordering of
#: A + Aᵀ) grow faster than the points of one compact hole, the worst case: a 724² hole (524 176 points) peaks at
#: 0.79 GB resident, 2.7 s of CPU; a 1024² hole at 1.9 GB; 513 968 scattered points at 0.43 GB. scipy's SuperLU
#: does not survive a failed allocation: a 2048² map with a 1943² hole crashed the interpreter (segmentation
#: fault) under a 4 GB address-space limit. So more points are refused before anything is allocated.
MAX_FILL_POINTS = 2 ** 19


class MissingDataWarning(UserWarning):
    """``missing="harmonic"`` filled more than :data:`FILL_WARNING_FRACTION` of a map's heights."""


def physical_size(shape: tuple, lengths, pixel_size) -> tuple:
    """``(Lx, Ly)`` [m] of a map of ``shape`` from its ``lengths`` or its ``pixel_size`` (exactly one given)."""
    if (lengths is None) == (pixel_size is None):
        raise ValueError("give the physical size as lengths (Lx, Ly) or as pixel_size (dx or (dx, dy)) in m, "
                         f"exactly one of them; got lengths = {lengths!r}, pixel_size = {pixel_size!r}")
    nx, ny = shape
    if pixel_size is not None:
        pair = (pixel_size, pixel_size) if np.ndim(pixel_size) == 0 else tuple(pixel_size)
        if len(pair) != 2:
            raise ValueError(f"pixel_size must be one number or a pair (dx, dy) in m, got {pixel_size!r}")
        dx, dy = (check_real(f"pixel_size[{axis}]", d, low=0.0, low_open=True) for axis, d in enumerate(pair))
        return nx * dx, ny * dy
    if np.ndim(lengths) > 0:
        return tuple(lengths)
    if ny == 1:
        return lengths, lengths / nx                        # a profile: the y size of one pixel
    if nx != ny:
        raise ValueError(f"lengths = {lengths!r} is one number for a map of shape {shape}, which would give "
                         "non-square pixels; give lengths=(Lx, Ly) or pixel_size")
    return lengths, lengths


def _frozen(array: np.ndarray) -> np.ndarray:
    array = np.array(array, dtype=np.float64, copy=True)
    array.flags.writeable = False
    return array


def harmonic_fill(heights, missing, spacing, periodic=False, *, max_points: int = MAX_FILL_POINTS) -> np.ndarray:
    """``heights`` with the ``missing`` pixels replaced by the discrete harmonic interpolation of the others.

    Each missing pixel p satisfies ``Σ_n (h_n − h_p)/d_n² = 0`` over its four neighbours n (``d_n`` the pixel
    size ``spacing`` [m] along the neighbour's axis): the five-point Laplace equation with the measured pixels
    as boundary values. A non-periodic axis has no neighbour beyond the edge (zero normal slope there); a
    periodic one wraps. Exact for ``a + b x + c y + e xy + f (x² − y²)`` in holes away from the edge.
    The sparse direct solve's memory grows with the number of missing points: more than ``max_points``
    (:data:`MAX_FILL_POINTS`) are refused.
    """
    from scipy.sparse import coo_matrix
    from scipy.sparse.linalg import splu
    missing = np.asarray(missing, dtype=bool)
    if missing.all():
        raise ValueError(f"every height is missing ({missing.size} pixels); nothing to interpolate from")
    count = int(np.count_nonzero(missing))
    if count > check_integer("max_points", max_points, low=0):
        raise ValueError(f"{count} missing heights of a {missing.shape[0]} x {missing.shape[1]} map exceed "
                         f"max_points = {max_points} of the harmonic fill (its sparse solve's memory grows faster "
                         "than the points: 0.8 GB at 2**19 in one hole); crop the map to its measured part "
                         "(missing='crop' or HeightField.cropped), or raise max_points where the memory is there")
    periodic = (periodic, periodic) if np.ndim(periodic) == 0 else tuple(periodic)
    known = np.where(missing, 0.0, heights)
    points = np.argwhere(missing)
    unknown = np.full(missing.shape, -1, dtype=np.intp)
    unknown[tuple(points.T)] = np.arange(len(points))
    diagonal, rhs = np.zeros(len(points)), np.zeros(len(points))
    rows, columns, values = [], [], []
    for axis, size in enumerate(missing.shape):
        weight = 1.0 / spacing[axis] ** 2
        for step in ((-1, 1) if size > 1 else ()):
            neighbour = points.copy()
            neighbour[:, axis] += step
            if periodic[axis]:
                neighbour[:, axis] %= size
            inside = (neighbour[:, axis] >= 0) & (neighbour[:, axis] < size)
            point, neighbour = np.flatnonzero(inside), neighbour[inside]
            diagonal[point] += weight
            index = unknown[tuple(neighbour.T)]
            rows.append(point[index >= 0])
            columns.append(index[index >= 0])
            values.append(np.full((index >= 0).sum(), -weight))
            np.add.at(rhs, point[index < 0], weight * known[tuple(neighbour[index < 0].T)])
    n = len(points)
    matrix = coo_matrix((np.concatenate(values + [diagonal]),
                         (np.concatenate(rows + [np.arange(n)]), np.concatenate(columns + [np.arange(n)]))),
                        shape=(n, n)).tocsr()
    filled = known.copy()
    # the matrix is symmetric: a minimum-degree ordering of A + Aᵀ keeps the LU factors about half as large as
    # the default column ordering does (a 971² hole: 7.1e7 against 1.3e8 non-zeros, 1.7 against 3.1 GB)
    filled[tuple(points.T)] = splu(matrix.tocsc(), permc_spec="MMD_AT_PLUS_A").solve(rhs)
    return filled


def measured_window(measured) -> tuple:
    """``((i0, i1), (j0, j1))``: the largest axis-aligned rectangle ``measured[i0:i1, j0:j1]`` of True pixels
    (the first found of equal area, scanning rows downwards).

    The exact maximal-rectangle recursion, O(n m): down row i, each column j carries the height of the run
    of True pixels ending at (i, j) and the widest span [left, right) that run's rows share around j; the
    largest rectangle is the largest (right − left) × height met. ``ValueError`` if no pixel is True.
    """
    measured = np.asarray(measured, dtype=bool)
    if measured.ndim != 2:
        raise ValueError(f"measured must be a 2-D mask, got shape {measured.shape}")
    if not measured.any():
        raise ValueError(f"no pixel of the {measured.shape[0]} x {measured.shape[1]} map is measured")
    n, m = measured.shape
    columns = np.arange(m)
    height, left, right = np.zeros(m, np.intp), np.zeros(m, np.intp), np.full(m, m, np.intp)
    best, window = 0, None
    for i, row in enumerate(measured):
        height = np.where(row, height + 1, 0)
        # the run of measured pixels through column j along this row: [run_start, run_end)
        run_start = np.maximum.accumulate(np.where(row, 0, columns + 1))
        run_end = np.minimum.accumulate(np.where(row, m, columns)[::-1])[::-1]
        left = np.where(row, np.maximum(left, run_start), 0)
        right = np.where(row, np.minimum(right, run_end), m)
        area = (right - left) * height
        j = int(np.argmax(area))
        if area[j] > best:
            best, window = int(area[j]), ((i + 1 - int(height[j]), i + 1), (int(left[j]), int(right[j])))
    return window


def missing_handled(heights, lengths, periodic, missing: str, source: str) -> tuple:
    """``(heights, lengths, periodic, record)`` of a measured map ``heights`` [m] on a window of ``lengths`` [m]
    whose NaN heights are missing: refused (``missing="refuse"``), filled by :func:`harmonic_fill` (warned above
    :data:`FILL_WARNING_FRACTION`) or cropped away (the :func:`measured_window`, its axes no longer periodic
    where cut). ``record``: ``missing``, ``missing_points``, ``filled_fraction`` (of the returned pixels) and,
    cropped, ``crop`` (the pixel ranges kept) and ``kept_fraction``; empty when nothing is missing."""
    holes = np.isnan(heights)
    count = int(np.count_nonzero(holes))
    if count == 0:
        return heights, lengths, periodic, {}
    shape = heights.shape
    spacing = tuple(length / n for length, n in zip(lengths, shape))
    periodic = (periodic, periodic) if np.ndim(periodic) == 0 else tuple(periodic)
    window = measured_window(~holes) if count < holes.size else None
    rectangle = "" if window is None else (f" (the largest fully measured rectangle: pixels {window[0][0]}:"
                                           f"{window[0][1]} x {window[1][0]}:{window[1][1]}, "
                                           f"{_kept(window, shape):.0%} of the map)")
    if missing == "refuse":
        raise ValueError(f"{source} has {count} missing heights (NaN, masked or absent points) of {holes.size}, "
                         f"the first at index {np.argwhere(holes)[0].tolist()}; pass missing='crop' to keep the "
                         f"measured part{rectangle} or missing='harmonic' to fill them from their neighbours")
    record = {"missing": missing, "missing_points": count}
    if missing == "harmonic":
        try:
            filled = harmonic_fill(heights, holes, spacing, periodic)
        except ValueError as error:
            raise ValueError(f"{source}: {error}") from None
        record["filled_fraction"] = count / holes.size
        if record["filled_fraction"] > FILL_WARNING_FRACTION:
            warnings.warn(f"{source}: missing='harmonic' invented {count} of its {holes.size} heights "
                          f"({record['filled_fraction']:.1%}, above {FILL_WARNING_FRACTION:.0%}), which a solve "
                          f"takes for measured ones; missing='crop' keeps the measured part{rectangle}",
                          MissingDataWarning, stacklevel=4)
        return filled, lengths, periodic, record
    if window is None:
        raise ValueError(f"{source}: every one of its {holes.size} heights is missing; nothing to crop to")
    (i0, i1), (j0, j1) = window
    kept = heights[i0:i1, j0:j1]
    periodic = tuple(wraps and stop - start == n for wraps, (start, stop), n in zip(periodic, window, shape))
    record.update(filled_fraction=0.0, crop=[[i0, i1], [j0, j1]], kept_fraction=_kept(window, shape))
    return kept, tuple(d * n for d, n in zip(spacing, kept.shape)), periodic, record


def _kept(window, shape) -> float:
    """The fraction of a map of ``shape`` inside ``window`` ((i0, i1), (j0, j1))."""
    (i0, i1), (j0, j1) = window
    return (i1 - i0) * (j1 - j0) / (shape[0] * shape[1])


def _cell_weights(n_old: int, n_new: int):
    """The sparse (n_new × n_old) matrix of the fractions of each new cell that each old cell covers, when
    n_new cells replace n_old on the same length: in units of 1/(n_old n_new) of it, old cell i spans
    [i n_new, (i + 1) n_new) and new cell I spans [I n_old, (I + 1) n_old), so the overlaps are exact integers."""
    from scipy.sparse import csr_matrix
    new = np.arange(n_new, dtype=np.int64)
    first, last = new * n_old // n_new, ((new + 1) * n_old - 1) // n_new
    counts = last - first + 1
    rows = np.repeat(new, counts)
    columns = np.repeat(first, counts) + np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts, counts)
    overlap = np.minimum((rows + 1) * n_old, (columns + 1) * n_new) - np.maximum(rows * n_old, columns * n_new)
    return csr_matrix((overlap / n_old, (rows, columns)), shape=(n_new, n_old))


def _numbers(path, raw: np.ndarray) -> np.ndarray:
    """The array ``raw`` read from ``path`` as float64 heights, 2-D (a profile as one column); ``ValueError``
    naming the file for more than two dimensions or values that are not numbers (strings, objects, records)."""
    if raw.ndim > 2:
        raise ValueError(f"{path} holds an array of shape {raw.shape}; a height map is 1-D (a profile) or 2-D")
    if raw.dtype.kind not in "iufc":
        raise ValueError(f"{path} holds values of dtype {raw.dtype}, not numbers; a height map holds integers or "
                         "floats")
    if np.iscomplexobj(raw):
        check_finite_array("heights", raw)                      # the TypeError naming complex heights
    raw = np.asarray(raw, dtype=np.float64)
    return raw[:, None] if raw.ndim == 1 else raw


def _column_export(path, raw: np.ndarray, layout: str, sized: bool):
    """``(heights, spacing)`` of the text table ``raw`` read as an x-z or x-y-z export
    (:func:`~surfaces.io.grid_from_columns`), or None for a matrix; ``layout`` and whether a size was given
    (``sized``) decide, as :meth:`HeightField.read` describes."""
    width = raw.shape[1]
    if layout == "matrix" or width not in (2, 3):
        if layout == "columns":
            raise ValueError(f"{path} has shape {raw.shape}, not the 2 or 3 columns of an x-z or x-y-z export")
        return None
    if layout == "columns":
        try:
            heights, spacing = grid_from_columns(raw)
        except ValueError as error:
            raise ValueError(f"{path}: {error}") from None
    else:
        try:
            heights, spacing = grid_from_columns(raw, raster_order=True)
        except ValueError as error:
            raise ValueError(f"{path} has {width} columns that are not an x-y-z (or x-z) export on a regular "
                             f"lattice in raster order ({error}); if it is a height matrix {width} pixels wide, "
                             "pass layout='matrix' (with lengths or pixel_size), if an export in another order, "
                             "layout='columns'") from None
    if sized:
        raise ValueError(f"{path} reads as a column export, which fixes the pixel size ({spacing[0]:g}, "
                         f"{spacing[1]!s} in the file's unit; {heights.shape[0]} x {heights.shape[1]} points): lengths "
                         f"and pixel_size must be None, or, if it is a height matrix {width} pixels wide, pass "
                         "layout='matrix'")
    return heights, spacing


@dataclass(frozen=True, eq=False)
class HeightField:
    """Immutable topography ``h(x, y)`` [m] on ``grid``; positive heights point towards the counter-face.

    ``metadata`` records how the field was made (generator name, parameters, seed) so a saved field can be
    regenerated. Fields on the same grid add (``a + b``) and scale (``2.0 * a``); each operation returns a
    new field whose metadata lists its parts.
    """

    grid: Grid
    heights: np.ndarray
    metadata: dict = field(default_factory=dict)

    # numpy operands defer to HeightField's operators (which refuse arrays) instead of broadcasting over it
    __array_ufunc__ = None

    def __post_init__(self):
        if not isinstance(self.grid, Grid):
            raise TypeError(f"grid must be a surfaces.Grid, got {type(self.grid).__name__}")
        heights = check_finite_array("heights", self.heights)
        if heights.shape != self.grid.shape:
            raise ValueError(f"heights has shape {heights.shape}, but grid.shape is {self.grid.shape}")
        object.__setattr__(self, "heights", _frozen(heights))
        object.__setattr__(self, "metadata", dict(self.metadata))

    # -- construction --------------------------------------------------------------------------------------
    @classmethod
    def from_array(cls, heights, lengths=None, periodic=False, *, pixel_size=None, **metadata) -> "HeightField":
        """Wrap a plain array of heights [m], ``heights[i, j]`` at ``(i dx, j dy)`` (a 1-D array is a profile).

        Give its physical size as ``lengths`` [m] (a pair; one number only for a square map or a profile) or
        as ``pixel_size`` [m] (one number: square pixels, or a pair (dx, dy)).
        """
        heights = check_finite_array("heights", heights)
        if heights.ndim not in (1, 2):
            raise ValueError(f"heights must be a 1-D profile or a 2-D map, got shape {heights.shape}")
        if heights.ndim == 1:
            heights = heights[:, None]
        if heights.size == 0:
            raise ValueError(f"heights is empty (shape {heights.shape}); it needs at least one pixel per axis")
        grid = Grid(heights.shape, physical_size(heights.shape, lengths, pixel_size), periodic)
        return cls(grid, heights, {"generator": "from_array", **metadata})

    @classmethod
    def read(cls, path, lengths=None, periodic=False, unit=1.0, *, pixel_size=None, channel: int = 0,
             rows: str = "x", layout: str = "auto", delimiter=None, skiprows: int = 0, lateral_unit=None,
             missing: str = "refuse") -> "HeightField":
        """Read a height map from ``.npz`` (a saved field), ``.npy`` or text (white space, ``,`` or ``;``).

        A text file is either a **matrix** of heights or an **x-y-z** (or x-z) **column export** on a regular
        lattice; ``layout="auto"`` reads 2 or 3 columns as a column export when no size is given and their
        points lie on a regular lattice in raster order (x or y outer, each ascending or descending), refuses
        other 2 or 3 columns naming ``layout`` (a matrix 2 or 3 pixels wide needs ``layout="matrix"``, an export
        in another order ``layout="columns"``), and reads anything else as a matrix.

        * ``unit``: metres per stored height, a factor or a name (``"um"``, ``"nm"``, …: the keys of
          :data:`surfaces.io.LENGTH_UNITS`); ``lateral_unit`` (column exports) the same for x and y, default
          ``unit``.
        * Matrix and ``.npy``: the size as ``lengths`` [m] or ``pixel_size`` [m] (see :meth:`from_array`);
          ``rows="x"``: row i holds the heights at x_i (numpy's layout of :attr:`heights`, what
          ``numpy.savetxt(path, field.heights)`` writes); ``rows="y"``: row j holds the heights along x at y_j
          (the image layout of instrument exports and of SurfaceTopography's text reader).
        * Column exports carry their size: ``lengths`` and ``pixel_size`` are refused; ``Lx = nx dx``. So does
          a saved ``.npz`` field, in metres: ``lengths``, ``pixel_size``, ``unit`` and ``lateral_unit`` are
          refused there.
        * ``channel``: these files hold one map, channel 0 (as :func:`surfaces.read_topography` takes it).
        * ``missing``: NaN heights (and lattice points a column export leaves out) are refused (``"refuse"``),
          filled with the harmonic interpolation of their neighbours (``"harmonic"``, :func:`harmonic_fill`,
          with a :class:`MissingDataWarning` above :data:`FILL_WARNING_FRACTION` of the map), or cropped away
          (``"crop"``: the largest fully measured rectangle, :func:`measured_window`). The metadata records
          ``missing_points``, ``filled_fraction`` (of the field's pixels) and, cropped, the ``crop`` kept.
        """
        path = Path(path)
        check_choice("rows", rows, ("x", "y"))
        check_choice("layout", layout, ("auto", "matrix", "columns"))
        check_choice("missing", missing, MISSING)
        scale = length_unit("unit", unit)
        if isinstance(channel, bool) or not isinstance(channel, (int, np.integer)) or channel != 0:
            raise ValueError(f"channel = {plain(channel)} is out of range; {path.name} holds one height map, "
                             "channel 0")
        if path.suffix == ".npz":
            if lengths is not None or pixel_size is not None or scale != 1.0 or lateral_unit is not None:
                raise ValueError(f"{path} is a saved HeightField, which stores its size and its heights in metres; "
                                 f"lengths = {lengths!r}, pixel_size = {pixel_size!r}, unit = {unit!r}, "
                                 f"lateral_unit = {lateral_unit!r} must be left out")
            return cls.load(path)
        raw = _numbers(path, read_npy(path) if path.suffix == ".npy" else read_text_table(path, delimiter, skiprows))
        source, label = {"source": str(path)}, str(path)
        export = None if path.suffix == ".npy" else _column_export(path, raw, layout,
                                                                   sized=lengths is not None or pixel_size is not None)
        if export is not None:
            heights, spacing = export
            lateral = scale if lateral_unit is None else length_unit("lateral_unit", lateral_unit)
            pixel_size = tuple(spacing[0] * lateral if d is None else d * lateral for d in spacing)
            source["layout"] = "columns"
            if layout == "auto" and np.isnan(heights).mean() > 0.5:       # as a matrix read as an export leaves it
                label += (f" (read as a column export, most of its lattice absent; a height matrix {raw.shape[1]} "
                          "pixels wide needs layout='matrix')")
        else:
            heights = raw.T if rows == "y" else raw
            if lengths is None and pixel_size is None:
                raise ValueError(f"lengths or pixel_size (physical size in m) is required to read {path.name}; "
                                 "got neither")
        size = physical_size(heights.shape, lengths, pixel_size)
        heights, size, periodic, record = missing_handled(heights * scale, size, periodic, missing, label)
        return cls.from_array(heights, size, periodic, **source, **record)

    # -- arithmetic ----------------------------------------------------------------------------------------
    def _check_same_grid(self, other: "HeightField"):
        if other.grid != self.grid:
            raise ValueError(f"cannot combine height fields on different grids: {self.grid} vs {other.grid}")

    def _refuse_array(self, other, operation):
        if isinstance(other, np.ndarray) and other.ndim > 0:
            raise TypeError(f"cannot {operation} a HeightField and a numpy array of shape {other.shape}: wrap the "
                            "array as HeightField(field.grid, array) first (or use field.heights)")

    def __add__(self, other):
        self._refuse_array(other, "add")
        if isinstance(other, HeightField):
            self._check_same_grid(other)
            return HeightField(self.grid, self.heights + other.heights,
                               {"generator": "sum", "parts": [self.metadata, other.metadata]})
        if isinstance(other, (int, float, np.floating, np.integer)):
            offset = check_real("offset", other)
            return HeightField(self.grid, self.heights + offset,
                               {"generator": "offset", "offset": offset, "parts": [self.metadata]})
        return NotImplemented

    __radd__ = __add__

    def __neg__(self):
        return self * -1.0

    def __sub__(self, other):
        self._refuse_array(other, "subtract")
        if not isinstance(other, (HeightField, int, float, np.floating, np.integer)):
            return NotImplemented
        return self + (-other)

    def __rsub__(self, other):
        return (-self) + other

    def __mul__(self, factor):
        self._refuse_array(factor, "multiply")
        if not isinstance(factor, (int, float, np.floating, np.integer)):
            return NotImplemented
        factor = check_real("factor", factor)
        return HeightField(self.grid, self.heights * factor,
                           {"generator": "scaled", "factor": factor, "parts": [self.metadata]})

    __rmul__ = __mul__

    def __truediv__(self, divisor):
        self._refuse_array(divisor, "divide")
        if not isinstance(divisor, (int, float, np.floating, np.integer)):
            return NotImplemented
        divisor = check_real("divisor", divisor)
        if divisor == 0:
            raise ValueError("divisor must be non-zero, got 0; valid range: finite reals except 0")
        return self * (1.0 / divisor)

    # -- derived quantities ----------------------------------------------------------------------------------
    @property
    def shape(self) -> tuple:
        return self.grid.shape

    def detrended(self, kind: str = "mean") -> "HeightField":
        """Copy with the mean height (``kind="mean"``) or the least-squares plane ``h0 + a x + b y`` removed
        (``kind="plane"``: the tilt of a measured scan; a line on a profile). A plane is not periodic, so
        ``"plane"`` is refused on a periodic axis; the removed slopes ``a``, ``b`` [-] go into the metadata."""
        check_choice("kind", kind, ("mean", "plane"))
        if kind == "mean":
            return HeightField(self.grid, self.heights - self.heights.mean(),
                               {"generator": "detrended", "kind": kind, "parts": [self.metadata]})
        axes = [axis for axis, n in enumerate(self.shape) if n > 1]
        if any(self.grid.periodic[axis] for axis in axes):
            raise ValueError(f"kind = 'plane' on a grid with periodic = {self.grid.periodic}: a tilted plane is not "
                             "periodic; remove the tilt before declaring the field periodic, or use kind='mean'")
        coordinates = [c - c.mean() for c in self.grid.meshgrid()]
        basis = np.stack([np.ones(self.grid.size)] + [coordinates[axis].ravel() for axis in axes], axis=-1)
        coefficients = np.linalg.lstsq(basis, self.heights.ravel(), rcond=None)[0]
        slopes = [0.0, 0.0]
        for axis, slope in zip(axes, coefficients[1:]):
            slopes[axis] = float(slope)
        return HeightField(self.grid, self.heights - (basis @ coefficients).reshape(self.shape),
                           {"generator": "detrended", "kind": kind, "slopes": slopes, "parts": [self.metadata]})

    def mirrored(self) -> "HeightField":
        """The periodic field twice as long along each non-periodic axis: the window followed by its mirror
        image, so that the periodic repeat of a measured window has no height step at its edges (only a slope
        kink). Costs four times the pixels of a 2-D window."""
        axes = [axis for axis, n in enumerate(self.shape) if n > 1 and not self.grid.periodic[axis]]
        if not axes:
            raise ValueError(f"the field is already periodic (periodic = {self.grid.periodic}); mirrored() extends "
                             "non-periodic axes")
        heights, lengths = self.heights, list(self.grid.lengths)
        for axis in axes:
            heights = np.concatenate([heights, np.flip(heights, axis)], axis=axis)
            lengths[axis] *= 2
        return HeightField(Grid(heights.shape, tuple(lengths), True), heights,
                           {"generator": "mirrored", "parts": [self.metadata]})

    def coarsened(self, factor: int) -> "HeightField":
        """The field on :meth:`Grid.coarsened` ``(factor)``: each coarse pixel holds the mean height of the
        ``factor`` × ``factor`` fine pixels it covers (``factor`` × 1 on a profile), so the mean height is kept.
        The pixel counts must be multiples of ``factor``; :meth:`resampled` takes any shape."""
        try:
            grid = self.grid.coarsened(factor)
        except ValueError as error:
            raise ValueError(f"{error}; resampled(shape) takes any shape, cropped() trims the window") from None
        (nx, ny), (fx, fy) = grid.shape, (self.shape[0] // grid.shape[0], self.shape[1] // grid.shape[1])
        heights = self.heights.reshape(nx, fx, ny, fy).mean(axis=(1, 3))
        return HeightField(grid, heights, {"generator": "coarsened", "factor": factor, "parts": [self.metadata]})

    def cropped(self, x=None, y=None, *, by: str = "pixels") -> "HeightField":
        """The part of the field in the window ``x`` × ``y``, each a pair ``(start, stop)``, half-open as a
        slice; ``None`` keeps that axis whole (a profile's y is always whole).

        ``by="pixels"``: pixel indices, ``0 <= start < stop <= n``. ``by="metres"``: coordinates [m], keeping
        the pixels i whose position ``i dx`` lies in ``[start, stop)`` (positions within 1e-9 of a pixel of a
        bound count as on it), ``0 <= start < stop <= L``. A cut axis is no longer periodic; the window's
        lengths are the kept pixels times the pixel size. The metadata records the pixel ranges kept."""
        check_choice("by", by, ("pixels", "metres"))
        ranges = [self._crop_range(axis, bounds, by) for axis, bounds in enumerate((x, y))]
        (i0, i1), (j0, j1) = ranges
        heights = self.heights[i0:i1, j0:j1]
        spacing = self.grid.spacing
        periodic = tuple(wraps and stop - start == n
                         for wraps, (start, stop), n in zip(self.grid.periodic, ranges, self.shape))
        grid = Grid(heights.shape, tuple(d * n for d, n in zip(spacing, heights.shape)), periodic)
        return HeightField(grid, heights, {"generator": "cropped", "x": [i0, i1], "y": [j0, j1],
                                           "parts": [self.metadata]})

    def _crop_range(self, axis: int, bounds, by: str) -> tuple:
        """``(start, stop)`` pixel indices of :meth:`cropped`'s ``bounds`` along ``axis``, checked."""
        name, n = "xy"[axis], self.shape[axis]
        if bounds is None:
            return 0, n
        if axis == 1 and self.grid.is_profile:
            raise ValueError(f"y = {bounds!r} given for a profile; crop a profile along x only (y=None)")
        if np.ndim(bounds) != 1 or len(bounds) != 2:
            raise ValueError(f"{name} must be a pair (start, stop) or None, got {bounds!r}")
        if by == "pixels":
            start, stop = (check_integer(f"{name}[{k}]", bound, low=0, high=n) for k, bound in enumerate(bounds))
        else:
            length, step = self.grid.lengths[axis], self.grid.spacing[axis]
            start, stop = (check_real(f"{name}[{k}]", bound, low=0.0, high=length) for k, bound in enumerate(bounds))
            start, stop = (int(np.ceil(bound / step - 1e-9)) for bound in (start, stop))
        if start >= stop:
            raise ValueError(f"{name} = {bounds!r} keeps no pixel (by = {by!r}); give start < stop, the window "
                             f"being {n} pixels, {self.grid.lengths[axis]:g} m, along {name}")
        return start, stop

    def resampled(self, shape) -> "HeightField":
        """The field on ``shape`` pixels (any counts) over the same window: each new pixel holds the area-weighted
        mean of the heights of the old pixels it overlaps, a pixel being the cell ``[i dx, (i + 1) dx)`` ×
        ``[j dy, (j + 1) dy)`` of its height. So the mean height is kept; ``coarsened(f)`` is the case
        ``shape = (nx/f, ny/f)``, and an integer refinement repeats each pixel (the field is not smoothed).

        Boundary: the new cells tile exactly the window ``[0, Lx) × [0, Ly)`` of the old ones, so the first and
        last new pixels average the first and last old ones and nothing beyond the window; nothing wraps round,
        periodic or not, and the grid keeps its periodicity. A profile resamples to ``(n, 1)``."""
        if np.ndim(shape) != 1 or len(shape) != 2:
            raise ValueError(f"shape must be a pair (nx, ny), got {shape!r}")
        nx, ny = (check_integer(f"shape[{axis}]", n, low=1) for axis, n in enumerate(shape))
        if (ny == 1) != self.grid.is_profile:
            raise ValueError(f"shape = {(nx, ny)} would turn a {'profile' if self.grid.is_profile else '2-D map'} "
                             f"of shape {self.shape} into a {'profile' if ny == 1 else '2-D map'}; a profile "
                             "resamples to (n, 1), a map to (nx, ny) with ny > 1")
        lengths = self.grid.lengths if ny > 1 else (self.grid.lengths[0], self.grid.lengths[0] / nx)
        rows = _cell_weights(self.shape[0], nx) @ self.heights
        heights = (_cell_weights(self.shape[1], ny) @ rows.T).T
        return HeightField(Grid((nx, ny), lengths, self.grid.periodic), heights,
                           {"generator": "resampled", "shape": [nx, ny], "parts": [self.metadata]})

    # -- persistence -----------------------------------------------------------------------------------------
    def save(self, path) -> Path:
        """Save heights, grid and metadata to ``path`` (``.npz``); :meth:`load` restores an equal field."""
        from . import __version__
        return save_npz(path, {"heights": self.heights},
                        {"kind": "HeightField", "grid": self.grid.to_dict(), "metadata": self.metadata,
                         "version": __version__})

    @classmethod
    def load(cls, path) -> "HeightField":
        arrays, meta = load_npz(path)
        if meta.get("kind") != "HeightField":
            raise ValueError(f"{path} holds a {meta.get('kind')!r}, not a HeightField")
        return cls(Grid.from_dict(meta["grid"]), arrays["heights"], meta["metadata"])

    def __reduce__(self):
        # rebuild through the constructor so the unpickled heights are validated and read-only again
        return (type(self), (self.grid, np.asarray(self.heights), self.metadata))

    def __eq__(self, other):
        if not isinstance(other, HeightField):
            return NotImplemented
        return self.grid == other.grid and np.array_equal(self.heights, other.heights)

    def __repr__(self):
        h = self.heights
        return (f"HeightField(shape={self.grid.shape}, lengths={self.grid.lengths}, periodic={self.grid.periodic}, "
                f"h_min={h.min():.3g} m, h_max={h.max():.3g} m, generator={self.metadata.get('generator')!r})")
