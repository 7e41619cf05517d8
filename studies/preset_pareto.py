"""Speed against accuracy of the study's settings: errors of d_eq, A_R and F_T against the reference setting
versus CPU cost, the Pareto front, and the measured table behind the presets (``docs/guide/presets.md``).

    python studies/preset_pareto.py --output /tmp/pareto-out            # the table of docs/guide/presets.md
    python studies/preset_pareto.py --output /tmp/pareto-out --library   # also roughcontact/study/preset_errors.csv
    python studies/preset_pareto.py --fast --output out                 # 32² patches, seconds

Scenes: the default scene (the presets are chosen on it) and two variants that are not used to choose them,
``rough`` (roughness rms 5 µm, seed 1000) and ``smooth`` (rms 1 µm, seed 2000); each at F_N = 0.5, 2 N and
U = 0, 200 V (the ends of the default scene's ranges). Settings: ``GRIDS`` x ``TOLERANCES`` (one ridge
period; ``TOLERANCES_AT`` for some grids), two-period patches, float32, cold starts, two pixels per cut-off and
the coupled scales at the grids below, and the first 1 ... 8 realisations of each; the reference setting is
512² pixels, tolerance 1e-8, 8 realisations, float64, warm starts.

Error of a setting on a scene: the largest relative difference of its realisation mean from the reference
mean, over the four points for d_eq and A_R/A0 and over the two loads for F_T at 200 V (the seed's friction
law fed with the study's d_eq,R and A_R, ``roughcontact.study.bottom_up_friction``); ``error`` is the largest
of the three. Realisation r has the rng seed scene seed + r in every setting, so the first R realisations of a
setting share their roughness with the reference's: the error holds the discretisation error plus the
difference between the mean of R and of 8 realisations; the reference's own sampling half-width (95 %) is
written beside it (``reference_ci``).

Cost: CPU seconds (``time.process_time``, one FFT thread, JIT compiled and FFTW plans made before timing) of
the study of the four points, summed over the realisations in use. Each realisation is solved as its own
study (scene seed + r, one realisation: the same solves as inside the full study, whose realisations are
independent chains) and cached in ``--output``/runs/ as soon as it is done: re-running skips finished ones.
Writes ``preset_pareto.csv`` (one row per setting and scene), ``preset_pareto_settings.csv`` (one row per
setting: the cost and the error on each scene), ``preset_pareto.png`` (error vs cost, the front and the
presets marked) into ``--output``.
"""
from __future__ import annotations

import argparse
import dataclasses
import functools
import json
import os
import time
from pathlib import Path

os.environ.setdefault("ROUGHCONTACT_FFT_THREADS", "1")            # CPU seconds of one thread

import numpy as np

from roughcontact.io import output_directory, parse_arguments, save_figure, write_atomic, write_csv
from roughcontact.study.friction import bottom_up_friction
from roughcontact.study.patch import patch_body
from roughcontact.study.plan import plan_study
from roughcontact.study.presets import SETTING_KEYS, TABLE_PATH, write_table
from roughcontact.study.records import PointResult
from roughcontact.study.run import StudyResult, run_study
from roughcontact.study.scene import load_scene

NORMAL_FORCES = (0.5, 2.0)            # N
VOLTAGES = (0.0, 200.0)               # V
FRICTION_VOLTAGE = 200.0              # V
#: Scenes: the default (presets chosen on it) and two variants not used to choose them (TOML overrides).
VARIANTS = {"default": "",
            "rough": "[roughness]\nrms_height = 5e-06\n[study]\nseed = 1000\n",
            "smooth": "[roughness]\nrms_height = 1e-06\n[study]\nseed = 2000\n"}
TUNED = "default"
REFERENCE = {"grid": 512, "periods": 1, "tolerance": 1e-8, "dtype": "float64", "warm_start": True,
             "scales": "resolved", "pixels_per_cutoff": 4.0}
REALISATIONS = 8
GRIDS = (64, 128, 256, 512)
TOLERANCES = (1e-5, 1e-6, 1e-7, 1e-8)
TOLERANCES_AT = {256: (1e-5, 1e-6, 1e-7), 512: (1e-8,)}     # 512²: the reference only
PERIODS_GRIDS = (128, 256)            # two-period patches (the same pixel as 64² and 128² on one period)
PERIODS_TOLERANCES = (1e-7,)
PERIODS_REALISATIONS = 4
#: float32 solves and cold starts (each solve from the solver's own start) at these grids and tolerances.
FLOAT32 = ((128, 1e-5),)
COLD = ((128, 1e-6), (256, 1e-6))
#: Two pixels per short cut-off at the grids that raise it (64², 128²: the cut-off 14 and 7 µm instead of 28, 14).
COARSE_CUTOFF = ((64, 1e-6), (128, 1e-6))
#: The coupled scale path (roughcontact.study.coupled: an interface law per realisation and voltage), one realisation:
#: its laws cost about 100 resolved 128² studies, far off the front.
COUPLED = ((128, 1e-6, 1),)
#: --fast: 32² patches against a 48² reference, two realisations.
FAST = {"reference": {**REFERENCE, "grid": 48, "tolerance": 1e-7}, "grids": (32,), "tolerances": (1e-5, 1e-7),
        "realisations": 2}

