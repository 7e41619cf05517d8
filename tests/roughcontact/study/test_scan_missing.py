"""A measured scan's missing points are visible in the study: the reader's record of them sits at the top of the
patch's metadata (and of ``patch.npz``), a fill above 5 % of the scan warns every time the patch is used (a
cached read included) and on the command line, and report.md and results.nc state the filled or cropped-away
fraction, also when read back from the results directory."""
import warnings

import numpy as np
import pytest
import xarray

import surfaces
from roughcontact.cli import main
from roughcontact.study.plan import plan_study
from roughcontact.study.report import report_text
from roughcontact.study.run import open_results, run_study
from roughcontact.study.scene import load_scene, measured_topography

pytest.importorskip("SurfaceTopography", reason="the text scans are read through SurfaceTopography")

NX, NY, PIXEL = 24, 20, 5e-6


@pytest.fixture
def holes(tmp_path):
    """A text scan in µm (rows along y) with a 6 x 5 hole: 30 of its 480 heights (6.25 %) undefined."""
    window = surfaces.self_affine(surfaces.Grid((NX, NY), (NX * PIXEL, NY * PIXEL), periodic=False), hurst=0.8,
                                  rms_height=3e-6, rng=3)
    heights = window.heights.copy()
    heights[10:16, 0:5] = np.nan
    np.savetxt(tmp_path / "holes.txt", heights.T * 1e6)
    return tmp_path / "holes.txt"


def scene_file(tmp_path, missing, loads="normal_forces = [0.5, 2.0]\nvoltages = [0.0, 150.0]"):
    (tmp_path / "scene.toml").write_text(
        f'[ridges]\nenabled = false\n[roughness]\ntopography = "holes.txt"\nunit = "um"\npixel_size = {PIXEL!r}\n'
        f'missing = "{missing}"\n[loads]\n{loads}\n'
        "[ridge_area]\ncoarse_graining = 2e-5\nsensitivity = [2.0]\n")
    return tmp_path / "scene.toml"


FILLED = r'holes.txt: roughness.missing = "harmonic" invented 30 of its heights \(6.2%, above 5%\)'


def test_a_fill_above_five_percent_warns_whenever_the_patch_is_used(tmp_path, holes):
    with pytest.warns(surfaces.MissingDataWarning, match=FILLED):
        scene = load_scene(scene_file(tmp_path, "harmonic"), preset="draft")
    # the read is cached by the file's digest: the study's plan warns all the same
    with pytest.warns(surfaces.MissingDataWarning, match=FILLED + r'.*roughness.missing = "crop" keeps'):
        plan = plan_study(scene)
    record = plan.topography.metadata                   # on top, not nested in the parts of the wrapped field
    assert (record["missing"], record["missing_points"], record["filled_fraction"]) == ("harmonic", 30, 30 / 480)
    with warnings.catch_warnings():
        warnings.simplefilter("error", surfaces.MissingDataWarning)
        measured_topography(load_scene(scene_file(tmp_path, "crop"), preset="draft").roughness)   # no fill: quiet


def test_the_filled_fraction_reaches_the_command_line_report_and_results(tmp_path, holes, capsys):
    out = tmp_path / "results"
    scene = scene_file(tmp_path, "harmonic")
    assert main(["run", str(scene), "--preset", "draft", "--out", str(out), "--workers", "1"]) == 0
    warned = [line for line in capsys.readouterr().err.splitlines() if "invented" in line]
    assert len(warned) == 1 and warned[0].startswith("roughcontact run: warning: holes.txt: roughness.missing")
    sentence = ("**Missing data**: 30 heights of the scan (6.2 %) were undefined and are filled by harmonic "
                "interpolation (`missing = \"harmonic\"`): invented heights that the solves take for measured ones, "
                "above the 5 % at which the reader warns")
    assert sentence in (out / "report.md").read_text()
    (tmp_path / "holes.txt").unlink()                  # the results stand without the scan: patch.npz holds the record
    assert sentence in report_text(open_results(out))
    with xarray.open_dataset(out / "results.nc", engine="h5netcdf") as data:
        assert (data.attrs["scan_missing_points"], data.attrs["scan_filled_fraction"]) == (30, 30 / 480)


def test_a_crop_states_what_it_cut_away(tmp_path, holes):
    scene = load_scene(scene_file(tmp_path, "crop", "normal_forces = [0.5]\nvoltages = [0.0]"), preset="draft")
    text = report_text(run_study(scene, workers=1))
    # the hole spans columns 0..4: columns 5..19 are kept, 25 % cut away
    assert ("**Missing data**: 30 heights of the scan were undefined; the patch is its largest fully measured "
            "rectangle (`missing = \"crop\"`), pixels 0:24 × 5:20: 25.0 % of the scan cropped away.") in text
