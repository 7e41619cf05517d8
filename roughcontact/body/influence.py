"""Real-space influence coefficients [m/Pa]: the displacement of an elastic body's surface under a uniform unit
pressure on one rectangular pixel, for the free-surface (zero-padded, linear) convolution.

* :func:`pixel_potential`: ∫∫ dA'/√(|r − r'|² + c²) over a pixel in closed form;
* :func:`love_pixel_displacement`: the half-space, Love (1929), Phil. Trans. A 228:377;
* :func:`free_surface_correction`: a layered body's correction to its layer's half-space, ΔΦ(q) = Φ(q) − 2/(E* q)
  transformed to real space (``docs/guide/layered.md``, "The free-surface kernel").

Pure numpy and scipy (special functions, splines): layer 2's bottom, beside the Fourier kernels of
:mod:`roughcontact.body.kernels`, and imported by the FFT operator :mod:`roughcontact.body.elastic`.
"""
from __future__ import annotations

import numpy as np


def pixel_potential(x, y, dx, dy, height=0.0):
    """∫∫ dA'/√(|r − r'|² + c²) [m] over the pixel |x'| ≤ dx/2, |y'| ≤ dy/2, at (x, y) [m] and height c ≥ 0 [m].

    Closed form: Σ± G(x ± dx/2, y ± dy/2) with G(X, Y) = X asinh(Y/√(X² + c²)) + Y asinh(X/√(Y² + c²))
    − c atan(XY/(c √(X² + Y² + c²))), whose ∂²G/∂X∂Y is the integrand (the X ln√(X² + c²) and Y ln√(Y² + c²)
    terms of the antiderivative cancel in the sum). ``x``, ``y`` broadcast; overflow-free for any finite c.
    """
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    c = float(height)

    def antiderivative(X, Y):
        rx, ry = np.hypot(X, c), np.hypot(Y, c)
        value = (np.where(rx > 0, X * np.arcsinh(Y / np.where(rx > 0, rx, 1.0)), 0.0)
                 + np.where(ry > 0, Y * np.arcsinh(X / np.where(ry > 0, ry, 1.0)), 0.0))
        if c > 0:
            value = value - c * np.arctan2(X * Y / c, np.hypot(np.hypot(X, Y), c))
        return value

    a, b = dx / 2, dy / 2
    return (antiderivative(x + a, y + b) - antiderivative(x + a, y - b)
            - antiderivative(x - a, y + b) + antiderivative(x - a, y - b))


def love_pixel_displacement(x, y, dx, dy, E_star):
    """Displacement u(x, y) [m per Pa] of a half-space under unit pressure on the pixel |x'| ≤ dx/2, |y'| ≤ dy/2.

    Love (1929): u = 1/(π E*) ∫∫ dA'/|r − r'| (:func:`pixel_potential` at height 0). ``x``, ``y`` [m] broadcast.
    """
    return pixel_potential(x, y, dx, dy) / (np.pi * E_star)


# -- free surface: real-space influence coefficients (docs/guide/layered.md, "The free-surface kernel") -------------
# ΔΦ(q) = Φ(q) − 2/(E* q) splits into b e^{−qt}/q (b = lim q ΔΦ, transformed in closed form) and a remainder
# ΔΦ₂ whose q ΔΦ₂ vanishes at q = 0 and, like ΔΦ, dies beyond q t ≈ 25, so its Hankel transform converges fast.
_HANKEL_QT = 30.0        # upper limit of the Hankel integral in q t: the remainder's tail is b e^{−30} ~ 1e-13 b
_HANKEL_NODES = 20       # Gauss–Legendre nodes per q panel
_HANKEL_PERIODS = 3.0    # a q panel spans at most 3 periods of J0(q r) and at most Δq = 1/t
_TABLE_STEP = 16         # the table of Δw₂(r) is uniform in r with step t/16 up to _TABLE_UNIFORM t ...
_TABLE_UNIFORM = 100.0
_TABLE_RATIO = 1.02      # ... and geometric beyond (the smooth r⁻³ tail)
_PIXEL_NODES = 4         # Gauss–Legendre nodes per pixel (or sub-cell) and axis
_MAX_SUBCELLS = 32       # sub-cells per pixel and axis near the load: at most 32, each ≤ t/2 wide
_NEAR_PIXELS, _NEAR_THICKNESSES = 3.0, 60.0    # "near": within 3 pixels + 60 t of the loaded pixel


def _gauss_panels(edges, nodes):
    """Gauss–Legendre nodes and weights on consecutive panels ``edges`` (1-D, increasing)."""
    x, w = np.polynomial.legendre.leggauss(nodes)
    width = np.diff(edges)[:, None]
    return (edges[:-1, None] + (x + 1.0) / 2.0 * width).ravel(), (w / 2.0 * width).ravel()


