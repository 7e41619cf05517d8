"""Rough (self-affine) contact: small-load area law, physics consistency, result object, load path, options."""
import dataclasses
import pickle

import numpy as np
import pytest

from roughcontact import ContactProblem, ContactResult, ElasticHalfSpace, load_path, solve_contact
from roughcontact.reference.benchmark import rough_surface
from roughcontact.solvers import PERIMETER_CORRECTION, SolverReport, boundary_edges
from roughcontact.solvers.polonsky_keer import STALL_STEPS, solve_hard_wall
from surfaces import Grid, rms_slope, self_affine

from contact_checks import check_contact_state

L, E_STAR, SLOPE = 1e-3, 1e6, 0.1


@pytest.fixture(scope="module")
def rough():
    grid = Grid((256, 256), (L, L), periodic=True)
    field = self_affine(grid, hurst=0.8, rms_slope=SLOPE, short_cutoff=8 * L / 256, rolloff=L / 4, rng=0)
    half = ElasticHalfSpace(grid, E_star=E_STAR)
    return field, half, solve_contact(field, half, mean_pressure=0.02 * E_STAR * SLOPE, tol=1e-9)


@pytest.mark.slow
def test_small_load_area_coefficient():
    """A/A0 = κ p̄/(E* h'_rms) at small load with κ in issue 4's band [1.6, 2.3] (Hyun et al. 2004: κ ≈ 2).

    docs/findings/contact_area.md (studies/contact_area_coefficient.py): pixel counting adds a perimeter term that
    falls as Δx/λ_s (Yastrebov et al. 2017), κ falls slowly with the breadth λ_r/λ_s, and one surface with 16
    roll-off cells scatters by ±0.11 (16 seeds), so a resolved, broad case averaged over seeds is tested:
    λ_s = 16 px, λ_r = 16 λ_s = L/4, p̄ = 0.01 E* h', seeds 0–3: κ = 2.40, 2.26, 2.29, 1.99, mean 2.24
    (16 seeds: 2.27 ± 0.03; pixel bias at 16 px +0.08, resolved limit 2.19). λ_s = 4 px gives 2.46 (fails).
    """
    grid = Grid((1024, 1024), (L, L), periodic=True)
    half = ElasticHalfSpace(grid, E_star=E_STAR)
    load = 0.01 * E_STAR * SLOPE
    kappas = []
    for seed in range(4):
        field = self_affine(grid, hurst=0.8, rms_slope=SLOPE, short_cutoff=16 * L / 1024, rolloff=L / 4, rng=seed)
        assert rms_slope(field) == pytest.approx(SLOPE, rel=1e-9)
        result = solve_contact(field, half, mean_pressure=load, tol=1e-8)
        assert result.converged
        kappas.append(result.contact_fraction / (load / (E_STAR * SLOPE)))
    # centred on the 16-seed mean 2.27 ± 3 standard errors of a 4-seed mean (3 × 0.11/√4), inside issue 4's bar
    # [1.6, 2.3]: a change of the contact set by more than the seed scatter fails (measured 2.24)
    assert max(1.6, 2.27 - 3 * 0.11 / 2) <= np.mean(kappas) <= min(2.3, 2.27 + 3 * 0.11 / 2)


