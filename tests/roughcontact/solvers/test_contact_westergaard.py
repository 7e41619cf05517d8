"""Westergaard sinusoid (plane strain, (n, 1) grid) and Johnson–Greenwood–Higginson bi-sinusoid.

References: roughcontact.reference (Westergaard 1939; Johnson 1985 §13.2; Johnson, Greenwood & Higginson
1985). Profile h = h0 cos(2πx/λ) on a periodic grid; p* = π E* h0/λ (1-D), √2 π E* Δ/λ (bi-sinusoid).
"""
import numpy as np
import pytest

from roughcontact import ElasticHalfSpace, load_path, solve_contact
from roughcontact import reference as ref
from surfaces import Grid, HeightField

from contact_checks import check_contact_state

LAMBDA, H0, E_STAR, N = 1e-3, 1e-6, 1e6, 8192
P_STAR = np.pi * E_STAR * H0 / LAMBDA
LOADS = [0.01, 0.05, 0.2, 0.5, 0.8, 0.95]


@pytest.fixture(scope="module")
def sinusoid():
    grid = Grid((N, 1), (LAMBDA, LAMBDA / N), periodic=True)
    x = grid.coordinates()[0]
    return HeightField(grid, H0 * np.cos(2 * np.pi * x / LAMBDA)[:, None]), ElasticHalfSpace(grid, E_star=E_STAR), x


@pytest.fixture(scope="module")
def solutions(sinusoid):
    field, half, _ = sinusoid
    return {s: solve_contact(field, half, mean_pressure=s * P_STAR, tol=1e-10) for s in LOADS + [0.99]}


def test_full_contact_pressure_reference():
    assert ref.westergaard_full_contact_pressure(H0, LAMBDA, E_STAR) == pytest.approx(P_STAR, rel=1e-15)


@pytest.mark.parametrize("s", LOADS)
def test_half_width_mean_gap_pressure_energy(solutions, sinusoid, s):
    _, _, x = sinusoid
    result = solutions[s]
    p_mean = s * P_STAR
    assert result.converged and result.mean_pressure == pytest.approx(p_mean, rel=1e-12)
    # bar: 0.5 %. Half-width from the counted contact set (±1 pixel per edge); measured ≤ 0.12 % (s = 0.01)
    half_width = result.contact_fraction * LAMBDA / 2
    assert half_width == pytest.approx(ref.westergaard_contact_half_width(p_mean, H0, LAMBDA, E_STAR), rel=2.5e-3)
    # bar: 0.5 %; measured ≤ 5.2e-7 (s = 0.95), assert 2e-6 (margin 4)
    assert result.mean_gap == pytest.approx(ref.westergaard_mean_gap(p_mean, H0, LAMBDA, E_STAR), rel=2e-6)
    # pressure away from the √ edges: measured ≤ 1.5e-6 p* (s = 0.01), assert 5e-6 p* (margin 3.4)
    a = ref.westergaard_contact_half_width(p_mean, H0, LAMBDA, E_STAR)
    distance = (x + LAMBDA / 2) % LAMBDA - LAMBDA / 2
    core = np.abs(distance) < 0.9 * a
    error = np.abs(result.pressure[:, 0] - ref.westergaard_pressure(x, p_mean, H0, LAMBDA, E_STAR))[core]
    assert error.max() < 5e-6 * P_STAR
    # energy per area (¼ − ½ ln s) s² h0 p*; measured ≤ 8.0e-7 (s = 0.01), assert 3e-6 (margin 3.7)
    assert result.elastic_energy / result.grid.area == pytest.approx(
        ref.westergaard_elastic_energy_density(p_mean, H0, LAMBDA, E_STAR), rel=3e-6)


def test_physics_consistency(sinusoid, solutions):
    field = sinusoid[0]
    for result in solutions.values():
        check_contact_state(field, result)                                   # on the raw gap s − h + u


def test_physics_check_fails_on_an_unconverged_result(sinusoid):
    field, half, _ = sinusoid
    result = solve_contact(field, half, mean_pressure=0.5 * P_STAR, tol=1e-10, maxiter=2, warn=False)
    assert not result.converged
    with pytest.raises(AssertionError, match="complementarity|interpenetration"):
        check_contact_state(field, result)


def test_converges_near_full_contact(solutions):
    result = solutions[0.99]
    assert result.converged and result.iterations < 1000
    # measured 9.4e-6 (the contact edge within a pixel of the valley), assert 3e-5 (margin 3)
    assert result.mean_gap == pytest.approx(ref.westergaard_mean_gap(0.99 * P_STAR, H0, LAMBDA, E_STAR), rel=3e-5)


