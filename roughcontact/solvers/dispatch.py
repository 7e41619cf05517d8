"""The contact methods: the registry :data:`METHODS` — Polonsky–Keer's constrained conjugate gradients for the hard
wall (:mod:`.polonsky_keer`), the minimum of the total energy over the gap for a smooth law with the wall
(:mod:`.projected_cg_gap`), the deferred correction around it for the time-averaged attraction of an AC drive
(:mod:`.deferred_correction`) — and :func:`method_and_options`, which picks the method that solves a law and the
options it takes. Each method's ``solve(problem, control, **options)`` takes a checked
:class:`~roughcontact.solvers.problem.ContactProblem` and :class:`~roughcontact.solvers.inputs.Control`."""
from __future__ import annotations

import warnings
from dataclasses import dataclass
from typing import Callable

from surfaces.validation import check_bool, check_choice

from ..interactions import Interaction
from .deferred_correction import METHOD as DEFERRED_CORRECTION
from .deferred_correction import driven, solve_driven
from .polonsky_keer import COLD_STARTS
from .polonsky_keer import METHOD as POLONSKY_KEER
from .projected_cg_gap import METHOD as PROJECTED_CG_GAP
from .projected_cg_gap import solve_hard_wall_handing_over, solve_smooth


class OptionWarning(UserWarning):
    """An option was given that the method solving the problem does not take (it is ignored)."""


@dataclass(frozen=True)
class Method:
    """A contact method: its ``name``, whether it solves the ``smooth`` laws (else the hard wall and laws that
    vanish), its ``solve(problem, control, **options)`` function, the ``options`` it takes beyond the
    :class:`~roughcontact.solvers.inputs.Control`, and whether a smooth method also solves the ``hard_wall`` when
    chosen by name."""

    name: str
    smooth: bool
    solve: Callable
    options: tuple = ()
    hard_wall: bool = False


#: The contact methods by name (Polonsky–Keer's solve continued on the gap where it is slow:
#: :func:`~roughcontact.solvers.projected_cg_gap.solve_hard_wall_handing_over`).
METHODS = {POLONSKY_KEER: Method(POLONSKY_KEER, False, solve_hard_wall_handing_over, ("cold_start", "preconditioned")),
           PROJECTED_CG_GAP: Method(PROJECTED_CG_GAP, True, solve_smooth, hard_wall=True),
           DEFERRED_CORRECTION: Method(DEFERRED_CORRECTION, True, solve_driven)}


def method_for(interaction: Interaction, method=None) -> Method:
    """The method that solves ``interaction``: ``method`` by name (checked against the law), or by default the
    one for the law (Polonsky–Keer for the hard wall and a law that vanishes, e.g. at 0 V; the energy method
    for a smooth law, and for the hard wall by name; the deferred correction for an AC drive through a leaky
    stratum corneum)."""
    smooth = interaction.smooth and not interaction.vanishes
    needed = METHODS[(DEFERRED_CORRECTION if driven(interaction) else PROJECTED_CG_GAP) if smooth else POLONSKY_KEER]
    if method is None:
        return needed
    chosen = METHODS[check_choice("method", method, tuple(METHODS))]
    if chosen is not needed and not (chosen.hard_wall and not smooth):
        solves = {POLONSKY_KEER: "the hard wall (or a law that vanishes)",
                  PROJECTED_CG_GAP: "a smooth law that attracts, or the hard wall",
                  DEFERRED_CORRECTION: "an AC drive through a leaky stratum corneum"}[chosen.name]
        raise ValueError(f"method = {method!r} solves {solves}; the interaction {type(interaction).__name__} needs "
                         f"method = {needed.name!r}")
    return chosen


def method_and_options(interaction: Interaction, method=None, cold_start=None, preconditioned=None) -> tuple:
    """The :class:`Method` that solves the checked ``interaction`` (:func:`method_for`) and the options it takes of
    those given (not None). An option that it does not take is checked all the same (a wrong value raises) and
    ignored with an :class:`OptionWarning`, as scipy.optimize does."""
    chosen = method_for(interaction, method)
    given = {}
    if cold_start is not None:
        given["cold_start"] = check_choice("cold_start", cold_start, COLD_STARTS)
    if preconditioned is not None:
        given["preconditioned"] = check_bool("preconditioned", preconditioned)
    for name, value in given.items():
        if name not in chosen.options:
            warnings.warn(f"{name} = {value!r} is not an option of method {chosen.name!r} (interaction "
                          f"{type(interaction).__name__}) and is ignored; it takes tol, maxiter, x0, callback, warn"
                          + "".join(f", {option}" for option in chosen.options), OptionWarning, stacklevel=3)
    return chosen, {name: value for name, value in given.items() if name in chosen.options}
