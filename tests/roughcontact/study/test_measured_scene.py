"""A measured topography as the study's patch: the scene key ``[roughness] topography`` with its boundary, the
checks at scene validation, the free-boundary A_R and gap slope, and ``roughcontact run`` on a scan end to end."""
import numpy as np
import pytest

import surfaces
from roughcontact.cli import main
from roughcontact.io import read_csv
from roughcontact.solvers import solve_contact
from roughcontact.study import apparent, patch
from roughcontact.study.scene import load_scene

st = pytest.importorskip("SurfaceTopography", reason="the scans are x3p files read through SurfaceTopography")

SIDE, N = 1.2e-4, 24                                  # a 0.12 mm scan of 24² pixels (5 µm)


@pytest.fixture
def scan(tmp_path):
    """A tilted self-affine window written as an ISO 25178-72 file in a sub-folder of the scene's."""
    window = surfaces.self_affine(surfaces.Grid((N, N), (SIDE, SIDE), periodic=False), hurst=0.8, rms_height=3e-6,
                                  short_cutoff=2e-5, rng=4)
    x, _ = window.grid.meshgrid()
    (tmp_path / "scans").mkdir()
    surfaces.to_topography(window + surfaces.HeightField(window.grid, 0.03 * x)).to_x3p(
        str(tmp_path / "scans" / "scan.x3p"))
    return window


def scene_text(boundary="mirrored", extra=""):
    return ("[ridges]\nenabled = false\n[roughness]\ntopography = \"scans/scan.x3p\"\n"
            f"boundary = \"{boundary}\"\n[loads]\nnormal_forces = [0.5, 2.0]\nvoltages = [0.0, 150.0]\n"
            "[ridge_area]\ncoarse_graining = 2e-5\nsensitivity = [2.0]\n" + extra)


@pytest.mark.parametrize("boundary, shape, periodic", [("mirrored", (2 * N, 2 * N), True),
                                                       ("periodic", (N, N), True), ("free", (N, N), False)])
def test_the_patch_is_the_levelled_scan_with_its_boundary(tmp_path, scan, boundary, shape, periodic):
    (tmp_path / "scene.toml").write_text(scene_text(boundary))
    scene = load_scene(tmp_path / "scene.toml", preset="draft")
    assert scene.roughness.topography == str((tmp_path / "scans" / "scan.x3p").resolve())   # from the file's folder
    grid = patch.patch_grid(scene)
    assert grid.shape == shape and grid.periodic == (periodic, periodic)
    assert grid.spacing == pytest.approx((SIDE / N, SIDE / N), rel=1e-12)           # the scan's own pixels
    heights = patch.patch_surface(scene, realisation=0)
    # the tilt of 0.03 is removed with the window's own plane: the patch is the plane-detrended window
    np.testing.assert_allclose(heights[:N, :N], scan.detrended("plane").heights, rtol=0, atol=1e-18)
    assert patch.realisation_count(scene) == 1 and np.isnan(patch.resolved_short_cutoff(scene))


@pytest.mark.parametrize("extra, line, message", [
    ("", 4, r"no such file"),
    ("[ridges]\nenabled = true\n", 2, r"its ridges included, but ridges.enabled = true"),
    ("[presets.draft]\nscales = \"coupled\"\n", 4, r"solved resolved"),
])
def test_a_bad_measured_scene_stops_at_validation(tmp_path, extra, line, message):
    text = scene_text().replace("[ridges]\nenabled = false\n", "") if "ridges" in extra else scene_text()
    (tmp_path / "scene.toml").write_text(text + extra)
    with pytest.raises(ValueError, match=rf"scene.toml, line {line}: scene key roughness.topography: .*{message}"):
        load_scene(tmp_path / "scene.toml", preset="draft")


