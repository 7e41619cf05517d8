"""Contact length, Eq. 34 fit and power laws of roughcontact.fe.analysis against analytic profiles (no FElupe)."""
import numpy as np
import pytest

from roughcontact.fe.analysis import contact_edges, contact_length, contact_pressure, fit_eq34, power_law_fit


def hertz_nodes(half_width, spacing, offset=0.0):
    """Nodal forces of the 2-D Hertz pressure p0 √(1 − x²/a²) on nodes of ``spacing`` (force = p ℓ), and a gap
    ∝ (|x| − a)^(3/2) outside, −1e-9 inside (a penalty's small penetration)."""
    x = np.arange(-3 * half_width, 3 * half_width, spacing) + offset
    pressure = np.sqrt(np.clip(1 - (x / half_width) ** 2, 0, None))
    gap = np.where(np.abs(x) < half_width, -1e-9, np.clip(np.abs(x) - half_width, 0, None) ** 1.5)
    return x, pressure * spacing, gap


@pytest.mark.parametrize("nodes_per_half_width", [10, 20, 40])
def test_pressure_edges_find_the_hertz_width(nodes_per_half_width):
    # the edge of p² extrapolated: the error is well below one node spacing (h/a = 1/n); the bound a/n²·3
    # is what a √-edge gives for linear p² (measured 0.2–0.9 of it); the off-grid offset avoids a node on the edge
    a = 1e-3
    x, force, gap = hertz_nodes(a, a / nodes_per_half_width, offset=0.37 * a / nodes_per_half_width)
    low, high = contact_edges(x, force, gap)
    assert abs((high - low) / (2 * a) - 1) < 3 / nodes_per_half_width ** 2
    # the gap crossing stays within one spacing but is much less accurate
    gap_length = contact_length(x, force, gap, edge="gap")
    assert abs(gap_length / (2 * a) - 1) < 1 / nodes_per_half_width


def test_pressure_is_force_over_tributary_length():
    x = np.array([0.0, 1.0, 3.0, 4.0])
    assert np.allclose(contact_pressure(x, [1.0, 3.0, 3.0, 1.0]), [1.0, 2.0, 2.0, 1.0])


def test_contact_at_the_end_of_the_candidates_is_refused():
    x = np.linspace(0, 1, 5)
    with pytest.raises(ValueError, match="end of the candidate"):
        contact_length(x, [1, 1, 0, 0, 0], [-1, -1, 1, 1, 1])
    with pytest.raises(ValueError, match="edge must be"):
        contact_length(x, [0, 1, 1, 1, 0], [1, -1, -1, -1, 1], edge="middle")
    assert contact_length(x, np.zeros(5), np.ones(5)) == 0.0


def test_eq34_and_power_law_fits_recover_their_parameters():
    rng = np.random.default_rng(3)
    f_t = np.linspace(0, 100, 30)
    fit = fit_eq34(f_t, 9e-3 - 2e-7 * f_t ** 2)
    assert fit.intercept == pytest.approx(9e-3, rel=1e-12) and fit.slope == pytest.approx(-2e-7, rel=1e-10)
    forces = np.array([25, 50, 100, 200, 400.0])
    noise = np.exp(0.05 * rng.standard_normal(forces.size))
    law = power_law_fit(forces, 3e-5 * forces ** -1.1 * noise)
    # 5 points with 5 % scatter over 1.2 decades: the exponent within 3 standard errors, and the error honest
    assert abs(law.slope + 1.1) < 3 * law.slope_error
    assert 0.01 < law.slope_error < 0.1
    with pytest.raises(ValueError, match="positive"):
        power_law_fit(forces, -forces)
