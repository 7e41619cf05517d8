"""Measured topographies: one scan in three file formats (ISO 25178-72 x3p, an x-y-z text export, a
SurfaceTopography NetCDF) reaches the same HeightField, units, sizes and axes included; the bridge both ways."""
import hashlib
import re
import subprocess
import sys
import zipfile
from pathlib import Path

import numpy as np
import pytest

import surfaces
from surfaces import HeightField

st = pytest.importorskip("SurfaceTopography", reason="the optional SurfaceTopography extra (roughcontact[topography])")
from surfaces.topography import from_topography, read_topography, to_topography  # noqa: E402

# A scan as instruments record it: non-square (24 x 16 pixels), non-square pixels (0.5 x 0.8 um), heights in
# micrometres with a tilt; the height is a known function of (x, y), so every axis or unit mix-up shows.
NX, NY, DX_UM, DY_UM = 24, 16, 0.5, 0.8


def scan_um(x_um, y_um):
    """Height [um] at (x, y) [um]: a wave along x, a tilt along y and a cross term."""
    return 1.5 * np.sin(2 * np.pi * x_um / (NX * DX_UM)) + 0.05 * y_um + 0.01 * x_um * y_um


X_UM, Y_UM = np.meshgrid(np.arange(NX) * DX_UM, np.arange(NY) * DY_UM, indexing="ij")
HEIGHTS_UM = scan_um(X_UM, Y_UM)
REFERENCE = HeightField.from_array(HEIGHTS_UM * 1e-6, pixel_size=(DX_UM * 1e-6, DY_UM * 1e-6))


def write_x3p(path, heights_m, dx, dy):
    """A minimal ISO 25178-72 file written here, independently of SurfaceTopography's writer: main.xml with the
    axes (CX, CY incremental in m, CZ absolute float64) and the matrix size, bindata/data.bin with the heights
    in the standard's point order (x fastest)."""
    nx, ny = heights_m.shape
    data = np.ascontiguousarray(heights_m.T, dtype="<f8").tobytes()
    axis = "<{0}><AxisType>I</AxisType><DataType>D</DataType><Increment>{1!r}</Increment><Offset>0</Offset></{0}>"
    xml = ('<?xml version="1.0" encoding="UTF-8"?>\n<p:ISO5436_2 xmlns:p="http://www.opengps.eu/2008/ISO5436_2">'
           "<Record1><Revision>ISO5436 - 2000</Revision><FeatureType>SUR</FeatureType><Axes>"
           + axis.format("CX", dx) + axis.format("CY", dy)
           + "<CZ><AxisType>A</AxisType><DataType>D</DataType></CZ></Axes></Record1>"
           f"<Record3><MatrixDimension><SizeX>{nx}</SizeX><SizeY>{ny}</SizeY><SizeZ>1</SizeZ></MatrixDimension>"
           "<DataLink><PointDataLink>bindata/data.bin</PointDataLink>"
           f"<MD5ChecksumPointData>{hashlib.md5(data).hexdigest().upper()}</MD5ChecksumPointData></DataLink>"
           "</Record3><Record4><ChecksumFile>md5checksum.hex</ChecksumFile></Record4></p:ISO5436_2>")
    with zipfile.ZipFile(path, "w") as archive:
        archive.writestr("main.xml", xml)
        archive.writestr("bindata/data.bin", data)
        archive.writestr("md5checksum.hex", f"{hashlib.md5(xml.encode()).hexdigest().upper()} *main.xml\n")
    return path


def write_xyz(path, order="y outer"):
    """An x-y-z export in micrometres, comma-separated with a comment header, one point per line."""
    points = zip(X_UM.ravel(), Y_UM.ravel(), HEIGHTS_UM.ravel()) if order == "x outer" else \
        zip(X_UM.T.ravel(), Y_UM.T.ravel(), HEIGHTS_UM.T.ravel())
    lines = (f"{float(x)!r},{float(y)!r},{float(z)!r}\n" for x, y, z in points)
    path.write_text("# x [um], y [um], z [um]\n" + "".join(lines))
    return path


