"""The bottom-up prediction against the measured fingertip: every number and the figure of
docs/validation/measurements.md and docs/findings/measured_fingertip.md.

    python studies/validation_measurements.py           # the seven studies and every table (about 7 min on 2 cores)
    python studies/validation_measurements.py --docs    # also the pages' tables and docs/img/validation_friction.png
    python studies/validation_measurements.py --fast    # 32² patches, few samples: a test run

Seven studies of the default scene share one task directory (``--tasks``, default ``<output>/tasks``), so an
interrupted or repeated run resumes and a task is never solved twice:

* ``central`` (standard preset): F_N = 0.5, 1, 1.5, 2, 4.5 N at U = 0–200 V RMS, the voltages including the RMS
  values of 100 and 200 V read as amplitudes (70.711, 141.421 V) and of Guo et al.'s 150 V peak to peak (53.033 V
  for a sine, 75 V for a square wave);
* ``inputs`` (draft): the eight physical inputs one at a time at the ends of their published ranges
  (``roughcontact/study/input_ranges.toml``);
* ``sample`` (draft): a Sobol' sample of the five inputs that move F_el most over their ranges, jointly;
* ``leak`` and ``drive`` (draft): an AC drive of 62.5 Hz – 100 kHz with the interface's leak σ_g = 1.5e-8 S/m (the
  default scene's half-way point near the measured 250 Hz, docs/guide/ac_drive.md) and without it;
* ``gaps`` (the central scene's patches re-solved at 0, 141.421 and 200 V): the field solved again on each
  equilibrium gap widened by a uniform extra gap t, and the share of the attraction on contact pixels;
* ``breakdown`` (draft): the breakdown field of the contact lines' air breakdown at half, twice and four times
  350 V/µm, and the plain layered field without it.

The measurement stand-in for Sirin et al. 2019a is the seed's friction law (``SlidingFrictionModel.paper_table1``),
which its authors fitted to the measured tangential forces with three parameters: a fit, labelled as such, not
a prediction. The bottom-up μ is μ0 (1 + F_el/F_N) with the seed's μ0 = 0.26 (the measured COF at 0 V) and the
solved F_el = σ̄_el A0. Writes ``tables.md`` (every table, each under its name), ``numbers.csv`` (the central
study's numbers per load and voltage), ``gaps.npz`` (the fixed-gap field solves), ``sample.csv`` (every sampled
variant's inputs and outputs) and ``validation_friction.png``; prints the tables.
"""
from __future__ import annotations

import argparse
import math
import re
import time
import warnings
from pathlib import Path

import numpy as np

from roughcontact.electrostatics import AIR_BREAKDOWN_FIELD, solve_field
from roughcontact.fe.feed import FEAreaReduction
from roughcontact.io import output_directory, parse_arguments, save_figure, write_atomic, write_csv
from roughcontact.macro import SlidingFrictionModel
from roughcontact.solvers import solve_contact
from roughcontact.study import bottom_up_friction, load_scene, load_variant_study, run_study, run_variants
from roughcontact.study.apparent import apparent_scale
from roughcontact.study.plan import plan_study
from roughcontact.study.presets import measured
from roughcontact.study.records import confidence_interval, positive_interval

ROOT = Path(__file__).resolve().parents[1]
PAGES = {"validation": ROOT / "docs" / "validation" / "measurements.md",
         "finding": ROOT / "docs" / "findings" / "measured_fingertip.md"}
FIGURE = "validation_friction.png"
SEED = SlidingFrictionModel.paper_table1()
MU0 = SEED.mu0
#: Sirin et al. 2019a's loads in the seed's fit (its range 0–2.3 N) and Guo et al. 2019's highest load
LOADS = (0.5, 1.0, 1.5, 2.0, 4.5)
SIRIN_LOADS = (0.5, 1.0, 1.5, 2.0)
#: the reported voltages and the two readings of them: the RMS value, or the amplitude of a sine (RMS = U/√2)
READINGS = {"RMS": 1.0, "amplitude": 1 / math.sqrt(2)}
#: Guo et al. 2019: 150 V peak to peak; RMS of a sine (53.033 V) and of a square wave (75 V)
GUO_PEAK_TO_PEAK = 150.0
GUO_SINE, GUO_SQUARE = round(GUO_PEAK_TO_PEAK / (2 * math.sqrt(2)), 3), GUO_PEAK_TO_PEAK / 2
#: Guo et al.'s power law through their end points, 2.5 µm at 0.5 N and 1.5 µm at 4.5 N
GUO_GAPS = {0.5: 2.5e-6, 4.5: 1.5e-6}
VOLTAGES = (0.0, 50.0, GUO_SINE, 70.711, GUO_SQUARE, 100.0, 141.421, 150.0, 200.0)
#: Sirin et al. 2019b: apparent-area reduction at the onset of sliding, (F_N, U reported) -> fraction (seed)
SIRIN_2019B = {(1.0, 0.0): 0.08, (1.0, 100.0): 0.13, (2.0, 0.0): 0.15, (2.0, 100.0): 0.20}
#: the inputs at their published ranges, one at a time; the first five also sampled jointly
INPUTS = ("roughness.rms_height", "skin.layer_thickness", "skin.layer_E_star", "skin.E_star", "ridges.height",
          "screen.eps_sc", "roughness.hurst", "screen.d_sc")
SAMPLED = INPUTS[:5]
DRAFT_LOADS, DRAFT_VOLTAGES = (0.5, 1.0, 2.0), (0.0, 70.711, 100.0, 141.421, 200.0)
#: The breakdown field of the contact lines' air breakdown over the measured 350 V/µm: the model's one parameter,
#: measured only in gaps from 0.1 µm up (docs/findings/contact_line.md); four times it is towards the several V/nm
#: that vacuum nano-gaps between metals hold, and inf the plain layered field (no breakdown)
BREAKDOWN_FACTORS = (0.5, 1.0, 2.0, 4.0, math.inf)
SAMPLE_LOADS = (0.5, 2.0)
#: the interface's leak and the drive frequencies: carriers of 100–480 Hz are used in this literature
LEAK_CONDUCTIVITY = 1.5e-8
LEAK_FREQUENCIES = (62.5, 100.0, 160.0, 250.0, 320.0, 500.0, 1000.0, 1e5)
DRIVE_FREQUENCIES = (0.0, 125.0, 1e5)
#: the drive frequencies of the budget: the carriers of this literature, 100–480 Hz, to the nearest solved one
LEAK_RANGE = (100.0, 500.0)
#: uniform extra gaps t [m] of the fixed-gap field solves
EXTRA_GAPS = tuple(np.array([0, 0.25, 0.5, 0.75, 1, 1.5, 2, 3, 4, 6, 8]) * 1e-6)
#: the bottom-up μ "meets" the stand-in where their ratio lies within 1 ± this
TOLERANCE = 0.2
FAST_PRESET = {"grid": 32, "realisations": 2, "tolerance": 1e-6, "pixels_per_cutoff": 3.0}
FAST_SAMPLES, SAMPLES = 2, 32


