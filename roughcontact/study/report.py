"""Results of a fingerpad study on disk: netCDF, CSV, PNG and report.md, with the seed's friction law fed
bottom-up (:mod:`roughcontact.study.friction`).

:func:`write_results` writes ``results.nc`` (xarray + h5netcdf, the ``io`` dependencies; skipped
with a message when missing), the CSV tables, the PNG figures and ``report.md`` into a results directory; for
a drive-frequency sweep (``[screen] frequency``) the tables gain a frequency column, ``results.nc`` a frequency
dimension, and the figure and report show the sweep (:func:`sweep_report_text`).
"""
from __future__ import annotations

import importlib.util
import time
from pathlib import Path

import numpy as np

from .._version import __version__
from ..electrostatics import crossover_frequency
from ..fe.feed import fe_friction_columns
from ..io.provenance import save_figure, write_csv
from ..macro import LinearGap, PowerLawGap, SlidingFrictionModel
from .friction import (FRICTION_MIN_LOADS, HOLDS_WITHIN, assumption_errors, bottom_up_friction, friction_computed,
                       friction_realisations)
from .presets import applicability, describe
from .records import CONFIDENCE, confidence_interval
from .run import StudyResult

MICRO = 1e6          # m -> µm in tables and figures
MM2 = 1e6            # m² -> mm²
#: Modules that writing results.nc needs (the ``io`` dependencies).
NETCDF_MODULES = ("xarray", "h5netcdf", "h5py")


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


#: Fields bounded by 1 (fractions of A0): their intervals are taken on the log-odds scale.
FRACTIONS = ("ridge_area_fractions", "contact_fraction")


def _realisations(result: StudyResult, name: str) -> np.ndarray:
    """Field ``name`` per realisation, shape (loads, voltages, realisations) (A_R/A0 at the scene's ℓ for
    ``ridge_area_fractions``), NaN where the solve did not converge."""
    values = result.ridge_area if name == "ridge_area_fractions" else result.array(name)
    return np.where(result.array("converged").astype(bool), values, np.nan)


def _friction_rows(result: StudyResult) -> list:
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


# ---------------------------------------------------------------------------------------------------------
# Tables
# ---------------------------------------------------------------------------------------------------------
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


# ---------------------------------------------------------------------------------------------------------
# netCDF
# ---------------------------------------------------------------------------------------------------------
def dataset(result: StudyResult, friction: bool = True):
    """The study as an ``xarray.Dataset`` (SI units in every variable's ``units``; scene, preset, seed and
    version in the attributes); a frequency sweep with a ``frequency`` dimension [Hz] after ``voltage`` (and no
    friction variables); ``friction`` False leaves the friction variables out."""
    import xarray as xr
    if result.frequencies:
        frequency = xr.DataArray(np.array(result.frequencies), dims="frequency", name="frequency",
                                 attrs={"units": "Hz"})
        parts = [dataset(result.at_frequency(k), friction=False) for k in range(len(result.frequencies))]
        data = xr.concat(parts, dim=frequency)
        data["apparent_area"] = parts[0]["apparent_area"]                 # one per load
        return data.transpose("normal_force", "voltage", "frequency", ...)
    scene = result.scene
    coords = {"normal_force": ("normal_force", result.normal_forces, {"units": "N"}),
              "voltage": ("voltage", result.voltages, {"units": "V"}),
              "realisation": ("realisation", np.arange(result.array("equivalent_gap").shape[-1])),
              "coarse_graining": ("coarse_graining", np.array(result.coarse_graining), {"units": "m"})}
    dims = ("normal_force", "voltage", "realisation")
    units = {"equivalent_gap": "m", "field_equivalent_gap": "m", "ridge_equivalent_gap": "m", "mean_gap": "m",
             "contact_fraction": "1", "electrostatic_attraction": "Pa", "pixel_law_attraction": "Pa",
             "field_ratio": "1", "gap_slope": "1", "iterations": "1", "unstable_steps": "1"}
    descriptions = {name: text for name, _, _, _, text in FIELDS}
    variables = {name: (dims, result.array(name), {"units": unit, "long_name": descriptions.get(name, name)})
                 for name, unit in units.items()}
    variables["converged"] = (dims, result.array("converged").astype(np.int8), {"units": "1"})
    variables["ridge_area_fraction"] = (("normal_force", "voltage", "coarse_graining", "realisation"),
                                        result.array("ridge_area_fractions"),
                                        {"units": "1", "long_name": "A_R / A0 after closing at coarse_graining"})
    variables["apparent_area"] = (("normal_force",), result.array("apparent_area")[:, 0], {"units": "m2"})
    variables["solve_seconds"] = (("normal_force", "voltage"), result.array("seconds"), {"units": "s"})
    friction = _friction_rows(result) if friction and friction_computed(result) else []
    for key, unit in (("bottom_up_tangential_force_N", "N"), ("bottom_up_tangential_force_ci95_N", "N"),
                      ("seed_tangential_force_N", "N"), ("bottom_up_friction_coefficient", "1"),
                      ("bottom_up_friction_coefficient_ci95", "1"), ("seed_friction_coefficient", "1")):
        if friction:
            values = np.array([row[key] for row in friction]).reshape(len(result.normal_forces), -1)
            variables[key.removesuffix("_N")] = (("normal_force", "voltage"), values, {"units": unit})
    attrs = {"title": "roughcontact multiscale fingerpad study", "roughcontact_version": __version__,
             "preset": scene.study.preset, "field": scene.screen.field, "seed": scene.study.seed,
             "scene_toml": scene.to_toml(), "short_cutoff_in_use": result.short_cutoff, "confidence": CONFIDENCE}
    for key, value in scene.flat().items():
        attrs[f"scene.{key}"] = int(value) if isinstance(value, bool) else value
    return xr.Dataset(variables, coords=coords, attrs=attrs)


