"""The numbers of a fingerpad study as tables: the CSV files of a results directory (``points.csv``,
``realisations.csv``, ``ridge_area_sensitivity.csv``, ``friction.csv``; a ``frequency_Hz`` column for a
drive-frequency sweep) and what the figures and the report draw on with them — the per-realisation samples
of a field, the friction rows of the recipe beside the seed's, a sweep's samples and crossover, the note on
the intervals."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ..electrostatics import crossover_frequency
from ..fe.feed import fe_friction_columns
from ..io.provenance import write_csv
from ..macro import SlidingFrictionModel
from .friction import bottom_up_friction, friction_computed, friction_realisations
from .records import CONFIDENCE, confidence_interval
from .run import StudyResult

MICRO = 1e6          # m -> µm in tables and figures
MM2 = 1e6            # m² -> mm²


def realisation_samples(result: StudyResult, name: str) -> np.ndarray:
    """Field ``name`` per realisation, shape (loads, voltages, realisations) (A_R/A0 at the scene's ℓ for
    ``ridge_area_fractions``), NaN where the solve did not converge."""
    values = result.ridge_area if name == "ridge_area_fractions" else result.array(name)
    return np.where(result.array("converged").astype(bool), values, np.nan)


#: The real contact fraction from which a patch counts as in full contact: its gap statistics rest on the last
#: 1 % of its pixels, and its numbers on the stack rather than on the topography.
FULL_CONTACT = 0.99
#: F_el/F_N from which the attraction dominates the load: the patch is pressed by the field, so its numbers (and
#: the friction law's μ = μ0 (1 + F_el/F_N) alike) follow from the stack rather than from the topography.
ATTRACTION_DOMINATES = 10.0


#: What each of :func:`point_flags` says (the long names in results.nc).
FLAG_DESCRIPTIONS = {
    "full_contact": f"a realisation in full contact (real contact fraction >= {FULL_CONTACT:g}): the numbers "
                    "say nothing about the topography",
    "attraction_dominates": f"F_el >= {ATTRACTION_DOMINATES:g} F_N: the field presses the patch, the numbers say "
                            "nothing about the topography",
    "electrostatic_to_normal_force": "F_el / F_N (F_el = mean sigma_el x apparent area)",
    "field_gap_clipped": "mean attraction at or above that of uniform contact: field_equivalent_gap is the bound 0"}


def point_flags(result: StudyResult) -> dict:
    """Per point (shape loads × voltages [× frequencies]) what makes its numbers say nothing about the topography:
    ``full_contact`` (a converged realisation at a real contact fraction ≥ :data:`FULL_CONTACT`),
    ``attraction_dominates`` (F_el = σ̄_el A0, the realisation mean, ≥ :data:`ATTRACTION_DOMINATES` F_N), with
    ``electrostatic_to_normal_force`` F_el/F_N; and ``field_gap_clipped`` (a realisation whose mean attraction
    reaches that of uniform contact, so its field-equivalent gap is the bound 0: ``records.patch_record``)."""
    converged = result.array("converged").astype(bool)
    contact = np.where(converged, result.array("contact_fraction"), np.nan)
    field_gap = np.where(converged, result.array("field_equivalent_gap"), np.nan)
    force = result.summary("electrostatic_attraction")[0] * result.array("apparent_area")
    ratio = force / result.normal_forces.reshape(-1, *[1] * (force.ndim - 1))
    with np.errstate(invalid="ignore"):
        return {"full_contact": np.any(contact >= FULL_CONTACT, axis=-1),
                "attraction_dominates": ratio >= ATTRACTION_DOMINATES, "electrostatic_to_normal_force": ratio,
                "field_gap_clipped": np.any(field_gap == 0, axis=-1)}


def friction_rows(result: StudyResult) -> list:
    """The rows of ``friction.csv``, one per (F_N, U): the ridge-area recipe's gap, A_R0, F_T and μ (with
    their 95 % half-widths over the realisations) beside the seed's fitted model, μ without the tangential
    area reduction (c₂ = 0) and with the FE fingertip's reduction (``roughcontact.fe.feed``)."""
    model, seed = bottom_up_friction(result), SlidingFrictionModel.paper_table1()
    rigid = bottom_up_friction(result, c2=0.0)
    spread = {name: confidence_interval(values)[1] for name, values in friction_realisations(result).items()}
    rows = []
    for i, force in enumerate(result.normal_forces):
        for j, voltage in enumerate(result.voltages):
            ours, theirs = model.state(force, voltage), seed.state(force, voltage)
            unreduced = rigid.state(force, voltage)
            rows.append({"normal_force_N": force, "voltage_V": voltage,
                         "bottom_up_gap_um": float(ours.gap) * MICRO, "seed_gap_um": float(theirs.gap) * MICRO,
                         "bottom_up_ridge_area_mm2": float(ours.initial_area) * MM2,
                         "seed_ridge_area_mm2": float(theirs.initial_area) * MM2,
                         "bottom_up_tangential_force_N": float(ours.tangential_force),
                         "bottom_up_tangential_force_ci95_N": float(spread["tangential_force"][i, j]),
                         "seed_tangential_force_N": float(theirs.tangential_force),
                         "bottom_up_friction_coefficient": float(ours.friction_coefficient),
                         "bottom_up_friction_coefficient_ci95": float(spread["friction_coefficient"][i, j]),
                         "seed_friction_coefficient": float(theirs.friction_coefficient),
                         "bottom_up_c2_0_friction_coefficient": float(unreduced.friction_coefficient),
                         "bottom_up_area_saturated": bool(ours.area_saturated)})
            # hook (roughcontact.fe, numpy only): the ridge-area reduction of the FE fingertip instead of c2
            rows[-1].update(fe_friction_columns(model, force, voltage))
    return rows


