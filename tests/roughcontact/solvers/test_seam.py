"""The solver seam: method registry and per-method options, the typed SolverReport, the audit's misbehaving
calls (tension, user laws, float32, 0 V, pull_off's arguments), and the inputs checked once (ContactProblem and
its Control; the methods check nothing again)."""
import dataclasses
import math
import pickle
import typing
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
    with pytest.raises(ValueError, match="method = 'deferred-correction' solves an AC drive"):
        solve_contact(surface, body, mean_pressure=0.1, method="deferred-correction")
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
    surface, body = sinusoid()
    result = solve_contact(surface, body, mean_pressure=0.1, interaction=ExponentialAdhesion(0.05, 0.05))
    clone = pickle.loads(pickle.dumps(result))
    assert np.array_equal(clone.gap, result.gap) and clone.solver.iterations == result.iterations
    for array in (clone.pressure, clone.gap, clone.contact, clone.solver.residuals):
        with pytest.raises(ValueError, match="read-only"):
            array[0] = 0


# -- checked once: ContactProblem and its Control; the methods check nothing again ---------------------------------
CHECKS = ("check_body", "checked_surface", "checked_interaction", "checked_control")
#: what a method module may not call: every check of surfaces.validation and of solvers.inputs
CHECK_NAMES = {"check_real", "check_positive", "check_integer", "check_bool", "check_choice", "check_finite_array",
               *CHECKS}


@pytest.fixture
def counted(monkeypatch):
    """Counters on the input checks and on the heights' conversion to the body's dtype, where problem.py (their
    only caller) calls them; ``conversions`` lists (input, output) of each conversion."""
    from roughcontact.solvers import problem
    counts = dict.fromkeys(CHECKS, 0)
    conversions = []

    def counting(name, original):
        def check(*args, **kwargs):
            counts[name] += 1
            return original(*args, **kwargs)
        return check

    for name in CHECKS:
        monkeypatch.setattr(problem, name, counting(name, getattr(problem, name)))
    original = problem.body_heights

    def converting(heights, body):
        converted = original(heights, body)
        conversions.append((heights, converted))
        return converted

    monkeypatch.setattr(problem, "body_heights", converting)
    return counts, conversions


def rough_patch(n, dtype=np.float64):
    from surfaces import self_affine
    grid = Grid((n, n), (1e-3, 1e-3), periodic=True)
    return (self_affine(grid, hurst=0.8, rms_height=3e-6, short_cutoff=8e-3 / n, rng=1),
            ElasticHalfSpace(grid, E_star=1e6, dtype=dtype))


@pytest.mark.parametrize("case", ["nested", "smooth", "ac"])
def test_each_input_is_checked_and_converted_once_per_solve(counted, case):
    counts, conversions = counted
    # float32: converting the heights makes a copy, so a second conversion of the user's heights would show
    surface, body = rough_patch(128 if case == "nested" else 32, np.float32)
    law = {"nested": None, "smooth": ElectrostaticInteraction(STACK, 50.0, field="parallel_plate"),
           "ac": ElectrostaticInteraction(STACK, 30.0, frequency=1e3)}[case]
    result = solve_contact(surface, body, mean_pressure=1e3, interaction=law, warn=False)
    # each path solves more than one problem: the coarse grids, the hard-wall start, the corrections
    assert {"nested": result.solver.details.get("nested_iterations"), "smooth": result.solver.start == "hard wall",
            "ac": result.solver.details.get("corrections", 0) >= 1 and result.solver.start == "hard wall"}[case]
    assert counts == dict.fromkeys(CHECKS, 1)
    mine = [(given, converted) for given, converted in conversions if given is surface.heights]
    assert len(mine) == 1 and mine[0][1].dtype == np.float32
    for given, converted in conversions[1:]:          # later: the converted heights as they are, or other heights
        assert converted is given or not np.shares_memory(given, surface.heights)


def test_a_sweep_checks_its_problem_once_and_each_control_once(counted):
    from roughcontact import load_path
    counts, _ = counted
    surface, body = rough_patch(32)
    results = list(load_path(surface, body, [1e3, 2e3, 4e3]))
    assert len(results) == 3 and all(result.converged for result in results)
    assert counts == {"check_body": 1, "checked_surface": 1, "checked_interaction": 1, "checked_control": 3}


def test_the_methods_call_no_check():
    # structurally: the method modules import no check, so a second check of an input cannot happen there
    from roughcontact.solvers import deferred_correction, polonsky_keer, projected_cg_gap, starts
    for module in (polonsky_keer, projected_cg_gap, deferred_correction, starts):
        assert not CHECK_NAMES & set(vars(module)), module.__name__


def test_the_functional_form_is_the_problem_solved():
    surface, body = rough_patch(32)
    law = ExponentialAdhesion(1e-3, 2e-7)
    for control in ({"mean_pressure": 1e3}, {"total_force": 1e3 * surface.grid.area}, {"penetration": 3e-6}):
        direct = solve_contact(surface, body, interaction=law, **control)
        solved = ContactProblem(surface, body, law).solve(**control)
        np.testing.assert_array_equal(direct.gap, solved.gap)
        assert (direct.control, direct.requested) == (solved.control, solved.requested) == next(iter(control.items()))


