"""The hard wall on the gap: displacement control handed over from Polonsky–Keer where it crawls, the hard wall by
name with method="projected-cg-gap", and the pinned preconditioner (docs/guide/solver.md, "Displacement control")."""
import numpy as np
import pytest

from roughcontact import ContactProblem, ElasticHalfSpace, load_path, solve_contact
from roughcontact.body.elastic import apply_foundation_multiplier
from roughcontact.solvers import projected_cg_gap
from roughcontact.solvers.polonsky_keer import SLOW_STEPS, solve_hard_wall
from roughcontact.study import load_scene
from roughcontact.study.patch import patch_body, roughness_heights
from surfaces import Grid, self_affine

from contact_checks import check_contact_state

TOL = 1e-8


def _micro_patch(n):
    """The default scene's micro patch on n² pixels (standard preset, realisation 0) on its layered skin (a 10 MPa
    layer on 0.1 MPa)."""
    scene = load_scene(text=f"[presets.standard]\ngrid = {n}\n", preset="standard")
    return np.asarray(roughness_heights(scene, 0), float), patch_body(scene)


@pytest.fixture(scope="module")
def micro():
    """The micro patch on 128² pixels, and the penetration that leaves a mean separation of 0.033 rms heights (87 %
    contact)."""
    heights, body = _micro_patch(128)
    return heights, body, heights.max() - heights.mean() - 0.033 * heights.std()


def test_displacement_control_near_full_contact_is_handed_over_to_the_gap(micro):
    """Polonsky–Keer alone takes 14 887 steps (+ 100 on the coarse grid) here, and 279 (+ 100) under load control
    at the same mean pressure; handed over after 20 steps it takes 32 (+ 20), 85 FFT pairs against 22 252.5 and
    680.5 (``python studies/bench_position.py --pk-alone``). The answer is an equilibrium (raw fields) and load
    control's at its mean pressure: the same contact set and flat position to the tolerance."""
    heights, body, penetration = micro
    result = solve_contact(heights, body, penetration=penetration, tol=TOL)
    assert result.converged and result.solver.method == "projected-cg-gap"
    assert result.solver.details["handed_over_at"] == SLOW_STEPS
    assert result.iterations < 60 and 0.85 < result.contact_fraction < 0.9
    # the gap minimised to a tenth of tol leaves the polish 1 step here (9 from the gap solved to tol)
    assert result.solver.details["polish_iterations"] <= 2
    assert result.flat_position == heights.max() - penetration
    check_contact_state(heights, result)
    load = solve_contact(heights, body, mean_pressure=result.mean_pressure, tol=TOL)
    np.testing.assert_array_equal(load.contact, result.contact)
    # flat positions measured 5.8e-11 rms heights apart at tol 1e-8: a bound of the tolerance itself
    assert abs(load.flat_position - result.flat_position) <= TOL * heights.std()


def test_the_gap_of_a_float32_body_stops_at_its_round_off_floor():
    """In float32 the gap is minimised to no less than float32's round-off floor (4 ε32): at tol 5e-7 on the micro
    patch, a tenth of it, 5e-8, is beyond float32's reach, and that gap ran to maxiter (10 000 steps, 30 000 FFT
    pairs); at the floor it takes 14 steps and the polish 16."""
    scene = load_scene(text='[presets.standard]\ngrid = 128\ndtype = "float32"\n', preset="standard")
    heights, body = np.asarray(roughness_heights(scene, 0)), patch_body(scene)
    result = solve_contact(heights, body, mean_pressure=4e5, tol=5e-7, maxiter=300)
    assert result.converged and result.solver.method == "projected-cg-gap"
    assert result.solver.details["gap_iterations"] < 30


def test_slow_exit_stops_polonsky_keer_where_it_crawls(micro):
    heights, body, penetration = micro
    problem = ContactProblem(heights, body)
    slow = solve_hard_wall(problem, problem.control(penetration=penetration, tol=TOL, warn=False), slow_exit=True)
    assert not slow.converged and slow.solver.details["slow_exit_at"] == SLOW_STEPS == slow.iterations
    assert slow.message.startswith("slow")
    # where PK converges fast (a wide separation on the half-space of the contact tests) nothing is handed over
    surface, half = _rough(64)
    problem = ContactProblem(surface, half)
    wide = solve_hard_wall(problem, problem.control(penetration=0.3 * np.ptp(surface.heights), tol=TOL),
                           slow_exit=True)
    assert wide.converged and "slow_exit_at" not in wide.solver.details


