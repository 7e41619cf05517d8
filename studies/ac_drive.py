"""The default scene's patch under an AC drive, 10 Hz – 10 kHz: the equilibrium solved at each frequency.

    python studies/ac_drive.py                        # 256², 1 N, 100 V RMS: the table of docs/guide/ac_drive.md
    python studies/ac_drive.py --grid 512 --output out
    python studies/ac_drive.py --fast                 # 64², seconds

The default scene's patch (realisation 0) at the apparent pressure of ``--force`` (the Hertz mean over the
footprint) is solved to equilibrium under the time-averaged attraction of ``--voltage`` RMS at each frequency
(``ElectrostaticInteraction(stack, U, frequency=f)``, the deferred correction of
``roughcontact.solvers.deferred_correction``; each solve cold, from the hard-wall start), at DC and at ω = ∞ (the
dielectric layered solve). Per frequency, of the solved equilibrium: the mean time-averaged attraction ⟨σ̄⟩ and
its ratio to the dielectric one, A/A0, the Eq. 25 gap, the field-equivalent gap (Eq. 21 inverted: what the seed's
friction model must be fed), the AC-equivalent gap (the uniform gap with the same attraction under the same
drive), the 2ω modulation depth |⟨σ̂₂⟩|/⟨σ̄⟩ and the number of corrections. For comparison, the **fixed gap** of the
dielectric solve with the field alone solved at each frequency (the layered ⟨σ̄⟩, its ratio and the per-pixel
law's ⟨σ̄⟩). The crossovers: the frequency where ⟨σ̄⟩ is halfway between DC and ω = ∞, measured on the solved
equilibria and on the fixed gap, and the circuit's f_c = σ_sc/(2π ε0 (ε_sc + d_sc/h_rest)) with
h_rest = ε0 U/⟨D̂_DC⟩, the DC capacitance thickness of air + insulator, of the DC equilibrium and of the fixed
gap. Writes ``ac_drive.csv`` with its provenance into ``--output`` and prints the table.
"""
from __future__ import annotations

import argparse
import math

import numpy as np
from scipy.optimize import brentq

from roughcontact import ElectrostaticInteraction, solve_contact
from roughcontact.electrostatics import EPSILON_0, crossover_frequency, solve_ac_field
from roughcontact.io import output_directory, parse_arguments, write_csv
from roughcontact.study.patch import default_scene_patch

COLUMNS = ("frequency_Hz", "mean_pressure_Pa", "ratio_to_dielectric", "contact_fraction", "equivalent_gap_m",
           "field_equivalent_gap_m", "ac_equivalent_gap_m", "modulation_depth", "corrections", "converged",
           "electrostatic_force_N", "fixed_mean_pressure_Pa", "fixed_ratio_to_dielectric",
           "fixed_parallel_plate_mean_pressure_Pa", "measured_crossover_Hz", "circuit_crossover_Hz", "h_rest_m",
           "fixed_measured_crossover_Hz", "fixed_circuit_crossover_Hz", "fixed_h_rest_m", "grid")


class Patch:
    """The default scene's patch on ``grid_size``² pixels at ``force`` [N] and ``voltage`` [V RMS]: its solves."""

    def __init__(self, grid_size: int, force: float, voltage: float, tol: float):
        patch = default_scene_patch(grid_size, force)
        self.area, self.pressure, self.stack, self.grid = patch.area, patch.pressure, patch.stack, patch.grid
        self.heights, self.body = patch.surface, patch.body
        self.voltage, self.tol = voltage, tol

    def solve(self, frequency):
        """The equilibrium under the drive at ``frequency`` [Hz] (inf: the dielectric layered solve)."""
        result = solve_contact(self.heights, self.body, mean_pressure=self.pressure, tol=self.tol,
                               interaction=ElectrostaticInteraction(self.stack, self.voltage, frequency=frequency))
        if not result.converged:
            raise RuntimeError(f"the contact solve at {frequency:g} Hz did not converge: {result.message}")
        return result

    def field(self, gap, frequency, model="layered"):
        return solve_ac_field(self.stack, gap, self.grid.lengths, self.voltage, frequency=frequency, model=model,
                              tol=self.tol)

    def rest_thickness(self, gap) -> float:
        """h_rest = ε0 U/⟨D̂_DC⟩ [m] of ``gap``."""
        return EPSILON_0 * self.voltage / float(np.mean(self.field(gap, 0.0).flux.real))


def halfway(attraction, low: float, high: float) -> float:
    """The frequency [Hz] where ``attraction(f)`` is halfway between its values ``low`` (DC) and ``high`` (∞)."""
    middle = 0.5 * (low + high)
    return 10 ** brentq(lambda log_f: attraction(10 ** log_f) - middle, 1, 4, xtol=1e-4)


