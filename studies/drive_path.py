"""The drive's history: the study's equilibria against a voltage ramped up and back down.

    python studies/drive_path.py --output out          # docs/findings/contact_line.md, "The drive's history"
    python studies/drive_path.py --laws breakdown none parallel_plate --output out
    python studies/drive_path.py --fast                # 256², 2 N, one realisation, 100 and 200 V: seconds

Each study point solves its voltage from the hard wall's contact (the finger touches down, then the voltage comes
on: the ``cold`` branch). A drive reaches its voltage along a ramp instead, and where snap-in leaves several
equilibria a ramp keeps the contact it has pulled in: on the way down more than on the way up
(:func:`~roughcontact.solvers.problem.voltage_path`). On the default scene's patch (standard preset on ``--grid``²
pixels, one ridge period, at the first ring's apparent pressure at each of ``--forces``), for each law of
``--laws`` (``breakdown``: the layered law with air breakdown at its contact lines, the default; ``none``: the plain
layered law; ``parallel_plate``: the per-pixel law, Eq. 21; ``ac``: the layered law under a sinusoidal drive of
RMS voltage U at ``--frequency``, whose field has no breakdown), each realisation 0 … R−1 and each of ``--voltages``:
the cold solve, the ramp ``up`` from the hard wall's equilibrium through the voltages, and the ramp back ``down``
(each step from the last, ``voltage_path``), all to ``--tol``. Prints, per law, the largest |F_el / F_el,cold − 1|
and |ΔA/A0| of each ramp against the cold solves. Writes ``drive_path.csv`` (one row per law, force, realisation,
voltage and branch) with its provenance into ``--output``.
"""
from __future__ import annotations

import argparse
import dataclasses
import os

os.environ.setdefault("ROUGHCONTACT_FFT_THREADS", "1")

from roughcontact import ElectrostaticInteraction, solve_contact, voltage_path
from roughcontact.io import output_directory, parse_arguments, write_csv
from roughcontact.study.patch import default_scene_patch

COLUMNS = ("law", "force_N", "realisation", "voltage_V", "branch", "electrostatic_force_N", "force_over_cold",
           "contact_fraction", "contact_minus_cold", "iterations", "fft_pairs", "converged")
#: the laws compared, as keywords of ElectrostaticInteraction
LAWS = {"breakdown": {}, "none": {"contact_line": None}, "parallel_plate": {"field": "parallel_plate"}, "ac": {}}
BRANCHES = ("cold", "up", "down")


def branch_results(patch, law, voltages, tol):
    """{branch: [ContactResult per voltage]} on ``patch`` (a :class:`~roughcontact.study.patch.ScenePatch`) with the
    electrostatic ``law`` at ``voltages`` [V] (ascending): each cold, the ramp up from the hard wall's equilibrium,
    and the ramp back down (its top voltage solved once, on the way up)."""
    options = dict(mean_pressure=patch.pressure, tol=tol, warn=False)
    hard = solve_contact(patch.surface, patch.body, **options)
    cold = [solve_contact(patch.surface, patch.body, interaction=dataclasses.replace(law, voltage=voltage), **options)
            for voltage in voltages]
    ramp = list(voltage_path(patch.surface, patch.body, list(voltages) + list(voltages[-2::-1]), interaction=law,
                             start=hard, **options))
    up, down = ramp[:len(voltages)], ramp[len(voltages):][::-1] + [ramp[len(voltages) - 1]]
    return {"cold": cold, "up": up, "down": down}


def rows_for(name, force, realisation, args):
    patch, voltages = default_scene_patch(args.grid, force, realisation), sorted(args.voltages)
    drive = {"frequency": args.frequency} if name == "ac" else {}
    law = ElectrostaticInteraction(patch.stack, voltages[-1], **LAWS[name], **drive)
    results = branch_results(patch, law, voltages, args.tol)
    rows = []
    for branch in BRANCHES:
        for voltage, result, cold in zip(voltages, results[branch], results["cold"]):
            rows.append(dict(law=name, force_N=force, realisation=realisation, voltage_V=voltage, branch=branch,
                             electrostatic_force_N=result.electrostatic_force,
                             force_over_cold=result.electrostatic_force / cold.electrostatic_force,
                             contact_fraction=result.contact_fraction,
                             contact_minus_cold=result.contact_fraction - cold.contact_fraction,
                             iterations=result.iterations, fft_pairs=result.solver.fft_pairs,
                             converged=result.converged))
    return rows


def summary(rows) -> dict:
    """{(law, branch): (largest |F_el / F_el,cold − 1|, largest |ΔA/A0|)} over the rows' forces, realisations and
    voltages."""
    worst = {}
    for row in rows:
        key = (row["law"], row["branch"])
        force, contact = worst.get(key, (0.0, 0.0))
        worst[key] = (max(force, abs(row["force_over_cold"] - 1)), max(contact, abs(row["contact_minus_cold"])))
    return worst


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                     formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    parser.add_argument("--grid", type=int, default=256, help="the patch's grid n (n² pixels; the standard preset's)")
    parser.add_argument("--forces", type=float, nargs="+", default=[0.5, 2.0], help="normal forces [N]")
    parser.add_argument("--realisations", type=int, default=4, help="patch realisations 0 … R−1")
    parser.add_argument("--voltages", type=float, nargs="+", default=[25.0, 50, 75, 100, 125, 150, 175, 200],
                        help="the ramp's voltages [V] (> 0)")
    parser.add_argument("--laws", nargs="+", choices=tuple(LAWS), default=["breakdown", "none"])
    parser.add_argument("--frequency", type=float, default=1000.0, help="the drive's frequency [Hz] of the law ac")
    parser.add_argument("--tol", type=float, default=1e-6, help="relative tolerance of every solve")
    parser.add_argument("--fast", action="store_true", help="2 N, one realisation, 100 and 200 V: seconds")
    parser.add_argument("--output", default="out", help="directory for drive_path.csv")
    args, provenance = parse_arguments(parser, argv, "studies/drive_path.py")
    if args.fast:
        args.forces, args.realisations, args.voltages = [2.0], 1, [100.0, 200.0]
    out = output_directory(args.output)
    rows = []
    for name in args.laws:
        for force in args.forces:
            for realisation in range(args.realisations):
                rows += rows_for(name, force, realisation, args)
                print(f"{name:15s} {force:g} N r{realisation}: done", flush=True)
    for (name, branch), (force, contact) in summary(rows).items():
        if branch != "cold":
            print(f"{name:15s} ramp {branch:4s}: |F_el/F_el,cold - 1| <= {force:.2e}, |dA/A0| <= {contact:.2e}")
    write_csv(out / "drive_path.csv", rows, provenance, COLUMNS)
    print(f"wrote {out / 'drive_path.csv'}")


if __name__ == "__main__":
    main()