def _rough(n, periodic=True, **body):
    grid = Grid((n, n), (1e-3, 1e-3), periodic=periodic)
    surface = self_affine(grid, hurst=0.8, rms_height=3e-6, short_cutoff=8e-3 / n, rng=1)
    return surface, ElasticHalfSpace(grid, E_star=1e6, **body)


@pytest.mark.parametrize("body, control", [
    ({}, "mean_pressure"), ({}, "penetration"),
    ({"thickness": 2e-4, "poisson": 0.3}, "penetration"),
    ({"thickness": 2e-4, "poisson": 0.45, "substrate_E_star": 1e4, "substrate_poisson": 0.49}, "mean_pressure"),
    ({"thickness": 2e-4, "poisson": 0.45, "substrate_E_star": 1e4, "substrate_poisson": 0.49}, "penetration"),
    ("free", "mean_pressure"), ("free", "penetration"), ("profile", "penetration")])
def test_the_hard_wall_by_name_on_the_gap_is_polonsky_keers_answer(body, control):
    """method="projected-cg-gap" solves the hard wall on every kernel and control: the same contact set as
    Polonsky–Keer, the conjugate quantity to the tolerance, a contact state of the raw fields."""
    if body == "profile":
        grid = Grid((512, 1), (1e-3, 1e-3), periodic=True)
        surface = self_affine(grid, hurst=0.8, rms_height=3e-6, short_cutoff=8e-3 / 512, rng=1)
        half = ElasticHalfSpace(grid, E_star=1e6)
    else:
        surface, half = _rough(64, periodic=body != "free", **({} if body == "free" else body))
    heights = surface.heights
    given = {"mean_pressure": 2e3} if control == "mean_pressure" else {"penetration": 0.5 * (heights.max() - heights.mean())}
    reference = solve_contact(surface, half, **given, tol=1e-10)
    result = solve_contact(surface, half, **given, tol=TOL, method="projected-cg-gap")
    assert result.converged and result.solver.method in ("projected-cg-gap", "polonsky-keer")
    check_contact_state(surface, result)
    np.testing.assert_array_equal(result.contact, reference.contact)
    if control == "mean_pressure":
        assert result.mean_pressure == pytest.approx(2e3, rel=1e-12)
        assert abs(result.flat_position - reference.flat_position) <= 10 * TOL * np.ptp(heights)
    else:
        assert result.flat_position == reference.flat_position
        assert result.mean_pressure == pytest.approx(reference.mean_pressure, rel=1e-5)


def test_the_pinned_preconditioner_cuts_the_gap_steps(micro, monkeypatch):
    """On the layered micro patch the open points cannot follow the long, compliant wavelengths that the points
    at the wall pin: with the foundation the gap takes 11 steps at 87 % contact, with the plain compliance (κ = 0)
    119. Load control, so that the gap runs from Polonsky–Keer's slow start."""
    heights, body, penetration = micro
    pressure = solve_contact(heights, body, penetration=penetration, tol=TOL).mean_pressure
    pinned = solve_contact(heights, body, mean_pressure=pressure, tol=TOL, method="projected-cg-gap")
    assert pinned.converged and pinned.solver.details["gap_iterations"] <= 25
    monkeypatch.setattr(projected_cg_gap, "_pinning_edge", lambda g, nx, ny, periodic: (0, 1))
    plain = solve_contact(heights, body, mean_pressure=pressure, tol=TOL, method="projected-cg-gap", maxiter=500)
    assert plain.solver.details["gap_iterations"] > 3 * pinned.solver.details["gap_iterations"]
    np.testing.assert_array_equal(plain.contact, pinned.contact)


