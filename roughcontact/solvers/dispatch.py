"""The contact solve: :func:`solve_contact` dispatches a problem to its method by the interaction law —
Polonsky–Keer's constrained conjugate gradients for the hard wall (:mod:`.polonsky_keer`), the minimum of the
total energy over the gap for a smooth law with the wall (:mod:`.energy_cg`)."""
from __future__ import annotations

from ..body import ElasticHalfSpace
from ..interactions import Interaction
from .energy_cg import solve_smooth
from .inputs import _check_body, _checked_interaction, default_tolerance
from .polonsky_keer import solve_hard_wall
from .result import ContactResult


def solve_contact(height_field, half: ElasticHalfSpace, *, mean_pressure=None, total_force=None,
                  penetration=None, tol=None, maxiter=10000, x0=None, cold_start="nested", callback=None,
                  preconditioned=True, interaction: Interaction | None = None, warn=True) -> ContactResult:
    """Press ``height_field`` onto a rigid flat and solve for pressure, displacement and gap.

    Parameters
    ----------
    height_field : surfaces.HeightField or array
        Topography h [m] on ``half.grid`` (peaks positive, towards the flat).
    half : ElasticHalfSpace
        The elastic body (kernel, FFT backend, dtype).
    mean_pressure, total_force, penetration
        Exactly one: the external load <p> [Pa] or F = <p> Lx Ly [N] (> 0 for the hard wall; any sign with a
        smooth interaction, where a tensile load beyond pull-off is reported as no equilibrium), or the
        penetration δ = max(h) − s [m] (displacement control; any sign).
    tol : float, optional
        Relative tolerance of the method's convergence criterion (its module docstring), in (0, 1); by default
        :func:`default_tolerance` of the body's dtype (1e-8 in float64, 1e-6 in float32).
    maxiter : int
        Maximum number of CG steps.
    x0 : ContactResult or array, optional
        Warm start: a previous result or a pressure field [Pa] (rescaled to the requested load); one that is
        zero everywhere carries no information and gets the cold start.
    cold_start : {"nested", "pk"}
        Initial guess without ``x0``. ``"nested"``: the pressure of the same problem on the grid coarsened
        2 × 2, recursively (:func:`~.polonsky_keer._nested_start`; fewer fine steps on rough surfaces,
        ``docs/guide/solver.md``); grids that do not halve down to 2 × ``NESTED_MIN`` pixels fall back to ``"pk"``:
        Polonsky and Keer's uniform p̄ (load control) or the rigid overlap (displacement control).
    callback : callable, optional
        ``callback(SolverState)`` after every step; raising ``StopIteration`` halts (``converged=False``).
    preconditioned : bool
        Precondition the conjugate gradients with the inverse kernel K⁻¹: one more FFT pair per step, fewer
        steps (``docs/guide/solver.md``).
    interaction : Interaction, optional
        Surface interaction law (:mod:`roughcontact.interactions`): :class:`~roughcontact.interactions.HardWall`
        (the default; Polonsky–Keer, :mod:`.polonsky_keer`) or a smooth law acting with the wall
        (:mod:`.energy_cg`; ``x0`` then a previous result, ``cold_start`` and ``preconditioned`` do
        not apply). A law that vanishes (0 V) is solved as the hard wall.
    warn : bool
        Emit a :class:`~roughcontact.io.ConvergenceWarning` when not converged.
    """
    _check_body(half)
    interaction = _checked_interaction(interaction)
    if interaction.smooth and not interaction.vanishes:    # (a law that vanishes, e.g. at 0 V, is the hard wall)
        tol = default_tolerance(half.dtype, interaction) if tol is None else tol
        return solve_smooth(height_field, half, interaction, mean_pressure=mean_pressure, total_force=total_force,
                            penetration=penetration, tol=tol, maxiter=maxiter, x0=x0, callback=callback, warn=warn)
    return solve_hard_wall(height_field, half, mean_pressure=mean_pressure, total_force=total_force,
                           penetration=penetration, tol=tol, maxiter=maxiter, x0=x0, cold_start=cold_start,
                           callback=callback, preconditioned=preconditioned, interaction=interaction, warn=warn)
