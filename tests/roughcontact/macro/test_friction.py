"""Sliding friction under electroadhesion (seed Eqs. 40–46) and the equivalent-gap models."""
import pickle

import numpy as np
import pytest

from roughcontact.electrostatics import DielectricStack
from roughcontact.macro import (ConstantGap, LinearGap, PowerLawContact, PowerLawGap, SlidingFrictionModel,
                                SlidingState, TabulatedGap)

MODEL = SlidingFrictionModel.paper_table1()
FORCES = np.array([1e-9, 0.1, 0.5, 1.0, 2.0, 2.3])


def test_table1_parameters():
    assert MODEL.mu0 == 0.26
    assert MODEL.c2 == pytest.approx(5000e-12, rel=1e-15)                  # 5000 mm⁴/N² in m⁴/N²
    assert MODEL.contact == PowerLawContact.table1_ridge()
    assert MODEL.stack == DielectricStack()
    assert MODEL.tau0 == 0.0
    np.testing.assert_allclose(MODEL.gap([0.0, 0.5, 2.0], 0.0), [3.1e-6, 2.85e-6, 2.1e-6], rtol=1e-14)


@pytest.mark.parametrize("voltage", [0.0, 1e-9])
def test_no_voltage_gives_amontons(voltage):
    # 1e-12: σ_el(1e-9 V) ~ 1e-15 Pa changes F_T by ~1e-20 relative; the rest is rounding
    np.testing.assert_allclose(MODEL.tangential_force(FORCES, voltage), 0.26 * FORCES, rtol=1e-12)
    np.testing.assert_allclose(MODEL.friction_coefficient(FORCES, voltage), 0.26, rtol=1e-12)


@pytest.mark.parametrize("voltage", [50.0, 100.0, 200.0])
def test_closed_form_solves_eqs_41_43_44(voltage):
    state = MODEL.state(FORCES, voltage)
    sigma, area_0, force_t = state.attraction, state.initial_area, state.tangential_force
    eta = MODEL.c2 / area_0                                               # Eq. 44
    # Eq. 41 with Eq. 43, self-consistently
    np.testing.assert_allclose(state.area, area_0 - eta * force_t ** 2, rtol=1e-12)
    np.testing.assert_allclose(force_t, 0.26 * (FORCES + sigma * state.area), rtol=1e-12)
    np.testing.assert_allclose(state.electrostatic_force, sigma * state.area, rtol=1e-14)
    # Eq. 45 as printed (well conditioned here: 4μ0²σηX is O(0.01-1))
    printed = (-1 / (2 * 0.26 * eta * sigma)
               + np.sqrt((2 * 0.26 * eta * sigma) ** -2 + FORCES / (eta * sigma) + area_0 / eta))
    np.testing.assert_allclose(force_t, printed, rtol=1e-7)
    np.testing.assert_allclose(state.friction_coefficient, 0.26 * (1 + state.electrostatic_force / FORCES),
                               rtol=1e-12)                                # Eq. 42
    # the chain: gap (Eq. 46) -> σ_el, w (Eqs. 21-22) -> A_R0 (Eq. 9 inverted)
    gap = 3.1e-6 - 0.5e-6 * FORCES
    np.testing.assert_allclose(state.gap, gap, rtol=1e-14)
    np.testing.assert_allclose(sigma, DielectricStack().attraction(gap, voltage), rtol=1e-14)
    np.testing.assert_allclose(area_0, MODEL.contact.area(FORCES, DielectricStack().work_of_adhesion(gap, voltage)),
                               rtol=1e-14)


def test_without_area_reduction():
    model = SlidingFrictionModel(c2=0.0)
    state = model.state(FORCES, 200.0)
    np.testing.assert_allclose(state.tangential_force, 0.26 * (FORCES + state.attraction * state.initial_area),
                               rtol=1e-14)


def test_adhesion_controlled_term_eq40():
    model = SlidingFrictionModel(tau0=2e3)
    for voltage in (0.0, 150.0):
        state = model.state(FORCES, voltage)
        np.testing.assert_allclose(state.tangential_force,
                                   2e3 * state.area + 0.26 * (FORCES + state.attraction * state.area), rtol=1e-12)


