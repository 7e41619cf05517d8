"""Small-load contact-area coefficient κ = (A/A0) / (p̄/(E* h'_rms)) of self-affine roughness: how it depends on
the resolution of the short cutoff λ_s/Δx, the spectral breadth λ_r/λ_s, the load and the seed (a script).

    python studies/contact_area_coefficient.py                 # the study of docs/findings/contact_area.md, into out/
    python studies/contact_area_coefficient.py --fast          # tiny grids, seconds

(from the repository root after ``pip install -e .``). H = 0.8, rms slope h' = 0.1
(spectral, i.e. the continuum value), periodic L × L window, λ_L = L, plateau between L and λ_r, hard-wall
contact solved by ``roughcontact.solve_contact`` (tol 1e-8) along the load path p̄/(E* h') = 0.0025 … 0.04.

Series (column ``series``): ``resolution`` — one physical surface (same seed, λ_r = L/4, λ_s = L/32 or L/64)
on grids that refine λ_s from 4 to 64 pixels (``self_affine`` with ``short_cutoff`` is refinement-consistent:
every grid realises the same Fourier modes); ``breadth`` — λ_s = 8 px, λ_r = L/4, λ_r/λ_s = 4 … 64 (the grid
grows with the breadth, so the number of roll-off cells (L/λ_r)² stays 16); ``ensemble`` — the two broad,
resolved 1024² cases (λ_s = 16 px, λ_r/λ_s = 16 and λ_s = 8 px, λ_r/λ_s = 32; λ_r = L/4) with 16 seeds, because
the seed-to-seed scatter of κ (16 roll-off cells) is larger than the resolution and breadth effects.

Two area estimators: ``pixels`` counts the pixels with p > 0; ``corrected`` subtracts the perimeter term of
Yastrebov, Anciaux & Molinari (2017, Tribol. Int. 114:161), A = N Δx² − (π − 1 + ln 2)/24 · M Δx², M the
number of contact/non-contact pixel edges. κ at p̄ → 0 is the intercept of a straight line fitted to κ(p̄) over
p̄ ≤ 0.01 E* h' for each seed. Outputs in ``--output``: ``contact_area_coefficient.csv`` (one row per case and
load), ``contact_area_summary.csv`` (seed mean ± std, extrapolated rows have load 0) and
``contact_area_coefficient.png``.
"""
from __future__ import annotations

import argparse
import math
import time
from dataclasses import asdict, dataclass

import numpy as np

import surfaces
from roughcontact import ElasticHalfSpace, load_path
from roughcontact.io import output_directory, parse_arguments, save_figure, write_csv
from roughcontact.reference.benchmark import contact_patches

LENGTH = 1e-3            # periodic square window L [m]
E_STAR = 1e6             # contact modulus [Pa] (κ depends only on p̄/(E* h'))
HURST, RMS_SLOPE = 0.8, 0.1
LOADS = (0.0025, 0.005, 0.01, 0.02, 0.04)       # p̄ / (E* h'_rms)
EXTRAPOLATION_MAX_LOAD = 0.01                   # κ(p̄) fitted linearly over p̄ ≤ this to get κ at p̄ → 0
BAND = (1.6, 2.3)                               # the band that κ of rigorous numerics falls in (docs/findings/contact_area.md)
TOL = 1e-8
SERIES = ("resolution", "breadth", "ensemble")
ENSEMBLE_SEEDS = 16                             # seeds of the two broad, resolved 1024² cases

COLUMNS = ("series", "n", "cutoff_pixels", "breadth", "rolloff_cells", "seed", "load", "contact_fraction",
           "kappa_pixels", "kappa_corrected", "kappa_pixels_fd_slope", "boundary_edges", "patches",
           "rms_slope_spectral", "rms_slope_fd", "iterations", "converged", "wall_time_s")
SUMMARY_COLUMNS = ("series", "n", "cutoff_pixels", "breadth", "load", "seeds", "kappa_pixels_mean",
                   "kappa_pixels_std", "kappa_corrected_mean", "kappa_corrected_std", "patches_min",
                   "rms_slope_fd_over_spectral")


