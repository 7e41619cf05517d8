"""The contact solve: :func:`solve_contact` hands a problem to a method of the registry :data:`METHODS` —
Polonsky–Keer's constrained conjugate gradients for the hard wall (:mod:`.polonsky_keer`), the minimum of the
total energy over the gap for a smooth law with the wall (:mod:`.projected_cg_gap`), the deferred correction
around it for the time-averaged attraction of an AC drive (:mod:`.deferred_correction`) — after checking that the
method solves the law and takes every option given."""
from __future__ import annotations

import warnings
from dataclasses import dataclass
from typing import Callable

import numpy as np

from surfaces.validation import check_bool, check_choice, check_real

from ..body import ElasticHalfSpace
from ..interactions import Interaction
from ..io.results import ConvergenceWarning
from .deferred_correction import METHOD as DEFERRED_CORRECTION
from .deferred_correction import driven, solve_driven
from .inputs import _check_body, _checked_interaction, default_tolerance
from .polonsky_keer import COLD_STARTS
from .polonsky_keer import METHOD as POLONSKY_KEER
from .polonsky_keer import solve_hard_wall
from .projected_cg_gap import METHOD as PROJECTED_CG_GAP
from .projected_cg_gap import solve_smooth
from .result import ContactResult

#: Relative tolerance below which a solve in float32 may not converge: its residual is computed from fields
#: resolved to ε32 ≈ 1.2e-7, so round-off may stop it near a few ε32 (a rough patch's Polonsky–Keer solve
#: stalls there; a smooth cosine's energy solve reached 1.2e-9, but not 1e-9, in 3000 steps).
FLOAT32_TOL_FLOOR = 4 * float(np.finfo(np.float32).eps)


class OptionWarning(UserWarning):
    """An option was given that the method solving the problem does not take (it is ignored)."""


@dataclass(frozen=True)
class Method:
    """A contact method: its ``name``, whether it solves the ``smooth`` laws (else the hard wall and laws that
    vanish), its ``solve`` function and the ``options`` it takes beyond the common ones (tol, maxiter, x0,
    callback, warn)."""

    name: str
    smooth: bool
    solve: Callable
    options: tuple = ()


#: The contact methods by name.
METHODS = {POLONSKY_KEER: Method(POLONSKY_KEER, False, solve_hard_wall, ("cold_start", "preconditioned")),
           PROJECTED_CG_GAP: Method(PROJECTED_CG_GAP, True, solve_smooth),
           DEFERRED_CORRECTION: Method(DEFERRED_CORRECTION, True, solve_driven)}


def method_for(interaction: Interaction, method=None) -> Method:
    """The method that solves ``interaction``: ``method`` by name (checked against the law), or by default the
    one for the law (Polonsky–Keer for the hard wall and a law that vanishes, e.g. at 0 V; the energy method
    for a smooth law; the deferred correction for an AC drive through a leaky stratum corneum)."""
    smooth = interaction.smooth and not interaction.vanishes
    needed = METHODS[(DEFERRED_CORRECTION if driven(interaction) else PROJECTED_CG_GAP) if smooth else POLONSKY_KEER]
    if method is None:
        return needed
    chosen = METHODS[check_choice("method", method, tuple(METHODS))]
    if chosen is not needed:
        solves = {POLONSKY_KEER: "the hard wall (or a law that vanishes)",
                  PROJECTED_CG_GAP: "a smooth law that attracts",
                  DEFERRED_CORRECTION: "an AC drive through a leaky stratum corneum"}[chosen.name]
        raise ValueError(f"method = {method!r} solves {solves}; the interaction {type(interaction).__name__} needs "
                         f"method = {needed.name!r}")
    return chosen


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
        Exactly one: the external load <p> [Pa] or F = <p> Lx Ly [N] (≥ 0 for the hard wall; any sign with a
        smooth law, where a tensile load with no equilibrium is reported as ``detached``, the message saying
        why), or the penetration δ = max(h) − s [m] (displacement control; any sign).
    interaction : Interaction, optional
        Surface interaction law (:mod:`roughcontact.interactions`): :class:`~roughcontact.interactions.HardWall`
        (the default) or a smooth law acting with the wall. A law that vanishes (0 V) is solved as the hard wall.
    method : str, optional
        A name of :data:`METHODS`: ``"polonsky-keer"`` (:mod:`.polonsky_keer`; the hard wall) or
        ``"projected-cg-gap"`` (:mod:`.projected_cg_gap`; smooth laws) or ``"deferred-correction"``
        (:mod:`.deferred_correction`; an ``ElectrostaticInteraction`` with a ``frequency``). By default the one
        that solves ``interaction``; a method that does not solve it raises ``ValueError``.
    tol : float, optional
        Relative tolerance of the method's convergence criterion (its module docstring), in (0, 1); by default
        :func:`default_tolerance` of the body's dtype (1e-8 in float64, 1e-6 in float32). In float32 a tolerance
        below :data:`FLOAT32_TOL_FLOOR` is warned of up front (a ConvergenceWarning): round-off may stop the
        residual above it.
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
    An option that the method does not take (``cold_start`` or ``preconditioned`` with a smooth law) is checked
    all the same (a wrong value raises) and ignored with an :class:`OptionWarning`, as scipy.optimize does.
    """
    _check_body(body)
    interaction = _checked_interaction(interaction)
    chosen = method_for(interaction, method)
    given = {name: value for name, value in (("cold_start", cold_start), ("preconditioned", preconditioned))
             if value is not None}
    for name, value in given.items():
        if name not in chosen.options:                     # checked all the same: a wrong value is an error
            check_choice(name, value, COLD_STARTS) if name == "cold_start" else check_bool(name, value)
            warnings.warn(f"{name} = {value!r} is not an option of method {chosen.name!r} (interaction "
                          f"{type(interaction).__name__}) and is ignored; it takes tol, maxiter, x0, callback, warn"
                          + "".join(f", {option}" for option in chosen.options), OptionWarning, stacklevel=2)
    given = {name: value for name, value in given.items() if name in chosen.options}
    tol = default_tolerance(body.dtype, interaction) if tol is None else \
        check_real("tol", tol, low=0.0, high=1.0, low_open=True, high_open=True)
    if body.dtype == np.float32 and tol < FLOAT32_TOL_FLOOR:
        warnings.warn(f"tol = {tol!r} is below float32's round-off floor {FLOAT32_TOL_FLOOR:.2g}: the residual may "
                      f"not get there (the solve may stall or run to maxiter = {maxiter}); use tol >= "
                      f"{FLOAT32_TOL_FLOOR:.2g} or a float64 body", ConvergenceWarning, stacklevel=2)
    return chosen.solve(surface, body, interaction, mean_pressure=mean_pressure, total_force=total_force,
                        penetration=penetration, tol=tol, maxiter=maxiter, x0=x0, callback=callback, warn=warn,
                        **given)
