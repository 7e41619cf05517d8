"""The computational grid: shape, physical size and periodicity — the single source of truth for all three.

Conventions (see ``docs/reference/conventions.md``): axis 0 is x, axis 1 is y; pixel ``(i, j)`` sits at
``(i*dx, j*dy)``; wavevectors follow ``numpy.fft`` order, ``q = 2*pi*k/L`` in rad/m. A one-dimensional
(plane-strain) profile is a grid of shape ``(n, 1)``.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from .validation import check_bool, check_integer, check_real

# Valid window lengths [m]: wide enough for any physical surface (nm to km, with 40 orders to spare), narrow
# enough that areas, squared wavevectors and the spectral moments of a grid stay inside float64.
MIN_LENGTH, MAX_LENGTH = 1e-50, 1e50


@dataclass(frozen=True, eq=True)
class Grid:
    """Regular 2-D grid of ``shape`` pixels covering ``lengths`` metres, periodic per axis.

    Parameters
    ----------
    shape : (int, int)
        Number of pixels along x and y; ``(n, 1)`` for a profile.
    lengths : (float, float)
        Physical size along x and y [m]. For a non-periodic axis it is the size of the sampled window.
    periodic : bool or (bool, bool)
        Whether the field repeats with period ``lengths`` along each axis. Stored as a tuple.
    """

    shape: tuple
    lengths: tuple
    periodic: tuple = (True, True)

    def __post_init__(self):
        shape = tuple(self.shape) if np.iterable(self.shape) else (self.shape,)
        lengths = tuple(self.lengths) if np.iterable(self.lengths) else (self.lengths,)
        if len(shape) != 2:
            raise ValueError(f"shape must have two entries (nx, ny), got {self.shape!r}; use (n, 1) for a profile")
        if len(lengths) != 2:
            raise ValueError(f"lengths must have two entries (Lx, Ly) in metres, got {self.lengths!r}")
        for axis, n in enumerate(shape):
            check_integer(f"shape[{axis}]", n, low=1)
        periodic = self.periodic
        periodic = (check_bool("periodic", periodic),) * 2 if np.ndim(periodic) == 0 else \
            tuple(check_bool(f"periodic[{axis}]", p) for axis, p in enumerate(periodic))
        if len(periodic) != 2:
            raise ValueError(f"periodic must be a bool or two bools, got {self.periodic!r}")
        object.__setattr__(self, "shape", tuple(int(n) for n in shape))
        object.__setattr__(self, "lengths", tuple(check_real(f"lengths[{axis}]", length, low=MIN_LENGTH,
                                                             high=MAX_LENGTH)
                                                  for axis, length in enumerate(lengths)))
        object.__setattr__(self, "periodic", periodic)

    @property
    def spacing(self) -> tuple:
        """Pixel size (dx, dy) [m]."""
        return tuple(length / n for length, n in zip(self.lengths, self.shape))

    @property
    def pixel_area(self) -> float:
        """Area of one pixel [m^2]."""
        return self.spacing[0] * self.spacing[1]

    @property
    def area(self) -> float:
        """Nominal (apparent) area Lx*Ly [m^2]."""
        return self.lengths[0] * self.lengths[1]

    @property
    def size(self) -> int:
        """Number of pixels."""
        return self.shape[0] * self.shape[1]

    @property
    def is_profile(self) -> bool:
        """True for a 1-D (plane-strain) profile, shape ``(n, 1)``."""
        return self.shape[1] == 1

    @property
    def fully_periodic(self) -> bool:
        """True if every axis with more than one pixel is periodic (a profile's y flag is irrelevant)."""
        return all(periodic for n, periodic in zip(self.shape, self.periodic) if n > 1)

    def coordinates(self) -> tuple:
        """Pixel coordinates ``(x, y)`` as two 1-D arrays [m]."""
        return tuple(np.arange(n) * d for n, d in zip(self.shape, self.spacing))

    def meshgrid(self) -> tuple:
        """Pixel coordinates as two arrays of ``shape`` [m] (``indexing='ij'``)."""
        return np.meshgrid(*self.coordinates(), indexing="ij")

    def mode_indices(self, real: bool = False) -> tuple:
        """Integer wavenumbers ``(kx, ky)`` in ``numpy.fft`` order, broadcastable to the spectrum shape.

        ``real=True`` gives the half spectrum of ``numpy.fft.rfft2`` (last axis ``0 .. ny//2``).
        """
        nx, ny = self.shape
        kx = np.concatenate([np.arange((nx - 1) // 2 + 1), np.arange(-(nx // 2), 0)])
        ky = np.arange(ny // 2 + 1) if real else np.concatenate([np.arange((ny - 1) // 2 + 1),
                                                                 np.arange(-(ny // 2), 0)])
        return kx[:, None], ky[None, :]

    def wavevectors(self, real: bool = False) -> tuple:
        """Angular wavevector components ``(qx, qy) = 2π (kx/Lx, ky/Ly)`` [rad/m], broadcastable to the
        spectrum shape.

        ``real=True`` gives the half spectrum of ``numpy.fft.rfft2`` (last axis halved). The values depend
        only on the integer wavenumber and the physical size, so a refined grid has bit-identical ``q`` on
        the modes it shares with the coarse one.
        """
        kx, ky = self.mode_indices(real)
        return 2 * np.pi * kx / self.lengths[0], 2 * np.pi * ky / self.lengths[1]

    @cached_property
    def _q_magnitude(self):
        qx, qy = self.wavevectors()
        q = np.hypot(qx, qy)
        q.flags.writeable = False
        return q

    def wavevector_magnitude(self) -> np.ndarray:
        """``|q|`` on the full FFT grid [rad/m] (read-only, cached)."""
        return self._q_magnitude

    def refined(self, factor: int) -> "Grid":
        """Same physical window with ``factor`` times more pixels per axis (profiles stay profiles)."""
        check_integer("factor", factor, low=1)
        ny = self.shape[1] if self.is_profile else self.shape[1] * factor
        return Grid((self.shape[0] * factor, ny), self.lengths, self.periodic)

    def coarsened(self, factor: int) -> "Grid":
        """Same physical window with ``factor`` times fewer pixels per axis (profiles stay profiles); the pixel
        counts must be multiples of ``factor``. The inverse of :meth:`refined`."""
        check_integer("factor", factor, low=1)
        ny_factor = 1 if self.is_profile else factor
        for axis, (n, f) in enumerate(zip(self.shape, (factor, ny_factor))):
            if n % f:
                raise ValueError(f"shape[{axis}] = {n} is not a multiple of factor = {factor}")
        return Grid((self.shape[0] // factor, self.shape[1] // ny_factor), self.lengths, self.periodic)

    def to_dict(self) -> dict:
        return {"shape": list(self.shape), "lengths": list(self.lengths), "periodic": list(self.periodic)}

    @classmethod
    def from_dict(cls, data: dict) -> "Grid":
        return cls(tuple(data["shape"]), tuple(data["lengths"]), tuple(data["periodic"]))

    def __getstate__(self):
        return self.to_dict()

    def __setstate__(self, state):
        object.__setattr__(self, "shape", tuple(state["shape"]))
        object.__setattr__(self, "lengths", tuple(state["lengths"]))
        object.__setattr__(self, "periodic", tuple(state["periodic"]))
