"""The attraction of the default scene's patch under an AC drive, 10 Hz – 10 kHz, at a fixed gap.

    python studies/ac_drive.py                        # 256², 1 N, 100 V RMS: the table of docs/guide/ac_drive.md
    python studies/ac_drive.py --grid 512 --output out
    python studies/ac_drive.py --fast                 # 64², seconds

The gap is the default scene's patch (realisation 0) solved with the layered field inside the contact solve at
the apparent pressure of ``--force`` (the Hertz mean over the footprint) and ``--voltage``: the dielectric
stratum corneum, i.e. the high-frequency limit. That gap is then held fixed (the skin's quasi-static response to
the frequency-dependent force is the next step, docs/dev/roadmap.md) and the field is solved with the leaky
stratum corneum (``DielectricStack.sigma_sc``) at each frequency, at DC and at ω = ∞. Per frequency: the mean
time-averaged attraction ⟨σ̄⟩ and its ratio to the dielectric one, the 2ω modulation depth |⟨σ̂₂⟩|/⟨σ̄⟩, the
field-equivalent gap (Eq. 21 inverted: the dielectric uniform gap with the same attraction, what the seed's
friction model must be fed), the AC-equivalent gap (the uniform gap with the same attraction under the same
drive) and the per-pixel (parallel-plate) law's ⟨σ̄⟩ on the same gap; the Eq. 25 gap of the fixed gap, the
measured crossover (⟨σ̄⟩ halfway between DC and ω = ∞) and the circuit's f_c = σ_sc/(2π ε0 (ε_sc + d_sc/h_rest))
with h_rest = ε0 U/⟨D̂_DC⟩, the DC capacitance thickness of air + insulator. Writes ``ac_drive.csv`` with its
provenance into ``--output`` and prints the table.
"""
from __future__ import annotations

import argparse
import math

import numpy as np
from scipy.optimize import brentq

from roughcontact import ElectrostaticInteraction, solve_contact
from roughcontact.electrostatics import EPSILON_0, crossover_frequency, solve_ac_field
from roughcontact.io import output_directory, parse_arguments, write_csv
from roughcontact.study.apparent import apparent_contact
from roughcontact.study.patch import patch_body, patch_grid, patch_surface
from roughcontact.study.scene import load_scene

COLUMNS = ("frequency_Hz", "mean_pressure_Pa", "ratio_to_dielectric", "modulation_depth", "field_equivalent_gap_m",
           "ac_equivalent_gap_m", "parallel_plate_mean_pressure_Pa", "equivalent_gap_m", "electrostatic_force_N",
           "measured_crossover_Hz", "circuit_crossover_Hz", "h_rest_m", "contact_fraction", "grid")


def scene_gap(grid_size: int, force: float, voltage: float, tol: float) -> tuple:
    """(stack, grid, gap [m], apparent area [m²], contact fraction) of the default scene's patch solved with the
    layered field at ``force`` [N] and ``voltage`` [V]."""
    scene = load_scene(text=f"[presets.standard]\ngrid = {grid_size}\n", preset="standard")
    area, (pressure,) = apparent_contact(scene.fingerpad, force, 1)
    stack = scene.screen.stack()
    result = solve_contact(patch_surface(scene, 0), patch_body(scene), mean_pressure=pressure, tol=tol,
                           interaction=ElectrostaticInteraction(stack, voltage, field="layered"))
    if not result.converged:
        raise RuntimeError(f"the contact solve did not converge: {result.message}")
    return stack, patch_grid(scene), result.gap, area, result.contact_fraction


