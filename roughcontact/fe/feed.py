"""The FE fingertip's contact-length reduction as the ridge-area reduction of the friction law (seed Eqs. 43–44),
bottom-up instead of the fitted c₂, at the friction level of the contact (numpy only: reads the FE study's
summary table, needs no FElupe).

Electroadhesion in the FE. The attraction F_el presses the finger onto the screen at the interface only: it is
balanced there by extra contact pressure, so the tissue carries F_N while the interface's shear capacity rises to
τ ≤ μ0 (p + σ_el). In its simplest form this is a local Coulomb coefficient μ_eff = μ0 (1 + F_el/F_N) in the FE
contact (:func:`effective_friction`), the tissue loaded by f_N alone (never by f_N + f_el). The FE runs at each
(f_N, μ) give L0, ξ of Eq. 34 and L at full slip, reached at f_T = μ f_N; :class:`FEAreaReduction` holds them as
a table over f_N and μ.

From 2-D to 3-D. The finger's force F_N [N] spreads over the footprint's width w across the section, taken as
the diameter of the circle of the apparent area, w = 2 √(A_app(F_N)/π) (Dzidek et al., seed Eq. 27), so
f_N = F_N/w and f_T = F_T/w. The footprint shrinks along the sliding direction as the section does; the ridge
area inside it shrinks in the same proportion, A_R/A_R0 = L(f_T)/L0 (``isotropic=False``), or, if the footprint
shrinks alike in both directions, A_R/A_R0 = (L/L0)² (``isotropic=True``). With the linear mapping
A_R = A_R0 − η F_T², η = A_R0 ξ/(L0 w²): Eq. 43 with c₂ = A_R0² ξ/(L0 w²) [m⁴/N²] of Eq. 44.

No extrapolation. At (F_N, U) the friction law reads the FE table at μ_eff = μ0 (1 + σ_el A_R0/F_N) (τ0 A_R0
added to the drive if τ0 > 0), the interface's capacity before the area shrinks. Its solution
F_T = μ0 (F_N + σ_el A_R) ≤ μ_eff F_N because A_R ≤ A_R0, so f_T never exceeds the FE's own full slip at that
μ_eff: Eq. 34 is evaluated only where the FE computed it (checked at every point, :func:`fe_reduced_state`).
Where μ_eff or f_N lie outside the table (or a run there did not reach full slip) the reduction is not defined:
NaN, with an :class:`FETableWarning`.

Interpolation: in f_N piecewise power laws through each μ's runs (linear in log–log), in μ linear between the
tabulated coefficients.
"""
from __future__ import annotations

import warnings
from dataclasses import dataclass, field, fields, replace
from functools import lru_cache
from pathlib import Path

import numpy as np

from surfaces.validation import check_finite_array, check_real

from ..io.provenance import read_csv
from ..macro.friction import SlidingFrictionModel, SlidingState
from ..macro.power_law import PowerLawContact

#: The FE runs' summary over f_N and μ on the default mesh, written by ``python studies/fe_friction_table.py`` (the
#: format of ``roughcontact fingertip-fe``'s summary; docs/findings/fe_fingertip.md).
PACKAGED_SUMMARY = Path(__file__).with_name("fingertip_fe_summary.csv")
#: Relative slack of the no-extrapolation check f_T <= μ_eff f_N (round-off of the friction law's root).
SLIP_TOLERANCE = 1e-9


class FETableWarning(UserWarning):
    """A friction point whose μ_eff or f_N lies outside the FE table: its FE-fed values are NaN."""


def effective_friction(mu0, electrostatic_force, normal_force) -> np.ndarray:
    """μ_eff = μ0 (1 + F_el/F_N): the local Coulomb coefficient of the FE contact whose capacity at full slip,
    μ_eff F_N, is the interface's μ0 (F_N + F_el) (module docstring); μ0 > 0, F_el, F_N [N] (or per unit width),
    F_N > 0."""
    mu0 = check_real("mu0", mu0, low=0.0, low_open=True)
    force = check_finite_array("normal_force", normal_force)
    if (force <= 0).any():
        raise ValueError(f"normal_force must be > 0, got {force.min()}")
    return mu0 * (1 + check_finite_array("electrostatic_force", electrostatic_force, nonnegative=True) / force)


