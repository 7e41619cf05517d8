"""Cost of a contact solve under an AC drive against the dielectric layered solve of the same patch.

    python studies/bench_ac_drive.py                  # 128² and 256²: the table of docs/guide/ac_drive.md
    python studies/bench_ac_drive.py --sizes 256 --frequencies 1000 --repeat 3 --output out
    python studies/bench_ac_drive.py --fast           # 64², one frequency, one timing: a test run

The default scene's patch (realisation 0, or 0 … R−1) at the apparent pressure of ``--force`` (the Hertz mean over the
footprint) and ``--voltage`` RMS, solved cold to ``--tol``. The reference is the dielectric layered solve
(``ElectrostaticInteraction(stack, U)``, the energy method); beside it:

* ``dielectric xF``: the same at ε_sc times each ``--spread`` factor F, how much a solve's cost varies with its
  path through the snap-ins of the patch;
* ``dc-direct``: the conservative DC law (no elastance of the stratum corneum) by the energy method;
* ``ac-drive``: ``ElectrostaticInteraction(stack, U, frequency=f)`` at each of ``--frequencies``, by the
  deferred correction (``roughcontact.solvers.deferred_correction``);
* ``surrogate``: each drive's surrogate law alone (the dielectric law at its matched ε_eff, no correction), the
  share of a drive's cost that is its law's own solve path.

Printed per solve: energy-solve iterations (per correction), real FFT pairs (all of them: the hard-wall start,
the field solves inside the solves, the corrections' AC field solves, listed apart) and CPU time (best of
``--repeat``; CPU, not wall time, so that the ratios hold on a shared machine: run with one FFT thread), their
ratios to the reference, F_el and A/A0, and the ε_sc of the law solved (a surrogate's ε_eff). Writes
``bench_ac_drive.csv`` with its provenance into ``--output``; with ``--realisations R`` > 1 every solve is repeated on
the patch realisations 0 … R−1 and ``bench_ac_drive_totals.csv`` holds the FFT pairs and CPU summed over them, as
ratios to the dielectric solve's sums (a single solve's cost moves by about ±30 % with its path).
"""
from __future__ import annotations

import argparse
import dataclasses
import math
import time

from _bench import best_of, count_argument, summed_ratios
from roughcontact import ElectrostaticInteraction, solve_contact
from roughcontact.io import output_directory, parse_arguments, write_csv
from roughcontact.solvers.deferred_correction import NO_ELASTANCE
from roughcontact.study.patch import default_scene_patch

COLUMNS = ("n", "realisation", "solve", "frequency_Hz", "eps_sc", "iterations", "solve_iterations", "fft_pairs", "correction_fft_pairs",
           "time_s", "fft_pair_ratio", "time_ratio", "electrostatic_force_N", "contact_fraction", "converged")