# ---------------------------------------------------------------------------------------------------------
# Figures
# ---------------------------------------------------------------------------------------------------------
def _bars(result: StudyResult, name: str, scale: float = 1.0) -> tuple:
    """``(mean, [below, above])`` of field ``name`` for ``errorbar``: the realisation mean and the distances to
    the bounds of :func:`positive_interval` (each ≥ 0), both × ``scale``."""
    samples = _realisations(result, name)
    mean = confidence_interval(samples)[0]
    low, high = positive_interval(samples, 1.0 if name in FRACTIONS else np.inf)
    below, above = (np.nan_to_num(np.maximum(d, 0.0)) for d in (mean - low, high - mean))
    return mean * scale, np.stack([below, above]) * scale


def bars_note(result: StudyResult) -> str:
    """What every error bar and band of the figures and interval of the report is."""
    count = result.array("converged").shape[-1]
    failed = not result.array("converged").all()
    if count < 2:
        return "one realisation: no interval"
    return (f"bars: {CONFIDENCE:.0%} confidence interval over N = {count} realisations"
            + (" (fewer where a solve failed)" if failed else "")
            + ", Student-t on the log scale (log-odds for fractions of A0: they stay inside 0-100 %)")


def _figures(result: StudyResult, out, provenance) -> list:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    forces, voltages = result.normal_forces, result.voltages
    d_mean, d_bars = _bars(result, "equivalent_gap", MICRO)
    a_mean, a_bars = _bars(result, "ridge_area_fractions", 100.0)
    c_mean, c_bars = _bars(result, "contact_fraction", 100.0)
    gap_mean = result.summary("mean_gap")[0]
    note = bars_note(result)
    written = []
    line = np.linspace(forces[0], forces[-1], 50)

    def finish(figure, name):
        figure.text(0.5, 0.005, note, ha="center", va="bottom", fontsize=7, style="italic")
        figure.tight_layout(rect=(0, 0.04, 1, 1))
        written.append(save_figure(figure, out / name, provenance))
        plt.close(figure)

    figure, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    for j, voltage in enumerate(voltages):
        left.errorbar(forces, d_mean[:, j], yerr=d_bars[:, :, j], marker="o", capsize=3,
                      label=f"Eq. 25, {voltage:g} V")
    left.plot(line, LinearGap.paper_table1()(line, 0.0) * MICRO, "k--", label="seed Eq. 46 (fit, any voltage)")
    guo = PowerLawGap.guo2019()
    span = np.linspace(max(forces[0], 0.5), min(forces[-1], 4.5), 50)     # its measured 0.5-4.5 N, our loads
    if span[0] < span[-1]:
        left.plot(span, guo(span, 0.0) * MICRO, "k:", label="Guo et al. 2019, measured at 150 V")
    left.set(xlabel="normal force F_N [N]", ylabel="equivalent air gap [µm]", title="d_eq vs load")
    left.legend(fontsize=7)
    right.plot(forces, gap_mean[:, 0] * MICRO, "s-", label=f"arithmetic mean gap, {voltages[0]:g} V")
    right.plot(forces, d_mean[:, 0], "o-", label=f"Eq. 25, {voltages[0]:g} V")
    right.set(xlabel="normal force F_N [N]", ylabel="gap [µm]", title="mean gap vs Eq. 25 (realisation means)")
    right.legend(fontsize=7)
    finish(figure, "equivalent_gap.png")

    figure, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    for i, force in enumerate(forces):
        left.errorbar(voltages, d_mean[i], yerr=d_bars[:, i], marker="o", capsize=3, label=f"{force:g} N")
        right.errorbar(voltages, a_mean[i], yerr=a_bars[:, i], marker="o", capsize=3, color=f"C{i}",
                       label=f"A_R/A0, {force:g} N")
        right.errorbar(voltages, c_mean[i], yerr=c_bars[:, i], marker="s", ls="--", capsize=3, color=f"C{i}",
                       label=f"real contact, {force:g} N")
    left.set(xlabel="voltage U [V]", ylabel="d_eq (Eq. 25) [µm]", title="voltage dependence of d_eq")
    right.set(xlabel="voltage U [V]", ylabel="fraction of A0 [%]",
              title="ridge (solid) and real (dashed) contact vs voltage")
    left.legend(fontsize=7)
    right.legend(fontsize=6)
    finish(figure, "voltage_dependence.png")

    figure, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    field_mean, field_bars = _bars(result, "field_equivalent_gap", MICRO)
    ratio_mean, ratio_bars = _bars(result, "field_ratio")
    for j, voltage in enumerate(voltages):
        colour = f"C{j}"
        left.errorbar(forces, d_mean[:, j], yerr=d_bars[:, :, j], marker="o", capsize=3, color=colour,
                      label=f"Eq. 25, {voltage:g} V")
        left.errorbar(forces, field_mean[:, j], yerr=field_bars[:, :, j], marker="s", capsize=3,
                      ls="--", color=colour, label=f"field-equivalent, {voltage:g} V")
    for i, force in enumerate(forces):
        right.errorbar(voltages, ratio_mean[i], yerr=ratio_bars[:, i], marker="o", capsize=3, label=f"{force:g} N")
    right.axhline(1.0, color="k", lw=0.8)
    left.set(xlabel="normal force F_N [N]", ylabel="gap [µm]", title="Eq. 25 (solid) vs field-equivalent (dashed)")
    right.set(xlabel="voltage U [V]", ylabel="F_el(field) / F_el(Eq. 21 per pixel)",
              title=f"{result.scene.screen.field} field against the per-pixel law")
    left.legend(fontsize=6)
    right.legend(fontsize=7)
    finish(figure, "field_ratio.png")

    if friction_computed(result):
        model, seed = bottom_up_friction(result), SlidingFrictionModel.paper_table1()
        ours = model.state(forces[:, None], voltages[None, :])
        samples = friction_realisations(result)
        figure, axes = plt.subplots(1, 3, figsize=(14, 4))
        for j, voltage in enumerate(voltages):
            theirs = seed.state(line, voltage)
            colour = f"C{j}"
            axes[0].plot(forces, ours.initial_area[:, j] * MM2, "o-", color=colour, label=f"bottom-up {voltage:g} V")
            axes[0].plot(line, theirs.initial_area * MM2, "--", color=colour)
            for axis, name in ((axes[1], "tangential_force"), (axes[2], "friction_coefficient")):
                value = getattr(ours, name)[:, j]
                low, high = positive_interval(samples[name][:, j])
                bars = np.nan_to_num(np.maximum(np.stack([value - low, high - value]), 0.0))
                axis.errorbar(forces, value, yerr=bars, marker="o", capsize=3, color=colour, label=f"{voltage:g} V")
                axis.plot(line, getattr(theirs, name), "--", color=colour)
        axes[0].set(xlabel="F_N [N]", ylabel="ridge area A_R0 [mm²]", title="A_R (solid) vs seed Eq. 9 (dashed)")
        axes[1].set(xlabel="F_N [N]", ylabel="F_T [N]", title="friction force (dashed: seed Table 1)")
        axes[2].set(xlabel="F_N [N]", ylabel="μ = F_T/F_N", title="friction coefficient (dashed: seed)")
        for axis in axes:
            axis.legend(fontsize=7)
        finish(figure, "friction.png")
    return written


