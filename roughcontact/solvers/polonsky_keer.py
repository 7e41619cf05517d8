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

the load constraint being satisfied exactly by construction. See ``docs/guide/solver.md``.
"""
from __future__ import annotations

import dataclasses
import math
import time
import warnings

import numpy as np
from numba import njit

from surfaces import HeightField
from surfaces.validation import (check_bool, check_choice, check_finite_array, check_integer, check_positive,
                                 check_real)

from .._version import __version__
from ..body import ElasticHalfSpace
from ..interactions import Interaction
from ..io.results import ConvergenceWarning
from .inputs import _check_body, _checked_interaction, _heights, default_tolerance
from .result import ContactResult, SolverState

METHOD = "polonsky-keer"
_REFRESH = 50          # exact recomputation of u at least every _REFRESH CG steps (round-off drift)
COLD_STARTS = ("nested", "pk")
NESTED_TOL = 1e-3      # tolerance of the nested start's coarse solves (their answer is only the fine guess)
NESTED_MIN = 64        # the nested start coarsens while the coarse grid keeps this many pixels per axis
STALL_STEPS = 20       # steps without a new smallest residual after which every entry restarts the CG
STALL_LIMIT = 200      # steps without a new smallest residual, restarting on every entry, that end the solve


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


def _warm_pressure(x0, shape):
    """The warm-start pressure [Pa] of ``x0`` (a ContactResult or a pressure array), checked; None without
    ``x0`` or when it is zero everywhere (no information: the cold start applies)."""
    if x0 is None:
        return None
    pressure = check_finite_array("x0", x0.pressure if isinstance(x0, ContactResult) else x0, nonnegative=True)
    if pressure.shape != shape:
        raise ValueError(f"x0 has shape {pressure.shape}, but the grid has shape {shape}")
    return pressure if pressure.any() else None


def _pk_pressure(heights, half, mean_pressure, flat_position):
    """Polonsky and Keer's initial guess [Pa]: uniform p̄ (load control) or the rigid overlap (displacement
    control)."""
    if mean_pressure is not None:
        return np.full(heights.shape, mean_pressure, dtype=half.dtype)
    overlap = np.maximum(heights - flat_position, 0)      # rigid overlap; pressure ~ E* δ / (contact size)
    contact_size = math.sqrt(np.count_nonzero(overlap) * half.grid.pixel_area)
    return (overlap * (half.E_star / contact_size)).astype(half.dtype)


def _nested_start(surface, half, mean_pressure, flat_position, tol, maxiter, preconditioned):
    """Cold-start pressure [Pa]: the same problem solved on the grid coarsened 2 × 2 (itself started the same
    way, down to ``NESTED_MIN`` pixels per axis) to tol max(tol, ``NESTED_TOL``), whose pressure, each coarse
    pixel's on the fine pixels it covers (:func:`_repeat_into`), is the fine guess — cascade multi-resolution
    (Bemporad & Paggi 2015, Int. J. Solids Struct. 69:94). Returns the coarse pressure (None where the grid does
    not halve or the flat misses the coarse surface) and the coarse solves' iterations, coarsest first. The
    coarse body is built here and dropped, so the fine solve's peak memory is unchanged."""
    grid = half.grid
    if any(n % 2 or n // 2 < NESTED_MIN for n in grid.shape[:1 if grid.is_profile else 2]):
        return None, []
    coarse = surface.coarsened(2)
    if mean_pressure is not None:
        control = {"mean_pressure": mean_pressure}
    else:                                                   # the same flat position (coarse peaks are lower)
        control = {"penetration": float(coarse.heights.max()) - flat_position}
        if control["penetration"] <= 0:
            return None, []
    result = solve_hard_wall(coarse, half.coarsened(), **control, tol=max(tol, NESTED_TOL), maxiter=maxiter,
                             preconditioned=preconditioned, warn=False)
    if not result.pressure.any():
        return None, []
    return result.pressure, result.params["nested_iterations"] + [result.iterations]


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


def _full_contact(h, half, mean_pressure, pressure, displacement):
    """The exact full-contact state under load control on a periodic body into the flat arrays ``pressure`` and
    ``displacement`` (from ``half.empty()``): p = p̄ + K⁻¹(h − ⟨h⟩), u = h − ⟨h⟩ + Φ(0) p̄ (one FFT pair). Returns
    the flat position s = ⟨h⟩ − Φ(0) p̄, or None if some pressure would be negative (partial contact)."""
    h_mean = float(h[0]) if float(h.min()) == float(h.max()) else float(h.mean(dtype=np.float64))   # flat: exact
    np.subtract(h, h_mean, out=displacement)
    shape = half.grid.shape
    half.stiffness_into(displacement.reshape(shape), pressure.reshape(shape))
    pressure += mean_pressure - float(pressure.mean(dtype=np.float64))        # the mean exactly p̄
    if float(pressure.min()) <= 0.0:
        return None
    displacement += half.uniform_compliance * mean_pressure
    return h_mean - half.uniform_compliance * mean_pressure


def solve_hard_wall(height_field, half: ElasticHalfSpace, *, mean_pressure=None, total_force=None,
                    penetration=None, tol=None, maxiter=10000, x0=None, cold_start="nested", callback=None,
                    preconditioned=True, interaction: Interaction | None = None, warn=True) -> ContactResult:
    """Polonsky–Keer's solve (module docstring) of :func:`~roughcontact.solvers.dispatch.solve_contact` for the
    hard wall, or a law that vanishes (0 V); same arguments."""
    start = time.perf_counter()
    _check_body(half)
    interaction = _checked_interaction(interaction)
    tol = default_tolerance(half.dtype, interaction) if tol is None else tol
    given = {name: value for name, value in (("mean_pressure", mean_pressure), ("total_force", total_force),
                                             ("penetration", penetration)) if value is not None}
    if len(given) != 1:
        raise ValueError(f"give exactly one of mean_pressure, total_force, penetration; got {sorted(given) or 'none'}")
    tol = check_real("tol", tol, low=0.0, high=1.0, low_open=True, high_open=True)
    check_integer("maxiter", maxiter, low=0)
    check_choice("cold_start", cold_start, COLD_STARTS)
    if callback is not None and not callable(callback):
        raise TypeError(f"callback must be callable, got {type(callback).__name__}")
    grid = half.grid
    preconditioned = check_bool("preconditioned", preconditioned)
    heights = _heights(height_field, half)
    warm = _warm_pressure(x0, heights.shape)
    warm_started = warm is not None
    if total_force is not None:
        mean_pressure = check_positive("total_force", total_force) / grid.area
    elif mean_pressure is not None:
        mean_pressure = check_positive("mean_pressure", mean_pressure)
    load_control = mean_pressure is not None
    h_max = float(heights.max())
    flat_position = None if load_control else h_max - check_real("penetration", penetration)
    if not load_control and half.periodic and half.uniform_compliance == 0.0:
        limit = h_max - float(heights.mean(dtype=np.float64))
        if penetration >= limit and penetration > 0:
            raise ValueError(f"penetration = {float(penetration)!r} m has no solution on a periodic body with ⟨u⟩ = 0: "
                             f"the mean gap s − ⟨h⟩ must stay > 0, i.e. penetration < max(h) − ⟨h⟩ = {limit!r} m (use "
                             "load control for full contact)")

    params = {"E_star": half.E_star, "grid": grid, "tol": tol, "maxiter": int(maxiter), "method": METHOD,
              "preconditioned": preconditioned, "start": "x0" if warm is not None else "pk", "nested_iterations": [],
              "restart_every_entry_from": None, "full_contact": False,
              "control": next(iter(given)), "requested": float(next(iter(given.values()))),
              "interaction": type(interaction).__name__, "kernel": half.description, "version": __version__}

    n_points = heights.size
    h = heights.reshape(-1)
    if not load_control and flat_position >= h_max:          # the flat does not reach the surface
        zeros = np.zeros(n_points, half.dtype)
        return _result(zeros, zeros.copy(), h, flat_position, half, interaction, params, 0, [0.0], True,
                       "no contact: penetration <= 0", start, 0)
    coarse_pressure = None
    if warm is None and cold_start == "nested":             # solved first, before the fine work arrays exist
        surface = height_field if isinstance(height_field, HeightField) else HeightField(grid, heights)
        coarse_pressure, params["nested_iterations"] = _nested_start(surface, half, mean_pressure, flat_position,
                                                                     tol, maxiter, preconditioned)
        del surface                                         # (a grid copy when the heights came as an array)
        params["start"] = "pk" if coarse_pressure is None else "nested"
    # grid-sized work arrays (aligned: the periodic FFT uses them in place); t and z_in stay 0 outside I_c
    p, u, t, r = (half.empty().reshape(-1) for _ in range(4))
    z_in = half.empty().reshape(-1) if preconditioned else t
    if load_control and half.periodic:                      # full contact is exact: no iteration
        shift = _full_contact(h, half, mean_pressure, p, u)
        if shift is not None:
            return _result(p, u, h, shift, half, interaction, {**params, "full_contact": True}, 0, [0.0], True,
                           "full contact: the pressure that flattens h, p̄ + K⁻¹(h − ⟨h⟩), is positive everywhere "
                           "(exact)", start, 2)
    index = np.empty(n_points, np.int32 if n_points < 2 ** 31 else np.int64)   # the contact set I_c, sorted
    if warm is not None:
        p[:] = warm.reshape(-1)
        del warm                                            # (a grid copy when x0 needed a dtype conversion)
    elif coarse_pressure is None:
        p[:] = _pk_pressure(heights, half, mean_pressure, flat_position).reshape(-1)
    else:
        _repeat_into(coarse_pressure, p.reshape(grid.shape))
        del coarse_pressure                                 # (a quarter grid array, not kept through the solve)
    been_in_contact = np.zeros(n_points, np.bool_)          # only a first entry into I_c restarts the CG
    n_contact = _restart(p, t, z_in, index, been_in_contact)

    def field(array):                                       # the 2-D view that the elastic operator takes
        return array.reshape(grid.shape)

    def recompute_displacement():                           # u = K p: one FFT pair (two transforms)
        half._displacement_into(field(p), field(u))
        return 2

    def conjugate_direction(beta):                          # (c) t ← (z − z̄ or g) + β (t − t̄); Σ g t
        t_mean = kept_t / n_contact if load_control and beta else 0.0
        if preconditioned:
            return _preconditioned_direction(index, n_contact, z_in, r, z_mean, beta, t_mean, t)
        return _conjugate_direction(index, n_contact, u, h, alpha, shift, beta, t_mean, t)

    # alpha: pending load normalisation (PK step (g)); the normalised fields are α p and α u = K(α p)
    alpha = mean_pressure * n_points / float(p.sum(dtype=np.float64)) if load_control else 1.0
    deviation = heights - heights.mean(dtype=np.float64)
    gap_scale = float(np.sqrt(np.mean(deviation * deviation, dtype=np.float64)))
    del deviation
    transforms, exact, since_exact = recompute_displacement(), True, 0
    if gap_scale == 0.0:                                    # flat surface: scale by the elastic displacement
        gap_scale = alpha * float(np.sqrt(np.mean(np.square(u, dtype=np.float64)))) or 1.0

    residuals, iterations, converged, message, stalled = [], 0, False, "", False
    smallest_residual, smallest_at, restart_every_entry = math.inf, 0, False
    shift = float(h.mean(dtype=np.float64)) - alpha * float(u.mean(dtype=np.float64)) if load_control else flat_position
    beta_allowed, previous_squared, tau, reported, kept_t = False, 1.0, 0.0, 0, 0.0
    while True:
        # (a)-(b) gap moments on the contact set; load control centres the gap there (flat position = shift)
        sum_g, sum_g2 = _gap_moments(index, n_contact, u, h, alpha, shift)
        if load_control and n_contact:
            correction = -sum_g / n_contact
            squared = max(sum_g2 - sum_g * sum_g / n_contact, 0.0)
            if n_contact * correction ** 2 > 1e6 * squared:  # moments about a stale shift lost precision
                shift += correction
                sum_g, squared = _gap_moments(index, n_contact, u, h, alpha, shift)
                correction = -sum_g / n_contact
            shift += correction
        else:
            squared = sum_g2
        residual = math.sqrt(squared / n_contact) / gap_scale if n_contact else math.inf
        if callback is not None and iterations > reported:
            reported = iterations
            try:
                callback(SolverState(iterations, residual, n_contact / n_points))
            except StopIteration:
                residuals.append(residual)
                message = f"halted by callback after {iterations} iterations (relative rms gap error {residual:.3g})"
                break
        # the penetration outside the contact set is checked only once the contact set is converged
        penetration_error = _largest_penetration(p, u, h, alpha, shift) / gap_scale if residual <= tol else math.nan
        if residual <= tol and penetration_error <= tol:
            if not exact:                                   # accept only on an exactly recomputed u
                transforms, exact, since_exact = transforms + recompute_displacement(), True, 0
                continue
            residuals.append(residual)
            converged, message = True, f"converged: relative rms gap error {residual:.3g} <= tol {tol:g}"
            break
        residuals.append(residual)
        if residual < smallest_residual:
            smallest_residual, smallest_at = residual, iterations
        elif not restart_every_entry and iterations - smallest_at >= STALL_STEPS:
            # the contact set cycles through re-entries (seen once: rough 1024², 0.0065 E*, PK start, where the
            # residual hovered at 1e-2 for 10⁴ steps): fall back to PK's rule, restart on every entry
            restart_every_entry, params["restart_every_entry_from"] = True, iterations
        elif restart_every_entry and iterations - smallest_at >= STALL_LIMIT:
            stalled = True
            message = (f"stalled: no smaller residual in {STALL_LIMIT} steps (smallest {smallest_residual:.3g} at step "
                       f"{smallest_at}, tol {tol:g}, {half.dtype.name})")
            break
        if iterations >= maxiter:
            message = f"not converged after {iterations} iterations: relative rms gap error {residual:.3g} (tol {tol:g})"
            if residual <= tol:
                message += f", but a penetration {penetration_error:.3g} outside the contact set"
            break
        iterations += 1
        step_incremental = False
        if n_contact == 0:                                  # displacement control lost all contact: restart
            p[:] = _pk_pressure(heights, half, None, flat_position).reshape(-1)
            alpha, beta_allowed = 1.0, False
            n_contact = _restart(p, t, z_in, index, been_in_contact)
        else:
            # (c) conjugate direction, optionally preconditioned: z = M g with M = K⁻¹ (one FFT pair)
            if preconditioned:
                _masked_gap(index, n_contact, u, h, alpha, shift, z_in)
                half.stiffness_into(field(z_in), field(r))
                transforms += 2
                sum_z, descent = _preconditioned_moments(index, n_contact, z_in, r)
                z_mean = sum_z / n_contact if load_control else 0.0
            else:
                descent, z_mean = squared, 0.0
            beta = descent / previous_squared if beta_allowed and previous_squared > 0 else 0.0
            previous_squared = descent
            sum_gt = conjugate_direction(beta)
            if sum_gt <= 0 and beta > 0:                    # not a descent direction: restart the CG
                sum_gt = conjugate_direction(0.0)
            # (d) step length τ = Σ g t / ⟨t, K t⟩, the curvature by Parseval (forward transform only)
            curvature = half.quadratic_form(field(t))
            transforms += 1
            if curvature > 0:
                tau = sum_gt / curvature
            elif tau == 0.0:                                # t = 0 on a gap-free contact set: re-entry only
                tau = 1.0 / half.pixel_compliance
            # (e) projected step on I_c, (f) re-entry of penetrated points (gap before the step)
            n_contact, total, left, entered, first_entries, kept_t = _step_and_reentry(
                p, t, z_in, u, h, alpha, shift, tau, index, been_in_contact)
            # re-entries of points that left keep the CG going, unless the residual stalled
            beta_allowed = (entered if restart_every_entry else first_entries) == 0
            step_incremental = left == 0 and entered == 0 and since_exact < _REFRESH and total > 0
            if step_incremental:                            # the set held: complete K t, u ← α u − τ K t
                half.pending_displacement_into(field(r))
                transforms += 1
                _advance_displacement(u, r, alpha, tau)
            alpha = 1.0
            if load_control:                                # (g), applied lazily through alpha
                if total > 0:
                    alpha = mean_pressure * n_points / total
                else:                                       # every point left: start again from uniform p
                    p[:] = mean_pressure
                    n_contact = _restart(p, t, z_in, index, been_in_contact)
                    beta_allowed = False
        if step_incremental:
            exact, since_exact = False, since_exact + 1
        else:                                               # contact set changed: recompute u exactly
            transforms, exact, since_exact = transforms + recompute_displacement(), True, 0
    if stalled and warm_started:                           # a warm start can lead PK into a cycle that the cold
        del p, u, t, r, z_in, index, been_in_contact        # start avoids: solve again from it
        retry = solve_hard_wall(height_field, half, mean_pressure=mean_pressure if total_force is None else None,
                                total_force=total_force, penetration=penetration, tol=tol, maxiter=maxiter,
                                cold_start=cold_start, callback=callback, preconditioned=preconditioned,
                                interaction=interaction, warn=warn)
        return dataclasses.replace(retry, params={**retry.params, "warm_start_stalled_at": iterations})
    if not exact:
        transforms += recompute_displacement()
    _scale(p, alpha)
    _scale(u, alpha)
    if not converged and warn:
        warnings.warn(message, ConvergenceWarning, stacklevel=2)
    return _result(p, u, h, shift, half, interaction, params, iterations, residuals, converged, message, start,
                   transforms)


def _result(p, u, h, shift, half, interaction, params, iterations, residuals, converged, message, start, transforms):
    grid = half.grid
    gap = np.empty(p.size, half.dtype)
    contact = np.empty(p.size, np.bool_)
    _finalise_gap(u, h, p, shift, gap, contact)
    pressure, displacement = p.reshape(grid.shape), u.reshape(grid.shape)
    gap, contact = gap.reshape(grid.shape), contact.reshape(grid.shape)
    for array in (pressure, displacement, gap, contact):
        array.flags.writeable = False
    params = {**params, "fft_pairs": transforms / 2}
    return ContactResult(
        pressure=pressure, displacement=displacement, gap=gap, contact=contact,
        contact_fraction=float(np.count_nonzero(contact)) / contact.size,
        mean_pressure=float(p.mean(dtype=np.float64)), mean_gap=float(gap.mean(dtype=np.float64)),
        penetration=float(h.max()) - float(shift), elastic_energy=half.elastic_energy(pressure, displacement),
        iterations=int(iterations), residuals=np.asarray(residuals, dtype=np.float64), converged=bool(converged),
        message=message, wall_time=time.perf_counter() - start, params=params,
        contact_pressure=pressure, interaction_traction=np.broadcast_to(np.zeros((), half.dtype), grid.shape),
        flat_position=float(shift), interaction=interaction, control=params["control"], requested=params["requested"])
