"""Frictionless normal contact of a rough elastic body with a rigid flat: Polonsky–Keer constrained CG.

Unknown: the contact pressure p ≥ 0 [Pa] on the grid; the gap g = s − h + u(p) ≥ 0 [m] with u = K p from
:class:`~roughcontact.body.ElasticHalfSpace` and p g = 0 (``docs/reference/conventions.md``). Load control fixes
<p> (the flat position s is the Lagrange multiplier); displacement control fixes s = max(h) − δ.

Algorithm: Polonsky & Keer (1999), Wear 231:206, steps (a)–(h), restricted conjugate gradients on the
contact set I_c = {p > 0} with the mean gap on I_c removed (load control), projection p ≥ 0 and re-entry
of penetrated points (I_ol; the CG restarts only when a point enters I_c for the first time in the solve:
re-entries of points that left keep it going, which cut the steps by 30–80 %; should the residual then make
no new minimum for ``STALL_STEPS`` steps, every entry restarts it from there on, as in PK). The direction t
is kept at zero mean on I_c, so the step length needs only ⟨t, K t⟩, which Parseval gives from the forward
transform of t alone. While the contact set holds, the backward transform completes K t and
u ← α u − τ K t: **one** FFT pair per step. When a point leaves or enters (or every ``_REFRESH`` steps, and
before accepting convergence) u = K p is recomputed instead: 1.5 pairs, never more. By default the CG is
preconditioned with the inverse kernel, z = K⁻¹ g: one more pair per step, fewer steps. Convergence
criterion, with ``gap_scale`` the rms height of h:

    sqrt(<(g − ḡ_c)²>_{I_c}) ≤ tol · gap_scale   and   max(−g outside I_c) ≤ tol · gap_scale,

the load constraint being satisfied exactly by construction. Where the CG is slow — under displacement control on
a periodic body with ⟨u⟩ = 0 near full contact, where a uniform pressure on the contact set hardly moves the
surface, and on a layered body whose long wavelengths are far more compliant than its pixels — a solve with
``slow_exit`` stops where its residual gains less than a decade in ``SLOW_STEPS`` steps, and
:func:`~roughcontact.solvers.projected_cg_gap.solve_hard_wall_handing_over` continues it on the gap. See
``docs/guide/solver.md``.
"""
from __future__ import annotations

import dataclasses
import math
import time
import warnings

import numpy as np
from numba import njit

from .._version import __version__
from ..io.results import ConvergenceWarning
from .inputs import Control
from .result import ContactResult, SolverReport, SolverState

METHOD = "polonsky-keer"
_REFRESH = 50          # exact recomputation of u at least every _REFRESH CG steps (round-off drift)
COLD_STARTS = ("nested", "pk")
NESTED_TOL = 1e-3      # tolerance of the nested start's coarse solves (their answer is only the fine guess)
NESTED_MIN = 64        # the nested start coarsens while the coarse grid keeps this many pixels per axis
NESTED_STEPS = 100     # steps of each coarse solve at most (a guess; 8–19 on the benchmark surface)
STALL_STEPS = 20       # steps without a new smallest residual after which every entry restarts the CG
STALL_LIMIT = 200      # steps without a new smallest residual, restarting on every entry, that end the solve
CYCLE_ABOVE_ROUND_OFF = 1e3   # a stall whose smallest residual is above this times the dtype's epsilon is a cycle
SLOW_STEPS = 20        # with slow_exit, a solve whose residual gains less than a decade in this many steps stops


# -- fused pointwise kernels (flat contiguous views; accumulators in float64) --------------------------------
# The contact set I_c is carried as a sorted index list, so the passes that only concern I_c (gap moments,
# conjugate direction, preconditioner input and moments) cost O(|I_c|), not a sweep over the
# grid; the direction t (and the preconditioner input) is kept zero outside I_c. Per iteration one pass
# streams whole grids, the projected step fused with the re-entry scan, plus the incremental displacement
# update when the set held.


@njit(cache=True)
def _gap(u, h, alpha, shift):
    """The gap g = α u − h + shift [m] at one point (α: the pending load normalisation, PK step (g))."""
    return alpha * u - h + shift


