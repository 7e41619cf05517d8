"""The seed's friction law fed bottom-up from a study, and the errors of the equivalent-gap assumption.

:func:`friction_recipe` is the recommended bottom-up friction model (the ridge-area recipe,
``docs/guide/friction_model.md``): d_eq,R(F_N, U) (:class:`~roughcontact.macro.TabulatedGap`) and A_R(F_N, w)
(:class:`~roughcontact.macro.TabulatedArea`) in :class:`~roughcontact.macro.SlidingFrictionModel` with the seed's
μ0 and c₂; :func:`bottom_up_friction` feeds it from a study (or from a finished results directory through
:func:`~.run.open_results`), :func:`friction_realisations` evaluates it per realisation for the uncertainty. d_eq,R is the uniform gap whose Eq. 21 attraction over A_R equals the solved field
force F_el (σ_el(d_eq,R) A_R = F_el), so the friction law's σ_el A_R is the solve's attraction whatever the field
model. The law interpolates its tables in F_N, so it needs at least two loads (:data:`FRICTION_MIN_LOADS`).
:func:`assumption_errors` measures what a voltage-independent gap, the arithmetic mean gap or the per-pixel
field (Eq. 21 pixel by pixel) would make of the electrostatic force.
"""
from __future__ import annotations

import numpy as np

from surfaces.validation import check_finite_array

from ..electrostatics import DielectricStack
from ..macro import SlidingFrictionModel, TabulatedArea, TabulatedGap
from ..macro.gap import table_axis
from .run import StudyResult

#: Relative error of the electrostatic force within which the report counts the equivalent-gap assumption as held.
HOLDS_WITHIN = 0.10
#: Loads the bottom-up friction law needs: its gap and area tables are interpolated in F_N.
FRICTION_MIN_LOADS = 2


def friction_computed(result: StudyResult) -> bool:
    """Whether the study has the loads the friction law needs (:data:`FRICTION_MIN_LOADS`) and a converged
    realisation at every point (its tables are realisation means: :func:`unconverged_points`)."""
    return len(result.normal_forces) >= FRICTION_MIN_LOADS and not unconverged_points(result)


def unconverged_points(result: StudyResult) -> str:
    """The points without a converged realisation, "F_N N at U V" joined by commas ("" if none): their
    realisation means are NaN."""
    converged = result.array("converged").astype(bool)
    none = ~converged.reshape(*converged.shape[:2], -1).any(axis=-1)
    return ", ".join(f"{result.normal_forces[i]:g} N at {result.voltages[j]:g} V" for i, j in zip(*np.nonzero(none)))


def friction_recipe(normal_forces, voltages, ridge_gaps, ridge_areas, stack, c2: float | None = None
                    ) -> SlidingFrictionModel:
    """The recommended bottom-up friction model, the *ridge-area recipe* (``docs/guide/friction_model.md``): the
    seed's friction law (Eqs. 41–45, μ0 and, unless ``c2`` [m⁴/N²] is given, c₂ of Table 1) applying σ_el of
    the gap ``ridge_gaps`` d_eq,R [m] on the ridge area ``ridge_areas`` A_R [m²], both of shape
    (len(normal_forces), len(voltages)) at ``normal_forces`` [N] (>= 2) and ``voltages`` [V] (one: voltage
    independent). d_eq,R is the uniform gap with σ_el(d_eq,R) A_R = the solved F_el, so the law's attraction is
    the solved one; A_R(F_N, w) replaces Eq. 9, with w = w(d_eq,R, U) of Eq. 22 (made non-decreasing in U)."""
    if not isinstance(stack, DielectricStack):
        raise TypeError(f"stack must be a DielectricStack, got {type(stack).__name__}")
    forces = table_axis("normal_forces", normal_forces, FRICTION_MIN_LOADS, nonnegative=True)
    voltages = table_axis("voltages", voltages, 1, nonnegative=True)
    gaps, areas = (check_finite_array(name, values, nonnegative=True)
                   for name, values in (("ridge_gaps", ridge_gaps), ("ridge_areas", ridge_areas)))
    for name, values in (("ridge_gaps", gaps), ("ridge_areas", areas)):
        if values.shape != (forces.size, voltages.size):
            raise ValueError(f"{name} has shape {values.shape}; it must be (len(normal_forces), len(voltages)) = "
                             f"{(forces.size, voltages.size)}")
    works = stack.work_of_adhesion(gaps, voltages[None, :])
    seed = SlidingFrictionModel.paper_table1()
    return SlidingFrictionModel(mu0=seed.mu0, c2=seed.c2 if c2 is None else c2, stack=stack,
                                gap_model=TabulatedGap(forces, voltages, gaps),
                                contact=TabulatedArea(forces, np.maximum.accumulate(works, axis=1), areas))


