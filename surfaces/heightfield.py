"""Height fields: heights in metres on a :class:`~surfaces.Grid`, with the recipe that made them."""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .validation import check_finite_array, check_real
from .grid import Grid
from .io import load_npz, save_npz


def _frozen(array: np.ndarray) -> np.ndarray:
    array = np.array(array, dtype=np.float64, copy=True)
    array.flags.writeable = False
    return array


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
    def from_array(cls, heights, lengths, periodic=False, **metadata) -> "HeightField":
        """Wrap a plain array of heights [m] measured over ``lengths`` [m]."""
        heights = check_finite_array("heights", heights)
        if heights.ndim == 1:
            heights = heights[:, None]
        if heights.size == 0:
            raise ValueError(f"heights is empty (shape {heights.shape}); it needs at least one pixel per axis")
        if np.ndim(lengths) == 0:
            lengths = (lengths, lengths if heights.shape[1] > 1 else lengths / heights.shape[0])
        grid = Grid(heights.shape, tuple(lengths), periodic)
        return cls(grid, heights, {"generator": "from_array", **metadata})

    @classmethod
    def read(cls, path, lengths=None, periodic=False, unit: float = 1.0) -> "HeightField":
        """Read a height map from ``.npz`` (saved field), ``.npy`` or whitespace-separated text.

        For ``.npy`` and text, ``lengths`` [m] is required and ``unit`` converts the stored numbers to metres
        (e.g. ``unit=1e-6`` for a map in µm).
        """
        path = Path(path)
        if path.suffix == ".npz":
            return cls.load(path)
        if lengths is None:
            raise ValueError(f"lengths (physical size in m) is required to read {path.name}; got None")
        check_real("unit", unit, low=0.0, low_open=True)
        raw = np.load(path) if path.suffix == ".npy" else np.loadtxt(path, ndmin=2)
        return cls.from_array(raw * unit, lengths, periodic, source=str(path))

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

    def detrended(self) -> "HeightField":
        """Copy with the mean height removed."""
        return HeightField(self.grid, self.heights - self.heights.mean(),
                           {"generator": "detrended", "parts": [self.metadata]})

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
