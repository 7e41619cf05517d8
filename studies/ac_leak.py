"""A leak across the skin–screen interface on the default scene: F_el(f) of a drive-frequency sweep study.

    python studies/ac_leak.py                  # draft preset, 1 N, 100 V RMS: the table of docs/guide/ac_drive.md
    python studies/ac_leak.py --fast           # 64², one realisation, three frequencies: a test run
    python studies/ac_leak.py --elements       # each element on a fixed gap: attraction and cost, 256²

Writes two scenes and runs ``roughcontact run <scene> --out <output>/<name>`` on each: the default scene at one
load and voltage, swept from DC to 100 kHz (``[screen] frequency``), with the leak ``[screen] gap_conductivity``
σ_g (a conducting medium in the gap, ``docs/guide/ac_drive.md``, "A leak across the interface"; optionally
``gap_conductance`` and ``contact_transfer``) and without it. Every point is the patch's equilibrium under the
time-averaged attraction. Then ``ac_leak.csv``: per frequency and scene the realisation mean of the
electrostatic attraction ⟨σ̄⟩ and of F_el = ⟨σ̄⟩ A0, the mean over realisations of ⟨σ̄⟩ over the same realisation's
⟨σ̄⟩ at the highest frequency (paired), the Eq. 25 gap, the real contact fraction and how many realisations'
contact solves converged. Prints the table.

``--elements`` instead solves the field alone on a fixed gap, the default scene's patch (realisation 0, ``--grid``
pixels, 1 N) in its dielectric equilibrium at ``--voltage``, with each element of the leak alone at DC and
10 Hz – 100 kHz (cold, to a relative residual of 1e-10, the operator built once), and writes
``ac_leak_elements.csv``: the mean attraction over the dielectric one, COCG iterations, real FFT pairs and CPU time
(best of three, after a solve that compiles the kernels) against the same frequency's solve without the leak.
"""
from __future__ import annotations

import argparse
import dataclasses
import time
from collections import defaultdict

import numpy as np

from roughcontact import ElectrostaticInteraction, solve_contact
from roughcontact.cli import main as roughcontact
from roughcontact.electrostatics import ACStackField, LeakyStack, StackField
from roughcontact.io import output_directory, parse_arguments, read_csv, write_csv
from roughcontact.study.apparent import apparent_contact
from roughcontact.study.patch import default_scene_patch
from roughcontact.study.scene import load_scene

FREQUENCIES = (0.0, 10.0, 30.0, 100.0, 300.0, 1e3, 3e3, 1e4, 3e4, 1e5)
#: the elements of the leak of ``--elements`` (orders of the measured 250 Hz corner, references §11)
ELEMENTS = {"none": {}, "gap_conductance": dict(gap_conductance=0.061),
            "gap_conductivity": dict(gap_conductivity=1.5e-8),
            "gap_cpe": dict(gap_cpe=1e-3, gap_cpe_exponent=0.7), "contact_transfer": dict(contact_transfer=True),
            "surface_film": dict(surface_conductance=1e-8, contact_transfer=True)}
ELEMENT_COLUMNS = ("element", "frequency_Hz", "ratio_to_dielectric", "iterations", "fft_pairs", "cpu_s",
                   "fft_pair_ratio", "cpu_ratio", "residual")
COLUMNS = ("scene", "frequency_Hz", "electrostatic_attraction_Pa", "electrostatic_force_N", "ratio_to_highest",
           "equivalent_gap_um", "real_contact_fraction", "converged", "realisations")


