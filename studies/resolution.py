"""Resolution near contacts: how the electrostatic attraction F_el and the equivalent gaps converge with the
pixel size, and the discretisation error at each preset's pixel (``docs/guide/presets.md``, "Discretisation error
of F_el and d_eq"; ``docs/findings/contact_line.md`` for the models of the contact line; the plain law's
measured correction in ``docs/dev/investigations.md``; the columns ``fel_error``, ``deq_error`` and
``field_deq_error`` of ``roughcontact/study/preset_errors.csv``).

    python studies/resolution.py --patch-grids 128 256 512 1024 --output out            # docs/guide/presets.md
    python studies/resolution.py --patch-grids 128 256 512 1024 --library --output out  # + preset_errors.csv
    python studies/resolution.py --fast --output out                # 3 pixel sizes, 2 realisations: seconds
    python studies/resolution.py --contact-line breakdown --voltage 100 --output out   # docs/findings/contact_line.md
    python studies/resolution.py --profiles out/resolution_profiles.csv --library --output again   # tables from rows

Profiles: one ridge period of the default scene across the ridges, ridges and micro-roughness
(``roughcontact.study.patch.profile_surface``: the line spectrum of the patch's 2-D roughness, the same
band-limited profile at every pixel), on ``PIXELS_PER_PERIOD`` pixels (3.5 µm down to 0.027 µm, halving), on
the scene's skin (plane strain), pressed at the apparent pressure of 0.5 and 2 N
(``roughcontact.study.apparent``): at 0 V (hard wall) and at 200 V with the layered law and with the per-pixel
law (Eq. 21), each inside its own contact solve. On every solved gap g, at 200 V: F_el/A0 of the layered field
(``solve_field``) and of the per-pixel law, d_eq of Eq. 25 and the field-equivalent gap (the uniform gap with
the layered field's mean attraction). ``--voltage`` sets that voltage, ``--contact-line`` the layered law's model
of the contact line (:func:`roughcontact.electrostatics.contact_line.parse_contact_line`: the layered solve and its
F_el use it; the per-pixel law has none).

Convergence: per point, law and quantity, the mean over the realisations (those whose solves converged at
every pixel) against the pixel h, up to the reference pixel ``REFERENCE_PIXELS`` (0.11 µm), and beyond it
(``beyond_reference``: the largest |f(h)/f_ref − 1| at finer pixels; ``halving_beyond_reference``: the largest
change per halving there). With air breakdown at the contact lines (the default) the layered F_el converges
below the reference too; without a model of the contact line (``--contact-line none``) its contact edges
resolve there structure the plain layered model does not describe (``docs/findings/contact_line.md``), so finer
pixels measure the model's edge error, not a discretisation error. Where the sequence up to the reference is regular (the observed orders
p = log2(Δ_coarse/Δ_fine) of the two finest triples agree within ``ORDER_SPREAD`` and p > 0), the converged
value is Richardson's f_h + (f_h − f_2h)/(2^p − 1) from the finest pair; otherwise the reference pixel's value
stands for it. The error at a preset's pixel is f(h)/f_∞ − 1, with a paired 95 % half-width (1.96 sd/√R of the
realisations' differences from their reference-pixel value, over f_∞). Without a model of the contact line the
layered law's F_el is irregular: single realisations jump between equilibria (neighbouring asperities pulled
into contact or not, contact edges trapped at different pixels) from one pixel to the next.

Measured correction: the factor f_ref/f(h) of the layered F_el at each preset pixel from the even
realisations, applied to the odd ones, and the error left there against their reference-pixel mean.

2-D check (``--patch-grids``, not in ``--fast``): realisation 0's patch (one ridge period, the scene's 10 µm
cut-off at every grid) at 2 N, hard wall and the layered law at 200 V: the same quantities, to set beside the
1-D trend at the same pixels.

Writes ``resolution_profiles.csv`` (one row per realisation, load, solve law and pixel),
``resolution_convergence.csv`` (per point, law and quantity: the means, the order, the converged value, the
error and half-width at each preset pixel), ``resolution_correction.csv`` and ``resolution_patches.csv``;
every CSV starts with its provenance line.
"""
from __future__ import annotations

import argparse
import dataclasses
import math
import os
import time

os.environ.setdefault("ROUGHCONTACT_FFT_THREADS", "1")

import numpy as np

