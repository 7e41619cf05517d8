"""Interaction laws and the contact solver for smooth laws with the wall (roughcontact.solvers.projected_cg_gap).

References: finite differences of the laws; the hard wall (Polonsky–Keer) at a vanishing law; parallel plates;
Johnson's (1995) adhesive sinusoid in the JKR limit; force balance, complementarity and u = K p recomputed
from the solver's own fields.
"""
import math

import numpy as np
import pytest

from surfaces import Grid, HeightField, self_affine
from roughcontact import (ContactProblem, ContactResult, ElasticHalfSpace, ElectrostaticInteraction,
                          ExponentialAdhesion, HardWall, MaugisDugdale, solve_contact)
from roughcontact.electrostatics import DielectricStack
from roughcontact.reference import johnson_sinusoid_load

from contact_checks import check_equilibrium

STACK = DielectricStack()


@pytest.mark.parametrize("law, gaps", [
    (ElectrostaticInteraction(STACK, 200.0), [0.0, 1e-7, 1e-6, 3e-6]),
    (ElectrostaticInteraction(DielectricStack(eps_a=2.0), -150.0), [0.0, 1e-7, 1e-6, 3e-6]),
    (ExponentialAdhesion(0.05, 2e-7), [0.0, 1e-7, 5e-7, 1e-6]),
    (MaugisDugdale(0.05, 2e-7), [0.0, 1e-7, 3e-7, 1e-6]),          # away from the jump at δ_c
])
def test_law_traction_and_stiffness_are_derivatives(law, gaps):
    gaps = np.array(gaps) + 1e-9
    step = 1e-11                                # central differences: error O(step²/length²) ~ 1e-8 relative
    traction = -(law.energy(gaps + step) - law.energy(gaps - step)) / (2 * step)
    stiffness = (law.traction(gaps + step) - law.traction(gaps - step)) / (2 * step)
    np.testing.assert_allclose(law.traction(gaps), traction, rtol=1e-6, atol=1e-9 * abs(law.traction(0.0)))
    np.testing.assert_allclose(law.stiffness(gaps), stiffness, rtol=1e-6, atol=1e-3)
    assert np.all(law.traction(gaps) <= 0) and abs(law.energy(1.0)) <= 1e-6 * abs(law.energy(0.0))   # V(∞) = 0


@pytest.mark.parametrize("law", [ElectrostaticInteraction(STACK, 200.0, field="parallel_plate"),
                                 ElectrostaticInteraction(DielectricStack(eps_a=2.0), -150.0, field="parallel_plate"),
                                 ExponentialAdhesion(0.05, 2e-7), MaugisDugdale(0.05, 2e-7)])
def test_solver_kernel_evaluates_the_laws_as_their_methods(law):
    # the solver evaluates a law through its numba kernel (law.kernel, compiled into projected_cg_gap's passes by
    # _law_at), a second writing of the formulas of the law's numpy methods: the two must agree to round-off, in
    # Python and compiled
    from numba import njit

    from roughcontact.solvers.projected_cg_gap import _evaluate, _law_at

    gaps = np.concatenate([[0.0, 1.999e-7, 2.001e-7], np.random.default_rng(0).uniform(0, 5e-6, 50)])
    kernel = law.kernel
    compiled = njit(lambda kernel, gap: _law_at(kernel, gap))
    for at in (_law_at, compiled):
        values = np.array([at(kernel, gap) for gap in gaps])
        for column, method in enumerate((law.energy, law.traction, law.stiffness)):
            np.testing.assert_allclose(values[:, column], method(gaps), rtol=1e-13, atol=0)
    traction, stiffness = np.empty_like(gaps), np.empty_like(gaps)
    pel, h_f = np.linspace(0.5, 1.5, gaps.size), np.linspace(-1e-6, 1e-6, gaps.size)
    sums = _evaluate(law, kernel, gaps, np.ones(gaps.size, np.bool_), h_f, pel, traction, stiffness)
    np.testing.assert_allclose(traction, law.traction(gaps), rtol=1e-13, atol=0)
    np.testing.assert_allclose(stiffness, law.stiffness(gaps), rtol=1e-13, atol=0)
    expected = (gaps.sum(), np.sum((gaps + h_f) * pel), pel.sum(), np.sum(law.energy(gaps)))
    np.testing.assert_allclose(sums, expected, rtol=1e-13, atol=0)