COLUMNS = ("variant", *SETTING_KEYS, "realisations", "cpu_seconds", "wall_seconds", "solves", "converged",
           "d_eq_error", "ridge_area_error", "friction_error", "error", "reference_ci")


def scene_of(variant: str, setting: dict, realisation: int):
    """The variant's scene at ``setting``, one realisation (rng seed: the variant's seed + ``realisation``),
    the experiment's loads and voltages."""
    scene = load_scene(text=VARIANTS[variant] + "[loads]\nnormal_forces = [0.5, 2.0]\nvoltages = [0.0, 200.0]\n",
                       preset="standard")
    preset = dataclasses.replace(scene.preset, realisations=1, **setting)
    scene = scene.with_setting(preset)
    return dataclasses.replace(scene, study=dataclasses.replace(scene.study, seed=scene.study.seed + realisation))


def setting_name(setting: dict) -> str:
    return "_".join(f"{key}={setting[key]}" for key in SETTING_KEYS)


@functools.cache
def _warm_up(dtype: str) -> None:
    """Compile (or load from numba's cache) the solvers of ``dtype`` once per process, before any timing."""
    setting = {**REFERENCE, "grid": 32, "tolerance": 1e-5, "dtype": dtype}
    run_study(scene_of(TUNED, setting, 0), workers=1)


def solve_realisation(variant: str, setting: dict, realisation: int, runs: Path) -> dict:
    """The study of one realisation at ``setting``, from the cache in ``runs`` or solved and cached: points,
    CPU and wall seconds, solves. A cached study whose points have other fields (another version's) is solved
    again."""
    path = runs / variant / setting_name(setting) / f"r{realisation}.json"
    if path.exists():
        record = json.loads(path.read_text())
        if set(record["points"][0][0]) == {item.name for item in dataclasses.fields(PointResult)}:
            return record
    scene = scene_of(variant, setting, realisation)
    _warm_up(setting["dtype"])
    patch_body(scene)                                    # FFTW plans made (and cached as wisdom) before timing
    cpu, wall = time.process_time(), time.perf_counter()
    result = run_study(scene, workers=1)                 # in this process: its CPU seconds are the study's
    record = {"cpu_seconds": time.process_time() - cpu, "wall_seconds": time.perf_counter() - wall,
              "solves": result.solves, "short_cutoff": result.short_cutoff,
              "coarse_graining": list(result.coarse_graining),
              "points": [[dataclasses.asdict(point) for point in row] for row in result.points]}
    path.parent.mkdir(parents=True, exist_ok=True)
    write_atomic(path, json.dumps(record))
    return record


def merged(variant: str, setting: dict, records: list) -> StudyResult:
    """One study result from the per-realisation ``records`` (realisations in order)."""
    scene = scene_of(variant, setting, 0)
    scene = scene.with_setting(dataclasses.replace(scene.preset, realisations=len(records)))

    def point(i, j):
        parts = [PointResult(**{key: _tuples(value) for key, value in record["points"][i][j].items()})
                 for record in records]
        fields = {}
        for item in dataclasses.fields(PointResult):
            values = [getattr(part, item.name) for part in parts]
            if item.name == "ridge_area_fractions":
                fields[item.name] = tuple(sum((v[k] for v in values), ()) for k in range(len(values[0])))
            elif isinstance(values[0], tuple) and item.name != "nominal_pressures":
                fields[item.name] = sum(values, ())
            elif item.name == "seconds":
                fields[item.name] = sum(values)
            else:
                fields[item.name] = values[0]
        return PointResult(**fields)

    shape = (len(NORMAL_FORCES), len(VOLTAGES))
    points = tuple(tuple(point(i, j) for j in range(shape[1])) for i in range(shape[0]))
    # the plan's closing lengths and cut-off are the records' (they do not depend on the seed)
    return StudyResult(plan=plan_study(scene), points=points, computed=shape[0] * shape[1],
                       solves=sum(record["solves"] for record in records))


def _tuples(value):
    return tuple(_tuples(v) for v in value) if isinstance(value, list) else value


