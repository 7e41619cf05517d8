"""The layered law at its contact edges: why its own contact solve does not converge with the pixel without a model
of the contact line, and what each model does (``docs/findings/contact_line.md``; ``docs/dev/investigations.md``,
"The layered law at contact edges", for the plain law).

    python studies/resolution_edges.py --output out          # every table (minutes), air breakdown (the default)
    python studies/resolution_edges.py --contact-line none --output out   # the plain layered law
    python studies/resolution_edges.py --fast --output out   # two pixels, one realisation: seconds
    python studies/resolution_edges.py --contact-line breakdown --output out   # docs/findings/contact_line.md
    python studies/resolution_edges.py --only strip fem cylinder --contact-line film:1e-7 --output out

``--contact-line`` gives the layered law a model of the contact line
(:func:`roughcontact.electrostatics.contact_line.parse_contact_line`): every layered solve and field below uses it,
the finite-element strip the same deposited-charge condition (air breakdown) or the same shifted gap (a film).

Six measurements, each a CSV (with the band of the layered F_el that they give):

* ``resolution_edges_zones.csv``: the cohesive (process) zone ℓ = (π/4) E* w / σ0² of a Dugdale-like edge
  (``zone_length``) for the per-pixel law (σ0 = ε0 U²/(2 c²), w = ε0 U²/(2 c), c = d_sc/ε_sc + d_i/ε_i), for
  the layered law at a wide contact (the stratum corneum an equipotential: c → h_i = d_i/ε_i) and for it with air
  breakdown (σ0 = ε0 E_bd²/2, w its work over the broken gaps g < U/E_bd − h_i and Eq. 22 beyond), with the skin
  layer's E* (the contact spots are far narrower than the layer).
* ``resolution_edges_strip.csv``: ``solve_field`` on FIXED gap fields with one contact strip (a periodic
  ``STRIP_WINDOW`` with a strip of ``STRIP_WIDTH``), the gap opening from its edges like an adhesive (crack-like)
  contact, g = A √s + s²/(2R), or like a Hertz contact, g = B (s/s0)^{3/2} + s²/(2R) (s the distance from the
  edge), on pixels from 0.5 µm down to 0.5 nm: F_el/A0 and its contact-pixel part, σ_el of the last contact
  pixel and of the first open one and the air field there (D_a/(ε0 f) along its tilted column); on the crack-like strip down to 3.9 nm also with the
  air's lateral field (``model="layered_air"``).
* ``resolution_edges_fem.csv``: both strips with the finite-element field
  (``roughcontact.reference.fem.field_solve_profile``, optional extra ``fieldcheck``; ``--no-fem`` skips
  it) on columns graded towards the contact lines (``graded_positions``: ``FEM_FINEST`` at the lines, growing by
  15 % per column to 0.1 µm) with the insulator's rows graded from its face as finely (``FEM_INSULATOR_ROWS``),
  so that no cell shears where the crack-like gap rises steeply: the independent reference of the strips' F_el.
* ``resolution_edges_fem_profiles.csv``: the layered field against the finite elements (graded columns, the same
  model of the contact line) on the gaps that the layered law's own solves reach on realisation 0's profile at
  0.11 µm pixels, 0.5 and 2 N, 100 and 200 V.
* ``resolution_edges_cylinder.csv``: the clean model problem, one contact per period (parabolic cylinders of
  ``CYLINDER_RADIUS`` every ``CYLINDER_PERIOD`` at ``CYLINDER_PRESSURE``, the scene's skin and stack), with the
  layered and the per-pixel law, cold and from the next coarser pixel's equilibrium, 156 … 9.8 nm pixels: F_el/A0,
  the contact width and Π/A0.
* ``resolution_edges_profile.csv``: realisation 0 of the default scene's profile (``studies/resolution.py``) at
  0.5 N and 200 V, the layered law's own cold solve on 1024 … 32768 pixels per period: F_el/A0, the contact
  fraction, F_el/A0 of the same solve to a tolerance of 1e-12, and, averaged over the contact spots' edges, the gap of the first open pixel, σ_el of the last
  contact pixel, the gap at ``EDGE_DISTANCES`` outside and σ_el at the same distances inside.
* ``resolution_edges_paths.csv``: per realisation, load and pixel, the layered solve started cold (the
  default: the field solves' tolerance adapted to the step), cold with the field solves at a fixed 1e-12
  (``fixed_field_tolerance``), and warm from the next coarser pixel's solution (its gap interpolated
  linearly): F_el/A0, the contact fraction and the total energy Π/A0 = (U_el + ∫V dA)/A0 + P̄ ⟨g⟩ of each
  equilibrium; ``resolution_edges_band.csv``: per load and pixel, the mean F_el/A0 of the cold solves and of
  the lowest-energy equilibrium any path reached, and the cold solves' excess over it; printed: the band
  (``model_band``) of the layered F_el about the cold solves at the 0.11 µm reference pixel.

Every CSV starts with its provenance line.
"""
from __future__ import annotations

