"""The contact equilibrium under the time-averaged attraction of an AC drive: deferred correction.

Under a sinusoidal drive at a frequency f (``ElectrostaticInteraction(stack, U, frequency=f)``, U the RMS
voltage) a leaky stratum corneum makes the layered field's time-averaged attraction σ̄(g)
(:mod:`roughcontact.electrostatics.ac`) a non-conservative traction t(g) = −σ̄(g): its Jacobian is not
symmetric (``docs/dev/roadmap.md``), so there is no energy for :mod:`.projected_cg_gap` to minimise. A conservative
**surrogate** law S carries the gap dependence and the rest of the true traction is frozen at the last gap:

    g_{n+1} = argmin Π_S(g) − ⟨c_n g⟩,   c_n = t(g_n) − t_S(g_n),

from c_0 = 0 (the surrogate alone) to a fixed point, where the solve's traction t_S(g) + c equals t(g): an
equilibrium of the true time-averaged traction (complementarity and force balance with p = p_S + c). t_S(g_n)
is the traction the solve balanced (its last field evaluation), t(g_n) one AC field solve (COCG,
:class:`~roughcontact.electrostatics.ac.ACStackField`, warm-started from the last gap's flux). S is the
dielectric layered law with a real ε_eff matched to the uniform mode of the circuit,

    |h_rest + d_sc/ε*_sc| = h_rest + d_sc/ε_eff,   h_rest = 1/⟨1/(g/(ε_a (1 + |∇g|²/3)) + d_i/ε_i)⟩,

h_rest the DC capacitance thickness of the air + insulator columns at the starting gap, so S has nearly the true
law's uniform response there and is the true law itself at DC (ε_eff → ∞). Any real ε_eff gives the same fixed
point; the match makes the corrections small. A frozen traction field c acts on the body like a change of its
heights by −K c and of the external load by −⟨c⟩ (g = s − h + K p_S + K c with ⟨p_S⟩ = P̄ − ⟨c⟩; the flat keeps
its position, so the penetration δ = max(h) − s becomes δ + max(h − K c) − max(h)): each step is an ordinary
warm-started energy solve of the surrogate, and nothing of that solver changes. Across a leaking interface
(:class:`~roughcontact.electrostatics.LeakyStack`) the surrogate folds the gap's conducting medium into the air
(ε_a/|t_m|, U √|t_m|, t_m = 1/(1 + σ_g/(iω ε0 ε_a)) the share of its charge every column keeps), takes ε_eff from
the series circuit with the leak at h_rest (:func:`~roughcontact.electrostatics.circuit_thickness`) and scales its
voltage so that its mean attraction at the starting gap is the drive's: a leak moves the attraction between the
contacts and the open gap, which the uniform mode alone does not see. Where the drive leaves no attraction the
surrogate is the hard wall.

Stopping rule: the change of the correction between the last two gaps, measured as the displacement it
causes, sqrt(⟨(K Δc̃)²⟩ + (Φ_L ⟨Δc⟩)²) ≤ tol · gap_scale (the energy solve's own criterion,
:mod:`.projected_cg_gap`; Φ_L the compliance of the longest wavelength, gap_scale the rms height). The returned
gap then solves the surrogate problem to ``tol`` and the true one to within that change: its true residual is at
most about twice ``tol``.
"""
from __future__ import annotations

import dataclasses
import math
import time
import warnings

import numpy as np

from ..electrostatics import EPSILON_0, DielectricStack, LeakyStack
from ..electrostatics.ac import ACStackField, circuit_thickness, medium_ratio
from ..electrostatics.field import StackField
from ..interactions import ElectrostaticInteraction
from ..io.results import ConvergenceWarning
from .inputs import Control
from .projected_cg_gap import FIELD_TOL_FLOOR, solve_hard_wall_handing_over, solve_smooth
from .result import ContactResult
from .starts import hard_wall_start

METHOD = "deferred-correction"
MAX_CORRECTIONS = 20       # corrections before the fixed point is reported as not converged
FIELD_TOL_FACTOR = 1e-2    # the corrections' field solves to this times tol (no tighter than FIELD_TOL_FLOOR)
#: ε_eff of a stratum corneum without elastance (DC): d_sc/ε_eff vanishes beside d_i/ε_i in float64
NO_ELASTANCE = 1e300


def leaking(stack) -> bool:
    """Whether ``stack`` is a :class:`~roughcontact.electrostatics.LeakyStack` whose interface leaks."""
    return isinstance(stack, LeakyStack) and stack.leaks