# ---------------------------------------------------------------------------------------------------------
# report.md
# ---------------------------------------------------------------------------------------------------------
def _number(value, digits) -> str:
    return f"{np.round(value, digits) + 0.0:.{digits}f}"                  # + 0.0: no "-0.00" for a rounded zero


def _cell(samples, scale=1.0, digits=2, upper=np.inf) -> str:
    """The realisation mean of a positive quantity (bounded by ``upper``) and its :func:`positive_interval`,
    "mean [low, high]"."""
    mean = confidence_interval(samples)[0]
    low, high = positive_interval(samples, upper)
    text = _number(mean * scale, digits)
    return text if not np.isfinite(low) else f"{text} [{_number(low * scale, digits)}, {_number(high * scale, digits)}]"


def _table(result, samples, scale=1.0, digits=2, unit="", upper=np.inf) -> list:
    """Table over loads × voltages of the positive quantity (bounded by ``upper``) with realisations
    ``samples`` (… , realisations)."""
    header = "| F_N [N] | " + " | ".join(f"{v:g} V" for v in result.voltages) + " |"
    lines = [header, "|---" * (len(result.voltages) + 1) + "|"]
    for i, force in enumerate(result.normal_forces):
        lines.append(f"| {force:g} | " + " | ".join(_cell(samples[i, j], scale, digits, upper)
                                                   for j in range(len(result.voltages))) + " |")
    note = f"\n({unit}; realisation mean [{bars_note(result).removeprefix('bars: ')}])"
    return lines + ([note] if unit else [])


def _unstable_sentence(result: StudyResult) -> str:
    """How many patch results crossed an instability on the way (concave solver steps), and from which voltage."""
    crossed = result.array("unstable_steps") > 0                 # (forces, voltages, [frequencies,] realisations)
    if not crossed.any():
        return "No solve crossed an instability."
    per_voltage = crossed.reshape(*crossed.shape[:2], -1).any(axis=(0, 2))
    lowest = result.voltages[int(np.flatnonzero(per_voltage)[0])]
    return (f"{int(crossed.sum())} of {crossed.size} patch results came from solves that crossed an instability "
            f"(concave steps, from {lowest:g} V on): where the attraction snaps regions into contact the "
            "equilibrium may depend on the path to it (`docs/guide/interactions.md`, \"Several equilibria\").")


