"""The contact-edge study (studies/resolution_edges.py): its cohesive-zone estimate, the layered field's edge
behaviour on fixed gaps, and the helpers that read edges and restart solves."""
import math

import numpy as np
import pytest

from roughcontact.solvers import projected_cg_gap
from roughcontact.study.scene import load_scene


@pytest.fixture(scope="module")
def edges(load_experiment):
    return load_experiment("resolution_edges")


def test_zone_length_is_the_dugdale_zone_and_scales_as_the_cube_of_the_thickness(edges):
    # JKR limit of a Dugdale edge: K² = 2 E* w, ℓ = π K² / (8 σ0²)
    assert edges.zone_length(1e7, 0.5, 2e6) == pytest.approx(math.pi * 2 * 1e7 * 0.5 / (8 * 4e12), rel=1e-14)
    rows = {row["law"]: row for row in edges.zone_rows(load_scene())}
    per_pixel, layered = rows["per_pixel"], rows["layered_wide_contact"]
    # w ∝ 1/h and σ0 ∝ 1/h² at the same voltage: ℓ ∝ h³
    ratio = (per_pixel["thickness_um"] / layered["thickness_um"]) ** 3
    assert per_pixel["zone_um"] / layered["zone_um"] == pytest.approx(ratio, rel=1e-12)
    assert layered["thickness_um"] == pytest.approx(1.0 / 3.9, rel=1e-12)       # d_i/ε_i of the scene's screen


def test_the_layered_field_has_an_edge_excess_only_on_a_crack_like_opening(edges):
    stack = load_scene().screen.stack()
    rows = edges.strip_rows(stack, edges.STRIP_PIXELS[:6])                     # 500 nm … 15.6 nm
    crack = [row["fel_kPa"] for row in rows if row["opening"] == "crack"]
    hertz = [row["fel_kPa"] for row in rows if row["opening"] == "hertz"]
    # a Hertz-like edge (g ∝ s^3/2) is resolved: the last halvings change F_el by < 1e-5 (measured 2e-6)
    assert abs(hertz[-1] / hertz[-2] - 1) < 1e-5 and abs(hertz[-2] / hertz[-3] - 1) < 1e-5
    # a crack-like edge (g ∝ √s) is not: every halving adds > 0.5 % (measured 2.5 … 0.54 %), most of it on the
    # contact pixels (the flux concentrating at the contact line)
    steps = np.diff(crack) / crack[:-1]
    assert np.all(steps > 5e-3)
    contact = [row["fel_contact_kPa"] for row in rows if row["opening"] == "crack"]
    assert contact[-1] - contact[0] > 0.9 * (crack[-1] - crack[0])


def test_edge_measures_read_the_pixels_beside_each_contact_line(edges):
    spacing = 0.01e-6
    gap = np.linspace(1.0, 2.0, 400) * 1e-9 * np.arange(1, 401)    # open everywhere but the spot below
    gap[100:150] = 0.0
    pressure = np.arange(400, dtype=float) * 1e6
    measures = edges.edge_measures(gap, pressure, spacing)
    assert measures["edges"] == 2
    assert measures["first_gap_nm"] == pytest.approx((gap[150] + gap[99]) / 2 * 1e9, rel=1e-12)
    assert measures["edge_sigma_MPa"] == pytest.approx((149 + 100) / 2, rel=1e-12)
    # 0.05 µm = 5 pixels: the gap 5 pixels out, σ_el 5 pixels in (the contact pixel at the line counted first)
    assert measures["gap_0.05um_nm"] == pytest.approx((gap[154] + gap[95]) / 2 * 1e9, rel=1e-12)
    assert measures["sigma_0.05um_MPa"] == pytest.approx((145 + 104) / 2, rel=1e-12)


def test_interpolated_gap_is_periodic_and_linear(edges):
    class Result:
        gap = np.array([0.0, 2.0, 4.0, 2.0])[:, None]
    assert edges.interpolated_gap(Result, 8)[:, 0] == pytest.approx([0, 1, 2, 3, 4, 3, 2, 1], abs=1e-15)


def test_fixed_field_tolerance_pins_and_restores_the_solvers_bounds(edges):
    names = ("FIELD_TOL_FLOOR", "FIELD_TOL_CEILING", "FIELD_TOL_START")
    bounds = tuple(getattr(projected_cg_gap, name) for name in names)
    with edges.fixed_field_tolerance(1e-12):
        assert all(getattr(projected_cg_gap, name) == 1e-12 for name in names)
    assert tuple(getattr(projected_cg_gap, name) for name in names) == bounds


