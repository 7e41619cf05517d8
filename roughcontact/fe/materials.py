"""Hyperelastic tissue parameters of the finger section (SI units).

Each tissue is an Ogden solid (Ogden 1973) with a nearly-incompressible volumetric part,

    ψ = Σ_i 2 μ_i/α_i² (λ̄1^α_i + λ̄2^α_i + λ̄3^α_i − 3) + K (J̄ − 1)²/2,

λ̄ the isochoric principal stretches; the initial shear modulus is μ = Σ μ_i and α = 2 is neo-Hooke. The
default values are assumptions (Wu et al.'s coefficients were not available; ``docs/guide/fe_fingertip.md`` gives
their sources and the measured sensitivity of the results to them).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from surfaces.validation import check_real


@dataclass(frozen=True)
class OgdenMaterial:
    """Ogden moduli ``mu`` μ_i [Pa] and exponents ``alpha`` α_i [-] (as many), bulk modulus ``bulk`` K [Pa]."""

    mu: tuple
    alpha: tuple
    bulk: float

    def __post_init__(self):
        mu = tuple(check_real("mu", m) for m in np.atleast_1d(self.mu))
        alpha = tuple(check_real("alpha", a) for a in np.atleast_1d(self.alpha))
        if len(mu) != len(alpha) or not mu:
            raise ValueError(f"mu and alpha need the same number (>= 1) of terms, got {len(mu)} and {len(alpha)}")
        if any(a == 0 for a in alpha) or sum(m * a for m, a in zip(mu, alpha)) <= 0:
            raise ValueError(f"Ogden terms need alpha_i != 0 and sum(mu_i alpha_i) > 0 (stability), got mu = {mu} "
                             f"Pa, alpha = {alpha}")
        object.__setattr__(self, "mu", mu)
        object.__setattr__(self, "alpha", alpha)
        object.__setattr__(self, "bulk", check_real("bulk", self.bulk, low=0.0, low_open=True))

    @classmethod
    def nearly_incompressible(cls, mu, alpha, poisson: float = 0.49) -> OgdenMaterial:
        """The Ogden terms with the bulk modulus of Poisson's ratio ν at small strain, K = 2μ(1+ν)/(3(1−2ν))."""
        poisson = check_real("poisson", poisson, low=-1.0, high=0.5, low_open=True, high_open=True)
        shear = float(np.sum(mu))
        return cls(mu=tuple(np.atleast_1d(mu)), alpha=tuple(np.atleast_1d(alpha)),
                   bulk=2 * shear * (1 + poisson) / (3 * (1 - 2 * poisson)))

    @property
    def shear_modulus(self) -> float:
        """Initial shear modulus μ = Σ μ_i [Pa]."""
        return float(sum(self.mu))

    @property
    def plane_strain_modulus(self) -> float:
        """E* = E/(1 − ν²) at small strain [Pa] (the Hertz modulus against a rigid plate)."""
        shear, bulk = self.shear_modulus, self.bulk
        young = 9 * bulk * shear / (3 * bulk + shear)
        poisson = (3 * bulk - 2 * shear) / (2 * (3 * bulk + shear))
        return young / (1 - poisson ** 2)


def _skin():
    return OgdenMaterial.nearly_incompressible(mu=(60e3,), alpha=(9.0,))


def _subcutaneous():
    return OgdenMaterial.nearly_incompressible(mu=(8e3,), alpha=(8.0,))


def _nail():
    return OgdenMaterial.nearly_incompressible(mu=(57e6,), alpha=(2.0,), poisson=0.3)


@dataclass(frozen=True)
class FingerMaterials:
    """The three tissues; ``docs/guide/fe_fingertip.md`` states the defaults (assumed) and their sensitivity."""

    skin: OgdenMaterial = field(default_factory=_skin)
    subcutaneous: OgdenMaterial = field(default_factory=_subcutaneous)
    nail: OgdenMaterial = field(default_factory=_nail)

    def __post_init__(self):
        for name in ("skin", "subcutaneous", "nail"):
            if not isinstance(getattr(self, name), OgdenMaterial):
                raise TypeError(f"{name} must be an OgdenMaterial, got {type(getattr(self, name)).__name__}")

    @classmethod
    def homogeneous(cls, shear_modulus: float, poisson: float) -> FingerMaterials:
        """One neo-Hookean solid everywhere (α = 2): the Hertz check."""
        solid = OgdenMaterial.nearly_incompressible(mu=(shear_modulus,), alpha=(2.0,), poisson=poisson)
        return cls(skin=solid, subcutaneous=solid, nail=solid)

    def by_label(self) -> tuple:
        """The materials in the order of the mesh labels (``geometry.SUBCUTANEOUS``, ``SKIN``, ``NAIL``)."""
        return (self.subcutaneous, self.skin, self.nail)
