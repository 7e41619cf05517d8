"""The layered capacitor of the seed's Fig. 2: stratum corneum | air gap | insulator (Heß & Forsbach 2020).

All quantities SI. ``gap`` is the air-gap thickness d_a [m] (>= 0, zero at contact points), ``voltage`` the
voltage U across the stack [V] (only U² enters). Everything broadcasts over ``gap`` and ``voltage`` arrays.

Sign convention (``docs/reference/conventions.md``): :meth:`DielectricStack.attraction` returns the *magnitude* of the
attractive electrostatic stress σ_el >= 0. As a surface traction in the contact solver's convention
(positive = compressive) it enters as ``-σ_el``. The interaction energy per unit area is
``V(d) = -w(d)`` (:meth:`DielectricStack.energy`) and ``σ_el = dV/dd``.

The layers' shared pieces of the field models live here too: :func:`slab_elastance`, a flat slab's exact
response per Fourier mode, and :func:`check_frequency`, a drive frequency's validation. :class:`LeakyStack` is a
stack whose skin–screen interface leaks under a drive (``docs/guide/ac_drive.md``, "A leak across the interface").

Pure numpy: importing this module loads neither numba nor an FFT library.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from numbers import Real

import numpy as np

from surfaces.validation import check_broadcast, check_finite_array, check_positive, check_real

#: Vacuum permittivity ε0 [F/m] (CODATA 2018).
EPSILON_0 = 8.8541878128e-12


@dataclass(frozen=True)
class ElectricFields:
    """Normal electric fields in the three layers [V/m] and the electric displacement D [C/m²] (Eqs. 18–19)."""

    stratum_corneum: np.ndarray
    air: np.ndarray
    insulator: np.ndarray
    displacement: np.ndarray


def slab_elastance(q, thickness: float, permittivity: float) -> np.ndarray:
    """tanh(q d)/(eps q) [m]: a flat slab's surface potential per unit flux (×ε0) for the mode q on a conductor
    at its far face; d/eps at q = 0."""
    q = np.asarray(q, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        out = np.tanh(q * thickness) / (permittivity * q)
    return np.where(q == 0, thickness / permittivity, out)


def check_frequency(frequency) -> float:
    """A drive ``frequency`` [Hz] as a float in [0, inf] (inf: the dielectric limit), or ``ValueError``/``TypeError``."""
    if isinstance(frequency, (Real, np.floating)) and not isinstance(frequency, bool) and frequency == math.inf:
        return math.inf
    return check_real("frequency", frequency, low=0.0)


#: The largest |voltage| [V] a field solve takes: U² = 1e200 keeps every attraction ε0U²/(2h²) finite in float64
#: down to air-equivalent thicknesses of 1e-60 m (far beyond any physical voltage; a larger one would overflow).
MAX_VOLTAGE = 1e100


def check_voltage(voltage) -> float:
    """A ``voltage`` [V] as a float with |U| ≤ :data:`MAX_VOLTAGE`, or ``ValueError``/``TypeError`` naming it."""
    return check_real("voltage", voltage, low=-MAX_VOLTAGE, high=MAX_VOLTAGE)


#: Conductivity of the stratum corneum [S/m]: the static conduction term of dry skin's dielectric spectrum
#: (Gabriel et al. 1996, ``docs/references.md`` §11); hydration raises it by orders of magnitude.
SIGMA_SC = 2e-4


@dataclass(frozen=True)
class DielectricStack:
    """Stratum corneum, air gap and insulating screen layer in series (seed Eqs. 18–25).

    Defaults are the seed's Table 1: ``d_sc`` = 250 µm, ``eps_sc`` = 3000, ``d_i`` = 1 µm, ``eps_i`` = 3.9,
    ``eps_a`` = 1. Thicknesses in m, permittivities relative (dimensionless). ``sigma_sc`` [S/m, >= 0] is the
    stratum corneum's conductivity; only an AC or DC drive uses it (:mod:`roughcontact.electrostatics.ac`), every
    method here is the seed's perfect dielectric, the high-frequency limit.
    """

    d_sc: float = 250e-6
    eps_sc: float = 3000.0
    d_i: float = 1e-6
    eps_i: float = 3.9
    eps_a: float = 1.0
    sigma_sc: float = SIGMA_SC

    def __post_init__(self):
        for name in ("d_sc", "eps_sc", "d_i", "eps_i", "eps_a"):
            object.__setattr__(self, name, check_positive(name, getattr(self, name)))
        object.__setattr__(self, "sigma_sc", check_real("sigma_sc", self.sigma_sc, low=0.0))

    # -- geometry of the series capacitor ------------------------------------------------------------------
    @property
    def dielectric_offset(self) -> float:
        """``c = d_sc/eps_sc + d_i/eps_i`` [m]: the solid layers' air-equivalent thickness (ε_ra = 1)."""
        return self.d_sc / self.eps_sc + self.d_i / self.eps_i

    def elastance(self, q) -> np.ndarray:
        """M̂(q) ε0 = tanh(q d_sc)/(eps_sc q) + tanh(q d_i)/(eps_i q) [m]: the solid layers' air-equivalent thickness
        seen by a flux mode of wavenumber ``q`` [1/m] (each a flat slab, :func:`slab_elastance`); c at q = 0, the
        layers' (1/eps_sc + 1/eps_i)/q where q ≫ 1/d_i (``docs/guide/electrostatics.md``)."""
        q = check_finite_array("q", q, nonnegative=True)
        return slab_elastance(q, self.d_sc, self.eps_sc) + slab_elastance(q, self.d_i, self.eps_i)

    def electrical_thickness(self, gap) -> np.ndarray:
        """``h(d) = d_sc/eps_sc + d/eps_a + d_i/eps_i`` [m], the bracket of Eqs. 20–22."""
        gap = check_finite_array("gap", gap, nonnegative=True)
        return self.dielectric_offset + gap / self.eps_a

    def _times_voltage_squared(self, name, per_volt_squared, voltage) -> np.ndarray:
        """``per_volt_squared · U²`` for a quantity ∝ U² (``per_volt_squared`` its value at 1 V), formed as
        ``±(U sqrt|·|)²`` so it overflows only when the result does; then ``ValueError`` with the valid range."""
        factor = np.sqrt(np.abs(per_volt_squared))
        with np.errstate(over="ignore"):
            values = np.sign(per_volt_squared) * (voltage * factor) ** 2
        if not np.all(np.isfinite(values)):
            limit = float(np.sqrt(np.finfo(float).max) / np.max(factor))
            raise ValueError(f"voltage = {float(np.max(np.abs(voltage))):g} V makes the {name} overflow float64 "
                             f"at these gaps; valid range |voltage| < {limit:.3g} V")
        return values

    def _inputs(self, gap, voltage) -> tuple:
        """``(h(d) [m], U [V])``, checked and broadcast together."""
        gap, voltage = check_broadcast(gap=gap, voltage=voltage)
        return self.electrical_thickness(gap), voltage

    # -- Eqs. 18-24 ----------------------------------------------------------------------------------------
    def fields(self, gap, voltage) -> ElectricFields:
        """Fields from D-continuity (Eq. 18) and the voltage sum (Eq. 19): ``E_k = U / (eps_k h(d))`` [V/m]."""
        thickness, voltage = self._inputs(gap, voltage)
        field_air_equivalent = voltage / thickness                           # = D / eps0
        return ElectricFields(stratum_corneum=field_air_equivalent / self.eps_sc,
                              air=field_air_equivalent / self.eps_a,
                              insulator=field_air_equivalent / self.eps_i,
                              displacement=EPSILON_0 * field_air_equivalent)

    def attraction(self, gap, voltage) -> np.ndarray:
        """Electrostatic attraction per unit area σ_el = ε0 U² / (2 eps_a h(d)²) [Pa] (Eq. 21)."""
        thickness, voltage = self._inputs(gap, voltage)
        return self._times_voltage_squared("attraction", EPSILON_0 / (2 * self.eps_a * thickness ** 2), voltage)

    def attraction_derivative(self, gap, voltage, order: int = 1) -> np.ndarray:
        """d^k σ_el / dd^k for k = 1, 2 [Pa/m^k]; the 1/eps_a chain-rule factor from dh/dd is included.

        ``dσ/dd = -2 σ / (eps_a h)``, ``d²σ/dd² = 6 σ / (eps_a h)²``.
        """
        if order not in (1, 2):
            raise ValueError(f"order must be 1 or 2, got {order!r}")
        thickness, voltage = self._inputs(gap, voltage)
        eps_a_h = self.eps_a * thickness
        sigma_per_volt_squared = EPSILON_0 / (2 * self.eps_a * thickness ** 2)
        per_volt_squared = -2 * sigma_per_volt_squared / eps_a_h if order == 1 else \
            6 * sigma_per_volt_squared / eps_a_h ** 2
        return self._times_voltage_squared(f"attraction derivative of order {order}", per_volt_squared, voltage)

    def force(self, gap, voltage, area) -> np.ndarray:
        """Electrostatic force F_el = σ_el A [N] on a plate of ``area`` [m²] (Eq. 20)."""
        gap, voltage, area = check_broadcast(gap=gap, voltage=voltage,
                                             area=check_finite_array("area", area, nonnegative=True))
        return self.attraction(gap, voltage) * area

    def strong_troxel_attraction(self, voltage) -> np.ndarray:
        """Direct-contact limit σ_el(d = 0) = ε0 U² / (2 eps_a c²) [Pa] (Eq. 23; Eq. 24 for eps_a = 1)."""
        return self.attraction(0.0, voltage)

    def work_of_adhesion(self, gap, voltage) -> np.ndarray:
        """Work of electroadhesion w(d) = ∫_d^∞ σ_el dd' = ε0 U² / (2 h(d)) [J/m²] (Eq. 22)."""
        thickness, voltage = self._inputs(gap, voltage)
        return self._times_voltage_squared("work of adhesion", EPSILON_0 / (2 * thickness), voltage)

    def energy(self, gap, voltage) -> np.ndarray:
        """Interaction energy per unit area V(d) = -w(d) [J/m²]; ``dV/dd = σ_el``."""
        return -self.work_of_adhesion(gap, voltage)

    def gap_for_attraction(self, mean_attraction: float, voltage: float) -> float:
        """The uniform gap d [m] whose Eq. 21 attraction at ``voltage`` is ``mean_attraction`` [Pa] (Eq. 21 inverted):
        d = eps_a (|U| sqrt(ε0 / (2 eps_a σ)) − c). Negative for σ above full contact's (Eq. 23); ``nan`` at U = 0."""
        if voltage == 0.0:
            return float("nan")
        mean_attraction = check_positive("mean_attraction", mean_attraction)
        thickness = abs(float(voltage)) * np.sqrt(EPSILON_0 / (2 * self.eps_a * mean_attraction))
        return float(self.eps_a * (thickness - self.dielectric_offset))

    # -- Eq. 25 --------------------------------------------------------------------------------------------
    def equivalent_gap(self, gap_field, weights=None) -> float:
        """Equivalent air gap d_eq with σ_el(d_eq) = <σ_el(d(x, y))> over the apparent area (Eq. 25) [m].

        Closed-form inversion: ``d_eq = eps_a c (<(1 + d/(eps_a c))^-2>^(-1/2) - 1)``; independent of the
        voltage. Contact points (d = 0) are part of the average. ``weights`` (same shape, >= 0, or a boolean
        mask of the apparent area) make it a weighted average.
        """
        gap = check_finite_array("gap_field", gap_field, nonnegative=True)
        if gap.size == 0:
            raise ValueError("gap_field is empty; it needs at least one value")
        offset = self.eps_a * self.dielectric_offset
        inverse_square = (1.0 + gap / offset) ** -2
        if weights is None:
            mean = inverse_square.mean()
        else:
            weights = check_finite_array("weights", weights, nonnegative=True)
            if weights.shape != gap.shape:
                raise ValueError(f"weights has shape {weights.shape}, gap_field has {gap.shape}; they must match")
            total = weights.sum()
            if total <= 0:
                raise ValueError("weights must have a positive sum (an empty apparent area was given)")
            mean = float(np.sum(weights * inverse_square) / total)
        return float(offset * (mean ** -0.5 - 1.0))