def test_pinning_edge_and_foundation_multiplier():
    """The edge count on a known pattern (periodic and not), and Φ/(1 + κΦ) applied to a spectrum."""
    g = np.ones((4, 5))
    g[0, 0] = 0.0                                  # one point at the wall in a corner
    # its neighbours (1, 0), (0, 1), and across the edges (3, 0), (0, 4): four beside the wall when periodic
    assert projected_cg_gap._pinning_edge(g, 4, 5, True) == (4, 19)
    assert projected_cg_gap._pinning_edge(g, 4, 5, False) == (2, 19)
    assert projected_cg_gap._pinning_edge(np.zeros((3, 3)), 3, 3, True) == (0, 0)
    rng = np.random.default_rng(0)
    spectrum = rng.normal(size=(4, 3)) + 1j * rng.normal(size=(4, 3))
    multiplier = rng.uniform(0.1, 2.0, size=(4, 3))
    expected = spectrum * multiplier / (1 + 0.7 * multiplier)
    apply_foundation_multiplier(spectrum, multiplier, 0.7)
    np.testing.assert_allclose(spectrum, expected, rtol=1e-14)


def test_a_warm_start_solved_on_the_gap_continues_on_the_gap(micro):
    """A load-controlled solve warm from a result that was handed over to the gap (Polonsky–Keer slow on this body)
    continues on the gap from that result's gap at once: 39 FFT pairs at 2 MPa from the 1.6 MPa result, where
    Polonsky–Keer from its pressure is slow again and hands over after 20 steps (94 pairs; the cold solve 93). The
    same answer as the cold solve. A pressure field as x0 still starts Polonsky–Keer."""
    heights, body, _ = micro
    last = solve_contact(heights, body, mean_pressure=1.6e6, tol=TOL)
    assert projected_cg_gap.solved_on_the_gap(last) and "handed_over_at" in last.solver.details
    warm = solve_contact(heights, body, mean_pressure=2e6, tol=TOL, x0=last)
    assert warm.converged and warm.solver.start == "x0" and "handed_over_at" not in warm.solver.details
    assert warm.solver.fft_pairs < 45
    cold = solve_contact(heights, body, mean_pressure=2e6, tol=TOL)
    np.testing.assert_array_equal(warm.contact, cold.contact)
    assert abs(warm.flat_position - cold.flat_position) <= TOL * heights.std()
    from_pressure = solve_contact(heights, body, mean_pressure=2e6, tol=TOL, x0=last.pressure)
    assert from_pressure.solver.details["handed_over_at"] == SLOW_STEPS


def test_a_load_sweep_on_the_layered_skin_costs_under_half_the_cold_solves():
    """``load_path`` on the 64² micro patch, 10 loads 0.4 … 4 MPa: each warm step continues on the gap from the
    secant of the last two gaps, 350 FFT pairs against the cold solves' 843 (0.42; from the last gap alone,
    ``predictor="previous"``, 375; Polonsky–Keer from the pressure's secant 834.5). The answers are the cold
    solves' to the tolerance; a sweep resumed from two saved results repeats the uninterrupted one exactly."""
    heights, body = _micro_patch(64)
    loads = np.linspace(0.4e6, 4e6, 10)
    warm = list(load_path(heights, body, loads, tol=TOL))
    cold = [solve_contact(heights, body, mean_pressure=load, tol=TOL) for load in loads]
    assert all(result.converged for result in warm + cold)
    assert [result.solver.start for result in warm[1:]] == ["x0"] * 9
    previous = list(load_path(heights, body, loads, tol=TOL, predictor="previous"))
    pairs = [sum(result.solver.fft_pairs for result in results) for results in (warm, cold, previous)]
    assert pairs[0] <= 0.45 * pairs[1] and pairs[0] < pairs[2]
    for a, b in zip(warm, cold):
        np.testing.assert_array_equal(a.contact, b.contact)
        # flat positions measured at most 2.4e-10 rms heights apart at tol 1e-8
        assert abs(a.flat_position - b.flat_position) <= TOL * heights.std()
    resumed = list(load_path(heights, body, loads[4:7], start=warm[2:4], tol=TOL))
    for a, b in zip(resumed, warm[4:7]):
        np.testing.assert_array_equal(a.gap, b.gap)
        assert a.iterations == b.iterations