def test_area_coefficient_falls_with_resolution_of_short_cutoff():
    """One surface (λ_s = L/32, λ_r = L/4, seed 0) on 128², 256², 512²: λ_s = 4, 8, 16 px, p̄ = 0.01 E* h'.

    Pixel counting over-estimates the area by a perimeter term ∝ Δx, so κ falls and converges at first order:
    measured κ = 2.81, 2.55, 2.47, steps 0.26 and 0.09 (step ratio 2.2–3.0 over seeds 0–3; 2 for exact first
    order; the perimeter-corrected κ stays at 2.32–2.35 on all three grids, docs/findings/contact_area.md).

    The Yastrebov correction removes that bias: corrected κ = 2.342, 2.317, 2.348 (spread 0.031; seeds 1–3:
    0.054, 0.014, 0.020) where the pixel count spreads by 0.35. Asserted: spread < 0.1, which the pixel count
    (0.25–0.42 over seeds 0–3) or the coefficient halved (0.17) or doubled (0.36) would fail.
    """
    kappas, corrected = [], []
    for n in (128, 256, 512):
        grid = Grid((n, n), (L, L), periodic=True)
        field = self_affine(grid, hurst=0.8, rms_slope=SLOPE, short_cutoff=L / 32, rolloff=L / 4, rng=0)
        load = 0.01 * E_STAR * SLOPE
        result = solve_contact(field, ElasticHalfSpace(grid, E_star=E_STAR), mean_pressure=load, tol=1e-8)
        assert result.converged
        kappas.append(result.contact_fraction / (load / (E_STAR * SLOPE)))
        corrected.append(result.corrected_contact_fraction / (load / (E_STAR * SLOPE)))
    coarse_step, fine_step = kappas[0] - kappas[1], kappas[1] - kappas[2]
    assert coarse_step > 1.5 * fine_step > 0
    assert max(corrected) - min(corrected) < 0.1


def test_physics_consistency(rough):
    field, half, result = rough
    assert result.converged and result.mean_pressure == pytest.approx(0.02 * E_STAR * SLOPE, rel=1e-12)
    # complementarity on the raw gap s − h + u (result.gap is clipped and zeroed under pressure: no test), and
    # the same check fails on the same problem stopped after two steps
    check_contact_state(field, result)
    unconverged = solve_contact(field, half, mean_pressure=result.mean_pressure, maxiter=2, warn=False)
    with pytest.raises(AssertionError, match="complementarity|interpenetration"):
        check_contact_state(field, unconverged)
    # u = K p exactly (recomputed at the end), periodic: <u> = 0, so <g> = s − <h> (to the solver tolerance)
    np.testing.assert_allclose(result.displacement, half.displacement(result.pressure), rtol=0,
                               atol=1e-12 * np.abs(result.displacement).max())
    flat_position = field.heights.max() - result.penetration
    assert result.mean_gap == pytest.approx(flat_position - field.heights.mean(), rel=1e-7)
    # gap on the contact set is zero to tol × rms height; outside it equals s − h + u
    raw_gap = flat_position - field.heights + result.displacement
    scale = field.heights.std()
    assert np.abs(raw_gap[result.contact]).max() < 1e-6 * scale
    np.testing.assert_allclose(result.gap[~result.contact], raw_gap[~result.contact], rtol=0, atol=1e-12 * scale)
    # energy: ½ Σ p u dA equals the Fourier-space form ½ A Σ_q 2|p̂|²/(E* q)
    q = field.grid.wavevector_magnitude()
    power = np.abs(np.fft.fft2(result.pressure) / result.pressure.size) ** 2
    fourier = 0.5 * field.grid.area * np.sum(np.divide(2 * power, E_STAR * q, out=np.zeros_like(q), where=q > 0))
    assert result.elastic_energy == pytest.approx(fourier, rel=1e-10)
    assert result.residuals[-1] <= 1e-9 and len(result.residuals) == result.iterations + 1


def test_load_and_displacement_control_agree(rough):
    field, half, result = rough
    force = solve_contact(field, half, total_force=result.total_force, tol=1e-9)
    np.testing.assert_allclose(force.pressure, result.pressure, rtol=0, atol=1e-6 * result.pressure.max())
    by_penetration = solve_contact(field, half, penetration=result.penetration, tol=1e-9)
    assert by_penetration.converged
    assert by_penetration.mean_pressure == pytest.approx(result.mean_pressure, rel=1e-5)
    assert by_penetration.contact_fraction == pytest.approx(result.contact_fraction, abs=2 / field.grid.size)


def same_record(a, b) -> bool:
    """Whether two results hold the same SolverReport (field by field, the residuals array by value), control and
    requested load."""
    same = all(np.array_equal(getattr(a.solver, f.name), getattr(b.solver, f.name)) if f.name == "residuals"
               else getattr(a.solver, f.name) == getattr(b.solver, f.name) for f in dataclasses.fields(SolverReport))
    return same and (a.control, a.requested) == (b.control, b.requested)