def scene_text(loads, voltages, preset: str, fast: bool, extra: str = "") -> str:
    """A scene file: the default scene at ``loads`` and ``voltages`` on ``preset`` (``fast``: 32² patches), then
    ``extra`` (a [screen] or [vary] table)."""
    lines = ["# written by studies/validation_measurements.py", "[loads]", f"normal_forces = {list(loads)!r}",
             f"voltages = {list(voltages)!r}", "[study]", f'preset = "{preset}"']
    if fast:
        lines += ["[roughness]", "long_cutoff = 1.5e-4", f"[presets.{preset}]"]
        lines += [f"{key} = {value!r}" for key, value in FAST_PRESET.items()]
    return "\n".join(lines) + "\n" + extra


def vary_table(design: str, names, samples: int | None = None) -> str:
    """A [vary] table: ``names`` at their published ranges in ``design``."""
    lines = ["[vary]", f'design = "{design}"']
    if samples is not None:
        lines += [f"samples = {samples}", "seed = 1"]
    return "\n".join(lines + [f'"{name}" = "literature"' for name in names]) + "\n"


def drive_table(frequencies, conductivity: float | None) -> str:
    """A [screen] table: an AC drive at ``frequencies`` [Hz], with the gap's ``conductivity`` σ_g [S/m] if given."""
    lines = ["[screen]", f"frequency = {list(frequencies)!r}"]
    if conductivity:
        lines.append(f"gap_conductivity = {conductivity!r}")
    return "\n".join(lines) + "\n"


def run_studies(args, tasks) -> dict:
    """The seven studies (module docstring), each resumed from the shared task directory ``tasks``; prints the
    wall time of each."""
    fast, workers = args.fast, args.workers or (1 if args.fast else 2)
    central = load_scene(text=scene_text(LOADS, VOLTAGES, "standard", fast))
    studies, began = {}, time.perf_counter()

    def done(name):
        nonlocal began
        print(f"{name}: {time.perf_counter() - began:.0f} s", flush=True)
        began = time.perf_counter()

    studies["central"] = run_study(central, tasks=tasks, workers=workers)
    done("central")
    for name, text in (("inputs", vary_table("one-at-a-time", INPUTS)),
                       ("sample", vary_table("sobol", SAMPLED, FAST_SAMPLES if fast else SAMPLES))):
        loads = SAMPLE_LOADS if name == "sample" else DRAFT_LOADS
        study = load_variant_study(text=scene_text(loads, DRAFT_VOLTAGES, "draft", fast, text))
        with warnings.catch_warnings():     # SALib on the outputs at 0 V, equal in every variant (F_el = 0)
            warnings.filterwarnings("ignore", message="Constant values encountered")
            studies[name] = run_variants(study, tasks=tasks, workers=workers)
        done(name)
    for name, frequencies, leak in (("leak", LEAK_FREQUENCIES, LEAK_CONDUCTIVITY), ("drive", DRIVE_FREQUENCIES, None)):
        voltages = (141.421, 200.0) if leak else (200.0,)
        scene = load_scene(text=scene_text(DRAFT_LOADS, voltages, "draft", fast, drive_table(frequencies, leak)))
        studies[name] = run_study(scene, tasks=tasks, workers=workers)
        done(name)
    studies["breakdown"] = {factor: run_study(load_scene(text=scene_text(
        DRAFT_LOADS, DRAFT_VOLTAGES[1:], "draft", fast, f'[screen]\ncontact_line = "{contact_line(factor)}"\n')),
        tasks=tasks, workers=workers) for factor in BREAKDOWN_FACTORS}
    done("breakdown")
    studies["gaps"] = extra_gap_fields(central)
    done("gaps")
    return studies


# ---------------------------------------------------------------------------------------------------------
# The stand-in and the central study
# ---------------------------------------------------------------------------------------------------------
def stand_in(force, voltage) -> np.ndarray:
    """F_el/F_N of the measurement stand-in: the seed's μ (Table 1, fitted to Sirin et al. 2019a) over μ0, less 1."""
    return np.asarray(SEED.friction_coefficient(force, voltage)) / MU0 - 1


def attraction_samples(result) -> np.ndarray:
    """F_el/F_N of every realisation, (loads, voltages[, frequencies], realisations); NaN where a solve failed."""
    force = result.array("electrostatic_attraction") * result.array("apparent_area")[..., None]
    force = np.where(result.array("converged").astype(bool), force, np.nan)
    shape = (-1,) + (1,) * (force.ndim - 1)
    return force / result.normal_forces.reshape(shape)


def central_numbers(result) -> dict:
    """The central study's numbers per (load, voltage): F_el/F_N (``x``) with its sampling interval and its total
    interval (sampling, then the standard preset's discretisation error of F_el, docs/guide/presets.md), d_field and
    d_eq with their intervals widened by the preset's gap errors, the real contact fraction with its interval, and
    the ridge-area reduction of the friction recipe. The errors are the standard preset's (measured on the default
    scene), in ``--fast`` too."""
    entry = measured(load_scene(preset="standard").preset)              # the standard preset's errors (--fast too)
    fel_error = entry.discretisation["fel_error"]                # |F_el error| of the pixel, either sign
    samples = attraction_samples(result)
    x = np.nanmean(samples, axis=-1)
    low, high = positive_interval(samples)
    numbers = {"x": x, "x_low": low, "x_high": high,
               "x_total_low": low / (1 + fel_error), "x_total_high": high / (1 - fel_error)}
    for name, error in (("field_equivalent_gap", entry.discretisation["field_deq_error"]),
                        ("equivalent_gap", entry.discretisation["deq_error"])):
        values = np.where(result.array("converged").astype(bool), result.array(name), np.nan)
        mean, (low, high) = np.nanmean(values, axis=-1), positive_interval(values)
        numbers[name] = mean
        numbers[name + "_low"], numbers[name + "_high"] = low * (1 - error), high * (1 + error)
        numbers[name + "_error"] = error
    numbers["contact"] = result.summary("contact_fraction")[0]
    numbers["contact_low"], numbers["contact_high"] = positive_interval(result.array("contact_fraction"), 1.0)
    numbers["reduction"] = bottom_up_friction(result).state(result.normal_forces[:, None],
                                                            result.voltages[None, :]).area_reduction
    return numbers


def index(values, value: float) -> int:
    """The index of ``value`` in ``values`` (to 1e-3 V or N)."""
    found = np.flatnonzero(np.isclose(np.asarray(values, dtype=float), value, atol=1e-3, rtol=0))
    if found.size != 1:
        raise ValueError(f"{value!r} is not one of {list(values)}")
    return int(found[0])


def reading_voltage(reported: float, reading: str) -> float:
    """The RMS voltage of the solve for a ``reported`` voltage under ``reading``, rounded as in the scenes."""
    return round(reported * READINGS[reading], 3)


