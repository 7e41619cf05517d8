"""Contact with a smooth interaction law and the impenetrable flat: the minimum of the total energy over the gap.

Unknown: the gap g ≥ 0 [m] on a periodic grid (``docs/interactions.md``). With u = g + h − s, the body's
displacement fluctuation u_f = (g − ⟨g⟩) + (h − ⟨h⟩) fixes the elastic traction fluctuation p_el = K⁻¹ u_f
(zero mean). The external load λ = ⟨p⟩ [Pa] is the mean traction. Total energy per unit area:

    load control (λ = P̄ fixed, any sign):      Π/A = ½⟨u_f p_el⟩ + ⟨V(g)⟩ + P̄ ⟨g⟩
    flat position s fixed, Φ(0) > 0 (layer):    Π/A = ½⟨u_f p_el⟩ + ⟨V(g)⟩ + ½ ū²/Φ(0),  ū = ⟨g⟩ + ⟨h⟩ − s
    flat position s fixed, Φ(0) = 0:            Π/A = ½⟨u_f p_el⟩ + ⟨V(g)⟩  subject to ⟨g⟩ = s − ⟨h⟩

Its gradient per pixel area, G = p_el + λ − p_int(g), is the wall's contact pressure: the minimum has G = 0
where g > 0 and G ≥ 0 where g = 0 (complementarity). Under load control the flat sits at
s = ⟨g⟩ + ⟨h⟩ − Φ(0) P̄; under the constraint λ is its multiplier.

Method: projected non-linear conjugate gradients (Polak–Ribière⁺) on the free set F = {g > 0} ∪ {g = 0, G < 0},
preconditioned by the compliance K (the inverse of the elastic Hessian; its q = 0 mode given the largest
compliance), with a projected Armijo line search on Π started from the step that minimises the local
quadratic model (curvature ⟨d, K⁻¹ d⟩ − ⟨k d²⟩). Each step costs one FFT pair for z = K r and one for K⁻¹ d,
plus one where the projection clipped the step. Π decreases monotonically. Convergence criterion, with
``gap_scale`` the rms height of h (the law's length on a flat surface):

    sqrt(⟨(K r)²⟩_F) ≤ tol · gap_scale,   r = G on F,

the displacement that the residual traction would still cause. Under load control a tensile load with no
contact left and every pixel pulled harder than the law attracts it has no equilibrium: reported, not
iterated.
"""
from __future__ import annotations

import math
import time
import warnings

import numpy as np

from surfaces import HeightField
from surfaces._checks import check_finite_array, check_integer, check_real

from ._version import __version__
from .contact import ContactResult, SolverState, _heights, solve_contact
from .results import ConvergenceWarning

METHOD = "projected-cg-gap"
ARMIJO = 1e-4            # sufficient-decrease constant of the projected line search
MAX_HALVINGS = 40        # line-search step halvings before the direction is given up
APPROACH = 0.5          # the largest fraction of (gap + law length) by which a point may close in one step
ENERGY_ROUND_OFF = 1e-12  # relative round-off of the energy sums, below which a rise is not a rise


class _Energy:
    """Π/A and its gradient for one control (module docstring); holds the body, law and the fixed fields."""

    def __init__(self, h, half, law, load, flat_position):
        self.half, self.law, self.load, self.flat_position = half, law, load, flat_position
        self.h_mean = float(h.mean(dtype=np.float64))
        self.h_f = h - self.h_mean
        self.uniform = half.uniform_compliance                  # Φ(0) [m/Pa]
        self.constrained = load is None and self.uniform == 0.0
        self.mean_target = None if flat_position is None else flat_position - self.h_mean

    def elastic_traction(self, g, out, work):
        """out ← p_el = K⁻¹ u_f for the flat gap g (one FFT pair); ``work`` (grid-shaped) holds u_f."""
        flat = work.reshape(-1)
        np.subtract(g, float(g.mean(dtype=np.float64)), out=flat)
        flat += self.h_f
        return self.half.stiffness_into(work, out)

    def external_load(self, g_mean, p_el, p_int, free):
        """λ [Pa]: P̄, the layer's ū/Φ(0), or the multiplier that balances the free set's mean residual."""
        if self.load is not None:
            return self.load
        if not self.constrained:
            return (g_mean + self.h_mean - self.flat_position) / self.uniform
        n_free = np.count_nonzero(free)
        if n_free == 0:
            return float(np.mean(p_int - p_el, dtype=np.float64))
        return float(np.mean((p_int - p_el)[free], dtype=np.float64))

    def value(self, g, p_el):
        """Π/A [J/m²] and its three parts' magnitudes (for the round-off allowance)."""
        g_mean = float(g.mean(dtype=np.float64))
        elastic = 0.5 * float(np.dot((g - g_mean + self.h_f).astype(np.float64), p_el.astype(np.float64))) / g.size
        interaction = float(np.mean(self.law.energy(g), dtype=np.float64))
        if self.load is not None:
            external = self.load * g_mean
        elif not self.constrained:
            external = 0.5 * (g_mean + self.h_mean - self.flat_position) ** 2 / self.uniform
        else:
            external = 0.0
        return elastic + interaction + external, abs(elastic) + abs(interaction) + abs(external)


