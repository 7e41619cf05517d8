"""Statistics of height fields, with one convention (``docs/reference/conventions.md``).

PSD: ``C(q) = (2π)^-2 ∫ d²x <h(x) h(0)> exp(-i q·x)`` [m^4], so that ``h_rms² = ∫ d²q C(q) = 2π ∫ q C(q) dq``,
``h'_rms² = 2π ∫ q³ C dq`` and ``h''_rms² = 2π ∫ q⁵ C dq``. On a periodic Lx×Ly grid with
``ĥ_q = fft2(h)/N`` this is ``C(q) = |ĥ_q|² Lx Ly / (2π)²``. For a profile (grid ``(n, 1)``) the 1-D PSD
``C₁(q) = |ĥ_q|² L / (2π)`` [m^3] satisfies ``h_rms² = 2 ∫_0^∞ C₁ dq``.

The rms slope is the rms *gradient* ``sqrt(<|∇h|²>)`` (both components; for a profile just ``dh/dx``) and the
rms curvature is ``sqrt(<(∇²h)²>)``. No factors of 2π or √2 are hidden: an isotropic surface has
``<(∂h/∂x)²> = h'_rms²/2``.
"""
from __future__ import annotations

import numpy as np

from .validation import check_choice, check_integer
from .heightfield import HeightField


def as_height_field(field) -> HeightField:
    if not isinstance(field, HeightField):
        raise TypeError(f"field must be a surfaces.HeightField, got {type(field).__name__}")
    return field


def normalised_heights(field: HeightField) -> tuple:
    """``(h / s, s)`` with ``s = max |h|`` (1 for a flat zero field): the statistics work on heights of order
    one and scale back, so that squares neither overflow (|h| ≳ 1e150 m) nor underflow (|h| ≲ 1e-150 m)."""
    scale = float(np.max(np.abs(field.heights)))
    scale = scale if scale > 0 else 1.0
    return field.heights / scale, scale


def _spectral_moment(heights: np.ndarray, grid, order: int) -> float:
    """``Σ_q |q|^(2*order) |ĥ_q|²`` of ``heights`` on a periodic ``grid`` (exact for band-limited fields)."""
    h = heights - heights.mean()
    power = np.abs(np.fft.fft2(h) / h.size) ** 2
    return float(np.sum(grid.wavevector_magnitude() ** (2 * order) * power))


def _default_method(field: HeightField, method):
    if method is None:
        method = "spectral" if field.grid.fully_periodic else "finite-difference"
    check_choice("method", method, {"spectral", "finite-difference"})
    if method == "spectral" and not field.grid.fully_periodic:
        raise ValueError("method='spectral' needs a periodic grid; this field has periodic="
                         f"{field.grid.periodic} (use method='finite-difference')")
    return method


def rms_height(field: HeightField) -> float:
    """Root-mean-square height about the mean, ``sqrt(<(h - <h>)²>)`` [m]."""
    h, scale = normalised_heights(as_height_field(field))
    return scale * float(np.sqrt(np.mean((h - h.mean()) ** 2)))


def gradient_components(h: np.ndarray, grid) -> list:
    """Central-difference gradient components of ``h`` (second-order one-sided at non-periodic edges)."""
    grads = []
    for axis, (n, d, periodic) in enumerate(zip(grid.shape, grid.spacing, grid.periodic)):
        if n == 1:
            continue
        if periodic:
            grads.append((np.roll(h, -1, axis) - np.roll(h, 1, axis)) / (2 * d))
        else:
            grads.append(np.gradient(h, d, axis=axis, edge_order=min(2, n - 1)))
    return grads


def rms_slope(field: HeightField, method=None) -> float:
    """Root-mean-square gradient ``sqrt(<|∇h|²>)`` [-].

    ``method='spectral'`` (default for periodic grids) is exact for band-limited periodic fields;
    ``'finite-difference'`` uses central differences (default for non-periodic grids).
    """
    field = as_height_field(field)
    h, scale = normalised_heights(field)
    if _default_method(field, method) == "spectral":
        return scale * float(np.sqrt(_spectral_moment(h, field.grid, 1)))
    return scale * float(np.sqrt(sum(np.mean(g ** 2) for g in gradient_components(h, field.grid))))