import argparse
import contextlib
import dataclasses
import math
import os

os.environ.setdefault("ROUGHCONTACT_FFT_THREADS", "1")

import numpy as np

from roughcontact import ElectrostaticInteraction, solve_contact
from roughcontact.electrostatics import EPSILON_0, AirBreakdown, RoughnessFilm, StackField, solve_field
from roughcontact.electrostatics.contact_line import parse_contact_line
from roughcontact.io import output_directory, parse_arguments, write_csv
from roughcontact.solvers import projected_cg_gap
from roughcontact.study.apparent import apparent_scale
from roughcontact.study.patch import patch_body, profile_surface
from roughcontact.study.scene import load_scene
from surfaces import Grid

VOLTAGE = 200.0                     # [V]
TOLERANCE = 1e-8                    # the contact solves' relative tolerance (studies/resolution.py)
#: the fixed-gap strip: periodic window, contact strip width, crack opening A [m^½], Hertz opening B at s0,
#: and the curvature radius R of the far gap [m]
STRIP_WINDOW, STRIP_WIDTH = 20e-6, 4e-6
CRACK_OPENING = 3.2e-4              # g ≈ A √s: the layered solves' edges (resolution_edges_profile.csv)
HERTZ_OPENING, HERTZ_LENGTH = 0.1e-6, 2e-6
STRIP_RADIUS = 50e-6
STRIP_PIXELS = tuple(40 * 2 ** k for k in range(14))       # 500 nm … 0.06 nm
#: the finite-element strips: the columns' spacing at the contact lines [m] (graded to 0.1 µm away from them) and
#: the insulator's rows, graded from its face at that spacing
FEM_FINEST = (50e-9, 20e-9, 8e-9, 3e-9, 1e-9)
FEM_COARSEST, FEM_RATIO, FEM_INSULATOR_ROWS = 0.1e-6, 1.15, 40
AIR_STRIP_PIXELS = 5120             # 3.9 nm: the finest strip solved with the air's lateral field too
PROFILE_PIXELS = (1024, 2048, 4096, 8192, 16384, 32768)   # 0.44 µm … 0.014 µm over the 450 µm period
EDGE_DISTANCES = (0.02e-6, 0.05e-6, 0.1e-6, 0.2e-6, 0.5e-6, 1e-6)   # [m] from a contact edge
PATH_PIXELS = (1024, 2048, 4096, 8192, 16384)
#: the clean model problem: a periodic row of parabolic cylinders (period, radius [m]) at a mean pressure [Pa]
CYLINDER_PERIOD, CYLINDER_RADIUS, CYLINDER_PRESSURE = 20e-6, 5e-6, 1e3
CYLINDER_PIXELS = (128, 256, 512, 1024, 2048)             # 156 nm … 9.8 nm
REFERENCE_PIXELS = 4096             # 0.11 µm, the reference pixel of studies/resolution.py
NORMAL_FORCES = (0.5, 2.0)          # [N]


def zone_length(E_star: float, work: float, strength: float) -> float:
    """ℓ = (π/4) E* w / σ0² [m]: the Dugdale zone at the edge of an adhesive contact (JKR limit: K² = 2 E* w,
    ℓ = π K² / (8 σ0²)) for work of adhesion ``work`` [J/m²] and cohesive stress ``strength`` [Pa]."""
    return math.pi / 4 * E_star * work / strength ** 2


