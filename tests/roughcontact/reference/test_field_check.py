"""The independent field check (docs/validation/field_check.md): second-order perturbation theory of a sinusoidal gap and
the finite-element solve of the full stack, each against limits and against the other."""
import numpy as np
import pytest

from roughcontact.electrostatics import EPSILON_0, DielectricStack
from roughcontact.reference.perturbation import (gradient_coefficient, second_order_attraction,
                                                 second_order_energy)

TABLE1 = DielectricStack()
HUMID = DielectricStack(d_sc=30e-6, eps_sc=1500.0, d_i=2e-6, eps_i=5.0, eps_a=1.7)
# bare conductors: no insulator, a perfectly conducting stratum corneum (offsets 1e-20 m; with 1e-16 m and
# eps_sc = 1e16 the stratum corneum's finite lateral conduction already shows at 4e-6 in K)
BARE = DielectricStack(d_sc=1e-3, eps_sc=1e20, d_i=1e-20, eps_i=1.0, eps_a=1.0)
VOLTAGE = 100.0


@pytest.fixture
def field_solve():
    pytest.importorskip("skfem", reason="the field check needs the optional extra roughcontact[fieldcheck]")
    pytest.importorskip("pyamg", reason="the field check needs the optional extra roughcontact[fieldcheck]")
    from roughcontact.reference.fem import field_solve_profile
    return field_solve_profile


# -- perturbation theory against its limits -----------------------------------------------------------------
@pytest.mark.parametrize("gap", [0.5e-6, 2e-6])
@pytest.mark.parametrize("wavelength", [1e-6, 1e-5, 1e-3])
def test_bare_conductors_energy_and_attraction(gap, wavelength):
    q = 2 * np.pi / wavelength
    # W2 = ε0 U² q coth(q g0) / (4 g0²); S = -dW2/dg0 differentiated by hand
    energy = EPSILON_0 * VOLTAGE ** 2 * q / np.tanh(q * gap) / (4 * gap ** 2)
    attraction = EPSILON_0 * VOLTAGE ** 2 / 4 * (q ** 2 / np.sinh(q * gap) ** 2 / gap ** 2
                                                 + 2 * q / np.tanh(q * gap) / gap ** 3)
    # BARE's 1e-20 m offsets perturb at ~1e-14 relative (measured at most 6e-14 for W2, 8e-14 for S)
    assert second_order_energy(BARE, gap, q, VOLTAGE) == pytest.approx(energy, rel=1e-12)
    assert second_order_attraction(BARE, gap, q, VOLTAGE) == pytest.approx(attraction, rel=1e-12)


@pytest.mark.parametrize("stack", [TABLE1, HUMID])
@pytest.mark.parametrize("gap", [0.5e-6, 2e-6])
def test_long_waves_are_the_per_pixel_average(stack, gap):
    # q -> 0: <σ_el(g0 + a cos qx)> = σ_el + (a²/4) σ_el'' exactly (q = 0 uses the Taylor branch)
    per_pixel = stack.attraction_derivative(gap, VOLTAGE, 2) / 4
    assert second_order_attraction(stack, gap, 0.0, VOLTAGE) == pytest.approx(per_pixel, rel=1e-13)
    # and the approach is q² (the derivative expansion): the deviation quarters when q halves
    q = 1.0 / stack.d_sc / 100
    deviation = [second_order_attraction(stack, gap, k, VOLTAGE) / per_pixel - 1 for k in (q, q / 2)]
    assert deviation[0] / deviation[1] == pytest.approx(4.0, rel=1e-4)       # measured 2.9e-5 (the q⁴ term)


