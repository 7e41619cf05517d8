"""Surface compliances Φ(q) [m/Pa] of layered elastic bodies in Fourier space.

For a frictionless normal surface pressure p̃(q) the normal surface displacement (positive into the body) is
ũ(q) = Φ(q) p̃(q). Each Fourier mode of wavevector magnitude q is a plane-strain problem (no variation
perpendicular to q), so the half-space has Φ = 2/(E* q) with the contact modulus E* = E/(1 − ν²).
Derivation, limits and references: ``docs/guide/layered.md`` ("Layered kernels").

All formulas are written with X = q t and e = exp(−2X) ≤ 1 (no cosh overflow at large q t) and without
subtractions of nearly equal terms at small q t (``_sinh_excess`` replaces sinh y − y by its series).
Pure numpy, vectorised over ``q``.
"""
from __future__ import annotations

import math

import numpy as np

from surfaces.validation import check_choice, check_finite_array, check_positive, check_real

__all__ = ["layer_on_rigid_base_compliance", "layer_on_half_space_compliance"]

BOTTOMS = ("bonded", "frictionless")

# Beyond X = q t = 25 every kernel equals the half-space of the layer, 2/(E* q), to round-off (measured: largest
# |R − 1| 1.1e-15 for X >= 22 over ν, ν0 in (−1, 0.5] and E0*/E* from 1e-3 to 1e3; the terms left are ~X² e^{−2X}
# < 1e-18 at X = 25); there it is returned as such, which also keeps q t = inf (t = 1e300 m) finite.
THICK_X = 25.0

# 1/(2k+1)! for k = 1..9: sinh y − y to relative 1e-17 for y < 1 (next term y^21/21! < 2e-20 · y^3/6)
_SINH_SERIES = np.array([1.0 / math.factorial(2 * k + 1) for k in range(1, 10)])


def _sinh_excess(y):
    """e^{−y} (sinh y − y) for y ≥ 0, accurate to round-off for all y (series below y = 1)."""
    y = np.asarray(y, dtype=float)
    small = y < 1.0
    ys = np.where(small, y, 0.0)
    series = np.polyval(_SINH_SERIES[::-1], ys * ys) * ys**3
    large = np.where(small, 1.0, y)
    direct = -0.5 * np.expm1(-2.0 * large) - large * np.exp(-large)
    return np.where(small, np.exp(-ys) * series, direct)


def _check_poisson(name, value):
    return check_real(name, value, low=-1.0, high=0.5, low_open=True)


def _thickness_product(q, t) -> tuple:
    """``(X, thick)``: X = q t capped at :data:`THICK_X` (no overflow) and the mask of the modes beyond it."""
    with np.errstate(over="ignore"):
        X = q * t
    return np.minimum(X, THICK_X), X >= THICK_X


def _half_space_beyond(thick, q, E_star, compliance):
    """``compliance``, with the layer's half-space 2/(E* q) on the ``thick`` modes (q > 0 there)."""
    with np.errstate(divide="ignore"):
        return np.where(thick, 2.0 / (E_star * np.where(thick, q, 1.0)), compliance)


def _bonded_ratio(X, mu, nu_, one_minus_mn):
    """R = Φ E* q / 2 of a layer bonded on a substrate, in the shifted parameters μ = 1 + m ≥ 0, ν' = 1 + n ≥ 0
    (and 1 − mn ≥ 0, passed in closed form).

    R = [1 − 4mXe − mn e²] / [(1 + me)(1 + ne) + 4mX²e] (``docs/guide/layered.md``, Eq. L3), rearranged so that
    the denominator is a sum of non-negative terms for every substrate (including the plate-bending
    cancellation of a stiff layer on a soft substrate, where (1−e)² − 4X²e ∝ X⁴).
    Returns numerator and denominator separately so the caller can divide by X when R(0) = 0.
    """
    m, n = mu - 1.0, nu_ - 1.0
    root_e = np.exp(-X)
    e = root_e * root_e
    one_minus_e = -np.expm1(-2.0 * X)
    one_minus_e2 = -np.expm1(-4.0 * X)
    # 1 − 4mXe − mn e² = (1 − mn) + m[(n − 1)(1 − e²) + (1 − e² − 4Xe)],  1 − e² − 4Xe = 2e^{−2X}(sinh 2X − 2X)
    numerator = one_minus_mn + m * ((n - 1.0) * one_minus_e2 + 2.0 * _sinh_excess(2.0 * X))
    # (1−e)² − 4X²e = [(1−e) − 2Xe^{−X}][(1−e) + 2Xe^{−X}] = 2 e^{−X}(sinh X − X)·[(1−e) + 2Xe^{−X}]
    bending = 2.0 * _sinh_excess(X) * (one_minus_e + 2.0 * X * root_e)
    denominator = bending + (mu + nu_) * e * one_minus_e + mu * nu_ * e * e + 4.0 * mu * (X * root_e) ** 2
    return numerator, denominator