def test_fast_run_tables_are_consistent(edges, read_csv, tmp_path):
    edges.main(["--fast", "--no-fem", "--contact-line", "none", "--output", str(tmp_path)])     # the plain law
    path = tmp_path
    paths, bands = read_csv(path / "resolution_edges_paths.csv"), read_csv(path / "resolution_edges_band.csv")
    assert all(row["converged"] == "True" for row in paths)
    for band in bands:
        mine = [row for row in paths if row["normal_force_N"] == band["normal_force_N"]
                and row["pixels"] == band["pixels"]]
        lowest = min(mine, key=lambda row: float(row["energy_J_m2"]))
        cold = next(row for row in mine if row["path"] == "cold")
        assert float(band["lowest_energy_fel_kPa"]) == pytest.approx(float(lowest["fel_kPa"]), rel=1e-12)
        assert float(band["cold_excess"]) == pytest.approx(float(cold["fel_kPa"]) / float(lowest["fel_kPa"]) - 1,
                                                           rel=1e-9, abs=1e-15)
    # on the coarser pixel of two only the cold solves exist; on the finer one the warm start from it too
    assert {row["path"] for row in paths if row["pixels"] == "2048"} == {"cold", "fixed_field_tolerance",
                                                                         "warm_from_coarser"}
    assert not (path / "resolution_edges_fem.csv").exists()
    # one cylinder per period at 78 nm: the per-pixel law (a 1.7 µm process zone) reaches one equilibrium from
    # either start, the layered law two stable ones (measured: 659 and 724 kPa, contact 4.22 and 4.92 µm)
    cylinder = {(row["law"], row["path"]): row for row in read_csv(path / "resolution_edges_cylinder.csv")
                if row["pixels"] == "256"}
    assert all(row["converged"] == "True" for row in cylinder.values())
    plate = [float(cylinder["parallel_plate", path]["fel_kPa"]) for path in ("cold", "warm_from_coarser")]
    assert plate[1] == pytest.approx(plate[0], rel=1e-7)       # the solves' tolerance, 1e-8 (measured 5e-9)
    layered = [float(cylinder["layered", path]["fel_kPa"]) for path in ("cold", "warm_from_coarser")]
    assert abs(layered[1] / layered[0] - 1) > 0.03
    for row in read_csv(path / "resolution_edges_profile.csv"):
        # a tolerance of 1e-12 instead of 1e-8 reaches the same equilibrium
        assert float(row["fel_kPa_tol_1e-12"]) == pytest.approx(float(row["fel_kPa"]), rel=1e-6)
        # the gap opens away from the contact line (1 µm is 2 and 5 pixels out on these profiles)
        assert 0 < float(row["first_gap_nm"]) < float(row["gap_1um_nm"])


def test_model_band_spans_the_lowest_energy_and_the_cold_solves_about_the_reference(edges):
    rows = [{"normal_force_N": force, "pixels": n, "cold_fel_kPa": cold, "lowest_energy_fel_kPa": lowest}
            for force, table in ((0.5, ((2048, 150.0, 90.0), (4096, 100.0, 95.0), (8192, 104.0, 93.0))),
                                 (2.0, ((4096, 200.0, 198.0), (8192, 210.0, 199.0))))
            for n, cold, lowest in table]
    below, above = edges.model_band(rows)
    # coarser pixels (2048) take no part; at 0.5 N 93/100 below, at 2 N 210/200 above
    assert below == pytest.approx(-0.07, rel=1e-12) and above == pytest.approx(0.05, rel=1e-12)


def test_the_finite_element_field_agrees_with_the_layered_field_on_the_crack_like_strip(edges):
    pytest.importorskip("skfem", reason="the finite-element field needs the optional extra fieldcheck")
    stack = load_scene().screen.stack()
    fem = {row["opening"]: row for row in edges.fem_strip_rows(stack, (50e-9,))}
    columns = {row["opening"]: row for row in edges.strip_rows(stack, edges.STRIP_PIXELS[6:7])}     # 7.8 nm
    # columns graded to 50 nm at the contact lines and the insulator's rows graded from its face keep the cells
    # unsheared where the crack-like gap rises steeply: the finite elements are then within 2.3 % of the layered
    # field (0.6 % at 20 nm, −0.1 % on the Hertz-like strip), where the uniform terrain-following mesh was 0.4 … 90 %
    # above it from 250 to 7.8 nm columns
    assert all(row["converged"] for row in fem.values())
    assert fem["crack"]["fel_kPa"] == pytest.approx(columns["crack"]["fel_kPa"], rel=0.03)
    assert fem["hertz"]["fel_kPa"] == pytest.approx(columns["hertz"]["fel_kPa"], rel=0.003)


def test_air_breakdown_gives_the_studies_one_equilibrium(edges, read_csv, tmp_path):
    # with air breakdown the cylinder's cold and warm starts meet (the layered law without it: 659 and 724 kPa at
    # 78 nm), the profile's edge holds the broken stress ε0 E_bd²/2 = 0.54 MPa (without: 5.4 … 44 MPa), and the
    # paths agree
    edges.main(["--fast", "--no-fem", "--contact-line", "breakdown", "--output", str(tmp_path)])
    cylinder = {(row["law"], row["path"]): row for row in read_csv(tmp_path / "resolution_edges_cylinder.csv")
                if row["pixels"] == "256"}
    layered = [float(cylinder["layered", path]["fel_kPa"]) for path in ("cold", "warm_from_coarser")]
    assert layered[1] == pytest.approx(layered[0], rel=1e-6)
    for row in read_csv(tmp_path / "resolution_edges_profile.csv"):
        assert float(row["edge_sigma_MPa"]) == pytest.approx(0.54, rel=0.05)
    for band in read_csv(tmp_path / "resolution_edges_band.csv"):
        assert float(band["path_spread"]) < 1e-5
    zones = {row["law"]: row for row in read_csv(tmp_path / "resolution_edges_zones.csv")}
    assert float(zones["layered_breakdown"]["strength_MPa"]) == pytest.approx(0.5423, rel=1e-3)
    assert float(zones["layered_breakdown"]["zone_um"]) > 10 * float(zones["layered_wide_contact"]["zone_um"])
