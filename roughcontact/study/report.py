"""Results of a fingerpad study on disk: netCDF, CSV, PNG and report.md, with the seed's friction law fed
bottom-up (:mod:`roughcontact.study.friction`).

:func:`write_results` writes ``results.nc`` (:mod:`.dataset`: xarray + h5netcdf), the CSV tables
(:mod:`.tables`), the PNG figures (:mod:`.figures`) and ``report.md`` (this module: :func:`report_text`) into a
results directory; for a drive-frequency sweep (``[screen] frequency``) the tables gain a frequency column,
``results.nc`` a frequency dimension, and the figure and report show the sweep (:func:`sweep_report_text`).
"""
from __future__ import annotations

import time
from pathlib import Path

import numpy as np

from surfaces.heightfield import FILL_WARNING_FRACTION

from .._version import __version__
from ..macro import LinearGap, PowerLawGap
from .dataset import write_dataset, write_variant_dataset
from .figures import write_figures, write_sensitivity_figure
from .friction import (FRICTION_MIN_LOADS, HOLDS_WITHIN, assumption_errors, friction_computed, friction_realisations,
                       unconverged_points)
from .patch import patch_scale_message
from .presets import applicability, describe
from .records import confidence_interval, positive_interval
from .run import StudyResult
from .scene import LEAK_KEYS
from .sensitivity import OUTPUTS
from .tables import (ATTRACTION_DOMINATES, FULL_CONTACT, MICRO, bars_note, friction_rows, point_flags,
                     realisation_samples, sweep_crossover, sweep_samples, write_tables, write_variant_tables)