#: Per-point fields: (StudyResult field, CSV/netCDF name, scale, unit, description).
FIELDS = (
    ("equivalent_gap", "equivalent_gap", MICRO, "um", "Eq. 25 equivalent air gap of the solved gap over the "
     "apparent area"),
    ("field_equivalent_gap", "field_equivalent_gap", MICRO, "um",
     "uniform gap whose Eq. 21 attraction is the solve's mean attraction (0 V: small-voltage limit)"),
    ("ridge_equivalent_gap", "ridge_equivalent_gap", MICRO, "um",
     "gap with sigma_el(d) A_R = F_el of the solve (the friction law's gap)"),
    ("mean_gap", "mean_gap", MICRO, "um", "arithmetic mean air gap over the apparent area"),
    ("contact_fraction", "real_contact_fraction", 1.0, "1", "real (pixel) contact area / apparent area"),
    ("electrostatic_attraction", "electrostatic_attraction", 1e-3, "kPa",
     "mean sigma_el of the solve's field over the apparent area"),
    ("pixel_law_attraction", "pixel_law_attraction", 1e-3, "kPa",
     "mean sigma_el of Eq. 21 pixel by pixel on the same solved gap"),
    ("field_ratio", "field_ratio", 1.0, "1",
     "F_el of the solve's field / F_el of Eq. 21 per pixel on the same gap (0 V: small-voltage limit)"),
    ("gap_slope", "gap_slope", 1.0, "1", "rms gap slope weighted by (c + g)^-2"),
)


