"""What a task of the study returns and how a point is assembled: :class:`PatchRecord` (one realisation at one
(F_N, U)), :class:`PointResult` (all realisations of a point) and the Student-t interval over realisations."""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np
from scipy.special import stdtrit

from ..electrostatics import solve_ac_field, solve_field
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


def positive_interval(samples, upper: float = np.inf) -> tuple:
    """``(low, high)`` of the :data:`CONFIDENCE` interval of a positive quantity over its realisations (last
    axis): the Student-t interval of ln x mapped back, exp(mean ln x ± t s/√N), which stays above zero; for a
    quantity bounded by ``upper`` too (a fraction: 1), that of the log-odds ln(x/(upper − x)), which stays
    inside (0, upper). Where a sample is on a bound, the Student-t interval of x clipped to [0, upper]. NaN
    where fewer than two samples are finite."""
    samples = np.asarray(samples, dtype=float)
    inside = (samples > 0) & (samples < upper)
    with np.errstate(divide="ignore", invalid="ignore"):
        odds = np.where(inside, samples / (upper - samples) if np.isfinite(upper) else samples, np.nan)
        log_mean, log_half = confidence_interval(np.log(odds))
    mean, half = confidence_interval(samples)
    bound = np.any(~inside & np.isfinite(samples), axis=-1)

    def back(log_odds):
        return np.exp(log_odds) if not np.isfinite(upper) else upper / (1 + np.exp(-log_odds))

    return (np.where(bound, np.maximum(mean - half, 0.0), back(log_mean - log_half)),
            np.where(bound, np.minimum(mean + half, upper), back(log_mean + log_half)))


def unit_attraction(stack, field: str, result, voltage: float, frequency: float | None = None) -> float:
    """⟨σ_el⟩/U² [Pa/V²] over the window of a solved patch ``result`` in the ``field`` model: from the solve's
    own attraction at ``voltage`` > 0 (F_el/(A0 U²), time-averaged under a drive of ``frequency`` [Hz]), at 0 V
    from the field of the hard-wall gap at 1 V (σ_el ∝ U², so this is the small-voltage limit; under the drive
    at that frequency)."""
    grid = result.grid
    if voltage > 0:
        return result.electrostatic_force / grid.area / voltage ** 2
    gap = np.asarray(result.gap, dtype=np.float64)
    if frequency is not None:
        return solve_ac_field(stack, gap, grid.lengths, 1.0, frequency=frequency, model=field,
                              periodic=grid.periodic).mean_attraction
    return solve_field(stack, gap, grid.lengths, 1.0, model=field, periodic=grid.periodic).mean_attraction


def field_ratio(stack, field_equivalent_gap: float, equivalent_gap: float) -> float:
    """F_el of the field over F_el of Eq. 21 per pixel on the same gap field: σ_el(d_field)/σ_el(d_eq) =
    (h(d_eq)/h(d_field))², h(d) = c + d/ε_a (seed Eq. 21 at the two equivalent gaps; independent of U)."""
    def thickness(gap):
        return stack.dielectric_offset + gap / stack.eps_a
    return float((thickness(equivalent_gap) / thickness(field_equivalent_gap)) ** 2)


@dataclass(frozen=True)
class PatchRecord:
    """One realisation's patch at one (F_N, U), averaged over the rings: ``equivalent_gap`` d_eq (seed Eq. 25
    of the solved gap), ``field_equivalent_gap`` d_field (the uniform gap whose Eq. 21 attraction is the solve's
    mean attraction; at 0 V that of the hard-wall gap's field in the small-voltage limit; 0 where that attraction
    reaches the one of uniform contact, which no gap ≥ 0 exceeds), ``ridge_equivalent_gap``
    d_eq,R (the uniform gap whose Eq. 21 attraction over A_R is the solve's F_el), ``mean_gap`` [m];
    ``contact_fraction``; ``ridge_area_fractions`` A_R/A0 per coarse-graining length; ``electrostatic_attraction``
    σ̄_el [Pa] of the solve's field, ``pixel_law_attraction`` [Pa] of Eq. 21 per pixel on the same solved gap and
    ``field_ratio`` their ratio (the small-voltage limit at 0 V); ``gap_slope`` (rms |∇g|, weighted by
    (ε_a c + g)⁻²); ``converged`` (every ring); ``iterations``, ``unstable_steps`` (concave steps: the solves
    crossed instabilities, so the answer may depend on the path; ``docs/guide/interactions.md``) and ``solves`` (summed
    over the rings, a cold retry included); ``seconds`` of solving."""

    equivalent_gap: float
    field_equivalent_gap: float
    ridge_equivalent_gap: float
    mean_gap: float
    contact_fraction: float
    ridge_area_fractions: tuple
    electrostatic_attraction: float
    pixel_law_attraction: float
    field_ratio: float
    gap_slope: float
    converged: bool
    iterations: int
    unstable_steps: int
    solves: int
    seconds: float


