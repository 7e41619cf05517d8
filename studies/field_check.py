"""The field models of the layered stack against the finite-element field solve (a script).

    python studies/field_check.py      # docs/validation/field_check.md: tables "Sinusoid", "Resolved profiles", "3-D patch"
    python studies/field_check.py --fast          # two sinusoids, 1 µm pixels, 2 N and 200 V: a smoke run

(from the repository root with ``pip install -e ".[fieldcheck]"``). Two tables:

* ``field_check_sinusoid.csv``: the second-order coefficient S of the mean attraction of a sinusoidal gap
  g0 + a cos(2πx/λ), σ̄ = σ_el(g0) + a² S, for λ = 10 µm … 5 mm and g0 = 0.5, 1, 2 µm: the exact result
  (``roughcontact.reference.perturbation``), the FE solve (``roughcontact.reference.fem``,
  Richardson in a from a = 0.05 g0 and 0.1 g0), the layered model with air columns (``solve_field``, the same
  Richardson), with the air's lateral field (``model="layered_air"``) and the per-pixel law (σ_el''/4), each as a
  ratio to the exact S.
* ``field_check_profiles.csv``: the mean attraction over resolved gap profiles, FE against the layered model
  (air columns and ``layered_air``) and the per-pixel law (relative differences, and the equivalent gaps of Eq. 21; the FE's own error as the
  change on a mesh with every length halved): (a) synthetic, a cylinder
  ridge cap with self-affine micro-roughness pressed onto the flat; (b) one period of the default scene's
  ridge with micro-roughness as a 1-D profile; each pressed (``solve_contact`` on a profile grid of shape
  (n, 1), pixels ``--pixel``) at the nominal pressures of 0.5 and 2 N of the default scene, at 0 V (hard
  wall) and 200 V (the per-pixel attraction inside the solve, ``field="parallel_plate"``, so that the gaps do
  not depend on one of the compared models). The attraction is compared at 200 V on every gap
  (all three models scale with U²).
* ``field_check_patch.csv``: the same comparison in 3-D (``field_solve_patch``) over a periodic 32 µm
  self-affine patch (H = 0.8, rms 0.5 µm, wavelengths 2–16 µm) of ``--patch-columns``² pixels pressed on a
  10 MPa half-space at 30 and 100 kPa, with the FE repeated on the gap interpolated to a grid twice as fine.

Every CSV starts with its provenance line.
"""
from __future__ import annotations

import argparse
import time

import numpy as np

from roughcontact import ElasticHalfSpace, ElectrostaticInteraction, solve_contact
from roughcontact.electrostatics import solve_field
from roughcontact.reference.fem import field_solve_patch, field_solve_profile
from roughcontact.reference.perturbation import second_order_attraction
from roughcontact.io import output_directory, parse_arguments, write_csv
from roughcontact.study.apparent import apparent_scale
from roughcontact.study.patch import patch_body, profile_surface
from roughcontact.study.scene import load_scene
from surfaces import Grid, self_affine

WAVELENGTHS = (10e-6, 100e-6, 1e-3, 5e-3)          # [m]
MEAN_GAPS = (0.5e-6, 1e-6, 2e-6)                   # [m]
NORMAL_FORCES = (0.5, 2.0)                         # [N], the default scene's nominal pressures
VOLTAGES = (0.0, 200.0)                            # [V] of the contact solve
COMPARISON_VOLTAGE = 200.0                         # [V] of the compared attraction
#: (a) the synthetic ridge cap: window [m], cap radius [m], roughness rms [m], Hurst exponent, cut-offs [m]
CAP = dict(window=400e-6, radius=200e-6, rms_height=0.5e-6, hurst=0.8, long_cutoff=50e-6, short_cutoff=2e-6)
#: the 3-D patch: a periodic self-affine window [m] pressed on a 10 MPa stratum-corneum-like half-space
PATCH = dict(window=32e-6, rms_height=0.5e-6, hurst=0.8, long_cutoff=16e-6, short_cutoff=2e-6, E_star=1e7)
PATCH_PRESSURES = (3e4, 1e5)                       # [Pa] nominal pressures on the patch


def _second_order(mean_attraction, gap):
    """S from σ̄ at a = 0.05 g0 and 0.1 g0 (Richardson: the a⁴ term removed); ``mean_attraction(a)`` [Pa]."""
    amplitude = 0.05 * gap
    excess = [mean_attraction(a) - mean_attraction(0.0) for a in (amplitude, 2 * amplitude)]
    return (16 * excess[0] - excess[1]) / (12 * amplitude ** 2)