@njit(cache=True)
def _gap_moments(index, n_contact, u, h, alpha, shift):
    """Σ g and Σ g² over the contact set."""
    sum_g = 0.0
    sum_g2 = 0.0
    for k in range(n_contact):
        i = index[k]
        g = _gap(u[i], h[i], alpha, shift)
        sum_g += g
        sum_g2 += g * g
    return sum_g, sum_g2


@njit(cache=True)
def _largest_penetration(p, u, h, alpha, shift):
    """max(−g) over the points outside the contact set (0 if none penetrates)."""
    largest = 0.0
    for i in range(p.size):
        if p[i] <= 0:
            largest = max(largest, -_gap(u[i], h[i], alpha, shift))
    return largest


@njit(cache=True)
def _conjugate_direction(index, n_contact, u, h, alpha, shift, beta, t_mean, t):
    """PK step (c): t ← g + β (t − t̄) on the contact set (t = 0 elsewhere already); t̄ = the mean of the
    previous t over I_c, removed so that t keeps a zero mean there (load control). Returns Σ g t."""
    sum_gt = 0.0
    for k in range(n_contact):
        i = index[k]
        g = _gap(u[i], h[i], alpha, shift)
        direction = g + beta * (t[i] - t_mean)
        t[i] = direction
        sum_gt += g * direction
    return sum_gt


@njit(cache=True)
def _masked_gap(index, n_contact, u, h, alpha, shift, out):
    """out ← g on the contact set (``out`` = 0 elsewhere already): the residual to precondition."""
    for k in range(n_contact):
        i = index[k]
        out[i] = _gap(u[i], h[i], alpha, shift)


@njit(cache=True)
def _preconditioned_moments(index, n_contact, g, z):
    """Σ z and Σ g z over the contact set, for the preconditioned residual z = M g (g kept in the
    preconditioner's input, so u and h are not read again)."""
    sum_z = 0.0
    sum_gz = 0.0
    for k in range(n_contact):
        i = index[k]
        sum_z += z[i]
        sum_gz += g[i] * z[i]
    return sum_z, sum_gz


@njit(cache=True)
def _preconditioned_direction(index, n_contact, g, z, z_mean, beta, t_mean, t):
    """Preconditioned PK step (c): t ← (z − z̄) + β (t − t̄) on the contact set (zero mean there, as in
    :func:`_conjugate_direction`). Returns Σ g t."""
    sum_gt = 0.0
    for k in range(n_contact):
        i = index[k]
        direction = z[i] - z_mean + beta * (t[i] - t_mean)
        t[i] = direction
        sum_gt += g[i] * direction
    return sum_gt


@njit(cache=True)
def _advance_displacement(u, r, alpha, tau):
    """u ← α u − τ r with r = K t: the displacement of the step p ← α p − τ t when the contact set held."""
    for i in range(u.size):
        u[i] = alpha * u[i] - tau * r[i]


@njit(cache=True)
def _step_and_reentry(p, t, residual_input, u, h, alpha, shift, tau, index, been_in_contact):
    """PK steps (e) and (f) in one pass over the grid. (e) on the contact set: p ← α p − τ t where that stays
    positive; a point that leaves gets p = 0, t = 0 and 0 in ``residual_input`` (the preconditioner's input),
    keeping both zero outside the set. (f) a point with p = 0 after (e) where the wall is penetrated (gap
    before the step g = α u − h + shift < 0) re-enters with p = −τ g. Rebuilds the sorted index list of the
    contact set and marks entering points in ``been_in_contact``. Returns its size, Σ p, the numbers of points
    that left, that entered and that entered for the first time in this solve, and Σ t over the points that
    stayed (for the next direction's mean)."""
    n_contact = 0
    total = 0.0
    left = 0
    entered = 0
    first_entries = 0
    kept_t = 0.0
    for i in range(p.size):
        if p[i] > 0.0:
            value = alpha * p[i] - tau * t[i]
            if value > 0.0:
                p[i] = value
                total += value
                kept_t += t[i]
                index[n_contact] = i
                n_contact += 1
                continue
            p[i] = 0.0
            t[i] = 0.0
            residual_input[i] = 0.0
            left += 1
        g = _gap(u[i], h[i], alpha, shift)
        if g < 0.0:
            p[i] = -tau * g
            total += p[i]
            entered += 1
            if not been_in_contact[i]:
                been_in_contact[i] = True
                first_entries += 1
            index[n_contact] = i
            n_contact += 1
    return n_contact, total, left, entered, first_entries, kept_t