@dataclass(frozen=True)
class Case:
    """One surface: ``n``² grid, λ_s = ``cutoff_pixels`` Δx, λ_r = ``breadth`` λ_s, random ``seed``."""

    series: str
    n: int
    cutoff_pixels: int
    breadth: int
    seed: int

    @property
    def short_cutoff(self) -> float:
        """λ_s [m]."""
        return self.cutoff_pixels * LENGTH / self.n

    @property
    def rolloff(self) -> float:
        """λ_r [m]."""
        return self.breadth * self.short_cutoff


def rough_surface(case: Case) -> surfaces.HeightField:
    """Self-affine surface of ``case`` (H = 0.8, spectral rms slope 0.1, λ_L = L) on a periodic grid."""
    grid = surfaces.Grid((case.n, case.n), (LENGTH, LENGTH), periodic=True)
    return surfaces.self_affine(grid, hurst=HURST, rms_slope=RMS_SLOPE, short_cutoff=case.short_cutoff,
                                rolloff=case.rolloff, rng=case.seed)


def solve_case(case: Case, loads=LOADS, tol=TOL) -> list:
    """Rows (dicts of ``COLUMNS``) of ``case`` along the load path p̄ = load · E* h' (warm-started)."""
    field = rough_surface(case)
    spectral = surfaces.rms_slope(field)
    finite_difference = surfaces.rms_slope(field, method="finite-difference")
    half = ElasticHalfSpace(field.grid, E_star=E_STAR)
    rows = []
    for load, result in zip(loads, load_path(field, half, [load * E_STAR * RMS_SLOPE for load in loads], tol=tol)):
        # the scale of κ is the continuum slope: the surface is normalised so that spectral == RMS_SLOPE
        kappa = result.contact_fraction / load
        rows.append({**asdict(case), "rolloff_cells": LENGTH / case.rolloff, "load": load,
                     "contact_fraction": result.contact_fraction, "kappa_pixels": kappa,
                     "kappa_corrected": result.corrected_contact_fraction / load,
                     "kappa_pixels_fd_slope": kappa * finite_difference / spectral,
                     "boundary_edges": result.perimeter_edges, "patches": contact_patches(result.contact),
                     "rms_slope_spectral": spectral, "rms_slope_fd": finite_difference,
                     "iterations": result.iterations, "converged": result.converged,
                     "wall_time_s": result.wall_time})
    return rows


def extrapolated(rows: list, max_load=EXTRAPOLATION_MAX_LOAD) -> dict:
    """Row with load 0: intercepts κ0 of straight lines κ(p̄) = κ0 + κ1 p̄ fitted over p̄ ≤ ``max_load``."""
    used = [row for row in rows if row["load"] <= max_load * (1 + 1e-12)]
    loads = np.array([row["load"] for row in used])
    result = dict(used[0], load=0.0, contact_fraction=0.0, patches=min(row["patches"] for row in used),
                  boundary_edges="", iterations="", wall_time_s="",
                  converged=all(row["converged"] for row in used))
    for key in ("kappa_pixels", "kappa_corrected", "kappa_pixels_fd_slope"):
        result[key] = float(np.polyfit(loads, [row[key] for row in used], 1)[1])
    return result