def bottom_up_friction(result: StudyResult, c2: float | None = None,
                       realisation: int | None = None) -> SlidingFrictionModel:
    """:func:`friction_recipe` fed by a study: its d_eq,R and A_R = (A_R/A0) A0, realisation means over the
    converged solves (or those of ``realisation`` r alone); ``ValueError`` for a study of one load."""
    forces, voltages = result.normal_forces, result.voltages
    if result.frequencies:
        raise ValueError(f"screen.frequency = {list(result.frequencies)} Hz: the seed's friction law has no drive "
                         "frequency; pass result.at_frequency(k), the study at one frequency")
    if len(forces) < FRICTION_MIN_LOADS:
        raise ValueError(f"loads.normal_forces = {forces.tolist()}: the bottom-up friction law interpolates d_eq,R and "
                         f"A_R in F_N and needs at least {FRICTION_MIN_LOADS} loads")
    apparent = result.array("apparent_area")
    if realisation is None:
        if unconverged := unconverged_points(result):
            raise ValueError(f"no realisation converged at {unconverged}: the bottom-up friction law "
                             "interpolates the realisation means of d_eq,R and A_R, which are NaN there")
        gaps = result.summary("ridge_equivalent_gap")[0]
        fractions = result.summary("ridge_area_fractions")[0][:, :, 0]
    else:
        count = result.array("converged").shape[-1]
        if not (isinstance(realisation, (int, np.integer)) and 0 <= realisation < count):
            raise ValueError(f"realisation = {realisation!r}; valid: an integer in [0, {count - 1}]")
        gaps = result.array("ridge_equivalent_gap")[:, :, realisation]
        fractions = result.ridge_area[:, :, realisation]
    return friction_recipe(forces, voltages, gaps, fractions * apparent, result.scene.screen.stack(), c2)


def friction_realisations(result: StudyResult, c2: float | None = None) -> dict:
    """F_T [N] (``"tangential_force"``) and μ (``"friction_coefficient"``) of :func:`bottom_up_friction` of each
    realisation at every (F_N, U) of the study, shape (loads, voltages, realisations); NaN for a realisation
    with a solve that did not converge. Their spread is the realisation uncertainty of the recipe's F_T and μ
    (:func:`~.records.confidence_interval` gives the study's 95 % interval, as for d_eq and A_R)."""
    forces, voltages = result.normal_forces[:, None], result.voltages[None, :]
    converged = result.array("converged").astype(bool)
    samples = {"tangential_force": [], "friction_coefficient": []}
    for r in range(converged.shape[-1]):
        if converged[:, :, r].all():
            state = bottom_up_friction(result, c2, realisation=r).state(forces, voltages)
            values = {name: getattr(state, name) for name in samples}
        else:
            values = {name: np.full((forces.size, voltages.size), np.nan) for name in samples}
        for name in samples:
            samples[name].append(values[name])
    return {name: np.stack(values, axis=-1) for name, values in samples.items()}


def assumption_errors(result: StudyResult) -> dict:
    """Relative errors of the solved electrostatic force σ̄_el A0 (shape loads × voltages, realisation means;
    NaN at 0 V): ``constant_gap``: the field-equivalent gap of the lowest voltage (0 V in the default scene: the
    small-voltage limit) used at every voltage (the seed's voltage-independent gap); ``mean_gap``: Eq. 21 at the
    arithmetic mean gap; ``per_pixel``: Eq. 21 pixel by pixel on the solved gap (Eq. 21 at d_eq). NaN too where
    no realisation converged (:func:`unconverged_points`)."""
    stack = result.scene.screen.stack()
    voltages = result.voltages[None, :]
    sigma = result.summary("electrostatic_attraction")[0]
    d_field = result.summary("field_equivalent_gap")[0]
    mean_gap = result.summary("mean_gap")[0]

    def attraction(gap):                        # Eq. 21 at the finite means, NaN where they are
        finite = np.isfinite(gap)
        return np.where(finite, stack.attraction(np.where(finite, gap, 0.0), voltages), np.nan)

    with np.errstate(divide="ignore", invalid="ignore"):
        constant = attraction(np.maximum(d_field[:, :1], 0.0)) / sigma - 1
        naive = attraction(mean_gap) / sigma - 1
        per_pixel = result.summary("pixel_law_attraction")[0] / sigma - 1
    on = result.voltages > 0
    return {name: np.where(on[None, :], error, np.nan)
            for name, error in (("constant_gap", constant), ("mean_gap", naive), ("per_pixel", per_pixel))}
