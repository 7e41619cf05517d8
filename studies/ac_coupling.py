"""Prototype: the contact equilibrium under the time-averaged AC attraction by deferred correction.

The library's solver (``ElectrostaticInteraction(stack, U, frequency=f)``, ``roughcontact.solvers.deferred_correction``)
grew out of this; the script keeps the design's measurements (both surrogates, every step) of docs/dev/roadmap.md.

    python studies/ac_coupling.py                     # 128², 1 N, 100 V RMS, DC and the crossover
    python studies/ac_coupling.py --grid 256 --frequencies 0 300 1000 --output out
    python studies/ac_coupling.py --fast              # 64², seconds

The time-averaged attraction σ̄(g) of a leaky stratum corneum is not the gradient of an energy
(docs/dev/roadmap.md, "AC drive"), so the energy-based contact solver cannot take it. Deferred correction: a
conservative surrogate law S (the dielectric layered field with a real effective ε_eff) carries the gap
dependence, and the rest of the true traction t(g) = −σ̄(g) is a traction field frozen at the last gap,

    g_{n+1} = argmin Π_S(g) − ⟨c_n g⟩,   c_n = t(g_n) − t_S(g_n),

repeated to a fixed point, where the solve's equilibrium is the true one. A frozen traction field c acts on the
body like a change of its heights by −K c̃ (the displacement of its zero-mean part; g = s − h + K p) and of the
external load by −⟨c⟩, so every step is an ordinary ``solve_contact`` with the surrogate law, warm-started from
the last gap; nothing of the solvers changes. Two surrogates: ε_eff = ε_sc (the dielectric model itself) and ε_eff
matched to the uniform mode, |h_rest + d_sc/ε*_sc| = h_rest + d_sc/ε_eff with h_rest the DC capacitance thickness
of air + insulator at the starting gap. Printed per step: the gap change max|g_{n+1} − g_n| / max g_n, ⟨σ̄⟩, the
contact fraction and the field-equivalent gap; at DC, where the true law is conservative, it is also solved
from the fixed point and from the start. ``ac_coupling.csv`` with its provenance goes to ``--output``.
"""
from __future__ import annotations

import argparse
import dataclasses

import numpy as np

from roughcontact import ElectrostaticInteraction, solve_contact
from roughcontact.electrostatics import EPSILON_0, solve_ac_field, solve_field
from roughcontact.io import output_directory, parse_arguments, write_csv
from roughcontact.solvers.deferred_correction import NO_ELASTANCE, surrogate_permittivity
from roughcontact.study.patch import default_scene_patch

COLUMNS = ("frequency_Hz", "surrogate", "eps_eff", "step", "gap_change", "mean_pressure_Pa", "contact_fraction",
           "field_equivalent_gap_m", "solver_iterations", "converged")


def matched_permittivity(stack, gap, lengths, voltage, frequency) -> float:
    """ε_eff with |h_rest + d_sc/ε*_sc| = h_rest + d_sc/ε_eff, h_rest = ε0 U/⟨D̂_DC⟩ at ``gap`` (the library's
    solver takes h_rest from the air + insulator columns instead, within about 1 % of this)."""
    direct = solve_ac_field(stack, gap, lengths, voltage, frequency=0.0)
    return surrogate_permittivity(stack, EPSILON_0 * voltage / float(np.mean(direct.flux.real)), frequency)