@pytest.fixture
def scans(tmp_path):
    """The scan in the three formats, each read the way a user would."""
    x3p = write_x3p(tmp_path / "scan.x3p", HEIGHTS_UM * 1e-6, DX_UM * 1e-6, DY_UM * 1e-6)
    xyz = write_xyz(tmp_path / "scan.xyz")
    topography_um = st.Topography(HEIGHTS_UM, (NX * DX_UM, NY * DY_UM), unit="µm", periodic=False)
    topography_um.to_netcdf(str(tmp_path / "scan.nc"))
    return {"x3p": read_topography(x3p), "xyz": HeightField.read(xyz, unit="um"),
            "nc": read_topography(tmp_path / "scan.nc")}


@pytest.mark.parametrize("name", ["x3p", "xyz", "nc"])
def test_three_formats_reach_the_same_heightfield(scans, name):
    field = scans[name]
    assert field.grid.shape == (NX, NY) and field.grid.periodic == (False, False)
    # sizes: the x3p increments and the x-y-z lattice are float64 (a lattice step is the span over n - 1, so a few
    # ulp); SurfaceTopography's NetCDF stores the lengths as float32 attributes, so 6e-8 relative there
    np.testing.assert_allclose(field.grid.lengths, (NX * DX_UM * 1e-6, NY * DY_UM * 1e-6), rtol=1e-7)
    np.testing.assert_allclose(field.grid.spacing, (DX_UM * 1e-6, DY_UM * 1e-6), rtol=1e-7)
    # heights in metres, on the right axes: pixel (i, j) at (i dx, j dy) holds scan_um(i dx, j dy) * 1e-6
    # (float64 throughout: the um -> m conversion is the only rounding, a few ulp)
    np.testing.assert_allclose(field.heights, REFERENCE.heights, rtol=1e-14, atol=1e-20)
    assert field.heights[5, 3] == pytest.approx(scan_um(5 * DX_UM, 3 * DY_UM) * 1e-6, rel=1e-14)
    assert field.heights[5, 3] != pytest.approx(scan_um(3 * DX_UM, 5 * DY_UM) * 1e-6, rel=1e-3)  # not transposed


def test_x_outer_export_and_surface_topography_text_reader_agree(tmp_path):
    """The column order of an export does not matter; SurfaceTopography reads the same export the same way."""
    xyz = write_xyz(tmp_path / "scan.csv", order="x outer")
    ours = HeightField.read(xyz, unit="um")
    assert ours == HeightField.read(write_xyz(tmp_path / "scan.xyz"), unit="um")
    theirs = read_topography(xyz, unit="um")
    np.testing.assert_allclose(theirs.heights, ours.heights, rtol=1e-14, atol=1e-20)
    np.testing.assert_allclose(theirs.grid.lengths, ours.grid.lengths, rtol=1e-12)


def test_matrix_text_axis_convention_at_the_file_boundary(tmp_path):
    """SurfaceTopography's text reader takes a row as a line along x at one y (image layout); HeightField.read
    does the same with rows='y', and with its default rows='x' reads numpy's layout of field.heights."""
    image_um = st.Topography(HEIGHTS_UM, (NX * DX_UM, NY * DY_UM), unit="µm")
    image_um.to_matrix(str(tmp_path / "image.txt"))       # '#' header (sizes, unit), then one row along x per y
    np.savetxt(tmp_path / "numpy.txt", HEIGHTS_UM)                            # row i = x_i
    theirs = read_topography(tmp_path / "image.txt")
    image = HeightField.read(tmp_path / "image.txt", rows="y", unit="um", pixel_size=(DX_UM * 1e-6, DY_UM * 1e-6))
    numpy_layout = HeightField.read(tmp_path / "numpy.txt", unit="um", pixel_size=(DX_UM * 1e-6, DY_UM * 1e-6))
    for field in (theirs, image, numpy_layout):
        assert field.grid.shape == (NX, NY)
        np.testing.assert_allclose(field.heights, REFERENCE.heights, rtol=1e-14, atol=1e-20)


