"""How the study's F_el depends on the breakdown field of air breakdown at the contact lines, the default model's one
parameter (``docs/findings/contact_line.md``, "How far the model moves F_el"; ``docs/findings/measured_fingertip.md``).

    python studies/breakdown_field.py --output out            # draft preset, 0.5 / 1 / 2 N at 100 and 200 V
    python studies/breakdown_field.py --fast --output out     # 32² patches: seconds

E_bd = 350 V/µm is the mean breakdown field measured in air gaps of 0.1–1 µm between metals (Peschot et al. 2014,
``docs/references.md`` §14); the model extrapolates it down to contact. The study solves the default scene on the
draft preset with ``[screen] contact_line = "breakdown:<E_bd>"`` at each of ``FIELDS`` and, for comparison, the plain
layered field (``"none"``), and prints F_el/F_N (realisation means) and F_el over its value at 350 V/µm. Writes
``breakdown_field.csv`` into ``--output``.
"""
from __future__ import annotations

import argparse

import numpy as np

from roughcontact.electrostatics import AIR_BREAKDOWN_FIELD
from roughcontact.io import output_directory, parse_arguments, write_csv
from roughcontact.study import load_scene, run_study

#: Breakdown fields [V/m]: half and twice the measured 350 V/µm, four times it (towards the several V/nm that
#: vacuum nano-gaps between metals hold, Lyon & Hubler 2013).
FIELDS = (0.5 * AIR_BREAKDOWN_FIELD, AIR_BREAKDOWN_FIELD, 2 * AIR_BREAKDOWN_FIELD, 4 * AIR_BREAKDOWN_FIELD)
NORMAL_FORCES = (0.5, 1.0, 2.0)         # N
VOLTAGES = (100.0, 200.0)               # V RMS


def scene_text(contact_line: str, fast: bool) -> str:
    """The default scene at :data:`NORMAL_FORCES` and :data:`VOLTAGES` with ``contact_line``, draft preset."""
    text = (f"[loads]\nnormal_forces = {list(NORMAL_FORCES)}\nvoltages = {list(VOLTAGES)}\n"
            f"[screen]\ncontact_line = \"{contact_line}\"\n[study]\npreset = \"draft\"\n")
    return text + ("[presets.draft]\ngrid = 32\nrealisations = 2\npixels_per_cutoff = 3.0\n" if fast else "")


def electrostatic_ratio(result) -> np.ndarray:
    """F_el/F_N per (load, voltage), the mean over the realisations."""
    force = result.array("apparent_area")[..., None] * result.array("electrostatic_attraction")
    return np.nanmean(force, axis=-1) / np.asarray(result.normal_forces)[:, None]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true", help="32² patches, two realisations")
    parser.add_argument("--output", default="out", help="output directory (its parent must exist)")
    args, provenance = parse_arguments(parser, argv, "studies/breakdown_field.py")
    directory = output_directory(args.output)
    models = {f"breakdown:{field:g}": field for field in FIELDS} | {"none": np.inf}
    ratios = {name: electrostatic_ratio(run_study(load_scene(text=scene_text(name, args.fast)), workers=1))
              for name in models}
    reference = ratios[f"breakdown:{AIR_BREAKDOWN_FIELD:g}"]
    rows = [{"contact_line": name, "breakdown_field_V_per_um": field / 1e6, "normal_force_N": force,
             "voltage_V": voltage, "fel_over_fn": ratios[name][i, j],
             "fel_over_350": ratios[name][i, j] / reference[i, j]}
            for name, field in models.items() for i, force in enumerate(NORMAL_FORCES)
            for j, voltage in enumerate(VOLTAGES)]
    write_csv(directory / "breakdown_field.csv", rows, provenance)
    print("F_el/F_N (F_el over its value at 350 V/um) at " + ", ".join(f"{f:g} N" for f in NORMAL_FORCES))
    for name in models:
        for j, voltage in enumerate(VOLTAGES):
            cells = "  ".join(f"{ratios[name][i, j]:.3f} ({ratios[name][i, j] / reference[i, j]:.2f})"
                              for i in range(len(NORMAL_FORCES)))
            print(f"{name:18s} {voltage:5.0f} V  {cells}")


if __name__ == "__main__":
    main()
