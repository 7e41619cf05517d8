"""Cost of the fingerpad study with the layered field against the per-pixel law (``[screen] field``).

    python studies/bench_study_field.py                      # the standard study, both fields back to back
    python studies/bench_study_field.py --preset draft       # quicker
    python studies/bench_study_field.py --fast               # 32² patches, two loads, 0 and 150 V: seconds

Runs the study of the default scene (or ``--scene``) at ``--preset`` in this process (one worker, so process
CPU time is the study's), once with ``field = "parallel_plate"`` and once with ``field = "layered"``,
alternating ``--repeat`` times, after one point of each (the first load at the last voltage) that compiles
the kernels, plans the FFTs and builds the bodies, untimed. For each run: wall time, CPU time, contact solves,
and the solver work in FFT pairs (each contact solve's ``solver.fft_pairs``, the layered field's CG passes
included, plus the field solves of the 0 V points' small-voltage limit), and the layered/per-pixel ratios. FFT
pairs do not depend on the machine's other load; wall and CPU times do (run on an idle machine for the docs' timing).
Writes ``bench_study_field.csv`` with its provenance into ``--output``.
"""
from __future__ import annotations

import argparse
import dataclasses
import time

import roughcontact.study.records as records
import roughcontact.study.resolved as resolved
from roughcontact.io import output_directory, parse_arguments, write_csv
from roughcontact.study.run import run_study
from roughcontact.study.scene import load_scene

COLUMNS = ("field", "repeat", "wall_s", "cpu_s", "solves", "fft_pairs", "wall_ratio", "cpu_ratio", "fft_pair_ratio")
FAST = """\
[loads]
normal_forces = [0.5, 2.0]
voltages = [0.0, 150.0]
[presets.draft]
grid = 32
realisations = 2
pixels_per_cutoff = 3.0
"""


class WorkCounter:
    """Sums the FFT pairs of the study's contact solves and field solves while it is active."""

    def __init__(self):
        self.fft_pairs = 0.0

    def __enter__(self):
        self.solve, self.field = resolved.solve_contact, records.solve_field

        def solve_contact(*args, **kwargs):
            result = self.solve(*args, **kwargs)
            self.fft_pairs += result.solver.fft_pairs
            return result

        def solve_field(*args, **kwargs):
            solution = self.field(*args, **kwargs)
            self.fft_pairs += solution.iterations + 1          # one pair per CG pass and one for the start
            return solution

        resolved.solve_contact, records.solve_field = solve_contact, solve_field
        return self

    def __exit__(self, *exception):
        resolved.solve_contact, records.solve_field = self.solve, self.field


def measure(scene, field: str) -> dict:
    """Wall and CPU time, solves and FFT pairs of the study of ``scene`` with the ``field`` model."""
    scene = dataclasses.replace(scene, screen=dataclasses.replace(scene.screen, field=field))
    with WorkCounter() as counter:
        wall, cpu = time.perf_counter(), time.process_time()
        result = run_study(scene, workers=1)
        wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
    return {"field": field, "wall_s": wall, "cpu_s": cpu, "solves": result.solves, "fft_pairs": counter.fft_pairs}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                     formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    parser.add_argument("--scene", default=None, help="scene file (default: the default scene)")
    parser.add_argument("--preset", default="standard", help="accuracy preset")
    parser.add_argument("--repeat", type=int, default=1, help="alternating runs of both fields")
    parser.add_argument("--fast", action="store_true", help="32² patches, 2 loads, 0 and 150 V: a test that it runs")
    parser.add_argument("--output", default="out", help="directory for bench_study_field.csv")
    args, provenance = parse_arguments(parser, argv, "studies/bench_study_field.py")
    scene = load_scene(text=FAST, preset="draft") if args.fast else load_scene(args.scene, preset=args.preset)
    loads = dataclasses.replace(scene.loads, normal_forces=scene.loads.normal_forces[:1],
                                voltages=scene.loads.voltages[-1:])
    warm = dataclasses.replace(scene, loads=loads)
    for field in ("parallel_plate", "layered"):       # compile the kernels, plan the FFTs, build the bodies
        measure(warm, field)
    rows = []
    for repeat in range(args.repeat):
        pixel, layered = measure(scene, "parallel_plate"), measure(scene, "layered")
        for key in ("wall", "cpu"):
            layered[f"{key}_ratio"] = layered[f"{key}_s"] / pixel[f"{key}_s"]
        layered["fft_pair_ratio"] = layered["fft_pairs"] / pixel["fft_pairs"]
        rows += [{"repeat": repeat, **pixel}, {"repeat": repeat, **layered}]
    path = write_csv(output_directory(args.output) / "bench_study_field.csv", rows, provenance, COLUMNS, echo=True)
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