def test_only_the_per_pixel_laws_carry_a_kernel():
    # the layered field is non-local and a user's law has no kernel unless it brings one: both are evaluated
    # through their numpy methods; a kernel's parameters are floats (an integer would change the compiled pass)
    assert HardWall().kernel is None and ElectrostaticInteraction(STACK, 100.0).kernel is None
    assert ElectrostaticInteraction(STACK, 100.0, field="parallel_plate").kernel.a == pytest.approx(
        0.5 * 8.8541878128e-12 * 100.0 ** 2, rel=1e-9)
    for law in (ExponentialAdhesion(1, 2), MaugisDugdale(1, 2)):
        assert all(type(value) is float for value in law.kernel)


def test_laws_reject_bad_parameters():
    with pytest.raises(ValueError, match="work_of_adhesion"):
        ExponentialAdhesion(-1.0, 1e-6)
    with pytest.raises(ValueError, match="length"):
        MaugisDugdale(0.1, 0.0)
    with pytest.raises(TypeError, match="stack"):
        ElectrostaticInteraction("stack", 10.0)
    with pytest.raises(ValueError, match="voltage"):
        ElectrostaticInteraction(STACK, math.nan)


# -- rough patch helpers ---------------------------------------------------------------------------------------
def rough_patch(n=64, E_star=1e6, **body):
    grid = Grid((n, n), (1e-3, 1e-3), periodic=True)
    surface = self_affine(grid, hurst=0.8, rms_height=3e-6, short_cutoff=8e-3 / n, rng=1)
    return surface, ElasticHalfSpace(grid, E_star=E_star, **body)


def test_zero_voltage_is_the_hard_wall_bit_for_bit():
    surface, half = rough_patch()
    hard = solve_contact(surface, half, mean_pressure=1e3)
    law = ElectrostaticInteraction(STACK, 0.0)
    res = solve_contact(surface, half, mean_pressure=1e3, interaction=law)
    np.testing.assert_array_equal(res.pressure, hard.pressure)
    np.testing.assert_array_equal(res.gap, hard.gap)
    assert res.interaction == law and hard.interaction == HardWall()
    assert res.equivalent_gap == STACK.equivalent_gap(hard.gap) and res.electrostatic_force == 0.0


def test_vanishing_attraction_matches_polonsky_keer():
    # 1e-6 V: σ_el ~ 1e-16 Pa, negligible; the smooth solver must reach the hard-wall answer by its own path
    surface, half = rough_patch()
    hard = solve_contact(surface, half, mean_pressure=1e3, tol=1e-10)
    res = solve_contact(surface, half, mean_pressure=1e3, interaction=ElectrostaticInteraction(STACK, 1e-6),
                        tol=1e-10)
    assert res.converged and res.solver.method == "projected-cg-gap"
    np.testing.assert_array_equal(res.contact, hard.contact)
    # measured 3e-9 of max p; the bound is the solvers' tolerance times a margin of 100 on the gap scale
    assert np.max(np.abs(res.pressure - hard.pressure)) <= 1e-6 * hard.pressure.max()


def test_parallel_plates():
    grid = Grid((16, 16), (1e-3, 1e-3), periodic=True)
    half = ElasticHalfSpace(grid, E_star=1e6)
    law = ElectrostaticInteraction(STACK, 200.0)
    gap = 2e-6
    res = solve_contact(HeightField(grid, np.zeros(grid.shape)), half, penetration=-gap, interaction=law)
    sigma = float(STACK.attraction(gap, 200.0))
    assert res.converged and res.contact_fraction == 0.0
    np.testing.assert_allclose(res.gap, gap, rtol=1e-14)
    assert res.mean_pressure == pytest.approx(-sigma, rel=1e-12)
    assert res.electrostatic_force == pytest.approx(sigma * grid.area, rel=1e-12)
    assert res.equivalent_gap == pytest.approx(gap, rel=1e-12)
    assert res.interaction_energy == pytest.approx(float(STACK.energy(gap, 200.0)) * grid.area, rel=1e-12)