def test_round_trip_through_surface_topography_keeps_grid_and_heights(tmp_path):
    periodic = surfaces.self_affine(surfaces.Grid((16, 12), (1e-4, 0.75e-4), periodic=True), hurst=0.8,
                                    rms_height=1e-6, rng=1)
    topography = to_topography(periodic)
    assert topography.is_periodic and topography.unit == "m" and topography.nb_grid_pts == (16, 12)
    back = from_topography(topography)
    assert back == periodic and back.metadata["unit"] == "m"
    profile = HeightField.from_array(np.linspace(0, 1e-6, 10), 1e-5)
    line = to_topography(profile)
    assert line.dim == 1 and from_topography(line) == profile
    topography.to_netcdf(str(tmp_path / "periodic.nc"))
    assert read_topography(tmp_path / "periodic.nc").grid.periodic == (True, True)       # carried by the file
    assert read_topography(tmp_path / "periodic.nc", periodic=False).grid.periodic == (False, False)
    with pytest.raises(ValueError, match="one periodicity flag"):
        to_topography(HeightField(surfaces.Grid((4, 4), (1.0, 1.0), periodic=(True, False)), np.zeros((4, 4))))


def test_undefined_points_are_refused_or_filled_harmonically(tmp_path):
    """Undefined points (a NaN hole in a float x3p, as instruments mark them) are never filled silently; the
    harmonic fill reproduces a discretely harmonic surface exactly (independent reference: the surface itself)."""
    x, y = REFERENCE.grid.meshgrid()
    harmonic = 2e-3 * x + 1e-3 * y + 4e2 * (x ** 2 - y ** 2) + 3e2 * x * y      # five-point Laplacian zero
    holed = harmonic.copy()
    holed[5:9, 4:7] = np.nan                                                    # an interior hole, 12 points
    path = write_x3p(tmp_path / "holed.x3p", holed, DX_UM * 1e-6, DY_UM * 1e-6)
    with pytest.raises(ValueError, match=r"holed.x3p has 12 missing heights .* of 384, the first at index \[5, 4\]"
                                         r".*missing='crop'.*pixels 9:24 x 0:16, 62% of the map"):
        read_topography(path)
    filled = read_topography(path, missing="harmonic")                  # 12 of 384 points: 3 %, not warned
    assert filled.metadata["missing_points"] == 12 and filled.metadata["filled_fraction"] == 12 / 384
    # the fill solves the five-point Laplace equation: exact to round-off (1e-22 m against 1e-9 m curvature terms)
    np.testing.assert_allclose(filled.heights, harmonic, rtol=0, atol=1e-20)
    assert np.abs(np.nanmean(holed) - harmonic[5:9, 4:7]).max() > 1e-10        # a mean fill would be far off


def test_tilt_is_removed_on_request_only(tmp_path):
    path = write_x3p(tmp_path / "scan.x3p", HEIGHTS_UM * 1e-6, DX_UM * 1e-6, DY_UM * 1e-6)
    assert read_topography(path) == REFERENCE                                  # no silent detrending
    levelled = read_topography(path, detrend="plane")
    expected = REFERENCE.detrended("plane")
    np.testing.assert_allclose(levelled.heights, expected.heights, rtol=0, atol=1e-20)
    assert abs(levelled.heights.mean()) < 1e-20


def test_unreadable_files_and_missing_metadata_are_named(tmp_path):
    junk = tmp_path / "junk.bin"
    junk.write_bytes(b"\x00\x01binary junk" * 10)
    with pytest.raises(ValueError, match="junk.bin is not a topography file SurfaceTopography can read"):
        read_topography(junk)
    with pytest.raises(ValueError, match="no such file"):
        read_topography(tmp_path / "absent.x3p")
    path = write_x3p(tmp_path / "scan.x3p", HEIGHTS_UM * 1e-6, DX_UM * 1e-6, DY_UM * 1e-6)
    with pytest.raises(ValueError, match=r"channel = 3 is out of range; scan.x3p has channels 0..0"):
        read_topography(path, channel=3)
    with pytest.raises(ValueError, match="stores its unit"):
        read_topography(path, unit="um")
    xyz = write_xyz(tmp_path / "scan.xyz")
    with pytest.raises(ValueError, match="stores no length unit; pass unit="):
        read_topography(xyz)
    with pytest.raises(ValueError, match="has no unit"):
        from_topography(st.Topography(HEIGHTS_UM, (1.0, 1.0)))
    with pytest.raises(ValueError, match="missing = 'zero' is not valid"):
        read_topography(path, missing="zero")