def scene_text(args, leak: bool) -> str:
    """The scene file: the default scene at ``args.force`` and ``args.voltage``, swept over ``args.frequencies``,
    with the leak of ``args`` (``leak``) or without it."""
    lines = ["# roughcontact scene written by studies/ac_leak.py (docs/guide/ac_drive.md, \"A leak across the "
             "interface\")", "[screen]", f"frequency = {list(args.frequencies)!r}"]
    if leak:
        lines += [f"gap_conductivity = {args.conductivity!r}", f"gap_conductance = {args.conductance!r}"]
        if args.contact_transfer:
            lines.append("contact_transfer = true")
    lines += ["[loads]", f"normal_forces = [{args.force!r}]", f"voltages = [{args.voltage!r}]",
              "[study]", 'preset = "draft"']
    if args.fast:
        lines += ["[presets.draft]", "grid = 64", "realisations = 1"]
    return "\n".join(lines) + "\n"


def study(directory, name: str, text: str, workers: int) -> list:
    """``roughcontact run`` on the scene ``text`` (written to ``<directory>/<name>.toml``): its realisations'
    rows."""
    path = directory / f"{name}.toml"
    path.write_text(text, encoding="utf-8")
    out = directory / name
    if roughcontact(["run", str(path), "--out", str(out), "--workers", str(workers)]) != 0:
        raise RuntimeError(f"roughcontact run {path} failed")
    return read_csv(out / "realisations.csv")


def summary(name: str, rows: list, area: float) -> list:
    """Per frequency: realisation means of ⟨σ̄⟩, F_el, the paired ratio to the highest frequency, d_eq, A/A0."""
    by_frequency = defaultdict(dict)
    for row in rows:
        by_frequency[float(row["frequency_Hz"])][int(row["realisation"])] = row
    highest = by_frequency[max(by_frequency)]
    table = []
    for frequency in sorted(by_frequency):
        realisations = by_frequency[frequency]

        def values(column, scale=1.0):
            return np.array([float(row[column]) * scale for row in realisations.values()])

        attraction = values("electrostatic_attraction_kPa", 1e3)
        paired = [float(row["electrostatic_attraction_kPa"]) / float(highest[r]["electrostatic_attraction_kPa"])
                  for r, row in realisations.items()]
        table.append(dict(scene=name, frequency_Hz=frequency, electrostatic_attraction_Pa=attraction.mean(),
                          electrostatic_force_N=attraction.mean() * area, ratio_to_highest=float(np.mean(paired)),
                          equivalent_gap_um=values("equivalent_gap_um").mean(),
                          real_contact_fraction=values("real_contact_fraction_1").mean(),
                          converged=sum(row["converged"] == "True" for row in realisations.values()),
                          realisations=len(realisations)))
    return table