@dataclass(frozen=True)
class LeakyStack(DielectricStack):
    """A :class:`DielectricStack` whose skin–screen interface passes charge under an AC or DC drive
    (:mod:`roughcontact.electrostatics.ac`; ``docs/guide/ac_drive.md``, "A leak across the interface"). Like
    ``sigma_sc``, the leak acts only under a drive: every dielectric number (Eq. 21, ``solve_field``, the layered law
    without a frequency) is the :class:`DielectricStack`'s, the high-frequency limit.

    * ``gap_conductance`` G_g [S/m², >= 0], ``gap_conductivity`` σ_g [S/m, >= 0] and a constant-phase element
      ``gap_cpe`` Q [S s^α/m², >= 0] of exponent ``gap_cpe_exponent`` α (0 < α <= 1): the admittance per unit area
      Y = G_g + σ_g/g + Q (iω)^α in parallel with an air column of gap g (:meth:`gap_admittance`). G_g is uniform
      over the columns and vanishes beside a closing gap's capacitance; σ_g fills the gap with a conducting medium,
      which drains every column at its own rate σ_g/(ε0 ε_a), contact columns included;
    * ``surface_conductance`` σ_s = 1/ρ_s [S, >= 0] (siemens per square): the screen's surface film, which spreads
      charge laterally over the insulator, a diffusion of coefficient 1/(ρ_s C_i) (layered field only; it needs
      ``contact_transfer``: the film touches the skin at every contact);
    * ``contact_transfer``: at a contact pixel the stratum corneum's conducted (free) charge passes to the screen
      and the skin keeps the flux of its own polarisation, ε_sc/ε*_sc of the total (without it, a contact column
      keeps the whole charge, as in the dielectric model, less what σ_g drains).

    All zero (and ``contact_transfer`` false) is the :class:`DielectricStack` itself: the same numbers bit for bit.
    """

    gap_conductance: float = 0.0
    gap_conductivity: float = 0.0
    gap_cpe: float = 0.0
    gap_cpe_exponent: float = 1.0
    surface_conductance: float = 0.0
    contact_transfer: bool = False

    def __post_init__(self):
        super().__post_init__()
        for name in ("gap_conductance", "gap_conductivity", "gap_cpe", "surface_conductance"):
            object.__setattr__(self, name, check_real(name, getattr(self, name), low=0.0))
        object.__setattr__(self, "gap_cpe_exponent", check_real("gap_cpe_exponent", self.gap_cpe_exponent, low=0.0,
                                                                high=1.0, low_open=True))
        if not isinstance(self.contact_transfer, (bool, np.bool_)):
            raise TypeError(f"contact_transfer must be true or false, got {self.contact_transfer!r}")
        object.__setattr__(self, "contact_transfer", bool(self.contact_transfer))
        if self.surface_conductance and not self.contact_transfer:
            raise ValueError(f"surface_conductance = {self.surface_conductance!r} S needs contact_transfer = True: the "
                             "screen's film touches the skin at every contact, where the conducted charge passes "
                             "(without it the contacts would hold the film's charge, and at DC an undetermined share)")

    @property
    def leaks(self) -> bool:
        """Whether any element of the leak is on (else the interface holds its charge, as a DielectricStack's)."""
        return bool(self.gap_conductance or self.gap_conductivity or self.gap_cpe or self.surface_conductance
                    or self.contact_transfer)

    def gap_admittance(self, frequency: float, gap: float) -> complex:
        """Y = G_g + σ_g/g + Q (iω)^α [S/m²] at ``frequency`` [Hz] (finite) in parallel with an air column of ``gap``
        g [m] (> 0): the leak of a uniform gap."""
        frequency = check_frequency(frequency)
        gap = check_real("gap", gap, low=0.0, low_open=True)
        if frequency == math.inf:
            raise ValueError("gap_admittance needs a finite frequency; at frequency = inf the leak carries no charge")
        cpe = self.gap_cpe * (2j * math.pi * frequency) ** self.gap_cpe_exponent if self.gap_cpe else 0.0
        return complex(self.gap_conductance + self.gap_conductivity / gap + cpe)

    def leak_corner_frequency(self, gap: float) -> float:
        """f_g = G / (2π (C_g + C_i)) [Hz] for a uniform air ``gap`` g [m] (> 0), G = G_g + σ_g/g, C_g = ε0 ε_a/g,
        C_i = ε0 ε_i/d_i: the corner of the conductances with the stratum corneum taken as a conductor
        (σ_sc/ε_sc → ∞). There the time average is F/F_∞ = (f/f_g)² / (1 + (f/f_g)²) of its value without the
        leak."""
        gap = check_real("gap", gap, low=0.0, low_open=True)
        capacitance = EPSILON_0 * (self.eps_a / gap + self.eps_i / self.d_i)
        return (self.gap_conductance + self.gap_conductivity / gap) / (2 * math.pi * capacitance)