def test_result_save_load_and_pickle(rough, tmp_path):
    _, _, result = rough
    loaded = ContactResult.load(result.save(tmp_path / "contact.npz"))
    for name in ("pressure", "displacement", "gap", "contact", "residuals"):
        np.testing.assert_array_equal(getattr(loaded, name), getattr(result, name))
        assert not getattr(loaded, name).flags.writeable                  # read-only, like the solver's result
    for name in ("contact_fraction", "mean_pressure", "mean_gap", "penetration", "elastic_energy", "iterations",
                 "converged", "message", "wall_time"):
        assert getattr(loaded, name) == getattr(result, name)
    assert same_record(loaded, result) and loaded.grid == result.grid
    assert loaded.solver.method == "polonsky-keer" and loaded.solver.kernel["backend"] == "pyfftw"
    clone = pickle.loads(pickle.dumps(result))
    np.testing.assert_array_equal(clone.pressure, result.pressure)
    assert same_record(clone, result)


def test_load_path_warm_start(rough):
    field, half, _ = rough
    loads = E_STAR * SLOPE * np.linspace(0.01, 0.03, 6)
    warm = list(load_path(field, half, loads, tol=1e-9))
    cold = list(load_path(field, half, loads, warm_start=False, cold_start="pk", tol=1e-9))
    nested = list(load_path(field, half, loads, warm_start=False, tol=1e-9))
    for w, c, load in zip(warm + nested, cold + cold, np.concatenate([loads, loads])):
        assert w.converged and c.converged and w.mean_pressure == pytest.approx(load, rel=1e-12)
        assert w.contact_fraction == pytest.approx(c.contact_fraction, abs=2 / field.grid.size)
        assert w.mean_gap == pytest.approx(c.mean_gap, rel=1e-6)
    # iteration counts are deterministic: the 5 warm steps take 88 iterations with the secant predictor, 93 from
    # the last field ("previous"), 121 cold from PK's uniform pressure, 90 (+ 9 at 64², 5 at 128² each) nested
    previous = list(load_path(field, half, loads, tol=1e-9, predictor="previous"))
    steps = {name: sum(r.iterations for r in results[1:]) for name, results in
             (("secant", warm), ("previous", previous), ("pk", cold), ("nested", nested))}
    assert steps["secant"] <= steps["previous"] < 0.8 * steps["pk"] and steps["nested"] < 0.8 * steps["pk"]
    assert [r.solver.start for r in warm] == ["nested"] + ["x0"] * 5
    assert all(r.solver.start == "nested" and len(r.solver.details["nested_iterations"]) == 2 for r in nested)
    assert [r.contact_fraction for r in warm] == sorted(r.contact_fraction for r in warm)
    with pytest.raises(ValueError, match="x0"):
        next(load_path(field, half, loads, x0=warm[0]))


def test_load_path_resumes_and_shows_progress(rough, capsys):
    """An interrupted sweep resumed from its last saved result gives the uninterrupted answers (to tol)."""
    field, half, _ = rough
    loads = E_STAR * SLOPE * np.linspace(0.01, 0.03, 4)
    whole = list(load_path(field, half, loads, tol=1e-9))
    first_two = list(load_path(field, half, loads[:2], tol=1e-9, progress=True))
    assert "load path" in capsys.readouterr().err                   # the tqdm bar went to stderr
    resumed = list(load_path(field, half, loads[2:], start=first_two, tol=1e-9))
    for a, b in zip(first_two + resumed, whole):
        # the same warm starts in the same order: identical iterates, hence identical results
        np.testing.assert_array_equal(a.pressure, b.pressure)
        assert a.iterations == b.iterations
    # from the last result alone the secant predictor restarts: a different first prediction, the same answer
    alone = next(load_path(field, half, loads[2:], start=first_two[-1], tol=1e-9))
    assert alone.iterations != whole[2].iterations
    assert alone.mean_gap == pytest.approx(whole[2].mean_gap, rel=1e-6)
    for bad in (whole[0].pressure, whole[:3], [whole[0], "x"]):
        with pytest.raises(TypeError, match="start"):
            next(load_path(field, half, loads, start=bad))
    with pytest.raises(ValueError, match="warm_start"):
        next(load_path(field, half, loads, start=whole[0], warm_start=False))