def elements(grid_size: int, voltage: float) -> list:
    """Rows of ``--elements``: each element of :data:`ELEMENTS` at DC, 10 Hz – 100 kHz on the dielectric
    equilibrium gap: the mean attraction over the dielectric one and the COCG solve's cost against no leak's."""
    patch = default_scene_patch(grid_size, 1.0)
    gap = solve_contact(patch.surface, patch.body, mean_pressure=patch.pressure,
                        interaction=ElectrostaticInteraction(patch.stack, voltage)).gap
    dielectric = float(np.mean(StackField(patch.stack, patch.grid).attraction(gap, StackField(
        patch.stack, patch.grid).solve_flux(gap, tol=1e-12)[0])))
    rows, reference = [], {}
    for element, keys in ELEMENTS.items():
        stack = LeakyStack(**{**dataclasses.asdict(patch.stack), **keys})
        for frequency in (0.0, 10.0, 100.0, 300.0, 1e3, 3e3, 1e4, 1e5):
            field = ACStackField(stack, patch.grid, frequency, threads=1)
            field.solve_flux(gap, tol=1e-10)                               # compiles the kernels of this column type
            times = []
            for _ in range(3):
                field.fft_pairs = 0
                began = time.process_time()
                flux, iterations, residual = field.solve_flux(gap, tol=1e-10)
                times.append(time.process_time() - began)
            mean = float(np.mean(field.attraction_phasors(gap, flux)[0]))
            row = dict(element=element, frequency_Hz=frequency, ratio_to_dielectric=mean / dielectric,
                       iterations=iterations, fft_pairs=field.fft_pairs, cpu_s=min(times), residual=residual)
            base = reference.setdefault(frequency, row)
            rows.append(dict(row, fft_pair_ratio=row["fft_pairs"] / base["fft_pairs"],
                             cpu_ratio=row["cpu_s"] / base["cpu_s"]))
    return rows


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                     formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    parser.add_argument("--conductivity", type=float, default=1.5e-8, help="gap_conductivity σ_g [S/m]")
    parser.add_argument("--conductance", type=float, default=0.0, help="gap_conductance G_g [S/m²]")
    parser.add_argument("--contact-transfer", action="store_true", help="contact_transfer = true")
    parser.add_argument("--frequencies", type=float, nargs="+", default=FREQUENCIES, help="drive frequencies [Hz]")
    parser.add_argument("--force", type=float, default=1.0, help="normal force F_N [N]")
    parser.add_argument("--voltage", type=float, default=100.0, help="RMS voltage U [V]")
    parser.add_argument("--workers", type=int, default=2, help="worker processes of each study")
    parser.add_argument("--fast", action="store_true", help="64², one realisation, DC, 100 Hz, 10 kHz: a test run")
    parser.add_argument("--elements", action="store_true", help="each element on a fixed gap instead")
    parser.add_argument("--grid", type=int, default=256, help="pixels per side of the patch of --elements")
    parser.add_argument("--output", default="out", help="directory for the CSV files and the two studies")
    args, provenance = parse_arguments(parser, argv, "studies/ac_leak.py")
    if args.fast:
        args.frequencies, args.grid = (0.0, 100.0, 1e4), 64
    directory = output_directory(args.output)
    if args.elements:
        rows = elements(args.grid, args.voltage)
        write_csv(directory / "ac_leak_elements.csv", rows, provenance, ELEMENT_COLUMNS)
        print(f"{args.grid}² dielectric equilibrium of the default scene at 1 N, {args.voltage:g} V; COCG to 1e-10")
        print("| element | f [Hz] | ⟨σ̄⟩ / dielectric | iterations | FFT pairs | / no leak | CPU / no leak |")
        print("|---|---|---|---|---|---|---|")
        for row in rows:
            print(f"| {row['element']} | {row['frequency_Hz']:g} | {row['ratio_to_dielectric']:.4g} | "
                  f"{row['iterations']} | {row['fft_pairs']} | {row['fft_pair_ratio']:.2f} | {row['cpu_ratio']:.2f} |")
        return
    area = float(apparent_contact(load_scene().fingerpad, args.force, 1)[0])
    rows = []
    for name, leak in (("leak", True), ("no_leak", False)):
        rows += summary(name, study(directory, name, scene_text(args, leak), args.workers), area)
    write_csv(directory / "ac_leak.csv", rows, provenance, COLUMNS)
    print(f"default scene, draft preset, {args.force:g} N, {args.voltage:g} V RMS; leak: σ_g = {args.conductivity:g} "
          f"S/m, G_g = {args.conductance:g} S/m², contact transfer {args.contact_transfer}")
    print("| f [Hz] | F_el [N], leak | / F_el(highest f), paired | A/A0 [%] | d_eq [µm] | converged "
          "| F_el [N], no leak | / F_el(highest f) |")
    print("|---|---|---|---|---|---|---|---|")
    leaky, plain = ([row for row in rows if row["scene"] == name] for name in ("leak", "no_leak"))
    for row, reference in zip(leaky, plain):
        frequency = row["frequency_Hz"]
        label = "DC" if frequency == 0 else f"{frequency:g}"
        print(f"| {label} | {row['electrostatic_force_N']:.4f} | {row['ratio_to_highest']:.4f} | "
              f"{row['real_contact_fraction'] * 100:.3f} | {row['equivalent_gap_um']:.3f} | "
              f"{row['converged']}/{row['realisations']} | {reference['electrostatic_force_N']:.4f} | "
              f"{reference['ratio_to_highest']:.4f} |")


if __name__ == "__main__":
    main()