def sweep(stack, grid, gap, voltage: float, frequencies, tol: float) -> tuple:
    """The rows at ``frequencies`` [Hz] (with 0 and inf) and (measured crossover [Hz], circuit's [Hz], h_rest [m])."""
    def solve(frequency, model="layered"):
        return solve_ac_field(stack, gap, grid.lengths, voltage, frequency=frequency, model=model, tol=tol)

    dielectric, direct = solve(math.inf), solve(0.0)
    rest = EPSILON_0 * voltage / float(np.mean(direct.flux.real))
    middle = 0.5 * (dielectric.mean_pressure + direct.mean_pressure)
    measured = 10 ** brentq(lambda log_f: solve(10 ** log_f).mean_pressure - middle, -2, 7, xtol=1e-6)
    rows = []
    for frequency in (0.0, *frequencies, math.inf):
        solution = solve(frequency)
        rows.append(dict(frequency_Hz=frequency, mean_pressure_Pa=solution.mean_pressure,
                         ratio_to_dielectric=solution.mean_pressure / dielectric.mean_pressure,
                         modulation_depth=solution.mean_oscillation / solution.mean_pressure,
                         field_equivalent_gap_m=solution.equivalent_gap,
                         ac_equivalent_gap_m=solution.ac_equivalent_gap,
                         parallel_plate_mean_pressure_Pa=solve(frequency, "parallel_plate").mean_pressure))
    return rows, (measured, crossover_frequency(stack, rest), rest)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                     formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    parser.add_argument("--grid", type=int, default=256, help="pixels per side of the patch")
    parser.add_argument("--force", type=float, default=1.0, help="normal force F_N [N]")
    parser.add_argument("--voltage", type=float, default=100.0, help="RMS voltage U [V]")
    parser.add_argument("--per-decade", type=int, default=4, help="frequencies per decade, 10 Hz – 10 kHz")
    parser.add_argument("--tol", type=float, default=1e-10, help="relative tolerance of the contact and field solves")
    parser.add_argument("--fast", action="store_true", help="64² and two frequencies per decade: a test run")
    parser.add_argument("--output", default="out", help="directory for ac_drive.csv")
    args, provenance = parse_arguments(parser, argv, "studies/ac_drive.py")
    if args.fast:
        args.grid, args.per_decade = 64, 2
    directory = output_directory(args.output)
    stack, grid, gap, area, contact = scene_gap(args.grid, args.force, args.voltage, args.tol)
    frequencies = np.logspace(1, 4, 3 * args.per_decade + 1)
    rows, (measured, circuit, rest) = sweep(stack, grid, gap, args.voltage, frequencies, args.tol)
    for row in rows:
        row.update(equivalent_gap_m=stack.equivalent_gap(gap), electrostatic_force_N=row["mean_pressure_Pa"] * area,
                   measured_crossover_Hz=measured, circuit_crossover_Hz=circuit, h_rest_m=rest,
                   contact_fraction=contact, grid=args.grid)
    write_csv(directory / "ac_drive.csv", rows, provenance, COLUMNS)
    print(f"{args.grid}² patch at {args.force:g} N, {args.voltage:g} V RMS: A/A0 = {contact:.4f}, Eq. 25 gap "
          f"{rows[0]['equivalent_gap_m'] * 1e6:.3f} µm; crossover measured {measured:.0f} Hz, circuit {circuit:.0f} Hz "
          f"(h_rest = {rest * 1e6:.3f} µm, {circuit / measured - 1:+.1%})")
    print("| f [Hz] | ⟨σ̄⟩ [kPa] | / dielectric | 2ω depth | field-eq. gap [µm] | AC-eq. gap [µm] | per-pixel ⟨σ̄⟩ [kPa] |")
    print("|---|---|---|---|---|---|---|")
    nearest = min(frequencies, key=lambda f: abs(math.log(f / measured)))
    for row in rows:
        frequency = row["frequency_Hz"]
        label = "DC" if frequency == 0 else "∞" if frequency == math.inf else f"{frequency:.0f}"
        label += " ← crossover" if frequency == nearest else ""
        print(f"| {label} | {row['mean_pressure_Pa'] / 1e3:.3f} | {row['ratio_to_dielectric']:.4f} | "
              f"{row['modulation_depth']:.4f} | {row['field_equivalent_gap_m'] * 1e6:.3f} | "
              f"{row['ac_equivalent_gap_m'] * 1e6:.3f} | {row['parallel_plate_mean_pressure_Pa'] / 1e3:.3f} |")


if __name__ == "__main__":
    main()