def _restore_mean(g, target):
    """g ← max(g + c, 0) with c such that ⟨g⟩ = target > 0: the Euclidean projection onto {g ≥ 0, ⟨g⟩ = target}
    (Newton on the convex, piecewise linear mean from above: exact in a few passes)."""
    c = target - float(g.mean(dtype=np.float64))
    for _ in range(100):
        shifted = g + c
        positive = shifted > 0
        excess = float(np.sum(shifted[positive], dtype=np.float64)) / g.size - target
        if excess <= 1e-15 * target:
            break
        c -= excess * g.size / max(np.count_nonzero(positive), 1)
    np.maximum(g + c, 0.0, out=g)


def _start_gap(h, half, law, load, flat_position, x0, tol, maxiter):
    """The initial gap [m]: ``x0``'s gap, else the hard-wall solution at the same control where it exists, else the
    undeformed gap with the flat at ``flat_position`` (or touching the highest point); and its name."""
    if isinstance(x0, ContactResult):
        if x0.gap.shape != h.shape:
            raise ValueError(f"x0 has shape {x0.gap.shape}, but the grid has shape {h.shape}")
        return np.array(x0.gap, dtype=half.dtype), "x0"
    if x0 is not None:
        raise TypeError(f"x0 of a smooth interaction must be a ContactResult (its gap starts the solve), got "
                        f"{type(x0).__name__}")
    h_max = float(h.max())
    if load is not None and load > 0:
        start = solve_contact(h, half, mean_pressure=load, tol=max(tol, 1e-6), maxiter=maxiter, warn=False)
    elif flat_position is not None and flat_position < h_max:
        start = solve_contact(h, half, penetration=h_max - flat_position, tol=max(tol, 1e-6), maxiter=maxiter,
                              warn=False)
    else:
        position = h_max if flat_position is None else flat_position
        return (position - h).astype(half.dtype), "rigid"
    return np.array(start.gap, dtype=half.dtype), "hard wall"