@pytest.mark.parametrize("s", [1.0, 1.05, 2.0])
def test_full_contact_reached_and_reported(sinusoid, s):
    field, half, x = sinusoid
    result = solve_contact(field, half, mean_pressure=s * P_STAR, tol=1e-10)
    assert result.converged
    if s == 1.0:    # at exactly p* the valley carries zero pressure: at most that pixel is out of contact
        assert result.contact_fraction >= 1 - 1 / N
    else:           # beyond p*: p = p̄ + p* cos(2πx/λ) > 0 everywhere (Φ = 2/(E* q) inverted exactly)
        assert result.contact_fraction == 1.0 and result.mean_gap == 0.0
        expected = s * P_STAR + P_STAR * np.cos(2 * np.pi * x / LAMBDA)
        np.testing.assert_allclose(result.pressure[:, 0], expected, rtol=0, atol=1e-9 * P_STAR)


def test_full_contact_is_exact_without_iterating(sinusoid):
    """Beyond p*, p = p̄ + p* cos(2πx/λ) > 0: the solver recognises full contact from p̄ + K⁻¹(h − ⟨h⟩) and
    returns it without a CG step, whatever the warm start (secant or previous field)."""
    field, half, x = sinusoid
    loads = P_STAR * np.array([1.2, 1.4, 1.7])
    secant = list(load_path(field, half, loads, tol=1e-10))
    previous = list(load_path(field, half, loads, tol=1e-10, predictor="previous"))
    assert all(r.converged and r.contact_fraction == 1.0 for r in secant + previous)
    assert all(r.iterations == 0 and r.solver.details["full_contact"] for r in secant + previous)
    just_below = solve_contact(field, half, mean_pressure=0.99 * P_STAR)
    assert not just_below.solver.details["full_contact"] and just_below.contact_fraction < 1.0
    expected = loads[2] + P_STAR * np.cos(2 * np.pi * x / LAMBDA)
    np.testing.assert_allclose(secant[2].pressure[:, 0], expected, rtol=0, atol=1e-9 * P_STAR)
    with pytest.raises(ValueError, match="predictor"):
        next(load_path(field, half, loads, predictor="linear"))


# -- bi-sinusoid -------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def bisinusoid():
    n, delta = 256, 1e-6
    grid = Grid((n, n), (LAMBDA, LAMBDA), periodic=True)
    x, y = grid.meshgrid()
    field = HeightField(grid, delta * np.cos(2 * np.pi * x / LAMBDA) * np.cos(2 * np.pi * y / LAMBDA))
    return field, ElasticHalfSpace(grid, E_star=E_STAR), ref.bisinusoid_full_contact_pressure(delta, LAMBDA, E_STAR)


@pytest.mark.parametrize("s", [0.002, 0.005])
def test_bisinusoid_low_load_area(bisinusoid, s):
    """A/λ² → 0.7616 (p̄/p*)^(2/3): measured ratio 1.04 and 1.03 on 256² (pixelation of ~12 px contacts)."""
    field, half, p_star = bisinusoid
    result = solve_contact(field, half, mean_pressure=s * p_star, tol=1e-9)
    assert result.converged
    assert result.contact_fraction / ref.bisinusoid_area_low_load(s) == pytest.approx(1.0, abs=0.06)


@pytest.mark.parametrize("s", [0.95, 0.97])
def test_bisinusoid_near_full_contact_area(bisinusoid, s):
    """1 − A/λ² → (3/(2π))(1 − p̄/p*): measured ratio 1.003 and 0.991 on 256²."""
    field, half, p_star = bisinusoid
    result = solve_contact(field, half, mean_pressure=s * p_star, tol=1e-9)
    assert result.converged
    assert (1 - result.contact_fraction) / (1 - ref.bisinusoid_area_near_full_contact(s)) == pytest.approx(1.0, abs=0.04)


def test_bisinusoid_full_contact(bisinusoid):
    field, half, p_star = bisinusoid
    result = solve_contact(field, half, mean_pressure=1.01 * p_star, tol=1e-9)
    assert result.converged and result.contact_fraction == 1.0
    # full contact: u = h + const, so p = p̄ + (E*|q|/2) h with |q| = √2 · 2π/λ (both modes of cos·cos),
    # i.e. p̄ + p* cos cos; measured 6.8e-14 p*, assert 1e-12 p*
    q = np.sqrt(2) * 2 * np.pi / LAMBDA
    np.testing.assert_allclose(result.pressure, 1.01 * p_star + E_STAR * q / 2 * field.heights, rtol=0,
                               atol=1e-12 * p_star)
    assert result.mean_gap == 0.0
