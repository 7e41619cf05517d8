"""The coupled path (roughcontact.study.coupled) against the fully resolved patches of the fingerpad study (a script).

    python studies/scale_coupling.py --preset standard --realisations 3     # docs/findings/equivalent_gap.md
    python studies/scale_coupling.py --fast                                  # 32² patches, 100 V, seconds

(from the repository root after ``pip install -e .``). The default scene at 0.5 and 2 N and the voltages given,
for each realisation r and voltage U: the resolved task (``roughcontact.study.solve_chain``: ridges and
micro-roughness in one grid) and the coupled path (``roughcontact.study.coupled``): an interface law of ``--nodes``
separations built from the same realisation's micro-roughness, and every other node of it, each acting on the
ridges alone on grids of ``--ridge-pixels`` pixels per period (``ridge_chain``). ``--shared-law`` adds one law
per voltage from a micro patch of two periods (another rng seed) acting for every realisation.

Writes ``scale_coupling.csv`` (one row per variant, realisation, load and voltage: d_eq, the real contact
fraction and A_R/A0 of both paths and their relative differences; CPU seconds of the resolved task, the law
and the ridge chain, ``time.process_time`` of this process; the thinned law's is the full law's times its share
of the nodes, an estimate) into ``--output`` and prints, per variant, the
differences per realisation and of the realisation means (95 % Student-t intervals) and the cost ratio.
"""
from __future__ import annotations

import argparse
import dataclasses
import time

import numpy as np

from roughcontact.io import output_directory, parse_arguments, write_csv
from roughcontact.study.coupled import LAW_NODES, RIDGE_PIXELS_PER_PERIOD, interface_law, ridge_chain
from roughcontact.study.patch import closing_lengths, patch_body, patch_grid, roughness_heights
from roughcontact.study.records import confidence_interval
from roughcontact.study.resolved import solve_chain
from roughcontact.study.scene import load_scene

FAST = "[presets.draft]\ngrid = 32\nrealisations = 2\npixels_per_cutoff = 3.0\n[roughness]\nlong_cutoff = 1.5e-4\n"
#: The compared quantities: (record field, CSV name); A_R/A0 at the scene's coarse-graining length.
QUANTITIES = (("equivalent_gap", "equivalent_gap_um"), ("contact_fraction", "contact_fraction"),
              ("ridge_area", "ridge_area_fraction"))
#: rng seed offset of the shared law's micro patch (a patch none of the compared realisations uses).
SHARED_SEED = 1000


def _value(record, name):
    if name == "ridge_area":
        return record.ridge_area_fractions[0]
    return record.equivalent_gap * 1e6 if name == "equivalent_gap" else getattr(record, name)


def _thinned(law):
    """The same law on every other node."""
    columns = ("separations", "tractions", "equivalent_gaps", "contact_fractions", "slopes", "field_equivalent_gaps")
    return dataclasses.replace(law, **{name: getattr(law, name)[::2] for name in columns},
                               ridge_area_fractions=tuple(column[::2] for column in law.ridge_area_fractions))


def _shared_laws(scene, nodes):
    """One law per voltage from a micro patch of two periods on twice the grid (rng seed + SHARED_SEED)."""
    preset = dataclasses.replace(scene.preset, grid=2 * scene.preset.grid, periods=2 * scene.preset.periods)
    large = dataclasses.replace(scene, presets={**scene.presets, scene.study.preset: preset},
                                study=dataclasses.replace(scene.study, seed=scene.study.seed + SHARED_SEED))
    micro, body = roughness_heights(large, 0), patch_body(large)
    laws = {}
    for voltage in scene.loads.voltages:
        start = time.process_time()
        law = interface_law(micro, body, scene.screen.stack(), voltage, nodes=nodes, tol=scene.preset.tolerance,
                            coarse_graining=closing_lengths(scene), field=scene.screen.field)
        laws[voltage] = law, time.process_time() - start
    return laws


def compare(scene, nodes: int, ridge_pixels, shared: bool) -> list:
    """Rows of the resolved and coupled tasks of every realisation and voltage of ``scene``."""
    from surfaces import Grid
    side = patch_grid(scene).lengths
    grids = {n: Grid((n * scene.preset.periods,) * 2, side, periodic=True) for n in ridge_pixels}
    shared_laws = _shared_laws(scene, nodes) if shared else {}
    rows = []
    for r in range(scene.preset.realisations):
        micro, body = roughness_heights(scene, r), patch_body(scene)
        for j, voltage in enumerate(scene.loads.voltages):
            start = time.process_time()
            resolved = solve_chain(scene, r, j)
            resolved_seconds = time.process_time() - start
            start = time.process_time()
            law = interface_law(micro, body, scene.screen.stack(), voltage, nodes=nodes,
                                tol=scene.preset.tolerance, coarse_graining=closing_lengths(scene),
                                field=scene.screen.field)
            law_seconds = time.process_time() - start
            variants = [("own", law, law_seconds, n) for n in ridge_pixels]
            variants.append(("own", _thinned(law), law_seconds * len(law.separations[::2]) / nodes,
                             ridge_pixels[0]))
            if shared:
                variants.append(("shared", *shared_laws[voltage], ridge_pixels[0]))
            for kind, variant, seconds, pixels in variants:
                start = time.process_time()
                coupled = ridge_chain(scene, variant, grid=grids[pixels])
                ridge_seconds = time.process_time() - start
                for force, full, point in zip(scene.loads.normal_forces, resolved, coupled):
                    row = {"law": kind, "law_nodes": len(variant.separations), "ridge_pixels": pixels,
                           "realisation": r, "normal_force_N": force, "voltage_V": voltage}
                    for name, column in QUANTITIES:
                        row[f"full_{column}"] = _value(full, name)
                        row[f"coupled_{column}"] = _value(point, name)
                        row[f"{column}_difference"] = _value(point, name) / _value(full, name) - 1
                    row.update(coupled_converged=point.converged, resolved_cpu_s=resolved_seconds,
                               law_cpu_s=seconds, ridge_cpu_s=ridge_seconds)
                    rows.append(row)
    return rows