def test_surface_topography_is_imported_lazily_and_its_absence_explained(monkeypatch):
    code = "import surfaces, surfaces.topography, sys; print('SurfaceTopography' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "False"
    monkeypatch.setitem(sys.modules, "SurfaceTopography", None)                 # as if not installed
    with pytest.raises(ImportError, match=r"pip install 'roughcontact\[topography\]'"):
        to_topography(REFERENCE)


def test_measured_topographies_section_of_the_docs_runs(capsys):
    """The Python block of docs/guide/surfaces.md §7 runs and prints the shape it read from the x-y-z export."""
    text = (Path(__file__).resolve().parents[2] / "docs" / "guide" / "surfaces.md").read_text()
    section = text[text.index("## 7. Measured topographies"):]
    blocks = re.findall(r"^```python\n(.*?)^```", section, re.MULTILINE | re.DOTALL)
    assert blocks
    namespace = {}
    for number, code in enumerate(blocks, 1):
        exec(compile(code, f"docs/guide/surfaces.md §7, python block {number}", "exec"), namespace)
    grid = namespace["from_text"].grid          # sizes through µm text and back: a few ulp
    assert grid.shape == (64, 48) and grid.periodic == (False, False)
    assert grid.lengths == pytest.approx((0.2e-3, 0.15e-3), rel=1e-12)
    # the plane fit is linear: the scan's slopes minus the window's own are the added tilt, to round-off
    assert namespace["tilt"] == pytest.approx([0.02, 0.0], abs=1e-12)
    assert capsys.readouterr().out.startswith("(64, 48) [")


# -- issue 36: missing data visible and bounded, every reader's arguments, non-square pixels -------------------
def bordered_x3p(tmp_path):
    """A 40 x 30 scan [m] measured inside pixels 6:34 x 5:25 only, with three lone spike pixels of 300 µm
    measured in the missing border band (what an .frt file of SurfaceTopography's examples holds: 31 % of its
    points undefined, spikes at its border)."""
    heights = REFERENCE.resampled((40, 30)).heights.copy()
    band = np.ones(heights.shape, bool)
    band[6:34, 5:25] = False
    heights[band] = np.nan
    heights[0, 3] = heights[39, 29] = heights[2, 28] = 300e-6
    return write_x3p(tmp_path / "bordered.x3p", heights, 0.5e-6, 0.8e-6), heights


def test_a_filled_border_band_is_warned_and_crop_keeps_the_measured_window(tmp_path):
    path, heights = bordered_x3p(tmp_path)
    missing = int(np.isnan(heights).sum())                               # 1200 - 560 - 3 = 637: 53 %
    with pytest.warns(surfaces.MissingDataWarning, match=rf"bordered.x3p: missing='harmonic' invented {missing} of "
                                                         r"its 1200 heights \(53.1%.*pixels 6:34 x 5:25, 47%"):
        filled = read_topography(path, missing="harmonic", detrend="plane")
    # the record stays on top of the detrended field's metadata, where a report reads it
    assert filled.metadata["filled_fraction"] == missing / 1200 and filled.metadata["missing_points"] == missing
    assert filled.metadata["generator"] == "detrended"
    # the fill spreads each lone 300 µm pixel into a mound: invented heights far above anything measured inside
    inside = heights[6:34, 5:25]
    with pytest.warns(surfaces.MissingDataWarning):
        mounds = read_topography(path, missing="harmonic").heights[np.isnan(heights)]
    assert mounds.max() > 50 * np.ptp(inside)                          # 257 µm against a relief of 3.5 µm
    cropped = read_topography(path, missing="crop")
    np.testing.assert_array_equal(cropped.heights, inside)
    assert cropped.grid.shape == (28, 20) and cropped.grid.spacing == pytest.approx((0.5e-6, 0.8e-6), rel=1e-12)
    assert cropped.metadata["crop"] == [[6, 34], [5, 25]] and cropped.metadata["filled_fraction"] == 0.0