def footprint_width(normal_force, apparent: PowerLawContact = PowerLawContact.dzidek_apparent()) -> np.ndarray:
    """The footprint's width across the section, w = 2 √(A_app(F_N)/π) [m], at F_N [N] (``apparent``: the
    footprint law, default Dzidek et al.'s, seed Eq. 27)."""
    return 2 * np.sqrt(apparent.nonadhesive_area(normal_force) / np.pi)


def line_load(normal_force, apparent: PowerLawContact = PowerLawContact.dzidek_apparent()) -> np.ndarray:
    """The finger's F_N [N] as the section's force per unit width f_N = F_N/w [N/m] (:func:`footprint_width`)."""
    force = check_finite_array("normal_force", normal_force, nonnegative=True)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(force > 0, force / footprint_width(force, apparent), 0.0)


@dataclass(frozen=True)
class FEAreaReduction:
    """Eq. 34 per unit width from the FE runs: ``normal_forces`` f_N [N/m] (n, ascending), ``frictions`` μ
    (m, ascending), and of shape (m, n): ``initial_lengths`` L0 [m], ``xi`` ξ [m³/N²], ``sliding_lengths`` L at
    full slip [m], NaN where a run did not reach full slip; ``apparent`` the footprint law A_app(F_N) for the
    width; ``isotropic`` the mapping (module docstring)."""

    normal_forces: np.ndarray
    frictions: np.ndarray
    initial_lengths: np.ndarray
    xi: np.ndarray
    sliding_lengths: np.ndarray
    apparent: PowerLawContact = field(default_factory=PowerLawContact.dzidek_apparent)
    isotropic: bool = False

    def __post_init__(self):
        for name in ("normal_forces", "frictions"):
            axis = check_finite_array(name, getattr(self, name))
            if axis.ndim != 1 or (axis <= 0).any() or (np.diff(axis) <= 0).any():
                raise ValueError(f"{name} must be a 1-D array of positive, ascending values, got {axis}")
            object.__setattr__(self, name, axis)
        shape = (self.frictions.size, self.normal_forces.size)
        for name in ("initial_lengths", "xi", "sliding_lengths"):
            values = np.asarray(getattr(self, name), float)
            if values.shape != shape:
                raise ValueError(f"{name} has shape {values.shape}; it must be (len(frictions), len(normal_forces)) "
                                 f"= {shape}")
            if (values[np.isfinite(values)] <= 0).any():
                raise ValueError(f"{name} must be positive (NaN where a run did not reach full slip), got {values}")
            object.__setattr__(self, name, values)
        usable = np.isfinite(self.initial_lengths) & np.isfinite(self.xi) & np.isfinite(self.sliding_lengths)
        if (usable.sum(axis=1) < 2).any():
            raise ValueError(f"every friction coefficient needs at least 2 runs with full slip; the table has "
                             f"{dict(zip(self.frictions.tolist(), usable.sum(axis=1).tolist()))}")

    @classmethod
    def from_summary(cls, path=PACKAGED_SUMMARY, **kwargs) -> FEAreaReduction:
        """From the ``fingertip_fe_summary.csv`` of ``roughcontact fingertip-fe`` (runs without full slip: NaN)."""
        rows = read_csv(path)
        forces = np.unique([float(row["normal_force_N_per_m"]) for row in rows])
        frictions = np.unique([float(row["friction"]) for row in rows])
        tables = {name: np.full((frictions.size, forces.size), np.nan)
                  for name in ("initial_length_m", "xi_m3_per_N2", "sliding_length_m")}
        for row in rows:
            if row["full_slip"] != "True":
                continue
            index = (np.searchsorted(frictions, float(row["friction"])),
                     np.searchsorted(forces, float(row["normal_force_N_per_m"])))
            for name, table in tables.items():
                table[index] = float(row[name])
        return cls(forces, frictions, tables["initial_length_m"], tables["xi_m3_per_N2"],
                   tables["sliding_length_m"], **kwargs)

    def width(self, normal_force) -> np.ndarray:
        """Footprint width across the section, w = 2 √(A_app(F_N)/π) [m]."""
        return footprint_width(normal_force, self.apparent)

    def line_load(self, normal_force) -> np.ndarray:
        """f_N = F_N / w [N/m]."""
        return line_load(normal_force, self.apparent)

    def eq34(self, line_load, friction) -> tuple:
        """(L0 [m], ξ [m³/N²], L at full slip [m]) at f_N [N/m] and μ: piecewise power laws in f_N through the
        runs with full slip of each tabulated μ, linear in μ between them; NaN outside the table (f_N outside
        the runs of a bracketing μ, μ outside ``frictions``)."""
        load, friction = np.broadcast_arrays(np.asarray(line_load, float), np.asarray(friction, float))
        per_friction = np.stack([self._along_forces(k, load) for k in range(self.frictions.size)])  # (m, 3, ...)
        if self.frictions.size == 1:
            values = per_friction[0]
        else:
            upper = np.clip(np.searchsorted(self.frictions, friction), 1, self.frictions.size - 1)
            low, high = self.frictions[upper - 1], self.frictions[upper]
            share = (friction - low) / (high - low)
            below, above = (np.take_along_axis(per_friction, k[None, None], axis=0)[0] for k in (upper - 1, upper))
            values = (1 - share) * below + share * above
        inside = (friction >= self.frictions[0]) & (friction <= self.frictions[-1])
        return tuple(np.where(inside, value, np.nan) for value in values)

    def _along_forces(self, k: int, load: np.ndarray) -> np.ndarray:
        """(L0, ξ, L_slip) of friction k at f_N = ``load``, log–log between its runs; NaN outside them."""
        rows = np.stack([self.initial_lengths[k], self.xi[k], self.sliding_lengths[k]])
        usable = np.isfinite(rows).all(axis=0)
        log_force = np.log(self.normal_forces[usable])
        with np.errstate(divide="ignore", invalid="ignore"):
            log_load = np.log(load)
        inside = (log_load >= log_force[0]) & (log_load <= log_force[-1])
        return np.stack([np.where(inside, np.exp(np.interp(log_load, log_force, np.log(row[usable]))), np.nan)
                         for row in rows])

    def length_ratio(self, line_load, friction, line_tangential) -> np.ndarray:
        """L(f_T)/L0 = 1 − ξ f_T²/L0 (Eq. 34) at f_N, μ and f_T [N/m], clipped at 0; NaN outside the table and
        where |f_T| exceeds the FE's full slip μ f_N (by more than :data:`SLIP_TOLERANCE`): no extrapolation."""
        initial, xi, _ = self.eq34(line_load, friction)
        beyond = (np.abs(np.asarray(line_tangential, float))
                  > np.asarray(friction) * np.asarray(line_load) * (1 + SLIP_TOLERANCE))
        return np.where(beyond, np.nan, np.maximum(1 - xi * np.asarray(line_tangential, float) ** 2 / initial, 0.0))

    def area_ratio(self, normal_force, tangential_force, friction) -> np.ndarray:
        """A/A0 at F_N, F_T [N] in the FE at μ: L/L0 or (L/L0)² (``isotropic``)."""
        force = check_finite_array("normal_force", normal_force, nonnegative=True)
        width = self.width(force)
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = self.length_ratio(force / width, friction, np.asarray(tangential_force, float) / width)
        return ratio ** 2 if self.isotropic else ratio