# ---------------------------------------------------------------------------------------------------------
# The inputs' ranges: one at a time and jointly
# ---------------------------------------------------------------------------------------------------------
def draft_factors(variants) -> tuple:
    """``(labels, F_el factors, d_field factors)``: each variant's realisation-mean F_el and field-equivalent gap
    over the baseline's (the first variant), shape (variants, loads, voltages); F_el NaN at 0 V."""
    force = variants.outputs["electrostatic_force"]
    gap = variants.outputs["field_equivalent_gap"]
    with np.errstate(divide="ignore", invalid="ignore"):
        return ([variant.label for variant in variants.variants], force / force[:1], gap / gap[:1])


def standard_over_draft(central, variants) -> tuple:
    """``(F_el, d_field)`` factors that take the draft baseline of ``variants`` to the central standard study at
    the variants' loads and voltages (the draft preset's discretisation against the standard's)."""
    base = variants.outputs
    forces = variants.normal_forces
    rows = [index(central.normal_forces, force) for force in forces]
    columns = [index(central.voltages, voltage) for voltage in variants.voltages]
    force = central.summary("electrostatic_attraction")[0] * central.array("apparent_area")
    gap = central.summary("field_equivalent_gap")[0]
    with np.errstate(divide="ignore", invalid="ignore"):
        return (force[np.ix_(rows, columns)] / base["electrostatic_force"][0],
                gap[np.ix_(rows, columns)] / base["field_equivalent_gap"][0])


def sample_rows(central, variants) -> list:
    """Every sampled variant: its inputs, its F_el/F_N at each load and voltage and d_field at 0 V (draft, scaled
    to the standard preset by :func:`standard_over_draft`), and its ratio to the stand-in at 100 and 200 V
    reported, read as RMS and as amplitude."""
    force_factor, gap_factor = standard_over_draft(central, variants)
    forces, voltages = variants.normal_forces, variants.voltages
    x = variants.outputs["electrostatic_force"] * force_factor / forces[None, :, None]
    gaps = variants.outputs["field_equivalent_gap"] * gap_factor
    rows = []
    for v, variant in enumerate(variants.variants):
        row = {"variant": v, "label": variant.label,
               **{name: value for name, value in zip(variants.study.variation.names, variant.values)}}
        for i, force in enumerate(forces):
            row[f"d_field_0V_{force:g}N_um"] = gaps[v, i, index(voltages, 0.0)] * 1e6
            for j, voltage in enumerate(voltages):
                if voltage > 0:
                    row[f"x_{force:g}N_{voltage:g}V"] = x[v, i, j]
            for reported in (100.0, 200.0):
                for reading in READINGS:
                    solved = x[v, i, index(voltages, reading_voltage(reported, reading))]
                    row[f"ratio_{force:g}N_{reported:g}V_{reading}"] = (1 + solved) / (1 + stand_in(force, reported))
        rows.append(row)
    return rows


def meets(row, loads, reported, reading: str) -> bool:
    """Whether a sampled variant's μ lies within 1 ± :data:`TOLERANCE` of the stand-in's at every load and
    reported voltage given."""
    return all(abs(row[f"ratio_{force:g}N_{voltage:g}V_{reading}"] - 1) <= TOLERANCE
               for force in loads for voltage in reported)


# ---------------------------------------------------------------------------------------------------------
# The missing physics: a uniform extra gap and the contact pixels' share, on fixed equilibrium gaps
# ---------------------------------------------------------------------------------------------------------
def extra_gap_fields(scene) -> dict:
    """On each realisation's equilibrium gap at 0 V (the hard wall) and at 141.421 and 200 V (the layered law;
    every load up to 2 N in order, each warm-started from the last, as the study's tasks): the mean attraction
    at those voltages with every gap widened by each of :data:`EXTRA_GAPS`, and the part of it on contact pixels.
    Returns ``{"forces", "voltages", "attraction": (loads, voltages, gap states, extra gaps, realisations) [Pa],
    "contact_share": (loads, voltages, gap states, realisations), "area": A0 per load}``; gap state 0 is the
    0 V gap, 1 the gap solved at that voltage."""
    plan = plan_study(scene)
    forces = tuple(force for force in scene.loads.normal_forces if force <= 2.0)
    voltages = (141.421, 200.0)
    scales = apparent_scale(scene)[:len(forces)]
    stack, body = scene.screen.stack(), plan.body(threads=1)
    count = plan.realisations
    attraction = np.full((len(forces), len(voltages), 2, len(EXTRA_GAPS), count), np.nan)
    share = np.full((len(forces), len(voltages), 2, count), np.nan)
    for r in range(count):
        heights = plan.surface(r)
        chains = {0.0: None, **{voltage: None for voltage in voltages}}
        for i, (_, (pressure, *_)) in enumerate(scales):
            for voltage in chains:
                law = scene.screen.interaction(voltage, None)
                chains[voltage] = solve_contact(heights, body, mean_pressure=pressure, interaction=law,
                                                tol=scene.preset.tolerance, x0=chains[voltage], warn=False)
            for j, voltage in enumerate(voltages):
                contact_line = scene.screen.interaction(voltage, None).contact_line     # the study's law's
                for state, solved in enumerate((chains[0.0], chains[voltage])):
                    if not solved.converged:
                        continue
                    gap = np.asarray(solved.gap, dtype=float)
                    for k, extra in enumerate(EXTRA_GAPS):
                        sigma = solve_field(stack, gap + extra, plan.grid.lengths, voltage, tol=1e-8,
                                            contact_line=contact_line).attraction
                        attraction[i, j, state, k, r] = sigma.mean()
                        if k == 0:
                            share[i, j, state, r] = sigma[np.asarray(solved.contact)].sum() / sigma.sum()
    return {"forces": forces, "voltages": voltages, "attraction": attraction, "contact_share": share,
            "area": np.array([area for area, _ in scales])}


def extra_gap_needed(gaps: dict, target: float, i: int, j: int, state: int) -> float:
    """The uniform extra gap [m] at which the realisation-mean attraction on gap state ``state`` falls to
    ``target`` [Pa] (log-linear between the solved extra gaps; 0 if already below, inf beyond the last)."""
    mean = np.nanmean(gaps["attraction"][i, j, state], axis=-1)
    if target >= mean[0]:
        return 0.0
    if target < mean[-1]:
        return math.inf
    return float(np.interp(-math.log(target), -np.log(mean), EXTRA_GAPS))


# ---------------------------------------------------------------------------------------------------------
# The drive: the leak's factor on F_el
# ---------------------------------------------------------------------------------------------------------
def drive_factors(result) -> tuple:
    """``(factor, converged)``: F_el at each drive frequency over the same realisation's F_el at the highest
    (paired), its mean over the realisations whose solves converged, shape (loads, voltages, frequencies), and how
    many did."""
    samples = attraction_samples(result)
    with np.errstate(divide="ignore", invalid="ignore"), warnings.catch_warnings():
        warnings.filterwarnings("ignore", message="Mean of empty slice")        # no realisation converged: NaN
        paired = samples / samples[:, :, -1:, :]
        return np.nanmean(paired, axis=-1), np.sum(np.isfinite(paired), axis=-1)


def first_order(frequency: float, corner: float = 250.0) -> float:
    """F/F∞ of a first-order leak with its corner at ``corner`` [Hz] (references §11): (f/f_g)²/(1 + (f/f_g)²)."""
    ratio = (frequency / corner) ** 2
    return ratio / (1 + ratio)