def test_non_square_pixels_of_an_x3p_file_are_kept(tmp_path):
    """dy/dx = 2.5 (a real x3p file of SurfaceTopography's examples has 2.46): the grid has its true spacings."""
    heights = REFERENCE.heights[:, :10]
    field = read_topography(write_x3p(tmp_path / "ratio.x3p", heights, 0.4e-6, 1e-6))
    assert field.grid.spacing == pytest.approx((0.4e-6, 1e-6), rel=1e-14)
    assert field.grid.spacing[1] / field.grid.spacing[0] == pytest.approx(2.5, rel=1e-14)
    np.testing.assert_array_equal(field.heights, heights)


def test_every_reader_takes_unit_size_and_channel(tmp_path):
    """A matrix without unit or size read through SurfaceTopography: unit as a name or a factor, size as lengths
    or pixel_size, channel 0; the same numbers through HeightField.read (rows='y': SurfaceTopography's text
    reader takes a row as a line along x)."""
    np.savetxt(tmp_path / "plain.txt", HEIGHTS_UM.T)                     # image layout: row j along x at y_j
    pixel = (DX_UM * 1e-6, DY_UM * 1e-6)
    ours = HeightField.read(tmp_path / "plain.txt", rows="y", unit="um", pixel_size=pixel, channel=0)
    for options in (dict(unit="um", pixel_size=pixel), dict(unit=1e-6, pixel_size=pixel),
                    dict(unit="um", lengths=(NX * pixel[0], NY * pixel[1])),
                    dict(unit=1e-6, lengths=REFERENCE.grid.lengths)):
        theirs = read_topography(tmp_path / "plain.txt", channel=0, **options)
        np.testing.assert_allclose(theirs.grid.spacing, pixel, rtol=1e-12)
        np.testing.assert_allclose(theirs.heights, ours.heights, rtol=1e-14, atol=1e-20)
    with pytest.raises(ValueError, match="stores no physical size; pass lengths=.* or pixel_size"):
        read_topography(tmp_path / "plain.txt", unit="um")
    with pytest.raises(ValueError, match="unit = -1.0 is out of range"):
        read_topography(tmp_path / "plain.txt", unit=-1.0, pixel_size=pixel)
    with pytest.raises(ValueError, match=r"pixel_size\[1\] = -1.0 is out of range"):
        read_topography(tmp_path / "plain.txt", unit="um", pixel_size=(1e-6, -1.0))
    x3p = write_x3p(tmp_path / "scan.x3p", HEIGHTS_UM * 1e-6, DX_UM * 1e-6, DY_UM * 1e-6)
    with pytest.raises(ValueError, match=r"pixel_size = 1e-06 given, but scan.x3p stores its physical size"):
        read_topography(x3p, pixel_size=1e-6)


def test_empty_files_and_bad_detrend_are_named(tmp_path):
    for name in ("empty.x3p", "empty.txt"):
        (tmp_path / name).write_bytes(b"")
        with pytest.raises(ValueError, match=rf"{name} is empty \(0 bytes\), not a topography file"):
            read_topography(tmp_path / name, unit="um", lengths=(1e-3, 1e-3))
    x3p = write_x3p(tmp_path / "scan.x3p", HEIGHTS_UM * 1e-6, DX_UM * 1e-6, DY_UM * 1e-6)
    for bad in ("bogus", 3):
        with pytest.raises(ValueError, match=rf"detrend = {bad!r} is not valid; choose one of "
                                             r"\['mean', 'plane', None\]"):
            read_topography(x3p, detrend=bad)
        with pytest.raises(ValueError, match=rf"detrend = {bad!r} is not valid"):
            from_topography(st.Topography(HEIGHTS_UM, (1.0, 1.0), unit="um"), detrend=bad)
