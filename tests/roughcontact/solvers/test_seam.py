"""The solver seam: method registry and per-method options, the typed SolverReport, and the audit's misbehaving
calls (tension, user laws, float32, 0 V, pull_off's arguments)."""
import dataclasses
import warnings

import numpy as np
import pytest

from roughcontact import ContactProblem, ElasticHalfSpace, ElectrostaticInteraction, ExponentialAdhesion, \
    MaugisDugdale, solve_contact
from roughcontact.electrostatics import DielectricStack
from roughcontact.interactions import HardWall, Interaction
from roughcontact.io import ConvergenceWarning
from roughcontact.solvers import ContactResult, SolverReport, pull_off
from roughcontact.solvers.dispatch import METHODS, OptionWarning
from surfaces import Grid, HeightField

from contact_checks import check_equilibrium

STACK = DielectricStack()


def sinusoid(n=64):
    """A 1-D cosine wave, wavelength 1 m, amplitude 1 m, on E* = 1/π (the adhesive path tests' problem)."""
    grid = Grid((n, 1), (1.0, 1.0 / n), periodic=True)
    x = (np.arange(n) + 0.5) / n - 0.5
    return HeightField(grid, -(1 - np.cos(2 * np.pi * x))[:, None]), ElasticHalfSpace(grid, E_star=1 / np.pi)


def flat(n=8):
    grid = Grid((n, n), (1e-3, 1e-3))
    return HeightField(grid, np.zeros((n, n))), ElasticHalfSpace(grid, E_star=1e6)


# -- the registry and its options --------------------------------------------------------------------------------
def test_an_option_the_method_does_not_take_raises():
    surface, body = sinusoid()
    law = ExponentialAdhesion(0.05, 0.05)
    # a wrong value is an error whatever the method; a right one that the method does not take is ignored with a
    # warning (scipy-style): the solve is the one without it
    with pytest.raises(ValueError, match="cold_start = 'bogus' is not valid"):
        solve_contact(surface, body, mean_pressure=0.1, interaction=law, cold_start="bogus")
    with pytest.raises(TypeError, match="preconditioned must be True or False"):
        solve_contact(surface, body, mean_pressure=0.1, interaction=law, preconditioned="yes please")
    with pytest.warns(OptionWarning, match="cold_start = 'pk' is not an option of method 'projected-cg-gap'"):
        ignored = solve_contact(surface, body, mean_pressure=0.1, interaction=law, cold_start="pk")
    np.testing.assert_array_equal(ignored.gap, solve_contact(surface, body, mean_pressure=0.1, interaction=law).gap)
    with pytest.raises(ValueError, match="method = 'polonsky-keer' solves the hard wall"):
        solve_contact(surface, body, mean_pressure=0.1, interaction=law, method="polonsky-keer")
    with pytest.raises(ValueError, match="method = 'projected-cg-gap' solves a smooth law"):
        solve_contact(surface, body, mean_pressure=0.1, method="projected-cg-gap")
    with pytest.raises(ValueError, match="method"):
        solve_contact(surface, body, mean_pressure=0.1, method="newton")
    # a 0 V law is the hard wall: Polonsky–Keer's options apply
    zero = solve_contact(surface, body, mean_pressure=0.1, interaction=ElectrostaticInteraction(STACK, 0.0),
                         cold_start="pk", preconditioned=False)
    assert zero.solver.method == "polonsky-keer" and zero.solver.details["preconditioned"] is False
    assert set(METHODS) == {"polonsky-keer", "projected-cg-gap", "deferred-correction"}


def test_the_report_is_typed():
    surface, body = sinusoid()
    hard = solve_contact(surface, body, mean_pressure=0.5)
    smooth = solve_contact(surface, body, mean_pressure=0.1, interaction=ExponentialAdhesion(0.05, 0.05))
    for result, method in ((hard, "polonsky-keer"), (smooth, "projected-cg-gap")):
        report = result.solver
        assert isinstance(report, SolverReport) and report.method == method and result.grid == body.grid
        assert (result.converged, result.iterations, result.message) == (report.converged, report.iterations,
                                                                          report.message)
        assert report.fft_pairs > 0 and report.tol == 1e-8 and report.residuals[-1] <= report.tol
    assert not smooth.detached and len(smooth.solver.details["energy_history"]) == smooth.iterations + 1
    # the result is built from its declared fields only: the report is not a set of loose fields
    with pytest.raises(TypeError, match="converged"):
        ContactResult(**{name: getattr(hard, name) for name in ("pressure", "displacement", "gap", "contact",
                                                                "contact_fraction", "mean_pressure", "mean_gap",
                                                                "penetration", "elastic_energy", "grid")},
                      solver=hard.solver, converged=False)


# -- tension: detached (and why) or an equilibrium -----------------------------------------------------------------
@pytest.mark.parametrize("law", [ExponentialAdhesion(0.2 ** 2 * np.pi / 2, 0.05),
                                 MaugisDugdale(0.2 ** 2 * np.pi / 2, 0.05)], ids=["exponential", "dugdale"])