from roughcontact import ElectrostaticInteraction, solve_contact
from roughcontact.electrostatics import solve_field
from roughcontact.electrostatics.contact_line import parse_contact_line
from roughcontact.interactions import DEFAULT_CONTACT_LINE
from roughcontact.io import output_directory, parse_arguments, read_csv, write_csv
from roughcontact.study.apparent import apparent_scale
from roughcontact.study.patch import patch_body, patch_surface, profile_surface
from roughcontact.study.presets import add_resolution_errors
from roughcontact.study.scene import load_scene

#: pixels per ridge period (450 µm): 3.5 µm (draft), 1.76 µm (standard), 0.88 µm (reference) … 0.027 µm
PIXELS_PER_PERIOD = (128, 256, 512, 1024, 2048, 4096, 8192, 16384)
#: the reference pixel, 0.11 µm: the finest at which the layered model describes its contact edges (there the
#: first open pixel's gap about equals the pixel; at finer pixels the crack-like edges, g ≈ A√s, resolve gaps
#: wider than their distance from the contact line, where one air column per pixel and the slope factor
#: 1 + |∇g|²/3 no longer hold; studies/resolution_edges.py); a shorter sequence uses its finest pixel
REFERENCE_PIXELS = 4096
FAST_PIXELS = (128, 256, 512)
#: the presets' patch grids over one ridge period
PRESET_PIXELS = {"draft": 128, "standard": 256, "reference": 512}
NORMAL_FORCES = (0.5, 2.0)          # [N]
FIELD_VOLTAGE = 200.0               # [V] of every compared attraction
#: the solve laws at each solve voltage: the hard wall at 0 V, both field models at 200 V
SOLVES = ((0.0, "hard_wall"), (FIELD_VOLTAGE, "layered"), (FIELD_VOLTAGE, "parallel_plate"))
QUANTITIES = ("fel_layered_Pa", "fel_per_pixel_Pa", "deq_um", "field_deq_um")
#: Richardson is used where the orders of the two finest triples differ by less than this
ORDER_SPREAD = 0.5
TOLERANCE = 1e-8


@dataclasses.dataclass(frozen=True)
class Setting:
    """The voltage [V] of the attractions compared and the layered law's model of the contact line (the library's
    default, air breakdown)."""
    voltage: float = FIELD_VOLTAGE
    contact_line: object = DEFAULT_CONTACT_LINE

    @property
    def solves(self) -> tuple:
        """The solve laws at each solve voltage: the hard wall at 0 V, both field models at ``voltage``."""
        return ((0.0, "hard_wall"), (self.voltage, "layered"), (self.voltage, "parallel_plate"))


def gap_quantities(stack, gap: np.ndarray, length: float, setting: Setting = Setting()) -> dict:
    """At the setting's voltage, on the profile or patch ``gap`` [m] of side ``length`` [m]: the mean attraction of
    the layered field (with the setting's contact line) and of the per-pixel law [Pa], Eq. 25's d_eq and the
    field-equivalent gap [µm]."""
    field = solve_field(stack, gap, length if gap.ndim == 1 else (length, length), setting.voltage, tol=1e-11,
                        contact_line=setting.contact_line)
    return {"fel_layered_Pa": field.mean_attraction,
            "fel_per_pixel_Pa": float(np.mean(stack.attraction(gap, setting.voltage))),
            "deq_um": stack.equivalent_gap(gap) * 1e6, "field_deq_um": field.field_equivalent_gap * 1e6}


def pressed(heights, body, pressure: float, voltage: float, law: str, stack, contact_line=None):
    """``(result, start)``: the contact solve of ``heights`` at ``pressure`` [Pa] under ``law`` at ``voltage``
    [V], with the nested cold start; for the hard wall, where that stalls, again without the K⁻¹
    preconditioner. The preconditioned hard-wall solve stalls on some 1-D profiles at 0 V below 0.25 µm pixels
    (no smaller residual in 200 steps; e.g. realisation 3 at 2 N on 2048 pixels, relative residual 2.5e-4), the
    unpreconditioned one converges (86 steps there). ``contact_line`` is the layered law's."""
    interaction = None if law == "hard_wall" else ElectrostaticInteraction(
        stack, voltage, field=law, contact_line=contact_line if law == "layered" else None)
    starts = [("nested", {})] + ([("unpreconditioned", {"preconditioned": False})] if law == "hard_wall" else [])
    for start, options in starts:
        result = solve_contact(heights, body, mean_pressure=pressure, interaction=interaction, tol=TOLERANCE,
                               warn=False, **options)
        if result.converged:
            break
    return result, start