def sinusoid_rows(stack, wavelengths, mean_gaps, columns: int, fem_options: dict) -> list:
    """One row per (λ, g0): S exact and the FE, layered and per-pixel S over it."""
    voltage, rows = COMPARISON_VOLTAGE, []
    for wavelength in wavelengths:
        x = np.arange(columns) * wavelength / columns
        shape = np.cos(2 * np.pi * x / wavelength)
        for gap in mean_gaps:
            exact = float(second_order_attraction(stack, gap, 2 * np.pi / wavelength, voltage))
            start = time.process_time()
            fem = _second_order(lambda a: field_solve_profile(stack, gap + a * shape, wavelength, voltage,
                                                              **fem_options).mean_attraction, gap)
            seconds = time.process_time() - start
            # the air-lateral solve's round-off floor is about 1e-16 q_max d_sc (its stratum-corneum stiffness)
            layered, layered_air = (_second_order(lambda a: solve_field(
                stack, gap + a * shape, wavelength, voltage, model=model, tol=tol).mean_attraction, gap)
                for model, tol in (("layered", 1e-13), ("layered_air", 1e-11)))
            per_pixel = float(stack.attraction_derivative(gap, voltage, 2)) / 4
            rows.append({"wavelength_um": wavelength * 1e6, "mean_gap_um": gap * 1e6, "S_exact_Pa_per_m2": exact,
                         "fem_over_exact": fem / exact, "layered_over_exact": layered / exact,
                         "layered_air_over_exact": layered_air / exact,
                         "per_pixel_over_exact": per_pixel / exact, "fem_columns": columns, "fem_cpu_s": seconds})
    return rows


def _pressed(heights, body, pressure, voltage, stack) -> tuple:
    """``(gap [m], cold start used)`` of ``heights`` pressed at ``pressure`` [Pa] (with the per-pixel attraction
    at ``voltage``). The solver's nested cold start stalls on some of these 1-D profiles (the default scene's
    ridge at 2 N, 0 V, 0.25 µm pixels: a 37 % contact state); then Polonsky and Keer's uniform start is used."""
    interaction = ElectrostaticInteraction(stack, voltage=voltage, field="parallel_plate") if voltage else None
    for cold_start in ("nested", "pk"):        # an option of the hard wall's method (a smooth law's start is nested)
        options = {} if interaction is not None else {"cold_start": cold_start}
        result = solve_contact(heights, body, mean_pressure=pressure, interaction=interaction, warn=False, **options)
        if result.converged:
            return np.asarray(result.gap)[:, 0], cold_start
    raise RuntimeError(f"the contact solve did not converge at {pressure:g} Pa, {voltage:g} V")


def profiles(scene, pixel: float, rng: int) -> dict:
    """{name: (heights (n, 1) [m], grid, body)}: (a) the synthetic cap, (b) one ridge period of the default
    scene's patch across the ridges (:func:`roughcontact.study.patch.profile_surface`)."""
    def grid_of(window):
        n = int(round(window / pixel))
        return Grid((n, 1), (window, window / n), periodic=True)

    cap_grid = grid_of(CAP["window"])
    x = (np.arange(cap_grid.shape[0]) + 0.5) * cap_grid.spacing[0] - CAP["window"] / 2
    cap = np.sqrt(np.maximum(CAP["radius"] ** 2 - x ** 2, 0.0)) - CAP["radius"]
    cap_rough = self_affine(cap_grid, CAP["hurst"], rms_height=CAP["rms_height"], long_cutoff=CAP["long_cutoff"],
                            short_cutoff=CAP["short_cutoff"], rng=rng).heights
    return {"cap": (cap[:, None] + cap_rough, cap_grid, patch_body(scene, grid=cap_grid)),
            "scene_ridge": profile_surface(scene, pixel, realisation=rng)}