def driven(law) -> bool:
    """Whether ``law`` is an AC drive that dissipates, in the stratum corneum (σ_sc > 0) or across a leaking
    interface (0 ≤ f < ∞): the laws this module solves. ``frequency`` None or ∞, or a lossless stack (σ_sc = 0, no
    leak), is the dielectric law (the energy solve)."""
    return (isinstance(law, ElectrostaticInteraction) and law.frequency is not None and law.frequency != math.inf
            and (law.stack.sigma_sc > 0.0 or leaking(law.stack)))


def surrogate_permittivity(stack, rest_thickness: float, frequency: float) -> float:
    """ε_eff with |h*| = h_rest + d_sc/ε_eff for the air + insulator thickness ``rest_thickness`` h_rest [m] at
    ``frequency`` [Hz], h* the series circuit's thickness (:func:`~roughcontact.electrostatics.circuit_thickness`;
    h_rest + d_sc/ε*_sc without a leak): the real permittivity whose uniform mode has the air's |D̂_a| under the
    drive (:data:`NO_ELASTANCE` at DC without a leak; 0 where a DC leak drains the gap)."""
    excess = abs(circuit_thickness(stack, rest_thickness, frequency)) - rest_thickness
    return stack.d_sc / excess if excess > stack.d_sc / NO_ELASTANCE else NO_ELASTANCE


class _Correction:
    """The true time-averaged traction t(g) on one grid (the drive's operator built once, each field solve
    warm-started from the last, to ``tol``) and the surrogate law, its ε_eff matched at ``gap`` with
    h_rest = 1/⟨1/(ε0 R + d_i/ε_i)⟩, the DC capacitance thickness of the air + insulator columns (at DC the
    conducting stratum corneum is an equipotential and the thin insulator barely couples the columns: within
    1.1 % of the DC field's ε0 U/⟨D_DC⟩ on the default scene's 128² patch). Across a leaking interface the
    surrogate is :meth:`_leak_surrogate`."""

    def __init__(self, law: ElectrostaticInteraction, grid, gap, tol: float):
        stack = law.stack
        self.drive = ACStackField(stack, grid, law.frequency)
        columns = EPSILON_0 * self.drive.column_elastance(gap) + stack.d_i / stack.eps_i
        self.rest_thickness = 1.0 / float(np.mean(1.0 / columns))
        self.squared_voltage, self.tol = law.voltage ** 2, tol
        self.flux = None
        self.residual = 0.0                              # the largest relative residual of a field solve
        self.matching_pairs = 0                          # FFT pairs of the leak surrogate's dielectric solve
        if leaking(stack):
            self.permittivity, self.surrogate = self._leak_surrogate(law, grid, gap)
        else:
            self.permittivity = surrogate_permittivity(stack, self.rest_thickness, law.frequency)
            self.surrogate = ElectrostaticInteraction(dataclasses.replace(stack, eps_sc=self.permittivity),
                                                      law.voltage, contact_line=None)

    def _leak_surrogate(self, law: ElectrostaticInteraction, grid, gap) -> tuple:
        """(ε_eff, S) across a leaking interface: the dielectric layered law with the gap's medium (σ_g) folded into
        the air, ε_a/|t_m| and U √|t_m| with t_m = 1/(1 + κ) (the share every column keeps; it scales the column's
        elastance and the attraction alike), ε_eff from the series circuit at h_rest (``inf`` drained: no stratum
        corneum elastance) and the voltage then scaled so that S's mean attraction at ``gap`` is the drive's (one
        field solve each; a leak concentrates or removes the attraction at contacts, which the uniform mode does
        not see). The hard wall (0 V) where the drive leaves no attraction."""
        stack, frequency = law.stack, law.frequency
        self.flux, _, residual = self.drive.solve_flux(gap, tol=self.tol)
        self.residual = max(self.residual, residual)
        drive = float(np.mean(self.drive.attraction_phasors(gap, self.flux)[0]))          # ⟨σ̄⟩/U² [Pa/V²]
        if drive <= 0.0:
            return 0.0, ElectrostaticInteraction(stack, 0.0, contact_line=None)
        kept = abs(1.0 / (1.0 + medium_ratio(stack, frequency)))                           # |t_m|
        insulator = stack.d_i / stack.eps_i
        rest = (self.rest_thickness - insulator) * kept + insulator
        excess = kept * abs(circuit_thickness(stack, self.rest_thickness, frequency)) - rest
        permittivity = stack.d_sc / excess if stack.d_sc / NO_ELASTANCE < excess < math.inf else NO_ELASTANCE
        surrogate_stack = DielectricStack(d_sc=stack.d_sc, eps_sc=permittivity, d_i=stack.d_i, eps_i=stack.eps_i,
                                          eps_a=stack.eps_a / kept)
        field = StackField(surrogate_stack, grid, threads=1)
        flux, iterations, residual = field.solve_flux(gap, tol=self.tol)
        self.matching_pairs, self.residual = iterations + 1, max(self.residual, residual)
        surrogate = float(np.mean(field.attraction(gap, flux)))                              # per V² at U √|t_m| = 1
        voltage = abs(law.voltage) * math.sqrt(drive / surrogate)
        return permittivity, ElectrostaticInteraction(surrogate_stack, voltage, contact_line=None)

    def __call__(self, result) -> tuple:
        """(t(g), c(g)) [Pa] at the gap of the surrogate solve ``result``: c = t − t_S with t_S the traction that
        solve balanced (its last field evaluation)."""
        gap = np.asarray(result.gap, dtype=np.float64)
        self.flux, _, residual = self.drive.solve_flux(gap, initial=self.flux, tol=self.tol)
        self.residual = max(self.residual, residual)
        traction = -self.squared_voltage * self.drive.attraction_phasors(gap, self.flux)[0]
        return traction, traction - np.asarray(result.interaction_traction, dtype=np.float64)