def zone_rows(scene, breakdown=AirBreakdown()) -> list:
    """The cohesive-zone estimate of both laws at ``VOLTAGE``, and of the layered law at a wide contact with air
    ``breakdown`` (module docstring)."""
    stack, E_star = scene.screen.stack(), scene.skin.layer_E_star
    rows = []
    for law, thickness in (("per_pixel", stack.dielectric_offset), ("layered_wide_contact", stack.d_i / stack.eps_i)):
        work = EPSILON_0 * VOLTAGE ** 2 / (2 * thickness)
        strength = EPSILON_0 * VOLTAGE ** 2 / (2 * thickness ** 2)
        rows.append({"law": law, "thickness_um": thickness * 1e6, "E_star_Pa": E_star, "work_J_m2": work,
                     "strength_MPa": strength / 1e6, "zone_um": zone_length(E_star, work, strength) * 1e6})
    thickness = stack.d_i / stack.eps_i
    broken = max(VOLTAGE / breakdown.field - thickness, 0.0)          # the gaps below break down
    work = breakdown.stress * broken + EPSILON_0 * VOLTAGE ** 2 / (2 * (thickness + broken))
    rows.append({"law": "layered_breakdown", "thickness_um": thickness * 1e6, "E_star_Pa": E_star, "work_J_m2": work,
                 "strength_MPa": breakdown.stress / 1e6,
                 "zone_um": zone_length(E_star, work, breakdown.stress) * 1e6})
    return rows


def strip_gap(kind: str, n: int) -> np.ndarray:
    """The fixed strip gap [m] on ``n`` pixels of ``STRIP_WINDOW`` (pixel centres; module docstring)."""
    return strip_opening(kind, (np.arange(n) + 0.5) * STRIP_WINDOW / n - STRIP_WINDOW / 2)


def strip_opening(kind: str, x: np.ndarray) -> np.ndarray:
    """The fixed strip gap [m] at the positions ``x`` [m] from the window's centre (module docstring)."""
    s = np.maximum(np.abs(x) - STRIP_WIDTH / 2, 0.0)
    opening = CRACK_OPENING * np.sqrt(s) if kind == "crack" else HERTZ_OPENING * (s / HERTZ_LENGTH) ** 1.5
    return opening + s * s / (2 * STRIP_RADIUS)


def strip_rows(stack, pixels, contact_line=None) -> list:
    """F_el/A0 of the layered field on the fixed strip gaps against the pixel (module docstring), and on the
    crack-like strip down to ``AIR_STRIP_PIXELS`` the same with the air's lateral field (``model="layered_air"``;
    a film's shifted gap, no air breakdown)."""
    rows = []
    lateral_air = not isinstance(contact_line, AirBreakdown)
    for kind in ("crack", "hertz"):
        for n in pixels:
            gap = strip_gap(kind, n)
            field = solve_field(stack, gap, STRIP_WINDOW, VOLTAGE, tol=1e-12, contact_line=contact_line)
            contact = gap == 0
            air = (solve_field(stack, gap, STRIP_WINDOW, VOLTAGE, model="layered_air", tol=1e-10,
                               contact_line=contact_line)
                   if kind == "crack" and n <= AIR_STRIP_PIXELS and lateral_air else None)
            first_open = np.flatnonzero(~contact & np.roll(contact, 1))[0]      # the open pixel beside a line
            factor = StackField(stack, Grid((n, 1), (STRIP_WINDOW, STRIP_WINDOW / n))).slope_factor(gap[:, None])[:, 0]
            rows.append({"opening": kind, "pixels": n, "pixel_nm": STRIP_WINDOW / n * 1e9,
                         "fel_kPa": field.mean_attraction / 1e3,
                         "fel_contact_kPa": float(field.attraction[contact].sum()) / n / 1e3,
                         "edge_sigma_MPa": float(field.attraction[contact].max()) / 1e6,
                         "open_sigma_MPa": float(field.attraction[first_open]) / 1e6,
                         "open_field_V_um": float((field.flux[first_open] - (0.0 if field.charge is None else
                                                   field.charge[first_open])) / (EPSILON_0 * factor[first_open]))
                         / 1e6,
                         "fel_lateral_air_kPa": "" if air is None else air.mean_attraction / 1e3,
                         "edge_sigma_lateral_air_MPa": "" if air is None else float(air.attraction[contact].max()) / 1e6})
    return rows