RECORD_FIELDS = {f.name for f in dataclasses.fields(PatchRecord)}


def patch_record(stack, field, voltage, results, lengths, spacing, solves, seconds,
                 frequency: float | None = None) -> PatchRecord:
    """Average the solved rings ``results`` of one patch (solved with the ``field`` model at ``voltage``, under a
    drive of ``frequency`` [Hz] or dielectric) over the apparent area (gaps in float64)."""
    gaps = np.stack([np.asarray(res.gap, dtype=np.float64) for res in results])
    d_eq = stack.equivalent_gap(gaps)
    periodic = results[0].grid.periodic
    fractions = tuple(float(np.mean([ridge_area_fraction(np.asarray(res.contact), spacing, length, periodic)
                                     for res in results])) for length in lengths)
    offset = stack.eps_a * stack.dielectric_offset
    attraction = float(np.mean([unit_attraction(stack, field, res, voltage, frequency)   # rings: equal area
                                for res in results]))
    # no attraction left (a leak across the interface at DC): no finite uniform gap attracts that little
    d_field = stack.gap_for_attraction(attraction, 1.0) if attraction > 0 else math.inf
    ratio = field_ratio(stack, d_field, d_eq)
    # above the attraction of uniform contact, σ_el(0) of Eq. 21 (the layered field's mean can exceed it near full
    # contact), Eq. 21 inverted gives a gap below zero, which no surface has: d_field = 0 there, the bound it
    # reaches; the report names those results (tables.point_flags)
    d_field = max(d_field, 0.0)
    return PatchRecord(
        equivalent_gap=float(d_eq), field_equivalent_gap=d_field,
        ridge_equivalent_gap=ridge_equivalent_gap(stack, d_field, fractions[0]) if d_field < math.inf
        else math.inf,
        mean_gap=float(gaps.mean()),
        contact_fraction=float(np.mean([res.contact_fraction for res in results])), ridge_area_fractions=fractions,
        electrostatic_attraction=attraction * voltage ** 2,
        pixel_law_attraction=float(np.mean(stack.attraction(gaps, voltage))),
        field_ratio=ratio,
        gap_slope=float(np.mean([gap_slope(g, (offset + g) ** -2.0, spacing, periodic) for g in gaps])),
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
    field_equivalent_gap: tuple
    ridge_equivalent_gap: tuple
    mean_gap: tuple
    contact_fraction: tuple
    ridge_area_fractions: tuple
    electrostatic_attraction: tuple
    pixel_law_attraction: tuple
    field_ratio: tuple
    gap_slope: tuple
    converged: tuple
    iterations: tuple
    unstable_steps: tuple
    seconds: float


#: The fields of a :class:`PointResult` with one value per realisation (a :class:`PatchRecord`'s each).
PER_REALISATION = ("equivalent_gap", "field_equivalent_gap", "ridge_equivalent_gap", "mean_gap",
                    "contact_fraction", "electrostatic_attraction", "pixel_law_attraction", "field_ratio",
                    "gap_slope", "converged", "iterations", "unstable_steps")


def point_result(force, voltage, area, pressures, records) -> PointResult:
    """The point from the :class:`PatchRecord` of each realisation (in realisation order)."""
    return PointResult(normal_force=force, voltage=voltage, apparent_area=float(area),
                       nominal_pressures=tuple(pressures),
                       ridge_area_fractions=tuple(zip(*(record.ridge_area_fractions for record in records))),
                       seconds=sum(record.seconds for record in records),
                       **{name: tuple(getattr(record, name) for record in records) for name in PER_REALISATION})
