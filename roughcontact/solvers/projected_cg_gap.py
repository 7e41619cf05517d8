"""Contact with a smooth interaction law (or none: the hard wall) and the impenetrable flat: the minimum of the total
energy over the gap.

Unknown: the gap g ≥ 0 [m] on a periodic grid (``docs/guide/interactions.md``); a free surface is solved as the
periodic body of its zero-padded grid, the law and the wall acting on the window only
(:class:`~roughcontact.body.PaddedOperator`). With u = g + h − s, the body's
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
quadratic model (curvature ⟨d, K⁻¹ d⟩ − ⟨k d²⟩). No point whose gap can be stable closes by more than 2 (g + law
length) in one step (no tunnelling through an energy barrier into contact; a saturated point of the layered law,
a broken column of air breakdown, has none to tunnel through), nor opens by more than that in the
first step along a concave direction (a body pulled off as a whole has no elastic curvature to limit it). Each
step costs one FFT pair for z = K r and one for K⁻¹ d, plus one where the projection clipped the step; the
pointwise work is in fused numba passes (a law's kernel compiled into them,
:attr:`~roughcontact.interactions.Interaction.kernel`; a law without one through its numpy methods).
Π decreases monotonically; a step along which Π is concave (⟨d, K⁻¹ d⟩ ≤ ⟨k d²⟩ plus the layer's mean
term) crosses an instability and is counted on the result (``unstable_steps``). After such a step the next
one skips the model and its K⁻¹ d: it tries twice the last length with the trial's exact p_el, and its own
curvature is that along the step taken, ⟨Δg, Δp_el⟩ − ⟨k Δg²⟩ (a snap-in step: two FFT pairs, not three).

The hard wall (V = 0; :func:`solve_hard_wall_handing_over`, where Polonsky–Keer is slow, and the method by name):
the energy is quadratic and no step is capped, and the preconditioner is the compliance of the body resting on a
foundation of stiffness κ per unit area, Φ/(1 + κΦ) (one FFT pair, as K): the points held at the wall pin the
surface, so the open points cannot follow wavelengths longer than the open regions. With κ = (e/f)/K_ii, f the
open points of the window and e those beside a point at the wall, f/e pixels is the open regions' mean width and
1/κ the compliance of a region that wide; the mean mode gets 1/(1/Φ_max + κ). The solve starts from
Polonsky–Keer's (which may finish it: it stops where slow) and ends with it, from the wall's reaction max(G, 0) on
the points at the wall, so that its result meets PK's criterion (this one bounds the rms of the residual
traction's displacement, which leaves single points √N times that); the gap is minimised to a tenth of tol first
(``GAP_TOL_FACTOR``), which leaves that polish a few steps.

Convergence criterion, with ``gap_scale`` the rms height of h (the law's length on a flat surface):

    sqrt(⟨(K r)²⟩_F) ≤ tol · gap_scale,   r = G on F,

the displacement that the residual traction would still cause. The layered field (a non-local law) is solved to a
tenth of the last residual, within [1e-12, 1e-2] until a trial step is first rejected and [1e-12, 1e-4] from
then on (``FIELD_TOL_START``), and a residual at or below tol is trusted only once its law has
been solved to a tenth of tol or tighter (a snap into full contact leaves F empty and the residual 0 at once, its
field still solved as loosely as at the start). Under load control a tensile load with no contact left and every
pixel pulled harder than the law attracts it has no equilibrium: reported, not iterated.
"""
from __future__ import annotations

import dataclasses
import math
import time
import warnings

import numpy as np
from numba import njit
from numba.extending import overload

from .._version import __version__
from ..electrostatics.field import FieldLaw, FieldSolveStalled
from ..interactions import ElectrostaticInteraction
from ..io.results import ConvergenceWarning
from .inputs import FLOAT32_TOL_FLOOR, Control
from .polonsky_keer import solve_hard_wall
from .result import ContactResult, SolverReport, SolverState
from .starts import hard_wall_start

METHOD = "projected-cg-gap"
ARMIJO = 1e-4             # sufficient-decrease constant of the projected line search
MAX_HALVINGS = 40         # line-search step halvings before the direction is given up
APPROACH = 2.0            # a stable point closes by at most this times (gap + law length) in one step
ENERGY_ROUND_OFF = 1e-12  # relative round-off of the energy sums (float64), below which a rise is not a rise
FIELD_TOL_FACTOR = 0.1   # the layered field's solves to this times the solve's relative residual,
FIELD_TOL_FLOOR = 1e-12  # but no tighter than this
FIELD_TOL_CEILING = 1e-4 # and no looser once a trial step has been rejected;
#: the bound before that (and the start's, whose residual is not known yet). Until a line search first rejects a
#: trial, a field solved to 1 % steers the steps through the snap-in as well as one solved to 1e-4; near contact
#: edges, where short steps gain less energy than a field solved to 1 % is off by, trials are rejected, and from the
#: first one on the bound is FIELD_TOL_CEILING. FFT pairs of the default law, four realisations at 512², 30 / 100 /
#: 200 V, against 1e-4 throughout: bench patch 1.09 / 0.54 / 0.53, scene patch 0.97 / 0.85 / 0.75 (``python
#: studies/bench_field.py --sizes 512 --realisations 4 --contact-line breakdown``, this constant set to 1e-4 for the
#: reference). 1e-2 throughout saves as much there but does not converge near contact edges at fine pixels
#: (``docs/dev/investigations.md``, "The layered field's tolerance").
FIELD_TOL_START = 1e-2
START_RESOLVE = 0.5       # an x0's law solved again while its residual asks for a field this much tighter or more
_REFRESH = 50             # exact recomputation of p_el at least every _REFRESH incremental steps
RETRACT_HALVINGS = 10     # halvings of a cold tensile solve's retract step before its branch is said to end
POLISH_STEPS = 100        # Polonsky–Keer's steps from the hard wall's answer on the gap, at most (0–4 measured)
#: The hard wall's gap minimised to this times tol before the polish: a reaction that close to the answer leaves the
#: polish 0–4 steps instead of 4–13 and the whole solve cheaper. Ten cold loads 0.4 … 4 MPa on the default scene's
#: micro patch, tol 1e-8, FFT pairs summed at factors 1 / 0.3 / 0.1 / 0.03: 1044 / 962 / 938 / 922 on 128², 1148 /
#: 1070 / 1036 / 1027 on 256², the flat positions within 1e-9 rms heights of each other
#: (``python studies/bench_position.py``, ``sweep`` rows, with this constant set so).
GAP_TOL_FACTOR = 0.1


