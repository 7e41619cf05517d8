"""What a task of the study returns and how a point is assembled: :class:`PatchRecord` (one realisation at one
(F_N, U)), :class:`PointResult` (all realisations of a point) and the Student-t interval over realisations."""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np
from scipy.special import stdtrit

from .patch import gap_slope, ridge_area_fraction, ridge_equivalent_gap

#: Two-sided confidence level of every reported interval.
CONFIDENCE = 0.95



def confidence_interval(samples) -> tuple:
    """``(mean, half-width)`` of the two-sided :data:`CONFIDENCE` Student-t interval over the last axis; NaN
    samples are left out (half-width NaN where fewer than two remain, mean NaN where none)."""
    samples = np.asarray(samples, dtype=float)
    count = np.sum(np.isfinite(samples), axis=-1)
    with np.errstate(invalid="ignore", divide="ignore"):
        mean = np.nansum(samples, axis=-1) / count
        spread = np.sqrt(np.nansum((samples - mean[..., None]) ** 2, axis=-1) / (count - 1))
        half = np.where(count > 1, stdtrit(np.maximum(count - 1, 1), 0.5 + CONFIDENCE / 2) * spread
                        / np.sqrt(count), np.nan)
    return mean, half


@dataclass(frozen=True)
class PatchRecord:
    """One realisation's patch at one (F_N, U), averaged over the rings: ``equivalent_gap`` d_eq,
    ``ridge_equivalent_gap`` d_eq,R, ``mean_gap`` [m]; ``contact_fraction``; ``ridge_area_fractions`` A_R/A0
    per coarse-graining length; ``electrostatic_pressure`` σ̄_el [Pa]; ``gap_slope`` (rms |∇g|, weighted by
    (ε_a c + g)⁻²); ``converged`` (every ring); ``iterations``, ``unstable_steps`` (concave steps: the solves
    crossed instabilities, so the answer may depend on the path; ``docs/guide/interactions.md``) and ``solves`` (summed
    over the rings, a cold retry included); ``seconds`` of solving."""

    equivalent_gap: float
    ridge_equivalent_gap: float
    mean_gap: float
    contact_fraction: float
    ridge_area_fractions: tuple
    electrostatic_pressure: float
    gap_slope: float
    converged: bool
    iterations: int
    unstable_steps: int
    solves: int
    seconds: float


RECORD_FIELDS = {f.name for f in dataclasses.fields(PatchRecord)}


def patch_record(stack, voltage, results, lengths, spacing, solves, seconds) -> PatchRecord:
    """Average the solved rings ``results`` of one patch over the apparent area (gaps in float64)."""
    gaps = np.stack([np.asarray(res.gap, dtype=np.float64) for res in results])
    d_eq = stack.equivalent_gap(gaps)
    fractions = tuple(float(np.mean([ridge_area_fraction(np.asarray(res.contact), spacing[0], length)
                                     for res in results])) for length in lengths)
    offset = stack.eps_a * stack.dielectric_offset
    return PatchRecord(
        equivalent_gap=float(d_eq), ridge_equivalent_gap=ridge_equivalent_gap(stack, d_eq, fractions[0]),
        mean_gap=float(gaps.mean()),
        contact_fraction=float(np.mean([res.contact_fraction for res in results])), ridge_area_fractions=fractions,
        electrostatic_pressure=float(np.mean(stack.pressure(gaps, voltage))),
        gap_slope=float(np.mean([gap_slope(g, (offset + g) ** -2.0, spacing) for g in gaps])),
        converged=all(bool(res.converged) for res in results), iterations=int(sum(res.iterations for res in results)),
        unstable_steps=int(sum(res.unstable_steps for res in results)), solves=solves, seconds=seconds)


@dataclass(frozen=True)
class PointResult:
    """The study at one (F_N [N], U [V]); tuples run over the realisations (``ridge_area_fractions`` over the
    coarse-graining lengths first). SI units: areas m², gaps m, pressures Pa; ``seconds`` of solving, summed
    over the realisations."""

    normal_force: float
    voltage: float
    apparent_area: float
    nominal_pressures: tuple
    equivalent_gap: tuple
    ridge_equivalent_gap: tuple
    mean_gap: tuple
    contact_fraction: tuple
    ridge_area_fractions: tuple
    electrostatic_pressure: tuple
    gap_slope: tuple
    converged: tuple
    iterations: tuple
    unstable_steps: tuple
    seconds: float


_PER_REALISATION = ("equivalent_gap", "ridge_equivalent_gap", "mean_gap", "contact_fraction",
                    "electrostatic_pressure", "gap_slope", "converged", "iterations", "unstable_steps")


def point_result(force, voltage, area, pressures, records) -> PointResult:
    """The point from the :class:`PatchRecord` of each realisation (in realisation order)."""
    return PointResult(normal_force=force, voltage=voltage, apparent_area=float(area),
                       nominal_pressures=tuple(pressures),
                       ridge_area_fractions=tuple(zip(*(record.ridge_area_fractions for record in records))),
                       seconds=sum(record.seconds for record in records),
                       **{name: tuple(getattr(record, name) for record in records) for name in _PER_REALISATION})
