"""Load paths of an adhesive contact: approach and retract branches, their jumps, and pull-off.

An adhesive contact is non-convex: at one external load there can be several equilibria, and which one a solve
finds depends on where it starts (``docs/guide/interactions.md``). A path solves a sequence of loads, each step
started from the previous equilibrium (quasi-static loading), so an approach followed by a retract gives the
loading and unloading branches. Where the branch being followed ends, the next solve falls onto another one:
that step is a **jump** (into contact, to full contact, out of contact, or a detachment), flagged on the path.
Under load control the most tensile load with an equilibrium on the retract branch is the **pull-off** load,
found by :func:`pull_off` (bracketed along the path, then bisected).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from surfaces.validation import check_integer, check_positive, check_real

from ..io.results import SavableResult
from .problem import ContactProblem
from .result import ContactResult

#: Default jump threshold: a step that changes the contact fraction by more than this is a jump.
JUMP_AREA = 0.02


@dataclass(frozen=True, eq=False)
class LoadCycle(SavableResult):
    """The equilibria of :func:`load_cycle` along a sequence of external loads ``loads`` [Pa] (mean pressures),
    in order.

    Per step: ``contact_fraction``, ``mean_gap`` [m], ``flat_position`` s [m], ``converged``, ``detached``
    (a tensile load beyond pull-off: no equilibrium) and ``unstable_steps`` (the solve's steps along which the
    energy was concave: it crossed an instability, :class:`~roughcontact.solvers.ContactResult`). ``jumps``:
    (step index, kind) for each step that left the branch being followed — "jump into contact" (the contact
    fraction rose by more than ``jump_area``), "jump to full contact", "jump out of contact" (fell by more),
    "detachment". ``results``: the :class:`~roughcontact.solvers.ContactResult` of each step when kept.
    """

    loads: np.ndarray
    contact_fraction: np.ndarray
    mean_gap: np.ndarray
    flat_position: np.ndarray
    converged: np.ndarray
    detached: np.ndarray
    unstable_steps: np.ndarray
    jumps: tuple
    jump_area: float
    results: tuple = field(default=(), repr=False)


def _jump(previous: ContactResult, current: ContactResult, jump_area: float):
    """The kind of jump between two consecutive equilibria, or None."""
    if current.detached:
        return "detachment"
    change = current.contact_fraction - previous.contact_fraction
    if current.contact_fraction == 1.0 and previous.contact_fraction < 1.0 and change > jump_area:
        return "jump to full contact"
    if change > jump_area:
        return "jump into contact"
    if change < -jump_area:
        return "jump out of contact"
    return None


def load_cycle(problem: ContactProblem, loads, x0: ContactResult | None = None, jump_area=JUMP_AREA,
               keep_results=False, progress=False, **solver_options) -> LoadCycle:
    """Solve ``problem`` at each of the external ``loads`` [Pa] in order, each step started from the previous
    equilibrium (the first from ``x0`` or cold), and flag the jumps (module docstring). A detachment ends the
    path (nothing is left to continue from). ``solver_options`` go to ``problem.solve``."""
    if not isinstance(problem, ContactProblem):
        raise TypeError(f"problem must be a ContactProblem, got {type(problem).__name__}")
    loads = np.array([check_real("loads", load) for load in np.ravel(loads)], dtype=float)
    if loads.size == 0:
        raise ValueError("loads is empty; give at least one external load [Pa]")
    jump_area = check_real("jump_area", jump_area, low=0.0, high=1.0, low_open=True)
    from tqdm.auto import tqdm

    results, jumps, previous = [], [], x0
    for index, load in enumerate(tqdm(loads, desc="load cycle", unit="step", disable=not progress)):
        result = problem.solve(mean_pressure=float(load), x0=previous, **solver_options)
        if previous is not None and (kind := _jump(previous, result, jump_area)) is not None:
            jumps.append((index, kind))
        results.append(result)
        if result.detached:
            break
        previous = result
    return LoadCycle(
        loads=loads[:len(results)], contact_fraction=np.array([r.contact_fraction for r in results]),
        mean_gap=np.array([r.mean_gap for r in results]), flat_position=np.array([r.flat_position for r in results]),
        converged=np.array([r.converged for r in results]),
        detached=np.array([r.detached for r in results]),
        unstable_steps=np.array([r.unstable_steps for r in results]), jumps=tuple(jumps),
        jump_area=jump_area, results=tuple(results) if keep_results else ())


@dataclass(frozen=True, eq=False)
class PullOff(SavableResult):
    """Pull-off under load control: ``mean_pressure`` [Pa], the most tensile external load with an equilibrium on
    the retract branch (to ``bracket``: the last attached and the first detached load), ``force`` [N] = that load
    times the area, ``last_attached`` the equilibrium there, ``solves`` the number of solves it took."""

    mean_pressure: float
    force: float
    bracket: tuple
    last_attached: ContactResult
    solves: int


def pull_off(problem: ContactProblem, start: ContactResult, step, tol=1e-3, max_steps=200,
             **solver_options) -> PullOff:
    """Retract from the equilibrium ``start`` by decreasing the external load in steps of ``step`` [Pa] (each
    solve from the last attached equilibrium, at most ``max_steps`` of them) until the contact detaches, then
    bisect between the last attached and the first detached load to ``tol`` of the step. ``problem`` needs a law
    that attracts (the hard wall and a 0 V law separate at zero load: no pull-off to find)."""
    if not isinstance(problem, ContactProblem):
        raise TypeError(f"problem must be a ContactProblem, got {type(problem).__name__}")
    if not problem.interaction.smooth or problem.interaction.vanishes:
        raise ValueError(f"pull_off needs an attractive interaction law; {problem.interaction!r} exerts no "
                         "attraction, so the contact separates at zero load (pull-off force 0)")
    if not isinstance(start, ContactResult) or not start.converged:
        raise ValueError("start must be a converged ContactResult on the branch to retract along")
    step = check_positive("step", step)
    tol = check_real("tol", tol, low=0.0, high=1.0, low_open=True, high_open=True)
    max_steps = check_integer("max_steps", max_steps, low=1)
    attached, solves = start, 0
    detached_load = None
    for _ in range(max_steps):
        load = attached.mean_pressure - step
        result = problem.solve(mean_pressure=load, x0=attached, warn=False, **solver_options)
        solves += 1
        if result.detached:
            detached_load = load
            break
        if not result.converged:
            raise RuntimeError(f"the retract step to {load:.6g} Pa did not converge: {result.message}")
        attached = result
    if detached_load is None:
        raise RuntimeError(f"no detachment within max_steps = {max_steps} steps of step = {step:g} Pa below "
                           f"{start.mean_pressure:g} Pa: raise max_steps or step")
    while attached.mean_pressure - detached_load > tol * step:
        load = 0.5 * (attached.mean_pressure + detached_load)
        result = problem.solve(mean_pressure=load, x0=attached, warn=False, **solver_options)
        solves += 1
        if result.detached or not result.converged:
            detached_load = load
        else:
            attached = result
    area = problem.body.grid.area
    return PullOff(mean_pressure=attached.mean_pressure, force=attached.mean_pressure * area,
                   bracket=(attached.mean_pressure, detached_load), last_attached=attached, solves=solves)


__all__ = ["LoadCycle", "PullOff", "load_cycle", "pull_off", "JUMP_AREA"]
