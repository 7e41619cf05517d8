"""The FE contact-length reduction mapped to the friction law's ridge-area reduction (no FElupe)."""
import numpy as np
import pytest

from roughcontact.fe.feed import PACKAGED_SUMMARY, FEAreaReduction, fe_reduced_state
from roughcontact.macro import SlidingFrictionModel


def synthetic(**kwargs):
    forces = np.array([25.0, 50.0, 100.0, 200.0, 400.0])
    return FEAreaReduction(forces, 1.0e-3 * forces ** 0.4, 3e-5 * forces ** -1.1, **kwargs)


def test_power_law_fits_return_the_table():
    reduction = synthetic()
    lengths, xi = reduction.eq34(np.array([50.0, 300.0]))
    assert np.allclose(lengths, 1.0e-3 * np.array([50.0, 300.0]) ** 0.4, rtol=1e-12)
    assert np.allclose(xi, 3e-5 * np.array([50.0, 300.0]) ** -1.1, rtol=1e-12)


def test_friction_law_with_the_fe_reduction_gives_the_fe_area_ratio():
    # the friction law solves A_R = A_R0 − η F_T² with η from reduction.c2; at its solution F_T the area ratio
    # must equal L(f_T)/L0 computed directly from ξ, L0 and the width (an independent path to 1e-12)
    model, reduction = SlidingFrictionModel.paper_table1(), synthetic()
    forces, voltages = np.array([[0.5], [1.0], [2.0]]), np.array([[0.0, 100.0, 200.0]])
    state = fe_reduced_state(model, forces, voltages, reduction)
    assert state.tangential_force.shape == (3, 3)
    expected = reduction.area_ratio(np.broadcast_to(forces, (3, 3)), state.tangential_force)
    assert np.allclose(state.area / state.initial_area, expected, rtol=1e-12)
    assert np.allclose(state.tangential_force[:, 0], model.mu0 * forces[:, 0], rtol=1e-12)   # U = 0: μ0 F_N
    assert (state.area < state.initial_area).all()
    # the seed's fitted c2 gives another answer: the feed really replaces it
    assert not np.allclose(state.tangential_force, model.state(forces, voltages).tangential_force, rtol=1e-3)


def test_width_is_the_diameter_of_the_apparent_area():
    reduction = synthetic()
    area = reduction.apparent.nonadhesive_area(1.0)
    assert reduction.width(1.0) == pytest.approx(2 * np.sqrt(area / np.pi), rel=1e-14)
    assert reduction.line_load(1.0) == pytest.approx(1.0 / reduction.width(1.0), rel=1e-14)
    # isotropic shrinkage: (L/L0)², twice the linear reduction for small reductions
    iso = synthetic(isotropic=True)
    small = reduction.area_ratio(1.0, 0.01)
    assert 1 - iso.area_ratio(1.0, 0.01) == pytest.approx(2 * (1 - small), rel=1e-4)


def test_bad_tables_are_refused():
    with pytest.raises(ValueError, match="xi"):
        FEAreaReduction(np.array([1.0, 2.0, 3.0]), np.ones(3), np.array([1.0, -1.0, 1.0]))
    with pytest.raises(ValueError, match="same length"):
        FEAreaReduction(np.array([1.0, 2.0, 3.0]), np.ones(4), np.ones(3))


def test_packaged_fe_table_gives_a_decreasing_xi():
    # the table written by 'roughcontact fingertip-fe' (default mesh) and shipped with the package
    reduction = FEAreaReduction.from_summary(PACKAGED_SUMMARY)
    assert reduction.normal_forces.size >= 3
    _, xi = reduction.eq34(np.array([50.0, 200.0]))
    assert xi[1] < xi[0]
