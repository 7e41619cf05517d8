"""Measured patches at the edge of what the study can say: a patch narrower than the closing length or the ridge
period (PatchScaleWarning), a mean attraction above that of uniform contact (the field-equivalent gap stays at
its bound 0, never below), and the points in full contact or pressed by F_el ≥ 10 F_N, flagged in points.csv,
results.nc and report.md."""
import math
from types import SimpleNamespace

import numpy as np
import pytest
import xarray

import surfaces
from roughcontact.cli import main
from roughcontact.io import read_csv
from roughcontact.study.patch import PatchScaleWarning, patch_scale_message
from roughcontact.study.plan import plan_study
from roughcontact.study.records import PatchRecord, patch_record, point_result
from roughcontact.study.run import StudyResult
from roughcontact.study.scene import load_scene
from roughcontact.study.tables import ATTRACTION_DOMINATES, FULL_CONTACT, point_flags

# ---------------------------------------------------------------------------------------------------------
# The field-equivalent gap never below zero
# ---------------------------------------------------------------------------------------------------------
def stand_in(contact, gap, spacing, force):
    """A solved patch as patch_record reads it."""
    grid = surfaces.Grid(contact.shape, (contact.shape[0] * spacing[0], contact.shape[1] * spacing[1]))
    return SimpleNamespace(gap=gap, contact=contact, grid=grid, contact_fraction=float(contact.mean()),
                           converged=True, iterations=1, unstable_steps=0, electrostatic_force=force)


def test_an_attraction_above_uniform_contact_keeps_the_field_gap_at_zero():
    """Eq. 21 inverted at a mean attraction 2 % above σ_el(0) gives a gap below zero; the record holds 0, and the
    field ratio (the solve's attraction over Eq. 21 per pixel) is the unclipped one."""
    stack, voltage = load_scene().screen.stack(), 200.0
    contact = np.zeros((16, 16), dtype=bool)
    contact[:, :12] = True
    gap = np.where(contact, 0.0, 2e-8)
    attraction = 1.02 * float(stack.attraction(0.0, voltage))
    result = stand_in(contact, gap, (1e-6, 1e-6), attraction * 16e-6 * 16e-6)
    assert stack.gap_for_attraction(attraction, voltage) < 0                  # what was reported before
    record = patch_record(stack, "layered", voltage, [result], (4e-6,), (1e-6, 1e-6), 1, 0.0)
    assert record.field_equivalent_gap == 0.0 and record.ridge_equivalent_gap == 0.0
    assert record.field_ratio == pytest.approx(record.electrostatic_attraction / record.pixel_law_attraction,
                                               rel=1e-12)


# ---------------------------------------------------------------------------------------------------------
# Flags: full contact, attraction dominating the load
# ---------------------------------------------------------------------------------------------------------
def record(contact, attraction, field_gap=1e-6):
    return PatchRecord(equivalent_gap=1e-6, field_equivalent_gap=field_gap, ridge_equivalent_gap=1e-6,
                       mean_gap=1e-6, contact_fraction=contact, ridge_area_fractions=(0.5,),
                       electrostatic_attraction=attraction, pixel_law_attraction=attraction, field_ratio=1.0,
                       gap_slope=0.1, converged=True, iterations=1, unstable_steps=0, solves=1, seconds=0.0)


def test_the_flags_mark_full_contact_and_an_attraction_ten_times_the_load():
    scene = load_scene(text="[loads]\nnormal_forces = [1.0]\nvoltages = [0.0, 100.0, 200.0, 250.0]\n"
                            "[presets.draft]\nrealisations = 2\n", preset="draft")
    area = 1e-4                                                   # m²: F_el = σ̄ A0, F_N = 1 N
    cells = [[record(0.2, 0.0), record(0.3, 0.0)],                                     # 0 V: nothing
             [record(0.5, 0.99 * ATTRACTION_DOMINATES / area), record(FULL_CONTACT - 1e-9, 0.99e5)],
             [record(0.5, 0.5e5), record(FULL_CONTACT, 0.5e5, field_gap=0.0)],          # one realisation full
             [record(0.9, 1.0 * ATTRACTION_DOMINATES / area), record(0.9, 1.0 * ATTRACTION_DOMINATES / area)]]
    points = ((*(point_result(1.0, voltage, area, (1.0 / area,), cell) for voltage, cell in
                 zip((0.0, 100.0, 200.0, 250.0), cells)),),)
    flags = point_flags(StudyResult(plan=plan_study(scene), points=points, computed=0, solves=0))
    assert flags["full_contact"].tolist() == [[False, False, True, False]]
    assert flags["attraction_dominates"].tolist() == [[False, False, False, True]]
    assert flags["electrostatic_to_normal_force"][0] == pytest.approx([0.0, 9.9, 5.0, 10.0], rel=1e-12)
    assert flags["field_gap_clipped"].tolist() == [[False, False, True, False]]