def _corrections(count: int) -> str:
    return f"{count} correction" + ("" if count == 1 else "s")


def _correction_size(body, change, gap_scale: float) -> float:
    """sqrt(⟨(K Δc̃)²⟩ + (Φ_L ⟨Δc⟩)²)/gap_scale for a change Δc [Pa] of the frozen traction (a free window: the
    rms of K Δc over it): the displacement it would cause, in the energy solve's units of its tolerance."""
    if not body.periodic:
        return float(np.sqrt(np.mean(body.displacement(change) ** 2))) / gap_scale
    mean = float(np.mean(change))
    longest = max(float(body.compliance(2 * math.pi / max(body.grid.lengths))), body.uniform_compliance)
    fluctuation = body.displacement(change - mean)
    return float(np.sqrt(np.mean(fluctuation ** 2) + (longest * mean) ** 2)) / gap_scale


def _start(problem, control, heights):
    """(the result the first solve starts from or None, its gap, its name, its FFT pairs): the energy solve's own
    start (:func:`~.starts.hard_wall_start`: ``x0``, else the hard-wall solution at the same control where one
    exists), solved here once since its gap also matches ε_eff; else None and the rigid gap of the float64
    ``heights`` (the energy solve starts itself)."""
    begin, kind, pairs = hard_wall_start(problem, control, solve_hard_wall_handing_over)
    if begin is None:
        h_max = float(heights.max())
        flat_position = h_max if control.penetration is None else h_max - control.penetration
        return None, np.maximum(flat_position - heights, 0.0), kind, pairs
    return begin, np.asarray(begin.gap, dtype=np.float64), kind, pairs