def profile_rows(scene, stack, pixel: float, forces, voltages, fem_options: dict, rng: int) -> list:
    """One row per profile, load and solve voltage: mean attraction at 200 V by FE, layered and per pixel."""
    pressures = {force: scale[1][0] for force, scale in zip(scene.loads.normal_forces, apparent_scale(scene))}
    rows, voltage = [], COMPARISON_VOLTAGE
    for name, (heights, grid, body) in profiles(scene, pixel, rng).items():
        length = grid.lengths[0]
        for force in forces:
            for solve_voltage in voltages:
                gap, cold_start = _pressed(heights, body, pressures[force], solve_voltage, stack)
                start = time.process_time()
                fem = field_solve_profile(stack, gap, length, voltage, **fem_options)
                seconds = time.process_time() - start
                # the same piecewise-linear gap on a mesh with every length halved: the FE's own error
                fine_x = np.arange(2 * gap.size) * length / (2 * gap.size)
                fine_gap = np.interp(fine_x, np.arange(gap.size + 1) * length / gap.size, np.append(gap, gap[0]))
                fine = field_solve_profile(stack, fine_gap, length, voltage,
                                           **{key: 2 * value for key, value in fem_options.items()})
                layered = solve_field(stack, gap, length, voltage, tol=1e-12).mean_attraction
                layered_air = solve_field(stack, gap, length, voltage, model="layered_air", tol=1e-11).mean_attraction
                per_pixel = float(np.mean(stack.attraction(gap, voltage)))
                rows.append({
                    "profile": name, "normal_force_N": force, "solve_voltage_V": solve_voltage,
                    "cold_start": cold_start, "pixels": gap.size, "pixel_um": length / gap.size * 1e6,
                    "contact_fraction": np.mean(gap == 0),
                    "mean_gap_um": gap.mean() * 1e6, "fem_Pa": fem.mean_attraction,
                    "fem_maxwell_Pa": fem.mean_maxwell_attraction,
                    "layered_Pa": layered, "per_pixel_Pa": per_pixel,
                    "layered_difference": layered / fem.mean_attraction - 1,
                    "layered_air_difference": layered_air / fem.mean_attraction - 1,
                    "per_pixel_difference": per_pixel / fem.mean_attraction - 1,
                    "fem_equivalent_gap_um": stack.gap_for_attraction(fem.mean_attraction, voltage) * 1e6,
                    "layered_equivalent_gap_um": stack.gap_for_attraction(layered, voltage) * 1e6,
                    "per_pixel_equivalent_gap_um": stack.equivalent_gap(gap) * 1e6,
                    "fem_refined_difference": fine.mean_attraction / fem.mean_attraction - 1,
                    "fem_unknowns": fem.unknowns, "fem_cpu_s": seconds})
    return rows


def _refined(gap):
    """The periodic gap field on a grid twice as fine, interpolated linearly along each axis (the mid-cell
    value the mean of the four corners)."""
    fine = np.empty((2 * gap.shape[0], 2 * gap.shape[1]))
    fine[::2, ::2] = gap
    fine[1::2, ::2] = 0.5 * (gap + np.roll(gap, -1, axis=0))
    fine[:, 1::2] = 0.5 * (fine[:, ::2] + np.roll(fine[:, ::2], -1, axis=1))
    return fine


def patch_rows(stack, columns: int, rng: int) -> list:
    """One row per nominal pressure: the 3-D FE solve over a pressed self-affine patch (``columns``² pixels)
    and on the same gap refined twice (the FE's own error), the layered model and the per-pixel law."""
    window, voltage, rows = PATCH["window"], COMPARISON_VOLTAGE, []
    grid = Grid((columns, columns), (window, window), periodic=True)
    heights = self_affine(grid, PATCH["hurst"], rms_height=PATCH["rms_height"], long_cutoff=PATCH["long_cutoff"],
                          short_cutoff=max(PATCH["short_cutoff"], 2 * grid.spacing[0]), rng=rng)
    body = ElasticHalfSpace(grid, E_star=PATCH["E_star"])
    for pressure in PATCH_PRESSURES:
        result = solve_contact(heights, body, mean_pressure=pressure)
        if not result.converged:
            raise RuntimeError(f"the patch's contact solve did not converge at {pressure:g} Pa")
        gap = np.asarray(result.gap)
        start = time.process_time()
        fem = field_solve_patch(stack, gap, (window, window), voltage)
        seconds = time.process_time() - start
        fine = field_solve_patch(stack, _refined(gap), (window, window), voltage)
        layered = solve_field(stack, gap, (window, window), voltage, tol=1e-12).mean_attraction
        layered_air = solve_field(stack, gap, (window, window), voltage, model="layered_air",
                                  tol=1e-11).mean_attraction
        per_pixel = float(np.mean(stack.attraction(gap, voltage)))
        rows.append({"nominal_pressure_Pa": pressure, "pixels": gap.size, "pixel_um": window / columns * 1e6,
                     "contact_fraction": np.mean(gap == 0), "mean_gap_um": gap.mean() * 1e6,
                     "fem_Pa": fem.mean_attraction, "layered_Pa": layered, "per_pixel_Pa": per_pixel,
                     "layered_difference": layered / fem.mean_attraction - 1,
                     "layered_air_difference": layered_air / fem.mean_attraction - 1,
                     "per_pixel_difference": per_pixel / fem.mean_attraction - 1,
                     "fem_refined_difference": fine.mean_attraction / fem.mean_attraction - 1,
                     "fem_unknowns": fem.unknowns, "fem_refined_unknowns": fine.unknowns, "fem_cpu_s": seconds,
                     "fem_converged": fem.converged and fine.converged})
    return rows


