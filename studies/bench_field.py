"""Cost of the layered field inside the contact solve against the per-pixel law on the same patch and tolerance.

    python studies/bench_field.py                      # 256² and 512², 30/100/200 V, one patch realisation
    python studies/bench_field.py --repeat 3 --output out
    python studies/bench_field.py --sizes 256 --realisations 4 --matched --output out   # the tables of
                                                       # docs/guide/electrostatics.md (and --sizes 512)
    python studies/bench_field.py --fast               # 64², seconds
    python studies/bench_field.py --sizes 256 --realisations 4 --contact-line breakdown --output out   # the cost
                                                       # of a contact-line model (docs/findings/contact_line.md)

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

With ``--matched`` each case also solves the per-pixel law at the voltage where its attraction matches the layered
solve's F_el (with ``--contact-line``, that model's; within ``MATCH_TOL``, by secant steps on log F_el against log
U; rows ``parallel_plate_matched``, their voltage in ``matched_voltage_V``): the layered solve's cost over that solve's separates the stronger
attraction (which the per-pixel law pays as well once driven to it) from what the layered law itself adds
(``docs/guide/electrostatics.md``, "Cost"). It also solves, at the voltage matched the same way, the per-pixel law of
the layered law's range (rows ``parallel_plate_local``; :func:`local_stack`): its offset is the layered field's
pixel elastance ε0 M_ii instead of the stack's c, so that a lone pixel's attraction and stiffness are the layered
law's; the layered solve's cost over that one is what the field's non-locality and its solves add to the physics
of a stronger, shorter-ranged attraction near contacts. The totals then also hold the ratios to both matched sums.

With ``--contact-line`` each case also solves the layered law with that model of the contact line
(:func:`roughcontact.electrostatics.contact_line.parse_contact_line`; rows ``layered_contact_line``), and the totals
hold its sums' ratios to the plain layered solve's (``fft_pairs_ratio_layered``, ``time_s_ratio_layered``): the
cost the model adds per solve.
"""
from __future__ import annotations

import argparse
import dataclasses
import math
import time

from _bench import best_of, count_argument, summed_ratios
from surfaces import Grid, self_affine
from roughcontact import ElasticHalfSpace, ElectrostaticInteraction, solve_contact
from roughcontact.electrostatics import EPSILON_0, DielectricStack, StackField
from roughcontact.electrostatics.contact_line import parse_contact_line
from roughcontact.io import output_directory, parse_arguments, write_csv
from roughcontact.study.patch import default_scene_patch

COLUMNS = ("patch", "n", "realisation", "voltage_V", "field", "time_s", "time_ratio", "iterations", "unstable_steps", "fft_pairs",
           "field_fft_pairs", "field_evaluations", "fft_pair_ratio", "contact_fraction", "electrostatic_force_N",
           "field_equivalent_gap_m", "equivalent_gap_m", "converged", "matched_voltage_V", "matched_force_ratio",
           "contact_line")
#: the row of the layered law with ``--contact-line``'s model
CONTACT_LINE = "layered_contact_line"
MATCH_TOL = 0.02          # |F_el(per pixel, U_m) / F_el(layered, U) − 1| at which a matched voltage is accepted
MATCH_SOLVES = 6          # per-pixel solves of the search before the closest is taken
#: the per-pixel references of --matched: the stack's own law, and the law of the layered field's pixel elastance
MATCHED = ("parallel_plate_matched", "parallel_plate_local")


def bench_patch(n, realisation=0):
    """The electrostatic bar's rough patch (seed 1 + ``realisation``) and its body, with its load p̄ [Pa]."""
    grid = Grid((n, n), (1e-3, 1e-3), periodic=True)
    surface = self_affine(grid, hurst=0.8, rms_height=3e-6, short_cutoff=8e-3 / n, rng=1 + realisation)
    return surface, ElasticHalfSpace(grid, E_star=1e6, planner_effort="FFTW_MEASURE"), 1e3, DielectricStack()


