"""The result of a contact solve: :class:`ContactResult` (fields, summary numbers, the solver's record; savable)
and :class:`SolverState`, what a solver's ``callback`` sees after each step."""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field

import numpy as np

from surfaces import Grid

from ..interactions import ElectrostaticInteraction, HardWall, Interaction
from ..io.results import SavableResult


# Counting contact pixels over-estimates the true area by a perimeter term that falls as Δx/λ_s; Yastrebov,
# Anciaux & Molinari (2017, Tribol. Int. 114:161) remove it by subtracting this fraction of a pixel per edge
# between a contact and a non-contact pixel (docs/findings/contact_area.md measures it: κ flat from 4 to 64 px).
PERIMETER_CORRECTION = (math.pi - 1 + math.log(2)) / 24


def boundary_edges(contact: np.ndarray, periodic=(True, True)) -> int:
    """Number M of pixel edges between a contact and a non-contact pixel; across the window's border only on
    the ``periodic`` axes."""
    edges = 0
    for axis, wraps in enumerate(periodic):
        edges += int(np.count_nonzero(np.diff(contact, axis=axis)))          # boolean diff: neighbours differ
        if wraps:
            edges += int(np.count_nonzero(contact.take(0, axis) != contact.take(-1, axis)))
    return edges


def _read_only_state(result, state: dict) -> None:
    """Unpickling: the fields back, arrays read-only as when the result was made (results are immutable)."""
    for name, value in state.items():
        if isinstance(value, np.ndarray):
            value.flags.writeable = False
        object.__setattr__(result, name, value)


@dataclass(frozen=True, eq=False)
class SolverReport(SavableResult):
    """What the solver did, typed: ``method`` (a name of :data:`~roughcontact.solvers.dispatch.METHODS`),
    ``converged``, ``message``, ``iterations``, ``residuals`` (history of the method's relative error), ``tol``
    and ``maxiter`` it ran with, ``start`` (what it started from: "nested", "pk", "x0", "hard wall", "rigid",
    "retract from 0 Pa"), ``fft_pairs`` (forward and backward transforms / 2, the start's included),
    ``wall_time`` [s], ``unstable_steps`` (steps of a smooth law's solve along which the energy was concave: it
    crossed an instability, so the equilibrium reached may depend on the path; 0 for the hard wall),
    ``detached`` (under a tensile load no equilibrium was found: the message says why), ``kernel`` (the body's
    description), ``version`` (of roughcontact) and ``details``, the method's own record
    (``docs/guide/solver.md``: Polonsky–Keer's "preconditioned", "nested_iterations", "restart_every_entry_from",
    "full_contact", "warm_start_stalled_at"; the smooth method's "energy_history" [J])."""

    method: str
    converged: bool
    message: str
    iterations: int
    residuals: np.ndarray
    tol: float
    maxiter: int
    start: str
    fft_pairs: float
    wall_time: float
    unstable_steps: int = 0
    detached: bool = False
    kernel: dict = field(default_factory=dict)
    version: str = ""
    details: dict = field(default_factory=dict)

    __setstate__ = _read_only_state

    def __eq__(self, other):
        """Field by field: arrays (``residuals``, those in ``details``) by value, NaN equal to NaN (a report
        and its saved-and-loaded copy are equal; the default comparison would take the arrays' truth value)."""
        if not isinstance(other, SolverReport):
            return NotImplemented
        return all(_same(getattr(self, name), getattr(other, name)) for name in self.__dataclass_fields__)

    def __hash__(self):
        # the fields that compare by plain equality (a float may be NaN, whose hash is its object's)
        return hash((self.method, self.converged, self.message, self.iterations, self.maxiter, self.start,
                     self.unstable_steps, self.detached, self.version))


def _same(a, b) -> bool:
    """Whether two field values are equal: arrays by shape and value, floats with NaN equal to NaN, dicts,
    lists and tuples item by item."""
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        a, b = np.asarray(a), np.asarray(b)
        return a.shape == b.shape and np.array_equal(a, b, equal_nan=a.dtype.kind in "fc" and b.dtype.kind in "fc")
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(_same(a[key], b[key]) for key in a)
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        return type(a) is type(b) and len(a) == len(b) and all(map(_same, a, b))
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    return bool(a == b)


def _from_report(name: str, doc: str) -> property:
    """A read-only attribute of the result that is the entry ``name`` of its SolverReport."""
    return property(lambda result: getattr(result.solver, name), doc=f"{doc} (``solver.{name}``)")