# -- Johnson (1995): adhesive sinusoid in the JKR limit ---------------------------------------------------------
def sinusoid(n):
    """h = −(1 − cos 2πx) on a unit wavelength, E* = 1/π, so that p* = π E* h/λ = 1."""
    grid = Grid((n, 1), (1.0, 1.0 / n), periodic=True)
    x = (np.arange(n) + 0.5) / n - 0.5
    return HeightField(grid, -(1 - np.cos(2 * np.pi * x))[:, None]), ElasticHalfSpace(grid, E_star=1 / np.pi)


def johnson_load(half_width, alpha):
    """p̄/p* of Johnson (1995) on the unit wavelength."""
    return johnson_sinusoid_load(half_width, 1.0, alpha)


def johnson_law(alpha, length):
    return ExponentialAdhesion(alpha ** 2 * np.pi / 2, length)      # α² = 2 w λ / (π² E* h²)


@pytest.mark.parametrize("load", [0.1, 0.3])
def test_johnson_sinusoid_load_versus_contact_width(load):
    n = 2048
    surface, half = sinusoid(n)
    res = solve_contact(surface, half, mean_pressure=load, interaction=johnson_law(0.2, np.sqrt(1 / n)))
    assert res.converged
    half_width = np.count_nonzero(res.contact) / n / 2
    # measured 0.0044 and 0.0049 p* (range √Δx: finite-range and pixel errors); the bar is 1 %
    assert abs(johnson_load(half_width, 0.2) - load) <= 0.01
    unconverged = solve_contact(surface, half, mean_pressure=load, interaction=johnson_law(0.2, np.sqrt(1 / n)),
                                maxiter=2, warn=False)
    assert not unconverged.converged
    assert abs(johnson_load(np.count_nonzero(unconverged.contact) / n / 2, 0.2) - load) > 0.01


@pytest.mark.parametrize("alpha, half_width", [(0.5, 0.2515), (0.55, 0.2924), (0.6, 0.5)])
def test_johnson_sinusoid_jump_to_full_contact(alpha, half_width):
    # from a hard-wall contact of half-width 0.27 λ released to zero load: a partial contact holds below
    # α ≈ 0.57 (at the JKR root), above it the contact closes. The range 0.05 λ lets the cohesive zone span
    # several pixels (a shorter one pins the crack front on the grid and stops it anywhere).
    n = 2048
    surface, half = sinusoid(n)
    start = solve_contact(surface, half, mean_pressure=np.sin(np.pi * 0.27) ** 2)
    res = solve_contact(surface, half, mean_pressure=0.0, interaction=johnson_law(alpha, 0.05), x0=start)
    assert res.converged
    # measured 0.2480, 0.2900, 0.5 (full contact): within 1.5 % of the JKR roots 0.2515, 0.2924
    assert np.count_nonzero(res.contact) / n / 2 == pytest.approx(half_width, rel=0.015)
    assert res.unstable_steps > 0       # the cohesive zone is concave: 3, 19, 14 steps measured


def test_no_tunnelling_into_contact(monkeypatch):
    # α = 0.5 at zero load from the flat touching the crest: the contact grows to a partial contact (the
    # loading branch, below JKR's 0.2515 λ with this short range); without the step limit the first long steps
    # carry the whole crest into contact
    n = 2048
    surface, half = sinusoid(n)
    law = johnson_law(0.5, np.sqrt(1 / n))
    res = solve_contact(surface, half, mean_pressure=0.0, interaction=law)
    assert res.converged and 0.2 < np.count_nonzero(res.contact) / n / 2 < 0.2515    # measured 0.2363
    monkeypatch.setattr("roughcontact.solvers.projected_cg_gap.APPROACH", np.inf)
    assert solve_contact(surface, half, mean_pressure=0.0, interaction=law).contact_fraction == 1.0


def test_tensile_load_beyond_pull_off_is_reported():
    n = 512
    surface, half = sinusoid(n)
    with pytest.warns(UserWarning, match="no equilibrium"):
        res = solve_contact(surface, half, mean_pressure=-0.5, interaction=johnson_law(0.2, np.sqrt(1 / n)))
    assert not res.converged and res.detached and res.contact_fraction == 0
    assert np.isfinite(res.gap).all() and np.isfinite(res.pressure).all()


