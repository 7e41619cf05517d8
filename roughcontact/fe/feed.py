"""The FE fingertip's contact-length reduction as the ridge-area reduction of the friction law (seed Eqs. 43–44),
bottom-up instead of the fitted c₂ (numpy only: reads the FE study's summary table, needs no FElupe).

From 2-D to 3-D. The FE section gives, per unit width, L(f_T) = L0(f_N) − ξ(f_N) f_T² (Eq. 34). The finger's
force F_N [N] spreads over the footprint's width w across the section, taken as the diameter of the circle of
the apparent area, w = 2 √(A_app(F_N)/π) (Dzidek et al., seed Eq. 27), so f_N = F_N/w and f_T = F_T/w.
Assumption: the footprint shrinks only along the sliding direction, as the section does, and the ridge area
inside it shrinks in the same proportion, so

    A_R(F_T) / A_R0 = L(f_T) / L0   ⇒   A_R = A_R0 − η F_T²,  η = A_R0 ξ(f_N) / (L0(f_N) w²),

which is Eq. 43 with the equivalent c₂ = η A_R0 = A_R0² ξ / (L0 w²) [m⁴/N²] of Eq. 44 (a function of F_N
and A_R0 here, a constant in the seed). If the footprint shrank isotropically instead, the area ratio would be
(L/L0)², about twice the reduction for small reductions: ``isotropic=True``.

L0 and ξ are interpolated between the FE runs as piecewise power laws (linear in log–log; ξ is a power law
only from f_N ≈ 100 N/m up, docs/guide/fe_fingertip.md); outside the sweep's f_N range the end segments continue.
The FE law holds without adhesion up to F_T = μ_FE F_N; the friction law under voltage uses it at larger F_T.
"""
from __future__ import annotations

from dataclasses import dataclass, field, fields, replace
from functools import lru_cache
from pathlib import Path

import numpy as np

from surfaces.validation import check_finite_array

from ..macro.friction import SlidingFrictionModel, SlidingState
from ..macro.power_law import PowerLawContact
from ..io.provenance import read_csv

#: The default FE sweep's summary, written by ``roughcontact fingertip-fe`` (see docs/guide/fe_fingertip.md).
PACKAGED_SUMMARY = Path(__file__).with_name("fingertip_fe_summary.csv")


