"""How much a warm start saves in a load sweep, and why (a script; docs/solver.md, "Warm start").

    python experiments/warm_start.py                        # 512², tol 1e-4 … 1e-10, ≈ 1 min
    python experiments/warm_start.py --fast                 # 64², seconds (the CI smoke run)

On the benchmark surface of ``experiments/bench_contact.py`` (H = 0.8, rms slope 0.1, short cutoff 4 px)
with the 20 loads 0.0005 … 0.01 E* of its ``sweep`` section, writes to ``--output``:

* ``warm_start_sweep.csv``: for each tolerance, the cold sweeps (every step from scratch: ``cold`` from
  Polonsky–Keer's uniform start, ``nested`` from the default coarse-grid start) and the warm-started ones
  (``load_path`` with the ``previous`` and the ``secant`` predictor): time [s], iterations (on the n² grid),
  ratios cold / this;
* ``warm_start_steps.csv``: for the probed steps (``--probe``), the two cold and the two warm solves of that
  step alone (warm from the two steps before it): iterations, first residual (the relative rms gap error
  the solve starts from) and the decades it falls, i.e. what the warm start saved at the start and how
  fast each then converges;
* ``warm_start_residuals.png``: the residual histories of the last probed step.
"""
from __future__ import annotations

import argparse
import math
import os
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))    # the benchmark's surface and the output writers, shared
from _output import save_semilogy, write_csv  # noqa: E402
from bench_contact import E_STAR, PRESSURE, SWEEP_STEPS, rough_surface  # noqa: E402

from roughcontact import ElasticHalfSpace, load_path, solve_contact  # noqa: E402


STARTS = {"cold": {"warm_start": False, "cold_start": "pk"},           # Polonsky–Keer's uniform start
          "nested": {"warm_start": False},                               # the default cold start: coarse grids
          "previous": {"predictor": "previous"}, "secant": {"predictor": "secant"}}


def sweep_rows(surface, half, pressures, tols):
    """The sweep at each tolerance, cold (PK and nested start) and warm-started with each predictor; ratios to
    the PK-start cold sweep."""
    for tol in tols:
        cold_time = cold_iterations = None
        for start, options in STARTS.items():
            begin = time.perf_counter()
            iterations = sum(r.iterations for r in load_path(surface, half, pressures, tol=tol, **options))
            elapsed = time.perf_counter() - begin
            if cold_time is None:
                cold_time, cold_iterations = elapsed, iterations
            yield {"tol": tol, "start": start, "time_s": elapsed, "iterations": iterations,
                   "ratio": cold_time / elapsed, "iteration_ratio": cold_iterations / iterations}


def step_rows(surface, half, pressures, probes, tol):
    """Each probed step (1-based, ≥ 3) solved alone, cold and warm-started with each predictor from the two
    steps before it: the rows, and the residual histories of the last probe."""
    rows, histories = [], {}
    for step in probes:
        before, previous = (solve_contact(surface, half, mean_pressure=pressures[k], tol=tol)
                            for k in (step - 3, step - 2))
        for start, options in STARTS.items():
            resumed = {"start": [before, previous]} if options.get("warm_start", True) else {}
            result = next(load_path(surface, half, pressures[step - 1:step], tol=tol, **options, **resumed))
            residuals = histories[start] = result.residuals
            rows.append({"step": step, "load_step_percent": 100 * (pressures[step - 1] / pressures[step - 2] - 1),
                         "start": start, "iterations": result.iterations, "first_residual": residuals[0],
                         "decades": math.log10(residuals[0] / residuals[-1])})
    return rows, histories


def plot_residuals(path, histories, step):
    save_semilogy(path, {start: (np.arange(residuals.size), residuals) for start, residuals in histories.items()},
                  xlabel="CG step", ylabel="relative rms gap error", title=f"step {step} of the sweep", marker=".")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--size", type=int, default=512, help="grid size n (n²)")
    parser.add_argument("--tols", type=float, nargs="+", default=[1e-4, 1e-6, 1e-8, 1e-10],
                        help="tolerances of the sweeps")
    parser.add_argument("--probe", type=int, nargs="+", default=[3, 10, 20], help="steps solved alone (3…20)")
    parser.add_argument("--probe-tol", type=float, default=1e-8, help="tolerance of the probed steps")
    parser.add_argument("--output", default="out/warm_start", help="output directory")
    parser.add_argument("--fast", action="store_true", help="64², two tolerances: a smoke run")
    args = parser.parse_args(argv)
    if args.fast:
        args.size, args.tols = 64, [1e-6, 1e-8]
    if not all(3 <= step <= SWEEP_STEPS for step in args.probe):
        raise ValueError(f"--probe = {args.probe}: steps must lie in [3, {SWEEP_STEPS}]")
    os.makedirs(args.output, exist_ok=True)
    surface = rough_surface(args.size)
    half = ElasticHalfSpace(surface.grid, E_star=E_STAR)
    pressures = PRESSURE * np.arange(1, SWEEP_STEPS + 1) / SWEEP_STEPS
    # untimed: JIT-compile the kernels and plan the coarse grids, so the first sweep timed is not charged for it
    solve_contact(surface, half, mean_pressure=pressures[0], tol=1e-2, maxiter=5, warn=False)
    write_csv(Path(args.output) / "warm_start_sweep.csv", sweep_rows(surface, half, pressures, args.tols), echo=True)
    rows, histories = step_rows(surface, half, pressures, sorted(args.probe), args.probe_tol)
    write_csv(Path(args.output) / "warm_start_steps.csv", rows, echo=True)
    plot_residuals(Path(args.output) / "warm_start_residuals.png", histories, max(args.probe))


if __name__ == "__main__":
    main()