def sweep(patch: Patch, frequencies) -> list:
    """The rows at DC, ``frequencies`` [Hz] and ∞, with the crossovers."""
    solved = {frequency: patch.solve(frequency) for frequency in (0.0, *frequencies, math.inf)}
    dielectric, direct = solved[math.inf], solved[0.0]
    fixed = {frequency: patch.field(dielectric.gap, frequency) for frequency in solved}

    def mean_attraction(result):
        return -float(np.mean(result.interaction_traction))

    measured = halfway(lambda f: mean_attraction(patch.solve(f)), mean_attraction(direct), mean_attraction(dielectric))
    fixed_measured = halfway(lambda f: patch.field(dielectric.gap, f).mean_attraction, fixed[0.0].mean_attraction,
                             fixed[math.inf].mean_attraction)
    rest, fixed_rest = patch.rest_thickness(direct.gap), patch.rest_thickness(dielectric.gap)
    common = dict(measured_crossover_Hz=measured, circuit_crossover_Hz=crossover_frequency(patch.stack, rest),
                  h_rest_m=rest, fixed_measured_crossover_Hz=fixed_measured, fixed_h_rest_m=fixed_rest,
                  fixed_circuit_crossover_Hz=crossover_frequency(patch.stack, fixed_rest), grid=patch.grid.shape[0])
    rows = []
    for frequency, result in solved.items():
        field = patch.field(result.gap, frequency)
        details = result.solver.details
        rows.append(dict(common, frequency_Hz=frequency, mean_pressure_Pa=field.mean_attraction,
                         ratio_to_dielectric=field.mean_attraction / fixed[math.inf].mean_attraction,
                         contact_fraction=result.contact_fraction, equivalent_gap_m=result.equivalent_gap,
                         field_equivalent_gap_m=field.field_equivalent_gap, ac_equivalent_gap_m=field.ac_equivalent_gap,
                         modulation_depth=field.mean_oscillation / field.mean_attraction,
                         corrections=details.get("corrections", 0), converged=result.converged,
                         electrostatic_force_N=field.mean_attraction * patch.area,
                         fixed_mean_pressure_Pa=fixed[frequency].mean_attraction,
                         fixed_ratio_to_dielectric=fixed[frequency].mean_attraction / fixed[math.inf].mean_attraction,
                         fixed_parallel_plate_mean_pressure_Pa=patch.field(dielectric.gap, frequency,
                                                                           "parallel_plate").mean_attraction))
    return rows


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
    patch = Patch(args.grid, args.force, args.voltage, args.tol)
    rows = sweep(patch, np.logspace(1, 4, 3 * args.per_decade + 1))
    write_csv(directory / "ac_drive.csv", rows, provenance, COLUMNS)
    first = rows[0]
    print(f"{args.grid}² patch at {args.force:g} N, {args.voltage:g} V RMS. Crossover of the solved equilibria: "
          f"measured {first['measured_crossover_Hz']:.0f} Hz, circuit {first['circuit_crossover_Hz']:.0f} Hz "
          f"(h_rest = {first['h_rest_m'] * 1e6:.3f} µm at DC, {first['circuit_crossover_Hz'] / first['measured_crossover_Hz'] - 1:+.1%}); "
          f"of the fixed gap: measured {first['fixed_measured_crossover_Hz']:.0f} Hz, circuit "
          f"{first['fixed_circuit_crossover_Hz']:.0f} Hz (h_rest = {first['fixed_h_rest_m'] * 1e6:.3f} µm)")
    print("| f [Hz] | ⟨σ̄⟩ [kPa] | / dielectric | A/A0 [%] | Eq. 25 gap [µm] | field-eq. gap [µm] | AC-eq. gap [µm] "
          "| 2ω depth | corrections | fixed gap: ⟨σ̄⟩ [kPa] | / dielectric | per-pixel ⟨σ̄⟩ [kPa] |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for row in rows:
        frequency = row["frequency_Hz"]
        label = "DC" if frequency == 0 else "∞ (dielectric)" if frequency == math.inf else f"{frequency:.0f}"
        print(f"| {label} | {row['mean_pressure_Pa'] / 1e3:.3f} | {row['ratio_to_dielectric']:.4f} | "
              f"{row['contact_fraction'] * 100:.3f} | {row['equivalent_gap_m'] * 1e6:.3f} | "
              f"{row['field_equivalent_gap_m'] * 1e6:.3f} | {row['ac_equivalent_gap_m'] * 1e6:.3f} | "
              f"{row['modulation_depth']:.4f} | {row['corrections']} | {row['fixed_mean_pressure_Pa'] / 1e3:.3f} | "
              f"{row['fixed_ratio_to_dielectric']:.4f} | {row['fixed_parallel_plate_mean_pressure_Pa'] / 1e3:.3f} |")


if __name__ == "__main__":
    main()