def fe_reduced_state(model: SlidingFrictionModel, normal_force, voltage, reduction: FEAreaReduction
                     ) -> tuple:
    """(state, μ_eff): the sliding state of ``model`` (its gap, area law, stack, μ0, τ0) with the FE-derived area
    reduction in place of its c₂, and the FE's friction coefficient μ_eff = (μ0 F_N + (τ0 + μ0 σ_el) A_R0)/F_N
    at each (F_N [N] > 0, U [V]) (module docstring). The reduction is the FE's at μ_eff, as the c₂ that puts
    Eq. 43 through the mapped FE area at the law's solution (exact for the linear mapping at every F_T).
    NaN (with an :class:`FETableWarning`) where the table does not cover (f_N, μ_eff); ``RuntimeError`` if a
    solution had f_T beyond the FE's full slip (it cannot: A_R <= A_R0)."""
    force, voltage = np.broadcast_arrays(np.asarray(normal_force, float), np.asarray(voltage, float))
    base = model.state(force, voltage)
    initial_area = base.initial_area
    mu_eff = (model.mu0 * force + (model.tau0 + model.mu0 * base.attraction) * initial_area) / force
    width, line_load = reduction.width(force), reduction.line_load(force)
    initial, xi, _ = reduction.eq34(line_load, mu_eff)
    c2 = initial_area ** 2 * xi / (initial * width ** 2)
    states = []
    for index in np.ndindex(force.shape):
        if not np.isfinite(c2[index]):
            states.append(None)
            continue
        state = replace(model, c2=float(c2[index])).state(force[index], voltage[index])
        if reduction.isotropic:
            state = _isotropic(model, state, reduction, mu_eff[index], width[index])
        states.append(state)
    outside = [index for index, state in zip(np.ndindex(force.shape), states) if state is None]
    if outside:
        warnings.warn("the FE table (f_N " f"{reduction.normal_forces.min():g}–{reduction.normal_forces.max():g} "
                      f"N/m, mu {reduction.frictions.min():g}–{reduction.frictions.max():g}) does not cover "
                      + ", ".join(f"F_N = {force[i]:g} N, U = {voltage[i]:g} V (f_N = {line_load[i]:.4g} N/m, "
                                  f"mu_eff = {mu_eff[i]:.4g})" for i in outside)
                      + "; their FE-fed values are NaN", FETableWarning, stacklevel=2)
    names = [f.name for f in fields(SlidingState)]
    nan = {name: np.nan for name in names}
    result = SlidingState(**{name: np.array([nan[name] if s is None else getattr(s, name) for s in states],
                                            dtype=float).reshape(force.shape) for name in names})
    beyond = result.tangential_force / width > mu_eff * line_load * (1 + SLIP_TOLERANCE)
    if beyond.any():
        raise RuntimeError(f"the friction law evaluated Eq. 34 beyond the FE's full slip at F_N = "
                           f"{force[beyond].tolist()} N")
    return result, mu_eff