def _point_rows(result: StudyResult) -> list:
    rows = []
    ridge_mean, ridge_half = result.summary("ridge_area_fractions")
    means = {name: result.summary(name) for name, *_ in FIELDS}
    flags = point_flags(result)                 # the points whose numbers say nothing about the topography
    for i, force in enumerate(result.normal_forces):
        for j, voltage in enumerate(result.voltages):
            point = result.points[i][j]
            row = {"normal_force_N": force, "voltage_V": voltage,
                   "apparent_area_mm2": point.apparent_area * MM2,
                   "nominal_pressure_kPa": force / point.apparent_area * 1e-3}
            for name, column, scale, unit, _ in FIELDS:
                row[f"{column}_{unit}"] = means[name][0][i, j] * scale
                row[f"{column}_ci95_{unit}"] = means[name][1][i, j] * scale
            row["ridge_area_fraction"] = ridge_mean[i, j, 0]
            row["ridge_area_fraction_ci95"] = ridge_half[i, j, 0]
            for name, column in (("electrostatic_attraction", "electrostatic_force"),
                                 ("pixel_law_attraction", "pixel_law_force")):
                row[f"{column}_N"] = means[name][0][i, j] * point.apparent_area
                row[f"{column}_ci95_N"] = means[name][1][i, j] * point.apparent_area
            row["converged"] = all(point.converged)
            row["solve_seconds"] = point.seconds
            row.update({name: values[i, j].item() for name, values in flags.items()})
            rows.append(row)
    return rows


def _rows(result: StudyResult, rows_of) -> list:
    """The CSV rows ``rows_of(result)`` of a loads × voltages study; of a frequency sweep those of each frequency
    with a ``frequency_Hz`` column after ``voltage_V``, in the order load, voltage, frequency (as the netCDF's
    dimensions)."""
    if not result.frequencies:
        return rows_of(result)
    rows = [{"normal_force_N": row["normal_force_N"], "voltage_V": row["voltage_V"], "frequency_Hz": frequency,
             **row} for k, frequency in enumerate(result.frequencies) for row in rows_of(result.at_frequency(k))]
    return sorted(rows, key=lambda row: (row["normal_force_N"], row["voltage_V"]))     # stable: frequencies in order


def _sensitivity_rows(result: StudyResult) -> list:
    mean, half = result.summary("ridge_area_fractions")
    return [{"normal_force_N": force, "voltage_V": voltage, "coarse_graining_um": length * MICRO,
             "ridge_area_fraction": mean[i, j, k], "ridge_area_fraction_ci95": half[i, j, k]}
            for i, force in enumerate(result.normal_forces) for j, voltage in enumerate(result.voltages)
            for k, length in enumerate(result.coarse_graining)]


def _realisation_rows(result: StudyResult) -> list:
    rows = []
    for i, force in enumerate(result.normal_forces):
        for j, voltage in enumerate(result.voltages):
            point = result.points[i][j]
            for r in range(len(point.equivalent_gap)):
                rows.append({"normal_force_N": force, "voltage_V": voltage, "realisation": r,
                             **{f"{column}_{unit}": getattr(point, name)[r] * scale
                                for name, column, scale, unit, _ in FIELDS},
                             "ridge_area_fraction": point.ridge_area_fractions[0][r],
                             "converged": point.converged[r], "iterations": point.iterations[r],
                             "unstable_steps": point.unstable_steps[r]})
    return rows


def bars_note(result: StudyResult) -> str:
    """What every error bar and band of the figures and interval of the report is."""
    count = result.array("converged").shape[-1]
    failed = not result.array("converged").all()
    if count < 2:
        return "one realisation: no interval"
    return (f"bars: {CONFIDENCE:.0%} confidence interval over N = {count} realisations"
            + (" (fewer where a solve failed)" if failed else "")
            + ", Student-t on the log scale (log-odds for fractions of A0: they stay inside 0-100 %)")


def sweep_crossover(result: StudyResult) -> tuple:
    """``(f_c [Hz], h_rest [m])`` per load and voltage of a frequency sweep: the series circuit's crossover
    (``crossover_frequency``) with h_rest = d_field/ε_a + d_i/ε_i, d_field the field-equivalent gap at the sweep's
    highest frequency (realisation mean), the air and insulator's share of the nearly dielectric stack."""
    stack = result.scene.screen.stack()
    field_equivalent_gap = result.summary("field_equivalent_gap")[0][:, :, -1]
    rest = np.maximum(field_equivalent_gap, 0.0) / stack.eps_a + stack.d_i / stack.eps_i
    return np.vectorize(lambda thickness: crossover_frequency(stack, thickness))(rest), rest