def _law_at(kernel, gap):
    """V [J/m²], p_int = −dV/dg [Pa] and k = dp_int/dg [Pa/m] of a law's ``kernel`` at the gap g
    (:attr:`~roughcontact.interactions.Interaction.kernel`)."""
    return type(kernel).at(gap, kernel)


@overload(_law_at)
def _compiled_law_at(kernel, gap):
    """In numba: the kernel class's own ``at``, compiled for that class and inlined (a static call: each pass that
    evaluates a law has one specialisation per kernel class, cached like the pass)."""
    at = njit(kernel.instance_class.at)
    return lambda kernel, gap: at(gap, kernel)


@njit(cache=True)
def _evaluate_law(kernel, g, window, h_f, pel, traction, stiffness):
    """traction, stiffness ← the law's ``kernel`` at every g in the window (0 outside); returns the sums of
    :func:`_work_terms` and Σ V, in one pass."""
    gap_sum, work, pel_sum, energy_sum = 0.0, 0.0, 0.0, 0.0
    for i in range(g.size):
        if window[i]:
            energy, traction[i], stiffness[i] = _law_at(kernel, g[i])
            energy_sum += energy
        else:
            traction[i], stiffness[i] = 0.0, 0.0
        gap_sum += g[i]
        work += (g[i] + h_f[i]) * pel[i]
        pel_sum += pel[i]
    return gap_sum, work, pel_sum, energy_sum


#: :func:`_evaluate_law` compiled without numba's disk cache, for a kernel class defined outside roughcontact (a
#: user's): the cache's index names every kernel class compiled into it, and a process that cannot import one could
#: not read the index at all. Such a kernel compiles once per process.
_evaluate_user_law = njit(_evaluate_law.py_func)


def _evaluate(law, kernel, g, window, h_f, pel, traction, stiffness) -> tuple:
    """The law's traction and stiffness at g in the window into the two arrays (0 outside; in numba through its
    ``kernel`` where it has one); returns Σ g, Σ (g + h_f) p_el, Σ p_el and Σ V (the sums of Π/A,
    :meth:`_Energy.value`). No law (the hard wall, a law that vanishes): its traction and stiffness stay 0."""
    if not law.smooth or law.vanishes:
        return _work_terms(g, h_f, pel) + (0.0,)
    if kernel is not None:
        cached = type(kernel).__module__.startswith("roughcontact.")
        return (_evaluate_law if cached else _evaluate_user_law)(kernel, g, window, h_f, pel, traction, stiffness)
    traction[:], stiffness[:] = 0.0, 0.0
    inside = g[window]
    traction[window], stiffness[window] = law.traction(inside), law.stiffness(inside)
    energy_sum = float(np.sum(law.energy(inside), dtype=np.float64))
    if not (math.isfinite(energy_sum) and np.isfinite(traction).all() and np.isfinite(stiffness).all()):
        raise ValueError(f"the interaction {type(law).__name__} returned a non-finite energy, traction or stiffness "
                         f"at gaps in [{float(inside.min())!r}, {float(inside.max())!r}] m; a law must be finite at "
                         "every gap g >= 0")
    return _work_terms(g, h_f, pel) + (energy_sum,)


@njit(cache=True)
def _open_mean_imbalance(g, pel, traction):
    """⟨p_int − p_el⟩ over the open points (g > 0), the multiplier of the mean-gap constraint; and their number."""
    total, count = 0.0, 0
    for i in range(g.size):
        if g[i] > 0:
            total += traction[i] - pel[i]
            count += 1
    return total, count


@njit(cache=True)
def _residual(g, pel, traction, load, window, r, free):
    """G = p_el + λ − p_int; the free set F = {g > 0} ∪ {g = 0, G < 0} ∪ (outside the window, where there is no
    wall); r ← G on F, 0 elsewhere. Returns |F|, Σ r, the number of points at the wall and the largest attraction."""
    n_free, sum_r, at_wall, largest_pull = 0, 0.0, 0, 0.0
    for i in range(g.size):
        gradient = pel[i] + load - traction[i]
        largest_pull = max(largest_pull, -traction[i])
        if g[i] > 0 or gradient < 0 or not window[i]:
            free[i] = True
            r[i] = gradient
            n_free += 1
            sum_r += gradient
        else:
            free[i] = False
            r[i] = 0.0
        if g[i] <= 0 and window[i]:
            at_wall += 1
    return n_free, sum_r, at_wall, largest_pull


@njit(cache=True)
def _mask_shift(z, free, shift, r, r_prev):
    """z ← z + shift on F, 0 elsewhere; returns Σ z, Σ z², Σ r z and Σ r_prev z."""
    total, zz, rz, pz = 0.0, 0.0, 0.0, 0.0
    for i in range(z.size):
        if free[i]:
            value = z[i] + shift
            z[i] = value
            total += value
            zz += value * value
            rz += r[i] * value
            pz += r_prev[i] * value
        else:
            z[i] = 0.0
    return total, zz, rz, pz


@njit(cache=True)
def _centre_on_free(values, free, mean):
    for i in range(values.size):
        if free[i]:
            values[i] -= mean


@njit(cache=True)
def _direction(d, z, free, beta, r):
    """d ← β d − z on F, 0 elsewhere; returns Σ d and the slope Σ r d."""
    total, slope = 0.0, 0.0
    for i in range(d.size):
        if free[i]:
            value = beta * d[i] - z[i]
            d[i] = value
            total += value
            slope += r[i] * value
        else:
            d[i] = 0.0
    return total, slope


@njit(cache=True)
def _dot(x, y):
    total = 0.0
    for i in range(x.size):
        total += x[i] * y[i]
    return total


@njit(cache=True)
def _centred_into(d, mean, out):
    for i in range(d.size):
        out[i] = d[i] - mean


@njit(cache=True)
def _fluctuation_into(g, h_f, out):
    """out ← u_f = (g − ⟨g⟩) + h_f, the displacement fluctuation of the gap g."""
    total = 0.0
    for i in range(g.size):
        total += g[i]
    mean = total / g.size
    for i in range(g.size):
        out[i] = g[i] - mean + h_f[i]


