"""Interaction laws between the elastic surface and the rigid counter-face, as functions of the gap g [m].

An interaction is described by three per-area quantities (``docs/reference/conventions.md``; ``docs/guide/interactions.md``):

* ``energy(g)``     V(g) [J/m²], the interaction energy per unit area, V → 0 as g → ∞;
* ``traction(g)``   p_int(g) = −dV/dg [Pa], the normal traction it exerts on the elastic body, positive
                    compressive (repulsive); an attraction such as electroadhesion is negative;
* ``stiffness(g)``  k(g) = dp_int/dg = −d²V/dg² [Pa/m].

Every law acts together with the impenetrable flat (g ≥ 0). The hard wall alone (:class:`HardWall`: no
adhesion) is the singular member of the family: its traction is not a function of the gap but the Lagrange
multiplier that the Polonsky–Keer solver computes. The smooth laws (:class:`ElectrostaticInteraction`,
:class:`ExponentialAdhesion`, :class:`MaugisDugdale`, or a user's subclass of :class:`Interaction`) add the
traction p_int(g) everywhere, the wall's contact pressure where g = 0.

A user's own law subclasses :class:`Interaction`, is a frozen dataclass (so that results can be saved and
pickled with it) and implements ``energy`` and ``traction`` on float arrays of gaps g ≥ 0 (finite values at
every such gap; the energy +inf where g < 0), ``stiffness`` if it can (otherwise the base class takes it by
differences of the traction), plus ``length``, the gap scale [m] over which it varies (the solver's scale for
"far away"; required, > 0), and optionally ``strength``, its largest attraction max_g −p_int(g) [Pa] (with it
a tensile load beyond the strength is reported as detached without iterating). The repulsion is the wall's: a
law that also models it (a potential whose minimum is the contact, such as the full 9-3 wall) puts a convex
well far stiffer than a pixel at the wall, which the solver converges through slowly.
``docs/guide/interactions.md`` has an example and the measured cost. The built-in laws refuse a non-finite gap, and a negative one in traction and stiffness
(``ValueError`` naming ``gap``); their energy is +inf where the wall is penetrated.

A law that acts pixel by pixel may also carry its ``kernel``: a :class:`~typing.NamedTuple` of its constant
parameters (floats) whose class has ``at(gap, kernel)`` → (V, p_int, k) at one gap, written in arithmetic that
numba compiles (:class:`ParallelPlateKernel`, :class:`ExponentialKernel`, :class:`DugdaleKernel`). The smooth
contact solve compiles ``at`` into its fused passes, one specialisation per kernel class (the library's cached on
disk, a user's compiled once per process), and evaluates a law without a kernel through its numpy methods. This
module itself does not import numba.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from surfaces.validation import check_choice, check_finite_array, check_positive

from .electrostatics import EPSILON_0, DielectricStack, LeakyStack
from .electrostatics.contact_line import AirBreakdown, RoughnessFilm, check_contact_line
from .electrostatics.stack import check_frequency, check_voltage
from .io.results import savable_field

#: Relative step of a stiffness taken by differences of the traction (ε^(1/3) of float64; :meth:`Interaction.stiffness`).
FINITE_DIFFERENCE_STEP = float(np.finfo(np.float64).eps) ** (1 / 3)
#: How an electrostatic law takes the field (:class:`ElectrostaticInteraction`).
FIELDS = ("parallel_plate", "layered")
#: The layered dielectric law's model of the contact line unless one is given: air breakdown at 350 V/µm
#: (``docs/findings/contact_line.md``).
DEFAULT_CONTACT_LINE = AirBreakdown()


def _gaps(gap) -> np.ndarray:
    """The gaps g [m] a traction or stiffness is evaluated at, checked: finite and ≥ 0 (the wall forbids g < 0)."""
    return check_finite_array("gap", gap, nonnegative=True)


def _with_wall(law_energy, gap) -> np.ndarray:
    """V(g) [J/m²] of a law acting with the wall: ``law_energy`` at g ≥ 0, +inf where the wall is penetrated
    (g < 0); ``gap`` checked finite."""
    gap = check_finite_array("gap", gap)
    return np.where(gap >= 0, law_energy(np.maximum(gap, 0.0)), np.inf)


class ParallelPlateKernel(NamedTuple):
    """The per-pixel electrostatic law's kernel: V = −a/h, h = c + g b, with a = ε0 U²/2 [J/m], b = 1/ε_a and
    c the dielectric offset [m] (seed Eqs. 20–22)."""

    a: float
    b: float
    c: float

    @staticmethod
    def at(gap, kernel):
        """(V [J/m²], p_int [Pa], k [Pa/m]) at the gap g [m]: one division, 1/h."""
        inverse = 1.0 / (kernel.c + gap * kernel.b)
        energy = -kernel.a * inverse
        traction = energy * inverse * kernel.b
        return energy, traction, -2.0 * traction * inverse * kernel.b


class ExponentialKernel(NamedTuple):
    """:class:`ExponentialAdhesion`'s kernel: V = −w e^(−g b), b = 1/ρ [1/m], w the work of adhesion [J/m²]."""

    work_of_adhesion: float
    inverse_length: float

    @staticmethod
    def at(gap, kernel):
        """(V [J/m²], p_int [Pa], k [Pa/m]) at the gap g [m]."""
        b = kernel.inverse_length
        e = kernel.work_of_adhesion * math.exp(-gap * b)
        return -e, -e * b, e * b * b


