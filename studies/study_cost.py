"""What a study's task costs per patch size: the calibration of ``roughcontact.study.cost``.

For the default scene's patch (ridges and micro-roughness, one ridge period) on n² pixels, one task per voltage
(the loads in order, each solve warm-started from the last, as ``roughcontact.study.resolved.solve_chain`` runs
them) is solved, and for each solve are recorded: its FFT pairs (``SolverReport.fft_pairs``: the contact
solver's and the field's; deterministic), its CPU seconds, and the CPU seconds of one application of the skin's
Green operator on the same grid (``ElasticHalfSpace.displacement_into``: one FFT pair and the multiplier, best
of three runs of 20), so that seconds per solve / (pairs per solve x seconds per pair) is the cost of a pair
inside a solve over a bare one. The task's peak traced memory (``tracemalloc``) is given in float64 arrays of
the patch (8 n² bytes). ``docs/dev/benchmarks.md`` ("The study's cost") holds the table.

    python studies/study_cost.py --sizes 64 128 256 512            # four loads, 0.5-2 N, 0 / 100 / 200 V
    python studies/study_cost.py --sizes 256 512 --loads 0.5 2.0   # two loads, one step of 4x
    python studies/study_cost.py --sizes 128 256 --free            # the patch as a free measured window
    python studies/study_cost.py --fast                            # 32², the test's case: seconds

One FFT thread (``ROUGHCONTACT_FFT_THREADS=1``, as a pool worker runs); CPU seconds, so that a shared machine's
load does not enter. Writes ``study_cost.csv`` (one row per size and voltage, with its provenance) into
``--output`` and prints it.
"""
import argparse
import os
import tempfile
import time
import tracemalloc
from pathlib import Path

import numpy as np

os.environ.setdefault("ROUGHCONTACT_FFT_THREADS", "1")

from surfaces import Grid, HeightField  # noqa: E402  (after the thread setting)
from roughcontact.io import output_directory, parse_arguments, write_csv  # noqa: E402
from roughcontact.solvers import solve_contact  # noqa: E402
from roughcontact.study.apparent import apparent_scale  # noqa: E402
from roughcontact.study.cost import operator_applications  # noqa: E402
from roughcontact.study.plan import plan_study  # noqa: E402
from roughcontact.study.scene import load_scene  # noqa: E402

COLUMNS = ("n", "boundary", "loads", "voltage_V", "pairs_mean", "pairs_max", "cpu_seconds_per_solve",
           "pair_seconds", "ratio", "applications", "model_applications", "peak_patch_arrays")


def pair_seconds(body, repeat=20) -> float:
    """CPU seconds of one Green-operator application (an FFT pair and the multiplier) on ``body``'s grid."""
    pressure, out = body.empty(), body.empty()
    pressure[...] = np.random.default_rng(0).random(pressure.shape)
    body.displacement_into(pressure, out)
    best = np.inf
    for _ in range(3):
        start = time.process_time()
        for _ in range(repeat):
            body.displacement_into(pressure, out)
        best = min(best, (time.process_time() - start) / repeat)
    return best


def task_cost(plan, voltage_index) -> dict:
    """The FFT pairs and CPU seconds of each solve of one task, its peak traced memory [bytes], a pair's seconds."""
    scene = plan.scene
    law = scene.screen.interaction(plan.voltages[voltage_index])
    heights, body = plan.surface(0), plan.body(1)
    pairs, seconds, latest = [], [], None
    tracemalloc.start()
    for _, (pressure, *_) in apparent_scale(scene):
        start = time.process_time()
        latest = solve_contact(heights, body, mean_pressure=pressure, interaction=law, tol=scene.preset.tolerance,
                               x0=latest, warn=False)
        seconds.append(time.process_time() - start)
        pairs.append(latest.solver.fft_pairs)
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    return {"pairs": pairs, "seconds": seconds, "peak": peak, "pair": pair_seconds(body),
            "transform": int(np.prod(body.transform_shape))}


def study_plan(n, args, scans):
    """The plan of the default scene's patch on n² pixels (as a free measured window with ``args.free``)."""
    text = (f"[loads]\nvoltages = [{', '.join(repr(v) for v in args.voltages)}]\n"
            f"normal_forces = [{', '.join(repr(f) for f in args.loads)}]\n[presets.standard]\ngrid = {n}\n"
            f"tolerance = {args.tolerance!r}\npixels_per_cutoff = 2.0\n")
    plan = plan_study(load_scene(text=text, preset="standard"))
    if not args.free:
        return plan
    scan = Path(scans) / f"patch{n}.npz"                           # the same heights as a measured free window
    HeightField(Grid(plan.grid.shape, plan.grid.lengths, periodic=False), plan.surface(0)).save(scan)
    return plan_study(load_scene(text=text + f'[ridges]\nenabled = false\n[roughness]\ntopography = "{scan}"\n'
                                 'boundary = "free"\ndetrend = "mean"\n', preset="standard"))


def rows(args, scans) -> list:
    warm = study_plan(32, args, scans)
    for j in range(len(warm.voltages)):                         # the numba kernels compiled or loaded, not timed
        task_cost(warm, j)
    table = []
    for n in args.sizes:
        plan = study_plan(n, args, scans)
        for j, voltage in enumerate(plan.voltages):
            cost = task_cost(plan, j)
            pairs, per_solve = np.mean(cost["pairs"]), np.mean(cost["seconds"])
            table.append({"n": n, "boundary": "free" if args.free else "periodic", "loads": len(args.loads),
                          "voltage_V": voltage, "pairs_mean": pairs, "pairs_max": max(cost["pairs"]),
                          "cpu_seconds_per_solve": per_solve, "pair_seconds": cost["pair"],
                          "ratio": per_solve / (pairs * cost["pair"]), "applications": per_solve / cost["pair"],
                          "model_applications": operator_applications(cost["transform"], voltage),
                          "peak_patch_arrays": cost["peak"] / (8 * n * n)})
            print(", ".join(f"{key} {value:.4g}" if isinstance(value, float) else f"{key} {value}"
                            for key, value in table[-1].items()), flush=True)
    return table


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                     formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    parser.add_argument("--sizes", type=int, nargs="+", default=[64, 128, 256], help="pixels per patch side")
    parser.add_argument("--voltages", type=float, nargs="+", default=[0.0, 100.0, 200.0], help="voltages [V]")
    parser.add_argument("--loads", type=float, nargs="+", default=[0.5, 1.0, 1.5, 2.0], help="normal forces [N]")
    parser.add_argument("--tolerance", type=float, default=1e-6, help="solver tolerance")
    parser.add_argument("--free", action="store_true", help="solve each patch as a measured free window")
    parser.add_argument("--fast", action="store_true", help="32² patches, 0 and 100 V, two loads (the test's case)")
    parser.add_argument("--output", default="out", help="directory for study_cost.csv")
    args, provenance = parse_arguments(parser, argv, "studies/study_cost.py")
    if args.fast:
        args.sizes, args.voltages, args.loads = [32], [0.0, 100.0], [0.5, 2.0]
    with tempfile.TemporaryDirectory() as scans:
        table = rows(args, scans)
    return write_csv(output_directory(args.output) / "study_cost.csv", table, provenance, COLUMNS)


if __name__ == "__main__":
    main()
