"""The FE fingertip (FElupe) against 2-D Hertz, the Coulomb limit at full slip and the seed's trends.

Skipped without FElupe. The runs use small meshes: the Hertz press 3 s, the two coarse press-and-slide runs
shared by three tests 15 s on the 2-core machine (11 s and 48 s while other jobs loaded it); marked slow.
"""
import numpy as np
import pytest

pytest.importorskip("felupe", reason="the FE fingertip needs FElupe: pip install 'roughcontact[fe]'")
pytest.importorskip("tensortrax", reason="the FE fingertip's Ogden tissues need tensortrax: "
                                         "pip install 'roughcontact[fe]'")

from roughcontact.fe.analysis import fit_eq34  # noqa: E402
from roughcontact.fe.geometry import FingerSection, MeshResolution  # noqa: E402
from roughcontact.fe.materials import FingerMaterials  # noqa: E402
from roughcontact.fe.model import FingertipModel  # noqa: E402


@pytest.mark.slow
def test_small_load_frictionless_press_matches_2d_hertz():
    # a round neo-Hookean section, rigid core, load for a Hertz half-width a = R/20 (a ≪ R and ≪ the 7 mm of
    # tissue under the core); a/h ≈ 10 on this mesh gives 1.6 % (3 % is the bar; 0.14 % at a/h = 32, see
    # docs/guide/fe_fingertip.md); a wrong E* by 10 % would move L by 5 %
    radius, shear, poisson = 10e-3, 10e3, 0.3
    materials = FingerMaterials.homogeneous(shear, poisson)
    half_width = radius / 20
    load = np.pi * materials.skin.plane_strain_modulus * half_width ** 2 / (4 * radius)
    model = FingertipModel(section=FingerSection.circular(radius, 3e-3, 0.3e-3), materials=materials,
                           resolution=MeshResolution(around=120, subcutaneous=8, skin=3, contact_refinement=0.1,
                                                     grading=2.0), approach_step=0.01)   # 0.1 mm: as the check
    pressed = model.press(load)
    assert pressed.snapshot.normal.sum() == pytest.approx(load, rel=1e-6)     # the plate carries the load
    assert pressed.length == pytest.approx(2 * half_width, rel=0.03)
    assert (pressed.snapshot.tangential == 0).all()                           # frictionless


MU0 = 0.26          # the friction law's μ0: the FE's contact at 0 V


@pytest.fixture(scope="module")
def coarse_runs():
    model = FingertipModel(resolution=MeshResolution.coarse(), friction=MU0)
    return [model.slide(force) for force in (50.0, 150.0)]


@pytest.mark.slow
def test_full_slip_reaches_the_coulomb_limit(coarse_runs):
    for run in coarse_runs:
        assert run.full_slip and run.converged
        # the force that drives the bone (its tie's reaction, not the contact sum) is μ f_N at full slip:
        # the Newton tolerance (1e-6 f_N) bounds the imbalance; the bar is 1e-3
        assert run.bone_tangential_force[-1] == pytest.approx(run.friction * run.normal_force, rel=1e-3)
        assert np.allclose(run.contact_normal_force, run.normal_force, rtol=1e-5)   # f_N held while sliding
        assert (run.bone_tangential_force[1:-1] < run.friction * run.normal_force).all()   # partial slip before


@pytest.mark.slow
def test_contact_length_shrinks_with_tangential_force_and_more_so_at_higher_load(coarse_runs):
    low, high = coarse_runs
    for run in coarse_runs:
        fit = fit_eq34(run.tangential_force, run.length)
        assert fit.slope < 0 and -fit.slope > 3 * fit.slope_error            # ξ > 0, resolved
        assert run.sliding_length < run.initial_length
    assert high.initial_length > low.initial_length
    assert high.relative_reduction > low.relative_reduction


@pytest.mark.slow
def test_study_outputs_carry_provenance(coarse_runs, tmp_path, capsys):
    from roughcontact.fe.feed import FEAreaReduction
    from roughcontact.fe.study import EXPONENT_CSV, SUMMARY_CSV, FingertipStudy, write_fingertip_outputs
    from roughcontact.io.provenance import Provenance

    study = FingertipStudy(model=FingertipModel(resolution=MeshResolution.coarse()), runs=tuple(coarse_runs))
    provenance = Provenance(command="pytest", parameters={})
    paths = write_fingertip_outputs(study, tmp_path, provenance)
    assert {p.suffix for p in paths} == {".csv", ".png"} and all(p.stat().st_size > 0 for p in paths)
    assert all(p.read_text().startswith("# roughcontact") for p in paths if p.suffix == ".csv")
    # two forces: no exponent table, and the reason said
    assert not (tmp_path / EXPONENT_CSV).exists() and "needs at least 3" in capsys.readouterr().err
    table = FEAreaReduction.from_summary(tmp_path / SUMMARY_CSV)     # one μ, two forces: a table of the feed
    assert table.frictions.tolist() == [MU0] and table.normal_forces.tolist() == [50.0, 150.0]


@pytest.mark.slow
def test_mu_eff_at_zero_attraction_is_the_mu0_run_bit_for_bit(coarse_runs):
    # electroadhesion enters the FE only through the contact's μ_eff = μ0 (1 + F_el/F_N): with F_el = 0 the run
    # is the μ0 run, every number identical (the tissue is loaded by f_N alone in both)
    from roughcontact.fe.feed import effective_friction

    mu_eff = float(effective_friction(MU0, 0.0, 50.0))
    run = FingertipModel(resolution=MeshResolution.coarse(), friction=mu_eff).slide(50.0)
    reference = coarse_runs[0]
    for name in ("travel", "tangential_force", "contact_normal_force", "length", "final_points"):
        assert np.array_equal(getattr(run, name), getattr(reference, name)), name


@pytest.mark.slow
def test_a_run_at_mu_eff_half_reaches_full_slip_at_half_the_normal_force():
    # the interface's capacity μ_eff f_N at full slip, the tissue loaded by f_N: the sum of the nodal friction
    # forces is μ_eff f_N to round-off (1e-9, measured 1e-13), the force on the bone to the Newton tolerance
    # (1e-6 f_N), and f_N is carried throughout
    run = FingertipModel(resolution=MeshResolution.coarse(), friction=0.5).slide(50.0)
    assert run.full_slip and run.converged
    assert run.tangential_force[-1] == pytest.approx(0.5 * 50.0, rel=1e-9)
    assert run.bone_tangential_force[-1] == pytest.approx(0.5 * 50.0, rel=1e-6)
    assert np.allclose(run.contact_normal_force, 50.0, rtol=1e-5)
    assert (run.tangential_force[1:-1] < 0.5 * 50.0).all()