def leak_factor(studies, force: float, voltage: float, frequency: float) -> float:
    """The leak's factor on F_el at (``force``, ``voltage`` RMS, ``frequency``), NaN where no realisation
    converged."""
    leak = studies["leak"]
    factor, _ = drive_factors(leak)
    return float(factor[index(leak.normal_forces, force), index(leak.voltages, voltage),
                        index(leak.frequencies, frequency)])


# ---------------------------------------------------------------------------------------------------------
# Tables
# ---------------------------------------------------------------------------------------------------------
def table(header, rows) -> str:
    """A markdown table."""
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    return "\n".join(lines + ["| " + " | ".join(str(cell) for cell in row) + " |" for row in rows])


def shown(value, digits: int = 2) -> str:
    """A number to ``digits`` decimals, or "–" where it is not finite (no realisation converged)."""
    return f"{value:.{digits}f}" if np.isfinite(value) else "–"


def span(low, high, digits: int = 3) -> str:
    return f"[{low:.{digits}f}, {high:.{digits}f}]"


def mu(x) -> np.ndarray:
    """The bottom-up (or stand-in) μ = μ0 (1 + F_el/F_N)."""
    return MU0 * (1 + np.asarray(x))


def sirin_table(numbers, central) -> str:
    """Sirin et al. 2019a: the stand-in's μ against the bottom-up μ at 100 and 200 V reported, read as RMS and as
    amplitude, with the total interval, and their ratios."""
    rows = []
    for force in SIRIN_LOADS:
        i = index(central.normal_forces, force)
        for reported in (100.0, 200.0):
            measured_mu = MU0 * (1 + stand_in(force, reported))
            row = [f"{force:g}", f"{reported:g}", f"{measured_mu:.3f} ({stand_in(force, reported):.2f})"]
            for reading in READINGS:
                j = index(central.voltages, reading_voltage(reported, reading))
                value = mu(numbers["x"][i, j])
                row += [f"{value:.3f} ({numbers['x'][i, j]:.2f}) "
                        + span(mu(numbers["x_total_low"][i, j]), mu(numbers["x_total_high"][i, j])),
                        f"{value / measured_mu:.2f}"]
            rows.append(row)
    return table(["F_N [N]", "U reported [V]", "stand-in μ (F_el/F_N)", "bottom-up μ, U as RMS (F_el/F_N) [total]",
                  "ratio", "bottom-up μ, U as amplitude (F_el/F_N) [total]", "ratio"], rows)


def budget_table(numbers, studies) -> str:
    """The uncertainty budget of the bottom-up μ at 200 V reported, at 0.5 and 2 N: each source's range."""
    central, inputs, sample = studies["central"], studies["inputs"], studies["sample"]
    _, force_factor, _ = draft_factors(inputs)
    sampled = sample_rows(central, sample)
    lines = {name: [] for name in ("stand-in (the seed's fit to the measurement)", "bottom-up, 200 V RMS: sampling",
                                   "+ discretisation", "inputs one at a time (draft)",
                                   "five inputs jointly (draft, Sobol' sample)",
                                   "200 V read as amplitude (141.4 V RMS)",
                                   "200 V RMS, leak at {:g}–{:g} Hz".format(*LEAK_RANGE),
                                   "amplitude and leak at {:g}–{:g} Hz".format(*LEAK_RANGE))}
    for force in SAMPLE_LOADS:
        i, j = index(central.normal_forces, force), index(central.voltages, 200.0)
        a = index(central.voltages, 141.421)
        measured_mu = MU0 * (1 + stand_in(force, 200.0))
        x = numbers["x"][i, j]

        def cell(low, high):
            return (f"{shown(mu(low), 3)}–{shown(mu(high), 3)} "
                    f"({shown(mu(low) / measured_mu)}–{shown(mu(high) / measured_mu)})")
        factors = force_factor[:, index(inputs.normal_forces, force), index(inputs.voltages, 200.0)]
        joint = [row[f"x_{force:g}N_200V"] for row in sampled]
        leak = [leak_factor(studies, force, voltage, f) for voltage in (200.0, 141.421) for f in LEAK_RANGE]
        values = [(x, x), (numbers["x_low"][i, j], numbers["x_high"][i, j]),
                  (numbers["x_total_low"][i, j], numbers["x_total_high"][i, j]),
                  (x * np.nanmin(factors), x * np.nanmax(factors)), (np.nanmin(joint), np.nanmax(joint)),
                  (numbers["x_total_low"][i, a], numbers["x_total_high"][i, a]),
                  (x * leak[0], x * leak[1]), (numbers["x"][i, a] * leak[2], numbers["x"][i, a] * leak[3])]
        first = list(lines)[0]
        lines[first].append(f"{measured_mu:.3f} (1)")
        for name, (low, high) in zip(list(lines)[1:], values[1:]):
            lines[name].append(cell(low, high))
    return table(["source", *(f"μ at {force:g} N (ratio)" for force in SAMPLE_LOADS)],
                 [[name, *cells] for name, cells in lines.items()])


def guo_law(force) -> np.ndarray:
    """Guo et al. 2019's gap [m] as the power law through their end points (2.5 µm at 0.5 N, 1.5 µm at 4.5 N)."""
    (f0, g0), (f1, g1) = GUO_GAPS.items()
    exponent = math.log(g1 / g0) / math.log(f1 / f0)
    return g0 * (np.asarray(force) / f0) ** exponent


def guo_table(numbers, central) -> str:
    """Guo et al. 2019: their gap law against the bottom-up field-equivalent gap at 150 V peak to peak (a sine:
    53.033 V RMS; a square wave: 75 V), and in the conventions they may have inferred theirs with (U_G = 75 V or
    150 V in ε0 U_G²/(2 (c + g)²) matched to the mean force): g_G = (c + d_field) U_G/U_RMS − c; and the shape
    (c + g)/(c + g at 0.5 N), which does not depend on U_G."""
    offset = central.scene.screen.stack().eps_a * central.scene.screen.stack().dielectric_offset
    sine, square = index(central.voltages, GUO_SINE), index(central.voltages, GUO_SQUARE)
    gaps = numbers["field_equivalent_gap"]
    rows = []
    for force in LOADS:
        i = index(central.normal_forces, force)
        d = gaps[i, sine]
        converted = [(offset + d) * level / GUO_SINE - offset for level in (GUO_SQUARE, GUO_PEAK_TO_PEAK)]
        shape_guo = (offset + guo_law(force)) / (offset + guo_law(0.5))
        shape_bottom_up = (offset + d) / (offset + gaps[0, sine])
        rows.append([f"{force:g}", f"{guo_law(force) * 1e6:.2f}",
                     f"{d * 1e6:.2f} " + span(numbers["field_equivalent_gap_low"][i, sine] * 1e6,
                                              numbers["field_equivalent_gap_high"][i, sine] * 1e6, 2),
                     *(f"{value * 1e6:.2f}" for value in converted), f"{gaps[i, square] * 1e6:.2f}",
                     f"{shape_guo:.3f} / {shape_bottom_up:.3f}"])
    return table(["F_N [N]", "Guo et al. [µm]", "bottom-up d_field, sine (53.0 V RMS) [µm] [total]",
                  "as Guo's with U_G = 75 V [µm]", "with U_G = 150 V [µm]", "d_field, square wave (75 V RMS) [µm]",
                  "(c + g)/(c + g)(0.5 N): Guo / bottom-up"], rows)