def scene_patch(n, realisation=0):
    """The default scene's patch on n² pixels, its skin body and the first ring's apparent pressure at 0.5 N."""
    patch = default_scene_patch(n, 0.5, realisation)
    return patch.surface, patch.body, patch.pressure, patch.stack


def local_stack(stack, grid):
    """``stack`` with both layers' permittivities scaled by c/(ε0 M_ii), so that the per-pixel law's offset c becomes
    the layered field's pixel elastance ε0 M_ii on ``grid`` (the air-equivalent thickness the layers present to one
    pixel's flux): the per-pixel law with the layered law's attraction and stiffness at a lone pixel."""
    scale = stack.dielectric_offset / (StackField(stack, grid).pixel_elastance * EPSILON_0)
    return dataclasses.replace(stack, eps_sc=stack.eps_sc * scale, eps_i=stack.eps_i * scale)


def matched_voltage(surface, body, pressure, stack, voltage, target, tol):
    """The voltage U_m [V] at which the per-pixel law's F_el is within ``MATCH_TOL`` of ``target`` [N] (secant
    steps on log F_el against log U from F ∝ U², at most ``MATCH_SOLVES`` solves; the closest one otherwise), and
    F_el(U_m) / target."""
    def force(u):
        law = ElectrostaticInteraction(stack, u, field="parallel_plate")
        return solve_contact(surface, body, mean_pressure=pressure, tol=tol, interaction=law,
                             warn=False).electrostatic_force

    if target <= 0:                             # no attraction (0 V): the same voltage matches it
        return voltage, 1.0
    tried = [(voltage, force(voltage))]
    exponent = 2.0
    for _ in range(MATCH_SOLVES - 1):
        u, f = tried[-1]
        if abs(f / target - 1) <= MATCH_TOL:
            break
        u_next = u * (target / f) ** (1 / exponent)
        f_next = force(u_next)
        if f_next != f:                        # the secant's exponent, kept within [1, 8] across jumps of the path
            exponent = min(8.0, max(1.0, math.log(f_next / f) / math.log(u_next / u)))
        tried.append((u_next, f_next))
    u, f = min(tried, key=lambda pair: abs(pair[1] / target - 1))
    return u, f / target