@pytest.mark.parametrize("stack", [TABLE1, HUMID, BARE])
@pytest.mark.parametrize("gap", [0.5e-6, 2e-6])
def test_q_squared_term_is_the_derivative_expansion(stack, gap):
    # (W2(q) - W2(0)) / q² -> K/4, with K from the separately derived q = 0 mapped energy; Richardson in q
    q = 1e-3 / max(gap, stack.d_sc if stack is not BARE else gap)
    slope = [(second_order_energy(stack, gap, k, VOLTAGE) - second_order_energy(stack, gap, 0.0, VOLTAGE)) / k ** 2
             for k in (q, 2 * q)]
    extrapolated = (4 * slope[0] - slope[1]) / 3
    # differencing loses ~1e-16/(q ℓ)² ~ 1e-10 of W2, the O(q⁴) remainder is removed: measured at most 2.2e-8
    assert extrapolated == pytest.approx(gradient_coefficient(stack, gap, VOLTAGE) / 4, rel=1e-6)


def test_bare_derivative_expansion_coefficient_is_one_third():
    # electrostatic derivative expansion of a slowly varying gap: W = ε0 U²/(2g) (1 + g'²/3)
    gap = np.array([0.3e-6, 1e-6, 5e-6])
    np.testing.assert_allclose(gradient_coefficient(BARE, gap, VOLTAGE), EPSILON_0 * VOLTAGE ** 2 / (3 * gap),
                               rtol=1e-9)          # measured 4e-10 (the 1e-20 m offsets)


def test_bad_inputs_are_named():
    with pytest.raises(ValueError, match="mean_gap"):
        second_order_attraction(TABLE1, 0.0, 1e5, VOLTAGE)
    with pytest.raises(ValueError, match="wavenumber"):
        second_order_energy(TABLE1, 1e-6, -1.0, VOLTAGE)


# -- the finite-element solve ---------------------------------------------------------------------------------
@pytest.mark.parametrize("stack", [TABLE1, HUMID])
@pytest.mark.parametrize("periodic", [True, False])
@pytest.mark.parametrize("gap", [0.0, 1e-6])
def test_uniform_gap_is_equation_21_and_contact_is_equation_23(field_solve, stack, periodic, gap):
    # P1 holds the 1-D solution exactly, so only rounding (~1e-12 at this permittivity contrast) remains;
    # gap = 0 is full contact: the air rows are merged and the attraction is the one-sided opening derivative
    solution = field_solve(stack, np.full(24, gap), 2e-5, VOLTAGE, periodic=periodic)
    assert solution.converged
    assert solution.mean_attraction == pytest.approx(stack.attraction(gap, VOLTAGE), rel=1e-10)
    np.testing.assert_allclose(solution.attraction, stack.attraction(gap, VOLTAGE), rtol=1e-9)
    energy = 0.5 * stack.work_of_adhesion(gap, VOLTAGE) * 2 * 2e-5           # ½ C U² per unit depth
    assert solution.energy == pytest.approx(energy, rel=1e-10)


@pytest.mark.parametrize("wavelength, gap, columns, tolerance", [
    (1e-4, 1e-6, 64, 1e-4),       # measured 2.3e-5
    (1e-3, 2e-6, 64, 5e-5),       # measured 1.2e-5
    (5e-3, 0.5e-6, 64, 2e-5),     # measured 4.3e-6
])
def test_sinusoid_against_perturbation_theory(field_solve, wavelength, gap, columns, tolerance):
    q = 2 * np.pi / wavelength
    x = np.arange(columns) * wavelength / columns
    amplitude = 0.05 * gap
    excess = [field_solve(TABLE1, gap + a * np.cos(q * x), wavelength, VOLTAGE).mean_attraction
              - TABLE1.attraction(gap, VOLTAGE) for a in (amplitude, 2 * amplitude)]
    second_order = (16 * excess[0] - excess[1]) / (12 * amplitude ** 2)          # Richardson: a⁴ removed
    expected = second_order_attraction(TABLE1, gap, q, VOLTAGE)
    assert second_order == pytest.approx(expected, rel=tolerance)
    # the per-pixel law is a different number here: the comparison can tell them apart
    assert abs(second_order / (TABLE1.attraction_derivative(gap, VOLTAGE, 2) / 4) - 1) > 10 * tolerance