# -- electroadhesion on a rough patch ---------------------------------------------------------------------------
def test_rough_patch_grows_with_voltage():
    surface, half = rough_patch()
    results = [solve_contact(surface, half, mean_pressure=1e3, interaction=ElectrostaticInteraction(STACK, U))
               for U in (0.0, 10.0, 30.0, 100.0)]
    assert all(res.converged for res in results)
    areas = [res.contact_fraction for res in results]
    forces = [res.electrostatic_force for res in results]
    gaps = [res.equivalent_gap for res in results]
    assert np.all(np.diff(areas) > 0) and np.all(np.diff(forces) > 0) and np.all(np.diff(gaps) < 0)
    for res in results[1:]:
        history = np.array(res.solver.details["energy_history"])
        assert np.all(np.diff(history) <= 1e-12 * np.abs(history).max())   # the energy never rises
        assert res.equivalent_gap == STACK.equivalent_gap(res.gap)
        imbalance = check_equilibrium(res, surface, half, tol_traction=1e-6 * 1e3)
        assert imbalance <= 1e-3 * 1e3                                      # measured ≤ 3e-6 p̄


def test_unstable_steps_count_the_snap_in():
    # the attraction out-softens the elastic stiffness only where it pulls regions into contact: on this patch
    # at 30 V and above (measured 0, 0, 0 steps at 1e-6, 3, 10 V; 4 of 27 at 30 V; 13 of 14 at 100 V, which jumps
    # to full contact). The count must see the concave steps and only those.
    surface, half = rough_patch()
    counts = {}
    for voltage in (1e-6, 10.0, 30.0, 100.0):
        res = solve_contact(surface, half, mean_pressure=1e3, interaction=ElectrostaticInteraction(STACK, voltage))
        assert res.converged
        counts[voltage] = (res.unstable_steps, res.iterations)
    assert counts[1e-6][0] == counts[10.0][0] == 0
    assert 0 < counts[30.0][0] < counts[30.0][1]
    assert counts[100.0][0] > 0
    assert solve_contact(surface, half, mean_pressure=1e3).unstable_steps == 0          # the hard wall


def test_step_curvature_is_the_energy_second_difference():
    # a snap-in step skips the model's K⁻¹d and judges Π's curvature along the step taken from its exact Δp_el
    # (gap_solver._step_curvature); it must be Π's second derivative along that step. The central second
    # difference over Δg ~ 2.5 nm at gaps ≥ 0.2 µm differs by the law's fourth-order term: measured 8.3e-5,
    # 1.3e-3 at 10 nm, falling 4× per halving of Δg.
    from roughcontact.solvers.projected_cg_gap import _Energy, _evaluate, _step_curvature
    surface, half = rough_patch()
    law = ElectrostaticInteraction(STACK, 100.0)
    h = surface.heights.reshape(-1)
    n, window = h.size, np.ones(h.size, np.bool_)
    energy = _Energy(h, half, 1e3, None)
    rng = np.random.default_rng(3)
    g = 2e-7 + 1e-6 * rng.random(n)
    dg = 2.5e-9 * rng.standard_normal(n)

    def state(gap):
        """Π/A, p_el and k at the gap."""
        pel = energy.elastic_traction(gap, half.empty(), half.empty()).copy()
        traction, stiffness = np.empty(n), np.empty(n)
        sums = _evaluate(law, law.kernel, gap, window, energy.h_f, pel, traction, stiffness)
        return energy.value(*sums, n)[0], pel, stiffness

    value, pel, stiffness = state(g)
    ahead, behind = state(g + dg), state(g - dg)
    curvature, total = _step_curvature(g, g + dg, pel, ahead[1], stiffness)
    assert curvature == pytest.approx((ahead[0] - 2 * value + behind[0]) * n, rel=2e-4)
    assert curvature < 0                # at 100 V the attraction out-softens the body along a rough step
    assert total == pytest.approx(dg.sum(), rel=1e-12)