def _differences(row) -> str:
    """The FE mean, its change on refinement and the other models' differences from it, as printed."""
    return (f"FE {row['fem_Pa']:.5g} Pa (refined {100 * row['fem_refined_difference']:+.2f} %), "
            f"layered {100 * row['layered_difference']:+.2f} %, with lateral air "
            f"{100 * row['layered_air_difference']:+.2f} %, per pixel {100 * row['per_pixel_difference']:+.2f} %")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--fast", action="store_true",
                        help="λ = 100 µm and 1 mm at g0 = 1 µm, 64 columns; profiles of 1 µm pixels at 2 N, 200 V")
    parser.add_argument("--pixel", type=float, default=0.25e-6, help="profile pixel [m] (default 0.25 µm)")
    parser.add_argument("--columns", type=int, default=256, help="FE columns per sinusoid wavelength")
    parser.add_argument("--patch-columns", type=int, default=64,
                        help="pixels per side of the 3-D patch (32 µm; its FE is refined to twice that)")
    parser.add_argument("--seed", type=int, default=0, help="rng seed of the micro-roughness")
    parser.add_argument("--output", default="out", help="output directory (its parent must exist)")
    args, provenance = parse_arguments(parser, argv, "python studies/field_check.py")
    output = output_directory(args.output)
    scene = load_scene(preset="draft")
    stack = scene.screen.stack()
    fem_options = dict(air_rows=8, insulator_rows=8, sc_rows=48)
    if args.fast:
        sinusoid = sinusoid_rows(stack, (100e-6, 1e-3), (1e-6,), 64, fem_options)
        rows = profile_rows(scene, stack, 1e-6, (2.0,), (COMPARISON_VOLTAGE,), fem_options, args.seed)
        patch = patch_rows(stack, 16, args.seed)
    else:
        sinusoid = sinusoid_rows(stack, WAVELENGTHS, MEAN_GAPS, args.columns, fem_options)
        rows = profile_rows(scene, stack, args.pixel, NORMAL_FORCES, VOLTAGES, fem_options, args.seed)
        patch = patch_rows(stack, args.patch_columns, args.seed)
    write_csv(output / "field_check_sinusoid.csv", sinusoid, provenance)
    for row in sinusoid:
        print(f"λ {row['wavelength_um']:7.0f} µm  g0 {row['mean_gap_um']:.1f} µm  S/S_exact: FE "
              f"{row['fem_over_exact']:.6f}  layered {row['layered_over_exact']:.6f}  "
              f"with lateral air {row['layered_air_over_exact']:.6f}  "
              f"per pixel {row['per_pixel_over_exact']:.6f}")
    write_csv(output / "field_check_profiles.csv", rows, provenance)
    for row in rows:
        print(f"{row['profile']:12s} {row['normal_force_N']:.1f} N, solved at {row['solve_voltage_V']:3.0f} V: "
              f"{_differences(row)}  (d_eq FE {row['fem_equivalent_gap_um']:.3f} µm, layered "
              f"{row['layered_equivalent_gap_um']:.3f}, per pixel {row['per_pixel_equivalent_gap_um']:.3f})")
    write_csv(output / "field_check_patch.csv", patch, provenance)
    for row in patch:
        print(f"patch {row['pixels']} px at {row['nominal_pressure_Pa'] / 1e3:.0f} kPa, contact "
              f"{100 * row['contact_fraction']:.1f} %: {_differences(row)}")
    print(f"written to {output}/")
    return sinusoid, rows, patch


if __name__ == "__main__":
    main()