def test_callback_and_halt(rough):
    field, half, _ = rough
    seen = []

    def callback(state):
        seen.append(state)
        if state.iteration == 5:
            raise StopIteration

    with pytest.warns(UserWarning, match="halted by callback after 5 iterations"):
        result = solve_contact(field, half, mean_pressure=0.02 * E_STAR * SLOPE, callback=callback)
    assert not result.converged and result.iterations == 5 and "halted" in result.message
    assert [s.iteration for s in seen] == [1, 2, 3, 4, 5]
    assert all(0 < s.contact_fraction < 1 and s.residual > 0 for s in seen)
    assert np.isfinite(result.pressure).all() and result.mean_pressure == pytest.approx(0.02 * E_STAR * SLOPE)


def test_float32_and_scipy_backend_agree(rough):
    field, _, result = rough
    grid = field.grid
    scipy_result = solve_contact(field, ElasticHalfSpace(grid, E_star=E_STAR, backend="scipy"),
                                 mean_pressure=result.mean_pressure, tol=1e-9)
    np.testing.assert_allclose(scipy_result.pressure, result.pressure, rtol=0, atol=1e-9 * result.pressure.max())
    single = solve_contact(field, ElasticHalfSpace(grid, E_star=E_STAR, dtype=np.float32),
                           mean_pressure=result.mean_pressure, tol=1e-5)
    assert single.converged and single.pressure.dtype == np.float32 and single.solver.kernel["dtype"] == "float32"
    # float32 resolves the gap to ~1e-7 of the heights: measured contact fraction 3.1e-4 (a few of ~7000 contact
    # pixels) and mean gap 1.1e-7 from float64; asserted 1e-3 and 5e-7 (margins 3 and 4.6)
    assert single.contact_fraction == pytest.approx(result.contact_fraction, rel=1e-3)
    assert single.mean_gap == pytest.approx(result.mean_gap, rel=5e-7)


def test_warm_start_from_array_is_rescaled(rough):
    field, half, result = rough
    again = solve_contact(field, half, mean_pressure=result.mean_pressure, x0=3 * np.asarray(result.pressure),
                          tol=1e-9)
    assert again.converged and again.iterations <= 2
    np.testing.assert_allclose(again.pressure, result.pressure, rtol=0, atol=1e-6 * result.pressure.max())


def test_agrees_with_tamaas(rough):
    """Same surface, load and E* in Tamaas' Polonsky–Keer–Rey solver (optional `bench` extra): contact
    fraction identical, mean gap to 1e-9 (measured 4e-12 at 512²), pressure field to 1e-7 of its maximum."""
    tm = pytest.importorskip("tamaas")
    field, _, result = rough
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, list(field.grid.lengths), list(field.grid.shape))
    model.E, model.nu = E_STAR, 0.0                       # Tamaas' E/(1 − ν²) is our E*
    heights = np.array(field.heights)
    solver = tm.PolonskyKeerRey(model, heights, 1e-12)
    solver.max_iter = 10000
    solver.solve(result.mean_pressure)
    traction, displacement = np.array(model.traction), np.array(model.displacement)
    assert np.mean(traction > 0) == result.contact_fraction
    gap = displacement - heights
    gap -= gap[traction > 0].mean()
    assert result.mean_gap == pytest.approx(gap.mean(), rel=1e-9)
    np.testing.assert_allclose(result.pressure, traction, rtol=0, atol=1e-7 * traction.max())