def test_equilibrium_checks_fail_on_an_unconverged_result():
    surface, half = rough_patch()
    res = solve_contact(surface, half, mean_pressure=1e3, interaction=ElectrostaticInteraction(STACK, 30.0),
                        maxiter=2, warn=False)
    assert not res.converged
    # the energy solver's unknown is the gap, so its raw gap stays consistent; what two steps leave wrong is the
    # wall's traction (measured −5.6e4 Pa at 1 kPa load) and the balance on the open gap
    with pytest.raises(AssertionError, match="the wall pulls"):
        check_equilibrium(res, surface, half, tol_traction=1e-6 * 1e3)
    assert check_equilibrium(res, surface, half, tol_traction=np.inf) > 1e-3 * 1e3


def test_equivalent_gap_falls_with_load():
    surface, half = rough_patch()
    law = ElectrostaticInteraction(STACK, 30.0)
    gaps = [solve_contact(surface, half, mean_pressure=p, interaction=law).equivalent_gap for p in (5e2, 1e3, 2e3)]
    assert np.all(np.diff(gaps) < 0)


@pytest.mark.parametrize("body", [{}, {"thickness": 2e-4, "poisson": 0.45},
                                  {"thickness": 2e-4, "poisson": 0.45, "bottom": "frictionless"},
                                  {"thickness": 2e-5, "poisson": 0.45, "substrate_E_star": 5e5,
                                   "substrate_poisson": 0.49}])
@pytest.mark.parametrize("field", ["layered", "parallel_plate"])
def test_load_and_position_control_agree(body, field):
    surface, half = rough_patch(**body)
    law = ElectrostaticInteraction(STACK, 30.0, field=field)
    by_load = solve_contact(surface, half, mean_pressure=1e3, interaction=law, tol=1e-10)
    # started from the load-controlled answer (a non-convex problem has several equilibria; each start finds one)
    by_position = solve_contact(surface, half, penetration=by_load.penetration, interaction=law, tol=1e-10,
                                x0=by_load)
    assert by_load.converged and by_position.converged
    assert by_position.mean_pressure == pytest.approx(1e3, rel=1e-5)
    np.testing.assert_allclose(by_position.gap, by_load.gap, atol=1e-6 * 3e-6)          # 1e-6 of the rms height


@pytest.mark.parametrize("voltage, load, penetration", [
    (30.0, 0.0, None),            # voltage-only contact: no external load
    (2000.0, 1e3, None),          # far beyond full contact
    (30.0, None, -5e-6),          # the flat 5 µm above the highest summit still pulls
])
def test_extremes_converge(voltage, load, penetration):
    surface, half = rough_patch()
    control = {"mean_pressure": load} if load is not None else {"penetration": penetration}
    res = solve_contact(surface, half, interaction=ElectrostaticInteraction(STACK, voltage), **control)
    assert res.converged and np.isfinite(res.pressure).all()
    if load == 0.0:
        assert res.contact_fraction > 0 and res.mean_pressure == 0.0
    if voltage == 2000.0:
        assert res.contact_fraction == 1.0


def test_problem_object_and_saved_result(tmp_path):
    surface, half = rough_patch()
    law = ElectrostaticInteraction(STACK, 30.0)
    res = ContactProblem(surface, half, law).solve(total_force=1e3 * surface.grid.area)
    assert res.control == "total_force" and res.interaction == law
    loaded = ContactResult.load(res.save(tmp_path / "res.npz"))
    assert loaded.interaction == law and loaded.flat_position == res.flat_position
    assert loaded.unstable_steps == res.unstable_steps > 0                  # 30 V snaps regions in on this patch
    np.testing.assert_array_equal(loaded.interaction_traction, res.interaction_traction)
    with pytest.raises(TypeError, match="interaction"):
        ContactProblem(surface, half, "electrostatic")


def free_cap(n=64, length=1e-3, radius=5e-3):
    """A paraboloidal cap on a free-surface (non-periodic) n² window."""
    grid = Grid((n, n), (length, length), periodic=False)
    x = (np.arange(n) - n / 2 + 0.5) * length / n
    return HeightField(grid, -(x[:, None] ** 2 + x[None, :] ** 2) / (2 * radius)), ElasticHalfSpace(grid, E_star=1e6)


