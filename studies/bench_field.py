"""Cost of the layered field inside the contact solve against the per-pixel law on the same patch and tolerance.

    python studies/bench_field.py                      # 256² and 512², 30/100/200 V: the table of docs/guide/electrostatics.md
    python studies/bench_field.py --repeat 3 --output out
    python studies/bench_field.py --sizes 256 --realisations 4 --output out   # costs summed over realisations
    python studies/bench_field.py --fast               # 64², seconds

Two patches per grid size n: ``bench``, the electrostatic bar's rough patch (1 mm square, 3 µm rms self-affine
heights, H = 0.8, short cut-off 8 px, E* = 1 MPa, p̄ = 1 kPa), and ``scene``, the default scene's patch (one ridge
period with micro-roughness on the layered skin, at the apparent pressure of the first ring at 0.5 N). At each
voltage the per-pixel law (``field="parallel_plate"``) and the layered field are solved cold at the same
tolerance; the layered solve's CPU time (best of ``--repeat``; CPU, not wall time, so that the ratios hold on a
shared machine: run with one FFT thread) and FFT pairs (the elastic ones and the field solves' ones) are
printed as multiples of the per-pixel solve's. Writes ``bench_field.csv`` with its provenance into ``--output``,
with the steps, the steps across an instability and the field solves' FFT pairs and evaluations of each solve.
With ``--realisations R`` > 1 every case is solved on R patch realisations (bench: seeds 1 … R; scene: its
realisations 0 … R−1) and ``bench_field_totals.csv`` holds the FFT pairs and CPU summed over them, as ratios to
the per-pixel law's sums: near instabilities one solve's cost moves by a factor 2 with its path.
"""
from __future__ import annotations

import argparse
import time

from surfaces import Grid, self_affine
from roughcontact import ElasticHalfSpace, ElectrostaticInteraction, solve_contact
from roughcontact.electrostatics import DielectricStack
from roughcontact.io import best_of, count_argument, output_directory, parse_arguments, summed_ratios, write_csv
from roughcontact.study.patch import default_scene_patch

COLUMNS = ("patch", "n", "realisation", "voltage_V", "field", "time_s", "time_ratio", "iterations", "unstable_steps", "fft_pairs",
           "field_fft_pairs", "field_evaluations", "fft_pair_ratio", "contact_fraction", "electrostatic_force_N",
           "field_equivalent_gap_m", "equivalent_gap_m", "converged")


def bench_patch(n, realisation=0):
    """The electrostatic bar's rough patch (seed 1 + ``realisation``) and its body, with its load p̄ [Pa]."""
    grid = Grid((n, n), (1e-3, 1e-3), periodic=True)
    surface = self_affine(grid, hurst=0.8, rms_height=3e-6, short_cutoff=8e-3 / n, rng=1 + realisation)
    return surface, ElasticHalfSpace(grid, E_star=1e6, planner_effort="FFTW_MEASURE"), 1e3, DielectricStack()


def scene_patch(n, realisation=0):
    """The default scene's patch on n² pixels, its skin body and the first ring's apparent pressure at 0.5 N."""
    patch = default_scene_patch(n, 0.5, realisation)
    return patch.surface, patch.body, patch.pressure, patch.stack



def rows_for(name, n, args, realisation=0):
    surface, body, pressure, stack = {"bench": bench_patch, "scene": scene_patch}[name](n, realisation)
    rows = []
    for voltage in args.voltages:
        reference = None
        for field in ("parallel_plate", "layered"):
            law = ElectrostaticInteraction(stack, voltage, field=field)
            solve_contact(surface, body, mean_pressure=pressure, tol=args.tol, interaction=law, warn=False)  # warm
            result, seconds = best_of(lambda: solve_contact(surface, body, mean_pressure=pressure, tol=args.tol,
                                                            interaction=law, warn=False),
                                      args.repeat, clock=time.process_time)
            reference = reference or (seconds, result.params["fft_pairs"])
            rows.append(dict(patch=name, n=n, realisation=realisation, voltage_V=voltage, field=field, time_s=seconds,
                             time_ratio=seconds / reference[0], iterations=result.iterations,
                             unstable_steps=result.unstable_steps,
                             field_fft_pairs=result.solver.details.get("field_fft_pairs", 0),
                             field_evaluations=result.solver.details.get("field_evaluations", 0),
                             fft_pairs=result.params["fft_pairs"],
                             fft_pair_ratio=result.params["fft_pairs"] / reference[1],
                             contact_fraction=result.contact_fraction,
                             electrostatic_force_N=result.electrostatic_force,
                             field_equivalent_gap_m=result.field_equivalent_gap,
                             equivalent_gap_m=result.equivalent_gap, converged=result.converged))
            print(f"{name:5s} {n:4d}² r{realisation} {voltage:5.0f} V {field:14s} {seconds:8.3f} s  x{rows[-1]['time_ratio']:.2f}  "
                  f"{result.params['fft_pairs']:7.1f} FFT pairs  x{rows[-1]['fft_pair_ratio']:.2f}  "
                  f"A/A0 {result.contact_fraction:.4f}", flush=True)
    return rows



def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                     formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    parser.add_argument("--sizes", type=int, nargs="+", default=[256, 512], help="grid sizes n (n² pixels)")
    parser.add_argument("--voltages", type=float, nargs="+", default=[30.0, 100.0, 200.0], help="voltages U [V]")
    parser.add_argument("--patches", nargs="+", choices=("bench", "scene"), default=["bench", "scene"])
    parser.add_argument("--tol", type=float, default=1e-8, help="relative tolerance of both solves")
    parser.add_argument("--repeat", type=count_argument, default=1, help="timings per solve; the best is kept")
    parser.add_argument("--realisations", type=count_argument, default=1,
                        help="patch realisations 0 … R−1; with R > 1 also the ratios of the sums over them")
    parser.add_argument("--fast", action="store_true", help="64² and one voltage: a test that the script runs")
    parser.add_argument("--output", default="out", help="directory for bench_field.csv")
    args, provenance = parse_arguments(parser, argv, "studies/bench_field.py")
    if args.fast:
        args.sizes, args.voltages = [64], [30.0]
    directory = output_directory(args.output)
    rows = [row for n in args.sizes for name in args.patches for realisation in range(args.realisations)
            for row in rows_for(name, n, args, realisation)]
    write_csv(directory / "bench_field.csv", rows, provenance, COLUMNS)
    if args.realisations > 1:
        # near instabilities one solve's cost moves by a factor 2 with its path: the sums average it
        totals = summed_ratios(rows, ("patch", "n", "voltage_V", "field"), lambda key: key[:3] + ("parallel_plate",))
        write_csv(directory / "bench_field_totals.csv", totals, provenance)
        for row in totals:
            print(f"{row['patch']:5s} {row['n']:4d}² {row['voltage_V']:5.0f} V {row['field']:14s} over {row['count']} "
                  f"realisations: FFT pairs x{row['fft_pairs_ratio']:.2f}  CPU x{row['time_s_ratio']:.2f}")


if __name__ == "__main__":
    main()