def _isotropic(model, state, reduction, mu_eff, width) -> SlidingState:
    """The law's solution with A_R/A_R0 = (L/L0)²: F_T = μ0 F_N + κ A_R0 (L(f_T)/L0)² by bisection between
    μ0 F_N and the linear mapping's F_T (the right side falls with F_T), as the state of the c₂ through it."""
    force, initial_area = float(state.normal_force), float(state.initial_area)
    kappa = model.tau0 + model.mu0 * float(state.attraction)
    residual = lambda f_t: (model.mu0 * force + kappa * initial_area   # noqa: E731
                            * reduction.area_ratio(force, f_t, mu_eff) - f_t)
    low, high = model.mu0 * force, float(state.tangential_force)
    for _ in range(200):
        middle = (low + high) / 2
        low, high = (middle, high) if residual(middle) > 0 else (low, middle)
        if high - low <= 1e-15 * high:
            break
    f_t = (low + high) / 2
    area = initial_area * float(reduction.area_ratio(force, f_t, mu_eff))
    c2 = (initial_area - area) * initial_area / f_t ** 2 if f_t > 0 else 0.0
    return replace(model, c2=c2).state(force, float(state.voltage))


@lru_cache(maxsize=1)
def _packaged() -> FEAreaReduction:
    return FEAreaReduction.from_summary(PACKAGED_SUMMARY)


def fe_friction_columns(model: SlidingFrictionModel, normal_force: float, voltage: float,
                        reduction: FEAreaReduction | None = None) -> dict:
    """The friction table's FE columns at one (F_N [N], U [V]) for ``model`` (the bottom-up friction law):
    μ and the relative ridge-area reduction at the onset of sliding with the FE-derived reduction at μ_eff
    (default: the packaged table), the c₂ it amounts to [mm⁴/N², the seed's unit] and μ_eff (NaN outside the
    table, warned)."""
    reduction = _packaged() if reduction is None else reduction
    state, mu_eff = fe_reduced_state(model, normal_force, voltage, reduction)
    lost = state.initial_area - state.area                  # c₂ = (A_R0 − A_R) A_R0 / F_T² of Eq. 43
    return {"bottom_up_fe_friction_coefficient": float(state.friction_coefficient),
            "bottom_up_fe_area_reduction": float(state.area_reduction),
            "bottom_up_fe_c2_mm4_per_N2": float(lost * state.initial_area / state.tangential_force ** 2) * 1e12,
            "bottom_up_fe_contact_friction": float(mu_eff)}