def study_plan(fast: bool, seeds: int, series=SERIES) -> list:
    """The cases of the chosen ``series``; ``fast``: tiny grids, two seeds everywhere."""
    if fast:
        plans = {"resolution": [(n, n // 8, 2) for n in (32, 64)],          # λ_s = L/8, λ_r = L/4: 4 → 8 px
                 "breadth": [(16 * b, 4, b) for b in (2, 4)],               # λ_r = L/4, λ_s = 4 px
                 "ensemble": [(64, 8, 2)]}
        seeds = ensemble_seeds = 2
    else:
        plans = {"resolution": [(n, n // 32, 8) for n in (128, 256, 512, 1024, 2048)]     # λ_s = L/32: 4 … 64 px
                 + [(n, n // 64, 16) for n in (256, 512, 1024, 2048)],                    # λ_s = L/64: 4 … 32 px
                 "breadth": [(32 * b, 8, b) for b in (4, 8, 16, 32, 64)],                 # λ_r = L/4, λ_s = 8 px
                 "ensemble": [(1024, 16, 16), (1024, 8, 32)]}                            # λ_r = L/4, many seeds
        ensemble_seeds = ENSEMBLE_SEEDS
    return [Case(name, n, pixels, b, seed) for name in series
            for seed in range(ensemble_seeds if name == "ensemble" else seeds) for n, pixels, b in plans[name]]


def run_study(cases: list, loads=LOADS, tol=TOL, progress=True) -> list:
    """Rows of every case plus, per case, the extrapolated row (load 0); identical surfaces solved once."""
    from tqdm import tqdm
    solved, rows = {}, []
    for case in tqdm(cases, desc="κ cases", unit="case", disable=not progress):
        key = (case.n, case.cutoff_pixels, case.breadth, case.seed)
        if key not in solved:
            solved[key] = solve_case(case, loads, tol)
        case_rows = [dict(row, series=case.series) for row in solved[key]]
        rows += case_rows + [extrapolated(case_rows)]
    return rows


def summarise(rows: list) -> list:
    """Seed mean and standard deviation (ddof 1; 0 for one seed) of κ per series, grid, cutoff, breadth, load."""
    groups = {}
    for row in rows:
        groups.setdefault((row["series"], row["n"], row["cutoff_pixels"], row["breadth"], row["load"]), []).append(row)
    summary = []
    for (series, n, pixels, breadth, load), group in groups.items():
        entry = {"series": series, "n": n, "cutoff_pixels": pixels, "breadth": breadth, "load": load,
                 "seeds": len(group), "patches_min": min(row["patches"] for row in group),
                 "rms_slope_fd_over_spectral": float(np.mean([row["rms_slope_fd"] / row["rms_slope_spectral"]
                                                              for row in group]))}
        for key in ("kappa_pixels", "kappa_corrected"):
            values = np.array([row[key] for row in group])
            entry[f"{key}_mean"] = float(values.mean())
            entry[f"{key}_std"] = float(values.std(ddof=1)) if values.size > 1 else 0.0
        summary.append(entry)
    return summary


def draw(summary: list, path, provenance, reference_load=EXTRAPOLATION_MAX_LOAD):
    """κ vs λ_s/Δx (resolution series, at ``reference_load`` and p̄ → 0), vs load and vs breadth; band shaded."""
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 3, figsize=(14.5, 4.3), constrained_layout=True)
    styles = {"kappa_pixels": ("pixel count", "o", "-"), "kappa_corrected": ("perimeter-corrected", "s", "--")}
    series = lambda name: [entry for entry in summary if entry["series"] == name]        # noqa: E731
    ax = axes[0]
    for breadth in sorted({entry["breadth"] for entry in series("resolution")}):
        for load, fill in ((reference_load, "full"), (0.0, "none")):
            chosen = sorted((entry for entry in series("resolution") if entry["breadth"] == breadth
                             and math.isclose(entry["load"], load)), key=lambda entry: entry["cutoff_pixels"])
            for key, (label, marker, line) in styles.items():
                ax.errorbar([entry["cutoff_pixels"] for entry in chosen], [entry[f"{key}_mean"] for entry in chosen],
                            [entry[f"{key}_std"] for entry in chosen], marker=marker, ls=line, fillstyle=fill,
                            capsize=2, label=f"λr/λs={breadth}, {label}, "
                                             + (f"p̄={load:g}" if load else "p̄→0"))
    ax.set_xscale("log", base=2)
    ax.set_xlabel("λ_s / Δx")
    ax.set_title("resolution series (fixed surface)")
    ax = axes[1]
    breadth_series = series("breadth")
    for breadth in sorted({entry["breadth"] for entry in breadth_series}):
        chosen = sorted((entry for entry in breadth_series if entry["breadth"] == breadth),
                        key=lambda entry: entry["load"])
        for key, (label, marker, line) in styles.items():
            ax.errorbar([entry["load"] for entry in chosen], [entry[f"{key}_mean"] for entry in chosen],
                        [entry[f"{key}_std"] for entry in chosen], marker=marker, ls=line, capsize=2,
                        label=f"λr/λs={breadth}, {label}")
    ax.set_xlabel("p̄ / (E* h'_rms)   (0: linear extrapolation)")
    ax.set_title(f"breadth series, λ_s = {breadth_series[0]['cutoff_pixels']} px" if breadth_series else "")
    ax = axes[2]
    for load, colour in ((0.0, "k"), (reference_load, "tab:blue"), (max(LOADS), "tab:red")):
        chosen = sorted((entry for entry in breadth_series if math.isclose(entry["load"], load)),
                        key=lambda entry: entry["breadth"])
        for key, (label, marker, line) in styles.items():
            ax.errorbar([entry["breadth"] for entry in chosen], [entry[f"{key}_mean"] for entry in chosen],
                        [entry[f"{key}_std"] for entry in chosen], marker=marker, ls=line, color=colour,
                        capsize=2, label=f"{label}, " + (f"p̄={load:g}" if load else "p̄→0"))
    ax.set_xscale("log", base=2)
    ax.set_xlabel("λ_r / λ_s")
    ax.set_title("breadth series")
    for ax in axes:
        ax.axhspan(*BAND, color="tab:green", alpha=0.12, label="band of rigorous numerics [1.6, 2.3]")
        ax.axhline(math.sqrt(8 / math.pi), color="gray", lw=0.8, ls=":")
        ax.axhline(math.sqrt(2 * math.pi), color="gray", lw=0.8, ls="-.")
        ax.set_ylabel("κ = (A/A0) / (p̄/(E* h'_rms))")
        ax.legend(fontsize=6)
    fig.suptitle("dotted: Persson √(8/π); dash-dot: Bush–Gibson–Thomas √(2π)", fontsize=9)
    save_figure(fig, path, provenance, dpi=90)
    plt.close(fig)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--fast", action="store_true", help="tiny grids (32²–64²), two seeds: a smoke run")
    parser.add_argument("--output", default="out", help="output directory (its parent must exist)")
    parser.add_argument("--seeds", type=int, default=4, help="seeds per case (full mode)")
    parser.add_argument("--tol", type=float, default=TOL, help="solver tolerance")
    parser.add_argument("--series", nargs="+", choices=SERIES, default=list(SERIES), help="series to run")
    args, provenance = parse_arguments(parser, argv, "python studies/contact_area_coefficient.py")
    output = output_directory(args.output)
    import matplotlib
    matplotlib.use("Agg")
    start = time.perf_counter()
    rows = run_study(study_plan(args.fast, args.seeds, args.series), tol=args.tol)
    summary = summarise(rows)
    write_csv(output / "contact_area_coefficient.csv", rows, provenance, COLUMNS)
    write_csv(output / "contact_area_summary.csv", summary, provenance, SUMMARY_COLUMNS)
    draw(summary, output / "contact_area_coefficient.png", provenance)
    print(f"{'series':10s} {'n':>5s} {'λs/Δx':>6s} {'λr/λs':>6s} {'p̄/E*h′':>8s} {'seeds':>5s} "
          f"{'κ pixels':>14s} {'κ corrected':>14s} {'patches':>7s} {'h′fd/h′':>8s}")
    for entry in summary:
        print(f"{entry['series']:10s} {entry['n']:5d} {entry['cutoff_pixels']:6d} {entry['breadth']:6d} "
              f"{entry['load']:8.4f} {entry['seeds']:5d} "
              f"{entry['kappa_pixels_mean']:7.3f}±{entry['kappa_pixels_std']:.3f} "
              f"{entry['kappa_corrected_mean']:7.3f}±{entry['kappa_corrected_std']:.3f} "
              f"{entry['patches_min']:7d} {entry['rms_slope_fd_over_spectral']:8.4f}")
    print(f"{time.perf_counter() - start:.0f} s; written to {output}/")
    return rows, summary


if __name__ == "__main__":
    main()