def test_free_surface_smooth_solve():
    # the free surface is solved on its zero-padded grid with the padding free: at a vanishing law it gives the
    # free-surface Polonsky–Keer answer, and load and position control meet
    surface, half = free_cap()
    hard = solve_contact(surface, half, total_force=1e-3, tol=1e-10)
    faint = solve_contact(surface, half, total_force=1e-3, interaction=ElectrostaticInteraction(STACK, 1e-6),
                          tol=1e-10)
    assert faint.converged and faint.total_force == pytest.approx(1e-3, rel=1e-12)
    np.testing.assert_array_equal(faint.contact, hard.contact)
    # measured 2.6e-8 of max p and 3e-10 of the penetration (128²); bounds 100× the solvers' tolerance scale
    assert np.max(np.abs(faint.pressure - hard.pressure)) <= 1e-6 * hard.pressure.max()
    assert faint.penetration == pytest.approx(hard.penetration, rel=1e-7)
    law = ElectrostaticInteraction(STACK, 30.0)
    by_load = solve_contact(surface, half, total_force=1e-3, interaction=law, tol=1e-10)
    by_position = solve_contact(surface, half, penetration=by_load.penetration, interaction=law, x0=by_load,
                                tol=1e-10)
    assert by_load.contact_fraction > hard.contact_fraction
    assert by_position.total_force == pytest.approx(1e-3, rel=1e-5)                  # measured 1e-7
    np.testing.assert_allclose(by_position.gap, by_load.gap, atol=1e-9 * np.ptp(surface.heights))
    check_equilibrium_free = half.displacement(by_load.pressure)                     # u = K p on the window
    np.testing.assert_allclose(by_load.displacement - by_load.displacement.mean(),
                               check_equilibrium_free - check_equilibrium_free.mean(),
                               atol=1e-6 * np.ptp(by_load.displacement))


def test_free_surface_sphere_pull_off():
    # an isolated Dugdale sphere (no periodic images), Maugis λ = 0.3: measured +1.3 % at 64², +0.52 % at 128²
    from roughcontact.reference import maugis_cohesive_stress, maugis_dugdale_pull_off
    from roughcontact.solvers import pull_off

    n, window, radius, E_star, work = 64, 0.8, 1.0, 1.0, 1e-3
    grid = Grid((n, n), (window, window), periodic=False)
    x = (np.arange(n) - n / 2 + 0.5) * window / n
    surface = HeightField(grid, -(x[:, None] ** 2 + x[None, :] ** 2) / (2 * radius))
    cohesive_stress = maugis_cohesive_stress(0.3, work, radius, E_star)
    problem = ContactProblem(surface, ElasticHalfSpace(grid, E_star=E_star),
                             MaugisDugdale(work, work / cohesive_stress))
    found = pull_off(problem, problem.solve(mean_pressure=0.0), step=0.1 * np.pi * work * radius / window ** 2,
                     tol=1e-2)
    error = found.force / (np.pi * work * radius) / maugis_dugdale_pull_off(0.3) - 1
    assert 0 < error < 0.02


def test_approach_retract_cycle_hysteresis_and_jumps():
    # α = 0.2: the JKR branch ends at p̄ ≈ 0.55 p*, so the approach jumps to full contact at 0.6 p*; unloading
    # stays in full contact at 0.3 p*, where the approach had a partial contact (hysteresis), and pulling
    # hard enough detaches the profile
    from roughcontact.solvers import load_cycle

    n = 1024
    surface, half = sinusoid(n)
    problem = ContactProblem(surface, half, johnson_law(0.2, np.sqrt(1 / n)))
    path = load_cycle(problem, [0.1, 0.3, 0.5, 0.6, 0.3, 0.0, -2.0], warn=False)
    assert path.converged[:6].all()
    assert (3, "jump to full contact") in path.jumps
    assert path.contact_fraction[1] < 0.6 and path.contact_fraction[4] == 1.0
    assert path.jumps[-1] == (6, "detachment") and path.detached[-1] and not path.converged[-1]
    # the jump crosses an instability (measured 8 concave steps); unloading in full contact has none
    assert path.unstable_steps[3] > 0 and path.unstable_steps[4] == path.unstable_steps[5] == 0


