"""Does the contact solver converge wherever a study may take it? (docs/dev/benchmarks.md, the hard-wall solver)

    python studies/solver_robustness.py                       # 256², 512²; 4 seeds; 20 loads; minutes
    python studies/solver_robustness.py --sizes 1024 --seeds 2
    python studies/solver_robustness.py --fast                # 128², 1 seed, 4 loads (the CI smoke run)

On seeded self-affine surfaces like the benchmark's (``roughcontact.reference.benchmark.rough_surface``: H = 0.8, rms
slope 0.1, short cutoff 4 px; seeds 0 … ``--seeds`` − 1) every load p̄ = 0.0005 … 0.01 E* is solved by each variant:

* ``nested`` — the defaults (periodic, preconditioned, nested cold start, float64): the reference;
* ``pk`` — Polonsky–Keer's uniform start; ``plain`` — the same without the preconditioner;
* ``warm`` — the loads in order through ``load_path`` (secant warm starts);
* ``float32`` — single precision, at tol max(``--tol``, 1e-5) (float32 resolves gaps to ~1e-7 of the heights);
* ``displacement`` — displacement control at the reference's penetration (must give back p̄);
* ``free`` — the same heights on a free (non-periodic) surface: other physics, convergence only.

Writes, into ``--output``, ``solver_robustness.csv`` (one row per solve: iterations, converged, the step from
which the stall fallback restarted on every entry, contact fraction, mean gap, mean pressure and their relative
differences to the reference solve of the same surface and load) and prints a summary per variant (solves, not
converged, fallbacks, median and largest iterations, largest differences), also in
``solver_robustness_summary.csv``; both with their provenance.
"""
from __future__ import annotations

import argparse

import numpy as np
from tqdm import tqdm

from roughcontact import ElasticHalfSpace, load_path, solve_contact
from roughcontact.io import output_directory, parse_arguments, write_csv
from roughcontact.reference.benchmark import E_STAR, PRESSURE, SWEEP_STEPS, rough_surface, sweep_pressures

FLOAT32_TOL = 1e-5
VARIANTS = ("nested", "pk", "plain", "warm", "float32", "displacement", "free")
START_OPTIONS = {"pk": {"cold_start": "pk"}, "plain": {"cold_start": "pk", "preconditioned": False}}
COMPARED = {"contact_fraction": "rel_diff_contact_fraction", "mean_gap": "rel_diff_mean_gap",
            "mean_pressure": "rel_diff_mean_pressure"}


def variant_results(variant, surface, seed, pressures, tol, maxiter, reference):
    """The results of ``variant`` at each of ``pressures`` on ``surface`` (seed ``seed``; ``reference``: the
    nested solves, whose penetrations the displacement-controlled variant imposes)."""
    if variant == "free":
        surface = rough_surface(surface.grid.shape[0], seed, periodic=False)
    half = ElasticHalfSpace(surface.grid, E_star=E_STAR, dtype=np.float32 if variant == "float32" else np.float64)
    options = {"tol": max(tol, FLOAT32_TOL) if variant == "float32" else tol, "maxiter": maxiter, "warn": False}
    if variant == "warm":
        return list(load_path(surface, half, pressures, **options))
    if variant == "displacement":
        return [solve_contact(surface, half, penetration=r.penetration, **options) for r in reference]
    options.update(START_OPTIONS.get(variant, {}))
    return [solve_contact(surface, half, mean_pressure=p, **options) for p in pressures]


def rows(sizes, seeds, pressures, tol, maxiter):
    """One row per solve, for every size, seed, variant and load (a progress bar over the variants' sweeps);
    the first variant, ``nested``, is the reference of the differences."""
    jobs = [(n, seed, variant) for n in sizes for seed in range(seeds) for variant in VARIANTS]
    for n, seed, variant in tqdm(jobs, desc="robustness", unit="sweep"):
        if variant == VARIANTS[0]:
            surface, reference = rough_surface(n, seed), None
        results = variant_results(variant, surface, seed, pressures, tol, maxiter, reference)
        reference = reference or results
        for load, result, ref in zip(pressures, results, reference):
            row = {"n": n, "seed": seed, "variant": variant, "load_E_star": load / E_STAR,
                   "iterations": result.iterations, "converged": result.converged,
                   "restart_every_entry_from": result.solver.details["restart_every_entry_from"],
                   "contact_fraction": result.contact_fraction, "mean_gap": result.mean_gap,
                   "mean_pressure": result.mean_pressure, "time_s": result.wall_time}
            for quantity, column in COMPARED.items():
                row[column] = "" if variant == "free" else abs(row[quantity] / getattr(ref, quantity) - 1)
            yield row


def summary(all_rows):
    """Per variant: solves, not converged, stall fallbacks, median and largest iterations, largest differences."""
    for variant in dict.fromkeys(row["variant"] for row in all_rows):
        mine = [row for row in all_rows if row["variant"] == variant]
        iterations = [row["iterations"] for row in mine]
        line = {"variant": variant, "solves": len(mine), "not_converged": sum(not row["converged"] for row in mine),
                "fallbacks": sum(row["restart_every_entry_from"] is not None for row in mine),
                "median_iterations": float(np.median(iterations)), "max_iterations": max(iterations)}
        for column in COMPARED.values():
            values = [row[column] for row in mine if row[column] != ""]
            line[f"max_{column}"] = max(values) if values else ""
        yield line


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--sizes", type=int, nargs="+", default=[256, 512], help="grid sizes n (n²)")
    parser.add_argument("--seeds", type=int, default=4, help="surfaces per size (seeds 0 … seeds − 1)")
    parser.add_argument("--loads", type=int, default=SWEEP_STEPS, help="loads 0.01 E* k/loads, k = 1 … loads")
    parser.add_argument("--tol", type=float, default=1e-8, help="solver tolerance (float32: at least 1e-5)")
    parser.add_argument("--maxiter", type=int, default=2000, help="iteration cap of every solve")
    parser.add_argument("--output", default="out", help="output directory (its parent must exist)")
    parser.add_argument("--fast", action="store_true", help="128², one seed, four loads: a smoke run")
    args, provenance = parse_arguments(parser, argv, "python studies/solver_robustness.py")
    output = output_directory(args.output)
    if args.fast:
        args.sizes, args.seeds, args.loads = [128], 1, 4
    pressures = sweep_pressures(PRESSURE, args.loads)
    all_rows = list(rows(args.sizes, args.seeds, pressures, args.tol, args.maxiter))
    write_csv(output / "solver_robustness.csv", all_rows, provenance)
    write_csv(output / "solver_robustness_summary.csv", summary(all_rows), provenance, echo=True)


if __name__ == "__main__":
    main()
