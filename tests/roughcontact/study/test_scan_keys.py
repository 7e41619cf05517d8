"""How a scene reads a measured scan: the [roughness] keys unit, lengths or pixel_size, channel, rows, crop (by
pixels or metres), resample and missing = "crop"; each checked at validation with an error naming the key, its line and
what is valid; a reader's own error written in the scene's keys; every key that changes the patch changes the
task keys (through the patch's digest)."""
import numpy as np
import pytest

import surfaces
from roughcontact.study import patch
from roughcontact.study.plan import plan_study
from roughcontact.study.scene import load_scene

pytest.importorskip("SurfaceTopography", reason="text and x3p scans are read through SurfaceTopography")

NX, NY, DX, DY = 24, 20, 5e-6, 12.5e-6                # non-square pixels, dy/dx = 2.5 (as real x3p files have)


@pytest.fixture
def scans(tmp_path):
    """One window written three ways: a text matrix in µm without size or unit (rows along y: SurfaceTopography's
    image layout), an x3p file (stores both) and a saved field; and the text with a 4 x 3 hole (12 of 480
    points, 2.5 %)."""
    window = surfaces.self_affine(surfaces.Grid((NX, NY), (NX * DX, NY * DY), periodic=False), hurst=0.8,
                                  rms_height=3e-6, rng=7)
    np.savetxt(tmp_path / "scan.txt", window.heights.T * 1e6)
    surfaces.to_topography(window).to_x3p(str(tmp_path / "scan.x3p"))
    window.save(tmp_path / "scan.npz")
    holes = window.heights.copy()
    holes[3:7, 2:5] = np.nan
    np.savetxt(tmp_path / "holes.txt", holes.T * 1e6)
    return window


def scene(tmp_path, name, keys="", boundary="mirrored"):
    text = (f'[ridges]\nenabled = false\n[roughness]\ntopography = "{name}"\nboundary = "{boundary}"\n{keys}'
            "[loads]\nnormal_forces = [0.5, 2.0]\nvoltages = [0.0, 150.0]\n")
    (tmp_path / "scene.toml").write_text(text)
    return load_scene(tmp_path / "scene.toml", preset="draft")


TEXT_KEYS = 'unit = "um"\npixel_size = [5e-6, 12.5e-6]\n'


def test_a_text_scan_is_read_with_its_unit_and_pixel_size_from_the_scene(tmp_path, scans):
    """Before these keys a text scan could not be read from a scene at all (its unit and size were not
    settable): it had to be re-saved as .npz in Python first."""
    measured = patch.patch_grid(scene(tmp_path, "scan.txt", TEXT_KEYS, boundary="free"))
    assert measured.shape == (NX, NY) and measured.spacing == pytest.approx((DX, DY), rel=1e-12)
    heights = patch.patch_surface(scene(tmp_path, "scan.txt", TEXT_KEYS, boundary="free"), 0)
    # the same heights as the window (written in µm with 18 digits) with its plane removed
    np.testing.assert_allclose(heights, scans.detrended("plane").heights, rtol=0, atol=1e-17)
    by_lengths = scene(tmp_path, "scan.txt", f'unit = 1e-6\nlengths = [{NX * DX!r}, {NY * DY!r}]\n', "free")
    np.testing.assert_array_equal(patch.patch_surface(by_lengths, 0), heights)
    one_size = scene(tmp_path, "scan.txt", 'unit = "um"\npixel_size = 5e-6\n', "free")
    assert patch.patch_grid(one_size).spacing == pytest.approx((DX, DX), rel=1e-12)       # one number: square


def test_rows_says_how_a_height_matrix_is_laid_out(tmp_path, scans):
    """The window written in the image layout (rows along y: scan.txt) and as numpy writes it (rows along x, .txt
    and .npy) reads to the same patch once ``rows`` says which it is; without it a text matrix is read in the
    image layout and a .npy as stored, so the same array saved both ways was read transposed."""
    np.savetxt(tmp_path / "numpy.txt", scans.heights * 1e6)
    np.save(tmp_path / "numpy.npy", scans.heights * 1e6)
    image = scene(tmp_path, "scan.txt", TEXT_KEYS, "free")
    expected = patch.patch_surface(image, 0)
    for name, rows in [("scan.txt", "y"), ("numpy.txt", "x"), ("numpy.npy", "x"), ("numpy.npy", "")]:
        read = scene(tmp_path, name, TEXT_KEYS + (f'rows = "{rows}"\n' if rows else ""), "free")
        assert patch.patch_grid(read) == patch.patch_grid(image)
        np.testing.assert_allclose(patch.patch_surface(read, 0), expected, rtol=0, atol=1e-17)
        assert patch.measured_topography(read.roughness).metadata.get("rows", "") == rows
    # the other layout is the window transposed: NY x NX pixels of 5 x 12.5 µm
    assert patch.patch_grid(scene(tmp_path, "numpy.txt", TEXT_KEYS, "free")).shape == (NY, NX)


