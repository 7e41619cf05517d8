"""Where a smooth law's solve starts: the warm start ``x0``, else the hard-wall solution at the same control
(Polonsky–Keer, loosely), else the undeformed surface. Shared by the energy method (:mod:`.projected_cg_gap`) and
the deferred correction around it (:mod:`.deferred_correction`), which solves the start once for all its
corrections.

Polonsky–Keer's own nested cold start stays in :mod:`.polonsky_keer`: it is the method solving its own problem on
the coarsened grid (with its options and its record of the coarse iterations), a cascade inside the method rather
than a guess from outside it; here it would also make an import cycle (this module solves the hard wall)."""
from __future__ import annotations

from ..interactions import HardWall
from .inputs import Control
from .polonsky_keer import solve_hard_wall

START_TOL = 1e-2          # tolerance of the hard-wall solve that starts a cold solve (a guess, not the answer)


def hard_wall_start(problem, control: Control, solve_at_position=solve_hard_wall) -> tuple:
    """What a smooth law's solve of the checked ``problem`` at ``control`` starts from: ``control.x0`` (a
    ContactResult), else the hard-wall solution at the same control where it exists (a compressive load, or a
    flat that reaches the surface) solved to tol max(tol, :data:`START_TOL`), else None (the undeformed surface).
    Under load control Polonsky–Keer solves it (the studies' equilibria, which depend on the start where a solve
    crosses instabilities, were measured from it); under displacement control ``solve_at_position`` does (the
    energy method's hand-over to the gap where Polonsky–Keer crawls, which this module cannot import). Returns
    (the start's result or None, its name "x0", "hard wall" or "rigid", its FFT pairs)."""
    if control.x0 is not None:
        return control.x0, "x0", 0.0
    heights = problem.heights
    h_max = float(heights.max())
    load = control.mean_pressure
    flat_position = None if load is not None else h_max - control.value
    # the start keeps the K⁻¹ preconditioner on profiles too: a smooth solve that crosses instabilities ends in an
    # equilibrium that depends on its start (docs/dev/investigations.md), and the profile studies were measured so
    options = dict(tol=max(control.tol, START_TOL), x0=None, callback=None, warn=False)
    if load is not None and load > 0:
        start = control.at(mean_pressure=load, **options)
    elif flat_position is not None and flat_position < h_max:
        start = control.at(penetration=h_max - flat_position, **options)
    else:
        return None, "rigid", 0.0
    solve = solve_hard_wall if load is not None else solve_at_position
    result = solve(problem.with_heights(heights, HardWall()), start, preconditioned=True)
    return result, "hard wall", result.solver.fft_pairs