@dataclass(frozen=True)
class FEAreaReduction:
    """Eq. 34 per unit width from the FE runs: ``normal_forces`` f_N [N/m], ``initial_lengths`` L0 [m], ``xi``
    ξ [m³/N²]; ``apparent`` the 3-D footprint law A_app(F_N) for the width; ``isotropic`` the mapping (module
    docstring)."""

    normal_forces: np.ndarray
    initial_lengths: np.ndarray
    xi: np.ndarray
    apparent: PowerLawContact = field(default_factory=PowerLawContact.dzidek_apparent)
    isotropic: bool = False

    def __post_init__(self):
        for name in ("normal_forces", "initial_lengths", "xi"):
            values = check_finite_array(name, getattr(self, name))
            if values.ndim != 1 or values.size < 3 or (values <= 0).any():
                raise ValueError(f"{name} must be a 1-D array of at least 3 positive values, got {values}")
            object.__setattr__(self, name, values)
        if not self.normal_forces.size == self.initial_lengths.size == self.xi.size:
            raise ValueError("normal_forces, initial_lengths and xi need the same length")

    @classmethod
    def from_summary(cls, path=PACKAGED_SUMMARY, **kwargs) -> FEAreaReduction:
        """From the ``fingertip_fe_summary.csv`` of ``roughcontact fingertip-fe`` (runs with full slip)."""
        rows = [row for row in read_csv(path) if row["full_slip"] == "True"]
        column = lambda name: np.array([float(row[name]) for row in rows])   # noqa: E731
        return cls(column("normal_force_N_per_m"), column("initial_length_m"), column("xi_m3_per_N2"), **kwargs)

    def width(self, normal_force) -> np.ndarray:
        """Footprint width across the section, w = 2 √(A_app(F_N)/π) [m]."""
        return 2 * np.sqrt(self.apparent.nonadhesive_area(normal_force) / np.pi)

    def line_load(self, normal_force) -> np.ndarray:
        """f_N = F_N / w [N/m]."""
        force = check_finite_array("normal_force", normal_force, nonnegative=True)
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(force > 0, force / self.width(force), 0.0)

    def eq34(self, line_load) -> tuple:
        """(L0 [m], ξ [m³/N²]) at f_N [N/m]: piecewise power laws through the FE runs (linear in log–log),
        continued by the end segments outside them."""
        log_load = np.log(np.asarray(line_load, float))
        order = np.argsort(self.normal_forces)
        log_force = np.log(self.normal_forces[order])

        def segment(log_values, a, b):          # the line through runs a and b, in log–log
            slope = (log_values[b] - log_values[a]) / (log_force[b] - log_force[a])
            return log_values[a] + slope * (log_load - log_force[a])

        def through(values):
            log_values = np.log(values[order])
            inside = np.interp(log_load, log_force, log_values)
            outside = np.where(log_load < log_force[0], segment(log_values, 0, 1), segment(log_values, -2, -1))
            return np.exp(np.where((log_load < log_force[0]) | (log_load > log_force[-1]), outside, inside))

        return through(self.initial_lengths), through(self.xi)

    def area_ratio(self, normal_force, tangential_force) -> np.ndarray:
        """A_R/A_R0 at F_N, F_T [N] (clipped at 0)."""
        force = check_finite_array("normal_force", normal_force, nonnegative=True)
        initial, xi = self.eq34(self.line_load(force))
        with np.errstate(divide="ignore", invalid="ignore"):
            shear = np.where(force > 0, np.asarray(tangential_force, float) / self.width(force), 0.0)
        ratio = np.maximum(1 - xi * shear ** 2 / initial, 0.0)
        return ratio ** 2 if self.isotropic else ratio

    def c2(self, normal_force, initial_area) -> np.ndarray:
        """The equivalent c₂ = A_R0² ξ/(L0 w²) of Eq. 44 [m⁴/N²] (the linear mapping; ×2 for ``isotropic``,
        its small-reduction limit)."""
        force = check_finite_array("normal_force", normal_force, nonnegative=True)
        initial, xi = self.eq34(self.line_load(force))
        with np.errstate(divide="ignore", invalid="ignore"):
            area = np.asarray(initial_area, float)
            c2 = np.where(force > 0, area ** 2 * xi / (initial * self.width(force) ** 2), 0.0)
        return 2 * c2 if self.isotropic else c2


def fe_reduced_state(model: SlidingFrictionModel, normal_force, voltage, reduction: FEAreaReduction) -> SlidingState:
    """The sliding state of ``model`` (its gap, area law, stack, μ0, τ0) with the FE-derived area reduction in
    place of its c₂: at each (F_N, U), c₂ = ``reduction.c2(F_N, A_R0)`` (A_R0 of ``model`` does not depend on
    c₂)."""
    force, voltage = np.broadcast_arrays(np.asarray(normal_force, float), np.asarray(voltage, float))
    initial_area = model.state(force, voltage).initial_area
    c2 = reduction.c2(force, initial_area)
    states = [replace(model, c2=float(c)).state(f, u) for c, f, u in zip(c2.ravel(), force.ravel(), voltage.ravel())]
    return SlidingState(**{f.name: np.array([getattr(s, f.name) for s in states]).reshape(force.shape)
                           for f in fields(SlidingState)})


@lru_cache(maxsize=1)
def _packaged() -> FEAreaReduction:
    return FEAreaReduction.from_summary(PACKAGED_SUMMARY)


def fe_friction_columns(model: SlidingFrictionModel, normal_force: float, voltage: float,
                        reduction: FEAreaReduction | None = None) -> dict:
    """The friction table's FE columns at one (F_N [N], U [V]) for ``model`` (the bottom-up friction law):
    μ and the relative ridge-area reduction at the onset of sliding with the FE-derived reduction (default:
    the packaged table), and the c₂ it amounts to [mm⁴/N², the seed's unit]."""
    reduction = _packaged() if reduction is None else reduction
    state = fe_reduced_state(model, normal_force, voltage, reduction)
    return {"bottom_up_fe_friction_coefficient": float(state.friction_coefficient),
            "bottom_up_fe_area_reduction": float(state.area_reduction),
            "bottom_up_fe_c2_mm4_per_N2": float(reduction.c2(normal_force, state.initial_area)) * 1e12}