@njit(cache=True)
def _closing_limit(g, d, stiffness, inside, length, pixel_compliance, approach, saturation):
    """The step τ by which a stable approaching point of the window (k K_ii < 1) closes by ``approach`` (g + ρ);
    inf for any other point. With ``saturation`` a point of zero stiffness is saturated (the layered law's broken
    column of air breakdown: its attraction stays the broken stress all the way into contact, so there is no
    barrier to tunnel through) and not capped either."""
    if d < 0 and inside and stiffness * pixel_compliance < 1.0 and not (saturation and stiffness == 0.0):
        return approach * (g + length) / -d
    return np.inf


@njit(cache=True)
def _curvature_and_cap(g, d, w, stiffness, window, length, pixel_compliance, approach, saturation):
    """Σ d K⁻¹d, Σ k d², and the largest step τ by which no stable approaching point closes by more than
    ``approach`` (g + ρ) (inf if none)."""
    dw, kdd, cap = 0.0, 0.0, np.inf
    for i in range(d.size):
        dw += d[i] * w[i]
        kdd += stiffness[i] * d[i] * d[i]
        cap = min(cap, _closing_limit(g[i], d[i], stiffness[i], window[i], length, pixel_compliance, approach,
                                      saturation))
    return dw, kdd, cap


@njit(cache=True)
def _cap(g, d, stiffness, window, length, pixel_compliance, approach, saturation):
    """The cap of :func:`_curvature_and_cap` alone."""
    cap = np.inf
    for i in range(d.size):
        cap = min(cap, _closing_limit(g[i], d[i], stiffness[i], window[i], length, pixel_compliance, approach,
                                      saturation))
    return cap


@njit(cache=True)
def _opening_cap(g, d, window, length, approach):
    """The largest step τ by which no point of the window opens by more than ``approach`` (g + ρ) (inf if none
    opens)."""
    cap = np.inf
    for i in range(d.size):
        if d[i] > 0 and window[i]:
            cap = min(cap, approach * (g[i] + length) / d[i])
    return cap


@njit(cache=True)
def _step_curvature(g, trial, pel, step, stiffness):
    """Σ Δg Δp_el − Σ k Δg² and Σ Δg for the step taken, Δg = trial − g, Δp_el = step − pel (exact)."""
    curvature, total = 0.0, 0.0
    for i in range(g.size):
        dg = trial[i] - g[i]
        curvature += dg * (step[i] - pel[i] - stiffness[i] * dg)
        total += dg
    return curvature, total


@njit(cache=True)
def _trial_gap(g, d, tau, r, window, trial):
    """trial ← g + τ d, clipped at 0 in the window; returns whether any point was clipped and Σ r (trial − g)."""
    clipped, predicted = False, 0.0
    for i in range(g.size):
        value = g[i] + tau * d[i]
        if value < 0 and window[i]:
            value = 0.0
            clipped = True
        trial[i] = value
        predicted += r[i] * (value - g[i])
    return clipped, predicted


@njit(cache=True)
def _advance_traction(pel, w, tau, out):
    for i in range(pel.size):
        out[i] = pel[i] + tau * w[i]


@njit(cache=True)
def _work_terms(gap, h_f, pel):
    """Σ g, Σ (g + h_f) p_el and Σ p_el: the elastic energy ½⟨u_f p_el⟩ without a pass over u_f."""
    gap_sum, work, total = 0.0, 0.0, 0.0
    for i in range(gap.size):
        gap_sum += gap[i]
        work += (gap[i] + h_f[i]) * pel[i]
        total += pel[i]
    return gap_sum, work, total


@njit(cache=True)
def _restore_mean(g, target):
    """g ← max(g + c, 0) with c such that ⟨g⟩ = target > 0: the Euclidean projection onto {g ≥ 0, ⟨g⟩ = target}
    (Newton on the convex, piecewise linear mean, from above: exact in a few passes)."""
    n = g.size
    total = 0.0
    for i in range(n):
        total += g[i]
    c = target - total / n
    for _ in range(100):
        excess, positive = 0.0, 0
        for i in range(n):
            value = g[i] + c
            if value > 0:
                excess += value
                positive += 1
        excess = excess / n - target
        if excess <= 1e-15 * target or positive == 0:
            break
        c -= excess * n / positive
    for i in range(n):
        g[i] = max(g[i] + c, 0.0)


@njit(cache=True)
def _pinning_edge(g, nx, ny, periodic):
    """The open points of the window g[:nx, :ny] (g > 0) and those among them with a 4-neighbour at the wall
    (neighbours across the window's edges only where ``periodic``): (beside the wall, open)."""
    edge, n_open = 0, 0
    for i in range(nx):
        for j in range(ny):
            if g[i, j] <= 0:
                continue
            n_open += 1
            for a, b in ((i - 1, j), (i + 1, j), (i, j - 1), (i, j + 1)):
                if periodic:
                    a, b = a % nx, b % ny
                elif a < 0 or a >= nx or b < 0 or b >= ny:
                    continue
                if g[a, b] <= 0:
                    edge += 1
                    break
    return edge, n_open


class _Energy:
    """Π/A for one control (module docstring): the load term and the elastic traction of a gap field."""

    def __init__(self, h, operator, load, flat_position):
        self.operator, self.load, self.flat_position = operator, load, flat_position
        self.h_mean = float(h.mean(dtype=np.float64))
        self.h_f = (h - self.h_mean).astype(operator.dtype)
        self.uniform = operator.uniform_compliance                  # Φ(0) [m/Pa]
        self.constrained = load is None and self.uniform == 0.0
        self.mean_target = None if flat_position is None else flat_position - self.h_mean

    def elastic_traction(self, g, out, work):
        """out ← p_el = K⁻¹ u_f for the flat gap g (one FFT pair); ``work`` (grid-shaped) holds u_f."""
        _fluctuation_into(g, self.h_f, work.reshape(-1))
        return self.operator.stiffness_into(work, out).reshape(-1)

    def external_load(self, g, pel, traction):
        """λ [Pa] at the gap g: P̄, the layer's ū/Φ(0), or (under the ⟨g⟩ constraint) the multiplier that
        balances the open points' mean traction."""
        if self.load is not None:
            return self.load
        if not self.constrained:
            return (float(g.mean(dtype=np.float64)) + self.h_mean - self.flat_position) / self.uniform
        imbalance, n_open = _open_mean_imbalance(g, pel, traction)
        return imbalance / max(n_open, 1)

    def value(self, g_sum, work, pel_sum, energy_sum, n):
        """Π/A [J/m²] from the pass sums, and the magnitude of its parts (for the round-off allowance)."""
        g_mean = g_sum / n
        elastic = 0.5 * (work - g_mean * pel_sum) / n
        interaction = energy_sum / n
        if self.load is not None:
            external = self.load * g_mean
        elif not self.constrained:
            external = 0.5 * (g_mean + self.h_mean - self.flat_position) ** 2 / self.uniform
        else:
            external = 0.0
        return elastic + interaction + external, abs(elastic) + abs(interaction) + abs(external)