def sirin_b_table(numbers, central) -> str:
    """Sirin et al. 2019b: the apparent-area reduction at the onset of sliding, measured, by the seed's Eq. 44
    (Table 1), by the bottom-up friction recipe (the seed's c₂ on the bottom-up A_R), both readings, and by the FE
    fingertip's packaged table (Eq. 34's fit) at the stand-in's F_T/F_N, mapped to the area linearly and
    isotropically (docs/findings/fe_fingertip.md)."""
    seed = SEED.state(np.array([force for force, _ in SIRIN_2019B]), np.array([u for _, u in SIRIN_2019B]))
    fe = {isotropic: FEAreaReduction.from_summary(isotropic=isotropic) for isotropic in (False, True)}
    reduction_fe = {isotropic: 1 - table.area_ratio(seed.normal_force, seed.tangential_force,
                                                    seed.tangential_force / seed.normal_force)
                    for isotropic, table in fe.items()}
    rows = []
    for n, ((force, reported), measured_value) in enumerate(SIRIN_2019B.items()):
        i = index(central.normal_forces, force)
        cells = [f"{100 * numbers['reduction'][i, index(central.voltages, reading_voltage(reported, reading))]:.1f}"
                 for reading in READINGS]
        rows.append([f"{force:g}", f"{reported:g}", f"{100 * measured_value:.0f}",
                     f"{100 * seed.area_reduction[n]:.1f}", *cells,
                     f"{100 * reduction_fe[False][n]:.1f} / {100 * reduction_fe[True][n]:.1f}"])
    return table(["F_N [N]", "U reported [V]", "measured [%]", "seed Eq. 44 [%]", "bottom-up recipe, U as RMS [%]",
                  "U as amplitude [%]", "FE fingertip, linear / isotropic [%]"], rows)


def aliabbasi_table(studies) -> str:
    """The drive frequency: F_el over its value at 100 kHz (paired by realisation) with the leak σ_g at 200 and
    141.421 V, without it at 200 V, and the first-order circuit with a 250 Hz corner."""
    leak, drive = studies["leak"], studies["drive"]
    factor, converged = drive_factors(leak)
    plain, plain_converged = drive_factors(drive)
    frequencies = sorted(set(leak.frequencies[:-1]) | set(drive.frequencies[:-1]))
    rows = []
    for frequency in frequencies:
        cells = []
        for voltage in (200.0, 141.421):
            if frequency in leak.frequencies:
                k = index(leak.frequencies, frequency)
                j = index(leak.voltages, voltage)
                cells.append(" / ".join("–" if not converged[i, j, k] else f"{factor[i, j, k]:.2f}"
                                        for i in range(len(leak.normal_forces))))
            else:
                cells.append("")
        if frequency in drive.frequencies:
            k = index(drive.frequencies, frequency)
            cells.append(" / ".join("–" if not plain_converged[i, 0, k] else f"{plain[i, 0, k]:.3f}"
                                    for i in range(len(drive.normal_forces))))
        else:
            cells.append("")
        label = "DC" if frequency == 0 else f"{frequency:g}"
        rows.append([label, f"{first_order(frequency):.3f}", *cells])
    return table(["f [Hz]", "first order, 250 Hz corner", "leak, 200 V: 0.5 / 1 / 2 N", "leak, 141.4 V",
                  "no leak, 200 V"], rows)


def exponent_samples(result, low: float, high: float) -> np.ndarray:
    """ln(F_el(high)/F_el(low))/ln(high/low) per realisation, (loads, realisations)."""
    x = attraction_samples(result)
    return np.log(x[:, index(result.voltages, high)] / x[:, index(result.voltages, low)]) / math.log(high / low)


def meyer_table(central, inputs) -> str:
    """Meyer et al. 2013 (F_el ∝ U²): the exponent of F_el in U over 50–100 and 100–200 V, of the stand-in, of
    the bottom-up (± the 95 % interval over realisations) and over the inputs' ranges one at a time (draft)."""
    rows = []
    force = inputs.outputs["electrostatic_force"]
    high, low = (force[:, :, index(inputs.voltages, voltage)] for voltage in (200.0, 100.0))
    spread = np.log(high / low) / math.log(2)
    for force_value in SIRIN_LOADS:
        i = index(central.normal_forces, force_value)
        cells = [f"{math.log(stand_in(force_value, high) / stand_in(force_value, low)) / math.log(high / low):.2f}"
                 for low, high in ((50.0, 100.0), (100.0, 200.0))]
        for low, high in ((50.0, 100.0), (100.0, 200.0)):
            mean, half = confidence_interval(exponent_samples(central, low, high)[i])
            cells.append(f"{mean:.2f} ± {half:.2f}")
        if force_value in inputs.normal_forces:
            values = spread[:, index(inputs.normal_forces, force_value)]
            cells.append(f"{np.nanmin(values):.2f}–{np.nanmax(values):.2f}")
        else:
            cells.append("")
        rows.append([f"{force_value:g}", *cells])
    return table(["F_N [N]", "stand-in, 50–100 V", "stand-in, 100–200 V", "bottom-up, 50–100 V",
                  "bottom-up, 100–200 V", "bottom-up 100–200 V, inputs one at a time"], rows)


def ayyildiz_table(numbers, central) -> str:
    """Ayyildiz et al. 2018: the real (pixel) contact fraction against the voltage, and its growth from 0 V."""
    voltages = (0.0, 50.0, 100.0, 150.0, 200.0)
    rows = []
    for force in (0.5, 1.0, 2.0):
        i = index(central.normal_forces, force)
        columns = [index(central.voltages, voltage) for voltage in voltages]
        cells = [f"{100 * numbers['contact'][i, j]:.2f} "
                 + span(100 * numbers["contact_low"][i, j], 100 * numbers["contact_high"][i, j], 2) for j in columns]
        rows.append([f"{force:g}", *cells, f"{numbers['contact'][i, columns[-1]] / numbers['contact'][i, 0]:.1f}"])
    return table(["F_N [N]", *(f"{voltage:g} V [%]" for voltage in voltages), "200 V / 0 V"], rows)


def readings_table(numbers, studies) -> str:
    """How much of the factor each reading explains: the bottom-up μ over the stand-in's at 200 V reported, read
    as RMS or as amplitude, without a leak and with the leak σ_g at 100, 250 and 500 Hz."""
    central = studies["central"]
    frequencies = (100.0, 250.0, 500.0)
    rows = []
    for force in DRAFT_LOADS:
        i = index(central.normal_forces, force)
        measured_mu = MU0 * (1 + stand_in(force, 200.0))
        cells = []
        for reading in READINGS:
            voltage = reading_voltage(200.0, reading)
            x = numbers["x"][i, index(central.voltages, voltage)]
            cells.append(f"{mu(x) / measured_mu:.2f}")
            cells += [shown(mu(x * leak_factor(studies, force, voltage, f)) / measured_mu) for f in frequencies]
        rows.append([f"{force:g}", *cells])
    header = ["F_N [N]"]
    for reading in READINGS:
        header += [f"U as {reading}", *(f"+ leak at {f:g} Hz" for f in frequencies)]
    return table(header, rows)