def profile_rows(scene, pixels, realisations, setting: Setting = Setting()) -> list:
    """One row per realisation, normal force, solve law and pixel count (module docstring)."""
    stack = scene.screen.stack()
    pressures = {force: scale[1][0] for force, scale in zip(scene.loads.normal_forces, apparent_scale(scene))}
    rows = []
    for realisation in range(realisations):
        for n in pixels:
            heights, grid, body = profile_surface(scene, scene.ridges.period / n, realisation)
            for force in NORMAL_FORCES:
                for voltage, law in setting.solves:
                    start = time.process_time()
                    result, start_used = pressed(heights, body, pressures[force], voltage, law, stack,
                                                 setting.contact_line)
                    seconds = time.process_time() - start
                    gap = np.asarray(result.gap)[:, 0]
                    rows.append({"realisation": realisation, "normal_force_N": force, "solve_voltage_V": voltage,
                                 "law": law, "pixels": n, "pixel_um": grid.spacing[0] * 1e6,
                                 "converged": result.converged, "start": start_used,
                                 "iterations": result.iterations, "fft_pairs": result.solver.fft_pairs,
                                 "cpu_s": seconds, "contact_fraction": float(np.mean(gap == 0)),
                                 **gap_quantities(stack, gap, grid.lengths[0], setting)})
    return rows


def stored_rows(path, pixels) -> list:
    """The rows of an earlier run's ``resolution_profiles.csv`` at ``pixels`` (numbers as numbers)."""
    def value(text):
        if text in ("True", "False"):
            return text == "True"
        try:
            return int(text)
        except ValueError:
            try:
                return float(text)
            except ValueError:
                return text
    rows = [{key: value(text) for key, text in row.items()} for row in read_csv(path)]
    return [row for row in rows if row["pixels"] in pixels]


def richardson(values) -> tuple:
    """``(converged value, observed order p or nan, regular)`` of a sequence on pixels halving each step."""
    values = np.asarray(values, dtype=float)
    differences = np.diff(values)
    with np.errstate(divide="ignore", invalid="ignore"):
        orders = np.log2(differences[:-1] / differences[1:])
    finest = orders[-2:] if orders.size >= 2 else orders
    regular = bool(finest.size and np.all(np.isfinite(finest)) and np.all(finest > 0)
                   and np.ptp(finest) < ORDER_SPREAD)
    if not regular:
        return float(values[-1]), float(orders[-1]) if orders.size else math.nan, False
    order = float(finest[-1])
    return float(values[-1] + differences[-1] / (2 ** order - 1)), order, True


def realisation_values(rows, force, law, quantity, pixels) -> np.ndarray:
    """(realisations, pixel counts) of ``quantity`` at ``force`` under ``law``, over the realisations whose
    solves converged at every pixel count."""
    mine = [row for row in rows if row["normal_force_N"] == force and row["law"] == law]
    failed = {row["realisation"] for row in mine if not row["converged"]}
    values = {}
    for row in mine:
        if row["realisation"] not in failed:
            values.setdefault(row["realisation"], {})[row["pixels"]] = row[quantity]
    return np.array([[by_pixels[n] for n in pixels] for _, by_pixels in sorted(values.items())])


def reference_column(pixels) -> int:
    """The column of the reference pixel in ``pixels``: ``REFERENCE_PIXELS``, or the finest below it."""
    return max(index for index, n in enumerate(pixels) if n <= REFERENCE_PIXELS)