def _patch_sentence(result: StudyResult, realisations: int) -> str:
    """What was solved: the synthetic patch (periods, pixels, realisations, cut-off) or the measured one."""
    scene, preset = result.scene, result.scene.preset
    roughness = scene.roughness
    if roughness.topography:
        grid = result.plan.grid
        return (f"patch the measured topography `{Path(roughness.topography).name}` ({roughness.boundary} "
                f"boundary, {roughness.detrend} removed), {grid.shape[0]} × {grid.shape[1]} pixels over "
                f"{grid.lengths[0] * 1e3:g} × {grid.lengths[1] * 1e3:g} mm, one realisation (a measured surface: no "
                "interval over realisations)")
    return (f"patch {preset.periods} ridge period(s) = {preset.periods * scene.ridges.period * 1e3:g} mm on "
            f"{preset.grid}² pixels, {realisations} realisation(s) (seed {scene.study.seed}), micro-roughness "
            f"short cut-off in use {result.short_cutoff * MICRO:.3g} µm")


def _run_sentence(result: StudyResult, seconds: float | None) -> str:
    """The report's first paragraph: version, preset, patch, tolerance, convergence, instabilities, run time."""
    scene, converged = result.scene, result.array("converged")
    return (f"roughcontact {__version__}, preset `{scene.study.preset}`: "
            + _patch_sentence(result, converged.shape[-1])
            + f", solver tolerance {scene.preset.tolerance:g}. Scene: `scene.toml` in this directory. "
            f"{converged.size - int(converged.sum())} of {converged.size} patch results did not converge (also "
            "from the solver's own start) and are left out of the means. " + _unstable_sentence(result)
            + (f" Run time {seconds:.0f} s, tables and figures included ({result.computed} points computed with "
               f"{result.solves} solves, "
               f"{result.array('seconds').size - result.computed} read back)." if seconds is not None else ""))