@contextlib.contextmanager
def fixed_field_tolerance(tol: float):
    """The layered law's field solves at ``tol`` throughout a contact solve instead of the solver's adaptive
    tolerance (0.1 × its residual, within [1e-12, 1e-2] until a trial step is rejected and [1e-12, 1e-4] from then
    on): the solver's module bounds pinned while inside."""
    names = ("FIELD_TOL_FLOOR", "FIELD_TOL_CEILING", "FIELD_TOL_START")
    bounds = tuple(getattr(projected_cg_gap, name) for name in names)
    for name in names:
        setattr(projected_cg_gap, name, tol)
    try:
        yield
    finally:
        for name, bound in zip(names, bounds):
            setattr(projected_cg_gap, name, bound)


def fem_strip_rows(stack, finest=FEM_FINEST, contact_line=None) -> list:
    """F_el/A0 of the finite-element field on both strips (``field_solve_profile`` on columns graded towards the
    contact lines, ``finest`` [m] there, the insulator's rows graded from its face; module docstring) with the
    same model of the contact line: the independent reference of :func:`strip_rows` (optional extra
    ``fieldcheck``)."""
    from roughcontact.reference.fem import field_solve_profile, graded_positions
    shift = contact_line.thickness if isinstance(contact_line, RoughnessFilm) else 0.0
    breakdown = contact_line if isinstance(contact_line, AirBreakdown) else None
    rows = []
    for kind in ("crack", "hertz"):
        for spacing in finest:
            positions = graded_positions(STRIP_WINDOW, (STRIP_WINDOW - STRIP_WIDTH) / 2 + np.array([0.0, STRIP_WIDTH]),
                                         spacing, FEM_COARSEST, FEM_RATIO)
            solution = field_solve_profile(stack, strip_opening(kind, positions - STRIP_WINDOW / 2) + shift,
                                           STRIP_WINDOW, VOLTAGE, positions=positions,
                                           insulator_rows=FEM_INSULATOR_ROWS, insulator_first=spacing,
                                           breakdown=breakdown)
            rows.append({"opening": kind, "finest_nm": spacing * 1e9, "columns": positions.size,
                         "fel_kPa": solution.mean_attraction / 1e3,
                         "fel_maxwell_kPa": solution.mean_maxwell_attraction / 1e3, "converged": solution.converged})
    return rows


def contact_edges(gap: np.ndarray, length: float) -> np.ndarray:
    """The contact lines [m] of a periodic profile ``gap`` on pixels of ``length``/n: the pixel edges between a
    contact pixel (g = 0) and an open one."""
    contact = gap == 0
    spacing = length / gap.size
    ends = np.flatnonzero(contact & ~np.roll(contact, -1))           # the last contact pixel of a spot
    starts = np.flatnonzero(contact & ~np.roll(contact, 1))          # the first one
    return np.concatenate([(ends + 1) * spacing, starts * spacing]) % length


def fem_profile_rows(scene, contact_line, pixels: int = 4096, voltages=(100.0, VOLTAGE), realisation: int = 0) -> list:
    """The layered field with ``contact_line`` against the finite-element field with the same condition on the
    gaps that the layered law's own solves reach on realisation 0's profile at both loads and ``voltages`` [V]
    (``pixels`` per period): the finite elements on columns graded towards the solved contact lines (``FEM_FINEST``'s
    coarsest entry there, 0.25 µm away from them, the insulator's rows graded from its face), the gap interpolated
    linearly between the pixel centres."""
    from roughcontact.reference.fem import field_solve_profile, graded_positions
    shift = contact_line.thickness if isinstance(contact_line, RoughnessFilm) else 0.0
    breakdown = contact_line if isinstance(contact_line, AirBreakdown) else None
    stack, rows = scene.screen.stack(), []
    for voltage in voltages:
        for force in NORMAL_FORCES:
            result, grid = layered_solve(scene, pixels, realisation, force, contact_line=contact_line,
                                         voltage=voltage)
            gap, length = np.asarray(result.gap)[:, 0], grid.lengths[0]
            columns = solve_field(stack, gap, length, voltage, tol=1e-12, contact_line=contact_line)
            positions = graded_positions(length, contact_edges(gap, length), FEM_FINEST[0], 0.25e-6, FEM_RATIO)
            centres = (np.arange(gap.size + 1) + 0.5) * length / gap.size
            sampled = np.interp(np.mod(positions - centres[0], length) + centres[0], centres, np.append(gap, gap[0]))
            fem = field_solve_profile(stack, sampled + shift, length, voltage, positions=positions,
                                      insulator_rows=FEM_INSULATOR_ROWS, insulator_first=FEM_FINEST[0],
                                      breakdown=breakdown)
            rows.append({"voltage_V": voltage, "normal_force_N": force, "pixels": pixels,
                         "contact_fraction": result.contact_fraction, "columns": positions.size,
                         "fel_kPa": columns.mean_attraction / 1e3, "fem_fel_kPa": fem.mean_attraction / 1e3,
                         "difference": columns.mean_attraction / fem.mean_attraction - 1, "fem_converged": fem.converged})
    return rows