def input_levels(inputs) -> dict:
    """``{input: (variant index at its low end, at its high end)}`` of a one-at-a-time study."""
    levels = {}
    for variant in inputs.variants[1:]:
        name = variant.label.split(" = ")[0]
        levels.setdefault(name, []).append(variant.index)
    return {name: tuple(found) for name, found in levels.items()}


def tornado_table(numbers, studies) -> str:
    """Each input at its published range's ends, the others at the default scene's values (draft, 0.5 N): the
    change of F_el at 200 V and of d_field at 0 V, and the bottom-up μ over the stand-in's at 200 V reported
    (the central study scaled by the draft change), read as RMS and as amplitude."""
    central, inputs = studies["central"], studies["inputs"]
    _, force_factor, gap_factor = draft_factors(inputs)
    i, ci = index(inputs.normal_forces, 0.5), index(central.normal_forces, 0.5)
    measured_mu = MU0 * (1 + stand_in(0.5, 200.0))
    names = inputs.study.variation.names
    rows = []
    for name, (low, high) in input_levels(inputs).items():
        values = [inputs.variants[v].values[names.index(name)] for v in (low, high)]
        cells = [f"{values[0]:.3g} … {values[1]:.3g}"]
        cells.append(" / ".join(f"{100 * (force_factor[v, i, index(inputs.voltages, 200.0)] - 1):+.0f}"
                                for v in (low, high)))
        cells.append(" / ".join(f"{100 * (gap_factor[v, i, 0] - 1):+.0f}" for v in (low, high)))
        for reading in READINGS:
            voltage = reading_voltage(200.0, reading)
            x = numbers["x"][ci, index(central.voltages, voltage)]
            cells.append(" / ".join(f"{mu(x * force_factor[v, i, index(inputs.voltages, voltage)]) / measured_mu:.2f}"
                                    for v in (low, high)))
        rows.append([f"`{name}`", *cells])
    return table(["input", "range", "F_el at 200 V: low / high end [%]", "d_field at 0 V [%]",
                  "μ ratio, 200 V as RMS", "μ ratio, as amplitude"], rows)


def contact_line(factor: float) -> str:
    """The scene's ``[screen] contact_line`` for a breakdown field ``factor`` times 350 V/µm (inf: none)."""
    return "none" if math.isinf(factor) else f"breakdown:{factor * AIR_BREAKDOWN_FIELD:g}"


def breakdown_table(numbers, studies) -> str:
    """The breakdown field E_bd at :data:`BREAKDOWN_FACTORS` times 350 V/µm (draft): the change of F_el at 200 V
    and the bottom-up μ over the stand-in's at 200 V reported (the central study scaled by the draft change), read
    as RMS and as amplitude, at each of :data:`DRAFT_LOADS`."""
    central, runs = studies["central"], studies["breakdown"]
    base = runs[1.0]

    def force(result):
        return result.summary("electrostatic_attraction")[0] * result.array("apparent_area")

    rows = []
    for factor, result in runs.items():
        change = force(result) / force(base)
        cells = [" / ".join(f"{100 * (change[i, index(result.voltages, 200.0)] - 1):+.0f}"
                            for i in range(len(DRAFT_LOADS)))]
        for reading in READINGS:
            voltage = reading_voltage(200.0, reading)
            ratios = []
            for i, load in enumerate(DRAFT_LOADS):
                x = numbers["x"][index(central.normal_forces, load), index(central.voltages, voltage)]
                scaled = x * change[i, index(result.voltages, voltage)]
                ratios.append(f"{mu(scaled) / (MU0 * (1 + stand_in(load, 200.0))):.2f}")
            cells.append(" / ".join(ratios))
        label = "∞ (the plain layered field)" if math.isinf(factor) else f"{factor * AIR_BREAKDOWN_FIELD / 1e6:g}"
        rows.append([label, *cells])
    loads = " / ".join(f"{load:g}" for load in DRAFT_LOADS)
    return table(["E_bd [V/µm]", f"F_el at 200 V, {loads} N [%]", f"μ ratio, 200 V as RMS, {loads} N",
                  "μ ratio, as amplitude"], rows)


#: how the tables show each input: scale and unit
UNITS = {"roughness.rms_height": (1e6, "µm"), "skin.layer_thickness": (1e6, "µm"), "skin.layer_E_star": (1e-6, "MPa"),
         "skin.E_star": (1e-6, "MPa"), "ridges.height": (1e6, "µm")}
#: what a combination meets: the reported voltages at which its μ is within 1 ± TOLERANCE of the stand-in's, and
#: whether its 0 V field-equivalent gap is also within 1 ± TOLERANCE of the seed's fitted gap (Eq. 46)
CRITERIA = {"μ at 200 V": ((200.0,), False), "μ at 100 and 200 V": ((100.0, 200.0), False),
            "μ at 100 and 200 V, and the 0 V gap": ((100.0, 200.0), True)}


def meets_all(row, reading: str, criterion: str) -> bool:
    """Whether a variant's row meets ``criterion`` (:data:`CRITERIA`) at 0.5 and 2 N under ``reading``."""
    reported, gap = CRITERIA[criterion]
    gaps = (abs(row[f"d_field_0V_{force:g}N_um"] / (SEED.gap(force, 0.0) * 1e6) - 1) <= TOLERANCE
            for force in SAMPLE_LOADS)
    return meets(row, SAMPLE_LOADS, reported, reading) and (not gap or all(gaps))


def feasible_table(joint, single, names) -> str:
    """The combinations of the inputs within their published ranges that meet each criterion at 0.5 and 2 N
    (:data:`CRITERIA`): how many of the joint sample, the range of each input among them and their 0 V
    field-equivalent gaps, and which single inputs at a range's end (the others at the default scene's) do."""
    lines = []
    for reading in READINGS:
        for criterion in CRITERIA:
            found = [row for row in joint if meets_all(row, reading, criterion)]
            cells = [reading, criterion, f"{len(found)} of {len(joint)}"]
            for name in names:
                scale, _ = UNITS[name]
                values = [row[name] * scale for row in found]
                cells.append(f"{min(values):.3g} – {max(values):.3g}" if values else "–")
            cells.append(" / ".join(f"{min(row[f'd_field_0V_{force:g}N_um'] for row in found):.1f} – "
                                    f"{max(row[f'd_field_0V_{force:g}N_um'] for row in found):.1f}"
                                    for force in SAMPLE_LOADS) if found else "–")
            alone = [row["label"] for row in single[1:] if meets_all(row, reading, criterion)]
            cells.append(", ".join(f"`{label}`" for label in alone) if alone else "none")
            lines.append(cells)
    return table(["U read as", "meets", "joint sample", *(f"`{name}` [{UNITS[name][1]}]" for name in names),
                  "d_field at 0 V, 0.5 / 2 N [µm]", "one input alone at a range's end"], lines)