def summarise(rows) -> list:
    """Printed lines per variant: differences per realisation and of the realisation means, cost ratio (rows
    as written or as read back from the CSV)."""
    lines = []
    for variant in dict.fromkeys((row["law"], row["law_nodes"], row["ridge_pixels"]) for row in rows):
        chosen = [row for row in rows if (row["law"], row["law_nodes"], row["ridge_pixels"]) == variant]
        lines.append(f"law {variant[0]}, {variant[1]} nodes, ridges {variant[2]} px per period:")
        for _, column in QUANTITIES:
            values = np.array([row[f"{column}_difference"] for row in chosen], dtype=float)
            mean, half = confidence_interval(values)
            # realisation means per (F_N, U): paired differences over the realisations, relative to the mean
            points = dict.fromkeys((row["normal_force_N"], row["voltage_V"]) for row in chosen)
            worst = (0.0, 0.0)
            for point in points:
                pairs = [(row[f"coupled_{column}"], row[f"full_{column}"]) for row in chosen
                         if (row["normal_force_N"], row["voltage_V"]) == point]
                coupled, full = np.array(pairs, dtype=float).T
                difference, spread = confidence_interval(coupled - full)
                relative = (difference / full.mean(), spread / full.mean())
                worst = max(worst, relative, key=lambda pair: abs(pair[0]))
            lines.append(f"  {column}: per realisation mean {100 * mean:+.1f} % ± {100 * half:.1f} %, largest "
                         f"|.| {100 * np.abs(values).max():.1f} %; realisation mean, largest of {len(points)} "
                         f"points {100 * worst[0]:+.1f} % ± {100 * worst[1]:.1f} %")
        chains = {(row["realisation"], row["voltage_V"]): row for row in chosen}.values()
        resolved, law, ridge = (sum(float(row[f"{name}_cpu_s"]) for row in chains)
                                for name in ("resolved", "law", "ridge"))
        coupled = law + ridge
        lines.append(f"  CPU: coupled {coupled:.1f} s (law {law:.1f} s), "
                     f"resolved {resolved:.1f} s, ratio {coupled / resolved:.2f}")
    return lines


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--fast", action="store_true",
                        help="32² patches, two realisations, a 7-node law, 100 V unless --voltages: a smoke run")
    parser.add_argument("--preset", default="draft", choices=("draft", "standard", "reference"))
    parser.add_argument("--realisations", type=int, default=None, help="default: the preset's")
    parser.add_argument("--voltages", type=float, nargs="+", default=None, help="[V] (default: 0 100 200)")
    parser.add_argument("--nodes", type=int, default=LAW_NODES,
                        help="separations of the law (every other one is the second variant)")
    parser.add_argument("--ridge-pixels", type=int, nargs="+", default=[RIDGE_PIXELS_PER_PERIOD, 32, 128],
                        help="ridge-scale pixels per period (the first also for the thinned and shared laws)")
    parser.add_argument("--shared-law", action="store_true",
                        help="also one law per voltage from a two-period micro patch, for every realisation")
    parser.add_argument("--output", default="out", help="output directory (its parent must exist)")
    args, provenance = parse_arguments(parser, argv, "python studies/scale_coupling.py")
    output = output_directory(args.output)
    voltages = args.voltages or ([100.0] if args.fast else [0.0, 100.0, 200.0])   # a 0 V law costs most
    voltages = ", ".join(str(v) for v in voltages)
    text = f"[loads]\nnormal_forces = [0.5, 2.0]\nvoltages = [{voltages}]\n" + (FAST if args.fast else "")
    scene = load_scene(text=text, preset="draft" if args.fast else args.preset)
    if args.realisations is not None:
        scene = dataclasses.replace(scene, presets={**scene.presets, scene.study.preset: dataclasses.replace(
            scene.preset, realisations=args.realisations)})
    pixels = [16, 32] if args.fast else args.ridge_pixels
    rows = compare(scene, 7 if args.fast else args.nodes, pixels, args.shared_law)
    write_csv(output / "scale_coupling.csv", rows, provenance)
    print("\n".join(summarise(rows)) + f"\nwritten to {output}/")
    return rows


if __name__ == "__main__":
    main()