def convergence_rows(rows, pixels, solves=SOLVES) -> list:
    """Per normal force, solve law and quantity: the means over the realisations converged at every pixel
    count, the observed order and the converged value up to the reference pixel, at each preset's pixel the
    relative error of the mean and its 95 % half-width (paired over the realisations: the spread of each
    realisation's difference from its reference-pixel value, 1.96 sd/√R, over the converged mean), the largest
    relative change of the mean at pixels finer than the reference (``beyond_reference``) and the largest change
    of the mean per halving of the pixel from the reference on (``halving_beyond_reference``)."""
    table, reference = [], reference_column(pixels)
    for force in NORMAL_FORCES:
        for voltage, law in solves:
            for quantity in QUANTITIES:
                values = realisation_values(rows, force, law, quantity, pixels)
                means = values.mean(axis=0)
                converged, order, regular = richardson(means[:reference + 1])
                beyond = [abs(mean / means[reference] - 1) for mean in means[reference + 1:]]
                halvings = np.abs(means[reference + 1:] / means[reference:-1] - 1)
                entry = {"normal_force_N": force, "solve_voltage_V": voltage, "law": law, "quantity": quantity,
                         "realisations": len(values), "order": order, "richardson": regular,
                         "converged_value": converged, "reference_pixels": pixels[reference],
                         "beyond_reference": max(beyond) if beyond else math.nan,
                         "halving_beyond_reference": float(halvings.max()) if halvings.size else math.nan,
                         **{f"mean_{n}": value for n, value in zip(pixels, means)}}
                for preset, n in PRESET_PIXELS.items():
                    if n in pixels:
                        column = pixels.index(n)
                        entry[f"error_{preset}"] = means[column] / converged - 1
                        differences = values[:, column] - values[:, reference]
                        spread = np.std(differences, ddof=1) if len(values) > 1 else math.nan
                        entry[f"ci_{preset}"] = 1.96 * spread / math.sqrt(len(values)) / abs(converged)
                table.append(entry)
    return table


def correction_rows(rows, pixels) -> list:
    """The measured correction tested out of sample: per normal force and preset pixel, the factor
    f_ref/f(h) of the layered F_el (the layered solve) measured on the even realisations, applied to the odd
    ones, and the error left against their reference-pixel mean."""
    table, reference = [], reference_column(pixels)
    for force in NORMAL_FORCES:
        values = realisation_values(rows, force, "layered", "fel_layered_Pa", pixels)
        train, test = values[0::2].mean(axis=0), values[1::2].mean(axis=0)
        for preset, n in PRESET_PIXELS.items():
            if n in pixels:
                column = pixels.index(n)
                factor = train[reference] / train[column]
                table.append({"normal_force_N": force, "preset": preset, "pixels": n, "factor": factor,
                              "error_uncorrected": test[column] / test[reference] - 1,
                              "error_corrected": factor * test[column] / test[reference] - 1})
    return table


def preset_errors(convergence) -> dict:
    """{pixels per period: (fel_error, deq_error, field_deq_error)}: the largest magnitude of the relative error
    of the realisation mean over the points the study computes with its law (the layered one): F_el and the
    field-equivalent gap at 200 V at both loads, d_eq at 0 and 200 V at both loads."""
    def largest(quantity, laws, preset):
        return max(abs(entry[f"error_{preset}"]) for entry in convergence
                   if entry["quantity"] == quantity and entry["law"] in laws)
    return {n: (largest("fel_layered_Pa", ("layered",), preset),
                largest("deq_um", ("hard_wall", "layered"), preset),
                largest("field_deq_um", ("layered",), preset))
            for preset, n in PRESET_PIXELS.items() if f"error_{preset}" in convergence[0]}


def patch_rows(grids, setting: Setting = Setting()) -> list:
    """The 2-D check: realisation 0's patch (one ridge period, the scene's 10 µm cut-off at every grid: 2
    pixels per cut-off) on ``grids``² pixels at 2 N, hard wall and the layered law at the setting's voltage."""
    rows, base = [], load_scene(preset="reference")
    for grid_points in grids:
        scene = base.with_setting(dataclasses.replace(base.preset, grid=grid_points, pixels_per_cutoff=2.0))
        stack, heights, body = scene.screen.stack(), patch_surface(scene, 0), patch_body(scene)
        grid = body.grid
        pressure = dict(zip(scene.loads.normal_forces, (scale[1][0] for scale in apparent_scale(scene))))[2.0]
        for voltage, law in setting.solves[:2]:
            start = time.process_time()
            result, start_used = pressed(heights, body, pressure, voltage, law, stack, setting.contact_line)
            rows.append({"pixels": grid_points, "pixel_um": grid.spacing[0] * 1e6,
                         "normal_force_N": 2.0, "solve_voltage_V": voltage, "law": law,
                         "converged": result.converged, "start": start_used, "cpu_s": time.process_time() - start,
                         "iterations": result.iterations, "fft_pairs": result.solver.fft_pairs,
                         "contact_fraction": float(np.mean(np.asarray(result.gap) == 0)),
                         **gap_quantities(stack, np.asarray(result.gap, dtype=float), grid.lengths[0], setting)})
    return rows


