"""The FE contact-length reduction over (f_N, μ) mapped to the friction law's ridge-area reduction (no FElupe)."""
import numpy as np
import pytest

from roughcontact.fe.feed import (PACKAGED_SUMMARY, FEAreaReduction, FETableWarning, effective_friction,
                                  fe_friction_columns, fe_reduced_state)
from roughcontact.macro import SlidingFrictionModel

FORCES = np.array([25.0, 50.0, 100.0, 200.0, 400.0])
FRICTIONS = np.array([0.26, 0.5, 1.0, 3.0])


def synthetic(**kwargs):
    """L0 = 1e-3 f_N^0.4, ξ = L0 (0.02 + 0.002 μ)/f_N² — power laws in f_N and linear in μ, so that the
    interpolation is exact; L at full slip from Eq. 34 at f_T = μ f_N (reductions 0.1–23 %)."""
    mu, force = FRICTIONS[:, None], FORCES[None, :]
    initial = np.broadcast_to(1.0e-3 * force ** 0.4, (mu.size, force.size))
    xi = initial * (0.02 + 0.002 * mu) / force ** 2
    return FEAreaReduction(FORCES, FRICTIONS, initial, xi, initial - xi * (mu * force) ** 2, **kwargs)


def test_table_interpolates_power_laws_in_f_N_and_lines_in_mu():
    reduction = synthetic()
    initial, xi, _ = reduction.eq34(np.array([50.0, 300.0, 70.0]), np.array([0.26, 0.75, 2.0]))
    forces = np.array([50.0, 300.0, 70.0])
    assert np.allclose(initial, 1.0e-3 * forces ** 0.4, rtol=1e-12)
    assert np.allclose(xi, initial * (0.02 + 0.002 * np.array([0.26, 0.75, 2.0])) / forces ** 2, rtol=1e-12)


def test_outside_the_table_is_nan_not_extrapolated():
    reduction = synthetic()
    values = reduction.eq34(np.array([10.0, 100.0, 100.0]), np.array([0.26, 0.2, 3.5]))
    assert np.isnan(np.stack(values)).all()
    # f_T beyond the FE's full slip μ f_N is refused, at it accepted
    assert np.isnan(reduction.length_ratio(100.0, 0.5, 50.0 * (1 + 1e-6)))
    assert np.isfinite(reduction.length_ratio(100.0, 0.5, 50.0))


@pytest.mark.parametrize("isotropic", [False, True])
def test_friction_law_with_the_fe_reduction_gives_the_fe_area_ratio_at_mu_eff(isotropic):
    # the law's solution F_T must satisfy F_T = μ0 (F_N + σ_el A_R) with A_R/A_R0 the FE's mapped L(f_T)/L0 at
    # μ_eff = μ0 (1 + σ_el A_R0/F_N), computed here on an independent path (to 1e-12; bisection to 1e-15)
    model, reduction = SlidingFrictionModel.paper_table1(), synthetic(isotropic=isotropic)
    forces, voltages = np.array([[0.5], [1.0], [2.0]]), np.array([[0.0, 100.0, 200.0]])
    state, mu_eff = fe_reduced_state(model, forces, voltages, reduction)
    base = model.state(forces, voltages)
    assert np.allclose(mu_eff, effective_friction(model.mu0, base.attraction * base.initial_area, forces), rtol=1e-14)
    expected = reduction.area_ratio(np.broadcast_to(forces, (3, 3)), state.tangential_force, mu_eff)
    assert np.allclose(state.area / state.initial_area, expected, rtol=1e-12)
    assert np.allclose(state.tangential_force, model.mu0 * (forces + state.attraction * state.area), rtol=1e-12)
    assert np.array_equal(state.tangential_force[:, 0], model.mu0 * forces[:, 0])   # U = 0: μ0 F_N
    assert np.array_equal(mu_eff[:, 0], np.full(3, model.mu0))                       # the FE at μ0
    assert (state.area < state.initial_area).all()
    # never beyond the FE's full slip: f_T <= μ_eff f_N at every point, at U = 0 exactly at it
    line_t = state.tangential_force / reduction.width(forces)
    assert (line_t <= mu_eff * reduction.line_load(forces) * (1 + 1e-12)).all()


def test_isotropic_mapping_reduces_more():
    model = SlidingFrictionModel.paper_table1()
    linear, _ = fe_reduced_state(model, 1.0, 100.0, synthetic())
    squared, _ = fe_reduced_state(model, 1.0, 100.0, synthetic(isotropic=True))
    assert squared.area_reduction > linear.area_reduction
    assert squared.tangential_force < linear.tangential_force


def test_points_outside_the_table_are_nan_and_warned():
    model = SlidingFrictionModel.paper_table1()
    small = FEAreaReduction(FORCES, FRICTIONS[:2], *(np.stack([row] * 2) for row in
                                                     (synthetic().initial_lengths[0], synthetic().xi[0],
                                                      synthetic().sliding_lengths[0])))
    with pytest.warns(FETableWarning, match="does not cover"):
        columns = fe_friction_columns(model, 1.0, 200.0, small)          # μ_eff > 0.5
    assert np.isnan(columns["bottom_up_fe_friction_coefficient"])
    assert columns["bottom_up_fe_contact_friction"] > 0.5


def test_width_is_the_diameter_of_the_apparent_area():
    reduction = synthetic()
    area = reduction.apparent.nonadhesive_area(1.0)
    assert reduction.width(1.0) == pytest.approx(2 * np.sqrt(area / np.pi), rel=1e-14)
    assert reduction.line_load(1.0) == pytest.approx(1.0 / reduction.width(1.0), rel=1e-14)


def test_bad_tables_are_refused():
    good = synthetic()
    with pytest.raises(ValueError, match="xi"):
        FEAreaReduction(FORCES, FRICTIONS, good.initial_lengths, -good.xi, good.sliding_lengths)
    with pytest.raises(ValueError, match="shape"):
        FEAreaReduction(FORCES, FRICTIONS, good.initial_lengths[:, :3], good.xi, good.sliding_lengths)
    with pytest.raises(ValueError, match="ascending"):
        FEAreaReduction(FORCES[::-1], FRICTIONS, good.initial_lengths, good.xi, good.sliding_lengths)
    holes = good.xi.copy()
    holes[1, 1:] = np.nan
    with pytest.raises(ValueError, match="at least 2 runs"):
        FEAreaReduction(FORCES, FRICTIONS, good.initial_lengths, holes, good.sliding_lengths)
    with pytest.raises(ValueError, match="normal_force must be > 0"):
        effective_friction(0.26, 1.0, 0.0)


def test_packaged_fe_table_covers_mu0_to_the_default_scenes_mu_eff():
    # the table written by 'roughcontact fingertip-fe' (default mesh) and shipped with the package: μ0 = 0.26
    # exactly (0 V), up to μ_eff = 2.5 (the default scene's largest is 2.15 at 0.5 N, 200 V), and a ξ that falls
    # with f_N and rises as μ falls (the +28 % of μ = 0.26 against 0.35)
    reduction = FEAreaReduction.from_summary(PACKAGED_SUMMARY)
    assert reduction.frictions[0] == 0.26 and reduction.frictions[-1] >= 2.5
    _, xi, _ = reduction.eq34(np.array([50.0, 200.0]), 0.26)
    assert xi[1] < xi[0]
    _, xi_low, _ = reduction.eq34(100.0, 0.26)
    _, xi_high, _ = reduction.eq34(100.0, 0.35)
    assert xi_low > xi_high
