"""Cost of displacement control against load control at the same mean pressure (the hard wall).

    python studies/bench_position.py                     # micro patch 128² and 256², bench surface 256²
    python studies/bench_position.py --sizes 128 --realisations 4 --output out
    python studies/bench_position.py --fast              # 64², two separations, seconds

Patches: ``micro``, the default scene's micro-roughness on its layered skin (the standard preset's roughness
on ``--sizes``² pixels, 4 pixels per cut-off; realisations 0 … R−1), brought to the mean separations
ū = s − ⟨h⟩ of ``--separations`` (in rms heights); ``bench``, the hard-wall benchmark surface
(``roughcontact.reference.benchmark.rough_surface``, half-space) on ``--bench-size``², at the mean pressures of
``--pressures`` (in E*), whose flat positions give the penetrations. At each point the hard wall is solved under
displacement control (``solve_contact(penetration=...)``: Polonsky–Keer, continued on the gap where it is slow)
and under load control at the mean pressure the first reached (``solve_contact(mean_pressure=...)``: the same
hand-over on a periodic 2-D grid); ``--pk-alone`` adds Polonsky–Keer alone under both controls
(``solve_hard_wall``, up to ``--pk-maxiter`` steps: on the micro patch it takes thousands). Then the coupled path's interface law at 0 V on each micro patch:
its ``LAW_NODES`` separations solved from far to near, each from the last, as ``interface_law`` solves them.
Then load sweeps (section ``sweep``): ``--sweep-loads`` mean pressures on each micro patch (0.4 … 4 MPa, 18–89 %
contact on 128²) and on the bench surface (0.001 … 0.01 E*), each solved cold, by ``load_path`` (warm, the secant
predictor: of the pressure, or of the gap where the last load was handed over to the gap) and by
``load_path(method="projected-cg-gap")`` (the hard wall on the gap by name), summed. Columns:
steps on the grid itself and the nested start's coarse steps, FFT pairs (the fine grid's), CPU time, contact
fraction, and the flat positions' difference in rms heights between the two controls (sweeps: the largest over
the loads against the cold solves). Writes
``bench_position.csv`` with its provenance into ``--output``; one FFT thread.
"""
from __future__ import annotations

import argparse
import time

import numpy as np

from roughcontact import ContactProblem, ElasticHalfSpace, load_path, solve_contact
from roughcontact.io import output_directory, parse_arguments, write_csv
from roughcontact.reference.benchmark import E_STAR, rough_surface
from roughcontact.solvers.polonsky_keer import solve_hard_wall
from roughcontact.study import load_scene
from roughcontact.study.coupled import LAW_NODES
from roughcontact.study.patch import patch_body, roughness_heights

COLUMNS = ("section", "patch", "n", "realisation", "control", "separation_rms", "mean_pressure_Pa", "iterations",
           "coarse_iterations", "fft_pairs", "time_s", "contact_fraction", "flat_position_difference_rms",
           "converged", "note")


def micro_patch(n, realisation):
    """The default scene's micro-roughness heights [m] on n² pixels (standard preset) and its skin body."""
    scene = load_scene(text=f"[presets.standard]\ngrid = {n}\n", preset="standard")
    return roughness_heights(scene, realisation), patch_body(scene, threads=1)


def timed(solve):
    start = time.process_time()
    result = solve()
    return result, time.process_time() - start


def row(section, patch, n, realisation, control, heights, result, seconds, flat_position=None):
    details = result.solver.details
    rms = float(np.std(heights))
    return dict(section=section, patch=patch, n=n, realisation=realisation, control=control,
                separation_rms=(result.flat_position - float(np.mean(heights))) / rms,
                mean_pressure_Pa=result.mean_pressure, iterations=result.iterations,
                coarse_iterations=sum(details.get("nested_iterations", [])), fft_pairs=result.solver.fft_pairs,
                time_s=seconds, contact_fraction=result.contact_fraction,
                flat_position_difference_rms="" if flat_position is None else (result.flat_position - flat_position) / rms,
                converged=result.converged, note=f"{result.solver.method}; start {result.solver.start}")


