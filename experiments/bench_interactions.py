"""Cost of electroadhesive contact against the hard wall, and of a voltage continuation against cold solves.

    python experiments/bench_interactions.py                     # 256² and 512², the table of docs/interactions.md
    python experiments/bench_interactions.py --sizes 1024 --output out
    python experiments/bench_interactions.py --fast              # 64², seconds

The scene is the electrostatic bar's rough patch: 1 mm square, 3 µm rms self-affine heights (H = 0.8, short
cut-off 8 px), contact modulus E* (``--E-star``, default 1 MPa), external load p̄ (``--pressure``, default
1 kPa), the seed's dielectric stack (Table 1). For each grid: the hard-wall solve (Polonsky–Keer) and the
electrostatic solves at each voltage, cold, their time and FFT pairs as multiples of the hard wall's; then the
voltage sweep 0 → max solved cold at every step and as a continuation (each solve starts from the last
gap). Writes ``bench_interactions.csv`` with its provenance into ``--output``.
"""
from __future__ import annotations

import argparse
import time

import numpy as np

from surfaces import Grid, self_affine
from roughcontact import ElasticHalfSpace, ElectrostaticInteraction, solve_contact
from roughcontact.electrostatics import DielectricStack
from roughcontact.provenance import output_directory, parse_arguments, write_csv

COLUMNS = ("section", "n", "voltage_V", "time_s", "time_ratio", "iterations", "fft_pairs", "fft_pair_ratio",
           "contact_fraction", "equivalent_gap_m", "converged")


def patch(n, E_star):
    grid = Grid((n, n), (1e-3, 1e-3), periodic=True)
    surface = self_affine(grid, hurst=0.8, rms_height=3e-6, short_cutoff=8e-3 / n, rng=1)
    return surface, ElasticHalfSpace(grid, E_star=E_star, planner_effort="FFTW_MEASURE")


def timed(solve):
    start = time.perf_counter()
    result = solve()
    return result, time.perf_counter() - start


def rows_for(n, args):
    surface, half = patch(n, args.E_star)
    stack = DielectricStack()
    solve_contact(surface, half, mean_pressure=args.pressure, tol=args.tol)              # JIT and plans warm
    hard, hard_time = timed(lambda: solve_contact(surface, half, mean_pressure=args.pressure, tol=args.tol))
    rows = [dict(section="hard_wall", n=n, voltage_V=0.0, time_s=hard_time, time_ratio=1.0,
                 iterations=hard.iterations, fft_pairs=hard.params["fft_pairs"], fft_pair_ratio=1.0,
                 contact_fraction=hard.contact_fraction, equivalent_gap_m=stack.equivalent_gap(hard.gap),
                 converged=hard.converged)]
    sweeps = {"cold": 0.0, "continuation": 0.0}
    previous = None
    for voltage in args.voltages:
        law = ElectrostaticInteraction(stack, voltage)
        for kind in ("cold", "continuation"):
            x0 = previous if kind == "continuation" and previous is not None and voltage > 0 else None
            res, seconds = timed(lambda: solve_contact(surface, half, mean_pressure=args.pressure, tol=args.tol,
                                                       interaction=law, x0=x0, warn=False))
            sweeps[kind] += seconds
            rows.append(dict(section=f"electrostatic_{kind}", n=n, voltage_V=voltage, time_s=seconds,
                             time_ratio=seconds / hard_time, iterations=res.iterations,
                             fft_pairs=res.params["fft_pairs"], fft_pair_ratio=res.params["fft_pairs"] /
                             hard.params["fft_pairs"], contact_fraction=res.contact_fraction,
                             equivalent_gap_m=res.equivalent_gap, converged=res.converged))
        previous = res
    rows.append(dict(section="sweep", n=n, voltage_V=max(args.voltages), time_s=sweeps["continuation"],
                     time_ratio=sweeps["cold"] / sweeps["continuation"]))
    return rows


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                     formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    parser.add_argument("--sizes", type=int, nargs="+", default=[256, 512], help="grid sizes n (n² pixels)")
    parser.add_argument("--voltages", type=float, nargs="+", default=[1e-6, 3.0, 10.0, 30.0, 100.0, 200.0],
                        help="voltages U [V], solved in this order")
    parser.add_argument("--E-star", type=float, default=1e6, help="contact modulus E* [Pa]")
    parser.add_argument("--pressure", type=float, default=1e3, help="external load p̄ [Pa]")
    parser.add_argument("--tol", type=float, default=1e-8, help="relative tolerance of both solvers")
    parser.add_argument("--fast", action="store_true", help="64² and two voltages: a test that the script runs")
    parser.add_argument("--output", default="out", help="directory for bench_interactions.csv")
    args, provenance = parse_arguments(parser, argv, "experiments/bench_interactions.py")
    if args.fast:
        args.sizes, args.voltages = [64], [10.0, 30.0]
    rows = [row for n in args.sizes for row in rows_for(n, args)]
    path = write_csv(output_directory(args.output) / "bench_interactions.csv", rows, provenance, COLUMNS)
    for row in rows:
        print("  ".join(f"{key}={value:.4g}" if isinstance(value, float) else f"{key}={value}"
                        for key, value in row.items()))
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