def solve_smooth(problem, control: Control) -> ContactResult:
    """Solve the checked ``problem`` (a :class:`~roughcontact.solvers.problem.ContactProblem` with a smooth law, or
    the hard wall: :func:`solve_wall`) at the checked ``control`` (module docstring): an external load of any sign,
    or a penetration δ = max(h) − s [m] of any sign; ``control.x0``, a previous result, starts the solve from its
    gap.
    """
    law, load = problem.interaction, control.mean_pressure
    if not law.smooth or law.vanishes:
        return solve_wall(problem, control)
    start = time.perf_counter()
    if control.x0 is None and load is not None and load < 0 and not (law.strength is not None and -load > law.strength):
        return _retract_to(problem, control, start)
    return _minimise(problem, control, *hard_wall_start(problem, control, solve_hard_wall_handing_over), start)


def solve_hard_wall_handing_over(problem, control: Control, *, cold_start="nested", preconditioned=None
                                 ) -> ContactResult:
    """Polonsky–Keer's solve of the hard wall (or a law that vanishes), continued on the gap where it is slow: the
    registry's ``"polonsky-keer"``. Under displacement control on a periodic body with ⟨u⟩ = 0 a uniform pressure
    on a contact set that covers most of the grid hardly moves the surface, and PK's CG crawls along that mode
    near full contact; on a layered periodic body whose long wavelengths are far more compliant than its pixels (a
    stiff skin layer on a soft substrate) its contact set also cycles under load control. So on a periodic body
    (under load control a 2-D grid), preconditioned (the plain CG gains only about a decade in ten steps), PK
    runs with ``slow_exit`` and, where it stops so, :func:`solve_wall` continues from its result. Arguments as
    :func:`~roughcontact.solvers.polonsky_keer.solve_hard_wall`'s. Where PK would run so and ``control.x0`` is a
    result solved on the gap (:func:`solved_on_the_gap`: PK was slow on this body before), the solve continues on
    the gap from its gap at once (a load sweep's warm steps, :func:`~roughcontact.solvers.sweep.load_steps`)."""
    body = problem.body
    profile = body.grid.is_profile
    slow_mode = body.periodic and (not profile if preconditioned is None else preconditioned) and \
        (not profile if control.mean_pressure is not None else body.uniform_compliance == 0.0)
    if slow_mode and solved_on_the_gap(control.x0):
        return solve_wall(problem, control)
    first = solve_hard_wall(problem, dataclasses.replace(control, warn=False), cold_start=cold_start,
                            preconditioned=preconditioned, slow_exit=slow_mode)
    if "slow_exit_at" in first.solver.details:
        return solve_wall(problem, control, first)
    if not first.converged and control.warn:
        warnings.warn(first.message, ConvergenceWarning, stacklevel=3)
    return first


def solved_on_the_gap(result) -> bool:
    """Whether ``result`` (a warm start ``x0``: a result, an array or None) is the hard wall's solve on the gap
    (:func:`solve_wall`'s, handed over from Polonsky–Keer or started on the gap; its ``details`` have
    ``gap_iterations``)."""
    return isinstance(result, ContactResult) and "gap_iterations" in result.solver.details


def solve_wall(problem, control: Control, first=None) -> ContactResult:
    """The hard wall (or a law that vanishes) on the gap (module docstring): from ``first`` (Polonsky–Keer's result,
    slow), else from ``control.x0`` where it is a result (its gap), else from Polonsky–Keer's solve with
    ``slow_exit`` (from ``x0``'s pressure field, or cold; returned where it converges); the gap minimised to tol ×
    ``GAP_TOL_FACTOR`` (in float32 not below its round-off floor), then Polonsky–Keer's polish (at most
    ``POLISH_STEPS`` steps; none where the gap did not converge) from the wall's reaction. The result's ``details``
    are the polish's, with ``gap_iterations``, ``polish_iterations`` and, after a slow start, ``handed_over_at``
    (PK's step) and the start's ``nested_iterations``; its ``iterations``, ``fft_pairs`` and ``residuals`` count
    every phase."""
    start = time.perf_counter()
    if first is None and not isinstance(control.x0, ContactResult):
        first = solve_hard_wall(problem, dataclasses.replace(control, warn=False), slow_exit=True)
        if "slow_exit_at" not in first.solver.details:
            if not first.converged and control.warn:
                warnings.warn(first.message, ConvergenceWarning, stacklevel=3)
            return first
    begin = control.x0 if first is None else first
    kind = "x0" if first is None else f"polonsky-keer from {first.solver.start}, slow at step {first.iterations}"
    # float32's gap gets no closer than its round-off floor (below it the solve runs to maxiter)
    floor = FLOAT32_TOL_FLOOR if problem.body.dtype == np.float32 else 0.0
    gap_tol = max(control.tol * GAP_TOL_FACTOR, min(control.tol, floor))
    gap = _minimise(problem, dataclasses.replace(control, tol=gap_tol, warn=False), begin, kind,
                    0.0 if first is None else first.solver.fft_pairs, start)
    reaction = np.where(gap.contact, np.maximum(gap.pressure, 0.0), 0.0).astype(problem.body.dtype)
    polish = solve_hard_wall(problem, dataclasses.replace(        # (none where the gap stopped unconverged)
        control, x0=reaction if reaction.any() else None, callback=None, warn=False,
        maxiter=min(control.maxiter, POLISH_STEPS) if gap.converged else 0))
    converged = gap.converged and polish.converged
    steps = gap.iterations + polish.iterations + (0 if first is None else first.iterations)
    details = {**polish.solver.details, "gap_iterations": gap.iterations, "polish_iterations": polish.iterations}
    if first is not None:
        details |= {"handed_over_at": first.iterations, "nested_iterations": first.solver.details["nested_iterations"]}
    report = dataclasses.replace(
        polish.solver, method=METHOD, start=kind, converged=converged,
        message=polish.message if gap.converged else gap.message, iterations=steps,
        residuals=np.concatenate([gap.solver.residuals, polish.solver.residuals]),
        fft_pairs=gap.solver.fft_pairs + polish.solver.fft_pairs, wall_time=time.perf_counter() - start,
        details=details)
    if not converged and control.warn:
        warnings.warn(report.message, ConvergenceWarning, stacklevel=3)
    return dataclasses.replace(polish, solver=report)