def solve_smooth(height_field, half, law, *, mean_pressure=None, total_force=None, penetration=None, tol=1e-8,
                 maxiter=10000, x0=None, callback=None, warn=True) -> ContactResult:
    """Solve the contact of ``height_field`` with the flat under the smooth ``law`` (module docstring).

    Called by :func:`~roughcontact.contact.solve_contact` for a smooth interaction: ``mean_pressure`` [Pa] or
    ``total_force`` [N] of any sign (external load control), or ``penetration`` δ = max(h) − s [m] of any sign.
    ``x0``: a previous result, whose gap starts the solve.
    """
    start = time.perf_counter()
    grid = half.grid
    if not half.periodic:
        raise ValueError("a smooth interaction needs a periodic grid (the gap-based energy uses the exact inverse "
                         "kernel K⁻¹, which the zero-padded free surface does not have); got grid.periodic = "
                         f"{grid.periodic}")
    given = {name: value for name, value in (("mean_pressure", mean_pressure), ("total_force", total_force),
                                             ("penetration", penetration)) if value is not None}
    if len(given) != 1:
        raise ValueError(f"give exactly one of mean_pressure, total_force, penetration; got {sorted(given) or 'none'}")
    (control, requested), = given.items()
    requested = check_real(control, requested)
    tol = check_real("tol", tol, low=0.0, high=1.0, low_open=True, high_open=True)
    check_integer("maxiter", maxiter, low=0)
    if callback is not None and not callable(callback):
        raise TypeError(f"callback must be callable, got {type(callback).__name__}")
    heights = _heights(height_field, half)
    h = heights.reshape(-1)
    load = requested / grid.area if control == "total_force" else requested if control == "mean_pressure" else None
    flat_position = None if load is not None else float(h.max()) - requested
    energy = _Energy(h, half, law, load, flat_position)
    if energy.constrained and energy.mean_target <= 0:
        raise ValueError(f"penetration = {requested!r} m leaves no room for a gap on a periodic half-space: the mean "
                         f"gap ⟨g⟩ = s − ⟨h⟩ must be > 0, i.e. penetration < max(h) − ⟨h⟩ = "
                         f"{float(h.max()) - energy.h_mean!r} m")

    g, start_kind = _start_gap(heights, half, law, load, flat_position, x0, tol, maxiter)
    g = g.reshape(-1)
    np.maximum(g, 0.0, out=g)
    if energy.constrained:
        _restore_mean(g, energy.mean_target)
    deviation = h - energy.h_mean
    gap_scale = float(np.sqrt(np.mean(deviation * deviation, dtype=np.float64))) or law.length or 1.0
    del deviation
    # work arrays (the transforms take and fill arrays of the body's own layout)
    field = grid.shape
    p_el, work, z, w = (half.empty() for _ in range(4))
    d = np.zeros(g.size, half.dtype)
    trial = np.empty(g.size, half.dtype)
    p_trial = half.empty()
    largest_compliance = max(float(half.compliance(2 * math.pi / max(grid.lengths))), energy.uniform)

    def elastic(gap, out):
        return energy.elastic_traction(gap, out, work).reshape(-1)

    pel = elastic(g, p_el)
    value, magnitude = energy.value(g, pel)
    transforms = 2
    residuals, iterations, converged, message = [], 0, False, ""
    previous_rz, tau, since_exact, detached = 0.0, 0.0, 0, False
    r_prev = np.zeros(g.size, half.dtype)
    history = [value]
    while True:
        p_int = law.traction(g)
        g_mean = float(g.mean(dtype=np.float64))
        at_wall = g <= 0
        free0 = ~at_wall
        load_now = energy.external_load(g_mean, pel, p_int, free0)
        gradient = pel + load_now - p_int
        free = free0 | (gradient < 0)
        if energy.constrained:                              # the multiplier of ⟨g⟩ balances the free set
            load_now = energy.external_load(g_mean, pel, p_int, free)
            gradient = pel + load_now - p_int
        r = np.where(free, gradient, 0.0).astype(half.dtype)
        # preconditioned residual z = K r on F (+ the largest compliance for the mean mode), zero mean on F
        # under the ⟨g⟩ constraint
        zf = half.displacement_into(r.reshape(field), z).reshape(-1)
        transforms += 2
        zf += (largest_compliance - energy.uniform) * float(r.mean(dtype=np.float64))
        zf[~free] = 0.0
        if energy.constrained and free.any():
            zf[free] -= float(zf[free].mean(dtype=np.float64))
        residual = float(np.sqrt(np.mean(np.square(zf, dtype=np.float64)))) / gap_scale
        residuals.append(residual)
        if callback is not None and iterations:
            try:
                callback(SolverState(iterations, residual, float(np.count_nonzero(at_wall)) / g.size))
            except StopIteration:
                message = f"halted by callback after {iterations} iterations (relative residual {residual:.3g})"
                break
        if residual <= tol:
            if since_exact:                                 # accept only on an exactly recomputed p_el
                pel, since_exact = elastic(g, p_el), 0
                transforms += 2
                residuals.pop()
                continue
            converged, message = True, f"converged: relative residual {residual:.3g} <= tol {tol:g}"
            break
        if load is not None and load < 0 and not at_wall.any() and float(np.max(-p_int)) < -load:
            detached = True
            message = (f"no equilibrium: the tensile load {load:.6g} Pa exceeds the attraction at every point "
                       f"(largest {float(np.max(-p_int)):.6g} Pa) with no contact left; the body separates "
                       "(beyond pull-off)")
            break
        if iterations >= maxiter:
            message = f"not converged after {iterations} iterations: relative residual {residual:.3g} (tol {tol:g})"
            break
        iterations += 1
        # Polak–Ribière⁺ conjugate direction on F
        rz = float(np.dot(r.astype(np.float64), zf))
        beta = max(0.0, (rz - float(np.dot(r_prev.astype(np.float64), zf))) / previous_rz) if previous_rz > 0 else 0.0
        d *= beta
        d -= zf
        d[~free] = 0.0
        if energy.constrained and free.any():
            d[free] -= float(d[free].mean(dtype=np.float64))
        slope = float(np.dot(gradient.astype(np.float64), d.astype(np.float64)))
        if slope >= 0:                                      # not a descent direction: steepest (preconditioned)
            np.negative(zf, out=d)
            slope = -rz
        previous_rz, r_prev = rz, r
        accepted, tau, transforms, since_exact, step = _line_search(
            g, d, gradient, slope, pel, value, magnitude, energy, law, elastic, w, trial, p_trial, tau, transforms)
        if not accepted and beta > 0:                       # retry along the preconditioned steepest descent
            np.negative(zf, out=d)
            d[~free] = 0.0
            accepted, tau, transforms, since_exact, step = _line_search(
                g, d, gradient, -rz, pel, value, magnitude, energy, law, elastic, w, trial, p_trial, tau, transforms)
        if not accepted:
            message = (f"stalled after {iterations} iterations: no decrease of the energy along the steepest "
                       f"descent (relative residual {residual:.3g}, tol {tol:g})")
            break
        g, trial = trial, g
        pel, p_trial = step, p_el
        p_el = pel.reshape(field)
        value, magnitude = energy.value(g, pel)
        history.append(value)
    if not converged and warn:
        warnings.warn(message, ConvergenceWarning, stacklevel=3)
    return _smooth_result(g, pel, h, heights, half, law, energy, control, requested, iterations, residuals,
                          converged, message, start, transforms, start_kind, tol, maxiter, detached, history)


