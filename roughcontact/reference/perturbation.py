"""Exact second-order response of the layered stack to a sinusoidal air gap (``docs/validation/field_check.md``).

The gap ``g(x) = g0 + a cos(q x)`` between a flat insulator (electrode at z = -d_i, potential 0) and a
stratum corneum of uniform vertical thickness d_sc whose top face (the tissue, potential U) follows the skin
surface. At fixed potentials the field energy per unit area expands as

    W(g0, a) = W0(g0) + a² W2(g0, q) + O(a⁴),   W0 = ε0 U² / (2 h),   h = d_sc/eps_sc + g0/eps_a + d_i/eps_i,

and the mean attraction (a rigid shift of the skin, g0 -> g0 + δ, at fixed a) is

    σ̄(a) = -dW/dg0 = σ_el(g0) + a² S(q, g0) + O(a⁴),   S = -∂W2/∂g0,

σ_el the parallel-plate attraction of seed Eq. 21. With e0 = U/h and Q(z) the amplitude of the first-order
(Eulerian) potential perturbation, harmonic in each layer (Q'' = q² Q) with

    Q(-d_i) = 0,   Q(g0 + d_sc) = -e0/eps_sc,   [eps Q'] = 0 at both interfaces,
    Q continuous at z = 0,   Q(g0+) - Q(g0-) = e0 (1/eps_a - 1/eps_sc),

the second-order energy is ``W2 = -(ε0 e0 / 4) [Q'(g0-) - Q'(g0+) + Q'(g0 + d_sc)]``. For bare conductors
(d_i -> 0, SC a perfect conductor) it is ``W2 = ε0 U² q coth(q g0) / (4 g0²)``; as q -> 0 it tends to W0''/4,
the per-pixel parallel plate averaged over the sinusoid. ``∂W2/∂g0`` is taken by a complex step (exact to
rounding). SI units; pure numpy.
"""
from __future__ import annotations

import numpy as np

from surfaces.validation import check_broadcast, check_finite_array

from ..electrostatics.stack import EPSILON_0, DielectricStack

#: Below this q·d the hyperbolic factors use their Taylor series (error ~ (q d)^6 / 1e3, below rounding).
_SERIES_LIMIT = 1e-3
#: Complex step of the g0 derivative, relative to g0 (any value << 1 is exact to rounding).
_COMPLEX_STEP = 1e-30


def _q_coth(q, d):
    """``q coth(q d)`` [1/m], finite at q = 0 (-> 1/d)."""
    x = q * d
    small = np.abs(x) < _SERIES_LIMIT
    safe = np.where(small, 1.0, x)
    return np.where(small, 1 / d + q * x / 3 - q * x ** 3 / 45, q / np.tanh(safe))


def _q_csch(q, d):
    """``q / sinh(q d)`` [1/m], finite at q = 0 (-> 1/d) and without overflow at large q d."""
    x = q * d
    small = np.abs(x) < _SERIES_LIMIT
    safe = np.where(small, 1.0, x)
    decay = np.exp(-safe)
    return np.where(small, 1 / d - q * x / 6 + 7 * q * x ** 3 / 360, 2 * q * decay / (1 - decay ** 2))


def _energy_per_volt_squared(stack: DielectricStack, gap, wavenumber):
    """``W2 / (a² U²)`` [F/m³]: the 2×2 interface system for Q(0) and Q(g0-) at e0 = 1/h (complex-safe in g0)."""
    e0 = 1 / (stack.dielectric_offset + gap / stack.eps_a)
    top = -e0 / stack.eps_sc                                       # Q at the tissue face
    jump = e0 * (1 / stack.eps_a - 1 / stack.eps_sc)              # Q(g0+) - Q(g0-)
    coth_i, coth_a, csch_a, coth_s, csch_s = (
        _q_coth(wavenumber, stack.d_i), _q_coth(wavenumber, gap), _q_csch(wavenumber, gap),
        _q_coth(wavenumber, stack.d_sc), _q_csch(wavenumber, stack.d_sc))
    # unknowns Q0 = Q(0), Qa = Q(g0-); flux continuity at z = 0 and z = g0:
    #   eps_i Q0 q coth(q d_i) = eps_a (Qa q csch(q g0) - Q0 q coth(q g0))
    #   eps_sc (top q csch(q d_sc) - (Qa + jump) q coth(q d_sc)) = eps_a (Qa q coth(q g0) - Q0 q csch(q g0))
    a11, a12 = stack.eps_i * coth_i + stack.eps_a * coth_a, -stack.eps_a * csch_a
    a21, a22 = -stack.eps_a * csch_a, stack.eps_a * coth_a + stack.eps_sc * coth_s
    b2 = stack.eps_sc * (top * csch_s - jump * coth_s)
    determinant = a11 * a22 - a12 * a21
    q0, qa = -a12 * b2 / determinant, a11 * b2 / determinant
    slope_air = qa * coth_a - q0 * csch_a                          # Q'(g0-)
    slope_sc = stack.eps_a * slope_air / stack.eps_sc              # Q'(g0+)
    slope_top = top * coth_s - (qa + jump) * csch_s                # Q'(g0 + d_sc)
    return -EPSILON_0 * e0 * (slope_air - slope_sc + slope_top) / 4