class DugdaleKernel(NamedTuple):
    """:class:`MaugisDugdale`'s kernel: V = −σ0 (δ_c − g) below δ_c, 0 beyond (σ0 [Pa], δ_c = ``length`` [m])."""

    cohesive_stress: float
    length: float

    @staticmethod
    def at(gap, kernel):
        """(V [J/m²], p_int [Pa], k [Pa/m]) at the gap g [m]."""
        if gap < kernel.length:
            return -kernel.cohesive_stress * (kernel.length - gap), -kernel.cohesive_stress, 0.0
        return 0.0, 0.0, 0.0


class Interaction:
    """Base class: a gap-dependent interaction law (energy, traction, stiffness; see the module docstring)."""

    #: Every law acts together with the impenetrable flat (g ≥ 0).
    hard_wall: bool = True
    #: False for the hard wall alone, whose traction is a multiplier, not a function of the gap.
    smooth: bool = True
    #: True where the law exerts no traction at any gap (the hard wall alone solves it).
    vanishes: bool = False
    #: A law also has ``length``: the gap scale [m] over which it varies (a field or a property).
    #: The largest attraction max_g −p_int(g) [Pa] over g ≥ 0, where known (None: not known).
    strength: float | None = None
    #: The law's numba kernel (module docstring), or None: the solve evaluates the numpy methods.
    kernel: NamedTuple | None = None

    def energy(self, gap) -> np.ndarray:
        raise NotImplementedError(f"{type(self).__name__} must implement energy(gap), V(g) [J/m²] "
                                  "(roughcontact.interactions; docs/guide/interactions.md)")

    def traction(self, gap) -> np.ndarray:
        raise NotImplementedError(f"{type(self).__name__} must implement traction(gap), p_int(g) = −dV/dg [Pa] "
                                  "(roughcontact.interactions; docs/guide/interactions.md)")

    def stiffness(self, gap) -> np.ndarray:
        """k(g) = dp_int/dg [Pa/m] by differences of :meth:`traction`, for a law without its own stiffness: the
        central difference with step δ = ε^(1/3) (g + length), the one-sided second-order one (−3p(g) + 4p(g+δ)
        − p(g+2δ))/(2δ) where g < δ (the wall); both err by O(δ²), ~1e-10 relative for a smooth law."""
        gap = check_finite_array("gap", gap, nonnegative=True)
        step = FINITE_DIFFERENCE_STEP * (gap + check_positive(f"{type(self).__name__}.length",
                                                                 getattr(self, "length", None)))
        ahead = self.traction(gap + step)
        central = (ahead - self.traction(np.maximum(gap - step, 0.0))) / (2 * step)
        one_sided = (4 * ahead - 3 * self.traction(gap) - self.traction(gap + 2 * step)) / (2 * step)
        return np.where(gap >= step, central, one_sided)


@dataclass(frozen=True)
class HardWall(Interaction):
    """Non-adhesive, impenetrable rigid flat: V(g) = 0 for g ≥ 0, +∞ for g < 0.

    The contact pressure is the multiplier of the constraint g ≥ 0, found by the solver (complementarity
    p ≥ 0, g ≥ 0, p g = 0); away from contact the wall exerts no traction.
    """

    smooth = False
    length = 0.0               # the wall acts at g = 0 only

    def energy(self, gap) -> np.ndarray:
        """V(g) [J/m²]: 0 where g ≥ 0, +inf where the wall is penetrated."""
        return _with_wall(np.zeros_like, gap)

    def traction(self, gap) -> np.ndarray:
        """p_int(g) = −dV/dg [Pa] for g ≥ 0: zero (the contact pressure is the solver's multiplier)."""
        return np.zeros_like(_gaps(gap))

    def stiffness(self, gap) -> np.ndarray:
        """k(g) = dp_int/dg [Pa/m] for g ≥ 0: zero."""
        return np.zeros_like(_gaps(gap))