def report_text(result: StudyResult, nc_written: bool, seconds: float | None = None) -> str:
    """The Markdown report: what was computed, tables with intervals, and where the equivalent-gap
    assumption holds and where it fails, with numbers."""
    scene, preset = result.scene, result.scene.preset
    forces, voltages = result.normal_forces, result.voltages
    friction_figure, friction_table = ((", `friction.png`", ", `friction.csv`") if friction_computed(result)
                                       else ("", ""))
    d_mean = result.summary("equivalent_gap")[0]
    f_mean = result.summary("field_equivalent_gap")[0]
    a_mean = result.summary("ridge_area_fractions")[0]
    slope = result.summary("gap_slope")[0]
    errors = assumption_errors(result)
    text = ["# Multiscale fingerpad study", "",
            _run_sentence(result, seconds), "",
            describe(preset, scene.study.preset) + applicability(scene) if not scene.roughness.topography else
            "The presets' measured errors (`docs/guide/presets.md`) are those of synthetic patches on the preset's "
            "grid and do not apply here: the measured patch is solved on the scan's own pixels, so its resolution "
            "is the instrument's.", "",
            f"Figures: `equivalent_gap.png`, `voltage_dependence.png`, `field_ratio.png`{friction_figure}. Tables: "
            f"`points.csv`, `realisations.csv`, `ridge_area_sensitivity.csv`{friction_table}"
            + (", all of it in `results.nc`." if nc_written else
               "; `results.nc` was not written (xarray/h5netcdf missing: `pip install 'roughcontact[io]'`)."), "",
            f"Definitions: the attraction is solved with the `{scene.screen.field}` field of the stack (`[screen] "
            "field`; `docs/guide/electrostatics.md`). d_eq by seed Eq. 25 of the solved gap over the apparent area A0 "
            "(contact points included): the seed's definition, the gap at which Eq. 21 gives the mean of Eq. 21 "
            "pixel by pixel. d_field, the field-equivalent gap: the uniform gap whose Eq. 21 attraction is the "
            "solve's mean attraction σ̄_el = F_el/A0 (at 0 V the same for the field of the hard-wall gap in the "
            "small-voltage limit). A_R the real contact closed with a disc of "
            f"{scene.ridge_area.coarse_graining * MICRO:g} µm diameter; d_eq,R the uniform gap whose Eq. 21 "
            "attraction over A_R is the solved F_el, σ_el(d_eq,R) A_R = σ̄_el A0: the seed's friction law (σ_el "
            "acting on A_R) is fed d_eq,R, so its electrostatic force is the solved one. "
            "Assumptions and their checks: `docs/findings/equivalent_gap.md` of the roughcontact repository.", "",
            "## Equivalent air gap d_eq [µm] (Eq. 25)", "",
            *_table(result, _realisations(result, "equivalent_gap"), MICRO, 2, "µm"), "",
            "## Field-equivalent gap d_field [µm]", "",
            *_table(result, _realisations(result, "field_equivalent_gap"), MICRO, 2, "µm"), "",
            *_per_pixel_section(result), "",
            "## Ridge contact fraction A_R/A0 [%]", "",
            *_table(result, _realisations(result, "ridge_area_fractions"), 100.0, 1, "%", 1.0), "",
            "## Real contact fraction [%]", "",
            *_table(result, _realisations(result, "contact_fraction"), 100.0, 2, "%", 1.0),
            "", "## Ridge-area gap d_eq,R [µm] (fed to the friction law)", "",
            *_table(result, _realisations(result, "ridge_equivalent_gap"), MICRO, 3, "µm"),
            *_clipped_ridge_gap(result), ""]

    text += ["## Where the equivalent-gap assumption holds and where it fails", ""]
    low = f"{voltages[0]:g} V"                       # the reference voltage of the comparisons (0 V by default)
    if len(voltages) > 1:
        constant = errors["constant_gap"]
        on = np.arange(len(voltages)) > 0
        worst = np.nanmax(np.abs(constant))
        held = [f"{v:g} V" for j, v in enumerate(voltages) if on[j] and np.all(np.abs(constant[:, j]) <= HOLDS_WITHIN)]
        change = d_mean[:, -1] / d_mean[:, 0] - 1
        within = f"{100 * HOLDS_WITHIN:.0f} %"
        text += [f"* **Voltage independence** (seed: d_eq depends on F_N only). From {low} to {voltages[-1]:g} V d_eq "
                 "changes by " + ", ".join(f"{100 * c:+.0f} % at {f:g} N" for c, f in zip(change, forces)) + ". "
                 f"Using the field-equivalent gap of {low} at voltage U misjudges the solved electrostatic force by "
                 f"up to {100 * worst:.0f} % (table below); "
                 + (f"it stays within {within} at every load for {', '.join(held)}." if held else
                    f"at every voltage above {low} it is off by more than {within} at some load."), "",
                 f"  Force error of the voltage-independent gap, σ_el(d_field({low}), U)/σ̄_el(U) − 1 [%]:",
                 "", *_error_table(forces, voltages[on], 100 * constant[:, on]), ""]
        naive = errors["mean_gap"]
        text += ["* **Arithmetic mean gap instead of Eq. 25**: the mean gap is "
                 + ", ".join(f"{m * MICRO:.1f} µm" for m in result.summary("mean_gap")[0][:, 0])
                 + f" at {low} against d_eq = " + ", ".join(f"{d * MICRO:.2f} µm" for d in d_mean[:, 0])
                 + f"; σ_el at the mean gap changes the electrostatic force by {_range(100 * naive, '+.0f')} %.", ""]
    else:
        text += [f"* One voltage ({low}) in the scene: its dependence on the voltage is not tested.", ""]
    seed_gap = LinearGap.paper_table1()(forces, 0.0)
    guo = PowerLawGap.guo2019()(forces, 0.0)
    d_low, d_high = positive_interval(_realisations(result, "equivalent_gap")[:, 0])
    inside = [f"{f:g} N" for f, low_bound, high_bound, fit in zip(forces, d_low, d_high, seed_gap)
              if low_bound <= fit <= high_bound]
    text += [f"* **Against the seed's fit (Eq. 46)**: at {low} d_eq = "
             + ", ".join(f"{d * MICRO:.2f} µm" for d in d_mean[:, 0]) + " against Eq. 46's "
             + ", ".join(f"{d * MICRO:.2f}" for d in seed_gap) + " µm and Guo et al.'s power law "
             + ", ".join(f"{d * MICRO:.2f}" for d in guo) + f" µm at F_N = {', '.join(f'{f:g}' for f in forces)} N "
             "(field-equivalent gap d_field: " + ", ".join(f"{d * MICRO:.2f}" for d in f_mean[:, 0]) + " µm); "
             f"Eq. 46 lies inside the confidence interval of d_eq at {', '.join(inside) if inside else 'no load'}. "
             f"d_eq falls with load at every voltage: {_yes(np.diff(d_mean, axis=0) < 0)}; A_R grows with load: "
             f"{_yes(np.diff(a_mean[:, :, 0], axis=0) > 0)}; A_R grows with voltage: "
             f"{_yes(np.diff(a_mean[:, :, 0], axis=1) > 0)} (realisation means).", "",
             f"* **Parallel-plate field per pixel** (Eq. 21 pixel by pixel, the assumption behind Eq. 25): on the "
             f"solved gaps it misjudges the solved attraction by {_range(100 * errors['per_pixel'], '+.0f')} % "
             f"({scene.screen.field} field; table above); the (c + g)⁻²-weighted rms gap slope is "
             f"{_range(slope, '.2f')}.", ""]
    lengths = result.coarse_graining
    if len(lengths) > 1:
        ratio = a_mean[:, :, 1:] / a_mean[:, :, :1]
        text += ["* **A_R depends on its coarse-graining length**: closing at "
                 + ", ".join(f"{l * MICRO:g} µm gives {_range(ratio[:, :, k], '.2f', '–')} ×"
                             for k, l in enumerate(lengths[1:]))
                 + f" the A_R at {lengths[0] * MICRO:g} µm (`ridge_area_sensitivity.csv`). d_eq does not depend "
                 "on it; the friction law's F_el = σ_el(d_eq,R) A_R = σ̄_el A0 does not either, only the "
                 "tangential area reduction (Eq. 44, η = c₂/A_R0) does.", ""]
    text += _friction_section(result)
    return "\n".join(text) + "\n"


