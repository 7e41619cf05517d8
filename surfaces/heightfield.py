"""Height fields: heights in metres on a :class:`~surfaces.Grid`, with the recipe that made them."""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .validation import check_choice, check_finite_array, check_real
from .grid import Grid
from .io import grid_from_columns, length_unit, load_npz, read_npy, read_text_table, save_npz


def _physical_size(shape: tuple, lengths, pixel_size) -> tuple:
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


def harmonic_fill(heights, missing, spacing, periodic=False) -> np.ndarray:
    """``heights`` with the ``missing`` pixels replaced by the discrete harmonic interpolation of the others.

    Each missing pixel p satisfies ``Σ_n (h_n − h_p)/d_n² = 0`` over its four neighbours n (``d_n`` the pixel
    size ``spacing`` [m] along the neighbour's axis): the five-point Laplace equation with the measured pixels
    as boundary values. A non-periodic axis has no neighbour beyond the edge (zero normal slope there); a
    periodic one wraps. Exact for ``a + b x + c y + e xy + f (x² − y²)`` in holes away from the edge.
    """
    from scipy.sparse import coo_matrix
    from scipy.sparse.linalg import spsolve
    missing = np.asarray(missing, dtype=bool)
    if missing.all():
        raise ValueError(f"every height is missing ({missing.size} pixels); nothing to interpolate from")
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
    filled[tuple(points.T)] = spsolve(matrix, rhs)
    return filled


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
        grid = Grid(heights.shape, _physical_size(heights.shape, lengths, pixel_size), periodic)
        return cls(grid, heights, {"generator": "from_array", **metadata})

    @classmethod
    def read(cls, path, lengths=None, periodic=False, unit=1.0, *, pixel_size=None, rows: str = "x",
             layout: str = "auto", delimiter=None, skiprows: int = 0, lateral_unit=None,
             missing: str = "refuse") -> "HeightField":
        """Read a height map from ``.npz`` (a saved field), ``.npy`` or text (white space, ``,`` or ``;``).

        A text file is either a **matrix** of heights or an **x-y-z** (or x-z) **column export** on a regular
        lattice; ``layout="auto"`` takes 2 or 3 columns whose first columns lie on a regular lattice as a
        column export, refuses 2 or 3 columns that do not, and reads anything else as a matrix.

        * ``unit``: metres per stored height, a factor or a name (``"um"``, ``"nm"``, …: the keys of
          :data:`surfaces.io.LENGTH_UNITS`); ``lateral_unit`` (column exports) the same for x and y, default
          ``unit``.
        * Matrix and ``.npy``: the size as ``lengths`` [m] or ``pixel_size`` [m] (see :meth:`from_array`);
          ``rows="x"``: row i holds the heights at x_i (numpy's layout of :attr:`heights`, what
          ``numpy.savetxt(path, field.heights)`` writes); ``rows="y"``: row j holds the heights along x at y_j
          (the image layout of instrument exports and of SurfaceTopography's text reader).
        * Column exports carry their size: ``lengths`` and ``pixel_size`` are refused; ``Lx = nx dx``.
        * ``missing``: NaN heights (and lattice points a column export leaves out) are refused (``"refuse"``)
          or filled with the harmonic interpolation of their neighbours (``"harmonic"``, :func:`harmonic_fill`;
          the count is kept in the metadata as ``missing_points``).
        """
        path = Path(path)
        if path.suffix == ".npz":
            return cls.load(path)
        check_choice("rows", rows, ("x", "y"))
        check_choice("layout", layout, ("auto", "matrix", "columns"))
        check_choice("missing", missing, ("refuse", "harmonic"))
        scale = length_unit("unit", unit)
        raw = read_npy(path) if path.suffix == ".npy" else read_text_table(path, delimiter, skiprows)
        if raw.ndim > 2:
            raise ValueError(f"{path} holds an array of shape {raw.shape}; a height map is 1-D (a profile) or 2-D")
        if np.iscomplexobj(raw):
            check_finite_array("heights", raw)                      # the TypeError naming complex heights
        raw = np.asarray(raw, dtype=np.float64)
        if raw.ndim == 1:
            raw = raw[:, None]
        source = {"source": str(path)}
        if path.suffix != ".npy" and layout != "matrix" and raw.ndim == 2 and raw.shape[1] in (2, 3):
            try:
                heights, spacing = grid_from_columns(raw)
            except ValueError as error:
                if layout == "columns":
                    raise ValueError(f"{path}: {error}") from None
                raise ValueError(f"{path} has {raw.shape[1]} columns that are not an x-y-z (or x-z) export on a "
                                 f"regular lattice ({error}); if it is a height matrix {raw.shape[1]} pixels wide, "
                                 "pass layout='matrix'") from None
            if lengths is not None or pixel_size is not None:
                raise ValueError(f"{path} is a column export, which fixes the pixel size ({spacing[0]:g}, "
                                 f"{spacing[1]!s} in the file's unit); lengths and pixel_size must be None")
            lateral = scale if lateral_unit is None else length_unit("lateral_unit", lateral_unit)
            pixel_size = tuple(spacing[0] * lateral if d is None else d * lateral for d in spacing)
            source["layout"] = "columns"
        elif layout == "columns":
            raise ValueError(f"{path} has shape {raw.shape}, not the 2 or 3 columns of an x-z or x-y-z export")
        else:
            heights = raw.T if rows == "y" else raw
            if lengths is None and pixel_size is None:
                raise ValueError(f"lengths or pixel_size (physical size in m) is required to read {path.name}; "
                                 "got neither")
        holes = np.isnan(heights)
        if holes.any():
            if missing == "refuse":
                raise ValueError(f"{path} has {int(holes.sum())} missing heights (NaN or absent points) of "
                                 f"{holes.size}, the first at index {np.argwhere(holes)[0].tolist()}; pass "
                                 "missing='harmonic' to fill them from their neighbours")
            size = _physical_size(heights.shape, lengths, pixel_size)
            spacing = (size[0] / heights.shape[0], size[1] / heights.shape[1])
            heights = harmonic_fill(heights, holes, spacing, periodic)
            source["missing_points"] = int(holes.sum())
        return cls.from_array(heights * scale, lengths, periodic, pixel_size=pixel_size, **source)

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
        ``factor`` × ``factor`` fine pixels it covers (``factor`` × 1 on a profile), so the mean height is kept."""
        grid = self.grid.coarsened(factor)
        (nx, ny), (fx, fy) = grid.shape, (self.shape[0] // grid.shape[0], self.shape[1] // grid.shape[1])
        heights = self.heights.reshape(nx, fx, ny, fy).mean(axis=(1, 3))
        return HeightField(grid, heights, {"generator": "coarsened", "factor": factor, "parts": [self.metadata]})

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