def rows_for(name, n, args, realisation=0):
    surface, body, pressure, stack = {"bench": bench_patch, "scene": scene_patch}[name](n, realisation)
    rows = []
    for voltage in args.voltages:
        reference, matched, layered_force = None, None, None
        model = parse_contact_line(args.contact_line)
        fields = ("parallel_plate", "layered") + ((CONTACT_LINE,) if model else ()) + (MATCHED if args.matched else ())
        for field in fields:
            law_field, solved_stack, solved_voltage, contact_line = field, stack, voltage, None
            if field == CONTACT_LINE:
                law_field, contact_line = "layered", model
            if field in MATCHED:
                law_field = "parallel_plate"
                if field == "parallel_plate_local":
                    solved_stack = local_stack(stack, body.grid)
                solved_voltage, matched = matched_voltage(surface, body, pressure, solved_stack, voltage,
                                                          layered_force, args.tol)
            law = ElectrostaticInteraction(solved_stack, solved_voltage, field=law_field, contact_line=contact_line)
            solve_contact(surface, body, mean_pressure=pressure, tol=args.tol, interaction=law, warn=False)  # warm
            result, seconds = best_of(lambda: solve_contact(surface, body, mean_pressure=pressure, tol=args.tol,
                                                            interaction=law, warn=False),
                                      args.repeat, clock=time.process_time)
            reference = reference or (seconds, result.solver.fft_pairs)
            rows.append(dict(patch=name, n=n, realisation=realisation, voltage_V=voltage, field=field, time_s=seconds,
                             matched_voltage_V=solved_voltage if matched else "", matched_force_ratio=matched or "",
                             time_ratio=seconds / reference[0], iterations=result.iterations,
                             unstable_steps=result.unstable_steps,
                             field_fft_pairs=result.solver.details.get("field_fft_pairs", 0),
                             field_evaluations=result.solver.details.get("field_evaluations", 0),
                             fft_pairs=result.solver.fft_pairs,
                             fft_pair_ratio=result.solver.fft_pairs / reference[1],
                             contact_fraction=result.contact_fraction,
                             electrostatic_force_N=result.electrostatic_force,
                             field_equivalent_gap_m=result.field_equivalent_gap,
                             equivalent_gap_m=result.equivalent_gap, converged=result.converged,
                             contact_line=args.contact_line if contact_line else ""))
            if field == (CONTACT_LINE if model else "layered"):    # the attraction the per-pixel law matches
                layered_force = result.electrostatic_force
            at = f" (at {solved_voltage:.0f} V: F_el x{matched:.3f})" if matched else ""
            print(f"{name:5s} {n:4d}² r{realisation} {voltage:5.0f} V {field:22s} {seconds:8.3f} s  "
                  f"x{rows[-1]['time_ratio']:.2f}  {result.solver.fft_pairs:7.1f} FFT pairs  "
                  f"x{rows[-1]['fft_pair_ratio']:.2f}  A/A0 {result.contact_fraction:.4f}{at}", flush=True)
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
    parser.add_argument("--matched", action="store_true",
                        help="also the per-pixel law, with the stack's offset and with the layered law's pixel "
                             "elastance, at the voltages that match the layered law's attraction")
    parser.add_argument("--contact-line", default="none",
                        help="also the layered law with this model of the contact line: breakdown[:E_bd], "
                             "film:<thickness in m>, ... (none: not)")
    parser.add_argument("--fast", action="store_true",
                        help="64², one voltage, with --matched: a test that the script runs")
    parser.add_argument("--output", default="out", help="directory for bench_field.csv")
    args, provenance = parse_arguments(parser, argv, "studies/bench_field.py")
    if args.fast:
        args.sizes, args.voltages, args.matched = [64], [30.0], True
    directory = output_directory(args.output)
    rows = [row for n in args.sizes for name in args.patches for realisation in range(args.realisations)
            for row in rows_for(name, n, args, realisation)]
    write_csv(directory / "bench_field.csv", rows, provenance, COLUMNS)
    if args.realisations > 1:
        # near instabilities one solve's cost moves by a factor 2 with its path: the sums average it
        group = ("patch", "n", "voltage_V", "field")
        totals = summed_ratios(rows, group, lambda key: key[:3] + ("parallel_plate",))
        for reference in MATCHED if args.matched else ():  # the same sums as ratios to each matched reference
            against = summed_ratios(rows, group, lambda key: key[:3] + (reference,))
            suffix = reference.removeprefix("parallel_plate_")
            for row, other in zip(totals, against):
                row.update({f"{name}_ratio_{suffix}": other[f"{name}_ratio"] for name in ("fft_pairs", "time_s")})
        if parse_contact_line(args.contact_line):         # the model's cost over the plain layered law's
            against = summed_ratios(rows, group, lambda key: key[:3] + ("layered",))
            for row, other in zip(totals, against):
                row.update({f"{name}_ratio_layered": other[f"{name}_ratio"] for name in ("fft_pairs", "time_s")})
        write_csv(directory / "bench_field_totals.csv", totals, provenance)
        for row in totals:
            matched = "".join(f"  ({suffix}: x{row[f'fft_pairs_ratio_{suffix}']:.2f}, CPU "
                              f"x{row[f'time_s_ratio_{suffix}']:.2f})" for suffix in ("matched", "local")
                              if args.matched)
            layered = (f"  (layered: x{row['fft_pairs_ratio_layered']:.3f}, CPU x{row['time_s_ratio_layered']:.3f})"
                       if "fft_pairs_ratio_layered" in row else "")
            print(f"{row['patch']:5s} {row['n']:4d}² {row['voltage_V']:5.0f} V {row['field']:22s} over {row['count']} "
                  f"realisations: FFT pairs x{row['fft_pairs_ratio']:.2f}  CPU x{row['time_s_ratio']:.2f}{matched}"
                  f"{layered}")


if __name__ == "__main__":
    main()