@dataclass(frozen=True, eq=False, kw_only=True)
class ContactResult(SavableResult):
    """Solution of one contact problem. Fields in SI units; see ``docs/reference/conventions.md`` for signs.

    Tractions [Pa], positive compressive: ``pressure`` p, the total normal traction that deforms the body
    (u = K p), = ``contact_pressure`` (the wall's multiplier: ≥ 0, non-zero on the contact set only) +
    ``interaction_traction`` p_int(g) of the ``interaction`` law (everywhere; −σ_el(g) for electroadhesion, 0
    for the hard wall). ``mean_pressure`` <p> [Pa] is the external load (any sign; ``total_force`` [N]).
    Geometry [m]: ``displacement`` u, ``gap`` g (≥ 0, 0 on the contact set), ``flat_position`` s, with
    g = s − h + u, ``penetration`` δ = max(h) − s, ``mean_gap``; ``contact`` (bool mask), ``contact_fraction``
    A/A0; ``grid`` the grid it was solved on. Energies [J]: ``elastic_energy`` ½∫p u dA, ``interaction_energy``
    ∫V(g) dA. ``control`` ("mean_pressure", "total_force" or "penetration") and ``requested`` say what was
    fixed. ``solver``: the :class:`SolverReport` (method, convergence, cost, start, detachment); its most read
    entries are also attributes of the result: ``converged``, ``message``, ``iterations``, ``residuals``,
    ``wall_time`` [s], ``unstable_steps``, ``detached``.
    """

    pressure: np.ndarray
    displacement: np.ndarray
    gap: np.ndarray
    contact: np.ndarray
    contact_fraction: float
    mean_pressure: float
    mean_gap: float
    penetration: float
    elastic_energy: float
    grid: Grid
    solver: SolverReport
    contact_pressure: np.ndarray | None = None
    interaction_traction: np.ndarray | None = None
    flat_position: float = math.nan
    interaction_energy: float = 0.0
    interaction: Interaction = HardWall()
    control: str = ""
    requested: float = math.nan

    def __post_init__(self):
        if not isinstance(self.grid, Grid) or not isinstance(self.solver, SolverReport):
            raise TypeError(f"ContactResult needs grid (a surfaces.Grid) and solver (a SolverReport), got "
                            f"{type(self.grid).__name__} and {type(self.solver).__name__}")

    __setstate__ = _read_only_state

    def __eq__(self, other):
        """Field by field (as :class:`SolverReport`'s): arrays by value, floats with NaN equal to NaN, the grid, the
        law and the report by their own equality (a result and its saved-and-loaded copy are equal)."""
        if not isinstance(other, ContactResult):
            return NotImplemented
        return all(_same(getattr(self, name), getattr(other, name)) for name in self.__dataclass_fields__)

    __hash__ = None     # equal by value, arrays included: no hash consistent with it

    converged = _from_report("converged", "Whether the solver met its tolerance.")
    message = _from_report("message", "The solver's closing message.")
    iterations = _from_report("iterations", "Steps of the method.")
    residuals = _from_report("residuals", "History of the method's relative error.")
    wall_time = _from_report("wall_time", "Seconds the solve took.")
    unstable_steps = _from_report("unstable_steps", "Steps along which the energy was concave "
                                  "(docs/guide/interactions.md, \"Several equilibria\").")
    detached = _from_report("detached", "Whether a tensile load found no equilibrium (the message says why).")

    @functools.cached_property
    def perimeter_edges(self) -> int:
        """Number M of pixel edges between a contact and a non-contact pixel (:func:`boundary_edges`, across the
        window's border on the grid's periodic axes)."""
        return boundary_edges(self.contact, self.grid.periodic)

    @property
    def corrected_contact_fraction(self) -> float:
        """A/A0 with the pixel-perimeter correction (N − c M)/N_total, c = (π − 1 + ln 2)/24 per contact edge
        (Yastrebov et al. 2017; derived for square pixels)."""
        return (np.count_nonzero(self.contact) - PERIMETER_CORRECTION * self.perimeter_edges) / self.contact.size

    @property
    def total_force(self) -> float:
        """Total normal force F = <p> Lx Ly [N]: the external load, positive pushing the bodies together."""
        return self.mean_pressure * self.grid.area

    @property
    def total_energy(self) -> float:
        """Elastic plus interaction energy [J] (the external load's work not included)."""
        return self.elastic_energy + self.interaction_energy

    @property
    def electrostatic_force(self) -> float:
        """Total electrostatic attraction F_el = ∫σ_el dA [N] (≥ 0) of an electrostatic solve, from the field the
        solve used: Eq. 21 of ``gap`` pixel by pixel, or the layered field (the solved traction)."""
        stack, voltage = self._electrostatics()
        if self.interaction.local:
            attraction = stack.attraction(self.gap, voltage)
        else:
            attraction = -np.asarray(self.interaction_traction, dtype=np.float64)
        return float(np.sum(attraction, dtype=np.float64)) * self.grid.pixel_area

    @property
    def equivalent_gap(self) -> float:
        """Equivalent air gap d_eq of seed Eq. 25 over the solved window (contact points included) [m]:
        ``DielectricStack.equivalent_gap`` of ``gap``, the seed's definition whatever field the solve used."""
        stack, _ = self._electrostatics()
        return stack.equivalent_gap(self.gap)

    @property
    def field_equivalent_gap(self) -> float:
        """The uniform gap d [m] whose Eq. 21 attraction equals F_el/A0 of the solve (:attr:`electrostatic_force`):
        the field-true counterpart of Eq. 25 (equal to it for the parallel-plate law; negative where the mean
        attraction exceeds full contact's, ``nan`` at 0 V)."""
        stack, voltage = self._electrostatics()
        if voltage == 0.0:
            return math.nan
        return stack.gap_for_attraction(self.electrostatic_force / self.grid.area, voltage)

    def _electrostatics(self):
        if not isinstance(self.interaction, ElectrostaticInteraction):
            raise ValueError(f"the result's interaction is {type(self.interaction).__name__}, not an "
                             "ElectrostaticInteraction; use DielectricStack.equivalent_gap(result.gap) for another stack")
        return self.interaction.stack, self.interaction.voltage

    def __repr__(self):
        return (f"ContactResult(contact_fraction={self.contact_fraction:.6g}, mean_pressure={self.mean_pressure:.6g} "
                f"Pa, mean_gap={self.mean_gap:.6g} m, converged={self.converged}, iterations={self.iterations})")


@dataclass(frozen=True)
class SolverState:
    """What a ``callback`` sees after each CG step: iteration, relative rms gap error, contact fraction."""

    iteration: int
    residual: float
    contact_fraction: float
