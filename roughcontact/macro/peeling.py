"""Tangential peeling under full stick (seed Eqs. 29–33): Savkoor–Briggs for a Hertzian contact, mode mixity.

Energy release rate of the compliance method with a tangential load (Eq. 29),
G = (F₁ − F_N)²/(2S²) dS/dA + F_T²/(2S_T²) dS_T/dA, with the Hertz stiffnesses S = 2E*√(A/π),
S_T = 2G*√(A/π) (Eq. 30). G = w gives the apparent area A₀(F_T, F_N) (Eq. 31) up to the critical tangential
force F_T,c (Eq. 32). SI units throughout.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from surfaces.validation import check_choice, check_finite_array, check_positive, check_real, plain

from .power_law import PowerLawContact


@dataclass(frozen=True)
class SavkoorBriggsPeeling:
    """Hertzian adhesive contact under normal force F_N and tangential force F_T in full stick (Eqs. 29–32).

    ``radius`` R* [m], ``E_star`` E* [Pa], ``G_star`` G* [Pa] with 1/G* = (2−ν₁)/(4G₁) + (2−ν₂)/(4G₂) (Eq. 30).
    """

    radius: float
    E_star: float
    G_star: float

    def __post_init__(self):
        for name in ("radius", "E_star", "G_star"):
            object.__setattr__(self, name, check_positive(name, getattr(self, name)))

    @classmethod
    def incompressible_on_rigid(cls, radius, E_star) -> SavkoorBriggsPeeling:
        """ν = 1/2 against a rigid flat: G*/E* = 2/3 (the seed's elastic-similarity choice for Fig. 5)."""
        E_star = check_positive("E_star", E_star)
        return cls(radius=radius, E_star=E_star, G_star=2 * E_star / 3)

    @property
    def hertz(self) -> PowerLawContact:
        """The non-adhesive Hertz law of this contact (Eq. 12)."""
        return PowerLawContact.hertz(self.radius, self.E_star)

    def normal_stiffness(self, area) -> np.ndarray:
        """S(A) = 2E* √(A/π) [N/m] (Eq. 30)."""
        return 2 * self.E_star * np.sqrt(check_finite_array("area", area, nonnegative=True) / np.pi)

    def tangential_stiffness(self, area) -> np.ndarray:
        """S_T(A) = 2G* √(A/π) [N/m] (Eq. 30)."""
        return 2 * self.G_star * np.sqrt(check_finite_array("area", area, nonnegative=True) / np.pi)

    def energy_release_rate(self, area, normal_force, tangential_force) -> np.ndarray:
        """G(A) [J/m²] of Eq. 29 with S, S_T from Eq. 30 (dS/dA = S/(2A), dS_T/dA = S_T/(2A))."""
        area = check_finite_array("area", area, nonnegative=True)
        normal_force = check_finite_array("normal_force", normal_force)
        tangential_force = check_finite_array("tangential_force", tangential_force)
        force_deficit = self.hertz.nonadhesive_force(area) - normal_force
        stiffness, stiffness_t = self.normal_stiffness(area), self.tangential_stiffness(area)
        return (force_deficit ** 2 / (2 * stiffness ** 2) * stiffness / (2 * area)
                + tangential_force ** 2 / (2 * stiffness_t ** 2) * stiffness_t / (2 * area))

    def _discriminant(self, tangential_force, normal_force, work_of_adhesion):
        tangential_force = check_finite_array("tangential_force", tangential_force)
        normal_force = check_finite_array("normal_force", normal_force)
        w = check_finite_array("work_of_adhesion", work_of_adhesion, nonnegative=True)
        adhesion = 3 * np.pi * self.radius * w
        normal_part = 2 * adhesion * normal_force + adhesion ** 2
        discriminant = normal_part - self.E_star / self.G_star * tangential_force ** 2
        # a deficit of 1e-12 relative is rounding (e.g. F_T computed as F_T,c), not a physically larger load
        rounding = (discriminant < 0) & (discriminant >= -1e-12 * np.abs(normal_part))
        return normal_force + adhesion, np.where(rounding, 0.0, discriminant)

    def critical_tangential_force(self, normal_force, work_of_adhesion) -> np.ndarray:
        """F_T,c = √(G*/E* (6πR*wF_N + 9π²R*²w²)) [N] (Eq. 32), end of stable peeling."""
        _, discriminant = self._discriminant(0.0, normal_force, work_of_adhesion)
        if (discriminant < 0).any():
            raise ValueError("normal_force is below the JKR pull-off force −(3/2)πwR*; valid range "
                             "[−(3/2)πwR*, inf)")
        return np.sqrt(self.G_star / self.E_star * discriminant)

    def area(self, tangential_force, normal_force, work_of_adhesion) -> np.ndarray:
        """Apparent area A₀(F_T, F_N) = π [3R*/(4E*) (F_N + 3πR*w + √(6πR*wF_N + 9π²R*²w² − E*/G* F_T²))]^(2/3)
        [m²] (Eq. 31, stable branch). |F_T| > F_T,c raises ``ValueError``."""
        shifted, discriminant = self._discriminant(tangential_force, normal_force, work_of_adhesion)
        if (discriminant < 0).any():
            raise ValueError("tangential_force exceeds the critical tangential force F_T,c of Eq. 32 (or the "
                             "normal force is below pull-off); valid range |F_T| <= F_T,c")
        return np.pi * (3 * self.radius / (4 * self.E_star) * (shifted + np.sqrt(discriminant))) ** (2 / 3)

    def mixed_mode_area(self, tangential_force, normal_force, work_of_adhesion, lam, form: int = 1,
                        n_scan: int = 2001) -> np.ndarray:
        """Apparent area [m²] with the mode-mixity toughness w̃ = w f(ψ) in place of w (Eqs. 29–31, 33).

        With P₁ = 4E*a³/(3R*) and D = P₁ − F_N, G = w f(ψ) reads
        h(D) = D² + (E*/G*) F_T² − 6πR*w (D + F_N) f(arctan(F_T/D)) = 0; the stable branch is the largest root
        D > 0, found by a logarithmic scan for the last sign change of h and bisection to machine precision.
        λ = 1 gives Eq. 31. Raises ``ValueError`` where no root exists (beyond the critical tangential force).
        """
        tangential_force, normal_force, w = np.broadcast_arrays(
            check_finite_array("tangential_force", tangential_force),
            check_finite_array("normal_force", normal_force),
            check_finite_array("work_of_adhesion", work_of_adhesion, nonnegative=True))
        lam = check_real("lam", lam, low=0.0, high=1.0)
        check_choice("form", form, {1, 2, 3})
        ratio = self.E_star / self.G_star

        def h(deficit, f_t, f_n, ww):
            psi = np.arctan2(np.abs(f_t), deficit)
            return deficit ** 2 + ratio * f_t ** 2 - 6 * np.pi * self.radius * ww * (deficit + f_n) \
                * hutchinson_suo_toughness(psi, lam, form)

        deficits = np.empty(tangential_force.shape)
        for index in np.ndindex(tangential_force.shape):
            f_t, f_n, ww = tangential_force[index], normal_force[index], w[index]
            if ww == 0 and f_t == 0:                       # Hertz: no adhesion, no tangential load
                deficits[index] = 0.0
                continue
            scale = 6 * np.pi * self.radius * ww + abs(f_n) + abs(f_t) + 1e-300
            grid = scale * np.geomspace(1e-12, 1e4, n_scan)
            values = h(grid, f_t, f_n, ww)
            rising = np.nonzero((values[:-1] <= 0) & (values[1:] > 0))[0]
            if rising.size == 0:
                raise ValueError(f"no stable contact for tangential_force = {plain(f_t)} N at normal_force = "
                                 f"{plain(f_n)} N (w = {plain(ww)} J/m², lam = {plain(lam)}): beyond the critical "
                                 "tangential force")
            low, high = grid[rising[-1]], grid[rising[-1] + 1]
            for _ in range(200):
                middle = 0.5 * (low + high)
                if middle in (low, high):
                    break
                if h(middle, f_t, f_n, ww) > 0:
                    high = middle
                else:
                    low = middle
            deficits[index] = high
        return self.hertz.nonadhesive_area(normal_force + deficits)

    def mode_mixity_angle(self, area, normal_force, tangential_force) -> np.ndarray:
        """ψ = arctan(K_II/K_I) = arctan(F_T/(F₁ − F_N)) [rad] (Eq. 33), F₁ the Hertz force at ``area``."""
        area = check_finite_array("area", area, nonnegative=True)
        deficit = self.hertz.nonadhesive_force(area) - check_finite_array("normal_force", normal_force)
        return np.arctan2(check_finite_array("tangential_force", tangential_force), deficit)


def hutchinson_suo_toughness(psi, lam, form: int = 1) -> np.ndarray:
    """Normalised interface toughness f(ψ) = Γ(ψ)/G_Ic, w → w̃ = w f(ψ) (Eq. 33; Hutchinson & Suo 1991).

    ``lam`` λ ∈ [0, 1] weights the mode-II contribution (λ = 1: f ≡ 1, ideally brittle; λ = 0: G_I = G_Ic,
    f = 1/cos²ψ for all three forms):

    * form 1: f = 1 + tan²((1 − λ)ψ)
    * form 2: f = 1 + (1 − λ) tan²ψ
    * form 3: f = 1 / (1 + (λ − 1) sin²ψ)
    """
    psi = check_finite_array("psi", psi)
    if (np.abs(psi) >= np.pi / 2).any():
        raise ValueError(f"psi must lie in (-pi/2, pi/2); got extreme value {plain(psi.flat[np.abs(psi).argmax()])}")
    lam = check_real("lam", lam, low=0.0, high=1.0)
    check_choice("form", form, {1, 2, 3})
    if form == 1:
        return 1 + np.tan((1 - lam) * psi) ** 2
    if form == 2:
        return 1 + (1 - lam) * np.tan(psi) ** 2
    return 1 / (1 + (lam - 1) * np.sin(psi) ** 2)