def rows_for(n: int, args, realisation: int = 0) -> list:
    patch = default_scene_patch(n, args.force, realisation)
    heights, body, stack, pressure = patch.surface, patch.body, patch.stack, patch.pressure
    laws = [("dielectric", math.inf, ElectrostaticInteraction(stack, args.voltage))]
    laws += [(f"dielectric x{factor:g}", math.inf,
              ElectrostaticInteraction(dataclasses.replace(stack, eps_sc=factor * stack.eps_sc), args.voltage))
             for factor in args.spread]
    laws += [("dc-direct", 0.0, ElectrostaticInteraction(dataclasses.replace(stack, eps_sc=NO_ELASTANCE), args.voltage))]
    laws += [("ac-drive", f, ElectrostaticInteraction(stack, args.voltage, frequency=f)) for f in args.frequencies]
    rows = []
    while laws:
        name, frequency, law = laws.pop(0)

        def solve():
            return solve_contact(heights, body, mean_pressure=pressure, interaction=law, tol=args.tol)
        solve()                                                  # compiles, warms the plans
        result, seconds = best_of(solve, args.repeat, clock=time.process_time)
        details = result.solver.details
        if name == "ac-drive":                                  # next: its surrogate law alone, solved directly
            surrogate = dataclasses.replace(stack, eps_sc=details["surrogate_eps_sc"])
            laws.insert(0, ("surrogate", frequency, ElectrostaticInteraction(surrogate, args.voltage)))
        rows.append(dict(n=n, realisation=realisation, solve=name, frequency_Hz=frequency, eps_sc=law.stack.eps_sc, iterations=result.iterations,
                         solve_iterations=" ".join(str(i) for i in details.get("solve_iterations", [result.iterations])),
                         fft_pairs=result.solver.fft_pairs, correction_fft_pairs=details.get("correction_fft_pairs", 0.0),
                         time_s=seconds, electrostatic_force_N=result.electrostatic_force,
                         contact_fraction=result.contact_fraction, converged=result.converged))
    reference = rows[0]
    for row in rows:
        row.update(fft_pair_ratio=row["fft_pairs"] / reference["fft_pairs"], time_ratio=row["time_s"] / reference["time_s"])
        print(f"{n:4d}² r{realisation} {row['solve']:15s} {row['frequency_Hz']:7.4g} Hz  eps_sc {row['eps_sc']:8.4g}  "
              f"{row['iterations']:4d} it "
              f"({row['solve_iterations']:>9s})  {row['fft_pairs']:7.1f} FFT pairs x{row['fft_pair_ratio']:.2f} "
              f"(corrections {row['correction_fft_pairs']:5.1f})  {row['time_s']:6.3f} s CPU x{row['time_ratio']:.2f}  "
              f"F_el {row['electrostatic_force_N'] * 1e3:.4f} mN  A/A0 {row['contact_fraction']:.4f}", flush=True)
    return rows


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                     formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    parser.add_argument("--sizes", type=int, nargs="+", default=[128, 256], help="grid sizes n (n² pixels)")
    parser.add_argument("--frequencies", type=float, nargs="+", default=[0.0, 10.0, 100.0, 1000.0, 10000.0],
                        help="drive frequencies [Hz]")
    parser.add_argument("--spread", type=float, nargs="*", default=[0.97, 1.01, 1.03],
                        help="factors on eps_sc at which the dielectric solve is repeated (its path's spread)")
    parser.add_argument("--force", type=float, default=1.0, help="normal force F_N [N]")
    parser.add_argument("--voltage", type=float, default=100.0, help="RMS voltage U [V]")
    parser.add_argument("--tol", type=float, default=1e-8, help="relative tolerance of every contact solve")
    parser.add_argument("--repeat", type=count_argument, default=3, help="timings per solve; the best is kept")
    parser.add_argument("--realisations", type=count_argument, default=1,
                        help="patch realisations 0 … R−1; with R > 1 also the ratios of the sums over them")
    parser.add_argument("--fast", action="store_true", help="64², 1 kHz, one timing: a test that the script runs")
    parser.add_argument("--output", default="out", help="directory for bench_ac_drive.csv")
    args, provenance = parse_arguments(parser, argv, "studies/bench_ac_drive.py")
    if args.fast:
        args.sizes, args.frequencies, args.spread, args.repeat = [64], [1000.0], [], 1
    directory = output_directory(args.output)
    rows = [row for n in args.sizes for realisation in range(args.realisations)
            for row in rows_for(n, args, realisation)]
    write_csv(directory / "bench_ac_drive.csv", rows, provenance, COLUMNS)
    if args.realisations > 1:
        # one solve's cost moves by about ±30 % with its path through the snap-ins: the sums average it
        totals = summed_ratios(rows, ("n", "solve", "frequency_Hz"), lambda key: (key[0], "dielectric", math.inf))
        write_csv(directory / "bench_ac_drive_totals.csv", totals, provenance)
        for row in totals:
            print(f"{row['n']:4d}² over {row['count']} realisations: {row['solve']:15s} "
                  f"{row['frequency_Hz']:7.4g} Hz  FFT pairs x{row['fft_pairs_ratio']:.2f}  CPU x{row['time_s_ratio']:.2f}")


if __name__ == "__main__":
    main()