def _line_search(g, d, gradient, slope, pel, value, magnitude, energy, law, elastic, w, trial, p_trial, tau, transforms):
    """Projected Armijo search along d from the minimiser of the quadratic model; the trial gap in ``trial`` and
    its elastic traction (returned). Returns (accepted, τ, transforms, since_exact flag, p_el of the trial)."""
    half = energy.half
    d_mean = float(d.mean(dtype=np.float64))
    w_flat = half.stiffness_into((d - d_mean).reshape(w.shape), w).reshape(-1)     # K⁻¹ d_f
    transforms += 2
    d64 = d.astype(np.float64)
    curvature = float(np.dot(d64, w_flat)) / d.size - float(np.mean(law.stiffness(g) * d64 * d64))
    if not energy.constrained and energy.load is None:
        curvature += d_mean ** 2 / energy.uniform
    if curvature > 0:
        tau = -slope / d.size / curvature
    else:                                                   # concave along d: step out, the wall or Armijo bound it
        tau = 2 * tau if tau > 0 else -slope / d.size / max(float(np.dot(d64, w_flat)) / d.size, 1e-300)
    approaching = d < 0                                     # at most half of (g + ρ) closer per step: no tunnelling
    if approaching.any():                                   # through an energy barrier into contact
        tau = min(tau, APPROACH * float(np.min((g[approaching] + law.length) / -d[approaching])))
    for _ in range(MAX_HALVINGS):
        np.add(g, tau * d, out=trial)
        clipped = bool((trial < 0).any())
        if clipped:
            np.maximum(trial, 0.0, out=trial)
        if energy.constrained and clipped:
            _restore_mean(trial, energy.mean_target)
        if clipped:
            step = elastic(trial, p_trial)
            transforms += 2
        else:
            step = p_trial.reshape(-1)
            np.add(pel, tau * w_flat, out=step)
        trial_value, _ = energy.value(trial, step)
        predicted = ARMIJO * float(np.dot(gradient.astype(np.float64), (trial - g).astype(np.float64))) / g.size
        if trial_value <= value + predicted + ENERGY_ROUND_OFF * magnitude:
            return True, tau, transforms, int(not clipped), step
        tau *= 0.5
    return False, tau, transforms, 0, pel


def _smooth_result(g, pel, h, heights, half, law, energy, control, requested, iterations, residuals, converged,
                   message, start, transforms, start_kind, tol, maxiter, detached, history):
    grid = half.grid
    g_mean = float(g.mean(dtype=np.float64))
    p_int = law.traction(g)
    load = energy.external_load(g_mean, pel, p_int, g > 0)
    pressure = (pel + load).astype(half.dtype)
    contact = g <= 0
    contact_pressure = np.where(contact, pressure - p_int, 0.0).astype(half.dtype)
    mean_displacement = energy.uniform * load
    displacement = (g - g_mean + energy.h_f + mean_displacement).astype(half.dtype)
    flat_position = g_mean + energy.h_mean - mean_displacement
    shape = grid.shape
    arrays = [a.reshape(shape) for a in (pressure, displacement, g.astype(half.dtype), contact, contact_pressure,
                                         p_int.astype(half.dtype))]
    for array in arrays:
        array.flags.writeable = False
    pressure, displacement, gap, contact, contact_pressure, interaction_traction = arrays
    params = {"E_star": half.E_star, "grid": grid, "tol": tol, "maxiter": int(maxiter), "method": METHOD,
              "start": start_kind, "interaction": type(law).__name__, "kernel": half.description,
              "version": __version__, "control": control, "requested": requested, "fft_pairs": transforms / 2,
              "detached": detached, "energy_history": [float(v) * grid.area for v in history]}
    return ContactResult(
        pressure=pressure, displacement=displacement, gap=gap, contact=contact,
        contact_fraction=float(np.count_nonzero(contact)) / contact.size, mean_pressure=float(load),
        mean_gap=g_mean, penetration=float(heights.max()) - flat_position,
        elastic_energy=half.elastic_energy(pressure, displacement), iterations=int(iterations),
        residuals=np.asarray(residuals, dtype=np.float64), converged=bool(converged), message=message,
        wall_time=time.perf_counter() - start, params=params, contact_pressure=contact_pressure,
        interaction_traction=interaction_traction, flat_position=float(flat_position),
        interaction_energy=float(np.sum(law.energy(g), dtype=np.float64)) * grid.pixel_area, interaction=law,
        control=control, requested=float(requested))