def implied_gap(central, force: float, reported: float, reading: str) -> float:
    """The field-equivalent gap [m] that the stand-in's F_el implies over A0: the uniform gap whose Eq. 21
    attraction at the reading's RMS voltage is F_el/A0."""
    area = central.array("apparent_area")[index(central.normal_forces, force), 0]
    sigma = stand_in(force, reported) * force / area
    return central.scene.screen.stack().gap_for_attraction(sigma, reported * READINGS[reading])


def field_gaps_table(numbers, central) -> str:
    """The field-equivalent gap that the stand-in implies over A0 at 100 and 200 V reported (both readings)
    against the bottom-up d_field at the voltages solved."""
    voltages = (0.0, 70.711, 100.0, 141.421, 200.0)
    rows = []
    for force in SIRIN_LOADS:
        i = index(central.normal_forces, force)
        implied = [f"{implied_gap(central, force, reported, reading) * 1e6:.2f}"
                   for reported in (100.0, 200.0) for reading in READINGS]
        solved = [f"{numbers['field_equivalent_gap'][i, index(central.voltages, voltage)] * 1e6:.2f}"
                  for voltage in voltages]
        rows.append([f"{force:g}", " / ".join(implied[:2]), " / ".join(implied[2:]),
                     f"{SEED.gap(force, 0.0) * 1e6:.2f}", *solved])
    return table(["F_N [N]", "stand-in, 100 V as RMS / amplitude [µm]", "stand-in, 200 V [µm]",
                  "seed's fit (Eq. 46) [µm]", *(f"bottom-up, {voltage:g} V [µm]" for voltage in voltages)], rows)


def extra_gap_table(central, gaps) -> str:
    """The missing physics on fixed equilibrium gaps: for the stand-in's F_el at 200 V reported (each reading),
    the uniform extra gap t that brings the field's F_el to it on the 0 V gap and on the gap solved at the
    reading's voltage (the self-consistent t lies between, where the equilibrium gap lies between them), the share
    of F_el on contact pixels, and the factor on the contact pixels' attraction that alone would bring it there
    on either gap (negative: not even none)."""
    rows = []
    for i, force in enumerate(gaps["forces"]):
        if force not in DRAFT_LOADS:
            continue
        for reading in READINGS:
            j = index(gaps["voltages"], reading_voltage(200.0, reading))
            target = stand_in(force, 200.0) * force / gaps["area"][i]            # [Pa]
            fields = np.nanmean(gaps["attraction"][i, j, :, 0], axis=-1)          # t = 0, both gap states
            shares = np.nanmean(gaps["contact_share"][i, j], axis=-1)
            needed = [extra_gap_needed(gaps, target, i, j, state) * 1e6 for state in (0, 1)]
            factors = [(target / fields[state] - 1 + shares[state]) / shares[state] for state in (0, 1)]
            rows.append([f"{force:g}", reading, f"{target * gaps['area'][i]:.2f}",
                         f"{fields[0] * gaps['area'][i]:.2f} / {fields[1] * gaps['area'][i]:.2f}",
                         f"{needed[0]:.2f} – {needed[1]:.2f}",
                         f"{100 * shares[0]:.0f} / {100 * shares[1]:.0f}", f"{factors[0]:.2f} / {factors[1]:.2f}"])
    return table(["F_N [N]", "200 V read as", "stand-in F_el [N]", "F_el on the 0 V / solved gap [N]",
                  "extra gap t [µm]", "on contact pixels [%]", "contact factor, 0 V / solved gap"], rows)


def summary_table(numbers, studies) -> str:
    """One line per anchor: what was measured and the bottom-up number under the stated conditions."""
    central, leak = studies["central"], studies["leak"]
    i1, i05, i2, i45 = (index(central.normal_forces, force) for force in (1.0, 0.5, 2.0, 4.5))
    v200, v141, vsine = (index(central.voltages, voltage) for voltage in (200.0, 141.421, GUO_SINE))
    measured_mu = MU0 * (1 + stand_in(1.0, 200.0))
    gap = numbers["field_equivalent_gap"]
    exponent = confidence_interval(exponent_samples(central, 100.0, 200.0)[i1])[0]
    b = index(central.voltages, 100.0)
    factor, _ = drive_factors(leak)
    low = factor[index(leak.normal_forces, 1.0), index(leak.voltages, 200.0), 0]
    plain, _ = drive_factors(studies["drive"])
    rows = [["Sirin et al. 2019a (stand-in: the seed's fit)", "μ at 1 N, 200 V", f"{measured_mu:.3f}",
             f"{mu(numbers['x'][i1, v200]):.3f} (RMS) / {mu(numbers['x'][i1, v141]):.3f} (amplitude)",
             f"{mu(numbers['x'][i1, v200]) / measured_mu:.2f} / {mu(numbers['x'][i1, v141]) / measured_mu:.2f}"],
            ["Guo et al. 2019", "gap at 150 V peak to peak, 0.5 → 4.5 N [µm]", "2.5 → 1.5",
             f"{gap[i05, vsine] * 1e6:.2f} → {gap[i45, vsine] * 1e6:.2f} (U_G = U_RMS)",
             f"{gap[i05, vsine] / 2.5e-6:.2f} → {gap[i45, vsine] / 1.5e-6:.2f}"],
            ["Sirin et al. 2019b", "area reduction at 1 N, 100 V [%]", f"{100 * SIRIN_2019B[(1.0, 100.0)]:.0f}",
             f"{100 * numbers['reduction'][i1, b]:.0f} (the seed's c₂ on the bottom-up A_R)",
             f"{numbers['reduction'][i1, b] / SIRIN_2019B[(1.0, 100.0)]:.1f}"],
            ["AliAbbasi et al.", "F_el(f)/F_el(100 kHz) below 250 Hz", "falls",
             f"{plain[index(studies['drive'].normal_forces, 1.0), 0, 0]:.3f} at DC without a leak; "
             f"{low:.2f} at {leak.frequencies[0]:g} Hz with σ_g", "–"],
            ["Meyer et al. 2013", "exponent of F_el in U", "2", f"{exponent:.2f} (1 N, 100–200 V)",
             f"{exponent / 2:.2f}"],
            ["Ayyildiz et al. 2018", "real contact against U", "grows",
             f"× {numbers['contact'][i05, v200] / numbers['contact'][i05, 0]:.1f} at 0.5 N, "
             f"× {numbers['contact'][i2, v200] / numbers['contact'][i2, 0]:.1f} at 2 N (0 → 200 V)", "–"]]
    return table(["anchor", "quantity", "measured", "bottom-up", "ratio"], rows)