def _contact_profile(columns, wavelength=1e-4):
    """2 µm (0.5 - cos qx)+: contact over a third of the period, opening linearly at the edges."""
    x = np.arange(columns) * wavelength / columns
    return 2e-6 * np.maximum(0.0, 0.5 - np.cos(2 * np.pi * x / wavelength))


def test_contact_opening_derivative_is_the_energy_slope(field_solve):
    # the opening derivative at contact columns against (E(δ) - E(0))/δ of the unmerged mesh (gap + δ),
    # Richardson-extrapolated to δ -> 0; the difference quotient is 3e-4 off at δ = 0.1 nm, linear in δ
    gap, length = _contact_profile(128), 1e-4
    contact = field_solve(TABLE1, gap, length, VOLTAGE)
    slopes = [(contact.energy - field_solve(TABLE1, gap + d, length, VOLTAGE).energy) / d / length
              for d in (1e-10, 2e-10)]
    assert 2 * slopes[0] - slopes[1] == pytest.approx(contact.mean_attraction, rel=1e-6)   # measured 2e-8
    assert contact.attraction @ np.full(128, length / 128) / length == pytest.approx(contact.mean_attraction,
                                                                                  rel=1e-12)


def test_fem_bad_inputs_are_named(field_solve):
    with pytest.raises(ValueError, match="gap"):
        field_solve(TABLE1, np.array([1e-6, -1e-9]), 1e-5, VOLTAGE)
    with pytest.raises(ValueError, match="solver"):
        field_solve(TABLE1, np.full(4, 1e-6), 1e-5, VOLTAGE, solver="cholesky")


def test_convergence_on_a_profile_with_contact(field_solve):
    # every length of the mesh halved per level (columns, rows of each layer, first stratum-corneum row);
    # measured on the contact profile: differences -610, -173, -52 Pa of 1.89e5 Pa, order 1.82 then 1.73 —
    # the contact edges (a zero-angle air wedge between the two dielectrics) keep it below 2
    means = [field_solve(TABLE1, _contact_profile(96 * 2 ** level), 1e-4, VOLTAGE, air_rows=2 * 2 ** level,
                         insulator_rows=2 * 2 ** level, sc_rows=12 * 2 ** level).mean_attraction
             for level in range(3)]
    differences = np.diff(means)
    order = np.log2(differences[0] / differences[1])
    assert 1.6 < order < 2.1
    assert abs(differences[1]) < 2e-3 * means[-1]


def test_virtual_work_against_air_side_maxwell_stress(field_solve):
    # the Maxwell traction uses the field inside the top air triangle, O(Δz) away from the skin: its mean
    # approaches σ̄ at first order in the air rows (measured 9.5e-5, 5.1e-5, 2.6e-5 on the sinusoid; 3.0e-4,
    # 1.5e-4, 6.8e-5 on the contact profile); uniform gap and full contact agree to rounding
    wavelength, columns = 1e-4, 128
    x = np.arange(columns) * wavelength / columns
    for gap in (1e-6 * (1 + 0.5 * np.cos(2 * np.pi * x / wavelength)), _contact_profile(columns)):
        errors = []
        for rows in (4, 8, 16):
            solution = field_solve(TABLE1, gap, wavelength, VOLTAGE, air_rows=rows, insulator_rows=8, sc_rows=48)
            errors.append(solution.mean_maxwell_attraction / solution.mean_attraction - 1)
        assert 0 < errors[-1] < 1e-4
        assert errors[0] / errors[1] == pytest.approx(2, rel=0.2)
        assert errors[1] / errors[2] == pytest.approx(2, rel=0.2)
    for gap in (1e-6, 0.0):
        solution = field_solve(TABLE1, np.full(16, gap), 1e-5, VOLTAGE)
        np.testing.assert_allclose(solution.maxwell_attraction, solution.mean_attraction, rtol=1e-9)


# -- the 3-D solve over 2-D gap fields --------------------------------------------------------------------------
@pytest.fixture
def patch_solve(field_solve):
    from roughcontact.reference.fem import field_solve_patch
    return field_solve_patch