@pytest.mark.parametrize("name, keys, line, key, message", [
    ("scan.x3p", 'rows = "x"\n', 6, "rows", r'roughness.rows = "x" says how a text height matrix or .npy is laid '
     r"out, but .*scan.x3p is a binary file .*; valid: leave roughness.rows out"),
    ("scan.npz", 'rows = "y"\n', 6, "rows", r"scan.npz is a saved HeightField, .*; valid: leave roughness.rows out"),
    ("scan.txt", 'pixel_size = 5e-6\nrows = "y"\n', 4, "topography",
     r'scan.txt stores no length unit; set roughness.unit \(e.g. "um" or metres per number\)'),
    ("scan.x3p", 'unit = "um"\n', 6, "unit",
     r'roughness.unit = "um" given, but scan.x3p stores its unit \(\'m\'\); leave roughness.unit out'),
    ("scan.x3p", "lengths = [1e-4, 1e-4]\n", 6, "lengths",
     r"scan.x3p stores its physical size .*; leave roughness.lengths and roughness.pixel_size out"),
    ("scan.x3p", "channel = 2\n", 6, "channel", r"roughness.channel = 2 is out of range; scan.x3p has channels 0..0"),
    ("scan.txt", "pixel_size = 5e-6\n", 4, "topography",
     r'scan.txt stores no length unit; set roughness.unit \(e.g. "um" or metres per number\)'),
    ("scan.txt", 'unit = "um"\n', 4, "topography", r"scan.txt stores no physical size; set roughness.lengths = "
     r"\[Lx, Ly\] or roughness.pixel_size = dx or \[dx, dy\] in m"),
    ("holes.txt", TEXT_KEYS, 4, "topography", r'holes.txt has 12 missing heights .* set roughness.missing = "crop" '
     r"to keep the measured part \(the largest .*\) or roughness.missing = \"harmonic\""),
    ("scan.npz", "pixel_size = 5e-6\n", 6, "pixel_size", r"scan.npz is a saved HeightField, which stores its size "
     r"and its heights in metres, one map \(channel 0\); valid: leave roughness.pixel_size out"),
    ("scan.x3p", "crop = [0, 30, 0, 10]\n", 6, "crop", r"roughness.crop = \[0, 30, 0, 10\] \(pixels\) does not fit "
     r"the scan as read, 24 x 20 pixels over .*: x\[1\] must be an integer in \[0, 24\], got 30"),
])
def test_a_reader_error_names_the_scene_key(tmp_path, scans, name, keys, line, key, message):
    with pytest.raises(ValueError, match=rf"scene.toml, line {line}: scene key roughness.{key}: .*{message}") as error:
        scene(tmp_path, name, keys)
    assert "pass " not in str(error.value) and "=None" not in str(error.value)       # not the reader's arguments


@pytest.mark.parametrize("keys, message", [
    ('unit = "furlong"\n', r'roughness.unit = \'furlong\' is not a length unit; valid: "" \(the unit the file '
     r'stores\), one of "m", "mm", "um".* or metres per number, in \(0, inf\)'),
    ("unit = -1e-6\n", r"roughness.unit = -1e-06 is not a length unit; valid: .* or metres per number"),
    ("lengths = [1e-4]\n", r"roughness.lengths must be \[\] \(none\), a list of 2 values, each a number in \(0, inf\)"),
    ("pixel_size = [5e-6, 0.0]\n", r"roughness.pixel_size\[1\] = 0.0 is out of range; valid range \(0, inf\)"),
    ("pixel_size = 5e-6\nlengths = [1e-4, 1e-4]\n", r"roughness.pixel_size = \[5e-06, 5e-06\] with roughness.lengths "
     r"= \[0.0001, 0.0001\]: give the scan's size once; valid: one of the two"),
    ("channel = -1\n", r"roughness.channel must be an integer in \[0, 1000\]"),
    ("crop = [0, 10.5, 0, 8]\n", r'roughness.crop = \[0.0, 10.5, 0.0, 8.0\] with crop_by = "pixels" needs pixel '
     r'indices; valid: whole numbers, or crop_by = "metres"'),
    ("crop = [10, 10, 0, 8]\n", r"roughness.crop = \[10, 10, 0, 8\] keeps nothing; valid: \[x0, x1, y0, y1\] with "
     r"x0 < x1 and y0 < y1"),
    ('crop_by = "inches"\n', r'crop_by = \'inches\' is not one of "pixels", "metres"'),
    ("resample = [4, 40]\n", r"resample\[0\] must be an integer in \[8, 4096\]"),
    ('missing = "zero"\n', r'roughness.missing = \'zero\' is not one of "refuse", "harmonic", "crop"'),
    ('rows = "z"\n', r'roughness.rows = \'z\' is not one of "", "x", "y"'),
])
def test_the_scan_keys_are_validated(tmp_path, scans, keys, message):
    with pytest.raises((ValueError, TypeError), match=rf"scene.toml, line 6: scene key roughness\.\w+: .*{message}"):
        scene(tmp_path, "scan.x3p", keys)