@njit(cache=True)
def _contact_index(p, index, been_in_contact):
    """Sorted indices of p > 0 into ``index``, also marked in ``been_in_contact``; returns their number."""
    n_contact = 0
    for i in range(p.size):
        if p[i] > 0.0:
            index[n_contact] = i
            n_contact += 1
            been_in_contact[i] = True
    return n_contact


@njit(cache=True)
def _scale(values, alpha):
    for i in range(values.size):
        values[i] *= alpha


@njit(cache=True)
def _finalise_gap(u, h, p, shift, gap, contact):
    """Gap field g = max(u − h + shift, 0), zero on the contact set; contact mask p > 0."""
    for i in range(p.size):
        contact[i] = p[i] > 0
        g = _gap(u[i], h[i], 1.0, shift)
        gap[i] = 0.0 if (contact[i] or g < 0) else g


def _warm_pressure(x0):
    """The warm-start pressure [Pa] of ``x0`` (the checked control's pressure field, or a result's); None without
    ``x0`` or when it is zero everywhere (no information: the cold start applies)."""
    pressure = x0.pressure if isinstance(x0, ContactResult) else x0
    return pressure if pressure is not None and pressure.any() else None


def _pk_pressure(heights, body, mean_pressure, flat_position):
    """Polonsky and Keer's initial guess [Pa]: uniform p̄ (load control) or the rigid overlap (displacement
    control)."""
    if mean_pressure is not None:
        return np.full(heights.shape, mean_pressure, dtype=body.dtype)
    overlap = np.maximum(heights - flat_position, 0)      # rigid overlap; pressure ~ E* δ / (contact size)
    contact_size = math.sqrt(np.count_nonzero(overlap) * body.grid.pixel_area)
    return (overlap * (body.E_star / contact_size)).astype(body.dtype)