@dataclass(frozen=True)
class ElectrostaticInteraction(Interaction):
    """The attraction of the dielectric stack at ``voltage`` [V] across the air gap (seed Eqs. 20–22).

    V(g) = −w(g) = −ε0 U² / (2 h(g)), p_int = −σ_el(g) = −ε0 U² / (2 ε_a h(g)²), h(g) = c + g/ε_a
    (:class:`~roughcontact.electrostatics.DielectricStack`; only U² enters, so the sign of the voltage does
    not matter).

    ``field`` says how the field is taken: ``"layered"`` (the default), the stack's field over the whole gap field
    (:mod:`roughcontact.electrostatics.field`: the stratum corneum and the insulator couple the columns;
    ``docs/guide/electrostatics.md``), or ``"parallel_plate"``, Eq. 21 pixel by pixel (the methods below), the seed's
    assumption. The layered law is non-local: its traction at a pixel depends on the whole gap field, so the
    contact solver evaluates it through :class:`~roughcontact.electrostatics.field.FieldLaw`, and the per-pixel
    methods give the parallel-plate values.

    ``frequency`` [Hz] drives the layered field with a sinusoid of RMS ``voltage`` through the leaky stratum
    corneum (``stack.sigma_sc``) and, for a :class:`~roughcontact.electrostatics.LeakyStack`, across its leaking
    interface (:mod:`roughcontact.electrostatics.ac`): the solve balances the time-averaged attraction
    (:mod:`roughcontact.solvers.deferred_correction`, ``docs/guide/ac_drive.md``). ``None`` (the default) is the
    dielectric stratum corneum, as is ``math.inf``; 0 is a DC voltage. It needs ``field="layered"``.

    ``contact_line`` is the layered field's model of the contact line
    (:mod:`roughcontact.electrostatics.contact_line`): an
    :class:`~roughcontact.electrostatics.contact_line.AirBreakdown` (the default of the layered dielectric law,
    :data:`DEFAULT_CONTACT_LINE`: without a finite strength at the contact line its F_el does not converge with
    the pixel, ``docs/findings/contact_line.md``), a :class:`~roughcontact.electrostatics.contact_line.RoughnessFilm`
    or None (the sharp line of the plain layered field); a model needs ``field="layered"`` and the dielectric
    stratum corneum (no ``frequency``), and the default is None for the per-pixel law and under a drive (the AC
    field has no model of the contact line).
    """

    stack: DielectricStack = DielectricStack()
    voltage: float = 0.0
    field: str = "layered"
    frequency: float | None = None
    contact_line: object = "default"

    def __post_init__(self):
        if not isinstance(self.stack, DielectricStack):
            raise TypeError(f"stack must be a DielectricStack, got {type(self.stack).__name__}")
        object.__setattr__(self, "voltage", check_voltage(self.voltage))
        check_choice("field", self.field, FIELDS)
        if self.frequency is not None:
            object.__setattr__(self, "frequency", check_frequency(self.frequency))
            if self.local:
                raise ValueError(f"frequency = {self.frequency!r} Hz needs field = 'layered' (the AC drive acts "
                                 f"through the layered field); got field = {self.field!r}")
        if isinstance(self.contact_line, str) and self.contact_line == "default":
            dielectric_layered = not self.local and self.frequency is None
            object.__setattr__(self, "contact_line", DEFAULT_CONTACT_LINE if dielectric_layered else None)
        if check_contact_line(self.contact_line) is not None and (self.local or self.frequency is not None):
            raise ValueError(f"contact_line = {self.contact_line!r} needs field = 'layered' and no frequency (the "
                             f"dielectric layered field); got field = {self.field!r}, frequency = {self.frequency!r}")

    @property
    def local(self) -> bool:
        """Whether the traction at a pixel depends on its own gap only (the parallel plate)."""
        return self.field == "parallel_plate"

    @property
    def vanishes(self) -> bool:
        """At 0 V there is no attraction: the hard-wall solver answers."""
        return self.voltage == 0.0

    @property
    def length(self) -> float:
        """ε_a c [m]: the gap at which σ_el has fallen to a quarter of its contact value."""
        return self.stack.eps_a * self.stack.dielectric_offset

    @property
    def strength(self) -> float | None:
        """σ_el(0) [Pa], the largest attraction of the per-pixel law (at contact); None for the layered field."""
        return float(self.stack.attraction(0.0, self.voltage)) if self.local else None

    @property
    def kernel(self) -> ParallelPlateKernel | None:
        """The per-pixel law's :class:`ParallelPlateKernel`; None for the layered field (non-local)."""
        if not self.local:
            return None
        stack = self.stack
        return ParallelPlateKernel(float(0.5 * EPSILON_0 * self.voltage ** 2), float(1.0 / stack.eps_a),
                                   float(stack.dielectric_offset))

    def energy(self, gap) -> np.ndarray:
        return _with_wall(lambda g: self.stack.energy(g, self.voltage), gap)

    def traction(self, gap) -> np.ndarray:
        return -self.stack.attraction(gap, self.voltage)

    def stiffness(self, gap) -> np.ndarray:
        return -self.stack.attraction_derivative(gap, self.voltage)