def _friction_section(result: StudyResult) -> list:
    """The report's friction section: the recipe's μ, F_T and A_R0 beside the seed's (or why it is missing)."""
    if not friction_computed(result):
        return ["## Friction", "", f"Not computed: the bottom-up friction law interpolates d_eq,R and A_R in F_N "
                f"and needs at least {FRICTION_MIN_LOADS} loads; the scene has one (`loads.normal_forces`), so "
                "`friction.csv` and `friction.png` are not written.", ""]
    rows = _friction_rows(result)
    saturated = sum(row["bottom_up_area_saturated"] for row in rows)
    bounds = {name: positive_interval(values) for name, values in friction_realisations(result).items()}

    def spread(name, i, j, digits):
        low, high = (_number(bound[i, j], digits) for bound in bounds[name])
        return "" if low == high or "nan" in low else f" [{low}, {high}]"        # none: no spread

    return ["## Friction: bottom-up (the ridge-area recipe) vs the seed's fitted model (Table 1)", "",
            "The seed's friction law fed d_eq,R on A_R (`roughcontact.study.friction_recipe`, "
            "docs/guide/friction_model.md); the bottom-up μ and F_T are the recipe on the realisation means, "
            f"in brackets the recipe evaluated per realisation [{bars_note(result).removeprefix('bars: ')}].",
            "",
            "μ = F_T/F_N: bottom-up / bottom-up with the FE fingertip's area reduction instead of c₂ "
            "(`roughcontact.fe.feed`, docs/guide/fe_fingertip.md) / bottom-up without the tangential area "
            "reduction (c₂ = 0) / seed. "
            "Where the bottom-up A_R0 is below √c₂ μ0 F_N the seed's reduction law (Eq. 43, c₂ fitted to its "
            "own, larger ridge area) empties the ridge area and F_T = μ0 F_N (the saturation rule of "
            f"`docs/guide/friction_model.md`): {saturated} of {len(rows)} "
            "points.", "",
            *_friction_table(result, rows, lambda i, j, c: f"{c['bottom_up_friction_coefficient']:.3f}"
                             f"{spread('friction_coefficient', i, j, 3)} / "
                             f"{c['bottom_up_fe_friction_coefficient']:.3f} / "
                             f"{c['bottom_up_c2_0_friction_coefficient']:.3f} / "
                             f"{c['seed_friction_coefficient']:.3f}"),
            "", "Friction force F_T [N] (bottom-up / seed):", "",
            *_friction_table(result, rows, lambda i, j, c: f"{c['bottom_up_tangential_force_N']:.3f}"
                             f"{spread('tangential_force', i, j, 3)} / {c['seed_tangential_force_N']:.3f}"),
            "", "Ridge area A_R0 [mm²] (bottom-up / seed Eq. 9):", "",
            *_friction_table(result, rows, lambda i, j, c: f"{c['bottom_up_ridge_area_mm2']:.1f} / "
                             f"{c['seed_ridge_area_mm2']:.1f}"), ""]


def _friction_table(result: StudyResult, rows: list, cell) -> list:
    """A loads × voltages table of the friction ``rows`` (:func:`_friction_rows`, in their order), each entry
    ``cell(i, j, row)``."""
    count = len(result.voltages)
    return (["| F_N [N] | " + " | ".join(f"{v:g} V" for v in result.voltages) + " |", "|---" * (count + 1) + "|"]
            + [f"| {force:g} | " + " | ".join(cell(i, j, rows[i * count + j]) for j in range(count)) + " |"
               for i, force in enumerate(result.normal_forces)])


def _per_pixel_section(result: StudyResult) -> list:
    """The table "how wrong is the per-pixel assumption": F_el of the solve's field and of Eq. 21 pixel by pixel
    on the same solved gap [N], and their ratio with its interval over the realisations."""
    area = result.array("apparent_area")[:, :, None]      # one per point
    field = area * _realisations(result, "electrostatic_attraction")
    pixel = area * _realisations(result, "pixel_law_attraction")
    ratio = _realisations(result, "field_ratio")
    voltages = result.voltages
    lines = ["## How wrong is the per-pixel field assumption", "",
             f"F_el [N] of the solve's `{result.scene.screen.field}` field / F_el [N] of Eq. 21 pixel by pixel on "
             "the same solved gap (what Eq. 25 assumes) / their ratio, each the realisation mean "
             f"[{bars_note(result).removeprefix('bars: ')}] (0 V: no force, –; the ratio is the "
             "small-voltage limit on the hard-wall gap):", "",
             "| F_N [N] | " + " | ".join(f"{v:g} V" for v in voltages) + " |", "|---" * (len(voltages) + 1) + "|"]
    for i, force in enumerate(result.normal_forces):
        cells = []
        for j, voltage in enumerate(voltages):
            forces = (f"{_cell(field[i, j], 1.0, 3)} / {_cell(pixel[i, j], 1.0, 3)}" if voltage > 0 else "– / –")
            cells.append(f"{forces} / {_cell(ratio[i, j], 1.0, 2)}")
        lines.append(f"| {force:g} | " + " | ".join(cells) + " |")
    return lines


def _clipped_ridge_gap(result: StudyResult) -> list:
    """A note where A_R cannot carry the solved F_el at any gap (d_eq,R = 0 in some realisation)."""
    clipped = int(np.sum(result.array("ridge_equivalent_gap") == 0))
    if clipped == 0:
        return []
    return ["", f"{clipped} of {result.array('ridge_equivalent_gap').size} patch results have A_R too small to carry "
            "the solved F_el even in full contact (σ_el(0) A_R < σ̄_el A0): d_eq,R = 0 there, and the friction "
            "law's electrostatic force falls short of the solved one."]