def _hankel_table(remainder, thickness, radii):
    """Δw₂(r) = (1/2π) ∫₀^∞ q ΔΦ₂(q) J0(q r) dq [m/Pa per m²] at ``radii`` [m], composite Gauss–Legendre in q on
    panels that resolve J0 for each block of radii (``remainder(q)`` = q ΔΦ₂(q) [1/Pa])."""
    from scipy.special import j0
    q_max = _HANKEL_QT / thickness
    table = np.empty(radii.size)
    for start in range(0, radii.size, 32):
        block = radii[start:start + 32]
        step = min(1.0 / thickness, _HANKEL_PERIODS * 2 * np.pi / block[-1]) if block[-1] > 0 else 1.0 / thickness
        q, weight = _gauss_panels(np.linspace(0.0, q_max, int(np.ceil(q_max / step)) + 1), _HANKEL_NODES)
        table[start:start + 32] = j0(np.outer(block, q)) @ (weight * remainder(q))
    return table / (2 * np.pi)


def _pixel_average(kernel, x, y, dx, dy, subcells):
    """∫∫ kernel(|r − r'|) dA' over the pixel centred at 0 for the offsets (x, y) (flat arrays), by
    ``subcells``² sub-cells of _PIXEL_NODES² Gauss–Legendre points."""
    points, weights = _gauss_panels(np.linspace(-0.5, 0.5, subcells + 1), _PIXEL_NODES)
    total = np.zeros(x.size)
    for a, weight in zip(points, weights):
        total += weight * (kernel(np.hypot(x[:, None] + a * dx, y[:, None] + points * dy)) @ weights)
    return total * dx * dy


def free_surface_correction(compliance, E_star, long_wave_slope, thickness, x, y, dx, dy):
    """Influence coefficients [m/Pa] of ΔΦ(q) = Φ(q) − 2/(E* q) on a free surface (``docs/guide/layered.md``, Eq. L5).

    The displacement at the offsets ``x[:, None]``, ``y[None, :]`` [m] (≥ 0) under unit pressure on a dx × dy
    pixel, to be added to Love's coefficients of the layer's half-space (E* = the layer's modulus, the q → ∞
    limit of Φ). ``compliance(q)``: Φ(q) [m/Pa]; ``long_wave_slope``: b = lim_{q→0} q ΔΦ(q) [1/Pa]
    (2/E0* − 2/E* on a half-space E0*, −2/E* on a rigid base); ``thickness`` t [m] of the layer.

        Δu = b/(2π) ∫∫ dA'/√(|r − r'|² + t²)  +  ∫∫ Δw₂(|r − r'|) dA',
        Δw₂(r) = (1/2π) ∫₀^∞ [q Φ(q) − 2/E* − b e^{−q t}] J0(q r) dq.
    """
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    X, Y = np.meshgrid(x, y, indexing="ij")
    r_max = float(np.hypot(x.max() + dx, y.max() + dy))
    step = min(thickness / _TABLE_STEP, r_max / 64)
    uniform_end = min(r_max, _TABLE_UNIFORM * thickness)
    radii = np.arange(0.0, uniform_end + step, step)
    if r_max > radii[-1]:
        count = int(np.ceil(np.log(r_max / radii[-1]) / np.log(_TABLE_RATIO))) + 1
        radii = np.concatenate([radii, radii[-1] * _TABLE_RATIO ** np.arange(1, count + 1)])

    def remainder(q):        # q ΔΦ₂(q): O(q) at q = 0, no division
        return q * compliance(q) - 2.0 / E_star - long_wave_slope * np.exp(-q * thickness)

    from scipy.interpolate import CubicSpline
    kernel = CubicSpline(radii, _hankel_table(remainder, thickness, radii), bc_type=((1, 0.0), "not-a-knot"))
    distance = np.hypot(np.maximum(X - dx / 2, 0.0), np.maximum(Y - dy / 2, 0.0))   # to the loaded pixel
    near = distance < _NEAR_PIXELS * max(dx, dy) + _NEAR_THICKNESSES * thickness
    subcells = min(_MAX_SUBCELLS, max(1, int(np.ceil(2 * max(dx, dy) / thickness))))
    smooth = np.empty(X.shape)
    smooth[~near] = _pixel_average(kernel, X[~near], Y[~near], dx, dy, 1)
    smooth[near] = _pixel_average(kernel, X[near], Y[near], dx, dy, subcells)
    return long_wave_slope / (2 * np.pi) * pixel_potential(X, Y, dx, dy, thickness) + smooth