@pytest.mark.parametrize("periodic", [True, False])
def test_plain_and_preconditioned_pk_agree(rough, periodic):
    """Plain Polonsky–Keer and the K⁻¹-preconditioned variant (the default) converge to the same contact
    solution, the preconditioned one in fewer steps (deterministic counts; measured 51 → 24 steps periodic,
    40 → 21 free)."""
    field, half, _ = rough
    if not periodic:
        grid = Grid((128, 96), (L, 0.75 * L), periodic=False)
        field = self_affine(grid, hurst=0.8, rms_slope=SLOPE, short_cutoff=8 * L / 128, rng=1)
        half = ElasticHalfSpace(grid, E_star=E_STAR)
    load = 0.02 * E_STAR * SLOPE
    default = solve_contact(field, half, mean_pressure=load, tol=1e-9)
    assert default.solver.details["preconditioned"]
    plain = solve_contact(field, half, mean_pressure=load, tol=1e-9, preconditioned=False)
    preconditioned = solve_contact(field, half, mean_pressure=load, tol=1e-9, preconditioned=True)
    assert plain.converged and preconditioned.converged
    assert preconditioned.iterations < plain.iterations
    # FFT pairs: one for the initial u, per step 1 (set held) to 1.5 (set changed) plus 1 for K⁻¹ g, and at
    # most one final exact recomputation of u
    for result, extra in ((plain, 0.0), (preconditioned, 1.0)):
        steps = result.iterations
        assert 1 + (1 + extra) * steps <= result.solver.fft_pairs <= 2 + (1.5 + extra) * steps
    assert plain.contact_fraction == preconditioned.contact_fraction
    np.testing.assert_allclose(plain.pressure, preconditioned.pressure, rtol=0,
                               atol=1e-6 * preconditioned.pressure.max())
    assert plain.mean_gap == pytest.approx(preconditioned.mean_gap, rel=1e-8)


@pytest.mark.parametrize("layer", [
    {"thickness": 1e-4, "poisson": 0.3},                                       # stratum-corneum-like slab
    {"thickness": 1e-4, "poisson": 0.3, "bottom": "frictionless"},
    {"thickness": 2.5e-4, "poisson": 0.45, "substrate_E_star": 1e4, "substrate_poisson": 0.49},
])
def test_layered_contact(layer):
    """Layered bodies: plain and preconditioned PK agree; on a rigid base ⟨u⟩ = p̄ t/M enters the mean gap."""
    grid = Grid((64, 64), (L, L), periodic=True)
    field = self_affine(grid, hurst=0.8, rms_slope=SLOPE, short_cutoff=8 * L / 64, rng=2)
    half = ElasticHalfSpace(grid, E_star=E_STAR, **layer)
    load = 0.05 * E_STAR * SLOPE
    results = [solve_contact(field, half, mean_pressure=load, tol=1e-10, preconditioned=flag) for flag in (True, False)]
    for result in results:
        assert result.converged
        check_contact_state(field, result)                   # raw gap s − h + u, including ⟨u⟩ = p̄ t/M
    unconverged = solve_contact(field, half, mean_pressure=load, maxiter=2, warn=False)
    with pytest.raises(AssertionError, match="complementarity|interpenetration"):
        check_contact_state(field, unconverged)
    assert results[0].contact_fraction == results[1].contact_fraction
    assert results[0].mean_gap == pytest.approx(results[1].mean_gap, rel=1e-8)
    result = results[0]
    assert result.displacement.mean() == pytest.approx(load * half.uniform_compliance, rel=1e-9, abs=1e-20)
    flat_position = field.heights.max() - result.penetration
    expected_gap = flat_position - field.heights.mean() + result.displacement.mean()
    assert result.mean_gap == pytest.approx(expected_gap, rel=1e-7)