def quantities(result: StudyResult) -> dict:
    """d_eq and A_R/A0 (means over the converged realisations, loads x voltages) and F_T at 200 V (per load);
    NaN where no realisation of a point converged."""
    d_eq = result.summary("equivalent_gap")[0]
    friction = np.full(len(result.normal_forces), np.nan)
    if np.isfinite(d_eq).all():
        model = bottom_up_friction(result)
        friction = np.array([float(model.state(force, FRICTION_VOLTAGE).tangential_force)
                             for force in result.normal_forces])
    return {"d_eq": d_eq, "ridge_area": result.summary("ridge_area_fractions")[0][:, :, 0], "friction": friction}


def relative_error(values, reference) -> float:
    """max |values/reference − 1|; infinite where a value is missing (no converged realisation)."""
    differences = np.abs(np.asarray(values) / np.asarray(reference) - 1)
    return float(np.max(differences)) if np.isfinite(differences).all() else float("inf")


def settings_grid(args) -> list:
    """``(setting, maximum realisations)`` of the sweep, the reference first, cheap before expensive."""
    if args.fast:
        reference, grids, tolerances = FAST["reference"], FAST["grids"], FAST["tolerances"]
        count = FAST["realisations"]
        periods = []
    else:
        reference, grids, tolerances, count = REFERENCE, GRIDS, TOLERANCES, REALISATIONS
        periods = [({**REFERENCE, "grid": grid, "periods": 2, "tolerance": tol}, PERIODS_REALISATIONS)
                   for grid in PERIODS_GRIDS for tol in PERIODS_TOLERANCES]
        periods += [({**REFERENCE, "grid": grid, "tolerance": tol, "dtype": "float32"}, count)
                    for grid, tol in FLOAT32]
        periods += [({**REFERENCE, "grid": grid, "tolerance": tol, "warm_start": False}, count) for grid, tol in COLD]
        periods += [({**REFERENCE, "grid": grid, "tolerance": tol, "pixels_per_cutoff": 2.0}, count)
                    for grid, tol in COARSE_CUTOFF]
        periods += [({**REFERENCE, "grid": grid, "tolerance": tol, "scales": "coupled"}, used)
                    for grid, tol, used in COUPLED]
    settings = [({**reference, "grid": grid, "tolerance": tol}, count) for grid in grids
                for tol in TOLERANCES_AT.get(grid, tolerances)]
    settings = sorted([s for s in settings + periods if s[0] != reference],
                      key=lambda s: (s[0]["grid"], -s[0]["tolerance"]))
    return [(reference, count)] + settings


def rows_of(args, runs: Path) -> list:
    from tqdm import tqdm
    plan = settings_grid(args)
    reference = plan[0][0]
    jobs = [(variant, setting, r) for setting, count in plan for variant in VARIANTS for r in range(count)]
    records = {}
    for variant, setting, r in tqdm(jobs, desc="preset_pareto", unit="study"):
        records[(variant, setting_name(setting), r)] = solve_realisation(variant, setting, r, runs)
    rows = []
    for variant in VARIANTS:
        count = plan[0][1]
        ref_records = [records[(variant, setting_name(reference), r)] for r in range(count)]
        ref_result = merged(variant, reference, ref_records)
        ref = quantities(ref_result)
        mean, half = ref_result.summary("equivalent_gap")
        reference_ci = float(np.max(half / mean))
        for setting, count in plan:
            for used in range(1, count + 1):
                parts = [records[(variant, setting_name(setting), r)] for r in range(used)]
                result = merged(variant, setting, parts)
                values = quantities(result)
                errors = {"d_eq_error": relative_error(values["d_eq"], ref["d_eq"]),
                          "ridge_area_error": relative_error(values["ridge_area"], ref["ridge_area"]),
                          "friction_error": relative_error(values["friction"], ref["friction"])}
                rows.append({"variant": variant, **setting, "realisations": used,
                             "cpu_seconds": sum(p["cpu_seconds"] for p in parts),
                             "wall_seconds": sum(p["wall_seconds"] for p in parts), "solves": result.solves,
                             "converged": bool(result.array("converged").all()), **errors,
                             "error": max(errors.values()), "reference_ci": reference_ci})
    return rows


def setting_rows(rows: list) -> list:
    """One row per setting: the tuned scene's CPU seconds and the error on every scene (``error``: the
    largest)."""
    table = {}
    for row in rows:
        key = tuple(row[k] for k in (*SETTING_KEYS, "realisations"))
        entry = table.setdefault(key, {**{k: row[k] for k in (*SETTING_KEYS, "realisations")}})
        if row["variant"] == TUNED:
            entry["cpu_seconds"] = row["cpu_seconds"]
        entry[f"error_{row['variant']}"] = row["error"]
    for entry in table.values():
        entry["error"] = max(entry[f"error_{variant}"] for variant in VARIANTS)
    return sorted(table.values(), key=lambda entry: entry["cpu_seconds"])