def test_extremes_stay_finite():
    # voltage-only contact (F_N = 0), tiny, large loads, 10 kV
    state = MODEL.state(np.array([0.0, 1e-9, 2.3, 100.0]), np.array([[0.0], [200.0], [1e4]]))
    assert state.tangential_force.shape == (3, 4)
    assert np.isfinite(state.tangential_force).all() and np.isfinite(state.area).all()
    assert state.tangential_force[0, 0] == 0.0 and state.friction_coefficient[0, 0] == 0.26   # nothing at all
    assert state.tangential_force[1, 0] > 0 and state.friction_coefficient[1, 0] == np.inf    # voltage only
    assert state.initial_area[1, 0] == pytest.approx(float(MODEL.contact.zero_load_area(state.work_of_adhesion[1, 0])),
                                                     rel=1e-12)
    # 100 N: the linear gap is saturated at 0 and the reduction law at A_R = 0 (F_T = μ0 F_N)
    assert state.gap[1, 3] == 0.0
    assert state.area_saturated[0, 3] and state.area_saturated[1, 3]
    assert state.tangential_force[1, 3] == pytest.approx(26.0, rel=1e-14)
    assert not state.area_saturated[:, :3].any()
    assert (state.area >= 0).all() and (state.area <= state.initial_area).all()


def test_saturation_is_continuous():
    """At c₂(μ0F_N)² = A_R0² the quadratic root equals μ0F_N, so the rule A_R >= 0 switches continuously."""
    forces = np.linspace(15.0, 25.0, 2001)
    state = SlidingFrictionModel(gap_model=ConstantGap(3e-6)).state(forces, 100.0)
    switch = np.argmax(state.area_saturated)
    assert 0 < switch
    jump = state.tangential_force[switch] - state.tangential_force[switch - 1]
    assert 0 < jump < 2 * 0.26 * (forces[1] - forces[0])


@pytest.mark.parametrize("force", [0.0, -1e-4, np.array([1.0, 0.0])])     # -1e-4 N: above the pull-off force
def test_friction_coefficient_needs_a_positive_normal_force(force):
    with pytest.raises(ValueError, match=r"normal_force > 0, got (0\.0|-0\.0001) N"):
        MODEL.friction_coefficient(force, 200.0)
    assert np.isfinite(MODEL.tangential_force(force, 200.0)).all()     # the force itself is defined there


def test_only_the_square_of_the_voltage_enters():
    np.testing.assert_array_equal(MODEL.friction_coefficient(FORCES, -150.0), MODEL.friction_coefficient(FORCES, 150.0))
    np.testing.assert_array_equal(MODEL.state(FORCES, -150.0).area, MODEL.state(FORCES, 150.0).area)


def test_below_pull_off_raises():
    with pytest.raises(ValueError, match="pull-off"):
        MODEL.tangential_force(-0.1, 200.0)


@pytest.mark.parametrize("call, name", [
    (lambda: MODEL.tangential_force(np.nan, 100.0), "normal_force"),
    (lambda: MODEL.tangential_force(1.0, np.inf), "voltage"),
    (lambda: SlidingFrictionModel(mu0=0.0), "mu0"),
    (lambda: SlidingFrictionModel(c2=-1.0), "c2"),
    (lambda: SlidingFrictionModel(stack=DielectricStack(d_sc=-1e-6)), "d_sc"),
    (lambda: SlidingFrictionModel(stack=DielectricStack(eps_i=0.0)), "eps_i"),
    (lambda: ConstantGap(-1e-6), "gap"),
    (lambda: LinearGap(-1e-6, 0.5e-6), "gap_at_zero_load"),
    (lambda: SlidingFrictionModel(gap_model=lambda f, u: -1e-6 + 0 * f).tangential_force(1.0, 100.0), "gap_model"),
    (lambda: SlidingFrictionModel(gap_model=lambda f, u: np.nan + 0 * f).tangential_force(1.0, 100.0), "gap_model"),
    (lambda: SlidingFrictionModel(gap_model=lambda f, u: np.full(3, 2e-6)).tangential_force(np.ones(2), 100.0),
     r"gap_model returned shape \(3,\) for normal_force and voltage of shape \(2,\)"),
    (lambda: MODEL.tangential_force(np.ones(3), np.ones(2) * 100.0), r"normal_force \(3,\), voltage \(2,\)"),
    (lambda: ConstantGap(2e-6)(np.ones(3), np.ones(2)), r"normal_force \(3,\), voltage \(2,\)"),
])
def test_bad_input_raises(call, name):
    with pytest.raises(ValueError, match=name):
        call()


