"""The seed's friction law fed bottom-up from a study, and the errors of the equivalent-gap assumption.

:func:`bottom_up_friction` puts the study's d_eq,R(F_N, U) (:class:`~roughcontact.macro.TabulatedGap`) and
A_R(F_N, w) (:class:`~roughcontact.macro.TabulatedArea`) into :class:`~roughcontact.macro.SlidingFrictionModel`
with the seed's μ0 and c₂; :func:`assumption_errors` measures what a voltage-independent gap or the arithmetic
mean gap would make of the electrostatic force.
"""
from __future__ import annotations

import numpy as np

from ..macro import SlidingFrictionModel, TabulatedArea, TabulatedGap
from .run import StudyResult

#: Relative error of the electrostatic force within which the report counts the equivalent-gap assumption as held.
HOLDS_WITHIN = 0.10


def bottom_up_friction(result: StudyResult, c2: float | None = None) -> SlidingFrictionModel:
    """The seed's friction law (μ0 and, unless ``c2`` [m⁴/N²] is given, c₂ of Table 1) with the study's mean
    d_eq,R and A_R = (A_R/A0) A0."""
    forces, voltages = result.normal_forces, result.voltages
    stack = result.scene.screen.stack()
    gaps = result.summary("ridge_equivalent_gap")[0]
    areas = result.summary("ridge_area_fractions")[0][:, :, 0] * result.array("apparent_area")
    works = stack.work_of_adhesion(gaps, voltages[None, :])
    seed = SlidingFrictionModel.paper_table1()
    return SlidingFrictionModel(mu0=seed.mu0, c2=seed.c2 if c2 is None else c2, stack=stack,
                                gap_model=TabulatedGap(forces, voltages, gaps),
                                contact=TabulatedArea(forces, np.maximum.accumulate(works, axis=1), areas))


def assumption_errors(result: StudyResult) -> dict:
    """Relative errors of the electrostatic force σ̄_el A0 (shape loads × voltages, realisation means; NaN at
    0 V): ``constant_gap``: the d_eq of the lowest voltage (0 V in the default scene) used at every voltage (the
    seed's voltage-independent gap); ``mean_gap``: the arithmetic mean gap used instead of Eq. 25."""
    stack = result.scene.screen.stack()
    voltages = result.voltages[None, :]
    sigma = result.summary("electrostatic_pressure")[0]
    d_eq = result.summary("equivalent_gap")[0]
    mean_gap = result.summary("mean_gap")[0]
    with np.errstate(divide="ignore", invalid="ignore"):
        constant = stack.pressure(d_eq[:, :1], voltages) / sigma - 1
        naive = stack.pressure(mean_gap, voltages) / sigma - 1
    on = result.voltages > 0
    return {"constant_gap": np.where(on[None, :], constant, np.nan), "mean_gap": np.where(on[None, :], naive, np.nan)}