def test_boundary_edges_and_corrected_contact_fraction():
    """Edge counting by hand on an 8 × 8 mask; the border is crossed only on periodic axes."""
    contact = np.zeros((8, 8), dtype=bool)
    contact[2:4, 2:5] = True                                  # a 2 × 3 block: perimeter 10 edges
    contact[0, 0] = contact[-1, 0] = contact[0, -1] = True    # three pixels joined across the periodic edges
    assert boundary_edges(contact) == 10 + 8
    # free on both axes: the three corner pixels are separate, two inner edges each
    assert boundary_edges(contact, periodic=(False, False)) == 10 + 6
    assert boundary_edges(np.ones((1, 8), bool)) == 0 and boundary_edges(np.ones((5, 5), bool)) == 0
    assert PERIMETER_CORRECTION == pytest.approx(0.118114, abs=1e-6)    # (π − 1 + ln 2)/24
    grid = Grid((8, 8), (L, L), periodic=True)
    result = solve_contact(np.where(contact, 1e-6, 0.0), ElasticHalfSpace(grid, E_star=E_STAR), penetration=1e-9)
    assert result.perimeter_edges == boundary_edges(result.contact) == boundary_edges(contact)
    assert result.corrected_contact_fraction == pytest.approx(
        (result.contact.sum() - PERIMETER_CORRECTION * boundary_edges(result.contact)) / 64, rel=1e-15)


def test_reentries_do_not_restart_the_conjugate_gradients():
    """Only a point's first entry into the contact set restarts the CG (docs/guide/solver.md, Restarts). On the
    benchmark surface at 256² (λ_s = 4 px, p̄ = 0.01 E*, tol 1e-10) plain PK then takes 88 steps, against 153
    with Polonsky–Keer's restart on every entry: the bound 110 fails if re-entries restart again."""
    grid = Grid((256, 256), (L, L), periodic=True)
    field = self_affine(grid, hurst=0.8, rms_slope=0.1, short_cutoff=4 * L / 256, rng=0)
    result = solve_contact(field, ElasticHalfSpace(grid, E_star=E_STAR), mean_pressure=0.01 * E_STAR, tol=1e-10,
                           preconditioned=False, cold_start="pk")
    assert result.converged and result.iterations <= 110


@pytest.mark.slow
def test_stalled_residual_restarts_on_every_entry():
    """Keeping β through re-entries can make the contact set cycle. On the benchmark surface at 1024² and
    p̄ = 0.0065 E* from PK's uniform start it did: the residual made its last new minimum at step 19 and
    hovered between 6e-3 and 1e-2 for 10⁴ steps, A/A0 ≈ 0.146–0.162 against 0.138 (found by the benchmark's
    PK-start sweep). After ``STALL_STEPS``
    steps without a new smallest residual every entry restarts the CG (PK's rule), and it converges in 126
    steps; the bound 250 allows for that, and without the fallback ``converged`` fails. ``solve_contact`` hands
    the slow start over to the gap before the fallback (docs/guide/solver.md, "Slow solves continue on the gap"), so the
    fallback is Polonsky–Keer's alone here. The answers must be the nested start's, which never needs either (its
    20 sweep loads at 1024² run 25–41 steps)."""
    surface = rough_surface(1024)
    half = ElasticHalfSpace(surface.grid, E_star=E_STAR)
    problem = ContactProblem(surface, half)
    stalled = solve_hard_wall(problem, problem.control(mean_pressure=0.0065 * E_STAR, tol=1e-8, maxiter=250),
                              cold_start="pk")
    assert stalled.converged
    assert stalled.solver.details["restart_every_entry_from"] >= STALL_STEPS
    handed = solve_contact(surface, half, mean_pressure=0.0065 * E_STAR, tol=1e-8, cold_start="pk", maxiter=250)
    assert handed.converged and "handed_over_at" in handed.solver.details
    nested = solve_contact(surface, half, mean_pressure=0.0065 * E_STAR, tol=1e-8)
    assert nested.solver.details["restart_every_entry_from"] is None and "handed_over_at" not in nested.solver.details
    for result in (stalled, handed):
        np.testing.assert_array_equal(result.contact, nested.contact)
        # converged to 1e-8 of the rms height: pressures agree far below 1e-6 of max p (nested-start test)
        assert np.max(np.abs(result.pressure - nested.pressure)) <= 1e-6 * nested.pressure.max()