def rms_curvature(field: HeightField, method=None) -> float:
    """Root-mean-square Laplacian ``sqrt(<(∇²h)²>)`` [1/m] (``= sqrt(2π ∫ q⁵ C dq)``)."""
    field = as_height_field(field)
    h, scale = normalised_heights(field)
    if _default_method(field, method) == "spectral":
        return scale * float(np.sqrt(_spectral_moment(h, field.grid, 2)))
    laplacian = 0.0
    for axis, (n, d, periodic) in enumerate(zip(field.grid.shape, field.grid.spacing, field.grid.periodic)):
        if n < 3:
            continue
        if periodic:
            laplacian = laplacian + (np.roll(h, -1, axis) - 2 * h + np.roll(h, 1, axis)) / d ** 2
        else:
            laplacian = laplacian + np.gradient(np.gradient(h, d, axis=axis, edge_order=2), d, axis=axis,
                                                edge_order=2)
    return scale * float(np.sqrt(np.mean(laplacian ** 2)))


def _window(field: HeightField, window):
    if window is None:
        window = "none" if field.grid.fully_periodic else "hann"
    check_choice("window", window, {"none", "hann"})
    if window == "none":
        return np.ones(field.grid.shape)
    w = np.ones(field.grid.shape)
    for axis, (n, periodic) in enumerate(zip(field.grid.shape, field.grid.periodic)):
        if n > 1 and not periodic:
            shape = [1, 1]
            shape[axis] = n
            w = w * np.hanning(n).reshape(shape)
    return w / np.sqrt(np.mean(w ** 2))     # keeps the total power (h_rms) unchanged on average


def psd(field: HeightField, bins=None, window=None) -> tuple:
    """Radially averaged power spectral density ``(q [rad/m], C [m^4])``; for a profile ``(q, C₁ [m^3])``.

    ``bins``: number of radial bins (default: one per ``2π/L`` ring). ``window``: ``'hann'`` (default on
    non-periodic axes, power-normalised; it tapers only the non-periodic axes, so on a periodic grid it
    equals ``'none'``) or ``'none'``. Only ``q > 0`` is returned; empty bins are dropped.
    Profile: ``C₁`` averages the ``±q`` pair; the Nyquist mode (even ``n``) has no partner and is halved, so that
    ``2 Σ_q C₁(q) Δq = h_rms²`` exactly (Parseval, ``Δq = 2π/L``) for an unwindowed periodic profile.
    """
    field = as_height_field(field)
    grid = field.grid
    if bins is not None:
        check_integer("bins", bins, low=1)
    h = (field.heights - field.heights.mean()) * _window(field, window)
    power = np.abs(np.fft.fft2(h) / h.size) ** 2
    if grid.is_profile:
        q = np.abs(grid.wavevectors()[0][:, 0])
        spectrum = power[:, 0] * grid.lengths[0] / (2 * np.pi)
        positive = q > 0
        order = np.argsort(q[positive], kind="stable")
        q_pos, c_pos = q[positive][order], spectrum[positive][order]
        unique_q, inverse = np.unique(q_pos, return_inverse=True)   # average the ±q pair
        c_mean = np.bincount(inverse, c_pos) / np.bincount(inverse)
        if grid.shape[0] % 2 == 0:
            c_mean[-1] /= 2                                           # Nyquist: its own partner
        return unique_q, c_mean
    spectrum = power * grid.area / (2 * np.pi) ** 2
    q = grid.wavevector_magnitude()
    dq = 2 * np.pi / max(grid.lengths)
    q_max = q.max()
    n_bins = int(np.ceil(q_max / dq)) if bins is None else int(bins)
    edges = np.linspace(0.5 * dq, q_max * (1 + 1e-12), n_bins + 1) if bins is not None else \
        (np.arange(n_bins + 1) + 0.5) * dq
    index = np.digitize(q.ravel(), edges) - 1
    valid = (index >= 0) & (index < n_bins) & (q.ravel() > 0)
    counts = np.bincount(index[valid], minlength=n_bins)
    mean_q = np.bincount(index[valid], q.ravel()[valid], minlength=n_bins)
    mean_c = np.bincount(index[valid], spectrum.ravel()[valid], minlength=n_bins)
    keep = counts > 0
    return mean_q[keep] / counts[keep], mean_c[keep] / counts[keep]