def cylinder_rows(scene, pixels, contact_line=None) -> list:
    """A single contact per period, the layered law (with ``contact_line``) and the per-pixel law: cold solves and
    solves started from the next coarser pixel's equilibrium, on the scene's skin (plane strain) and stack at
    ``VOLTAGE``: F_el/A0 [kPa], the contact width [µm] and Π/A0 [J/m²]."""
    stack, rows = scene.screen.stack(), []
    for law in ("layered", "parallel_plate"):
        interaction = ElectrostaticInteraction(stack, VOLTAGE, field=law,
                                               contact_line=contact_line if law == "layered" else None)
        coarser = None
        for n in pixels:
            grid = Grid((n, 1), (CYLINDER_PERIOD, CYLINDER_PERIOD / n), periodic=True)
            x = (np.arange(n) + 0.5) * CYLINDER_PERIOD / n - CYLINDER_PERIOD / 2
            heights, body = (-x * x / (2 * CYLINDER_RADIUS))[:, None], patch_body(scene, grid=grid)
            cold = solve_contact(heights, body, mean_pressure=CYLINDER_PRESSURE, interaction=interaction,
                                 tol=TOLERANCE, warn=False)
            starts = {"cold": cold}
            if coarser is not None:
                start = dataclasses.replace(cold, gap=interpolated_gap(coarser, n))
                starts["warm_from_coarser"] = solve_contact(heights, body, mean_pressure=CYLINDER_PRESSURE,
                                                            interaction=interaction, tol=TOLERANCE, warn=False,
                                                            x0=start)
            for path, result in starts.items():
                values = equilibrium(scene, result, grid, contact_line)[0]
                rows.append({"law": law, "pixels": n, "pixel_nm": grid.spacing[0] * 1e9, "path": path, **values,
                             "contact_um": result.contact_fraction * CYLINDER_PERIOD * 1e6})
            coarser = starts.get("warm_from_coarser", cold)
    return rows


def layered_solve(scene, pixels: int, realisation: int, force: float, x0=None, tol: float = TOLERANCE,
                  contact_line=None, voltage: float = VOLTAGE):
    """``(result, grid)``: the layered law's contact solve (with ``contact_line``, at ``voltage`` [V]) of the profile
    at ``force`` [N] (apparent pressure) to the relative tolerance ``tol``."""
    stack = scene.screen.stack()
    pressure = dict(zip(scene.loads.normal_forces, (scale[1][0] for scale in apparent_scale(scene))))[force]
    heights, grid, body = profile_surface(scene, scene.ridges.period / pixels, realisation)
    result = solve_contact(heights, body, mean_pressure=pressure,
                           interaction=ElectrostaticInteraction(stack, voltage, contact_line=contact_line),
                           tol=tol, warn=False, x0=x0)
    return result, grid


def equilibrium(scene, result, grid, contact_line=None) -> dict:
    """F_el/A0 [kPa] (the layered field with ``contact_line`` on the solved gap), the contact fraction and Π/A0
    [J/m²] (with air breakdown: the solve's merit in place of the interaction energy, which it has not)."""
    gap = np.asarray(result.gap)[:, 0]
    field = solve_field(scene.screen.stack(), gap, grid.lengths[0], VOLTAGE, tol=1e-12, contact_line=contact_line)
    energy = (result.elastic_energy + result.interaction_energy) / grid.area + result.mean_pressure * result.mean_gap
    return {"converged": result.converged, "iterations": result.iterations, "fel_kPa": field.mean_attraction / 1e3,
            "contact_fraction": result.contact_fraction, "energy_J_m2": energy}, gap, field.attraction


