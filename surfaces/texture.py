"""Texture statistics of ridged height fields: dominant wavelength, ridge orientation, sweat pores.

Conventions as in ``docs/reference/conventions.md``: orientation θ is the direction of the ridges measured from the
x axis (axis 0) in ``[0, π)``; wavevectors are angular, ``q = 2π/λ``.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.fft
import scipy.ndimage
import scipy.signal
import scipy.spatial

from .validation import check_positive, check_real
from .ridges import PORE_DEPTH, PORE_DIAMETER
from .heightfield import HeightField
from .statistics import as_height_field, gradient_components, normalised_heights


def dominant_wavelength(field: HeightField, band: float = np.sqrt(2.0)) -> float:
    """Wavelength ``2π/q̄`` [m] of the strongest spectral peak, resolved below the bin spacing ``2π/L``.

    The peak ring ``q_p`` maximises the radial power density ``Σ_ring |ĥ_q|²`` (∝ q C(q)); ``q̄`` is then the
    power-weighted mean ``Σ |q| |ĥ_q|² / Σ |ĥ_q|²`` over all 2-D modes with ``q_p/band ≤ |q| ≤ q_p·band``
    (harmonics of a ridge profile at ``2q_p`` and the q = 0 mode are outside). Non-periodic axes are tapered
    by a Tukey window (cosine over a quarter of the length at each end): its leakage is symmetric about a mode, so
    the centroid interpolates between modes, and it weights the window almost uniformly (a Hann window would
    weight its centre, where a fingerprint core often sits).
    """
    field = as_height_field(field)
    band = check_real("band", band, low=1.0, low_open=True, high=2.0)
    grid = field.grid
    h = (field.heights - field.heights.mean()) * _tukey_window(grid)
    power = np.abs(np.fft.fft2(h)) ** 2
    q = grid.wavevector_magnitude()
    ring = np.rint(q / (2 * np.pi / max(grid.lengths))).astype(np.int64).ravel()
    ring_power = np.bincount(ring, power.ravel())
    ring_power[0] = 0.0
    if not ring_power.any():
        raise ValueError("field is flat (no spectral power at q > 0); its dominant wavelength is undefined")
    q_peak = np.argmax(ring_power) * 2 * np.pi / max(grid.lengths)
    selected = (q >= q_peak / band) & (q <= q_peak * band)
    q_mean = np.sum(q[selected] * power[selected]) / np.sum(power[selected])
    return float(2 * np.pi / q_mean)


def _tukey_window(grid, taper: float = 0.5) -> np.ndarray:
    """Product of Tukey windows (cosine-tapered fraction ``taper``) on the non-periodic axes."""
    window = np.ones(grid.shape)
    for axis, (n, periodic) in enumerate(zip(grid.shape, grid.periodic)):
        if n > 1 and not periodic:
            window *= scipy.signal.windows.tukey(n, taper).reshape((n, 1) if axis == 0 else (1, n))
    return window


@dataclass(frozen=True)
class OrientationField:
    """Ridge orientation estimated by the structure tensor.

    ``angle`` [rad]: ridge direction from the x axis in ``[0, π)``, per pixel; ``coherence`` [-]:
    ``sqrt((Jxx − Jyy)² + 4Jxy²)/(Jxx + Jyy)`` in [0, 1] (1 = perfectly straight parallel ridges);
    ``window`` [m]: standard deviation of the Gaussian that averaged the tensor.
    """

    angle: np.ndarray
    coherence: np.ndarray
    window: float


def _gaussian_smooth(values: np.ndarray, sigma, periodic) -> np.ndarray:
    """Gaussian filter of std ``sigma`` [pixels] by FFT: wrapped on periodic axes, mirrored (3σ) otherwise."""
    pad = [(0, 0) if wraps else (int(np.ceil(3 * s)),) * 2 for s, wraps in zip(sigma, periodic)]
    padded = np.pad(values, pad, mode="symmetric")
    spectrum = scipy.ndimage.fourier_gaussian(scipy.fft.rfft2(padded), sigma, n=padded.shape[-1])
    smoothed = scipy.fft.irfft2(spectrum, s=padded.shape)
    return smoothed[tuple(slice(before, before + n) for (before, _), n in zip(pad, values.shape))]


def orientation_field(field: HeightField, window=None) -> OrientationField:
    """Structure-tensor ridge orientation (Kass & Witkin 1987; Bazen & Gerez 2002) of a height field.

    ``J = G_w * (∇h ∇hᵀ)`` with central-difference gradients and a Gaussian of standard deviation ``window``
    [m] (default: the :func:`dominant_wavelength`, which averages over one ridge and one furrow), applied by FFT
    (wrapped on periodic axes, mirrored on the others). The gradient
    points across the ridges, so ``θ = ½ atan2(2Jxy, Jxx − Jyy) + π/2`` (mod π).
    """
    field = as_height_field(field)
    grid = field.grid
    if grid.is_profile:
        raise ValueError(f"orientation_field needs a 2-D field; got grid shape {grid.shape}")
    window = dominant_wavelength(field) if window is None else check_positive("window", window)
    gx, gy = gradient_components(normalised_heights(field)[0], grid)      # angle and coherence do not depend on the scale
    sigma = (window / grid.spacing[0], window / grid.spacing[1])
    jxx, jyy, jxy = (_gaussian_smooth(values, sigma, grid.periodic) for values in (gx * gx, gy * gy, gx * gy))
    anisotropy = np.hypot(jxx - jyy, 2 * jxy)
    angle = np.mod(0.5 * np.arctan2(2 * jxy, jxx - jyy) + 0.5 * np.pi, np.pi)
    coherence = anisotropy / np.maximum(jxx + jyy, np.finfo(float).tiny)
    return OrientationField(angle, coherence, window)


def angular_difference(a, b) -> np.ndarray:
    """Smallest difference of two orientations (mod π) [rad], in ``[0, π/2]``."""
    d = np.mod(np.asarray(a) - np.asarray(b), np.pi)
    return np.minimum(d, np.pi - d)


@dataclass(frozen=True)
class DetectedPores:
    """Sweat pores found by :func:`detect_pores`: ``centres`` (m, shape (count, 2)), ``count`` and
    ``density`` = count / nominal area [1/m²]."""

    centres: np.ndarray
    count: int
    density: float


def detect_pores(field: HeightField, pore_diameter: float = PORE_DIAMETER, min_depth=None,
                 orientation: OrientationField = None) -> DetectedPores:
    """Find pits on ridge crests: points lower by ``min_depth`` [m] than both points ``±R t`` along the ridge.

    ``t`` is the local ridge direction (``orientation``, default :func:`orientation_field`) and
    ``R = 0.75 pore_diameter`` [m] lies just outside a pore of that opening diameter. A furrow or a flank is
    level along ``t`` and a crest is a maximum there, so only closed pits pass; both points ``±R t`` must also
    lie on the crest, in the top quarter between the local furrow and crest levels (minimum and maximum over
    one :func:`dominant_wavelength`), which rejects furrows where ``t`` is uncertain (minutiae). Each pore is
    a lowest passing pixel; passing pixels within one diameter of it (minimum image on periodic axes)
    belong to it (distinct pores are at least 1.25 diameters apart, as :func:`fingerprint` places them).
    The pore must span at least 3 pixels. ``min_depth`` defaults to a quarter of the default pore depth
    (5 µm); on a rough field it must clear the roughness (about 4× its rms height, see
    ``docs/guide/fingerprint.md``).
    """
    field = as_height_field(field)
    grid = field.grid
    pore_diameter = check_positive("pore_diameter", pore_diameter)
    pixel = max(grid.spacing)
    if pore_diameter < 3 * pixel:
        raise ValueError(f"pore_diameter = {pore_diameter!r} m spans fewer than 3 pixels of {pixel:g} m; "
                         f"valid range [{3 * pixel:g}, inf) m on this grid")
    min_depth = 0.25 * PORE_DEPTH if min_depth is None else check_positive("min_depth", min_depth)
    if orientation is None:
        orientation = orientation_field(field)
    h = field.heights
    spacing = np.asarray(grid.spacing)
    radius_px = 0.75 * pore_diameter / spacing
    i, j = np.meshgrid(np.arange(grid.shape[0]), np.arange(grid.shape[1]), indexing="ij")
    ti, tj = np.cos(orientation.angle) * radius_px[0], np.sin(orientation.angle) * radius_px[1]
    wrap = grid.fully_periodic
    ahead = scipy.ndimage.map_coordinates(h, [i + ti, j + tj], order=1, mode="grid-wrap" if wrap else "nearest")
    behind = scipy.ndimage.map_coordinates(h, [i - ti, j - tj], order=1, mode="grid-wrap" if wrap else "nearest")
    surroundings = np.minimum(ahead, behind)
    mode = ["wrap" if periodic else "nearest" for periodic in grid.periodic]
    size = np.maximum(1, np.rint(dominant_wavelength(field) / spacing)).astype(int)
    crest = scipy.ndimage.maximum_filter(h, size=size, mode=mode)
    furrow = scipy.ndimage.minimum_filter(h, size=size, mode=mode)
    pits = np.argwhere((h < surroundings - min_depth) & (surroundings > furrow + 0.75 * (crest - furrow)))
    # one pore per pit: take the lowest pit pixel, drop the pit pixels within one diameter, repeat
    positions = pits * spacing
    order = np.argsort(h[tuple(pits.T)], kind="stable")
    box = [length if periodic else 3 * length for length, periodic in zip(grid.lengths, grid.periodic)]
    tree = scipy.spatial.cKDTree(positions, boxsize=box)
    taken = np.zeros(len(pits), dtype=bool)
    centres = []
    for index in order:
        if taken[index]:
            continue
        centres.append(positions[index])
        taken[tree.query_ball_point(positions[index], pore_diameter)] = True
    centres = np.array(centres, dtype=float).reshape(-1, 2)
    return DetectedPores(centres, len(centres), len(centres) / grid.area)