def _range(values, spec, joint=" to ") -> str:
    """"low to high" of the finite ``values`` formatted with ``spec``; one number where both read the same."""
    finite = np.round(np.asarray(values)[np.isfinite(values)], 12) + 0.0      # + 0.0: no "-0" for a zero error
    if finite.size == 0:
        return "n/a (no voltage above 0 V)"
    low, high = format(np.min(finite), spec), format(np.max(finite), spec)
    return low if low == high else f"{low}{joint}{high}"


def _yes(condition) -> str:
    return "n/a" if np.size(condition) == 0 else "yes" if np.all(condition) else "no"


def _error_table(forces, voltages, values) -> list:
    lines = ["  | F_N [N] | " + " | ".join(f"{v:g} V" for v in voltages) + " |",
             "  " + "|---" * (len(voltages) + 1) + "|"]
    for i, force in enumerate(forces):
        lines.append(f"  | {force:g} | " + " | ".join(f"{values[i, j]:+.0f}" for j in range(len(voltages))) + " |")
    return lines


# ---------------------------------------------------------------------------------------------------------
# A drive-frequency sweep
# ---------------------------------------------------------------------------------------------------------
def sweep_crossover(result: StudyResult) -> tuple:
    """``(f_c [Hz], h_rest [m])`` per load and voltage of a frequency sweep: the series circuit's crossover
    (``crossover_frequency``) with h_rest = d_field/ε_a + d_i/ε_i, d_field the field-equivalent gap at the sweep's
    highest frequency (realisation mean), the air and insulator's share of the nearly dielectric stack."""
    stack = result.scene.screen.stack()
    field_equivalent_gap = result.summary("field_equivalent_gap")[0][:, :, -1]
    rest = np.maximum(field_equivalent_gap, 0.0) / stack.eps_a + stack.d_i / stack.eps_i
    return np.vectorize(lambda thickness: crossover_frequency(stack, thickness))(rest), rest


def _sweep_samples(result: StudyResult) -> dict:
    """Per-realisation F_el [N], F_el over that of the same realisation at the highest frequency (the paired
    ratio: the realisations' spread cancels), d_eq [µm] and A_R/A0 [%] of a sweep, shape (loads, voltages,
    frequencies, realisations), NaN where a solve did not converge."""
    area = result.array("apparent_area")[..., None]
    force = area * _realisations(result, "electrostatic_attraction")
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = force / force[:, :, -1:, :]
    return {"F_el [N]": force, f"F_el / F_el({result.frequencies[-1]:g} Hz)": ratio,
            "d_eq (Eq. 25) [µm]": MICRO * _realisations(result, "equivalent_gap"),
            "A_R/A0 [%]": 100.0 * _realisations(result, "ridge_area_fractions")}