def _inputs(gap, wavenumber, voltage):
    gap, wavenumber, voltage = check_broadcast(
        mean_gap=check_finite_array("mean_gap", gap, nonnegative=True),
        wavenumber=check_finite_array("wavenumber", wavenumber, nonnegative=True),
        voltage=check_finite_array("voltage", voltage))
    if np.any(gap <= 0):
        raise ValueError(f"mean_gap must be > 0 (the sinusoid needs an air layer); got min {gap.min():g} m")
    return gap, wavenumber, voltage


def second_order_energy(stack: DielectricStack, mean_gap, wavenumber, voltage) -> np.ndarray:
    """``W2`` [J/m⁴]: the field energy per unit area is W0(g0) + a² W2 + O(a⁴) for g = g0 + a cos(q x).

    ``mean_gap`` g0 > 0 [m], ``wavenumber`` q = 2π/λ >= 0 [1/m], ``voltage`` U [V]; broadcast together.
    """
    gap, wavenumber, voltage = _inputs(mean_gap, wavenumber, voltage)
    return voltage ** 2 * _energy_per_volt_squared(stack, gap, wavenumber)


def second_order_attraction(stack: DielectricStack, mean_gap, wavenumber, voltage) -> np.ndarray:
    """``S = -∂W2/∂g0`` [Pa/m²]: the mean attraction is σ̄ = σ_el(g0) + a² S + O(a⁴) (module docstring)."""
    gap, wavenumber, voltage = _inputs(mean_gap, wavenumber, voltage)
    step = _COMPLEX_STEP * gap
    derivative = np.imag(_energy_per_volt_squared(stack, gap + 1j * step, wavenumber)) / step
    return -voltage ** 2 * derivative


def mean_attraction(stack: DielectricStack, mean_gap, amplitude, wavenumber, voltage) -> np.ndarray:
    """``σ̄ = σ_el(g0) + a² S`` [Pa], the mean attraction to second order in the amplitude a [m] (a <= g0)."""
    amplitude = check_finite_array("amplitude", amplitude, nonnegative=True)
    return stack.attraction(mean_gap, voltage) + amplitude ** 2 * second_order_attraction(
        stack, mean_gap, wavenumber, voltage)


def gradient_coefficient(stack: DielectricStack, gap, voltage) -> np.ndarray:
    """``K(g)`` [J/m²] of the derivative expansion W ≈ ∫ [W0(g) + ½ K(g) g'²] dx, the q² term of W2:
    ``W2 = W0''/4 + q² K/4 + O(q⁴)``.

    From the mapped energy at q = 0 (``docs/validation/field_check.md``): with e0 = U/h, flux C = -e0/(eps_a h) and the
    first-order mapped potential P0 piecewise linear, 0 -> p1 = C d_i/eps_i -> p2 = p1 - C c -> 0 (c the
    dielectric offset),
    ``K = ε0 [e0² (g/(3 eps_a) + d_sc/eps_sc) + Σ_layers eps d (A² + AB + B²)/3 - 2 e0 (g (p1 + 2 p2)/6
    + d_sc p2/2)]``. Bare conductors: K = ε0 U²/(3 g), the 1/3 of the electrostatic derivative expansion.
    """
    gap = check_finite_array("gap", gap, nonnegative=True)
    voltage = check_finite_array("voltage", voltage)
    e0 = voltage / (stack.dielectric_offset + gap / stack.eps_a)
    flux = -e0 / (stack.eps_a * (stack.dielectric_offset + gap / stack.eps_a))
    p1 = flux * stack.d_i / stack.eps_i
    p2 = p1 - flux * stack.dielectric_offset        # = p1 + (e0 + C g)/eps_a without the cancellation
    stored = (stack.eps_i * stack.d_i * p1 ** 2 + stack.eps_a * gap * (p1 ** 2 + p1 * p2 + p2 ** 2)
              + stack.eps_sc * stack.d_sc * p2 ** 2) / 3
    coupling = 2 * e0 * (gap * (p1 + 2 * p2) / 6 + stack.d_sc * p2 / 2)
    return EPSILON_0 * (e0 ** 2 * (gap / (3 * stack.eps_a) + stack.d_sc / stack.eps_sc) + stored - coupling)