@pytest.mark.parametrize("stack", [TABLE1, HUMID])
@pytest.mark.parametrize("periodic", [True, False])
@pytest.mark.parametrize("gap", [0.0, 1e-6])
def test_patch_uniform_gap_and_contact(patch_solve, stack, periodic, gap):
    # as in 2-D, P1 holds the 1-D solution; AMG-CG to 1e-12 leaves ~1e-11 (measured at most 6e-11)
    solution = patch_solve(stack, np.full((6, 5), gap), (2e-5, 1.5e-5), VOLTAGE, periodic=periodic, tol=1e-12)
    assert solution.converged
    assert solution.mean_attraction == pytest.approx(stack.attraction(gap, VOLTAGE), rel=1e-9)
    interior = solution.attraction if periodic else solution.attraction[1:-1, 1:-1]     # free: corners (docstring)
    np.testing.assert_allclose(interior, stack.attraction(gap, VOLTAGE), rtol=1e-8)
    assert solution.energy == pytest.approx(stack.work_of_adhesion(gap, VOLTAGE) * 3e-10, rel=1e-9)


def test_patch_of_a_ridge_profile_is_the_profile_solve(field_solve, patch_solve):
    # a gap invariant along y: the six tetrahedra of every hexahedron hold the 2-D P1 solution exactly, so the
    # 3-D solve reproduces the 2-D one on the contact profile to the solver's tolerance (measured 5e-11)
    gap, length = _contact_profile(32), 1e-4
    profile = field_solve(TABLE1, gap, length, VOLTAGE)
    patch = patch_solve(TABLE1, np.repeat(gap[:, None], 4, axis=1), (length, length / 8), VOLTAGE, tol=1e-12)
    assert patch.mean_attraction == pytest.approx(profile.mean_attraction, rel=1e-9)
    np.testing.assert_allclose(patch.attraction, np.repeat(profile.attraction[:, None], 4, axis=1), rtol=1e-7)


def test_patch_contact_opening_derivative_is_the_energy_slope(patch_solve):
    # a 2-D bump field with contact on 17 % of the window: measured 2.4e-7 with δ = 0.1, 0.2 nm (Richardson)
    x = np.arange(24) / 24
    gap = 2e-6 * np.maximum(0.0, 0.5 - np.cos(2 * np.pi * x)[:, None] * np.cos(2 * np.pi * x)[None, :])
    lengths = (1e-4, 1e-4)
    contact = patch_solve(TABLE1, gap, lengths, VOLTAGE, tol=1e-12)
    slopes = [(contact.energy - patch_solve(TABLE1, gap + d, lengths, VOLTAGE, tol=1e-12).energy) / d / 1e-8
              for d in (1e-10, 2e-10)]
    assert 2 * slopes[0] - slopes[1] == pytest.approx(contact.mean_attraction, rel=2e-6)


def test_patch_egg_box_against_perturbation_theory(patch_solve):
    # g0 + a cos(qx) cos(qy) = g0 + (a/2)[cos q(x+y) + cos q(x-y)]: two modes of |k| = √2 q, oblique to the
    # mesh; second order adds them: σ̄ = σ_el + (a²/2) S(√2 q). Measured 1.2e-4 on 16², 6.3e-5 on 32² columns
    wavelength, gap, columns = 1e-4, 1e-6, 16
    x = np.arange(columns) * wavelength / columns
    shape = np.cos(2 * np.pi * x / wavelength)[:, None] * np.cos(2 * np.pi * x / wavelength)[None, :]
    amplitude = 0.05 * gap
    excess = [patch_solve(TABLE1, gap + a * shape, (wavelength, wavelength), VOLTAGE).mean_attraction
              - TABLE1.attraction(gap, VOLTAGE) for a in (amplitude, 2 * amplitude)]
    second_order = (16 * excess[0] - excess[1]) / (12 * amplitude ** 2)
    expected = 0.5 * second_order_attraction(TABLE1, gap, np.sqrt(2) * 2 * np.pi / wavelength, VOLTAGE)
    assert second_order == pytest.approx(expected, rel=3e-4)