def sweep_samples(result: StudyResult) -> dict:
    """Per-realisation F_el [N], F_el over that of the same realisation at the highest frequency (the paired
    ratio: the realisations' spread cancels), d_eq [µm] and A_R/A0 [%] of a sweep, shape (loads, voltages,
    frequencies, realisations), NaN where a solve did not converge."""
    area = result.array("apparent_area")[..., None]
    force = area * realisation_samples(result, "electrostatic_attraction")
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = force / force[:, :, -1:, :]
    return {"F_el [N]": force, f"F_el / F_el({result.frequencies[-1]:g} Hz)": ratio,
            "d_eq (Eq. 25) [µm]": MICRO * realisation_samples(result, "equivalent_gap"),
            "A_R/A0 [%]": 100.0 * realisation_samples(result, "ridge_area_fractions")}


def write_tables(result: StudyResult, out, provenance) -> list:
    """Write the CSV tables of ``result`` into the directory ``out`` (``friction.csv`` where the friction law is
    computed, not for a frequency sweep); returns their paths."""
    files = [write_csv(out / "points.csv", _rows(result, _point_rows), provenance),
             write_csv(out / "realisations.csv", _rows(result, _realisation_rows), provenance),
             write_csv(out / "ridge_area_sensitivity.csv", _rows(result, _sensitivity_rows), provenance)]
    if not result.frequencies and friction_computed(result):
        files.append(write_csv(out / "friction.csv", friction_rows(result), provenance))
    return files


#: The outputs of a parameter study in its tables: (output, column, scale).
VARIANT_COLUMNS = (("equivalent_gap", "equivalent_gap_um", MICRO), ("field_equivalent_gap", "field_equivalent_gap_um",
                                                                     MICRO),
                   ("electrostatic_force", "electrostatic_force_N", 1.0),
                   ("ridge_area_fraction", "ridge_area_fraction", 1.0),
                   ("friction_coefficient", "bottom_up_friction_coefficient", 1.0))


def input_value(value):
    """An input's value in a table: a number, a topography's file name, or NaN for an absent drive frequency."""
    if value is None:
        return float("nan")
    return Path(value).name if isinstance(value, str) else value


def variant_rows(result) -> list:
    """The rows of ``variants.csv``: one per variant, load and voltage, with the variant's inputs and the
    realisation means of d_eq, d_field, F_el, A_R/A0 and the bottom-up μ (a :class:`VariantStudyResult`)."""
    names = result.study.variation.names
    rows = []
    for variant in result.variants:
        for i, force in enumerate(result.normal_forces):
            for j, voltage in enumerate(result.voltages):
                row = {"variant": variant.index, "label": variant.label,
                       **{name: input_value(value) for name, value in zip(names, variant.values)},
                       "normal_force_N": force, "voltage_V": voltage}
                row.update({column: result.outputs[name][variant.index, i, j] * scale
                            for name, column, scale in VARIANT_COLUMNS})
                rows.append(row)
    return rows


def sensitivity_rows(result) -> list:
    """The rows of ``sensitivity.csv``: one per output, load, voltage and input, with the design's measures
    (:data:`~.sensitivity.MEASURES`)."""
    sensitivity = result.sensitivity
    return [{"output": output, "normal_force_N": force, "voltage_V": voltage, "input": name,
             **{measure: values[o, n, i, j] for measure, values in sensitivity.measures.items()}}
            for o, output in enumerate(sensitivity.outputs) for i, force in enumerate(sensitivity.normal_forces)
            for j, voltage in enumerate(sensitivity.voltages) for n, name in enumerate(sensitivity.inputs)]


def write_variant_tables(result, out, provenance) -> list:
    """Write ``variants.csv`` and ``sensitivity.csv`` of a parameter study into ``out``; returns their paths."""
    return [write_csv(out / "variants.csv", variant_rows(result), provenance),
            write_csv(out / "sensitivity.csv", sensitivity_rows(result), provenance)]