def _sweep_figure(result: StudyResult, out, provenance) -> list:
    """``frequency_sweep.png``: F_el, its paired ratio to the highest frequency's, d_eq and A_R/A0 against
    frequency (log axis) per load, a row per voltage
    above 0 V, DC as a dotted line, the circuit's crossover (:func:`sweep_crossover`) as a dashed line."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    voltages = [j for j, voltage in enumerate(result.voltages) if voltage > 0]
    frequencies = np.array(result.frequencies)
    ac = frequencies > 0
    if not voltages or not ac.any():
        return []
    crossover = sweep_crossover(result)[0]
    samples = _sweep_samples(result)
    figure, axes = plt.subplots(len(voltages), 4, figsize=(18, 3.6 * len(voltages)), squeeze=False)
    for row, j in zip(axes, voltages):
        for (label, values), axis in zip(samples.items(), row):
            upper = 100.0 if label.startswith("A_R") else np.inf
            for i, force in enumerate(result.normal_forces):
                mean = confidence_interval(values[i, j])[0]
                low, high = positive_interval(values[i, j], upper)
                bars = np.nan_to_num(np.maximum(np.stack([mean - low, high - mean]), 0.0))
                colour = f"C{i}"
                axis.errorbar(frequencies[ac], mean[ac], yerr=bars[:, ac], marker="o", capsize=3,
                              color=colour, label=f"{force:g} N")
                if not ac.all():
                    axis.axhline(mean[0], color=colour, ls=":", lw=1, label=f"{force:g} N, DC")
                axis.axvline(crossover[i, j], color=colour, ls="--", lw=0.8)
            axis.set(xscale="log", xlabel="drive frequency f [Hz]", ylabel=label,
                     title=f"{label.split(' [')[0]} at {result.voltages[j]:g} V RMS")
            axis.legend(fontsize=6)
    figure.text(0.5, 0.005, "dashed: crossover f_c of the series circuit, h_rest = field-equivalent gap at the "
                "highest frequency + d_i/ε_i; dotted: DC; " + bars_note(result), ha="center", va="bottom",
                fontsize=7, style="italic")
    figure.tight_layout(rect=(0, 0.03, 1, 1))
    written = [save_figure(figure, out / "frequency_sweep.png", provenance)]
    plt.close(figure)
    return written


def sweep_report_text(result: StudyResult, nc_written: bool, seconds: float | None = None) -> str:
    """The Markdown report of a drive-frequency sweep: what was solved, and F_el, d_eq, d_field and A_R/A0
    against frequency per load and voltage with the circuit's crossover."""
    scene, preset = result.scene, result.scene.preset
    crossover, rest = sweep_crossover(result)
    samples = _sweep_samples(result)
    field_equivalent_gap = _realisations(result, "field_equivalent_gap")
    contact = _realisations(result, "contact_fraction")
    text = ["# Multiscale fingerpad study: drive-frequency sweep", "",
            _run_sentence(result, seconds), "",
            describe(preset, scene.study.preset) + applicability(scene), "",
            "The drive (`[screen] frequency`, `docs/guide/ac_drive.md`): each voltage is the RMS value of a "
            "sinusoid at each frequency (0 Hz: DC), the stratum corneum conducts with σ_sc = "
            f"{scene.screen.sigma_sc:g} S/m, and every patch is the skin's quasi-static equilibrium under the "
            "time-averaged attraction of the layered field (the 2ω oscillation and the skin's viscoelasticity are "
            "not modelled). F_el is that time average; d_eq is seed Eq. 25 of the solved gap, d_field the uniform "
            "gap whose dielectric Eq. 21 attraction is the solved one, A_R the real contact closed with a disc of "
            f"{scene.ridge_area.coarse_graining * MICRO:g} µm diameter. The crossover f_c is the series circuit's "
            "(stratum corneum R‖C, air and insulator a capacitor of air-equivalent thickness h_rest): "
            "f_c = σ_sc/(2π ε0 (ε_sc + d_sc/h_rest)), with h_rest = d_field/ε_a + d_i/ε_i at the sweep's highest "
            "frequency.", "",
            "Figure: `frequency_sweep.png`. Tables: `points.csv`, `realisations.csv`, `ridge_area_sensitivity.csv`, "
            "each with a `frequency_Hz` column"
            + (", all of it in `results.nc` (dimension `frequency`)." if nc_written else
               "; `results.nc` was not written (xarray/h5netcdf missing: `pip install 'roughcontact[io]'`)."), "",
            "Not produced for a frequency sweep: the figures and sections against load and voltage and the "
            "friction step (the seed's friction law has no drive frequency); every per-point number is in the "
            "tables above, and `StudyResult.at_frequency(k)` gives the loads × voltages study at one frequency.",
            ""]
    labels = ["DC" if f == 0 else f"{f:g}" for f in result.frequencies]
    for j, voltage in enumerate(result.voltages):
        if voltage == 0:
            continue
        for i, force in enumerate(result.normal_forces):
            text += [f"## F_N = {force:g} N, U = {voltage:g} V RMS: crossover f_c = {crossover[i, j]:.0f} Hz "
                     f"(h_rest = {rest[i, j] * MICRO:.3f} µm)", "",
                     f"| f [Hz] | F_el [N] | F_el / F_el({labels[-1]} Hz), paired | d_eq [µm] | d_field [µm] "
                     "| A_R/A0 [%] | real contact [%] |", "|---" * 7 + "|"]
            for k, label in enumerate(labels):
                fel = samples["F_el [N]"][i, j, k]
                ratio = samples[f"F_el / F_el({result.frequencies[-1]:g} Hz)"][i, j, k]
                text.append(f"| {label} | {_cell(fel, 1.0, 4)} | {_cell(ratio, 1.0, 4)} | "
                            f"{_cell(samples['d_eq (Eq. 25) [µm]'][i, j, k], 1.0, 3)} | "
                            f"{_cell(field_equivalent_gap[i, j, k], MICRO, 3)} | "
                            f"{_cell(samples['A_R/A0 [%]'][i, j, k] / 100.0, 100.0, 2, 1.0)} | "
                            f"{_cell(contact[i, j, k], 100.0, 3, 1.0)} |")
            text += ["", f"(realisation mean [{bars_note(result).removeprefix('bars: ')}])", ""]
    if all(voltage == 0 for voltage in result.voltages):
        text += ["Every voltage is 0 V: the hard wall, the same at every frequency; no sweep to show.", ""]
    return "\n".join(text) + "\n"


def write_results(result: StudyResult, out, provenance, seconds: float | None = None) -> dict:
    """Write ``results.nc`` (when xarray and h5netcdf are installed), the CSV tables, the figures and
    ``report.md`` into the directory ``out``; ``seconds`` the run time so far (the study's). Returns
    ``{"netcdf": written?, "files": [paths], "seconds": the run time the report states}``, the writing
    included, so that a command can print the report's number."""
    start = time.perf_counter()
    files = [write_csv(out / "points.csv", _rows(result, _point_rows), provenance),
             write_csv(out / "realisations.csv", _rows(result, _realisation_rows), provenance),
             write_csv(out / "ridge_area_sensitivity.csv", _rows(result, _sensitivity_rows), provenance)]
    if result.frequencies:
        files += _sweep_figure(result, out, provenance)
    else:
        if friction_computed(result):
            files.append(write_csv(out / "friction.csv", _friction_rows(result), provenance))
        files += _figures(result, out, provenance)
    netcdf = all(importlib.util.find_spec(name) is not None for name in NETCDF_MODULES)
    if netcdf:
        data = dataset(result)
        data.attrs["provenance"] = provenance.line
        data.to_netcdf(out / "results.nc", engine="h5netcdf")
        files.append(out / "results.nc")
    report = out / "report.md"
    if seconds is not None:
        seconds += time.perf_counter() - start
    report.write_text((sweep_report_text if result.frequencies else report_text)(result, netcdf, seconds))
    return {"netcdf": netcdf, "files": files + [report], "seconds": seconds}