def point_rows(patch, n, realisation, heights, body, penetration, args):
    """Displacement control at ``penetration`` [m], load control at its mean pressure (and PK alone)."""
    tol = args.tol
    position, seconds = timed(lambda: solve_contact(heights, body, penetration=penetration, tol=tol, warn=False))
    rows = [row("point", patch, n, realisation, "penetration", heights, position, seconds)]
    load, seconds = timed(lambda: solve_contact(heights, body, mean_pressure=position.mean_pressure, tol=tol,
                                                warn=False))
    rows.append(row("point", patch, n, realisation, "mean_pressure", heights, load, seconds, position.flat_position))
    if args.pk_alone:
        problem = ContactProblem(heights, body)
        for control, value in (("penetration", penetration), ("mean_pressure", position.mean_pressure)):
            alone, seconds = timed(lambda: solve_hard_wall(problem, problem.control(
                **{control: value}, tol=tol, maxiter=args.pk_maxiter, warn=False)))
            rows.append(row("point", patch, n, realisation, f"{control}, polonsky-keer alone", heights, alone,
                            seconds, position.flat_position))
    for entry in rows:
        print(f"{patch:5s} {n:4d}² r{realisation} {entry['control']:34s} ū {entry['separation_rms']:.4f} h_rms  "
              f"A/A0 {entry['contact_fraction']:.4f}  {entry['iterations']:6d} + {entry['coarse_iterations']:5d} steps  "
              f"{entry['fft_pairs']:8.1f} FFT pairs  {entry['time_s']:.3f} s", flush=True)
    return rows


def law_rows(n, realisation, heights, body, args):
    """The coupled path's 0 V interface law: its nodes from far to near, each from the last."""
    mean, top, rms = float(heights.mean()), float(heights.max()), float(heights.std())
    separations = np.geomspace(0.02 * rms, top - mean + 2 * rms, args.nodes)[::-1]
    previous, totals = None, dict(iterations=0, coarse_iterations=0, fft_pairs=0.0, time_s=0.0)
    converged = True
    for separation in separations:
        result, seconds = timed(lambda: solve_contact(heights, body, penetration=top - mean - separation,
                                                      tol=args.law_tol, x0=previous, warn=False))
        entry = row("law", "micro", n, realisation, "penetration", heights, result, seconds)
        for name in totals:
            totals[name] += entry[name]
        converged, previous = converged and result.converged, result
    print(f"micro {n:4d}² r{realisation} 0 V interface law, {args.nodes} nodes: {totals['iterations']} + "
          f"{totals['coarse_iterations']} steps, {totals['fft_pairs']:.1f} FFT pairs, {totals['time_s']:.2f} s, "
          f"converged {converged}", flush=True)
    return [dict(section="law", patch="micro", n=n, realisation=realisation, control="penetration",
                 separation_rms=float(len(separations)), converged=converged,
                 note=f"{args.nodes} nodes from {separations[0] / rms:.3g} to {separations[-1] / rms:.3g} h_rms",
                 **totals)]