def edge_measures(gap: np.ndarray, pressure: np.ndarray, spacing: float) -> dict:
    """Averaged over the edges of the contact spots of a periodic profile: the gap of the first open pixel
    [nm], σ_el of the last contact pixel [MPa], and the gap [nm] / σ_el [MPa] at ``EDGE_DISTANCES`` outside /
    inside (the pixel nearest that distance)."""
    contact = gap == 0
    n = gap.size
    edges = [(index, +1) for index in np.flatnonzero(contact & ~np.roll(contact, -1))]      # contact ends
    edges += [(index, -1) for index in np.flatnonzero(contact & ~np.roll(contact, 1))]      # contact starts
    measures = {"edges": len(edges),
                "first_gap_nm": np.mean([gap[(i + side) % n] for i, side in edges]) * 1e9,
                "edge_sigma_MPa": np.mean([pressure[i] for i, _ in edges]) / 1e6}
    for distance in EDGE_DISTANCES:
        steps = max(1, int(round(distance / spacing)))
        label = f"{distance * 1e6:g}um"
        measures[f"gap_{label}_nm"] = np.mean([gap[(i + side * steps) % n] for i, side in edges]) * 1e9
        measures[f"sigma_{label}_MPa"] = np.mean([pressure[(i - side * (steps - 1)) % n] for i, side in edges]) / 1e6
    return measures


def profile_rows(scene, pixels, contact_line=None) -> list:
    """The edges of realisation 0's layered solve at 0.5 N against the pixel (module docstring), and F_el of the
    same solve to a tolerance of 1e-12 instead of 1e-8."""
    rows = []
    for n in pixels:
        result, grid = layered_solve(scene, n, 0, 0.5, contact_line=contact_line)
        values, gap, pressure = equilibrium(scene, result, grid, contact_line)
        tight, _ = layered_solve(scene, n, 0, 0.5, tol=1e-12, contact_line=contact_line)
        rows.append({"pixels": n, "pixel_nm": grid.spacing[0] * 1e9, **values,
                     "fel_kPa_tol_1e-12": equilibrium(scene, tight, grid, contact_line)[0]["fel_kPa"],
                     **edge_measures(gap, pressure, grid.spacing[0])})
    return rows


def interpolated_gap(result, pixels: int) -> np.ndarray:
    """``result``'s periodic profile gap [m] interpolated linearly onto ``pixels``, shaped (pixels, 1)."""
    gap = np.asarray(result.gap)[:, 0]
    coarse = np.arange(gap.size + 1) * pixels / gap.size
    fine = np.interp(np.arange(pixels), coarse, np.append(gap, gap[0]))[:, None]
    return fine


def path_rows(scene, pixels, realisations, contact_line=None) -> list:
    """Cold, fixed-field-tolerance and warm-from-coarser solves per realisation, load and pixel."""
    rows = []
    for realisation in range(realisations):
        for force in NORMAL_FORCES:
            coarser = None
            for n in pixels:
                cold, grid = layered_solve(scene, n, realisation, force, contact_line=contact_line)
                with fixed_field_tolerance(1e-12):
                    fixed, _ = layered_solve(scene, n, realisation, force, contact_line=contact_line)
                starts = {"cold": cold, "fixed_field_tolerance": fixed}
                if coarser is not None:
                    # the smooth solver starts from a ContactResult's gap and reads nothing else of it
                    start = dataclasses.replace(cold, gap=interpolated_gap(coarser, n))
                    starts["warm_from_coarser"], _ = layered_solve(scene, n, realisation, force, x0=start,
                                                                   contact_line=contact_line)
                for path, result in starts.items():
                    rows.append({"realisation": realisation, "normal_force_N": force, "pixels": n,
                                 "pixel_um": grid.spacing[0] * 1e6, "path": path,
                                 **equilibrium(scene, result, grid, contact_line)[0]})
                coarser = starts.get("warm_from_coarser", cold)
    return rows


def band_rows(paths) -> list:
    """Per load and pixel: the mean F_el/A0 [kPa] of the cold solves and of the lowest-energy equilibrium each
    realisation reached by any path, the cold solves' excess over the lowest (a fraction) and the paths' spread,
    the mean over the realisations of (largest − smallest F_el of its paths)/cold F_el (with air breakdown the only
    measure of path dependence: its solves have no energy to rank them)."""
    table = []
    for force in NORMAL_FORCES:
        for n in sorted({row["pixels"] for row in paths}):
            by_realisation = {}
            for row in paths:
                if row["normal_force_N"] == force and row["pixels"] == n:
                    by_realisation.setdefault(row["realisation"], []).append(row)
            cold = np.mean([row["fel_kPa"] for rows in by_realisation.values() for row in rows if row["path"] == "cold"])
            lowest = np.mean([min(rows, key=lambda row: row["energy_J_m2"])["fel_kPa"]
                              for rows in by_realisation.values()])
            spread = np.mean([(max(row["fel_kPa"] for row in rows) - min(row["fel_kPa"] for row in rows))
                              / next(row["fel_kPa"] for row in rows if row["path"] == "cold")
                              for rows in by_realisation.values()])
            table.append({"normal_force_N": force, "pixels": n, "realisations": len(by_realisation),
                          "cold_fel_kPa": cold, "lowest_energy_fel_kPa": lowest, "cold_excess": cold / lowest - 1,
                          "path_spread": spread})
    return table