def front(costs, errors) -> np.ndarray:
    """Indices of the Pareto front (no other point is both cheaper and more accurate), by increasing cost."""
    order = np.lexsort((errors, costs))
    best, chosen = np.inf, []
    for index in order:
        if errors[index] < best:
            best = errors[index]
            chosen.append(index)
    return np.array(chosen, dtype=int)


def preset_labels(entries: list) -> dict:
    """``{index in entries: preset name}`` of the default scene's presets found among the settings."""
    presets = load_scene().presets
    labels = {}
    for index, entry in enumerate(entries):
        for name, preset in presets.items():
            if all(getattr(preset, key) == entry[key] for key in (*SETTING_KEYS, "realisations")):
                labels[index] = name
    return labels


def _kind(entry: dict) -> str:
    if entry["scales"] == "coupled":
        return "coupled scales"
    if entry["dtype"] == "float32":
        return "float32"
    if not entry["warm_start"]:
        return "cold starts"
    if entry["pixels_per_cutoff"] == 2.0:
        return "2 px per cut-off"
    return "two periods" if entry["periods"] == 2 else "float64, warm"


MARKERS = {"float64, warm": "o", "float32": "s", "cold starts": "^", "two periods": "D", "2 px per cut-off": "v",
           "coupled scales": "P"}


def figure_of(entries: list, provenance, path: Path) -> Path:
    """Error against CPU cost on the tuned scene and the largest over all scenes (log-log; the reference,
    error 0 by definition, as a dotted line at its cost), the Pareto front and the presets marked."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    cost = np.array([entry["cpu_seconds"] for entry in entries])
    labels = preset_labels(entries)
    figure, axes = plt.subplots(1, 2, figsize=(11, 4.4), sharey=True)
    grids = sorted({entry["grid"] for entry in entries})
    for axis, key, title in ((axes[0], f"error_{TUNED}", "default scene (presets chosen on it)"),
                             (axes[1], "error", "largest over the default, rough and smooth scenes")):
        error = np.array([entry[key] for entry in entries])
        shown = (error > 0) & np.isfinite(error)
        for entry, x, y, visible in zip(entries, cost, error, shown):
            if visible:
                axis.scatter(x, 100 * y, s=14, alpha=0.6, marker=MARKERS[_kind(entry)],
                             color=f"C{grids.index(entry['grid'])}")
        on = front(cost[shown], error[shown])
        axis.step(cost[shown][on], 100 * error[shown][on], where="post", color="k", lw=1)
        axis.axvline(cost[error == 0].min(), color="k", ls=":", lw=1)
        for index, name in labels.items():
            if shown[index]:
                axis.scatter(cost[index], 100 * error[index], s=90, facecolors="none", edgecolors="r")
                axis.annotate(name, (cost[index], 100 * error[index]), xytext=(5, 5), textcoords="offset points",
                              color="r")
        axis.set(xscale="log", yscale="log", xlabel="CPU seconds (F_N 0.5, 2 N x U 0, 200 V; one FFT thread)",
                 title=title)
        axis.grid(alpha=0.3, which="both")
    handles = [plt.Line2D([], [], ls="", marker="o", color=f"C{i}", label=f"{grid}² px") for i, grid in enumerate(grids)]
    handles += [plt.Line2D([], [], ls="", marker=marker, color="grey", label=kind) for kind, marker in MARKERS.items()]
    handles += [plt.Line2D([], [], color="k", lw=1, label="Pareto front"),
                plt.Line2D([], [], color="k", ls=":", lw=1, label="reference (error 0)")]
    axes[1].legend(handles=handles, fontsize=7, loc="upper right")
    axes[0].set_ylabel("error vs reference [%]: max of d_eq, A_R, F_T(200 V)")
    figure.tight_layout()
    written = save_figure(figure, path, provenance, colors=64)
    plt.close(figure)
    return written


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--output", default="preset-pareto", help="output and cache directory")
    parser.add_argument("--fast", action="store_true", help="32² against 48², two realisations: a test that it runs")
    parser.add_argument("--library", action="store_true",
                        help=f"also write the per-setting table into the library ({TABLE_PATH.name})")
    args, provenance = parse_arguments(parser, argv, "studies/preset_pareto.py")
    output = output_directory(args.output)
    runs = output / "runs"
    runs.mkdir(exist_ok=True)
    rows = rows_of(args, runs)
    entries = setting_rows(rows)
    written = [write_csv(output / "preset_pareto.csv", rows, provenance, COLUMNS),
               write_csv(output / "preset_pareto_settings.csv", entries, provenance),
               figure_of(entries, provenance, output / "preset_pareto.png")]
    if args.library:
        written.append(write_table(entries, provenance))
    for path in written:
        print(f"wrote {path}")
    return rows


if __name__ == "__main__":
    main()
