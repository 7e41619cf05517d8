"""The FE-fed friction law on the default scene: at every voltage up to 200 V no friction point evaluates the FE's
L(f_T) beyond the FE's own full slip at its μ_eff, and the packaged table covers every μ_eff (no FElupe: the
packaged table; the scene's draft study, about 20 s on 2 cores, marked slow)."""
import numpy as np
import pytest

from roughcontact.fe.feed import PACKAGED_SUMMARY, FEAreaReduction, fe_reduced_state
from roughcontact.study.friction import bottom_up_friction
from roughcontact.study.run import run_study
from roughcontact.study.scene import load_scene


@pytest.fixture(scope="module")
def default_scene():
    return run_study(load_scene(preset="draft"))


@pytest.mark.slow
@pytest.mark.parametrize("isotropic", [False, True])
def test_default_scene_never_asks_the_fe_beyond_its_full_slip(default_scene, isotropic):
    result = default_scene
    model = bottom_up_friction(result)
    table = FEAreaReduction.from_summary(PACKAGED_SUMMARY, isotropic=isotropic)
    forces, voltages = result.normal_forces[:, None], result.voltages[None, :]
    assert voltages.max() >= 200.0
    state, mu_eff = fe_reduced_state(model, forces, voltages, table)     # RuntimeError if a point went beyond
    assert np.isfinite(state.tangential_force).all()                   # every μ_eff inside the table
    assert mu_eff.max() <= table.frictions.max() and np.array_equal(mu_eff[:, 0], np.full(forces.size, model.mu0))
    # f_T <= μ_eff f_N with the mapped FE length ratio at f_T defined (NaN beyond full slip)
    width = table.width(forces)
    line_t, line_n = state.tangential_force / width, table.line_load(forces)
    assert (line_t <= mu_eff * line_n * (1 + 1e-12)).all()
    assert np.isfinite(table.length_ratio(np.broadcast_to(line_n, mu_eff.shape), mu_eff, line_t)).all()
    # the electroadhesion raises μ above μ0, the reduction holds it below μ_eff
    assert (state.friction_coefficient[:, 1:] > model.mu0).all()
    assert (state.friction_coefficient <= mu_eff * (1 + 1e-12)).all()