def _minimise(problem, control, begin, start_kind, start_pairs, start) -> ContactResult:
    """The minimisation from ``begin`` (a result, or None: the undeformed surface), named ``start_kind`` and costing
    ``start_pairs`` FFT pairs, the solve's clock started at ``start``."""
    body, law, heights = problem.body, problem.interaction, problem.heights
    grid = body.grid
    load, requested = control.mean_pressure, control.value
    flat_position = None if load is not None else float(heights.max()) - requested
    nx, ny = grid.shape
    if body.periodic:                                       # the grid itself
        operator, h = body, heights.reshape(-1)
        window = np.ones(h.size, np.bool_)
        largest_compliance = max(float(body.compliance(2 * math.pi / max(grid.lengths))), body.uniform_compliance)
    else:                                                   # the window in the corner of the padded grid
        operator = body.padded_operator()
        padded = np.zeros(body.transform_shape)
        padded[:nx, :ny] = heights
        h = padded.reshape(-1)
        window = np.zeros(body.transform_shape, np.bool_)
        window[:nx, :ny] = True
        window = window.reshape(-1)
        largest_compliance = operator.largest_compliance
    scale_to_operator = h.size / heights.size       # external load per operator pixel = per window pixel / this
    energy = _Energy(h, operator, None if load is None else load / scale_to_operator, flat_position)
    if energy.constrained and energy.mean_target <= 0:
        raise ValueError(f"penetration = {requested!r} m leaves no room for a gap on a periodic half-space: the mean "
                         f"gap ⟨g⟩ = s − ⟨h⟩ must be > 0, i.e. penetration < max(h) − ⟨h⟩ = "
                         f"{float(h.max()) - energy.h_mean!r} m")
    g, start_pairs = _start_gap(begin, h, operator, window, heights, flat_position, start_pairs)
    if energy.constrained:
        _restore_mean(g, energy.mean_target)
    deviation = heights - float(heights.mean(dtype=np.float64))
    gap_scale = float(np.sqrt(np.mean(deviation * deviation, dtype=np.float64))) or law.length or 1.0
    state = _Solver(g, energy, law, gap_scale, start_pairs, window, largest_compliance, scale_to_operator, grid)
    return state.run(control.tol, control.maxiter, control.callback, control.warn, body, heights, control.kind,
                     requested, start_kind, start)


def _retract_to(problem, control, start) -> ContactResult:
    """A cold solve under the tensile load ``load`` [Pa] (< 0, within the law's strength): the equilibrium at zero
    load, then a quasi-static retract along its branch to ``load``, each solve from the last equilibrium, the step
    halved where a solve finds none (at most ``RETRACT_HALVINGS`` times). A cold descent from the undeformed
    surface would not follow the branch: it separates where a retract stays attached. Returns the equilibrium at
    ``load`` (start "retract from 0 Pa"; ``details["retract_loads"]`` the loads solved), or, where the branch
    ends first, the detached result, its message bracketing the branch's pull-off."""
    load = control.mean_pressure
    attached = solve_smooth(problem, control.at(mean_pressure=0.0, warn=False))
    solved, pairs, trial = [0.0], attached.solver.fft_pairs, attached
    attached_load, step = 0.0, -load
    while attached.converged and attached_load > load:
        trial = solve_smooth(problem, control.at(mean_pressure=max(load, attached_load - step), x0=attached,
                                                 warn=False))
        solved.append(trial.requested)
        pairs += trial.solver.fft_pairs
        if trial.converged:
            attached, attached_load = trial, trial.requested
        elif step <= -load * 0.5 ** RETRACT_HALVINGS:
            break
        else:
            step *= 0.5
    message = trial.message
    if trial.detached:
        message = (f"detached: the branch retracted from zero load has no equilibrium beyond {attached_load:.6g} Pa "
                   f"(it separates at {trial.requested:.6g} Pa), so {load:.6g} Pa lies beyond its pull-off")
    elif not attached.converged:
        message = f"the zero-load start of the retract did not converge: {attached.message}"
    report = dataclasses.replace(trial.solver, message=message, start="retract from 0 Pa", fft_pairs=pairs,
                                 wall_time=time.perf_counter() - start,
                                 details={**trial.solver.details, "retract_loads": solved})
    if not report.converged and control.warn:
        warnings.warn(message, ConvergenceWarning, stacklevel=4)
    return dataclasses.replace(trial, solver=report, control=control.kind, requested=float(control.value))


def _start_gap(begin, h, operator, window, heights, flat_position, start_pairs):
    """The starting gap on the operator's grid (flat) from the start's gap (periodic) or from its traction and flat
    position (padded free surface: the padding's displacement is K_T of the window's traction); clipped at 0 in
    the window. Returns it and the FFT pairs spent."""
    if begin is None:                                       # the undeformed surface under the flat
        position = float(heights.max()) if flat_position is None else flat_position
        g = (position - h).astype(operator.dtype)
    elif window.all():
        g = np.array(begin.gap, dtype=operator.dtype).reshape(-1)
    else:
        traction = operator.empty()
        traction[...] = 0.0
        nx, ny = heights.shape
        traction[:nx, :ny] = begin.pressure
        displacement = operator._displacement_into(traction, operator.empty())
        g = (displacement.reshape(-1) - h + begin.flat_position).astype(operator.dtype)
        start_pairs += 1.0
    g[window] = np.maximum(g[window], 0.0)
    return g, start_pairs