def summarise(convergence, corrections, patches) -> list:
    lines = ["relative error of the realisation mean at the presets' pixels ± 95 % (1-D profiles; R: Richardson, "
             "order p; *: against the reference pixel; beyond: the largest change at finer pixels)"]
    for entry in convergence:
        errors = "  ".join(f"{preset} {100 * entry[f'error_{preset}']:+6.1f} ± {100 * entry[f'ci_{preset}']:.1f} %"
                           for preset in PRESET_PIXELS if f"error_{preset}" in entry)
        mark = f"R p={entry['order']:.2f}" if entry["richardson"] else f"* p={entry['order']:.2f}"
        lines.append(f"  {entry['normal_force_N']:.1f} N {entry['law']:>14} {entry['quantity']:>16}: "
                     f"{entry['converged_value']:.5g} ({mark}, {entry['realisations']} r)  {errors}  "
                     f"beyond {100 * entry['beyond_reference']:.1f} % (per halving "
                     f"{100 * entry['halving_beyond_reference']:.2f} %)")
    lines.append("measured correction of the layered F_el (even realisations) on the odd ones:")
    for entry in corrections:
        lines.append(f"  {entry['normal_force_N']:.1f} N {entry['preset']:>9}: factor {entry['factor']:.3f}, error "
                     f"{100 * entry['error_uncorrected']:+.1f} % -> {100 * entry['error_corrected']:+.1f} %")
    for row in patches:
        lines.append(f"  2-D {row['pixels']}² {row['law']:>9}: F_el layered {row['fel_layered_Pa']:.4g} Pa, per pixel "
                     f"{row['fel_per_pixel_Pa']:.4g} Pa, d_eq {row['deq_um']:.4f} µm, field d_eq "
                     f"{row['field_deq_um']:.4f} µm, contact {100 * row['contact_fraction']:.2f} %")
    return lines


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--fast", action="store_true", help="128-512 px per period, 2 realisations, no 2-D check")
    parser.add_argument("--realisations", type=int, default=24)
    parser.add_argument("--pixels", type=int, nargs="+", default=list(PIXELS_PER_PERIOD),
                        help="pixels per ridge period, halving the pixel each step (with 128, 256 and 512)")
    parser.add_argument("--patch-grids", type=int, nargs="*", default=list(PRESET_PIXELS.values()),
                        help="pixels per side of the 2-D check (none: skip it)")
    parser.add_argument("--library", action="store_true",
                        help="write fel_error, deq_error, field_deq_error into roughcontact/study/preset_errors.csv")
    parser.add_argument("--voltage", type=float, default=FIELD_VOLTAGE, help="voltage of the attractions [V]")
    parser.add_argument("--contact-line", default="breakdown",
                        help="the layered law's model of the contact line: none, breakdown[:E_bd], "
                             "breakdown-bulk[:E_bd], breakdown-energy[:E_bd], film:<thickness in m>")
    parser.add_argument("--profiles", default=None,
                        help="the resolution_profiles.csv of an earlier run of the same setting: its rows instead of "
                             "new solves (the tables, and with --library the columns, from them)")
    parser.add_argument("--output", default="out", help="output directory (its parent must exist)")
    args, provenance = parse_arguments(parser, argv, "python studies/resolution.py")
    output = output_directory(args.output)
    scene = load_scene()
    setting = Setting(args.voltage, parse_contact_line(args.contact_line))
    pixels = list(FAST_PIXELS if args.fast else args.pixels)
    if args.profiles is None:
        rows = profile_rows(scene, pixels, 2 if args.fast else args.realisations, setting)
    else:
        rows = stored_rows(args.profiles, pixels)
    write_csv(output / "resolution_profiles.csv", rows, provenance)
    convergence = convergence_rows(rows, pixels, setting.solves)
    write_csv(output / "resolution_convergence.csv", convergence, provenance)
    corrections = correction_rows(rows, pixels)
    if corrections:
        write_csv(output / "resolution_correction.csv", corrections, provenance)
    patches = [] if args.fast or args.profiles else patch_rows(args.patch_grids, setting)
    if patches:
        write_csv(output / "resolution_patches.csv", patches, provenance)
    if args.library:
        add_resolution_errors(preset_errors(convergence), scene.ridges.period, provenance)
    print("\n".join(summarise(convergence, corrections, patches)) + f"\nwritten to {output}/")
    return rows, convergence, patches


if __name__ == "__main__":
    main()