def test_complex_input_is_refused():
    for call in (lambda: MODEL.tangential_force(1.0 + 0j, 100.0), lambda: MODEL.state(1.0, np.array([100.0 + 0j])),
                 lambda: SlidingFrictionModel(gap_model=lambda f, u: 2e-6 + 0j * f).tangential_force(1.0, 100.0)):
        with pytest.raises(TypeError, match="must be real, got complex"):
            call()


def test_gap_must_be_callable():
    with pytest.raises(TypeError, match="gap_model"):
        SlidingFrictionModel(gap_model=3e-6)


# -- gap models -----------------------------------------------------------------------------------------------
def test_linear_gap_saturates_at_zero():
    gap = LinearGap.paper_table1()
    np.testing.assert_allclose(gap([0.0, 6.2, 7.0, 100.0], 200.0), [3.1e-6, 0.0, 0.0, 0.0], atol=1e-20)


def test_power_law_gap_through_guo_points():
    gap = PowerLawGap.guo2019()
    np.testing.assert_allclose(gap([0.5, 4.5], 150.0), [2.5e-6, 1.5e-6], rtol=1e-13)
    assert gap(0.0, 150.0) == gap.max_gap
    with pytest.raises(ValueError, match="normal_force"):
        gap(-0.1, 0.0)


def test_tabulated_gap_is_bilinear_and_plugs_in():
    forces, voltages = np.array([0.0, 1.0, 2.5]), np.array([0.0, 100.0, 200.0])
    table = (3.1e-6 - 0.5e-6 * forces[:, None]) * (1 - 1e-3 * voltages[None, :] / 200)
    gap = TabulatedGap(forces, voltages, table)
    # a bilinear function is reproduced exactly, also between the nodes; the voltage enters as |U|
    f, u = np.array([0.3, 1.7, 2.5]), np.array([-50.0, 150.0, 200.0])
    np.testing.assert_allclose(gap(f, u), (3.1e-6 - 0.5e-6 * f) * (1 - 1e-3 * np.abs(u) / 200), rtol=1e-13)
    with pytest.raises(ValueError, match="normal_force"):
        gap(3.0, 0.0)
    # a voltage-independent table that equals Eq. 46 gives the paper's friction
    linear = TabulatedGap(np.array([0.0, 2.5]), np.array([0.0]), np.array([[3.1e-6], [1.85e-6]]))
    model = SlidingFrictionModel(gap_model=linear)
    np.testing.assert_allclose(model.tangential_force(FORCES, 150.0), MODEL.tangential_force(FORCES, 150.0),
                               rtol=1e-12)
    assert pickle.loads(pickle.dumps(model)) == model


def test_any_callable_is_a_gap_model():
    model = SlidingFrictionModel(gap_model=lambda force, voltage: np.full(np.shape(force), 2e-6))
    reference = SlidingFrictionModel(gap_model=ConstantGap(2e-6))
    np.testing.assert_array_equal(model.tangential_force(FORCES, 100.0), reference.tangential_force(FORCES, 100.0))


# -- results --------------------------------------------------------------------------------------------------
def test_pickle_and_save_round_trip(tmp_path):
    assert pickle.loads(pickle.dumps(MODEL)) == MODEL
    state = MODEL.state(FORCES, [[0.0], [200.0]])
    for copy in (pickle.loads(pickle.dumps(state)), SlidingState.load(state.save(tmp_path / "state.npz"))):
        for name in state.__dataclass_fields__:
            np.testing.assert_array_equal(getattr(copy, name), getattr(state, name))


def test_a_pickled_tabulated_gap_is_read_only_again():
    import pickle
    gap = TabulatedGap(np.array([0.5, 2.0]), np.array([0.0, 100.0]), np.array([[3e-6, 2e-6], [2e-6, 1e-6]]))
    copy = pickle.loads(pickle.dumps(gap))
    assert copy == gap and not copy.gaps.flags.writeable and not copy.normal_forces.flags.writeable
    with pytest.raises(ValueError, match="read-only"):
        copy.gaps[0, 0] = 0.0