class _Solver:
    """The work arrays and the iteration of :func:`solve_smooth` (fields, not closures, so that each step's
    buffers swap without allocation)."""

    def __init__(self, g, energy, law, gap_scale, start_pairs, window, largest_compliance, scale_to_operator, grid):
        operator = energy.operator
        self.energy, self.law, self.operator, self.gap_scale = energy, law, operator, gap_scale
        self.window, self.largest_compliance, self.scale_to_operator = window, largest_compliance, scale_to_operator
        self.kernel = law.kernel
        self.wall = not law.smooth or law.vanishes             # the hard wall: pinned preconditioner, no step cap
        self.approach = math.inf if self.wall else APPROACH
        self.periodic, self.grid_shape = bool(window.all()), grid.shape
        n, dtype = g.size, operator.dtype
        self.n = n
        self.g, self.trial = g, np.empty(n, dtype)
        self.pel_field, self.trial_field, self.work, self.z_field, self.w_field = (operator.empty() for _ in range(5))
        self.d, self.r, self.r_prev = np.zeros(n, dtype), np.zeros(n, dtype), np.zeros(n, dtype)
        self.free = np.zeros(n, np.bool_)
        self.window_view = tuple(slice(0, m) for m in grid.shape)  # the grid in the corner of the operator's fields
        # the layered law, evaluated by field solves on the window; it also carries its unit-voltage flux and
        # column elastance per point (zero outside the window)
        self.field_ceiling = FIELD_TOL_START                   # the field's bound, until a trial is rejected
        self.field = FieldLaw(law.stack, law.voltage, grid, tol=FIELD_TOL_START, contact_line=law.contact_line) \
            if isinstance(law, ElectrostaticInteraction) and not law.local else None
        arrays = 2 if self.field is None else 4
        # the layered law's stiffness is positive wherever its column is unbroken: zero marks a saturated point
        self.saturation = self.field is not None
        self.law_now = [np.zeros(n, dtype) for _ in range(arrays)]     # p_int, k at g (and D₁, R)
        self.law_trial = [np.zeros(n, dtype) for _ in range(arrays)]   # the same at the trial gap
        self.pixel_compliance = operator.pixel_compliance
        # float32 fields carry the energy's terms to a few ε32: a smaller rise is round-off, not a rise
        self.round_off = max(ENERGY_ROUND_OFF, 3 * float(np.finfo(dtype).eps))
        self.transforms = 2 * start_pairs                      # the start's solve included
        self.unstable_steps = 0                                # accepted steps along which Π was concave
        self.snapping = False                                  # whether the last accepted step was concave

    def elastic(self, gap, field):
        self.transforms += 2
        return self.energy.elastic_traction(gap, field, self.work)

    def evaluate(self, gap, pel, arrays):
        """Π/A, its magnitude and Σ V at ``gap`` with elastic traction ``pel``; the law evaluated into ``arrays``."""
        if self.field is None:
            sums = _evaluate(self.law, self.kernel, gap, self.window, self.energy.h_f, pel, *arrays)
        else:
            sums = _work_terms(gap, self.energy.h_f, pel) + (self.evaluate_field(gap, arrays),)
        return self.energy.value(*sums, self.n) + (sums[-1],)

    def evaluate_field(self, gap, arrays):
        """The layered law's traction, stiffness and flux at ``gap`` into ``arrays`` (window only), warm-started
        from the accepted gap's flux; returns Σ V."""
        shape, inside = self.pel_field.shape, self.window_view
        traction, stiffness, flux, columns = (array.reshape(shape)[inside] for array in arrays)
        start = None
        if self.field.evaluations:                     # the accepted gap's columns and flux
            start = tuple(array.reshape(shape)[inside] for array in (self.law_now[3], self.law_now[2]))
        try:
            return self.field.evaluate(gap.reshape(shape)[inside], traction, stiffness, flux, columns, start=start)
        except FieldSolveStalled as error:          # whether it wrote the accepted gap's law (as far as it got)
            error.accepted = arrays is self.law_now
            raise

    def run(self, tol, maxiter, callback, warn, body, heights, control, requested, start_kind, start):
        energy, operator, n = self.energy, self.operator, self.n
        pel = self.elastic(self.g, self.pel_field)
        history, residuals, interaction = [], [], 0.0
        iterations, converged, message, detached = 0, False, "", False
        previous_rz, tau, since_exact = 0.0, 0.0, 0
        # the tolerance the accepted gap's law was solved to (at the start, FieldLaw's first)
        law_tol = FIELD_TOL_START if self.field is not None else 0.0
        accept_tol = max(FIELD_TOL_FLOOR, FIELD_TOL_FACTOR * tol)   # and the one it needs to be accepted
        try:
            value, magnitude, interaction = self.evaluate(self.g, pel, self.law_now)
            history.append(value)
            while True:
                g, d, r, free = self.g, self.d, self.r, self.free
                traction = self.law_now[0]
                load = energy.external_load(g, pel, traction)
                n_free, sum_r, at_wall, largest_pull = _residual(g, pel, traction, load, self.window, r, free)
                # preconditioned residual z = K r on F (+ the largest compliance for the mean mode); zero mean on F
                # under the ⟨g⟩ constraint
                z, mean_compliance = self.precondition(r)
                self.transforms += 2
                sum_z, zz, rz, prz = _mask_shift(z, free, mean_compliance * sum_r / n, r, self.r_prev)
                if energy.constrained and n_free:           # centred on F, and the moments of the centred z
                    _, zz, rz, prz = _mask_shift(z, free, -sum_z / n_free, r, self.r_prev)
                residual = math.sqrt(zz / n) / self.gap_scale
                residuals.append(residual)
                if self.field is not None:                  # the field solves as accurate as the step needs
                    self.field.tol = min(self.field_ceiling, max(FIELD_TOL_FLOOR, FIELD_TOL_FACTOR * residual))
                    if self.field.tol < START_RESOLVE * law_tol and not iterations:
                        # a start near its equilibrium (x0): its law solved again, warm, as tightly as its residual
                        # asks, before that residual is trusted (until it asks for no field much tighter)
                        value, magnitude, interaction = self.evaluate(g, pel, self.law_now)
                        law_tol = self.field.tol
                        history[-1] = value
                        residuals.pop()
                        continue
                if callback is not None and iterations:
                    try:
                        callback(SolverState(iterations, residual, at_wall / heights.size))
                    except StopIteration:
                        message = f"halted by callback after {iterations} iterations (relative residual {residual:.3g})"
                        break
                if residual <= tol:
                    if since_exact:                             # accept only on an exactly recomputed p_el
                        pel, since_exact = self.elastic(g, self.pel_field), 0
                        residuals.pop()
                        continue
                    if law_tol > accept_tol:
                        # a residual that fell past its law's accuracy (a snap into full contact empties F: 0 at
                        # once): the law solved again, warm, as tightly as that residual asks, before it is trusted
                        value, magnitude, interaction = self.evaluate(g, pel, self.law_now)
                        law_tol = self.field.tol
                        history[-1] = value
                        residuals.pop()
                        continue
                    converged, message = True, f"converged: relative residual {residual:.3g} <= tol {tol:g}"
                    break
                message = self.detachment(at_wall, largest_pull, start_kind)
                if message:
                    detached = True
                    break
                if iterations >= maxiter:
                    message = (f"not converged after {iterations} iterations: relative residual {residual:.3g} "
                               f"(tol {tol:g})")
                    break
                iterations += 1
                beta = max(0.0, (rz - prz) / previous_rz) if previous_rz > 0 else 0.0     # Polak–Ribière⁺
                accepted, step = False, None
                for attempt_beta in ((beta, 0.0) if beta > 0 else (0.0,)):
                    if attempt_beta == 0.0 and beta > 0:        # retry along the preconditioned steepest descent
                        d[:] = 0.0
                    sum_d, slope = _direction(d, z, free, attempt_beta, r)
                    if energy.constrained and n_free:       # centred on F: Σ r (d − m) = slope − m Σ r
                        _centre_on_free(d, free, sum_d / n_free)
                        slope -= sum_d / n_free * sum_r
                        sum_d = 0.0
                    if slope >= 0:                              # not a descent direction
                        continue
                    accepted, tau, step, since_exact, step_value = self.line_search(slope, sum_d, pel, value, magnitude,
                                                                                    tau, since_exact)
                    if accepted:
                        break
                if not accepted:
                    message = (f"stalled after {iterations} iterations: no decrease of the energy along the steepest "
                               f"descent (relative residual {residual:.3g}, tol {tol:g})")
                    break
                self.g, self.trial = self.trial, self.g
                self.pel_field, self.trial_field = self.trial_field, self.pel_field
                self.law_now, self.law_trial = self.law_trial, self.law_now
                law_tol = self.field.tol if self.field is not None else 0.0
                self.r, self.r_prev = self.r_prev, self.r
                previous_rz = rz
                pel = step
                value, magnitude, interaction = step_value
                history.append(value)
        except FieldSolveStalled as error:              # report the last accepted state, its law as last solved
            message = f"stopped after {iterations} iterations: {error}"
            if error.accepted and error.energy is not None:     # the start's field, or the accepted gap's again
                interaction = error.energy
        if not converged and warn:
            warnings.warn(message, ConvergenceWarning, stacklevel=4)
        return self.result(pel, interaction, body, heights, control, requested, iterations, residuals, converged,
                           message, start, start_kind, tol, maxiter, detached, history)

    def precondition(self, r):
        """z = K r on the operator's grid, and the compliance its mean mode gets beyond the multiplier's: the
        largest; for the hard wall the compliance on the pinning foundation, Φ/(1 + κΦ) and 1/(1/Φ_max + κ)
        (module docstring)."""
        operator, field = self.operator, self.z_field
        if not self.wall:
            z = operator._displacement_into(r.reshape(field.shape), field).reshape(-1)
            return z, self.largest_compliance - self.energy.uniform
        beside_wall, n_open = _pinning_edge(self.g.reshape(field.shape), *self.grid_shape, self.periodic)
        foundation = beside_wall / max(n_open, 1) / self.pixel_compliance            # κ [Pa/m]
        z = operator._foundation_displacement_into(r.reshape(field.shape), field, foundation).reshape(-1)
        uniform = self.energy.uniform / (1.0 + foundation * self.energy.uniform)
        return z, 1.0 / (1.0 / self.largest_compliance + foundation) - uniform

    def detachment(self, at_wall, largest_pull, start_kind) -> str:
        """Why a tensile load P̄ < 0 has no equilibrium here ("" while it may have one): P̄ beyond the law's
        ``strength`` σ_max (the mean traction ⟨p_int⟩ + ⟨contact pressure⟩ ≥ −σ_max can never balance it: none at
        any gap), or, with no contact left, every point pulled off harder than the law attracts it (the energy
        falls without bound as the body recedes: it separates along the path from this start)."""
        load = self.energy.load
        if load is None or load >= 0:
            return ""
        tension, strength = -load * self.scale_to_operator, self.law.strength
        if strength is not None and tension > strength:
            return (f"detached: no equilibrium at any gap, since the tensile load {-tension:.6g} Pa exceeds the "
                    f"strongest attraction of the law, {strength:.6g} Pa (the mean traction can never balance it)")
        if at_wall == 0 and largest_pull < tension:
            return (f"detached: no contact left and the tensile load {-tension:.6g} Pa exceeds the attraction at every "
                    f"point (largest {largest_pull:.6g} Pa), so the body separates along the path from its start "
                    f"({start_kind}): beyond the pull-off of the branch followed")
        return ""

    def line_search(self, slope, sum_d, pel, value, magnitude, tau, since_exact):
        """Projected Armijo search along d. Where the last step was concave (the solve is crossing an instability)
        it first tries twice that step's length, evaluated exactly, without the model's FFT pair; otherwise, or if
        that fails, it starts from the minimiser of the quadratic model along d (twice the last length where Π is
        concave along d) and halves. Every first try is capped so that no stable point tunnels into contact, and a
        concave one with no last length opens no point by more than 2 (g + ρ).
        Returns (accepted, τ, the trial's p_el, steps since an exact p_el, the trial's Π/A, its magnitude and Σ V
        (None if rejected))."""
        operator, n, g, d = self.operator, self.n, self.g, self.d
        stiffness, length = self.law_now[1], float(self.law.length)
        rejected = math.inf                                 # the snap-in try's length, if Armijo rejected it
        if self.snapping:
            first = min(2 * tau, _cap(g, d, stiffness, self.window, length, self.pixel_compliance, self.approach,
                                      self.saturation))
            trial = self.trial_step(first, None, pel, value, magnitude, since_exact)
            if trial is not None:                           # concave along the step taken: the next one snaps too
                curvature, total = _step_curvature(g, self.trial, pel, trial[0], stiffness)
                self.snapping = self.curvature(curvature / n, total / n) <= 0
                self.unstable_steps += self.snapping
                return (True, first) + trial
            rejected = first
            self.tighten_field()
        self.snapping = False
        d_mean = sum_d / n
        _centred_into(d, d_mean, self.work.reshape(-1))
        w = operator.stiffness_into(self.work, self.w_field).reshape(-1)        # K⁻¹ d_f
        self.transforms += 2
        dw, kdd, cap = _curvature_and_cap(g, d, w, stiffness, self.window, length, self.pixel_compliance,
                                          self.approach, self.saturation)
        curvature = self.curvature((dw - kdd) / n, d_mean)
        concave = curvature <= 0
        if not concave:
            tau = min(-slope / n / curvature, cap)
        else:                                               # concave along d: step out; the caps and Armijo bound it
            # with no last length, the elastic model's, no point opening by more than 2 (g + ρ): the body's opening
            # as a whole has no elastic curvature, and a tensile load beyond pull-off would take it out of range
            first = 2 * tau if tau > 0 else min(-slope / max(dw, 1e-300),
                                                _opening_cap(g, d, self.window, length, APPROACH))
            tau = min(first, cap, rejected / 2)
        for _ in range(MAX_HALVINGS):
            trial = self.trial_step(tau, w, pel, value, magnitude, since_exact)
            if trial is not None:
                self.snapping = concave
                self.unstable_steps += concave
                return (True, tau) + trial
            self.tighten_field()
            tau *= 0.5
        return False, tau, pel, since_exact, None

    def tighten_field(self):
        """A rejected trial: the layered field's solves bounded by FIELD_TOL_CEILING from here on (the next trial's
        included)."""
        if self.field is not None and self.field_ceiling > FIELD_TOL_CEILING:
            self.field_ceiling = FIELD_TOL_CEILING
            self.field.tol = min(self.field.tol, FIELD_TOL_CEILING)

    def curvature(self, curvature, mean):
        """Π's curvature per unit area along a step from Σ Δg K⁻¹Δg − Σ k Δg² over n and ⟨Δg⟩: plus the layer's
        uniform compression ⟨Δg⟩²/Φ(0) where the flat position is fixed."""
        if not self.energy.constrained and self.energy.load is None:
            curvature += mean ** 2 / self.energy.uniform
        return curvature

    def trial_step(self, tau, w, pel, value, magnitude, since_exact):
        """The trial gap g + τ d projected onto g ≥ 0 (and ⟨g⟩ restored under that constraint) into ``trial``, and
        its p_el: τ w added where nothing was clipped and ``w`` = K⁻¹d is given, else exact. Returns (p_el, steps
        since an exact p_el, (Π/A, its magnitude, Σ V)) if the trial passes the Armijo test, else None."""
        energy, n, g, trial, r = self.energy, self.n, self.g, self.trial, self.r
        clipped, predicted = _trial_gap(g, self.d, tau, r, self.window, trial)
        if clipped and energy.constrained:
            _restore_mean(trial, energy.mean_target)
            predicted = _dot(r, trial) - _dot(r, g)
        exact = w is None or clipped or since_exact >= _REFRESH
        if exact:
            step = self.elastic(trial, self.trial_field)
        else:
            step = self.trial_field.reshape(-1)
            _advance_traction(pel, w, tau, step)
        evaluated = self.evaluate(trial, step, self.law_trial)
        if evaluated[0] <= value + ARMIJO * predicted / n + self.round_off * magnitude:
            return step, 0 if exact else since_exact + 1, evaluated
        return None

    def result(self, pel, interaction, body, heights, control, requested, iterations, residuals, converged, message,
               start, start_kind, tol, maxiter, detached, history):
        """The ContactResult on the window (the whole grid when periodic)."""
        energy, law, g = self.energy, self.law, self.g
        grid = body.grid
        g_mean = float(g.mean(dtype=np.float64))
        traction = self.law_now[0]
        load = energy.external_load(g, pel, traction)
        mean_displacement = energy.uniform * load
        flat_position = g_mean + energy.h_mean - mean_displacement
        nx, ny = grid.shape
        operator_shape = self.pel_field.shape

        def window(values):
            return np.array(values.reshape(operator_shape)[:nx, :ny], dtype=body.dtype)

        pressure = window(pel + load)
        displacement = window(g - g_mean + energy.h_f + mean_displacement)
        gap, traction = window(g), window(traction)
        contact = gap <= 0
        contact_pressure = np.where(contact, pressure - traction, 0.0).astype(body.dtype)
        for array in (pressure, displacement, gap, contact, contact_pressure, traction):
            array.flags.writeable = False
        report = SolverReport(
            method=METHOD, converged=bool(converged), message=message, iterations=int(iterations),
            residuals=np.asarray(residuals, dtype=np.float64), tol=tol, maxiter=int(maxiter), start=start_kind,
            fft_pairs=self.transforms / 2 + (self.field.fft_pairs if self.field else 0),
            wall_time=time.perf_counter() - start, unstable_steps=self.unstable_steps, detached=detached,
            kernel=body.description, version=__version__,
            details={"energy_history": [float(v) * grid.area * self.scale_to_operator for v in history],
                     **({} if self.field is None else {"field_fft_pairs": self.field.fft_pairs,
                                                       "field_evaluations": self.field.evaluations})})
        return ContactResult(
            pressure=pressure, displacement=displacement, gap=gap, contact=contact,
            contact_fraction=float(np.count_nonzero(contact)) / contact.size,
            mean_pressure=float(load) * self.scale_to_operator, mean_gap=float(gap.mean(dtype=np.float64)),
            penetration=float(heights.max()) - flat_position,
            elastic_energy=body.elastic_energy(pressure, displacement), grid=grid, solver=report,
            contact_pressure=contact_pressure, interaction_traction=traction, flat_position=float(flat_position),
            interaction_energy=interaction * grid.pixel_area, interaction=law, control=control,
            requested=float(requested))