from .variant_run import VariantStudyResult

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
    mark = np.where(_marked(result), " †", "")
    for i, force in enumerate(result.normal_forces):
        lines.append(f"| {force:g} | " + " | ".join(_cell(samples[i, j], scale, digits, upper) + mark[i, j]
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


def _caveats(result: StudyResult) -> list:
    """The report's paragraphs on what limits its numbers (each followed by an empty line): the measured scan's
    missing points and window, a patch narrower than the length scales it is measured with, the points that say
    nothing about the topography, the field-equivalent gaps at their bound 0."""
    scale = patch_scale_message(result.scene, result.plan.grid)
    paragraphs = [_scan_sentence(result), f"**Patch too small**: {scale}." if scale else "", _flag_sentence(result),
                  _clipped_field_gap(result)]
    return [line for paragraph in paragraphs if paragraph for line in (paragraph, "")]


def _marked(result: StudyResult) -> np.ndarray:
    """Per (load, voltage), any frequency: the point is in full contact or its attraction dominates the load
    (:func:`point_flags`), marked † in the report's tables."""
    flags = point_flags(result)
    marked = flags["full_contact"] | flags["attraction_dominates"]
    return marked.reshape(*marked.shape[:2], -1).any(axis=-1)


def _flag_sentence(result: StudyResult) -> str:
    """The points whose numbers say nothing about the topography, and why ("" if none)."""
    flags, marked = point_flags(result), _marked(result)
    if not marked.any():
        return ""

    def points(mask):
        mask = mask.reshape(*mask.shape[:2], -1).any(axis=-1)
        return ", ".join(f"{force:g} N at {voltage:g} V" for i, force in enumerate(result.normal_forces)
                         for j, voltage in enumerate(result.voltages) if mask[i, j])

    reasons = []
    if flags["full_contact"].any():
        reasons.append(f"in full contact (a realisation's real contact ≥ {100 * FULL_CONTACT:g} %) at "
                       f"{points(flags['full_contact'])}")
    if flags["attraction_dominates"].any():
        reasons.append(f"pressed by an attraction F_el ≥ {ATTRACTION_DOMINATES:g} F_N (up to "
                       f"{np.nanmax(flags['electrostatic_to_normal_force']):.0f} F_N) at "
                       f"{points(flags['attraction_dominates'])}")
    return (f"**Points that say nothing about the topography** (marked † in the tables): the patch is "
            f"{'; and '.join(reasons)}. There the field presses the skin onto the screen, so d_eq, A_R and the "
            "friction law's μ follow from the stack, not from the roughness: read them as bounds, not as predictions "
            "(`full_contact`, `attraction_dominates`, `electrostatic_to_normal_force` in `points.csv` and "
            "`results.nc`).")


def _clipped_field_gap(result: StudyResult) -> str:
    """A note where d_field is the bound 0 (the mean attraction reached that of uniform contact), "" if nowhere."""
    clipped = point_flags(result)["field_gap_clipped"]
    if not clipped.any():
        return ""
    return (f"**d_field = 0** at {int(clipped.sum())} of {clipped.size} points: a realisation's mean attraction "
            "there reaches the attraction of uniform contact, σ_el(0) of Eq. 21 (the layered field's mean can exceed "
            "it near full contact), and Eq. 21 inverted would give a gap below zero, which no surface has; d_field "
            "is reported at its bound, 0 (`field_gap_clipped` in `points.csv` and `results.nc`).")


def _scan_sentence(result: StudyResult) -> str:
    """How the measured scan's missing points were handled and how it was windowed ("" for a synthetic patch or
    a complete scan used whole), from the patch's record (``roughcontact.study.scene.measured_topography``)."""
    if result.plan.topography is None:
        return ""
    record, text = result.plan.topography.metadata, []
    if "missing_points" in record and record.get("missing") == "harmonic":
        fraction = record["filled_fraction"]
        text.append(f"**Missing data**: {record['missing_points']} heights of the scan ({100 * fraction:.1f} %) were "
                    "undefined and are filled by harmonic interpolation (`missing = \"harmonic\"`): invented "
                    "heights that the solves take for measured ones"
                    + (f", above the {100 * FILL_WARNING_FRACTION:.0f} % at which the reader warns; `missing = "
                       "\"crop\"` keeps the largest fully measured rectangle instead." if fraction >
                       FILL_WARNING_FRACTION else "."))
    elif "missing_points" in record:
        (i0, i1), (j0, j1) = record["measured_window"]
        text.append(f"**Missing data**: {record['missing_points']} heights of the scan were undefined; the patch is "
                    f"its largest fully measured rectangle (`missing = \"crop\"`), pixels {i0}:{i1} × {j0}:{j1}: "
                    f"{100 * (1 - record['kept_fraction']):.1f} % of the scan cropped away.")
    if "crop" in record:
        text.append(f"The scan is cropped to `crop = {record['crop']}` ({record.get('crop_by', 'pixels')}).")
    if "resample" in record:
        text.append(f"It is resampled to {record['resample'][0]} × {record['resample'][1]} pixels.")
    return " ".join(text)


def _run_sentence(result: StudyResult, seconds: float | None) -> str:
    """The report's first paragraph: version, preset, patch, tolerance, convergence, instabilities, run time."""
    scene, converged, unconverged = result.scene, result.array("converged"), unconverged_points(result)
    return (f"roughcontact {__version__}, preset `{scene.study.preset}`: "
            + _patch_sentence(result, converged.shape[-1])
            + f", solver tolerance {scene.preset.tolerance:g}. Scene: `scene.toml` in this directory. "
            f"{converged.size - int(converged.sum())} of {converged.size} patch results did not converge (also "
            "from the solver's own start) and are left out of the means"
            + (f"; none converged at {unconverged}, whose means are NaN (`nan` in the tables, left out of the "
               "comparisons below)" if unconverged else "") + ". "
            + _unstable_sentence(result)
            + (f" Run time {seconds:.0f} s, tables and figures included ({result.computed} points computed with "
               f"{result.solves} solves, "
               f"{result.array('seconds').size - result.computed} read back)." if seconds is not None else ""))


def report_text(result: StudyResult, seconds: float | None = None) -> str:
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
    none_above = "no converged point above 0 V" if voltages[-1] > 0 else "no voltage above 0 V"   # errors NaN at 0 V
    text = ["# Multiscale fingerpad study", "",
            _run_sentence(result, seconds), "", *_caveats(result),
            describe(preset, scene.study.preset) + applicability(scene) if not scene.roughness.topography else
            "The presets' measured errors (`docs/guide/presets.md`) are those of synthetic patches on the preset's "
            "grid and do not apply here: the measured patch is solved on the scan's own pixels, so its resolution "
            "is the instrument's.", "",
            f"Figures: `equivalent_gap.png`, `voltage_dependence.png`, `field_ratio.png`{friction_figure}. Tables: "
            f"`points.csv`, `realisations.csv`, `ridge_area_sensitivity.csv`{friction_table}"
            ", all of it in `results.nc`.", "",
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
            *_table(result, realisation_samples(result, "equivalent_gap"), MICRO, 2, "µm"), "",
            "## Field-equivalent gap d_field [µm]", "",
            *_table(result, realisation_samples(result, "field_equivalent_gap"), MICRO, 2, "µm"), "",
            *_per_pixel_section(result), "",
            "## Ridge contact fraction A_R/A0 [%]", "",
            *_table(result, realisation_samples(result, "ridge_area_fractions"), 100.0, 1, "%", 1.0), "",
            "## Real contact fraction [%]", "",
            *_table(result, realisation_samples(result, "contact_fraction"), 100.0, 2, "%", 1.0),
            "", "## Ridge-area gap d_eq,R [µm] (fed to the friction law)", "",
            *_table(result, realisation_samples(result, "ridge_equivalent_gap"), MICRO, 3, "µm"),
            *_clipped_ridge_gap(result), ""]

    text += ["## Where the equivalent-gap assumption holds and where it fails", ""]
    low = f"{voltages[0]:g} V"                       # the reference voltage of the comparisons (0 V by default)
    if len(voltages) > 1:
        constant = errors["constant_gap"]
        on = np.arange(len(voltages)) > 0
        finite = np.abs(constant[np.isfinite(constant)])          # none where no point converged
        worst = f"{100 * finite.max():.0f} %" if finite.size else "n/a (no converged point above 0 V)"
        held = [f"{v:g} V" for j, v in enumerate(voltages) if on[j] and _yes(HOLDS_WITHIN - np.abs(constant[:, j]))
                == "yes"]
        with np.errstate(divide="ignore", invalid="ignore"):       # d_eq = 0 at both (a flat patch): no change
            change = np.where(d_mean[:, -1] == d_mean[:, 0], 0.0, d_mean[:, -1] / d_mean[:, 0] - 1)
        within = f"{100 * HOLDS_WITHIN:.0f} %"
        text += [f"* **Voltage independence** (seed: d_eq depends on F_N only). From {low} to {voltages[-1]:g} V d_eq "
                 "changes by " + ", ".join((f"{100 * c:+.0f} %" if np.isfinite(c) else "n/a") + f" at {f:g} N"
                                           for c, f in zip(change, forces)) + ". "
                 f"Using the field-equivalent gap of {low} at voltage U misjudges the solved electrostatic force by "
                 f"up to {worst} (table below)"
                 + (f"; it stays within {within} at every load for {', '.join(held)}." if held else
                    f"; at every voltage above {low} it is off by more than {within} at some load." if finite.size
                    else "."), "",
                 f"  Force error of the voltage-independent gap, σ_el(d_field({low}), U)/σ̄_el(U) − 1 [%]:",
                 "", *_error_table(forces, voltages[on], 100 * constant[:, on]), ""]
        naive = errors["mean_gap"]
        text += ["* **Arithmetic mean gap instead of Eq. 25**: the mean gap is "
                 + ", ".join(f"{m * MICRO:.1f} µm" for m in result.summary("mean_gap")[0][:, 0])
                 + f" at {low} against d_eq = " + ", ".join(f"{d * MICRO:.2f} µm" for d in d_mean[:, 0])
                 + "; σ_el at the mean gap changes the electrostatic force by "
                 + f"{_range(100 * naive, '+.0f', missing=none_above)} %.", ""]
    else:
        text += [f"* One voltage ({low}) in the scene: its dependence on the voltage is not tested.", ""]
    seed_gap = LinearGap.paper_table1()(forces, 0.0)
    guo = PowerLawGap.guo2019()(forces, 0.0)
    d_low, d_high = positive_interval(realisation_samples(result, "equivalent_gap")[:, 0])
    inside = [f"{f:g} N" for f, low_bound, high_bound, fit in zip(forces, d_low, d_high, seed_gap)
              if low_bound <= fit <= high_bound]
    text += [f"* **Against the seed's fit (Eq. 46)**: at {low} d_eq = "
             + ", ".join(f"{d * MICRO:.2f} µm" for d in d_mean[:, 0]) + " against Eq. 46's "
             + ", ".join(f"{d * MICRO:.2f}" for d in seed_gap) + " µm and Guo et al.'s power law "
             + ", ".join(f"{d * MICRO:.2f}" for d in guo) + f" µm at F_N = {', '.join(f'{f:g}' for f in forces)} N "
             "(field-equivalent gap d_field: " + ", ".join(f"{d * MICRO:.2f}" for d in f_mean[:, 0]) + " µm); "
             f"Eq. 46 lies inside the confidence interval of d_eq at {', '.join(inside) if inside else 'no load'}. "
             f"d_eq falls with load at every voltage: {_yes(-np.diff(d_mean, axis=0))}; A_R grows with load: "
             f"{_yes(np.diff(a_mean[:, :, 0], axis=0))}; A_R grows with voltage: "
             f"{_yes(np.diff(a_mean[:, :, 0], axis=1))} (realisation means).", "",
             f"* **Parallel-plate field per pixel** (Eq. 21 pixel by pixel, the assumption behind Eq. 25): on the "
             "solved gaps it misjudges the solved attraction by "
             f"{_range(100 * errors['per_pixel'], '+.0f', missing=none_above)} % "
             f"({scene.screen.field} field; table above); the (c + g)⁻²-weighted rms gap slope is "
             f"{_range(slope, '.2f', missing='no converged point')}.", ""]
    lengths = result.coarse_graining
    if len(lengths) > 1:
        ratio = a_mean[:, :, 1:] / a_mean[:, :, :1]
        text += ["* **A_R depends on its coarse-graining length**: closing at "
                 + ", ".join(f"{l * MICRO:g} µm gives {_range(ratio[:, :, k], '.2f', '–', 'no converged point')} ×"
                             for k, l in enumerate(lengths[1:]))
                 + f" the A_R at {lengths[0] * MICRO:g} µm (`ridge_area_sensitivity.csv`). d_eq does not depend "
                 "on it; the friction law's F_el = σ_el(d_eq,R) A_R = σ̄_el A0 does not either, only the "
                 "tangential area reduction (Eq. 44, η = c₂/A_R0) does.", ""]
    text += _friction_section(result)
    return "\n".join(text) + "\n"


def _friction_section(result: StudyResult) -> list:
    """The report's friction section: the recipe's μ, F_T and A_R0 beside the seed's (or why it is missing)."""
    if not friction_computed(result):
        reason = (f"the bottom-up friction law interpolates d_eq,R and A_R in F_N and needs at least "
                  f"{FRICTION_MIN_LOADS} loads; the scene has one (`loads.normal_forces`)"
                  if len(result.normal_forces) < FRICTION_MIN_LOADS else
                  f"no realisation converged at {unconverged_points(result)} (`converged` in `points.csv` and "
                  "`realisations.csv`), where the realisation means of d_eq,R and A_R that the bottom-up friction "
                  "law interpolates are NaN")
        return ["## Friction", "", f"Not computed: {reason}, so `friction.csv` and `friction.png` are not written.",
                ""]
    rows = friction_rows(result)
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
    """A loads × voltages table of the friction ``rows`` (:func:`friction_rows`, in their order), each entry
    ``cell(i, j, row)``."""
    count, mark = len(result.voltages), np.where(_marked(result), " †", "")
    return (["| F_N [N] | " + " | ".join(f"{v:g} V" for v in result.voltages) + " |", "|---" * (count + 1) + "|"]
            + [f"| {force:g} | " + " | ".join(cell(i, j, rows[i * count + j]) + mark[i, j] for j in range(count))
               + " |" for i, force in enumerate(result.normal_forces)])


def _per_pixel_section(result: StudyResult) -> list:
    """The table "how wrong is the per-pixel assumption": F_el of the solve's field and of Eq. 21 pixel by pixel
    on the same solved gap [N], and their ratio with its interval over the realisations."""
    area = result.array("apparent_area")[:, :, None]      # one per point
    field = area * realisation_samples(result, "electrostatic_attraction")
    pixel = area * realisation_samples(result, "pixel_law_attraction")
    ratio = realisation_samples(result, "field_ratio")
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


def _range(values, spec, joint=" to ", missing="no voltage above 0 V") -> str:
    """"low to high" of the finite ``values`` formatted with ``spec``; one number where both read the same; "n/a"
    and why (``missing``) where none is finite."""
    finite = np.round(np.asarray(values)[np.isfinite(values)], 12) + 0.0      # + 0.0: no "-0" for a zero error
    if finite.size == 0:
        return f"n/a ({missing})"
    low, high = format(np.min(finite), spec), format(np.max(finite), spec)
    return low if low == high else f"{low}{joint}{high}"


def _yes(rises) -> str:
    """"yes" if every finite one of ``rises`` is positive, "no" if one is not, "n/a" if none is finite."""
    finite = rises[np.isfinite(rises)]
    return "n/a" if finite.size == 0 else "yes" if np.all(finite > 0) else "no"


def _error_table(forces, voltages, values) -> list:
    lines = ["  | F_N [N] | " + " | ".join(f"{v:g} V" for v in voltages) + " |",
             "  " + "|---" * (len(voltages) + 1) + "|"]
    for i, force in enumerate(forces):
        lines.append(f"  | {force:g} | " + " | ".join(f"{values[i, j]:+.0f}" for j in range(len(voltages))) + " |")
    return lines


def _leak_phrase(screen) -> str:
    """", the interface leaks (…)" naming the leak keys a scene sets (``docs/guide/ac_drive.md``), else ""."""
    if not screen.leaks:
        return ""
    keys = ", ".join(f"{key} = {getattr(screen, key)!r}" for key, absent in LEAK_KEYS.items()
                     if getattr(screen, key) != absent)
    return f", the skin–screen interface leaks ({keys}; \"A leak across the interface\")"


def sweep_report_text(result: StudyResult, seconds: float | None = None) -> str:
    """The Markdown report of a drive-frequency sweep: what was solved, and F_el, d_eq, d_field and A_R/A0
    against frequency per load and voltage with the circuit's crossover."""
    scene, preset = result.scene, result.scene.preset
    crossover, rest = sweep_crossover(result)
    samples = sweep_samples(result)
    field_equivalent_gap = realisation_samples(result, "field_equivalent_gap")
    contact = realisation_samples(result, "contact_fraction")
    text = ["# Multiscale fingerpad study: drive-frequency sweep", "",
            _run_sentence(result, seconds), "", *_caveats(result),
            describe(preset, scene.study.preset) + applicability(scene), "",
            "The drive (`[screen] frequency`, `docs/guide/ac_drive.md`): each voltage is the RMS value of a "
            "sinusoid at each frequency (0 Hz: DC), the stratum corneum conducts with σ_sc = "
            f"{scene.screen.sigma_sc:g} S/m{_leak_phrase(scene.screen)}, and every patch is the skin's quasi-static "
            "equilibrium under the "
            "time-averaged attraction of the layered field (the 2ω oscillation and the skin's viscoelasticity are "
            "not modelled). F_el is that time average; d_eq is seed Eq. 25 of the solved gap, d_field the uniform "
            "gap whose dielectric Eq. 21 attraction is the solved one, A_R the real contact closed with a disc of "
            f"{scene.ridge_area.coarse_graining * MICRO:g} µm diameter. The crossover f_c is the series circuit's "
            "(stratum corneum R‖C, air and insulator a capacitor of air-equivalent thickness h_rest): "
            "f_c = σ_sc/(2π ε0 (ε_sc + d_sc/h_rest)), with h_rest = d_field/ε_a + d_i/ε_i at the sweep's highest "
            "frequency.", "",
            "Figure: `frequency_sweep.png`. Tables: `points.csv`, `realisations.csv`, `ridge_area_sensitivity.csv`, "
            "each with a `frequency_Hz` column"
            ", all of it in `results.nc` (dimension `frequency`).", "",
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


def variant_report_text(result: VariantStudyResult, seconds: float | None = None) -> str:
    """The Markdown report of a parameter study: what was solved, the inputs with their ranges and sources, the
    sensitivity at the report point and every variant's d_eq, d_field, F_el, A_R/A0 and μ."""
    study, sensitivity = result.study, result.sensitivity
    base, (force, voltage) = study.base, result.point
    converged = np.concatenate([variant.array("converged").ravel() for variant in result.results])
    text = [f"# Parameter study: {len(result.variants)} variants of the scene ({result.design})", "",
            f"roughcontact {__version__}, preset `{base.study.preset}`, solver tolerance {base.preset.tolerance:g}. "
            f"Scene: `scene.toml` in this directory, the base scene (the baseline) and its `[vary]` table. The "
            f"variants hold {result.tasks} distinct tasks ({result.computed} solved in this run with "
            f"{result.solves} contact solves, the others read back; a task that several variants share is solved "
            f"once). {converged.size - int(converged.sum())} of {converged.size} patch results did not converge "
            "and are left out of the means."
            + (f" Run time {seconds:.0f} s, tables and figures included." if seconds is not None else ""), "",
            describe(base.preset, base.study.preset) + applicability(base), "",
            "## Inputs", "", "Each variant is the base scene with these values substituted (the others at the "
            "baseline's); every variant's roughness uses the same seeds (`study.seed`), so the variants differ by "
            "their inputs only.", "", "| input | baseline | values | source |", "|---|---|---|---|"]
    for item, baseline in zip(study.inputs, study.baseline_values()):
        shown = "none" if baseline is None else Path(baseline).name if isinstance(baseline, str) else f"{baseline:g}"
        text.append(f"| `{item.name}` | {shown} | {item.describe()} | {item.source or 'the scene file'} |")
    text += ["", _design_sentence(result), "",
             f"## Sensitivity at F_N = {force:g} N, U = {voltage:g} V", "",
             f"Figure: `sensitivity.png`. Inputs in the order of their {sensitivity.ranked_by} for F_el; every "
             "load and voltage in `sensitivity.csv` and `results.nc`.", "",
             "| input | " + " | ".join(f"{OUTPUTS[name][0]}" for name in sensitivity.outputs) + " |",
             "|---" * (len(sensitivity.outputs) + 1) + "|"]
    for name in sensitivity.ranking("electrostatic_force", force, voltage):
        n = sensitivity.inputs.index(name)
        cells = [_measure_cell(sensitivity, output, n, force, voltage) for output in sensitivity.outputs]
        text.append(f"| `{name}` | " + " | ".join(cells) + " |")
    text += ["", "## Variants", "", "Realisation means; μ the bottom-up friction coefficient (ridge-area recipe). "
             "Tables: `variants.csv`, `sensitivity.csv`"
             ", all of it in `results.nc` (dimension `variant`, the inputs as its coordinates).",
             "", "| variant | F_N [N] | U [V] | d_eq [µm] | d_field [µm] | F_el [N] | A_R/A0 [%] | μ |",
             "|---" * 8 + "|"]
    for variant in result.variants:
        for i, f in enumerate(result.normal_forces):
            for j, u in enumerate(result.voltages):
                value = {name: result.outputs[name][variant.index, i, j] for name in OUTPUTS}
                text.append(f"| {variant.index}: {variant.label} | {f:g} | {u:g} | "
                            f"{value['equivalent_gap'] * MICRO:.3f} | {value['field_equivalent_gap'] * MICRO:.3f} | "
                            f"{value['electrostatic_force']:.4g} | {100 * value['ridge_area_fraction']:.3g} | "
                            f"{value['friction_coefficient']:.3f} |")
    return "\n".join(text) + "\n"


def _design_sentence(result: VariantStudyResult) -> str:
    """What the design's variants are and what its measures mean."""
    variation = result.study.variation
    if result.design == "one-at-a-time":
        return (f"Design: one at a time, {len(result.variants)} variants (the baseline, then each input at each "
                "listed value or at its range's two ends). Each cell: the change of the output from the baseline "
                "at the input's lowest / highest level [%]; the inputs are ranked by the swing, the output's range "
                "over the baseline and the input's levels over the baseline's value.")
    sampler = (f"Morris, {variation.samples} trajectories on {variation.levels} levels" if result.design == "morris"
               else f"Sobol'/Saltelli, {variation.samples} base points (first and total order)")
    measures = ("μ* ± its 95 % interval (σ): the mean absolute elementary effect of a step across the input's range "
                "(the unit cube of the sampler: a log range per its log-span) and its spread, which nonlinearity "
                "and interactions raise" if result.design == "morris" else
                "S1 / ST: the share of the output's variance due to the input alone, and with all its interactions")
    return (f"Design: {sampler} (SALib, seed {variation.seed}), {len(result.variants)} variants. Each cell: "
            f"{measures}.")


def _measure_cell(sensitivity, output: str, n: int, force: float, voltage: float) -> str:
    """One input's measures of ``output`` at (``force``, ``voltage``) for the report's table."""
    def value(name):
        return sensitivity.measure(name, output, force, voltage)[n]
    if not np.isfinite(value(sensitivity.ranked_by)):
        return "–"
    if sensitivity.design == "one-at-a-time":
        return f"{100 * value('low'):+.1f} / {100 * value('high'):+.1f}"
    if sensitivity.design == "morris":
        return f"{value('mu_star'):.3g} ± {value('mu_star_conf'):.2g} ({value('sigma'):.3g})"
    return f"{value('S1'):.2f} / {value('ST'):.2f}"


def write_results(result: StudyResult | VariantStudyResult, out, provenance, seconds: float | None = None) -> dict:
    """Write ``results.nc``, the CSV tables, the figures and ``report.md`` into the directory ``out``; ``seconds``
    the run time so far (the study's). Returns ``{"files": [paths], "seconds": the run time the report states}``,
    the writing included, so that a command can print the report's number. A parameter study (a
    :class:`~.variant_run.VariantStudyResult`) gets ``variants.csv``, ``sensitivity.csv``, ``sensitivity.png``,
    ``results.nc`` with a variant dimension and its report (:func:`variant_report_text`)."""
    start = time.perf_counter()
    if isinstance(result, VariantStudyResult):
        files = (write_variant_tables(result, out, provenance) + write_sensitivity_figure(result, out, provenance)
                 + [write_variant_dataset(result, out, provenance)])
        seconds = None if seconds is None else seconds + time.perf_counter() - start
        (out / "report.md").write_text(variant_report_text(result, seconds))
        return {"files": files + [out / "report.md"], "seconds": seconds}
    files = (write_tables(result, out, provenance) + write_figures(result, out, provenance)
             + [write_dataset(result, out, provenance)])
    report = out / "report.md"
    if seconds is not None:
        seconds += time.perf_counter() - start
    report.write_text((sweep_report_text if result.frequencies else report_text)(result, seconds))
    return {"files": files + [report], "seconds": seconds}