def test_a_cold_tensile_solve_follows_the_retract_branch(law):
    surface, body = sinusoid()
    problem = ContactProblem(surface, body, law)
    found = pull_off(problem, problem.solve(mean_pressure=0.1), step=0.02, tol=0.05)
    half = found.mean_pressure / 2
    cold = problem.solve(mean_pressure=half)
    assert cold.converged and not cold.detached and cold.solver.start == "retract from 0 Pa"
    assert cold.mean_pressure == pytest.approx(half, rel=1e-12) and cold.contact.any()
    # an equilibrium, checked from the raw fields (u = K p, raw gap, complementarity): on the open gap the
    # traction balances the law to 5e-8 Pa (exponential) and 1e-10 Pa (Dugdale) at |load| ~ 0.03 Pa, measured;
    # two steps from the zero-load state leave 0.05 and 2.4e-4 Pa, so the bound 1e-5 |load| separates them
    imbalance = check_equilibrium(cold, surface, body, tol_traction=1e-6 * abs(half))
    assert imbalance <= 1e-5 * abs(half)
    unconverged = problem.solve(mean_pressure=half, x0=problem.solve(mean_pressure=0.0), maxiter=2, warn=False)
    assert check_equilibrium(unconverged, surface, body, tol_traction=np.inf) > 1e-5 * abs(half)
    # beyond this branch's pull-off: detached, and the message brackets it
    beyond = problem.solve(mean_pressure=1.5 * found.bracket[1], warn=False)
    assert beyond.detached and not beyond.converged and "beyond its pull-off" in beyond.message


@pytest.mark.parametrize("law", [ElectrostaticInteraction(STACK, 100.0, field="parallel_plate"),
                                 ExponentialAdhesion(1e-3, 2e-7), MaugisDugdale(1e-3, 2e-7)],
                         ids=["electrostatic", "exponential", "dugdale"])
def test_tension_on_a_flat_detaches_beyond_the_strength_of_the_law(law):
    surface, body = flat()
    strength = law.strength
    assert strength == pytest.approx(float(-law.traction(np.zeros(1))[0]), rel=1e-12)   # the attraction at contact
    # within the strength: the flat stays in full contact, mean traction = the load (exact on a flat)
    held = solve_contact(surface, body, mean_pressure=-0.5 * strength, interaction=law)
    assert held.converged and not held.detached and held.contact_fraction == 1.0
    assert held.mean_pressure == pytest.approx(-0.5 * strength, rel=1e-12)
    with pytest.warns(ConvergenceWarning, match="strongest attraction"):
        beyond = solve_contact(surface, body, mean_pressure=-1.01 * strength, interaction=law)
    assert beyond.detached and not beyond.converged and beyond.iterations == 0


def test_load_cycle_and_pull_off_see_the_detachment_on_a_flat():
    from roughcontact.solvers import load_cycle
    surface, body = flat()
    law = ExponentialAdhesion(1e-3, 2e-7)                   # strength 5 kPa
    problem = ContactProblem(surface, body, law)
    path = load_cycle(problem, [1e3, -2e3, -4e3, -6e3, -8e3], warn=False)
    assert path.jumps == ((3, "detachment"),) and path.detached.tolist() == [False, False, False, True]
    found = pull_off(problem, problem.solve(mean_pressure=0.0), step=1e3, tol=1e-3)
    assert found.bracket[0] <= -law.strength * (1 - 1e-3) and found.bracket[1] < -law.strength


# -- user laws -----------------------------------------------------------------------------------------------------
@dataclasses.dataclass(frozen=True)
class Harmonic(Interaction):
    """V = −w (1 − g/ρ)² for g < ρ: a user law (length ρ, no strength given)."""
    work: float = 0.05
    length: float = 0.05

    def energy(self, gap):
        return -self.work * np.maximum(1 - np.asarray(gap) / self.length, 0) ** 2

    def traction(self, gap):
        return -2 * self.work / self.length * np.maximum(1 - np.asarray(gap) / self.length, 0)

    def stiffness(self, gap):
        return np.where(np.asarray(gap) < self.length, 2 * self.work / self.length ** 2, 0.0)


@dataclasses.dataclass(frozen=True)
class NoLength(Interaction):
    def energy(self, gap):
        return np.zeros_like(gap)

    traction = stiffness = energy


@dataclasses.dataclass(frozen=True)
class NaNTraction(Harmonic):
    def traction(self, gap):
        return np.where(np.asarray(gap) > 0.5, np.nan, super().traction(gap))


def test_user_laws_are_checked_up_front():
    surface, body = sinusoid()
    with pytest.raises(ValueError, match="NoLength needs length"):
        solve_contact(surface, body, mean_pressure=0.1, interaction=NoLength())
    with pytest.raises(ValueError, match="NaNTraction returned a non-finite"):
        solve_contact(surface, body, mean_pressure=0.1, interaction=NaNTraction())
    res = solve_contact(surface, body, mean_pressure=0.1, interaction=Harmonic())
    assert res.converged and res.solver.method == "projected-cg-gap"