def number_rows(central) -> list:
    """``numbers.csv``: the central study's numbers at every load and voltage."""
    numbers = central_numbers(central)
    rows = []
    for i, force in enumerate(central.normal_forces):
        for j, voltage in enumerate(central.voltages):
            row = {"normal_force_N": force, "voltage_V": voltage}
            for name in ("x", "x_low", "x_high", "x_total_low", "x_total_high"):
                row[name.replace("x", "fel_over_fn", 1)] = numbers[name][i, j]
            row["mu"] = mu(numbers["x"][i, j])
            row["stand_in_mu"] = MU0 * (1 + stand_in(force, voltage)) if force <= 2.3 else math.nan
            for name in ("field_equivalent_gap", "equivalent_gap"):
                for suffix in ("", "_low", "_high"):
                    row[f"{name}{suffix}_um"] = numbers[name + suffix][i, j] * 1e6
            for suffix in ("", "_low", "_high"):
                row[f"real_contact{suffix}"] = numbers["contact" + suffix][i, j]
            row["ridge_area_reduction"] = numbers["reduction"][i, j]
            rows.append(row)
    return rows


def all_tables(studies) -> dict:
    """Every table, by its name in the pages."""
    central = studies["central"]
    numbers = central_numbers(central)
    sample = sample_rows(central, studies["sample"])
    return {"summary": summary_table(numbers, studies), "sirin2019a": sirin_table(numbers, central),
            "budget": budget_table(numbers, studies), "guo2019": guo_table(numbers, central),
            "sirin2019b": sirin_b_table(numbers, central), "aliabbasi": aliabbasi_table(studies),
            "meyer2013": meyer_table(central, studies["inputs"]), "ayyildiz2018": ayyildiz_table(numbers, central),
            "readings": readings_table(numbers, studies), "inputs": tornado_table(numbers, studies),
            "feasible": feasible_table(sample, sample_rows(central, studies["inputs"]),
                                       studies["sample"].study.variation.names),
            "field_gaps": field_gaps_table(numbers, central), "extra_gap": extra_gap_table(central, studies["gaps"]),
            "breakdown": breakdown_table(numbers, studies)}


# ---------------------------------------------------------------------------------------------------------
# The figure and the pages
# ---------------------------------------------------------------------------------------------------------
def figure(studies, path, provenance):
    """μ against the reported voltage at 0.5, 1 and 2 N: the stand-in against the bottom-up μ read as RMS and as
    amplitude (bands: the total interval; dotted: the lowest and highest μ of the inputs one at a time)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.ticker import FormatStrFormatter

    central, inputs = studies["central"], studies["inputs"]
    numbers = central_numbers(central)
    _, force_factor, _ = draft_factors(inputs)
    fig, axes = plt.subplots(1, 3, figsize=(12, 4.2), sharey=True)
    reported = np.linspace(0, 200, 81)
    plain = [j for j, voltage in enumerate(central.voltages) if voltage not in (GUO_SINE, GUO_SQUARE)]
    for ax, force in zip(axes, DRAFT_LOADS):
        i, k = index(central.normal_forces, force), index(inputs.normal_forces, force)
        ax.plot(reported, MU0 * (1 + stand_in(force, reported)), "k-", lw=2,
                label="stand-in: the seed's fit to Sirin et al. 2019a")
        for (reading, scale), color in zip(READINGS.items(), ("C0", "C1")):
            voltages = central.voltages[plain]
            shown = voltages / scale <= 200 + 1e-6
            u = voltages[shown] / scale
            columns = np.array(plain)[shown]
            ax.fill_between(u, mu(numbers["x_total_low"][i, columns]), mu(numbers["x_total_high"][i, columns]),
                            color=color, alpha=0.35, lw=0)
            ax.plot(u, mu(numbers["x"][i, columns]), "o-", color=color, ms=3, label=f"bottom-up, U read as {reading}")
            drafted = [(voltage / scale, index(central.voltages, voltage), index(inputs.voltages, voltage))
                       for voltage in inputs.voltages if voltage > 0 and voltage / scale <= 200 + 1e-6]
            for pick in (np.nanmin, np.nanmax):
                ax.plot([0.0] + [u for u, _, _ in drafted],
                        [MU0] + [mu(numbers["x"][i, c] * pick(force_factor[:, k, d])) for _, c, d in drafted],
                        ":", color=color, lw=1)
        ax.set_yscale("log")
        ax.set_ylim(0.2, 5.0)
        for axis in (ax.yaxis.set_major_formatter, ax.yaxis.set_minor_formatter):
            axis(FormatStrFormatter("%g"))
        ax.set_title(f"F_N = {force:g} N")
        ax.set_xlabel("reported voltage U [V]")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("μ = F_T/F_N")
    axes[0].legend(loc="upper left", fontsize=8)
    fig.suptitle("Bottom-up μ0 (1 + F_el/F_N) against the measurement stand-in (bands: sampling, discretisation and "
                 "contact edges; dotted: each input at its range's ends)", fontsize=10)
    fig.tight_layout()
    save_figure(fig, path, provenance, colors=64)
    plt.close(fig)


#: a generated block of a page: <!-- begin NAME --> ... <!-- end NAME -->
BLOCK = re.compile(r"(<!-- begin (\w+) -->\n)(.*?)(<!-- end \2 -->)", re.DOTALL)


def page_blocks(text: str) -> list:
    """The names of the generated blocks of a page, in order."""
    return [match.group(2) for match in BLOCK.finditer(text)]


def fill_page(text: str, tables: dict) -> str:
    """The page ``text`` with each generated block replaced by the table of its name (KeyError for an unknown
    name)."""
    return BLOCK.sub(lambda match: match.group(1) + tables[match.group(2)] + "\n" + match.group(4), text)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                     formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    parser.add_argument("--output", default="validation-out", help="directory for the tables, CSV files and figure")
    parser.add_argument("--tasks", default=None, help="the studies' task directory (default: OUTPUT/tasks)")
    parser.add_argument("--workers", type=int, default=None,
                        help="worker processes of each study (1: this process; default 2, with --fast 1)")
    parser.add_argument("--fast", action="store_true", help="32² patches and two samples: a test run")
    parser.add_argument("--docs", action="store_true",
                        help="also write the tables into the two pages and the figure into docs/img")
    args, provenance = parse_arguments(parser, argv, "studies/validation_measurements.py")
    directory = output_directory(args.output)
    tasks = output_directory(args.tasks if args.tasks else directory / "tasks")
    studies = run_studies(args, tasks)
    tables = all_tables(studies)
    write_atomic(directory / "tables.md", "".join(f"## {name}\n\n{text}\n\n" for name, text in tables.items()))
    write_csv(directory / "numbers.csv", number_rows(studies["central"]), provenance)
    np.savez(directory / "gaps.npz", **{key: np.asarray(value) for key, value in studies["gaps"].items()})
    write_csv(directory / "sample.csv", sample_rows(studies["central"], studies["sample"]), provenance)
    figure(studies, directory / FIGURE, provenance)
    if args.docs:
        for page in PAGES.values():
            write_atomic(page, fill_page(page.read_text(encoding="utf-8"), tables))
        figure(studies, ROOT / "docs" / "img" / FIGURE, provenance)
    for name, text in tables.items():
        print(f"\n{name}\n{text}")


if __name__ == "__main__":
    main()