def test_float32_electrostatic_solve():
    # float32's default tolerance is 1e-5 (its energy's round-off stops the line search a decade or so below), and
    # at that tolerance its answer is an equilibrium of float64's problem: float64 started from it stays there.
    # (Not float64's own cold answer: this path crosses 7-8 instabilities and the patch holds several equilibria
    # one contact pixel apart, which the two precisions' round-off picks between; docs/dev/investigations.md.)
    surface, half = rough_patch()
    single = ElasticHalfSpace(surface.grid, E_star=1e6, dtype=np.float32)
    law = ElectrostaticInteraction(STACK, 30.0)
    res = solve_contact(surface, single, mean_pressure=1e3, interaction=law)
    assert res.converged and res.solver.tol == 1e-5 and res.gap.dtype == np.float32
    polished = solve_contact(surface, half, mean_pressure=1e3, interaction=law, tol=1e-8, x0=res)
    assert polished.converged
    np.testing.assert_array_equal(polished.contact, res.contact)
    # tol 1e-5 bounds the displacement error by 1e-5 of the rms height; the mean gap moved 2.0e-11 m (measured)
    assert abs(polished.mean_gap - res.mean_gap) < 1e-5 * np.std(surface.heights)


def test_float32_on_the_layered_skin_at_200_volts():
    # the fingerpad study's patch (ridges and roughness on the 10 MPa layer over 0.1 MPa, 256²) at 2 N and 200 V:
    # float32 reaches tol 1e-6 (it stalled at 1.0e-5 while the line search took float32's round-off of the energy
    # for a rise) with float64's contact set and d_eq to 3e-8 (measured; bound 1e-6, float32's resolution of the
    # gap against its 1 µm scale). The per-pixel law: with the layered field the two precisions cross the snap-in
    # to equilibria whose contact sets differ on 56 of 65536 pixels (docs/guide/interactions.md, "Several equilibria")
    from roughcontact.study.apparent import apparent_contact
    from roughcontact.study.patch import patch_body, patch_surface
    from roughcontact.study.scene import load_scene
    results = {}
    for dtype in ("float64", "float32"):
        scene = load_scene(text=f'[presets.standard]\ngrid = 256\ndtype = "{dtype}"\n', preset="standard")
        _, (pressure,) = apparent_contact(scene.fingerpad, 2.0, 1)
        results[dtype] = solve_contact(patch_surface(scene, 0), patch_body(scene), mean_pressure=pressure, tol=1e-6,
                                       interaction=ElectrostaticInteraction(scene.screen.stack(), 200.0,
                                                                            field="parallel_plate"))
    double, single = results["float64"], results["float32"]
    assert single.converged and single.gap.dtype == np.float32 and single.residuals[-1] <= 1e-6
    np.testing.assert_array_equal(single.contact, double.contact)
    assert single.equivalent_gap == pytest.approx(double.equivalent_gap, rel=1e-6)


def test_paths_save_and_load_with_their_results(tmp_path):
    # a LoadCycle keeps its ContactResults and a PullOff its last attached equilibrium: both round-trip whole
    from roughcontact.solvers import LoadCycle, PullOff, load_cycle, pull_off

    n = 256
    surface, half = sinusoid(n)
    problem = ContactProblem(surface, half, johnson_law(0.2, 0.05))
    path = load_cycle(problem, [0.1, 0.3], keep_results=True)
    loaded = LoadCycle.load(path.save(tmp_path / "path.npz"))
    assert loaded.jumps == path.jumps and isinstance(loaded.results[1], ContactResult)
    np.testing.assert_array_equal(loaded.results[1].gap, path.results[1].gap)
    np.testing.assert_array_equal(loaded.contact_fraction, path.contact_fraction)
    np.testing.assert_array_equal(loaded.unstable_steps, path.unstable_steps)
    assert loaded.results[1].unstable_steps == path.results[1].unstable_steps
    found = pull_off(problem, path.results[0], step=0.05, tol=0.1)
    again = PullOff.load(found.save(tmp_path / "pull_off.npz"))
    assert again.mean_pressure == found.mean_pressure and again.bracket == found.bracket
    assert again.last_attached.interaction == found.last_attached.interaction
    np.testing.assert_array_equal(again.last_attached.pressure, found.last_attached.pressure)
    assert not again.last_attached.pressure.flags.writeable