def test_built_in_laws_check_gaps_alike():
    for law in (HardWall(), ElectrostaticInteraction(STACK, 100.0), ExponentialAdhesion(1e-3, 1e-6),
                MaugisDugdale(1e-3, 1e-6)):
        assert law.energy([-1e-9])[0] == np.inf           # the wall: a penetrating gap costs infinite energy
        for method in (law.energy, law.traction, law.stiffness):
            with pytest.raises(ValueError, match="gap must be finite"):
                method([np.nan])
        for method in (law.traction, law.stiffness):
            with pytest.raises(ValueError, match="gap must be >= 0"):
                method([-1e-9])


# -- float32, 0 V, pull_off's arguments ----------------------------------------------------------------------------
def test_float32_warns_of_a_tolerance_below_its_round_off_up_front():
    surface, _ = sinusoid()
    single = ElasticHalfSpace(surface.grid, E_star=1 / np.pi, dtype=np.float32)
    for law in (None, ExponentialAdhesion(0.05, 0.05)):
        with pytest.warns(ConvergenceWarning, match="below float32's round-off floor 4.8e-07"):
            solve_contact(surface, single, mean_pressure=0.1, interaction=law, tol=1e-9, maxiter=5, warn=False)
    with warnings.catch_warnings():
        warnings.simplefilter("error")                     # at the default tolerance: no warning
        assert solve_contact(surface, single, mean_pressure=0.1, interaction=ExponentialAdhesion(0.05, 0.05)).converged


def test_a_zero_volt_law_takes_any_load_like_its_neighbours():
    surface, body = sinusoid()
    zero = ElectrostaticInteraction(STACK, 0.0, field="parallel_plate")
    touching = solve_contact(surface, body, mean_pressure=0.0, interaction=zero)
    assert touching.converged and touching.contact_fraction == 0 and touching.penetration == 0.0
    assert np.max(touching.pressure) == 0 and touching.gap.min() == 0.0
    with pytest.warns(ConvergenceWarning, match="exerts no traction"):
        pulled = solve_contact(surface, body, mean_pressure=-0.1, interaction=zero)
    assert pulled.detached and not pulled.converged
    with pytest.raises(ValueError, match="mean_pressure"):
        solve_contact(surface, body, mean_pressure=0.0)    # the hard wall itself still needs a compressive load


def test_pull_off_names_its_bad_arguments():
    surface, body = sinusoid()
    adhesive = ContactProblem(surface, body, ExponentialAdhesion(0.05, 0.05))
    start = adhesive.solve(mean_pressure=0.1)
    for steps in (0, 2.5):
        with pytest.raises((ValueError, TypeError), match="max_steps"):
            pull_off(adhesive, start, step=0.05, max_steps=steps)
    hard = ContactProblem(surface, body)
    with pytest.raises(ValueError, match="pull_off needs an attractive interaction law"):
        pull_off(hard, hard.solve(mean_pressure=0.1), step=0.05)
    with pytest.raises(ValueError, match="tol"):
        pull_off(adhesive, start, step=0.05, tol=1.5)


def test_a_cold_tensile_solve_on_a_rough_patch_stays_attached():
    # the audit's case: on a rough patch a cold solve at half the pull-off tension went straight to "detached"
    # (descent from the undeformed surface separated) while the retract path from zero load stays attached
    from surfaces import self_affine
    grid = Grid((32, 32), (1e-3, 1e-3))
    surface = self_affine(grid, hurst=0.8, rms_height=1e-6, short_cutoff=2.5e-4, rng=1)
    problem = ContactProblem(surface, ElasticHalfSpace(grid, E_star=1e6), ExponentialAdhesion(2e-3, 2e-7))
    found = pull_off(problem, problem.solve(mean_pressure=10.0), step=1e3, tol=0.1)
    cold = problem.solve(mean_pressure=found.mean_pressure / 2)
    assert cold.converged and not cold.detached and cold.contact_fraction > 0.1
    assert cold.mean_pressure == pytest.approx(found.mean_pressure / 2, rel=1e-12)
    # (the bound as in test_a_cold_tensile_solve_follows_the_retract_branch)
    load = abs(cold.mean_pressure)
    assert check_equilibrium(cold, surface, problem.body, tol_traction=1e-6 * load) <= 1e-5 * load


def test_a_pickled_result_comes_back_read_only():
    import pickle
    surface, body = sinusoid()
    result = solve_contact(surface, body, mean_pressure=0.1, interaction=ExponentialAdhesion(0.05, 0.05))
    clone = pickle.loads(pickle.dumps(result))
    assert np.array_equal(clone.gap, result.gap) and clone.solver.iterations == result.iterations
    for array in (clone.pressure, clone.gap, clone.contact, clone.solver.residuals):
        with pytest.raises(ValueError, match="read-only"):
            array[0] = 0