# ---------------------------------------------------------------------------------------------------------
# A 10 µm AFM scan at 200 V, end to end
# ---------------------------------------------------------------------------------------------------------
@pytest.fixture
def afm(tmp_path):
    """A 10 µm scan (32² pixels of 0.31 µm, rms 0.1 µm), saved as a field, and its scene at 0 and 200 V."""
    surfaces.self_affine(surfaces.Grid((32, 32), (1e-5, 1e-5), periodic=False), hurst=0.8, rms_height=1e-7,
                         short_cutoff=1.25e-6, rng=1).save(tmp_path / "afm.npz")
    (tmp_path / "scene.toml").write_text('[ridges]\nenabled = false\n[roughness]\ntopography = "afm.npz"\n'
                                         "[loads]\nnormal_forces = [0.5, 2.0]\nvoltages = [0.0, 200.0]\n")
    return tmp_path / "scene.toml"


def test_a_patch_narrower_than_the_length_scales_warns(afm):
    with pytest.warns(PatchScaleWarning, match=r"the patch's surface, 10 x 10 µm \(the scan; the patch is its mirror "
                                               r"images\), is narrower than the A_R closing length ridge_area."
                                               r"coarse_graining = 120 µm and than the ridge period ridges.period = "
                                               r"450 µm: A_R/A0 closes over the whole patch"):
        plan_study(load_scene(afm, preset="draft"))
    # a synthetic patch of one ridge period: only a closing length beyond it
    wide = load_scene(text="[ridge_area]\ncoarse_graining = 5e-4\n", preset="draft")
    with pytest.warns(PatchScaleWarning, match=r"the patch's surface, 450 x 450 µm, is narrower than the A_R closing "
                                               r"length ridge_area.coarse_graining = 500 µm: A_R/A0 closes over the "
                                               r"whole patch \(it tends to 100 %\), so d_eq"):
        plan_study(wide)
    assert patch_scale_message(load_scene(), plan_study(load_scene()).grid) == ""


def test_a_patch_pressed_by_the_field_is_flagged_and_no_gap_is_negative(afm, tmp_path):
    out = tmp_path / "results"
    assert main(["run", str(afm), "--preset", "draft", "--out", str(out), "--workers", "1"]) == 0
    points = read_csv(out / "points.csv")
    for row in points:
        for column in ("equivalent_gap_um", "field_equivalent_gap_um", "ridge_equivalent_gap_um", "mean_gap_um"):
            assert float(row[column]) >= 0, (column, row)
    high = [row for row in points if float(row["voltage_V"]) == 200.0]
    assert all(row["attraction_dominates"] == "True" and float(row["electrostatic_to_normal_force"]) > 25
               for row in high)
    # air breakdown at the contact lines (the default) holds the mean attraction below ε0 E_bd²/2 = 0.54 MPa, so
    # the field gap stays above U/E_bd - c = 0.232 µm at 200 V (measured 0.235 µm at 62-63 % contact): not clipped
    assert all(row["field_gap_clipped"] == "False" and 0.2317 < float(row["field_equivalent_gap_um"]) < 0.24
               for row in high)
    assert all(row["attraction_dominates"] == "False" for row in points if float(row["voltage_V"]) == 0.0)
    report = (out / "report.md").read_text()
    assert "**Points that say nothing about the topography** (marked † in the tables): the patch is pressed by an " \
           "attraction F_el ≥ 10 F_N" in report and "0.5 N at 200 V, 2 N at 200 V" in report
    assert "**d_field = 0**" not in report and "**Patch too small**" in report
    friction = report[report.index("## Friction"):]
    assert friction.count(" †") == 3 * 2               # μ, F_T and A_R0 at the two flagged points
    # the numbers docs/guide/study.md quotes: F_el = 76 F_N, μ = 20 without the area reduction (0.5 N, 200 V)
    assert "(up to 76 F_N)" in report
    row = next(row for row in read_csv(out / "friction.csv") if row["voltage_V"] == "200.0")
    assert round(float(row["bottom_up_c2_0_friction_coefficient"])) == 20
    with xarray.open_dataset(out / "results.nc", engine="h5netcdf") as data:
        assert data["attraction_dominates"].values.tolist() == [[0, 1], [0, 1]]
        assert float(data["field_equivalent_gap"].min()) >= 0 and not math.isnan(float(data["full_contact"].sum()))