def _nested_start(problem, control, flat_position, preconditioned, slow_exit):
    """Cold-start pressure [Pa]: the same problem solved on the grid coarsened 2 × 2 (itself started the same
    way, down to ``NESTED_MIN`` pixels per axis) to tol max(tol, ``NESTED_TOL``), whose pressure, each coarse
    pixel's on the fine pixels it covers (:func:`_repeat_into`), is the fine guess — cascade multi-resolution
    (Bemporad & Paggi 2015, Int. J. Solids Struct. 69:94). Returns the coarse pressure (None where the grid does
    not halve or the flat misses the coarse surface) and the coarse solves' iterations, coarsest first. The
    coarse body is built here and dropped, so the fine solve's peak memory is unchanged. Each coarse solve takes at
    most ``NESTED_STEPS`` steps (on a layered body they took up to 3710), and under displacement control it stops
    where slow as the fine one does (``slow_exit``)."""
    grid = problem.body.grid
    if any(n % 2 or n // 2 < NESTED_MIN for n in grid.shape[:1 if grid.is_profile else 2]):
        return None, []
    coarse = problem.coarsened()
    if control.mean_pressure is not None:
        target = {"mean_pressure": control.mean_pressure}
    else:                                                   # the same flat position (coarse peaks are lower)
        target = {"penetration": float(coarse.surface.heights.max()) - flat_position}
        if target["penetration"] <= 0:
            return None, []
    coarse_control = control.at(**target, tol=max(control.tol, NESTED_TOL), maxiter=min(control.maxiter, NESTED_STEPS),
                                x0=None, callback=None, warn=False)
    result = solve_hard_wall(coarse, coarse_control, preconditioned=preconditioned,
                             slow_exit=slow_exit and control.mean_pressure is None)
    if not result.pressure.any():
        return None, []
    return result.pressure, result.solver.details["nested_iterations"] + [result.iterations]


def _repeat_into(coarse, fine):
    """fine ← each coarse pixel's value on the 2 × 2 fine pixels it covers (2 × 1 on a profile)."""
    (nx, ny), factor_y = coarse.shape, fine.shape[1] // coarse.shape[1]
    fine.reshape(nx, 2, ny, factor_y)[...] = coarse[:, None, :, None]


def _restart(p, t, z_in, index, been_in_contact) -> int:
    """Start the conjugate gradients afresh from p: t = 0, preconditioner input 0, I_c = {p > 0} (marked in
    ``been_in_contact``); its size."""
    t[:] = 0.0
    z_in[:] = 0.0
    return _contact_index(p, index, been_in_contact)


def _full_contact(h, body, mean_pressure, pressure, displacement):
    """The exact full-contact state under load control on a periodic body into the flat arrays ``pressure`` and
    ``displacement`` (from ``body.empty()``): p = p̄ + K⁻¹(h − ⟨h⟩), u = h − ⟨h⟩ + Φ(0) p̄ (one FFT pair). Returns
    the flat position s = ⟨h⟩ − Φ(0) p̄, or None if some pressure would be negative (partial contact)."""
    h_mean = float(h[0]) if float(h.min()) == float(h.max()) else float(h.mean(dtype=np.float64))   # flat: exact
    np.subtract(h, h_mean, out=displacement)
    shape = body.grid.shape
    body.stiffness_into(displacement.reshape(shape), pressure.reshape(shape))
    pressure += mean_pressure - float(pressure.mean(dtype=np.float64))        # the mean exactly p̄
    if float(pressure.min()) <= 0.0:
        return None
    displacement += body.uniform_compliance * mean_pressure
    return h_mean - body.uniform_compliance * mean_pressure


def solve_hard_wall(problem, control: Control, *, cold_start="nested", preconditioned=None,
                    slow_exit=False) -> ContactResult:
    """Polonsky–Keer's solve (module docstring) of the checked ``problem`` (a
    :class:`~roughcontact.solvers.problem.ContactProblem`: the hard wall, or a law that vanishes, 0 V) at the
    checked ``control``, from its ``x0`` or the ``cold_start``; ``preconditioned`` by default on 2-D grids
    (:func:`~roughcontact.solvers.problem.solve_contact`). ``slow_exit``: stop, unconverged, where the residual gains
    less than a decade in ``SLOW_STEPS`` steps (``details["slow_exit_at"]``), unless it is within
    ``CYCLE_ABOVE_ROUND_OFF`` times the dtype's epsilon (round-off, which the stall rules handle)."""
    start = time.perf_counter()
    body, interaction, heights = problem.body, problem.interaction, problem.heights
    tol, maxiter, callback, warn = control.tol, control.maxiter, control.callback, control.warn
    grid = body.grid
    # K⁻¹ saves steps on 2-D grids; on 1-D profiles it does not (docs/guide/solver.md): off there by default
    preconditioned = not grid.is_profile if preconditioned is None else preconditioned
    warm = _warm_pressure(control.x0)
    warm_started = warm is not None
    mean_pressure, penetration = control.mean_pressure, control.penetration
    load_control = mean_pressure is not None
    h_max = float(heights.max())
    flat_position = None if load_control else h_max - penetration
    if not load_control and body.periodic and body.uniform_compliance == 0.0:
        limit = h_max - float(heights.mean(dtype=np.float64))
        if penetration >= limit and penetration > 0:
            raise ValueError(f"penetration = {float(penetration)!r} m has no solution on a periodic body with ⟨u⟩ = 0: "
                             f"the mean gap s − ⟨h⟩ must stay > 0, i.e. penetration < max(h) − ⟨h⟩ = {limit!r} m (use "
                             "load control for full contact)")

    settings = {"tol": tol, "maxiter": int(maxiter), "start": "x0" if warm is not None else "pk",
              "control": control.kind, "requested": float(control.value),
              "details": {"preconditioned": preconditioned, "nested_iterations": [], "restart_every_entry_from": None,
                          "full_contact": False}}

    n_points = heights.size
    h = heights.reshape(-1)
    if not load_control and flat_position >= h_max:          # the flat does not reach the surface
        zeros = np.zeros(n_points, body.dtype)
        return _result(zeros, zeros.copy(), h, flat_position, body, interaction, settings, 0, [0.0], True,
                       "no contact: penetration <= 0", start, 0)
    if load_control and mean_pressure <= 0:                 # nothing presses: a law that vanishes (0 V) at 0 or less
        zeros = np.zeros(n_points, body.dtype)
        if mean_pressure == 0:
            return _result(zeros, zeros.copy(), h, h_max, body, interaction, settings, 0, [0.0], True,
                           "zero load: the flat touches the highest point and presses nothing", start, 0)
        message = (f"detached: no equilibrium under the tensile load {mean_pressure:.6g} Pa, since the law "
                   f"{type(interaction).__name__} exerts no traction (it vanishes); the bodies separate")
        if warn:
            warnings.warn(message, ConvergenceWarning, stacklevel=3)
        return _result(zeros, zeros.copy(), h, h_max, body, interaction, settings, 0, [math.inf], False, message,
                       start, 0, detached=True)
    coarse_pressure = None
    if warm is None and cold_start == "nested":             # solved first, before the fine work arrays exist
        coarse_pressure, settings["details"]["nested_iterations"] = _nested_start(
            problem, control, flat_position, preconditioned, slow_exit)
        settings["start"] = "pk" if coarse_pressure is None else "nested"
    # grid-sized work arrays (aligned: the periodic FFT uses them in place); t and z_in stay 0 outside I_c
    p, u, t, r = (body.empty().reshape(-1) for _ in range(4))
    z_in = body.empty().reshape(-1) if preconditioned else t
    if load_control and body.periodic:                      # full contact is exact: no iteration
        shift = _full_contact(h, body, mean_pressure, p, u)
        if shift is not None:
            settings["details"]["full_contact"] = True
            return _result(p, u, h, shift, body, interaction, settings, 0, [0.0], True,
                           "full contact: the pressure that flattens h, p̄ + K⁻¹(h − ⟨h⟩), is positive everywhere "
                           "(exact)", start, 2)
    index = np.empty(n_points, np.int32 if n_points < 2 ** 31 else np.int64)   # the contact set I_c, sorted
    if warm is not None:
        p[:] = warm.reshape(-1)
        del warm                                            # (a grid copy when x0 needed a dtype conversion)
    elif coarse_pressure is None:
        p[:] = _pk_pressure(heights, body, mean_pressure, flat_position).reshape(-1)
    else:
        _repeat_into(coarse_pressure, p.reshape(grid.shape))
        del coarse_pressure                                 # (a quarter grid array, not kept through the solve)
    solver = _PolonskyKeer(body, heights, (p, u, t, r, z_in), index, mean_pressure, flat_position, preconditioned,
                           settings["details"])
    iterations, residuals, converged, message, stalled = solver.iterate(tol, maxiter, callback, slow_exit)
    cycled = stalled and min(residuals) > CYCLE_ABOVE_ROUND_OFF * np.finfo(body.dtype).eps
    if stalled and (warm_started or (preconditioned and cycled)):
        # a warm start can lead PK into a cycle that the cold start avoids: solve again from it; a cold start that
        # cycles with the K⁻¹ preconditioner far above round-off (seen on 1-D skin profiles at 0.25 µm pixels,
        # about one in ten) converges without it: solve again unpreconditioned
        del p, u, t, r, z_in, index, solver
        retry = solve_hard_wall(problem, dataclasses.replace(control, x0=None), cold_start=cold_start,
                                preconditioned=preconditioned and warm_started, slow_exit=slow_exit)
        key = "warm_start_stalled_at" if warm_started else "preconditioned_stalled_at"
        details = {**retry.solver.details, key: iterations}
        return dataclasses.replace(retry, solver=dataclasses.replace(retry.solver, details=details))
    solver.finish()
    if not converged and warn:
        warnings.warn(message, ConvergenceWarning, stacklevel=3)
    return _result(p, u, h, solver.shift, body, interaction, settings, iterations, residuals, converged, message, start,
                   solver.transforms)


class _PolonskyKeer:
    """The state and the iteration of :func:`solve_hard_wall` (the module docstring's steps (a)–(g)): the
    pressure p and displacement u (normalised lazily by ``alpha``, PK step (g)), the direction t, the
    preconditioner's input and output, the contact set I_c as a sorted index list, and the CG's scalars."""

    def __init__(self, body, heights, arrays, index, mean_pressure, flat_position, preconditioned, details):
        self.body, self.heights, self.h = body, heights, heights.reshape(-1)
        self.p, self.u, self.t, self.r, self.z_in = arrays          # t and z_in stay 0 outside I_c
        self.index = index
        self.been_in_contact = np.zeros(heights.size, np.bool_)    # only a first entry into I_c restarts the CG
        self.n_contact = _restart(self.p, self.t, self.z_in, index, self.been_in_contact)
        self.mean_pressure, self.flat_position = mean_pressure, flat_position
        self.load_control, self.preconditioned, self.details = mean_pressure is not None, preconditioned, details
        # alpha: pending load normalisation (PK step (g)); the normalised fields are α p and α u = K(α p)
        self.alpha = mean_pressure * heights.size / float(self.p.sum(dtype=np.float64)) if self.load_control else 1.0
        deviation = heights - heights.mean(dtype=np.float64)
        self.gap_scale = float(np.sqrt(np.mean(deviation * deviation, dtype=np.float64)))
        del deviation
        self.transforms = 0
        self.recompute_displacement()
        if self.gap_scale == 0.0:                           # flat surface: scale by the elastic displacement
            self.gap_scale = self.alpha * float(np.sqrt(np.mean(np.square(self.u, dtype=np.float64)))) or 1.0
        self.shift = float(self.h.mean(dtype=np.float64)) - self.alpha * float(self.u.mean(dtype=np.float64)) \
            if self.load_control else flat_position
        self.beta_allowed, self.previous_squared, self.tau, self.kept_t, self.z_mean = False, 1.0, 0.0, 0.0, 0.0
        self.restart_every_entry = False
        self.round_off = CYCLE_ABOVE_ROUND_OFF * float(np.finfo(body.dtype).eps)   # no slow exit below this residual

    def field(self, array):
        """The 2-D view that the elastic operator takes."""
        return array.reshape(self.body.grid.shape)

    def recompute_displacement(self):
        """u = K p exactly: one FFT pair (two transforms)."""
        self.body._displacement_into(self.field(self.p), self.field(self.u))
        self.transforms += 2
        self.exact, self.since_exact = True, 0

    def iterate(self, tol, maxiter, callback, slow_exit=False):
        """Steps until converged, stalled, halted, slow (``slow_exit``) or ``maxiter``: (iterations, residuals,
        converged, message, stalled)."""
        residuals, iterations, reported = [], 0, 0
        smallest_residual, smallest_at, earlier_best = math.inf, 0, math.inf
        while True:
            squared, residual = self.residual()
            if callback is not None and iterations > reported:
                reported = iterations
                try:
                    callback(SolverState(iterations, residual, self.n_contact / self.h.size))
                except StopIteration:
                    residuals.append(residual)
                    return iterations, residuals, False, (f"halted by callback after {iterations} iterations "
                                                          f"(relative rms gap error {residual:.3g})"), False
            # the penetration outside the contact set is checked only once the contact set is converged
            penetration_error = _largest_penetration(self.p, self.u, self.h, self.alpha, self.shift) / \
                self.gap_scale if residual <= tol else math.nan
            if residual <= tol and penetration_error <= tol:
                if not self.exact:                          # accept only on an exactly recomputed u
                    self.recompute_displacement()
                    continue
                residuals.append(residual)
                return (iterations, residuals, True, f"converged: relative rms gap error {residual:.3g} <= tol {tol:g}",
                        False)
            residuals.append(residual)
            if slow_exit and iterations >= SLOW_STEPS:      # the best of the last SLOW_STEPS against the one before
                earlier_best = min(earlier_best, residuals[-SLOW_STEPS - 1])
                if min(residuals[-SLOW_STEPS:]) > max(0.1 * earlier_best, self.round_off):
                    self.details["slow_exit_at"] = iterations
                    return iterations, residuals, False, (f"slow: less than a decade in {SLOW_STEPS} steps (relative "
                                                          f"rms gap error {residual:.3g})"), False
            if residual < smallest_residual:
                smallest_residual, smallest_at = residual, iterations
            elif not self.restart_every_entry and iterations - smallest_at >= STALL_STEPS:
                # the contact set cycles through re-entries (seen once: rough 1024², 0.0065 E*, PK start, where the
                # residual hovered at 1e-2 for 10⁴ steps): fall back to PK's rule, restart on every entry
                self.restart_every_entry, self.details["restart_every_entry_from"] = True, iterations
            elif self.restart_every_entry and iterations - smallest_at >= STALL_LIMIT:
                return iterations, residuals, False, (f"stalled: no smaller residual in {STALL_LIMIT} steps (smallest "
                                                      f"{smallest_residual:.3g} at step {smallest_at}, tol {tol:g}, "
                                                      f"{self.body.dtype.name})"), True
            if iterations >= maxiter:
                message = (f"not converged after {iterations} iterations: relative rms gap error {residual:.3g} "
                           f"(tol {tol:g})")
                if residual <= tol:
                    message += f", but a penetration {penetration_error:.3g} outside the contact set"
                return iterations, residuals, False, message, False
            iterations += 1
            self.step(squared)

    def residual(self):
        """(a)–(b) the gap moments on the contact set (load control centres the gap there: flat position =
        ``shift``); returns Σ(g − ḡ)² and the relative rms gap error."""
        index, n_contact, u, h, alpha = self.index, self.n_contact, self.u, self.h, self.alpha
        sum_g, sum_g2 = _gap_moments(index, n_contact, u, h, alpha, self.shift)
        if self.load_control and n_contact:
            correction = -sum_g / n_contact
            squared = max(sum_g2 - sum_g * sum_g / n_contact, 0.0)
            if n_contact * correction ** 2 > 1e6 * squared:  # moments about a stale shift lost precision
                self.shift += correction
                sum_g, squared = _gap_moments(index, n_contact, u, h, alpha, self.shift)
                correction = -sum_g / n_contact
            self.shift += correction
        else:
            squared = sum_g2
        return squared, math.sqrt(squared / n_contact) / self.gap_scale if n_contact else math.inf

    def conjugate_direction(self, beta):
        """(c) t ← (z − z̄ or g) + β (t − t̄); returns Σ g t."""
        t_mean = self.kept_t / self.n_contact if self.load_control and beta else 0.0
        if self.preconditioned:
            return _preconditioned_direction(self.index, self.n_contact, self.z_in, self.r, self.z_mean, beta, t_mean,
                                             self.t)
        return _conjugate_direction(self.index, self.n_contact, self.u, self.h, self.alpha, self.shift, beta, t_mean,
                                    self.t)

    def step(self, squared):
        """One step, (c)–(g), from the residual's Σ(g − ḡ)²; u advanced incrementally while I_c holds, else
        recomputed exactly."""
        body, p, t, r, z_in, index = self.body, self.p, self.t, self.r, self.z_in, self.index
        step_incremental = False
        if self.n_contact == 0:                             # displacement control lost all contact: restart
            p[:] = _pk_pressure(self.heights, body, None, self.flat_position).reshape(-1)
            self.alpha, self.beta_allowed = 1.0, False
            self.n_contact = _restart(p, t, z_in, index, self.been_in_contact)
        else:
            # (c) conjugate direction, optionally preconditioned: z = M g with M = K⁻¹ (one FFT pair)
            if self.preconditioned:
                _masked_gap(index, self.n_contact, self.u, self.h, self.alpha, self.shift, z_in)
                body.stiffness_into(self.field(z_in), self.field(r))
                self.transforms += 2
                sum_z, descent = _preconditioned_moments(index, self.n_contact, z_in, r)
                self.z_mean = sum_z / self.n_contact if self.load_control else 0.0
            else:
                descent, self.z_mean = squared, 0.0
            beta = descent / self.previous_squared if self.beta_allowed and self.previous_squared > 0 else 0.0
            self.previous_squared = descent
            sum_gt = self.conjugate_direction(beta)
            if sum_gt <= 0 and beta > 0:                    # not a descent direction: restart the CG
                sum_gt = self.conjugate_direction(0.0)
            # (d) step length τ = Σ g t / ⟨t, K t⟩, the curvature by Parseval (forward transform only)
            curvature = body.quadratic_form(self.field(t))
            self.transforms += 1
            if curvature > 0:
                self.tau = sum_gt / curvature
            elif self.tau == 0.0:                           # t = 0 on a gap-free contact set: re-entry only
                self.tau = 1.0 / body.pixel_compliance
            # (e) projected step on I_c, (f) re-entry of penetrated points (gap before the step)
            self.n_contact, total, left, entered, first_entries, self.kept_t = _step_and_reentry(
                p, t, z_in, self.u, self.h, self.alpha, self.shift, self.tau, index, self.been_in_contact)
            # re-entries of points that left keep the CG going, unless the residual stalled
            self.beta_allowed = (entered if self.restart_every_entry else first_entries) == 0
            step_incremental = left == 0 and entered == 0 and self.since_exact < _REFRESH and total > 0
            if step_incremental:                            # the set held: complete K t, u ← α u − τ K t
                body.pending_displacement_into(self.field(r))
                self.transforms += 1
                _advance_displacement(self.u, r, self.alpha, self.tau)
            self.alpha = 1.0
            if self.load_control:                           # (g), applied lazily through alpha
                if total > 0:
                    self.alpha = self.mean_pressure * p.size / total
                else:                                       # every point left: start again from uniform p
                    p[:] = self.mean_pressure
                    self.n_contact = _restart(p, t, z_in, index, self.been_in_contact)
                    self.beta_allowed = False
        if step_incremental:
            self.exact, self.since_exact = False, self.since_exact + 1
        else:                                               # contact set changed: recompute u exactly
            self.recompute_displacement()

    def finish(self):
        """p and u normalised (α applied), u exact."""
        if not self.exact:
            self.recompute_displacement()
        _scale(self.p, self.alpha)
        _scale(self.u, self.alpha)


def _result(p, u, h, shift, body, interaction, settings, iterations, residuals, converged, message, start, transforms,
            detached=False):
    grid = body.grid
    gap = np.empty(p.size, body.dtype)
    contact = np.empty(p.size, np.bool_)
    _finalise_gap(u, h, p, shift, gap, contact)
    pressure, displacement = p.reshape(grid.shape), u.reshape(grid.shape)
    gap, contact = gap.reshape(grid.shape), contact.reshape(grid.shape)
    for array in (pressure, displacement, gap, contact):
        array.flags.writeable = False
    report = SolverReport(
        method=METHOD, converged=bool(converged), message=message, iterations=int(iterations),
        residuals=np.asarray(residuals, dtype=np.float64), tol=settings["tol"], maxiter=settings["maxiter"],
        start=settings["start"], fft_pairs=transforms / 2, wall_time=time.perf_counter() - start, detached=detached,
        kernel=body.description, version=__version__, details=settings["details"])
    return ContactResult(
        pressure=pressure, displacement=displacement, gap=gap, contact=contact,
        contact_fraction=float(np.count_nonzero(contact)) / contact.size,
        mean_pressure=float(p.mean(dtype=np.float64)), mean_gap=float(gap.mean(dtype=np.float64)),
        penetration=float(h.max()) - float(shift), elastic_energy=body.elastic_energy(pressure, displacement),
        grid=grid, solver=report, contact_pressure=pressure,
        interaction_traction=np.broadcast_to(np.zeros((), body.dtype), grid.shape),
        flat_position=float(shift), interaction=interaction, control=settings["control"],
        requested=settings["requested"])
