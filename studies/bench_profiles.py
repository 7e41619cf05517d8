"""The hard-wall solve of 1-D skin profiles with and without the K⁻¹ preconditioner (a script).

    python studies/bench_profiles.py --output out          # the table of docs/guide/solver.md, "Preconditioning"
    python studies/bench_profiles.py --fast --output out   # one pixel, one realisation: seconds

The profiles of ``studies/field_check.py`` (a rough cylinder cap and one ridge period of the default scene, both
as plane-strain profiles on the scene's layered skin) at the apparent pressures of 0.5 and 2 N, over
``--realisations`` roughness realisations, at each ``--pixels``: per setting the summed steps, FFT pairs and CPU time
(each solve timed after one untimed run) of the preconditioned and the plain Polonsky–Keer solve from the default
start, and how many preconditioned solves cycled and were repeated without the preconditioner (their steps and CPU
include the cycled attempt's; their FFT pairs are the repeat's only). Writes
``bench_profiles.csv`` with its provenance into ``--output``.
"""
from __future__ import annotations

import argparse
import time

from _bench import best_of
from field_check import profiles
from roughcontact import solve_contact
from roughcontact.io import output_directory, parse_arguments, write_csv
from roughcontact.study.apparent import apparent_scale
from roughcontact.study.scene import load_scene

FORCES = (0.5, 2.0)                                    # [N] the default scene's apparent pressures


def rows_for(pixel: float, realisations: int, scene, pressures) -> list:
    totals = {flag: {"steps": 0, "fft_pairs": 0.0, "cpu_s": 0.0, "cycled": 0} for flag in (True, False)}
    for rng in range(realisations):
        for heights, _, body in profiles(scene, pixel, rng).values():
            for force in FORCES:
                for flag, total in totals.items():
                    def solve():
                        return solve_contact(heights, body, mean_pressure=pressures[force], preconditioned=flag,
                                             warn=False)
                    solve()
                    result, seconds = best_of(solve, 1, clock=time.process_time)
                    total["steps"] += result.iterations + result.solver.details.get("preconditioned_stalled_at", 0)
                    total["fft_pairs"] += result.solver.fft_pairs
                    total["cpu_s"] += seconds
                    total["cycled"] += "preconditioned_stalled_at" in result.solver.details
    return [{"pixel_um": pixel * 1e6, "preconditioned": flag, "solves": realisations * 2 * len(FORCES), **total}
            for flag, total in totals.items()]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--pixels", type=float, nargs="+", default=[0.88e-6, 0.25e-6, 0.055e-6], help="pixels [m]")
    parser.add_argument("--realisations", type=int, default=4, help="roughness realisations per pixel")
    parser.add_argument("--fast", action="store_true", help="0.88 µm pixels, one realisation")
    parser.add_argument("--output", default="out", help="output directory (its parent must exist)")
    args, provenance = parse_arguments(parser, argv, "python studies/bench_profiles.py")
    output = output_directory(args.output)
    pixels, realisations = ([0.88e-6], 1) if args.fast else (args.pixels, args.realisations)
    scene = load_scene(preset="draft")
    pressures = {force: scale[1][0] for force, scale in zip(scene.loads.normal_forces, apparent_scale(scene))}
    rows = [row for pixel in pixels for row in rows_for(pixel, realisations, scene, pressures)]
    write_csv(output / "bench_profiles.csv", rows, provenance)
    for row in rows:
        print(f"{row['pixel_um']:.3f} µm, {'K⁻¹' if row['preconditioned'] else 'plain'}: {row['steps']} steps, "
              f"{row['fft_pairs']:.0f} FFT pairs, {row['cpu_s']:.3f} s CPU, {row['cycled']} repeated unpreconditioned")
    return rows


if __name__ == "__main__":
    main()