def test_a_scan_key_without_a_scan_is_refused():
    with pytest.raises(ValueError, match=r'line 2: scene key roughness.crop: roughness.crop = \[0, 8, 0, 8\] says how '
                                         r"a measured scan is read, but roughness.topography is empty"):
        load_scene(text="[roughness]\ncrop = [0, 8, 0, 8]\n")


def test_crop_and_resample_window_the_scan_as_read(tmp_path, scans):
    read = surfaces.read_topography(tmp_path / "scan.x3p")
    pixels = scene(tmp_path, "scan.x3p", "crop = [2, 18, 4, 16]\nresample = [8, 24]\n")
    expected = read.cropped((2, 18), (4, 16)).resampled((8, 24)).detrended("plane").mirrored()
    assert patch.patch_grid(pixels) == expected.grid
    np.testing.assert_array_equal(patch.patch_surface(pixels, 0), expected.heights)
    # by metres: the pixels whose position i dx lies in [x0, x1), the same window
    metres = scene(tmp_path, "scan.x3p", f'crop = [1e-5, 9e-5, 5e-5, 2e-4]\ncrop_by = "metres"\nresample = [8, 24]\n')
    np.testing.assert_array_equal(patch.patch_surface(metres, 0), expected.heights)
    record = patch.measured_topography(metres.roughness).metadata
    assert (record["crop"], record["crop_by"], record["resample"]) == ([1e-5, 9e-5, 5e-5, 2e-4], "metres", [8, 24])


def test_missing_crop_keeps_the_largest_measured_rectangle(tmp_path, scans):
    cropped = scene(tmp_path, "holes.txt", TEXT_KEYS + 'missing = "crop"\n', boundary="free")
    field = patch.measured_topography(cropped.roughness)
    assert field.shape == (NX, NY - 5)                   # columns 5..19: the hole spans columns 2..4
    record = field.metadata
    assert record["measured_window"] == [[0, NX], [5, NY]] and record["missing_points"] == 12
    assert record["kept_fraction"] == pytest.approx(NX * (NY - 5) / (NX * NY), rel=1e-15)
    np.testing.assert_allclose(field.heights, surfaces.HeightField(
        field.grid, scans.heights[:, 5:]).detrended("plane").heights, rtol=0, atol=1e-17)


def test_every_scan_key_that_changes_the_patch_changes_the_task_keys(tmp_path, scans):
    def keys(name, extra=""):
        return [task.key for task in plan_study(scene(tmp_path, name, extra)).tasks]

    base = keys("scan.txt", TEXT_KEYS)
    changed = {"unit": keys("scan.txt", 'unit = "nm"\npixel_size = [5e-6, 12.5e-6]\n'),
               "pixel_size": keys("scan.txt", 'unit = "um"\npixel_size = [5e-6, 5e-6]\n'),
               "crop": keys("scan.txt", TEXT_KEYS + "crop = [0, 20, 0, 20]\n"),
               "resample": keys("scan.txt", TEXT_KEYS + "resample = [12, 10]\n"),
               "missing": keys("holes.txt", TEXT_KEYS + 'missing = "harmonic"\n'),
               "rows": keys("scan.txt", TEXT_KEYS + 'rows = "x"\n')}
    assert keys("holes.txt", TEXT_KEYS + 'missing = "crop"\n') != changed["missing"]
    for name, tasks in changed.items():
        assert not set(tasks) & set(base), name
    # the same patch however it is asked for: the same keys
    assert keys("scan.txt", 'unit = 1e-6\npixel_size = [5e-6, 12.5e-6]\n') == base
    assert keys("scan.txt", TEXT_KEYS + 'missing = "crop"\n') == base            # nothing missing: nothing cut
    assert keys("scan.txt", TEXT_KEYS + 'rows = "y"\n') == base                   # the text reader's own layout


def test_the_scan_keys_round_trip_and_stay_out_of_a_scene_without_them(tmp_path, scans):
    chosen = scene(tmp_path, "scan.txt", TEXT_KEYS + 'crop = [0, 2e-5, 0, 1e-4]\ncrop_by = "metres"\n')
    assert load_scene(text=chosen.to_toml()) == chosen
    plain = load_scene()
    assert not {"unit", "lengths", "pixel_size", "channel", "rows", "crop", "crop_by", "resample"} & set(
        plain.to_dict()["roughness"])