def deferred_correction(scene_parts, frequency, surrogate_eps, args) -> list:
    """The fixed-point iteration at ``frequency`` [Hz] with the surrogate ε_eff; its rows per step."""
    stack, grid, heights, body, pressure, start = scene_parts
    surrogate = dataclasses.replace(stack, eps_sc=surrogate_eps)
    law = ElectrostaticInteraction(surrogate, args.voltage, field="layered")
    result, correction, rows = start, np.zeros(grid.shape), []
    displacement = body.empty()
    for step in range(args.steps + 1):
        gap = result.gap
        true = solve_ac_field(stack, gap, grid.lengths, args.voltage, frequency=frequency, tol=1e-12)
        rows.append(dict(frequency_Hz=frequency, eps_eff=surrogate_eps, step=step,
                         mean_pressure_Pa=true.mean_attraction,
                         contact_fraction=result.contact_fraction, field_equivalent_gap_m=true.field_equivalent_gap,
                         solver_iterations=result.iterations, converged=result.converged))
        if step == args.steps:
            break
        modelled = solve_field(surrogate, gap, grid.lengths, args.voltage, tol=1e-12)
        correction = modelled.attraction - true.attraction          # t − t_S with t = −σ̄ (positive compressive)
        shifted = correction - correction.mean()
        body.displacement_into(shifted.astype(body.dtype), displacement)
        result_next = solve_contact(heights - displacement, body, mean_pressure=pressure - correction.mean(),
                                    interaction=law, x0=result, tol=args.tol, warn=False)
        rows[-1]["gap_change"] = float(np.max(np.abs(result_next.gap - gap)) / np.max(gap))
        result = result_next
        print(f"  step {step}: gap change {rows[-1]['gap_change']:.2e}, <σ̄> {true.mean_attraction:.6g} Pa, "
              f"A/A0 {result.contact_fraction:.4f}", flush=True)
    if frequency == 0.0:
        check_equilibrium(scene_parts, result, args)
    return rows


def check_equilibrium(scene_parts, fixed_point, args):
    """At DC the true law is conservative (the layered field without the stratum corneum's elastance): solve it
    from the fixed point (an equilibrium stays put) and from the dielectric start (the direct path)."""
    stack, grid, heights, body, pressure, start = scene_parts
    law = ElectrostaticInteraction(dataclasses.replace(stack, eps_sc=NO_ELASTANCE), args.voltage, field="layered")
    for name, x0 in (("the fixed point", fixed_point), ("the dielectric start", start)):
        result = solve_contact(heights, body, mean_pressure=pressure, interaction=law, x0=x0, tol=args.tol)
        change = np.max(np.abs(result.gap - fixed_point.gap)) / np.max(fixed_point.gap)
        print(f"  the DC law solved from {name}: gap differs from the fixed point by {change:.2e}, "
              f"A/A0 {result.contact_fraction:.5f} (fixed point {fixed_point.contact_fraction:.5f})", flush=True)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                     formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    parser.add_argument("--grid", type=int, default=128, help="pixels per side of the patch")
    parser.add_argument("--force", type=float, default=1.0, help="normal force F_N [N]")
    parser.add_argument("--voltage", type=float, default=100.0, help="RMS voltage U [V]")
    parser.add_argument("--frequencies", type=float, nargs="+", default=[0.0, 1000.0], help="drive frequencies [Hz]")
    parser.add_argument("--steps", type=int, default=12, help="deferred-correction steps")
    parser.add_argument("--tol", type=float, default=1e-10, help="relative tolerance of the contact solves")
    parser.add_argument("--fast", action="store_true", help="64², three steps: a test run")
    parser.add_argument("--output", default="out", help="directory for ac_coupling.csv")
    args, provenance = parse_arguments(parser, argv, "studies/ac_coupling.py")
    if args.fast:
        args.grid, args.steps = 64, 3
    directory = output_directory(args.output)
    patch = default_scene_patch(args.grid, args.force)
    stack, grid, heights, body, pressure = patch.stack, patch.grid, patch.surface, patch.body, patch.pressure
    start = solve_contact(heights, body, mean_pressure=pressure, tol=args.tol,
                          interaction=ElectrostaticInteraction(stack, args.voltage, field="layered"))
    parts = (stack, grid, heights, body, pressure, start)
    rows = []
    for frequency in args.frequencies:
        matched = matched_permittivity(stack, start.gap, grid.lengths, args.voltage, frequency)
        for name, eps in (("dielectric", stack.eps_sc), ("matched", matched)):
            print(f"{frequency:g} Hz, surrogate {name} (eps_eff = {eps:.4g}):", flush=True)
            rows += [dict(row, surrogate=name) for row in deferred_correction(parts, frequency, eps, args)]
    write_csv(directory / "ac_coupling.csv", rows, provenance, COLUMNS)


if __name__ == "__main__":
    main()