def test_scene_checks_of_the_measured_keys(tmp_path, scan):
    (tmp_path / "scene.toml").write_text(scene_text("tiled"))
    with pytest.raises(ValueError, match=r'line 5: scene key roughness.boundary: .*"mirrored", "periodic", "free"'):
        load_scene(tmp_path / "scene.toml")
    scan.save(tmp_path / "scans" / "saved.npz")
    periodic = surfaces.HeightField(surfaces.Grid((N, N), (SIDE, SIDE), periodic=True), scan.heights)
    periodic.save(tmp_path / "scans" / "periodic.npz")
    (tmp_path / "scene.toml").write_text(scene_text("free").replace("scan.x3p", "saved.npz"))
    assert patch.patch_grid(load_scene(tmp_path / "scene.toml", preset="draft")).periodic == (False, False)
    (tmp_path / "scene.toml").write_text(scene_text("mirrored").replace("scan.x3p", "periodic.npz")
                                         .replace("boundary = \"mirrored\"", "detrend = \"mean\""))
    with pytest.raises(ValueError, match="line 4: scene key roughness.topography: the field is already periodic"):
        load_scene(tmp_path / "scene.toml")


def test_ridge_area_on_a_free_window_does_not_merge_across_opposite_edges():
    """Two contact stripes at opposite edges, two empty rows apart across the wrap: a closing with a 4-pixel disc
    bridges the wrap on a periodic window (rows 14, 15, 0, 1 covered: 1/4) but not on a free one (2/16)."""
    contact = np.zeros((16, 16))
    contact[1], contact[14] = 1.0, 1.0
    assert patch.ridge_area_fraction(contact, 1.0, 4.0) == pytest.approx(0.25, abs=1e-15)
    assert patch.ridge_area_fraction(contact, 1.0, 4.0, periodic=(False, True)) == pytest.approx(0.125, abs=1e-15)
    # free along the stripes: the bridge pixels in the edge column lack the disc's outer pixel beyond the edge
    # ((15, -2) is not in the dilated set), so the bridge stops one pixel short of each end: 64 - 4 pixels
    assert patch.ridge_area_fraction(contact, 1.0, 4.0, periodic=(True, False)) == pytest.approx(60 / 256, abs=1e-15)


def test_gap_slope_of_a_free_window_is_exact_for_a_linear_gap():
    """A gap rising linearly along x has slope 0.02 everywhere; periodic differences would see a cliff at the
    wrap, the one-sided edge differences of a free window do not."""
    x = np.arange(16.0)[:, None] * np.ones((1, 8)) * 1e-6
    gap, weights = 1e-6 + 0.02 * x, np.ones((16, 8))
    assert patch.gap_slope(gap, weights, (1e-6, 1e-6), (False, False)) == pytest.approx(0.02, rel=1e-12)
    assert patch.gap_slope(gap, weights, (1e-6, 1e-6)) > 0.05


def test_run_command_on_a_measured_scan(tmp_path, scan, capsys):
    """``roughcontact run`` on a scene pointing at an x3p writes the full report; its d_eq at the first load and
    0 V is that of the levelled, mirrored scan solved directly (the same cold solve: to round-off)."""
    (tmp_path / "scene.toml").write_text(scene_text())
    out = tmp_path / "results"
    assert main(["run", str(tmp_path / "scene.toml"), "--preset", "draft", "--out", str(out), "--workers", "1"]) == 0
    assert "4 points computed" in capsys.readouterr().out
    for name in ("report.md", "points.csv", "realisations.csv", "friction.csv", "equivalent_gap.png", "friction.png",
                 "scene.toml"):
        assert (out / name).is_file(), name
    report = (out / "report.md").read_text()
    assert "patch the measured topography `scan.x3p` (mirrored boundary, plane removed), 48 × 48 pixels" in report
    assert "do not apply here: the measured patch is solved on the scan's own pixels" in report
    assert "Measured error of preset" not in report
    scene = load_scene(tmp_path / "scene.toml", preset="draft")
    surface = surfaces.read_topography(tmp_path / "scans" / "scan.x3p", detrend="plane").mirrored()
    area, (pressure,) = apparent.apparent_contact(scene.fingerpad, 0.5, 1)
    direct = solve_contact(surface, patch.patch_body(scene), mean_pressure=pressure, tol=scene.preset.tolerance)
    row = read_csv(out / "points.csv")[0]
    assert float(row["normal_force_N"]) == 0.5 and float(row["voltage_V"]) == 0.0
    assert float(row["equivalent_gap_um"]) == pytest.approx(scene.screen.stack().equivalent_gap(direct.gap) * 1e6,
                                                            rel=1e-9)
    assert load_scene(out / "scene.toml") == scene                           # the results carry the absolute path