def test_the_control_is_checked_and_in_si():
    surface, body = rough_patch(16)
    problem = ContactProblem(surface, body, ExponentialAdhesion(1e-3, 2e-7))
    force = problem.control(total_force=2.0)
    assert (force.kind, force.value, force.mean_pressure, force.penetration) == ("total_force", 2.0, 2e6, None)
    assert force.tol == 1e-8 and force.maxiter == 10000 and force.x0 is None and force.warn is True
    position = problem.control(penetration=-1e-6, tol=1e-3)
    assert (position.mean_pressure, position.penetration, position.tol) == (None, -1e-6, 1e-3)
    moved = position.at(mean_pressure=5.0, warn=False)
    assert (moved.kind, moved.value, moved.mean_pressure, moved.tol, moved.warn) == ("mean_pressure", 5.0, 5.0,
                                                                                      1e-3, False)
    for keywords, error, words in [({}, ValueError, "give exactly one"),
                                   ({"mean_pressure": 1.0, "penetration": 1e-6}, ValueError, "give exactly one"),
                                   ({"mean_pressure": 1.0, "tol": 1.0}, ValueError, "tol"),
                                   ({"mean_pressure": 1.0, "maxiter": -1}, ValueError, "maxiter"),
                                   ({"mean_pressure": 1.0, "callback": 3}, TypeError, "callback must be callable"),
                                   ({"mean_pressure": 1.0, "warn": "no"}, TypeError, "warn must be True or False"),
                                   ({"mean_pressure": 1.0, "x0": np.zeros((16, 16))}, TypeError, "ContactResult")]:
        with pytest.raises(error, match=words):
            problem.control(**keywords)
    with pytest.raises(ValueError, match=r"mean_pressure = -1.0 is out of range; valid range \(0, inf\)"):
        ContactProblem(surface, body).control(mean_pressure=-1.0)
    assert ContactProblem(surface, body).control(mean_pressure=1.0, x0=np.ones((16, 16))).x0.shape == (16, 16)


def test_the_problem_holds_its_heights_in_the_body_dtype_once():
    surface, body = rough_patch(64, np.float32)
    problem = ContactProblem(surface, body)
    assert problem.heights.dtype == np.float32 and not problem.heights.flags.writeable
    np.testing.assert_array_equal(problem.heights, surface.heights.astype(np.float32))
    assert ContactProblem(surface, ElasticHalfSpace(surface.grid, E_star=1e6)).heights is surface.heights  # no copy
    clone = pickle.loads(pickle.dumps(problem))                       # rebuilt from its parts, checked again
    assert not clone.heights.flags.writeable and np.array_equal(clone.heights, problem.heights)
    coarse = problem.coarsened()
    assert coarse.body.grid == surface.grid.coarsened(2) and coarse.interaction == problem.interaction
    np.testing.assert_array_equal(coarse.surface.heights, surface.coarsened(2).heights)
    shifted = problem.with_heights(surface.heights + 1e-6, ExponentialAdhesion(1e-3, 2e-7))
    assert shifted.body is body and shifted.heights.dtype == np.float32
    with pytest.raises(ValueError, match="finite"):                    # new heights get a HeightField's checks
        problem.with_heights(np.full(surface.grid.shape, np.nan))


class Exponential(typing.NamedTuple):
    """A user's kernel: the exponential law's arithmetic (interactions.ExponentialKernel) in the user's class."""
    work: float
    inverse_length: float

    @staticmethod
    def at(gap, kernel):
        e = kernel.work * math.exp(-gap * kernel.inverse_length)
        return -e, -e * kernel.inverse_length, e * kernel.inverse_length ** 2


@dataclasses.dataclass(frozen=True)
class KernelOnly(Interaction):
    """A user's law that only has its kernel: the solve must run on it (its numpy methods raise)."""
    work: float = 1e-3
    length: float = 2e-7

    @property
    def kernel(self):
        return Exponential(self.work, 1.0 / self.length)


def test_a_users_kernel_is_compiled_into_the_solve():
    surface, body = rough_patch(32)
    mine = solve_contact(surface, body, mean_pressure=1e3, interaction=KernelOnly())
    built_in = solve_contact(surface, body, mean_pressure=1e3, interaction=ExponentialAdhesion(1e-3, 2e-7))
    assert mine.converged and mine.iterations == built_in.iterations
    np.testing.assert_array_equal(mine.gap, built_in.gap)                # the same arithmetic, bit for bit
    # numba's disk cache of the pass holds the library's kernel classes only: its index names each class, and a
    # process that cannot import this test module could not read it
    from roughcontact.solvers.projected_cg_gap import _evaluate_law
    assert {signature[0].instance_class.__module__ for signature in _evaluate_law.signatures} <= {
        "roughcontact.interactions"}
    with pytest.raises(TypeError, match="kernel must be None or a NamedTuple of floats"):
        solve_contact(surface, body, mean_pressure=1e3, interaction=KernelOnly(work=1))   # an int parameter