def model_band(bands) -> tuple:
    """``(below, above)``: the band of the layered F_el about the cold solves' mean at the reference pixel, over
    both loads: the lowest-energy equilibria's mean at that pixel or finer below, the cold solves' mean at finer
    pixels above (fractions)."""
    below, above = 0.0, 0.0
    for force in NORMAL_FORCES:
        mine = [row for row in bands if row["normal_force_N"] == force and row["pixels"] >= REFERENCE_PIXELS]
        reference = next(row["cold_fel_kPa"] for row in mine if row["pixels"] == REFERENCE_PIXELS)
        below = min(below, min(row["lowest_energy_fel_kPa"] for row in mine) / reference - 1)
        above = max(above, max(row["cold_fel_kPa"] for row in mine) / reference - 1)
    return below, above


def summarise(zones, strips, fem, cylinders, profiles, paths, bands, pixels) -> list:
    lines = ["cohesive zone (π/4) E* w/σ0²:"]
    lines += [f"  {row['law']:>21}: h {row['thickness_um']:.3f} µm, σ0 {row['strength_MPa']:.2f} MPa, "
              f"w {row['work_J_m2']:.3f} J/m², ℓ {row['zone_um']:.2f} µm" for row in zones]
    lines.append("fixed strip gaps, F_el/A0 [kPa] (contact part) against the pixel:")
    lines += [f"  {row['opening']:>5} {row['pixel_nm']:9.2f} nm: {row['fel_kPa']:.3f} ({row['fel_contact_kPa']:.3f}),"
              f" edge σ {row['edge_sigma_MPa']:.2f} MPa, first open pixel σ {row['open_sigma_MPa']:.2f} MPa "
              f"(air field {row['open_field_V_um']:.0f} V/µm)"
              + (f"; lateral air {row['fel_lateral_air_kPa']:.3f}, edge σ {row['edge_sigma_lateral_air_MPa']:.2f} MPa"
                 if row["fel_lateral_air_kPa"] != "" else "") for row in strips]
    lines += [f"  FE {row['opening']:>5}, {row['finest_nm']:6.2f} nm at the lines ({row['columns']} columns): "
              f"{row['fel_kPa']:.3f} (Maxwell {row['fel_maxwell_kPa']:.3f})" if "opening" in row else
              f"  FE on the solved profile, {row['voltage_V']:.0f} V, {row['normal_force_N']} N: layered "
              f"{row['fel_kPa']:.3f} kPa, FE {row['fem_fel_kPa']:.3f} kPa ({100 * row['difference']:+.2f} %)"
              for row in fem]
    lines.append("one cylinder per period: F_el/A0, contact width, Π/A0:")
    lines += [f"  {row['law']:>14} {row['pixel_nm']:7.2f} nm {row['path']:>17}: {row['fel_kPa']:.2f} kPa, "
              f"{row['contact_um']:.4f} µm, {row['energy_J_m2']:.8f} J/m²{'' if row['converged'] else ' (not converged)'}"
              for row in cylinders]
    lines.append("realisation 0, 0.5 N, layered solve: edges against the pixel:")
    lines += [f"  {row['pixel_nm']:7.1f} nm: F_el {row['fel_kPa']:.2f} kPa (tolerance 1e-12: {row['fel_kPa_tol_1e-12']:.2f}), "
              f"contact {100 * row['contact_fraction']:.3f} %, first gap {row['first_gap_nm']:.1f} nm, "
              f"edge σ {row['edge_sigma_MPa']:.2f} MPa" for row in profiles]
    lines.append("paths: mean F_el/A0 [kPa] (mean |ΔF_el| from cold) per load and pixel:")
    for force in NORMAL_FORCES if paths else ():
        for n in pixels:
            mine = [row for row in paths if row["normal_force_N"] == force and row["pixels"] == n]
            cold = {row["realisation"]: row["fel_kPa"] for row in mine if row["path"] == "cold"}
            text = []
            for path in ("cold", "fixed_field_tolerance", "warm_from_coarser"):
                values = {row["realisation"]: row["fel_kPa"] for row in mine if row["path"] == path}
                if values:
                    spread = np.mean([abs(values[r] / cold[r] - 1) for r in values]) * 100
                    text.append(f"{path} {np.mean(list(values.values())):.2f} ({spread:.1f} %)")
            lines.append(f"  {force} N {n:6d}: " + ", ".join(text))
    lines.append("the cold solves against the lowest-energy equilibrium of any path (mean F_el/A0):")
    lines += [f"  {row['normal_force_N']} N {row['pixels']:6d}: cold {row['cold_fel_kPa']:.2f} kPa, lowest energy "
              f"{row['lowest_energy_fel_kPa']:.2f} kPa, cold {100 * row['cold_excess']:+.1f} %, paths' spread "
              f"{100 * row['path_spread']:.2f} %" for row in bands]
    if REFERENCE_PIXELS in pixels and bands:
        below, above = model_band(bands)
        lines.append(f"band about the cold solves at {REFERENCE_PIXELS} pixels: {100 * below:+.1f} … {100 * above:+.1f} %")
    return lines