def sweep_rows(patch, n, realisation, heights, body, loads, args):
    """The loads [Pa] solved cold, by load_path, and by load_path on the gap; each summed."""
    ways = {"cold": lambda: [solve_contact(heights, body, mean_pressure=load, tol=args.tol, warn=False)
                             for load in loads],
            "load_path": lambda: list(load_path(heights, body, loads, tol=args.tol, warn=False)),
            "load_path, projected-cg-gap": lambda: list(load_path(heights, body, loads, tol=args.tol, warn=False,
                                                                  method="projected-cg-gap"))}
    rows, cold = [], None
    for way, solve in ways.items():
        results, seconds = timed(solve)
        cold = cold or results
        rms = float(np.std(getattr(heights, "heights", heights)))
        rows.append(dict(section="sweep", patch=patch, n=n, realisation=realisation, control=way,
                         separation_rms=float(len(loads)),
                         iterations=sum(result.iterations for result in results),
                         coarse_iterations=sum(sum(result.solver.details.get("nested_iterations", []))
                                               for result in results),
                         fft_pairs=sum(result.solver.fft_pairs for result in results), time_s=seconds,
                         flat_position_difference_rms=max(abs(a.flat_position - b.flat_position) / rms
                                                          for a, b in zip(results, cold)),
                         converged=all(result.converged for result in results),
                         note=f"{len(loads)} loads {loads[0]:.4g} … {loads[-1]:.4g} Pa"))
        print(f"{patch:5s} {n:4d}² r{realisation} sweep, {way:28s} {rows[-1]['iterations']:6d} + "
              f"{rows[-1]['coarse_iterations']:5d} steps {rows[-1]['fft_pairs']:8.1f} FFT pairs  {seconds:.3f} s  "
              f"({rows[-1]['fft_pairs'] / rows[0]['fft_pairs']:.2f} and {seconds / rows[0]['time_s']:.2f} of cold)",
              flush=True)
    return rows


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                     formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    parser.add_argument("--sizes", type=int, nargs="+", default=[128, 256], help="micro patch grids n (n² pixels)")
    parser.add_argument("--realisations", type=int, default=1, help="micro patch realisations 0 … R−1")
    parser.add_argument("--separations", type=float, nargs="+", default=[2.0, 1.0, 0.3, 0.1, 0.033, 0.02],
                        help="mean separations ū of the micro patch [rms heights]")
    parser.add_argument("--bench-size", type=int, default=256, help="the benchmark surface's grid (0: skip it)")
    parser.add_argument("--pressures", type=float, nargs="+", default=[0.001, 0.01, 0.03, 0.1],
                        help="the benchmark surface's mean pressures [E*]")
    parser.add_argument("--tol", type=float, default=1e-8, help="relative tolerance of the point solves")
    parser.add_argument("--law-tol", type=float, default=1e-5, help="the interface law's tolerance (the preset's)")
    parser.add_argument("--nodes", type=int, default=LAW_NODES, help="the interface law's separations (0: skip it)")
    parser.add_argument("--sweep-loads", type=int, default=10, help="loads of each sweep (0: no sweeps)")
    parser.add_argument("--pk-alone", action="store_true", help="also Polonsky–Keer alone under both controls")
    parser.add_argument("--pk-maxiter", type=int, default=30000, help="its step limit")
    parser.add_argument("--fast", action="store_true", help="64², two separations, no law: a test that the script runs")
    parser.add_argument("--output", default="out", help="directory for bench_position.csv")
    args, provenance = parse_arguments(parser, argv, "studies/bench_position.py")
    if args.fast:
        args.sizes, args.separations, args.bench_size, args.pressures, args.nodes = [64], [1.0, 0.05], 64, [0.05], 0
        args.sweep_loads = 3
    out = output_directory(args.output)
    rows = []
    for n in args.sizes:
        for realisation in range(args.realisations):
            heights, body = micro_patch(n, realisation)
            top, mean, rms = float(heights.max()), float(heights.mean()), float(heights.std())
            for separation in args.separations:
                rows += point_rows("micro", n, realisation, heights, body, top - mean - separation * rms, args)
            if args.nodes:
                rows += law_rows(n, realisation, heights, body, args)
            if args.sweep_loads:
                rows += sweep_rows("micro", n, realisation, heights, body, np.linspace(0.4e6, 4e6, args.sweep_loads),
                                   args)
    if args.bench_size:
        surface = rough_surface(args.bench_size)
        body = ElasticHalfSpace(surface.grid, E_STAR, threads=1)
        for pressure in args.pressures:
            flat_position = solve_contact(surface, body, mean_pressure=pressure * E_STAR, tol=args.tol,
                                          warn=False).flat_position
            rows += point_rows("bench", args.bench_size, 0, surface.heights, body,
                               float(surface.heights.max()) - flat_position, args)
        if args.sweep_loads:
            rows += sweep_rows("bench", args.bench_size, 0, surface, body,
                               np.linspace(0.001, 0.01, args.sweep_loads) * E_STAR, args)
    write_csv(out / "bench_position.csv", rows, provenance, COLUMNS)
    print(f"wrote {out / 'bench_position.csv'}")


if __name__ == "__main__":
    main()
