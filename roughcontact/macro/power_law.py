"""Shull's compliance method for power-law contacts (seed Eqs. 1–14): the adhesive solution from the non-adhesive one.

The non-adhesive contact is given by two power laws (Eqs. 5–6),

    A = α F₁^m,   A = β δ₁^n,   0 < m < n,

and the adhesive solution follows from Eq. 1 with G = w (errata (a), (b) in ``docs/findings/errata.md``):

    F₁ − F_N = S √(2w / (dS/dA)) = n √(2 w A F₁ / ((n − m) δ₁)),
    δ₁ − δ   =   √(2w / (dS/dA)) = m √(2 w A δ₁ / ((n − m) F₁)).

Written with the non-adhesive load F₁ as the variable, the force is a difference of two power laws,

    F_N = F₁ − k F₁^s,   s = (1 + m − m/n)/2,   k = n √(2 w α^(1−1/n) β^(1/n) / (n − m)),

which gives the pull-off force (dF_N/dF₁ = 0) and the zero-load area in closed form. 0 < s < 1 is required for
a finite pull-off force, i.e. 1/m + 1/n > 1 (true for every half-space law, m = 2n/(n + 2) with n < 4).

All quantities SI: areas m², forces N, lengths m, work of adhesion J/m².
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from surfaces.validation import check_broadcast, check_finite_array, check_integer, check_positive, check_real, plain

from ..io.results import SavableResult

#: 1 mm in m, for the seed's mm-based parameter sets.
MILLIMETRE = 1e-3


@dataclass(frozen=True)
class PullOff(SavableResult):
    """Pull-off point of an adhesive power-law contact (global minimum of F_N(A), Eq. 9).

    ``force`` [N] is negative (tensile), ``area`` [m²] and ``indentation`` [m] at that point,
    ``work_of_adhesion`` [J/m²] the w it belongs to.
    """

    force: np.ndarray
    area: np.ndarray
    indentation: np.ndarray
    work_of_adhesion: np.ndarray


@dataclass(frozen=True)
class PowerLawContact:
    """Non-adhesive power laws A = α F₁^m (Eq. 5), A = β δ₁^n (Eq. 6) and their adhesive extension (Eqs. 7–10).

    SI parameters: ``alpha`` [m² N^-m], ``beta`` [m^(2-n)]; ``m``, ``n`` dimensionless with 0 < m < n and
    1/m + 1/n > 1 (finite pull-off force).
    """

    m: float
    alpha: float
    n: float
    beta: float

    def __post_init__(self):
        for name in ("m", "alpha", "n", "beta"):
            object.__setattr__(self, name, check_positive(name, getattr(self, name)))
        if not self.m < self.n:
            raise ValueError(f"m = {self.m!r} must be smaller than n = {self.n!r}; valid range 0 < m < n "
                             "(dS/dA > 0, Eq. 8)")
        if not 1 / self.m + 1 / self.n > 1:
            raise ValueError(f"1/m + 1/n = {1 / self.m + 1 / self.n!r} must exceed 1 (m = {self.m!r}, "
                             f"n = {self.n!r}); otherwise the adhesive term of Eq. 9 dominates at large area and "
                             "there is no finite pull-off force")

    # -- presets -------------------------------------------------------------------------------------------
    @classmethod
    def from_millimetres(cls, m, alpha_mm, n, beta_mm) -> PowerLawContact:
        """Law from the seed's units: ``alpha_mm`` [mm² N^-m], ``beta_mm`` [mm^(2-n)]."""
        m, n = check_positive("m", m), check_positive("n", n)
        return cls(m=m, alpha=check_positive("alpha_mm", alpha_mm) * MILLIMETRE ** 2, n=n,
                   beta=check_positive("beta_mm", beta_mm) * MILLIMETRE ** (2 - n))

    @classmethod
    def dzidek_apparent(cls) -> PowerLawContact:
        """Apparent area of Dzidek et al. (2017), seed Eq. 27: m₀ = 0.37, α₀ = 91.9 mm² N^-m₀, n₀ = 1, β₀ = 64.4 mm."""
        return cls.from_millimetres(0.37, 91.9, 1.0, 64.4)

    @classmethod
    def dzidek_ridge(cls) -> PowerLawContact:
        """Ridge area of Dzidek et al. (2017), seed Eq. 28: m_R = 0.52, α_R = 54.9 mm² N^-m_R, n_R = 1.41,
        β_R = 33.3 mm^(2-n_R) (erratum (c): the seed prints the unit of β as mm² N^-n)."""
        return cls.from_millimetres(0.52, 54.9, 1.41, 33.3)

    @classmethod
    def table1_ridge(cls) -> PowerLawContact:
        """Ridge area scaled to Delhaye/Sirin data, seed Table 1: α_R = 74 mm² N^-m_R, β_R = 43.5 mm^(2-n_R)."""
        return cls.from_millimetres(0.52, 74.0, 1.41, 43.5)

    @classmethod
    def hertz(cls, radius, E_star) -> PowerLawContact:
        """Hertz contact (Eq. 12): m = 2/3, n = 1, β = π R*, α = π (3R*/(4E*))^(2/3); R* [m], E* [Pa].

        With Eqs. 9–10 it gives the JKR solution (Eqs. 13–14).
        """
        radius, E_star = check_positive("radius", radius), check_positive("E_star", E_star)
        return cls(m=2 / 3, alpha=np.pi * (3 * radius / (4 * E_star)) ** (2 / 3), n=1.0, beta=np.pi * radius)

    # -- non-adhesive contact ------------------------------------------------------------------------------
    def nonadhesive_force(self, area) -> np.ndarray:
        """F₁(A) = (A/α)^(1/m) [N] (Eq. 5 inverted)."""
        return (check_finite_array("area", area, nonnegative=True) / self.alpha) ** (1 / self.m)

    def nonadhesive_indentation(self, area) -> np.ndarray:
        """δ₁(A) = (A/β)^(1/n) [m] (Eq. 6 inverted)."""
        return (check_finite_array("area", area, nonnegative=True) / self.beta) ** (1 / self.n)

    def nonadhesive_area(self, normal_force) -> np.ndarray:
        """A(F₁) = α F₁^m [m²] (Eq. 5)."""
        return self.alpha * check_finite_array("normal_force", normal_force, nonnegative=True) ** self.m

    def stiffness(self, area) -> np.ndarray:
        """Normal contact stiffness S = dF₁/dδ₁ = (n/m) β^(1/n) α^(-1/m) A^(1/m − 1/n) [N/m] (Eqs. 2, 7)."""
        area = check_finite_array("area", area, nonnegative=True)
        return (self.n / self.m) * self.beta ** (1 / self.n) * self.alpha ** (-1 / self.m) \
            * area ** (1 / self.m - 1 / self.n)

    def stiffness_derivative(self, area) -> np.ndarray:
        """dS/dA = (n − m)/(n m) · S/A [N/m³] (Eq. 8)."""
        area = check_finite_array("area", area, nonnegative=True)
        return (self.n - self.m) / (self.m ** 2) * self.beta ** (1 / self.n) * self.alpha ** (-1 / self.m) \
            * area ** (1 / self.m - 1 / self.n - 1)

    # -- adhesive contact (Eqs. 3-4, 9-10) -----------------------------------------------------------------
    @property
    def force_exponent(self) -> float:
        """s in F_N = F₁ − k F₁^s: s = (1 + m − m/n)/2, 0 < s < 1."""
        return 0.5 * (1 + self.m - self.m / self.n)

    def adhesion_coefficient(self, work_of_adhesion) -> np.ndarray:
        """k(w) = n √(2 w α^(1−1/n) β^(1/n)/(n − m)) [N^(1−s)] in F_N = F₁ − k F₁^s."""
        w = check_finite_array("work_of_adhesion", work_of_adhesion, nonnegative=True)
        return self.n * np.sqrt(2 * w * self.alpha ** (1 - 1 / self.n) * self.beta ** (1 / self.n)
                                / (self.n - self.m))

    def normal_force(self, area, work_of_adhesion) -> np.ndarray:
        """Adhesive normal force F_N(A) = F₁ − n √(2 w A F₁/((n − m) δ₁)) [N] (Eq. 9, corrected prefactor n²)."""
        area = check_finite_array("area", area, nonnegative=True)
        w = check_finite_array("work_of_adhesion", work_of_adhesion, nonnegative=True)
        force_1 = self.nonadhesive_force(area)
        return force_1 - self.n * np.sqrt(2 * w * self.alpha ** (1 - 1 / self.n) * self.beta ** (1 / self.n)
                                          / (self.n - self.m) * force_1 ** (2 * self.force_exponent))

    def indentation(self, area, work_of_adhesion) -> np.ndarray:
        """Adhesive indentation δ(A) = δ₁ − m √(2 w A δ₁/((n − m) F₁)) [m] (Eq. 10).

        The adhesive term scales as A^((1 − 1/m + 1/n)/2); for laws with 1/m > 1 + 1/n (e.g. Dzidek's apparent
        area) it diverges as A → 0, so δ(0) = −inf for w > 0 (and δ₁ = 0 for w = 0).
        """
        area = check_finite_array("area", area, nonnegative=True)
        w = check_finite_array("work_of_adhesion", work_of_adhesion, nonnegative=True)
        exponent = 1 - 1 / self.m + 1 / self.n
        with np.errstate(divide="ignore", invalid="ignore"):
            adhesive = np.sqrt(2 * w * self.m ** 2 / (self.n - self.m) * self.beta ** (-1 / self.n)
                               * self.alpha ** (1 / self.m) * area ** exponent)
        return self.nonadhesive_indentation(area) - np.where(w > 0, adhesive, 0.0)

    def pull_off(self, work_of_adhesion) -> PullOff:
        """Pull-off under load control: the global minimum of F_N(A) (closed form).

        dF_N/dF₁ = 1 − s k F₁^(s−1) = 0 gives F₁,c = (s k)^(1/(1−s)) and F_c = −F₁,c (1 − s)/s [N] < 0.
        For Hertz (s = 1/2): F_c = −(3/2) π w R (JKR).
        """
        w = check_finite_array("work_of_adhesion", work_of_adhesion, nonnegative=True)
        s = self.force_exponent
        force_1 = (s * self.adhesion_coefficient(w)) ** (1 / (1 - s))
        area = self.nonadhesive_area(force_1)
        return PullOff(force=-force_1 * (1 - s) / s, area=area, indentation=self.indentation(area, w),
                       work_of_adhesion=w)

    def zero_load_area(self, work_of_adhesion) -> np.ndarray:
        """Contact area at F_N = 0 (adhesion-only contact): F₁ = k^(1/(1−s)), A = α F₁^m [m²]."""
        return self.nonadhesive_area(self.adhesion_coefficient(work_of_adhesion) ** (1 / (1 - self.force_exponent)))

    def area(self, normal_force, work_of_adhesion, *, rtol: float = 1e-14, maxiter: int = 200) -> np.ndarray:
        """Contact area A [m²] on the stable branch (dF_N/dA > 0) of Eq. 9 for a given normal force [N].

        Solves F₁ − k F₁^s = F_N for F₁ ≥ F₁,c by Newton's method; g(F₁) = F₁ − k F₁^s − F_N is convex and
        increasing there, so the iteration started at F₁ = max(2 F_N, (2k)^(1/(1−s))) (where g ≥ 0) descends
        monotonically onto the root. Broadcasts over ``normal_force`` and ``work_of_adhesion``. A normal force
        below the pull-off force raises ``ValueError``. ``rtol`` in (0, 1) is the relative step at which F₁ counts
        as converged; ``maxiter`` >= 0 bounds the Newton steps (0: only inputs that need none, w = 0 or F₁ = 0).
        """
        rtol = check_real("rtol", rtol, low=0.0, high=1.0, low_open=True, high_open=True)
        maxiter = check_integer("maxiter", maxiter, low=0)
        force, w = check_broadcast(normal_force=normal_force,
                                   work_of_adhesion=check_finite_array("work_of_adhesion", work_of_adhesion,
                                                                       nonnegative=True))
        s, k = self.force_exponent, self.adhesion_coefficient(w)
        pull_off = self.pull_off(w)
        # one part in 1e12 of the pull-off force is rounding, not a physically lower load
        too_low = force < pull_off.force * (1 + 1e-12)
        if too_low.any():
            index = np.argwhere(too_low)[0]
            raise ValueError(f"normal_force = {plain(force[tuple(index)])} N is below the pull-off force "
                             f"{plain(pull_off.force[tuple(index)])} N (w = {plain(w[tuple(index)])} J/m²); "
                             "valid range [pull-off force, inf)")
        force_1_c = (s * k) ** (1 / (1 - s))
        force_1 = np.maximum(2 * np.maximum(force, 0.0), (2 * k) ** (1 / (1 - s)))
        adhesive = k > 0
        force_1 = np.where(adhesive, force_1, np.maximum(force, 0.0))   # w = 0: F₁ = F_N exactly
        active = adhesive & (force_1 > 0)
        for _ in range(maxiter):
            if not active.any():
                break
            x, kk, f = force_1[active], k[active], force[active]
            residual = x - kk * x ** s - f
            slope = 1 - s * kk * x ** (s - 1)
            with np.errstate(divide="ignore", invalid="ignore"):
                step = np.where(residual > 0, residual / slope, 0.0)
            new = np.maximum(x - step, force_1_c[active])
            force_1[active] = new
            converged = (x - new <= rtol * new) | (residual <= 0)
            still = np.zeros_like(active)
            still[active] = ~converged
            active = still
        if active.any():
            raise RuntimeError(f"area(): Newton iteration did not converge in maxiter = {maxiter} steps "
                               f"(rtol = {rtol:g})")
        return self.nonadhesive_area(force_1)
