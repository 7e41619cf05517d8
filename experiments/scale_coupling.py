"""The coupled path (roughcontact.coupling) against the fully resolved patches of the fingerpad study (a script).

    python experiments/scale_coupling.py                           # docs/equivalent_gap.md, "Scale coupling"
    python experiments/scale_coupling.py --fast                    # 32² patches, seconds

(from the repository root after ``pip install -e .``). The default scene at 0.5 and 2 N and the voltages given:
the fully resolved study (ridges and micro-roughness in one grid, ``roughcontact.study.run_study``) and the
coupled path — an :class:`~roughcontact.coupling.InterfaceLaw` built from the micro-roughness of the same
realisation on the same grid, acting on the ridges alone on a ``--ridge-grid``² grid. Writes
``scale_coupling.csv`` (one row per realisation, load and voltage: d_eq and the real contact fraction of both
paths, their relative differences, the solve times) into ``--output`` and prints the mean and largest
differences.
"""
from __future__ import annotations

import argparse
import time

import numpy as np

from roughcontact.coupling import coupled_point, interface_law
from roughcontact.provenance import output_directory, parse_arguments, write_csv
from roughcontact.scene import load_scene
from roughcontact.study import (apparent_contact, confidence_interval, patch_body, patch_grid, ridge_heights,
                                roughness_heights, run_study)

FAST = "[presets.draft]\ngrid = 32\nrealisations = 1\npixels_per_cutoff = 3.0\n[roughness]\nlong_cutoff = 1.5e-4\n"


def compare(scene, ridge_grid: int) -> list:
    """Rows of the fully resolved study and the coupled path of ``scene`` (ridges on ``ridge_grid``² pixels)."""
    from surfaces import Grid
    start = time.perf_counter()
    full = run_study(scene)
    full_seconds = time.perf_counter() - start
    grid = patch_grid(scene)
    coarse = Grid((ridge_grid, ridge_grid), grid.lengths, periodic=True)
    body, ridge_body = patch_body(scene), patch_body(scene, coarse)
    ridges, stack = ridge_heights(scene, coarse), scene.screen.stack()
    rows = []
    for r in range(full.array("equivalent_gap").shape[-1]):
        micro = roughness_heights(scene, r)
        for j, voltage in enumerate(scene.loads.voltages):
            start = time.perf_counter()
            law = interface_law(micro, body, stack, voltage, tol=scene.preset.tolerance)
            law_seconds, previous = time.perf_counter() - start, None
            for i, force in enumerate(scene.loads.normal_forces):
                _, (pressure,) = apparent_contact(scene.fingerpad, force, 1)
                start = time.perf_counter()
                point, previous = coupled_point(ridges, ridge_body, law, pressure, tol=scene.preset.tolerance,
                                                x0=previous)
                resolved = full.points[i][j]
                rows.append({"realisation": r, "normal_force_N": force, "voltage_V": voltage,
                             "full_equivalent_gap_um": resolved.equivalent_gap[r] * 1e6,
                             "coupled_equivalent_gap_um": point.equivalent_gap * 1e6,
                             "equivalent_gap_difference": point.equivalent_gap / resolved.equivalent_gap[r] - 1,
                             "full_contact_fraction": resolved.contact_fraction[r],
                             "coupled_contact_fraction": point.contact_fraction,
                             "contact_fraction_difference": point.contact_fraction / resolved.contact_fraction[r] - 1,
                             "coupled_converged": point.converged, "law_seconds": law_seconds,
                             "ridge_seconds": time.perf_counter() - start,
                             "full_seconds_per_point": full_seconds / full.array("seconds").size})
    return rows


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--fast", action="store_true", help="32² patches, one realisation: a smoke run")
    parser.add_argument("--preset", default="draft", choices=("draft", "standard", "reference"))
    parser.add_argument("--realisations", type=int, default=None, help="default: the preset's")
    parser.add_argument("--voltages", type=float, nargs="+", default=[0.0, 100.0, 200.0], help="[V]")
    parser.add_argument("--ridge-grid", type=int, default=64, help="pixels per side of the ridge-scale grid")
    parser.add_argument("--output", default="out", help="output directory (its parent must exist)")
    args, provenance = parse_arguments(parser, argv, "python experiments/scale_coupling.py")
    output = output_directory(args.output)
    voltages = ", ".join(str(v) for v in args.voltages)
    text = f"[loads]\nnormal_forces = [0.5, 2.0]\nvoltages = [{voltages}]\n" + (FAST if args.fast else "")
    if args.realisations is not None:
        text += f"[presets.{args.preset}]\nrealisations = {args.realisations}\n"
    scene = load_scene(text=text, preset="draft" if args.fast else args.preset)
    rows = compare(scene, 16 if args.fast else args.ridge_grid)
    write_csv(output / "scale_coupling.csv", rows, provenance)
    for name in ("equivalent_gap_difference", "contact_fraction_difference"):
        values = np.array([row[name] for row in rows])
        mean, half = confidence_interval(values)
        print(f"{name}: mean {100 * mean:+.1f} % ± {100 * half:.1f} % (95 %), "
              f"largest |.| {100 * np.abs(values).max():.1f} %")
    print(f"law {np.mean([row['law_seconds'] for row in rows]):.1f} s per voltage and realisation, ridge solve "
          f"{np.mean([row['ridge_seconds'] for row in rows]):.2f} s, fully resolved "
          f"{rows[0]['full_seconds_per_point']:.2f} s per point; written to {output}/")
    return rows


if __name__ == "__main__":
    main()
