"""What to solve, checked once: :class:`ContactProblem` (surface, body, interaction law) and its
:meth:`~ContactProblem.control` (what is fixed, tolerance, iteration limit, warm start, callback); its
:meth:`~ContactProblem.solve` hands both to the method that solves the law (:data:`~.dispatch.METHODS`), which
takes them as they are. :func:`solve_contact` and :func:`load_path` are the functional forms, with the same
keywords, and :func:`voltage_path` sweeps an electrostatic law's voltage."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from surfaces import HeightField

from ..body import ElasticHalfSpace
from ..interactions import HardWall, Interaction
from .dispatch import method_and_options
from .inputs import Control, body_heights, check_body, checked_control, checked_interaction, checked_surface
from .result import ContactResult
from .sweep import load_steps, voltage_steps


@dataclass(frozen=True)
class ContactProblem:
    """What to solve: the topography ``surface`` h [m] (a HeightField on the body's grid, or an array of heights
    of its shape), the elastic ``body`` and the ``interaction`` law, checked once on construction; ``heights`` is h
    as the solvers take it (C-contiguous in the body's dtype, read-only).

    ``problem.solve(mean_pressure=…)`` (or ``total_force=`` [N], ``penetration=`` [m]; the other keywords as in
    :func:`solve_contact`) returns a :class:`ContactResult`; ``problem.load_path(loads)`` sweeps the load
    (:func:`load_path`), ``problem.voltage_path(voltages, mean_pressure=…)`` the voltage (:func:`voltage_path`).
    A sweep or a load cycle checks the problem once and each solve's control once.
    """

    surface: HeightField
    body: ElasticHalfSpace
    interaction: Interaction = HardWall()
    heights: np.ndarray = field(init=False, repr=False, compare=False)

    def __post_init__(self):
        check_body(self.body)
        object.__setattr__(self, "surface", checked_surface(self.surface, self.body))
        object.__setattr__(self, "interaction", checked_interaction(self.interaction))
        object.__setattr__(self, "heights", body_heights(self.surface.heights, self.body))

    def __reduce__(self):
        """Pickles by its parts (rebuilt and checked on loading, the heights read-only again)."""
        return type(self), (self.surface, self.body, self.interaction)

    def control(self, *, mean_pressure=None, total_force=None, penetration=None, tol=None, maxiter=10000, x0=None,
                callback=None, warn=True) -> Control:
        """The checked :class:`~roughcontact.solvers.inputs.Control` of a solve of this problem (keywords as in
        :func:`solve_contact`)."""
        return checked_control(self.body, self.interaction, mean_pressure=mean_pressure, total_force=total_force,
                               penetration=penetration, tol=tol, maxiter=maxiter, x0=x0, callback=callback,
                               warn=warn)

    def solve(self, *, mean_pressure=None, total_force=None, penetration=None, method=None, tol=None,
              maxiter=10000, x0=None, callback=None, warn=True, cold_start=None,
              preconditioned=None) -> ContactResult:
        """Solve at one control (:func:`solve_contact`'s keywords, without surface, body and interaction)."""
        chosen, options = method_and_options(self.interaction, method, cold_start, preconditioned)
        control = self.control(mean_pressure=mean_pressure, total_force=total_force, penetration=penetration,
                               tol=tol, maxiter=maxiter, x0=x0, callback=callback, warn=warn)
        return chosen.solve(self, control, **options)

    def load_path(self, mean_pressures, warm_start=True, start=None, progress=False, predictor="secant",
                  **solver_options):
        """Yield the results at each of ``mean_pressures`` [Pa] in order (:func:`load_path`)."""
        return load_steps(self, mean_pressures, warm_start, start, progress, predictor, solver_options)

    def voltage_path(self, voltages, warm_start=True, start=None, progress=False, **solver_options):
        """Yield the results with the law at each of ``voltages`` [V] in order (:func:`voltage_path`)."""
        return voltage_steps(self, voltages, warm_start, start, progress, solver_options)

    def coarsened(self) -> ContactProblem:
        """The same problem on the grid coarsened 2 × 2 (each coarse pixel the mean height of the four it covers;
        :meth:`~roughcontact.body.ElasticHalfSpace.coarsened`): Polonsky–Keer's nested start. Made from the
        checked problem, so not checked again."""
        return self._checked(self.surface.coarsened(2), self.body.coarsened(), self.interaction)

    def with_heights(self, heights, interaction: Interaction | None = None) -> ContactProblem:
        """The problem of the same body with the heights ``heights`` [m] (an array on the grid, a HeightField's
        checks) and the law ``interaction`` (this one by default), which are a solve's own: the hard-wall start
        of a smooth law, the deferred correction's surrogate with its shifted heights. Body and law are not
        checked again."""
        surface = self.surface if heights is self.surface.heights else HeightField(self.body.grid, heights)
        return self._checked(surface, self.body, self.interaction if interaction is None else interaction,
                             heights)

    @classmethod
    def _checked(cls, surface, body, interaction, heights=None) -> ContactProblem:
        """A problem of parts that are checked already (no check again)."""
        problem = object.__new__(cls)
        for name, value in (("surface", surface), ("body", body), ("interaction", interaction),
                            ("heights", body_heights(surface.heights if heights is None else heights, body))):
            object.__setattr__(problem, name, value)
        return problem


def solve_contact(surface, body: ElasticHalfSpace, *, mean_pressure=None, total_force=None,
                  penetration=None, interaction: Interaction | None = None, method=None, tol=None, maxiter=10000,
                  x0=None, callback=None, warn=True, cold_start=None, preconditioned=None) -> ContactResult:
    """Press ``surface`` onto a rigid flat and solve for pressure, displacement and gap.

    Parameters
    ----------
    surface : surfaces.HeightField or array
        Topography h [m] on ``body.grid`` (peaks positive, towards the flat).
    body : ElasticHalfSpace
        The elastic body (kernel, FFT backend, dtype).
    mean_pressure, total_force, penetration
        Exactly one: the external load <p> [Pa] or F = <p> Lx Ly [N] (> 0 for the hard wall; any sign with a
        smooth law, where a tensile load with no equilibrium is reported as ``detached``, the message saying
        why), or the penetration δ = max(h) − s [m] (displacement control; any sign).
    interaction : Interaction, optional
        Surface interaction law (:mod:`roughcontact.interactions`): :class:`~roughcontact.interactions.HardWall`
        (the default) or a smooth law acting with the wall. A law that vanishes (0 V) is solved as the hard wall.
    method : str, optional
        A name of :data:`~.dispatch.METHODS`: ``"polonsky-keer"`` (:mod:`.polonsky_keer`; the hard wall) or
        ``"projected-cg-gap"`` (:mod:`.projected_cg_gap`; smooth laws) or ``"deferred-correction"``
        (:mod:`.deferred_correction`; an ``ElectrostaticInteraction`` with a ``frequency``). By default the one
        that solves ``interaction``; a method that does not solve it raises ``ValueError``.
    tol : float, optional
        Relative tolerance of the method's convergence criterion (its module docstring), in (0, 1); by default
        :func:`~.inputs.default_tolerance` of the body's dtype (1e-8 in float64, 1e-6 in float32). In float32 a
        tolerance below :data:`~.inputs.FLOAT32_TOL_FLOOR` is warned of up front (a ConvergenceWarning):
        round-off may stop the residual above it.
    maxiter : int
        Maximum number of steps.
    x0 : ContactResult or array, optional
        Warm start: a previous result (the smooth method starts from its gap; Polonsky–Keer from its pressure,
        rescaled to the requested load), or for Polonsky–Keer a pressure field [Pa]; one that is zero
        everywhere carries no information and gets the cold start.
    callback : callable, optional
        ``callback(SolverState)`` after every step; raising ``StopIteration`` halts (``converged=False``).
    warn : bool
        Emit a :class:`~roughcontact.io.ConvergenceWarning` when not converged.
    cold_start : {"nested", "pk"}, Polonsky–Keer only
        Initial guess without ``x0``. ``"nested"`` (default): the pressure of the same problem on the grid
        coarsened 2 × 2, recursively (``docs/guide/solver.md``); grids that do not halve down to 2 × ``NESTED_MIN``
        pixels fall back to ``"pk"``: Polonsky and Keer's uniform p̄ (load control) or the rigid overlap
        (displacement control).
    preconditioned : bool, Polonsky–Keer only
        Precondition the conjugate gradients with the inverse kernel K⁻¹: one more FFT pair per step, fewer steps
        (``docs/guide/solver.md``). Default: True on 2-D grids, False on 1-D profiles (where it saves no steps).

    Notes
    -----
    ``solve_contact(surface, body, interaction=law, **keywords)`` is
    ``ContactProblem(surface, body, law).solve(**keywords)``: the problem and the control are checked once, and
    the method takes them as they are. An option that the method does not take (``cold_start`` or
    ``preconditioned`` with a smooth law) is checked all the same (a wrong value raises) and ignored with an
    :class:`~.dispatch.OptionWarning`, as scipy.optimize does.
    """
    problem = ContactProblem(surface, body, interaction)
    chosen, options = method_and_options(problem.interaction, method, cold_start, preconditioned)
    control = problem.control(mean_pressure=mean_pressure, total_force=total_force, penetration=penetration,
                              tol=tol, maxiter=maxiter, x0=x0, callback=callback, warn=warn)
    return chosen.solve(problem, control, **options)


def load_path(surface, body: ElasticHalfSpace, mean_pressures, warm_start=True, start=None, progress=False,
              predictor="secant", *, interaction: Interaction | None = None, **solver_options):
    """Yield :func:`solve_contact` results for each of ``mean_pressures`` [Pa] in order:
    ``ContactProblem(surface, body, interaction).load_path(mean_pressures, …)``.

    With ``warm_start`` each solve starts from a prediction of its pressure field, which the solver rescales
    to the new load: ``predictor="secant"`` (default) extrapolates linearly in load from the two previous
    results (exact where p is linear in load, e.g. in full contact; where the last load was solved on the gap,
    their gaps, and the solve continues on the gap), ``"previous"`` takes the last field as it is; the first warm
    step has only one result and takes it (a smooth law's solve starts from the last gap).
    ``start`` warm-starts the first step, so a sweep resumes where it stopped: a ``ContactResult`` (e.g. the last
    one saved by an interrupted sweep) or the last two in order, with which the secant predictor continues
    exactly as if uninterrupted. ``progress`` shows a tqdm bar with the contact fraction and iterations of the
    last step. ``solver_options`` go to :func:`solve_contact`. (docs/guide/solver.md, "Warm start", measures the
    predictors and lists the variants that did not shorten warm solves.)
    """
    return ContactProblem(surface, body, interaction).load_path(mean_pressures, warm_start, start, progress,
                                                                predictor, **solver_options)


def voltage_path(surface, body: ElasticHalfSpace, voltages, warm_start=True, start=None, progress=False, *,
                 interaction: Interaction, **solver_options):
    """Yield :func:`solve_contact` results with the electrostatic law ``interaction`` (an
    :class:`~roughcontact.interactions.ElectrostaticInteraction`) at each of ``voltages`` [V] in order, at the
    control in ``solver_options`` (``mean_pressure=``, ``total_force=`` or ``penetration=``):
    ``ContactProblem(surface, body, interaction).voltage_path(voltages, …)``.

    With ``warm_start`` each solve starts from the last result's gap, so the sweep follows the branch a drive
    ramped through these voltages reaches: ramped down after a ramp up, the contact that snapped in stays where
    the attraction still holds it (the hysteresis of docs/guide/interactions.md, "Several
    equilibria"), and each step costs what its change of voltage asks (on the bench's patch, 256², ten 20 V steps,
    0.67 of the cold solves' FFT pairs; ``studies/bench_interactions.py``). A secant predictor is not offered: it
    carries the path across the instabilities it predicts (docs/dev/roadmap.md). ``start`` (a ContactResult, e.g.
    the last one saved by an interrupted sweep) warm-starts the first step, so a sweep resumes exactly where it
    stopped. ``progress`` shows a tqdm bar with the voltage, contact fraction and iterations of the last step.
    """
    return ContactProblem(surface, body, interaction).voltage_path(voltages, warm_start, start, progress,
                                                                   **solver_options)