@dataclass(frozen=True)
class ExponentialAdhesion(Interaction):
    """V(g) = −w e^{−g/ρ} [J/m²]: work of adhesion ``work_of_adhesion`` w [J/m²] over the range ``length`` ρ [m].

    p_int = −(w/ρ) e^{−g/ρ}, k = (w/ρ²) e^{−g/ρ}. As ρ → 0 (Tabor parameter → ∞) contacts follow JKR.
    """

    work_of_adhesion: float
    length: float

    def __post_init__(self):
        object.__setattr__(self, "work_of_adhesion", check_positive("work_of_adhesion", self.work_of_adhesion))
        object.__setattr__(self, "length", check_positive("length", self.length))

    @property
    def strength(self) -> float:
        """w/ρ [Pa], the attraction at contact (the largest)."""
        return self.work_of_adhesion / self.length

    @property
    def kernel(self) -> ExponentialKernel:
        return ExponentialKernel(float(self.work_of_adhesion), float(1.0 / self.length))

    def energy(self, gap) -> np.ndarray:
        return _with_wall(self._energy, gap)

    def traction(self, gap) -> np.ndarray:
        return self._energy(_gaps(gap)) / self.length

    def stiffness(self, gap) -> np.ndarray:
        return -self._energy(_gaps(gap)) / self.length ** 2

    def _energy(self, gap):
        return -self.work_of_adhesion * np.exp(-gap / self.length)


@dataclass(frozen=True)
class MaugisDugdale(Interaction):
    """Dugdale cohesive zone (Maugis 1992): a constant attraction σ0 = w/δ_c up to the gap δ_c, none beyond.

    V(g) = −σ0 (δ_c − g) for g < δ_c, 0 beyond [J/m²]; p_int = −σ0 for g < δ_c, 0 beyond; k = 0 except the
    jump at δ_c. ``work_of_adhesion`` w [J/m²], ``length`` δ_c [m].
    """

    work_of_adhesion: float
    length: float

    def __post_init__(self):
        object.__setattr__(self, "work_of_adhesion", check_positive("work_of_adhesion", self.work_of_adhesion))
        object.__setattr__(self, "length", check_positive("length", self.length))

    @property
    def cohesive_stress(self) -> float:
        """σ0 = w/δ_c [Pa]."""
        return self.work_of_adhesion / self.length

    @property
    def strength(self) -> float:
        """σ0 [Pa], the attraction at every gap below δ_c."""
        return self.cohesive_stress

    @property
    def kernel(self) -> DugdaleKernel:
        return DugdaleKernel(float(self.cohesive_stress), float(self.length))

    def energy(self, gap) -> np.ndarray:
        return _with_wall(lambda g: -self.cohesive_stress * np.maximum(self.length - g, 0.0), gap)

    def traction(self, gap) -> np.ndarray:
        return np.where(_gaps(gap) < self.length, -self.cohesive_stress, 0.0)

    def stiffness(self, gap) -> np.ndarray:
        return np.zeros_like(_gaps(gap))


#: The laws that results can be saved and loaded with (by class name).
LAWS = {law.__name__: law for law in (HardWall, ElectrostaticInteraction, ExponentialAdhesion, MaugisDugdale)}
# a result holding a law (and its stack, its contact line) loads them by name
for _kind in (*LAWS.values(), DielectricStack, LeakyStack, AirBreakdown, RoughnessFilm):
    savable_field(_kind)


__all__ = ["Interaction", "HardWall", "ElectrostaticInteraction", "ExponentialAdhesion", "MaugisDugdale",
           "ParallelPlateKernel", "ExponentialKernel", "DugdaleKernel"]