def layer_on_rigid_base_compliance(q, E_star, poisson, thickness, bottom="bonded"):
    """Compliance Φ(q) [m/Pa] of an elastic layer of thickness t [m] on a rigid base (``docs/guide/layered.md``).

    bonded (no slip):  Φ = 2/(E* q) · [κ(1−e²) − 4Xe] / [κ(1+e²) + (1+κ²+4X²) e]   (Eq. L1)
    frictionless:      Φ = 2/(E* q) · (1−e)² / (1 − e² + 4Xe)                       (Eq. L2)
    with X = q t, e = exp(−2X), κ = 3 − 4ν. Finite at q = 0: Φ(0) = t(1−2ν)/(E*(1−ν)²) (bonded:
    uniaxial-strain column t/M) and Φ(0) = t/E* (frictionless: laterally free plane-strain column).

    Parameters
    ----------
    q : array_like
        Wavevector magnitudes [rad/m], >= 0.
    E_star : float
        Contact modulus of the layer E/(1 − ν²) [Pa].
    poisson : float
        Poisson ratio ν of the layer, in (−1, 0.5].
    thickness : float
        Layer thickness t [m].
    bottom : {"bonded", "frictionless"}
        Interface with the rigid base.
    """
    q = check_finite_array("q", q, nonnegative=True)
    E_star = check_positive("E_star", E_star)
    nu = _check_poisson("poisson", poisson)
    t = check_positive("thickness", thickness)
    check_choice("bottom", bottom, BOTTOMS)
    X, thick = _thickness_product(q, t)
    if bottom == "bonded":
        kappa = 3.0 - 4.0 * nu
        # rigid substrate: m = 1/κ, n = κ (the G0 → ∞ limit of Eq. L3), so 1 − mn = 0 and R ∝ X
        numerator, denominator = _bonded_ratio(X, 1.0 + 1.0 / kappa, 1.0 + kappa, 0.0)
        limit = (1.0 - 2.0 * nu) / (2.0 * (1.0 - nu) ** 2)
    else:
        numerator = np.expm1(-2.0 * X) ** 2
        denominator = -np.expm1(-4.0 * X) + 4.0 * X * np.exp(-2.0 * X)
        limit = 0.5
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio_over_X = np.where(X > 0, numerator / (denominator * X), limit)
    return _half_space_beyond(thick, q, E_star, 2.0 * t / E_star * ratio_over_X)


def layer_on_half_space_compliance(q, E_star, poisson, thickness, substrate_E_star, substrate_poisson):
    """Compliance Φ(q) [m/Pa] of a layer of thickness t [m] perfectly bonded on an elastic half-space.

    Φ = 2/(E* q) · [1 − 4mXe − mn e²] / [1 + (m + n + 4mX²) e + mn e²]   (``docs/guide/layered.md``, Eq. L3)
    with X = q t, e = exp(−2X), γ = G0/G (substrate over layer shear modulus), κ = 3 − 4ν,
    m = (γ − 1)/(γκ + 1), n = (γκ − κ0)/(γ + κ0). Limits: 2/(E* q) for q t → ∞ and
    2/(E0* q) for q t → 0. Φ(0) = inf (the mean displacement of a half-space is undetermined).

    Parameters
    ----------
    q : array_like
        Wavevector magnitudes [rad/m], >= 0.
    E_star, poisson : float
        Contact modulus [Pa] and Poisson ratio (in (−1, 0.5]) of the layer.
    thickness : float
        Layer thickness t [m].
    substrate_E_star, substrate_poisson : float
        Contact modulus [Pa] and Poisson ratio (in (−1, 0.5]) of the half-space below.
    """
    q = check_finite_array("q", q, nonnegative=True)
    E_star = check_positive("E_star", E_star)
    nu = _check_poisson("poisson", poisson)
    t = check_positive("thickness", thickness)
    E0_star = check_positive("substrate_E_star", substrate_E_star)
    nu0 = _check_poisson("substrate_poisson", substrate_poisson)
    # shear moduli G = E*(1 − ν)/2
    gamma = E0_star * (1.0 - nu0) / (E_star * (1.0 - nu))
    kappa, kappa0 = 3.0 - 4.0 * nu, 3.0 - 4.0 * nu0
    mu = gamma * (kappa + 1.0) / (gamma * kappa + 1.0)      # 1 + m
    nu_ = gamma * (kappa + 1.0) / (gamma + kappa0)         # 1 + n
    one_minus_mn = gamma * (kappa + 1.0) * (kappa0 + 1.0) / ((gamma * kappa + 1.0) * (gamma + kappa0))
    X, thick = _thickness_product(q, t)
    numerator, denominator = _bonded_ratio(X, mu, nu_, one_minus_mn)
    with np.errstate(divide="ignore"):
        return _half_space_beyond(thick, q, E_star, 2.0 / (E_star * q) * (numerator / denominator))