def solve_driven(problem, control: Control) -> ContactResult:
    """The equilibrium of the checked ``problem`` (a :class:`~roughcontact.solvers.problem.ContactProblem` whose
    law is an AC drive) on the flat under the drive's time-averaged attraction (module docstring), at the checked
    ``control`` (a load or a penetration), as for :func:`~roughcontact.solvers.projected_cg_gap.solve_smooth`,
    whose ``tol``, ``maxiter``, ``callback`` and ``warn`` every energy solve takes.

    The result's ``interaction_traction`` is the true t(g) = −σ̄(g) at the returned gap and ``pressure`` the
    solved traction p_S + c (their difference on the open gap is the last correction's change);
    ``interaction_energy`` is ``nan`` where the stack dissipates (f > 0, or a leaking interface: no energy exists),
    the DC law's at f = 0.
    ``solver.details`` holds ``frequency`` [Hz], ``voltage`` (RMS) [V], ``corrections`` (the energy solves after
    the first, the surrogate's alone), ``correction_size`` (the last change of c, in units of ``tol``'s measure)
    with ``correction_sizes`` (one per solve, the first is c itself), ``surrogate_eps_sc`` ε_eff,
    ``surrogate_eps_a`` and ``surrogate_voltage`` [V] (the drive's own without a leak), ``rest_thickness`` h_rest
    [m], ``solve_iterations`` per solve and ``correction_fft_pairs``, the real FFT pairs of the AC field solves
    and of the leak surrogate's matching (``fft_pairs`` counts them with the solves' and the hard-wall start's).
    """
    began = time.perf_counter()
    body, law, tol = problem.body, problem.interaction, control.tol
    grid = body.grid
    heights = np.asarray(problem.heights, dtype=np.float64)
    load, requested = control.mean_pressure, control.value
    begin, gap, start_kind, pairs = _start(problem, control, heights)
    deviation = heights - float(heights.mean())
    gap_scale = float(np.sqrt(np.mean(deviation ** 2))) or law.length
    correction = _Correction(law, grid, gap, max(FIELD_TOL_FLOOR, FIELD_TOL_FACTOR * tol))
    frozen = np.zeros(grid.shape)                       # the first solve: the surrogate alone
    sizes, iterations, result, traction, message = [], [], begin, None, ""
    while True:
        shift = body.displacement(frozen.astype(body.dtype))                # K c: the frozen traction's displacement
        shifted = heights - shift
        target = dict(mean_pressure=load - float(np.mean(frozen))) if load is not None else \
            dict(penetration=requested + float(shifted.max()) - float(heights.max()))
        result = solve_smooth(problem.with_heights(shifted, correction.surrogate),
                              control.at(**target, x0=result, warn=False))
        pairs += result.solver.fft_pairs + 2                                 # and K c, K Δc
        start_kind = result.solver.start if begin is None and not iterations else start_kind   # the solve's own
        iterations.append(result.iterations)
        if not result.converged:
            message = f"solve {len(iterations)} (after {_corrections(len(sizes))}) stopped: {result.message}"
            break
        traction, update = correction(result)
        sizes.append(_correction_size(body, update - frozen, gap_scale))
        if sizes[-1] <= tol:
            message = (f"converged after {_corrections(len(sizes) - 1)}: the correction changed by "
                       f"{sizes[-1]:.3g} <= tol {tol:g}; the last solve {result.message}")
            break
        if len(sizes) > MAX_CORRECTIONS:
            message = (f"not converged: the deferred correction changed by {sizes[-1]:.3g} > tol {tol:g} after "
                       f"{_corrections(len(sizes) - 1)}")
            break
        frozen = update
    converged = result.converged and bool(sizes) and sizes[-1] <= tol and correction.residual <= correction.tol
    if result.converged and correction.residual > correction.tol:
        message = (f"not converged: an AC field solve stopped at relative residual {correction.residual:.3g} "
                   f"> {correction.tol:g}")
    leak = ", leaking interface" if leaking(law.stack) else ""
    message += f" (AC drive {law.frequency:g} Hz, {law.voltage:g} V RMS{leak})"
    if not converged and control.warn:
        warnings.warn(message, ConvergenceWarning, stacklevel=3)
    correction_pairs = correction.drive.fft_pairs + correction.matching_pairs
    surrogate = correction.surrogate
    details = {"frequency": law.frequency, "voltage": law.voltage, "corrections": len(iterations) - 1,
               "correction_size": sizes[-1] if sizes else math.inf, "correction_sizes": sizes,
               "surrogate_eps_sc": correction.permittivity, "rest_thickness": correction.rest_thickness,
               "surrogate_voltage": surrogate.voltage, "surrogate_eps_a": surrogate.stack.eps_a,
               "solve_iterations": iterations, "correction_fft_pairs": float(correction_pairs)}
    report = dataclasses.replace(result.solver, method=METHOD, converged=converged, message=message,
                                 iterations=sum(iterations), start=start_kind, fft_pairs=float(pairs + correction_pairs),
                                 wall_time=time.perf_counter() - began, details={**result.solver.details, **details})
    return _driven_result(result, body, heights, law, frozen, traction if result.converged else None, report,
                          control.kind, requested)


def _driven_result(result, body, heights, law, frozen, traction, report, control, requested) -> ContactResult:
    """The ContactResult of the original problem from the last surrogate solve ``result`` (which had the traction
    ``frozen`` c added) with the ``report``: p = p_S + c, u = u_S + K c, the true traction ``traction`` t(g) at
    its gap (None where that solve did not converge: the solve's own t_S + c)."""
    dtype = body.dtype
    if traction is None:
        traction = np.asarray(result.interaction_traction, dtype=np.float64) + frozen
    pressure = np.asarray(result.pressure, dtype=np.float64) + frozen
    displacement = np.asarray(result.displacement, dtype=np.float64) + body.displacement(frozen.astype(dtype))
    contact_pressure = np.where(result.contact, pressure - traction, 0.0)
    arrays = {name: values.astype(dtype) for name, values in (("pressure", pressure), ("displacement", displacement),
                                                              ("interaction_traction", traction),
                                                              ("contact_pressure", contact_pressure))}
    for values in arrays.values():
        values.flags.writeable = False
    energy = result.interaction_energy if law.frequency == 0.0 and not leaking(law.stack) else math.nan
    return dataclasses.replace(
        result, **arrays, mean_pressure=result.mean_pressure + float(np.mean(frozen)),
        penetration=float(heights.max()) - result.flat_position,
        elastic_energy=body.elastic_energy(arrays["pressure"], arrays["displacement"]), interaction_energy=energy,
        interaction=law, control=control, requested=float(requested), solver=report)
