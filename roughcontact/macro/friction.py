"""Sliding friction of a fingerpad under electroadhesion (seed Eqs. 35–46).

Chain for a normal force F_N [N] and voltage U [V]:

1. equivalent air gap d_eq = gap_model(F_N, U) (Eq. 46 or any gap model, :mod:`.gap`);
2. σ_el = σ_el(d_eq, U) (Eq. 21) and w = w(d_eq, U) (Eq. 22) from :class:`~roughcontact.electrostatics.DielectricStack`;
3. ridge area before sliding A_R0 = law.area(F_N, w) (Eq. 9 inverted);
4. friction law F_T = τ0 A_R + μ0 (F_N + σ_el A_R) (Eq. 40; τ0 = 0 gives Eq. 41) with the area reduction
   A_R = A_R0 − η F_T², η = c₂/A_R0 (Eqs. 43–44). With κ = τ0 + μ0 σ_el this is the quadratic
   κ η F_T² + F_T − (μ0 F_N + κ A_R0) = 0, whose positive root (Eq. 45) is used in the rationalised form

       F_T = 2 X / (1 + √(1 + 4 κ η X)),   X = μ0 F_N + κ A_R0,

   exact and smooth as σ_el → 0 (it gives F_T = μ0 F_N exactly at U = 0, where Eq. 45 is 0·∞).
5. μ = F_T / F_N (Eq. 42).

Inputs outside the physics: the voltage enters only through U² (Eqs. 21–22), so −U and U give the same state
(a DC voltage of either polarity; an AC amplitude). μ is defined for F_N > 0 only:
:meth:`SlidingFrictionModel.friction_coefficient` refuses F_N <= 0, because at F_N = 0 a voltage alone still
produces a finite friction force (use :meth:`~SlidingFrictionModel.tangential_force`), while the
``friction_coefficient`` field of :class:`SlidingState` records +inf there.

Saturation rule (outside the paper's 0–2.3 N): the empirical reduction law would make A_R negative when
c₂ (μ0 F_N)² > A_R0² (about 18 N for Table 1). A contact area cannot be negative, so A_R = max(A_R0 − η F_T², 0);
the self-consistent solution there is A_R = 0, F_T = μ0 F_N, reported by ``area_saturated``.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from surfaces.validation import check_broadcast, check_finite_array, check_real

from ..electrostatics import DielectricStack
from ..io.results import SavableResult
from .gap import LinearGap
from .power_law import MILLIMETRE, PowerLawContact


@dataclass(frozen=True)
class SlidingState(SavableResult):
    """State of the sliding contact at given (F_N, U); arrays broadcast over both (SI units).

    ``gap`` d_eq [m], ``attraction`` σ_el [Pa], ``work_of_adhesion`` w [J/m²], ``initial_area`` A_R0 [m²] (before
    tangential loading), ``area`` A_R [m²] (sliding), ``tangential_force`` F_T [N], ``electrostatic_force``
    F_el = σ_el A_R [N], ``friction_coefficient`` μ = F_T/F_N (Eq. 42; +inf at F_N = 0 with F_T > 0, μ0 at
    F_N = F_T = 0), ``area_saturated`` where the reduction law hit A_R = 0.
    """

    normal_force: np.ndarray
    voltage: np.ndarray
    gap: np.ndarray
    attraction: np.ndarray
    work_of_adhesion: np.ndarray
    initial_area: np.ndarray
    area: np.ndarray
    tangential_force: np.ndarray
    electrostatic_force: np.ndarray
    friction_coefficient: np.ndarray
    area_saturated: np.ndarray

    @property
    def area_reduction(self) -> np.ndarray:
        """Relative ridge-area reduction 1 − A_R/A_R0 at the onset of sliding (0 where A_R0 = 0)."""
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(self.initial_area > 0, 1 - self.area / self.initial_area, 0.0)


def _default_gap_model():
    return LinearGap.paper_table1()


@dataclass(frozen=True)
class SlidingFrictionModel:
    """Pressure-controlled sliding friction with electroadhesion and tangential area reduction (Eqs. 40–45).

    ``mu0`` μ0 [-], ``contact`` the ridge-area law: a power law (Eq. 9) or any object with a method
    ``area(normal_force, work_of_adhesion)`` [m²] (e.g. :class:`~roughcontact.macro.TabulatedArea`), ``stack`` the
    dielectric stack (Eqs. 21–22),
    ``gap_model`` any callable (F_N [N], U [V]) -> d_eq [m], ``c2`` [m⁴/N²] of η = c₂/A_R0 (Eq. 44),
    ``tau0`` the intrinsic interfacial shear strength τ0 [Pa] of Eq. 40 (0: pressure-controlled, Eq. 41).
    """

    mu0: float = 0.26
    contact: PowerLawContact = field(default_factory=PowerLawContact.table1_ridge)
    stack: DielectricStack = field(default_factory=DielectricStack)
    gap_model: object = field(default_factory=_default_gap_model)
    c2: float = 5000 * MILLIMETRE ** 4
    tau0: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "mu0", check_real("mu0", self.mu0, low=0.0, low_open=True))
        object.__setattr__(self, "c2", check_real("c2", self.c2, low=0.0))
        object.__setattr__(self, "tau0", check_real("tau0", self.tau0, low=0.0))
        if not callable(getattr(self.contact, "area", None)):
            raise TypeError("contact must have a method area(normal_force, work_of_adhesion), e.g. a PowerLawContact; "
                            f"got {type(self.contact).__name__}")
        if not isinstance(self.stack, DielectricStack):
            raise TypeError(f"stack must be a DielectricStack, got {type(self.stack).__name__}")
        if not callable(self.gap_model):
            raise TypeError(f"gap_model must be callable as gap_model(normal_force, voltage), "
                            f"got {type(self.gap_model).__name__}")

    @classmethod
    def paper_table1(cls) -> SlidingFrictionModel:
        """The seed's Table 1: μ0 = 0.26, Table-1 stack, ridge law α_R = 74 mm² N^-0.52, β_R = 43.5 mm^0.59,
        n_R = 1.41, gap d_a = 3.1 µm − 0.5 µm/N · F_N (Eq. 46), c₂ = 5000 mm⁴/N²."""
        return cls()

    def gap(self, normal_force, voltage) -> np.ndarray:
        """Equivalent air gap d_eq [m] from the gap model, checked to be finite and >= 0."""
        force, voltage = check_broadcast(normal_force=normal_force, voltage=voltage)
        gap = check_finite_array("gap_model output (equivalent gap)", self.gap_model(force, voltage),
                                 nonnegative=True)
        if gap.shape not in ((), force.shape):
            raise ValueError(f"gap_model returned shape {gap.shape} for normal_force and voltage of shape "
                             f"{force.shape}; it must return that shape (or a scalar)")
        return np.broadcast_to(gap, force.shape)

    def state(self, normal_force, voltage) -> SlidingState:
        """Full sliding state at normal force F_N [N] and voltage U [V] (Eqs. 21–22, 9, 40–45)."""
        force, voltage = check_broadcast(normal_force=normal_force, voltage=voltage)
        gap = self.gap(force, voltage)
        sigma = self.stack.attraction(gap, voltage)
        w = self.stack.work_of_adhesion(gap, voltage)
        initial_area = self.contact.area(force, w)
        kappa = self.tau0 + self.mu0 * sigma                     # shear stress per unit ridge area [Pa]
        loaded = initial_area > 0
        with np.errstate(divide="ignore", invalid="ignore"):
            mean_pressure = np.where(loaded, self.mu0 * force / initial_area, 0.0)   # μ0 F_N / A_R0 [Pa]
        drive = self.mu0 * force + kappa * initial_area           # X [N]
        if (drive < 0).any():
            index = tuple(np.argwhere(drive < 0)[0])
            raise ValueError(f"normal_force = {float(force[index])} N is so tensile that μ0 F_N + (τ0 + μ0 σ_el) A_R0 "
                             f"< 0 at voltage {float(voltage[index])} V; the friction law needs it >= 0")
        tangential = 2 * drive / (1 + np.sqrt(1 + 4 * kappa * self.c2 * (mean_pressure + kappa)))
        saturated = self.c2 * (self.mu0 * force) ** 2 > initial_area ** 2
        tangential = np.where(saturated, self.mu0 * force, tangential)
        with np.errstate(divide="ignore", invalid="ignore"):
            area = np.where(loaded & ~saturated, initial_area - self.c2 * tangential ** 2 / initial_area, 0.0)
            excess = tangential - self.mu0 * force
            mu = np.where(force > 0, tangential / force, np.where(excess > 0, np.inf, self.mu0))
        return SlidingState(normal_force=force.copy(), voltage=voltage.copy(), gap=gap, attraction=sigma,
                            work_of_adhesion=w, initial_area=initial_area, area=np.maximum(area, 0.0),
                            tangential_force=tangential, electrostatic_force=sigma * np.maximum(area, 0.0),
                            friction_coefficient=mu, area_saturated=saturated)

    def tangential_force(self, normal_force, voltage) -> np.ndarray:
        """Sliding friction force F_T [N] (Eq. 45, rationalised; Eq. 40 if τ0 > 0)."""
        return self.state(normal_force, voltage).tangential_force

    def friction_coefficient(self, normal_force, voltage) -> np.ndarray:
        """Apparent friction coefficient μ = F_T/F_N = μ0 (1 + F_el/F_N) (Eq. 42) at normal forces F_N > 0 [N]
        (``ValueError`` otherwise: μ is unbounded as F_N → 0 under voltage) and voltages U of either sign (only
        U² enters)."""
        force = check_finite_array("normal_force", normal_force)
        if (force <= 0).any():
            raise ValueError(f"friction_coefficient needs normal_force > 0, got {float(force[force <= 0].flat[0])} N: "
                             "μ = F_T/F_N is unbounded as F_N → 0 under voltage; use tangential_force() there")
        return self.state(force, voltage).friction_coefficient