#: the measurements of the script, each a CSV (module docstring); ``--only`` runs some of them
TABLES = ("zones", "strip", "fem", "fem_profiles", "cylinder", "profile", "paths")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--fast", action="store_true", help="two pixels, one realisation")
    parser.add_argument("--realisations", type=int, default=8)
    parser.add_argument("--no-fem", action="store_true", help="skip the finite-element strip (needs scikit-fem)")
    parser.add_argument("--only", nargs="+", choices=TABLES, default=list(TABLES),
                        help="the measurements to run (default: all; paths also gives the band)")
    parser.add_argument("--contact-line", default="breakdown",
                        help="the layered law's model of the contact line: none, breakdown[:E_bd], "
                             "breakdown-bulk[:E_bd], breakdown-energy[:E_bd], film:<thickness in m>")
    parser.add_argument("--output", default="out", help="output directory (its parent must exist)")
    args, provenance = parse_arguments(parser, argv, "python studies/resolution_edges.py")
    output = output_directory(args.output)
    scene = load_scene()
    stack = scene.screen.stack()
    contact_line = parse_contact_line(args.contact_line)
    tables = set(args.only) - ({"fem", "fem_profiles"} if args.no_fem else set())
    zones = zone_rows(scene) if "zones" in tables else []
    strips = strip_rows(stack, STRIP_PIXELS[:6] if args.fast else STRIP_PIXELS, contact_line) \
        if "strip" in tables else []
    fem = fem_strip_rows(stack, FEM_FINEST[:2] if args.fast else FEM_FINEST, contact_line) if "fem" in tables else []
    fem_profiles = fem_profile_rows(scene, contact_line, *((1024, (VOLTAGE,)) if args.fast else (REFERENCE_PIXELS,))) \
        if "fem_profiles" in tables else []
    cylinders = cylinder_rows(scene, CYLINDER_PIXELS[:2] if args.fast else CYLINDER_PIXELS, contact_line) \
        if "cylinder" in tables else []
    profiles = profile_rows(scene, PROFILE_PIXELS[:2] if args.fast else PROFILE_PIXELS, contact_line) \
        if "profile" in tables else []
    path_pixels = PATH_PIXELS[:2] if args.fast else PATH_PIXELS
    paths = path_rows(scene, path_pixels, 1 if args.fast else args.realisations, contact_line) \
        if "paths" in tables else []
    bands = band_rows(paths)
    for name, rows in (("zones", zones), ("strip", strips), ("fem", fem), ("fem_profiles", fem_profiles),
                       ("cylinder", cylinders), ("profile", profiles), ("paths", paths), ("band", bands)):
        if rows:
            write_csv(output / f"resolution_edges_{name}.csv", rows, provenance)
    print("\n".join(summarise(zones, strips, fem + fem_profiles, cylinders, profiles, paths, bands, path_pixels))
          + f"\nwritten to {output}/")
    return zones, strips, fem, cylinders, profiles, paths, bands


if __name__ == "__main__":
    main()
