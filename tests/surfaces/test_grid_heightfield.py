"""Grid and HeightField: geometry, immutability, arithmetic, persistence, import, pickling, plotting."""
import dataclasses
import pickle
import warnings

import numpy as np
import pytest

import surfaces
from surfaces import plotting

L = 2e-3


# -- Grid ---------------------------------------------------------------------------------------------------
def test_grid_geometry_and_wavevectors():
    grid = surfaces.Grid((5, 8), (L, 3 * L), periodic=(True, False))
    assert grid.spacing == (L / 5, 3 * L / 8) and grid.area == 3 * L ** 2 and grid.size == 40
    assert grid.pixel_area == pytest.approx(L / 5 * 3 * L / 8, rel=1e-15)
    assert grid.periodic == (True, False) and not grid.fully_periodic
    x, y = grid.coordinates()
    assert np.allclose(x, np.arange(5) * L / 5, rtol=1e-15) and np.allclose(y, np.arange(8) * 3 * L / 8)
    kx, ky = grid.mode_indices()
    assert np.array_equal(kx[:, 0], np.rint(np.fft.fftfreq(5) * 5)) and np.array_equal(
        ky[0], np.rint(np.fft.fftfreq(8) * 8))
    qx, qy = grid.wavevectors()
    assert np.allclose(qx[:, 0], 2 * np.pi * np.fft.fftfreq(5, L / 5), rtol=1e-14)
    assert np.allclose(qy[0], 2 * np.pi * np.fft.fftfreq(8, 3 * L / 8), rtol=1e-14)
    assert np.allclose(grid.wavevectors(real=True)[1][0], 2 * np.pi * np.fft.rfftfreq(8, 3 * L / 8), rtol=1e-14)
    assert np.allclose(grid.wavevector_magnitude(), np.hypot(qx, qy), rtol=1e-15)
    assert not grid.wavevector_magnitude().flags.writeable


def test_refined_grid_shares_bit_identical_wavevectors():
    grid = surfaces.Grid((7, 6), (L, 0.7 * L))
    fine = grid.refined(3)
    assert fine.shape == (21, 18) and fine.lengths == grid.lengths
    kx, ky = grid.mode_indices()
    assert np.array_equal(fine.wavevector_magnitude()[kx[:, 0]][:, ky[0]], grid.wavevector_magnitude())
    assert surfaces.Grid((16, 1), (L, L / 16)).refined(2).shape == (32, 1)
    assert surfaces.Grid((16, 1), (L, L / 16), periodic=(True, False)).fully_periodic   # profile: y irrelevant


def test_coarsened_grid_and_field_average_blocks():
    grid = surfaces.Grid((6, 4), (L, 0.5 * L), periodic=(True, False))
    assert grid.coarsened(2) == surfaces.Grid((3, 2), (L, 0.5 * L), periodic=(True, False))
    assert grid.refined(3).coarsened(3) == grid
    heights = np.arange(24.0).reshape(6, 4) * 1e-9
    coarse = surfaces.HeightField(grid, heights).coarsened(2)
    # pixel (1, 0) covers fine rows 2-3, columns 0-1: heights 8, 9, 12, 13 nm
    assert coarse.heights[1, 0] == pytest.approx(10.5e-9, rel=1e-15) and coarse.grid == grid.coarsened(2)
    assert coarse.heights.mean() == pytest.approx(heights.mean(), rel=1e-15)
    profile = surfaces.HeightField(surfaces.Grid((8, 1), (L, L / 8)), np.arange(8.0)[:, None] * 1e-9)
    np.testing.assert_allclose(profile.coarsened(4).heights[:, 0], [1.5e-9, 5.5e-9], rtol=1e-15)
    with pytest.raises(ValueError, match=r"shape\[0\] = 6 is not a multiple of factor = 4"):
        grid.coarsened(4)
    with pytest.raises(ValueError, match="factor"):
        grid.coarsened(0)


def test_grid_equality_hash_dict_and_pickle():
    grid = surfaces.Grid((4, 4), (L, L), periodic=True)
    grid.wavevector_magnitude()                                                   # fill the cache
    assert grid == surfaces.Grid([4, 4], [L, L], (True, True)) and hash(grid) == hash(surfaces.Grid((4, 4), (L, L)))
    assert grid != surfaces.Grid((4, 4), (L, L), periodic=False)
    assert surfaces.Grid.from_dict(grid.to_dict()) == grid
    restored = pickle.loads(pickle.dumps(grid))
    assert restored == grid and np.array_equal(restored.wavevector_magnitude(), grid.wavevector_magnitude())
    with pytest.raises(dataclasses.FrozenInstanceError):
        grid.shape = (2, 2)


@pytest.mark.parametrize("kwargs, name", [
    (dict(shape=(4,), lengths=(L, L)), "shape"),
    (dict(shape=(4, 0), lengths=(L, L)), "shape"),
    (dict(shape=(4.0, 4), lengths=(L, L)), "shape"),
    (dict(shape=(4, 4), lengths=(L, -L)), "lengths"),
    (dict(shape=(4, 4), lengths=(0.0, L)), "lengths"),
    (dict(shape=(4, 4), lengths=(float("nan"), L)), "lengths"),
    (dict(shape=(4, 4), lengths=(L, L), periodic=(True, False, True)), "periodic"),
    (dict(shape=(4, 4), lengths=(1e300, L)), r"lengths\[0\] = 1e\+300 is out of range; valid range \[1e-50, 1e\+50\]"),
    (dict(shape=(4, 4), lengths=(L, 1e-300)), r"lengths\[1\] = 1e-300 is out of range"),
])
def test_grid_bad_input(kwargs, name):
    with pytest.raises(ValueError, match=name):
        surfaces.Grid(**kwargs)


@pytest.mark.parametrize("periodic", ["no", 1, None, ("yes", True), (True, 0)])
def test_grid_periodic_must_be_booleans(periodic):
    with pytest.raises(TypeError, match="periodic.* must be True or False"):
        surfaces.Grid((4, 4), (L, L), periodic=periodic)


def test_grid_periodic_accepts_numpy_booleans_and_extreme_lengths_keep_a_finite_area():
    grid = surfaces.Grid((4, 4), (L, L), periodic=np.bool_(False))
    assert grid.periodic == (False, False) and type(grid.periodic[0]) is bool
    assert surfaces.Grid((4, 4), (1e50, 1e50)).area == pytest.approx(1e100, rel=1e-15)
    assert surfaces.Grid((4, 4), (1e-50, 1e-50)).pixel_area == pytest.approx(1e-100 / 16, rel=1e-15)


def test_check_messages_print_plain_numbers():
    with pytest.raises(ValueError) as error:
        surfaces.Grid((np.int64(-1), 4), (L, L))
    assert "got -1" in str(error.value) and "np." not in str(error.value)
    with pytest.raises(ValueError) as error:
        surfaces.HeightField(surfaces.Grid((2, 2), (L, L)), np.array([[0.0, -np.inf], [0.0, 0.0]]))
    assert "found -inf" in str(error.value) and "np." not in str(error.value)


# -- HeightField --------------------------------------------------------------------------------------------
GRID = surfaces.Grid((6, 5), (L, L), periodic=True)


def field_of(values, **metadata):
    return surfaces.HeightField(GRID, values, metadata)


def test_heightfield_is_immutable_and_copies_its_input():
    values = np.arange(30.0).reshape(6, 5) * 1e-6
    field = field_of(values, generator="test")
    values[0, 0] = 1.0
    assert field.heights[0, 0] == 0.0
    assert not field.heights.flags.writeable
    with pytest.raises(ValueError):
        field.heights[0, 0] = 1.0
    with pytest.raises(dataclasses.FrozenInstanceError):
        field.heights = values


def test_heightfield_arithmetic():
    a = field_of(np.full((6, 5), 1e-6), generator="a")
    b = field_of(np.arange(30.0).reshape(6, 5) * 1e-7, generator="b")
    assert np.array_equal((a + b).heights, a.heights + b.heights)
    assert (a + b).metadata == {"generator": "sum", "parts": [a.metadata, b.metadata]}
    assert np.array_equal((a - b).heights, a.heights - b.heights)
    assert np.array_equal((2.0 * b).heights, 2 * b.heights) and (b * 2) == (2 * b)
    assert np.array_equal((b / 4).heights, b.heights * 0.25)
    assert np.array_equal((1e-6 - b).heights, 1e-6 - b.heights) and np.array_equal((b + 1e-6).heights,
                                                                                   b.heights + 1e-6)
    assert np.array_equal((-b).heights, -b.heights)
    assert sum([a, b, b]) == a + b + b                                     # builtin sum starts from 0
    other = surfaces.HeightField(surfaces.Grid((6, 5), (L, L), periodic=False), a.heights)
    with pytest.raises(ValueError, match="different grids"):
        a + other
    with pytest.raises(ValueError, match="offset"):
        a + float("nan")
    with pytest.raises(ValueError, match="factor"):
        a * float("inf")
    with pytest.raises(ValueError, match="divisor"):
        a / 0
    with pytest.raises(TypeError):
        a + "1"
    for combine in (lambda: a + np.ones(GRID.shape), lambda: np.ones(GRID.shape) + a,
                    lambda: np.ones(GRID.shape) * a, lambda: a - np.ones(GRID.shape)):
        with pytest.raises(TypeError, match="HeightField and a numpy array of shape"):
            combine()                                  # not an object array of 30 HeightFields
    assert (a * np.float64(2.0)).heights[0, 0] == 2e-6 and (np.float64(2.0) * a) == a * 2.0
    assert b.detrended().heights.mean() == pytest.approx(0, abs=1e-20)     # round-off of 30 values ~3e-6


@pytest.mark.parametrize("values, match", [
    (np.full((6, 5), np.nan), "heights"),
    (np.zeros((5, 6)), "shape"),
])
def test_heightfield_bad_heights(values, match):
    with pytest.raises(ValueError, match=match):
        field_of(values)


def test_complex_heights_are_refused_everywhere(tmp_path):
    values = np.ones((6, 5)) * (1 + 0j)                    # complex even with a zero imaginary part
    np.save(tmp_path / "complex.npy", values)
    for make in (lambda: field_of(values), lambda: surfaces.HeightField.from_array(values, L),
                 lambda: surfaces.HeightField.read(tmp_path / "complex.npy", lengths=L)):
        with pytest.raises(TypeError, match="heights must be real, got complex"):
            make()


def test_save_load_round_trip_is_exact(tmp_path):
    grid = surfaces.Grid((33, 20), (L, 0.6 * L), periodic=(False, True))
    field = surfaces.self_affine(grid, hurst=0.6, rms_height=1e-6, rng=np.int64(3))
    path = field.save(tmp_path / "rough")
    assert path.suffix == ".npz"
    loaded = surfaces.HeightField.load(path)
    assert loaded == field and loaded.grid == grid
    assert np.array_equal(loaded.heights, field.heights) and loaded.metadata == field.metadata
    assert surfaces.HeightField.read(path) == field
    assert surfaces.self_affine(grid, **{k: loaded.metadata[k] for k in ("hurst", "rms_height")},
                                rng=loaded.metadata["seed"]) == field           # regenerated from the record
    other = tmp_path / "other.npz"
    surfaces.io.save_npz(other, {"x": np.zeros(2)}, {"kind": "Something"})
    with pytest.raises(ValueError, match="HeightField"):
        surfaces.HeightField.load(other)


def test_read_plain_height_maps(tmp_path):
    values_um = np.random.default_rng(0).standard_normal((12, 9))
    np.save(tmp_path / "map.npy", values_um)
    np.savetxt(tmp_path / "map.txt", values_um)
    np.savetxt(tmp_path / "profile.txt", values_um[:, 0])
    for name in ("map.npy", "map.txt"):
        field = surfaces.HeightField.read(tmp_path / name, lengths=(L, 0.75 * L), unit=1e-6)
        assert field.grid == surfaces.Grid((12, 9), (L, 0.75 * L), periodic=False)
        assert np.allclose(field.heights, values_um * 1e-6, rtol=1e-15, atol=0)
    profile = surfaces.HeightField.read(tmp_path / "profile.txt", lengths=L, unit=1e-6)
    assert profile.grid.is_profile and profile.grid.spacing[0] == pytest.approx(L / 12, rel=1e-15)
    with pytest.raises(ValueError, match="lengths"):
        surfaces.HeightField.read(tmp_path / "map.npy")
    with pytest.raises(ValueError, match="unit"):
        surfaces.HeightField.read(tmp_path / "map.npy", lengths=L, unit=-1.0)


def test_from_array():
    field = surfaces.HeightField.from_array(np.ones((4, 3)), (L, L), periodic=True, source="test")
    assert field.grid == surfaces.Grid((4, 3), (L, L), True) and field.metadata["source"] == "test"
    assert surfaces.HeightField.from_array(np.ones((4, 4)), L).grid.lengths == (L, L)
    square = surfaces.HeightField.from_array(np.ones((4, 3)), pixel_size=L / 4)
    assert square.grid.lengths == (L, 0.75 * L) and square.grid.spacing == (L / 4, L / 4)
    assert surfaces.HeightField.from_array(np.ones((4, 3)), pixel_size=(1e-6, 2e-6)).grid.lengths == (4e-6, 6e-6)
    with pytest.raises(ValueError, match=r"lengths = 0.002 is one number for a map of shape \(4, 3\).*non-square"):
        surfaces.HeightField.from_array(np.ones((4, 3)), L)              # would give non-square pixels silently
    with pytest.raises(ValueError, match="exactly one of them"):
        surfaces.HeightField.from_array(np.ones((4, 3)), (L, L), pixel_size=L / 4)
    with pytest.raises(ValueError, match=r"pixel_size\[1\] = -1.0 is out of range"):
        surfaces.HeightField.from_array(np.ones((4, 3)), pixel_size=(1.0, -1.0))
    assert surfaces.HeightField.from_array(np.ones(8), L).grid.shape == (8, 1)
    for empty in (np.zeros(0), np.zeros((3, 0))):
        with pytest.raises(ValueError, match="heights is empty"):
            surfaces.HeightField.from_array(empty, 1.0)


def test_pickle_round_trip_keeps_field_read_only():
    field = surfaces.self_affine(surfaces.Grid((16, 16), (L, L)), hurst=0.8, rms_height=1e-6, rng=1)
    restored = pickle.loads(pickle.dumps(field))
    assert restored == field and restored.metadata == field.metadata
    assert not restored.heights.flags.writeable


# -- plotting (smoke test, Agg) -----------------------------------------------------------------------------
def test_plotting_helpers_return_their_artists():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rc_before = dict(matplotlib.rcParams)
    field = surfaces.self_affine(surfaces.Grid((32, 24), (L, L)), hurst=0.8, rms_height=1e-6, rng=2)
    figure, axes = plt.subplots(1, 3)
    try:
        image = plotting.plot_map(field, ax=axes[0])
        assert image.axes is axes[0] and np.allclose(image.get_array(), field.heights.T * 1e6)
        line = plotting.plot_profile(field, ax=axes[1], axis=1, index=3)
        assert np.allclose(line.get_ydata(), field.heights[3] * 1e6)
        psd_line = plotting.plot_psd(field, ax=axes[2])
        assert np.allclose(psd_line.get_xdata(), surfaces.psd(field)[0])
        with pytest.raises(ValueError, match="index"):
            plotting.plot_profile(field, ax=axes[1], index=99)
        own = plotting.plot_psd(field)                                          # ax=None makes a figure
        assert own.figure is not figure
        plt.close(own.figure)
    finally:
        plt.close(figure)
    assert dict(matplotlib.rcParams) == rc_before


# -- text exports, units, missing data, tilt, mirroring --------------------------------------------------------
def xyz_lines(heights_um, dx_um, dy_um, delimiter=" ", skip=()):
    """x y z lines of a map in micrometres, y outer, x inner (an export's usual order), without points ``skip``."""
    nx, ny = heights_um.shape
    return "".join(f"{i * dx_um!r}{delimiter}{j * dy_um!r}{delimiter}{float(heights_um[i, j])!r}\n"
                   for j in range(ny) for i in range(nx) if (i, j) not in skip)


MAP_UM = np.random.default_rng(5).standard_normal((7, 5))


@pytest.mark.parametrize("delimiter, suffix", [(" ", "xyz"), (",", "csv"), (";", "txt"), ("\t", "dat")])
def test_xyz_exports_are_regridded_not_read_as_a_three_column_map(tmp_path, delimiter, suffix):
    path = tmp_path / f"scan.{suffix}"
    path.write_text("# exported scan, x y z in um\n" + xyz_lines(MAP_UM, 0.25, 0.4, delimiter))
    field = surfaces.HeightField.read(path, unit="um")
    assert field.grid.shape == (7, 5) and field.grid.periodic == (False, False)
    np.testing.assert_allclose(field.grid.spacing, (0.25e-6, 0.4e-6), rtol=1e-14)       # lattice step: a few ulp
    np.testing.assert_allclose(field.grid.lengths, (7 * 0.25e-6, 5 * 0.4e-6), rtol=1e-14)
    np.testing.assert_allclose(field.heights, MAP_UM * 1e-6, rtol=1e-15)
    assert field.metadata["layout"] == "columns"
    nm_heights = surfaces.HeightField.read(path, unit=1e-9, lateral_unit="um")     # z in nm, x and y in um
    np.testing.assert_allclose(nm_heights.heights, MAP_UM * 1e-9, rtol=1e-15)
    assert nm_heights.grid.lengths == field.grid.lengths


def test_xz_profile_export_and_comma_matrix(tmp_path):
    (tmp_path / "profile.csv").write_text("".join(f"{i * 0.5!r},{float(v)!r}\n" for i, v in enumerate(MAP_UM[:, 0])))
    profile = surfaces.HeightField.read(tmp_path / "profile.csv", unit="um")
    assert profile.grid.is_profile and profile.grid.lengths == pytest.approx((3.5e-6, 0.5e-6), rel=1e-14)
    np.testing.assert_allclose(profile.heights[:, 0], MAP_UM[:, 0] * 1e-6, rtol=1e-15)
    np.savetxt(tmp_path / "map.csv", MAP_UM, delimiter=",")                      # a comma matrix, 5 columns
    matrix = surfaces.HeightField.read(tmp_path / "map.csv", pixel_size=1e-6, unit="um")
    assert matrix.grid.lengths == pytest.approx((7e-6, 5e-6), rel=1e-15)            # 5 * 1e-6 in float64
    np.testing.assert_allclose(matrix.heights, MAP_UM * 1e-6, rtol=1e-15)


def test_text_layout_is_detected_or_refused_with_a_remedy(tmp_path):
    three_wide = np.random.default_rng(1).standard_normal((6, 3))               # a map 3 pixels wide
    np.savetxt(tmp_path / "narrow.txt", three_wide)
    with pytest.raises(ValueError, match=r"3 columns that are not an x-y-z .*pass layout='matrix'"):
        surfaces.HeightField.read(tmp_path / "narrow.txt", lengths=(1e-3, 0.5e-3))
    narrow = surfaces.HeightField.read(tmp_path / "narrow.txt", lengths=(1e-3, 0.5e-3), layout="matrix")
    assert narrow.grid.shape == (6, 3)
    path = tmp_path / "scan.xyz"
    path.write_text(xyz_lines(MAP_UM, 0.25, 0.4))
    with pytest.raises(ValueError, match="column export, which fixes the pixel size"):
        surfaces.HeightField.read(path, lengths=1e-3)
    with pytest.raises(ValueError, match=r"y column is not on a regular lattice"):
        (tmp_path / "off.xyz").write_text(xyz_lines(MAP_UM, 0.25, 0.4).replace("\n0.0 0.4 ", "\n0.0 0.5 ", 1))
        surfaces.HeightField.read(tmp_path / "off.xyz", layout="columns")
    (tmp_path / "nan.xyz").write_text(xyz_lines(MAP_UM, 0.25, 0.4) + "nan 0.0 1.0\n")
    with pytest.raises(ValueError, match=r"the x column holds nan in data row 36; coordinates must be finite"):
        surfaces.HeightField.read(tmp_path / "nan.xyz", layout="columns")
    (tmp_path / "twice.xyz").write_text(xyz_lines(MAP_UM, 0.25, 0.4) + "0.0 0.0 1.0\n")
    with pytest.raises(ValueError, match=r"point \(x index 0, y index 0\) is given 2 times"):
        surfaces.HeightField.read(tmp_path / "twice.xyz", layout="columns")


def test_missing_points_are_refused_or_filled(tmp_path):
    """An export without two points, and a matrix with a NaN: refused by default, filled on request; the
    harmonic fill reproduces a discretely harmonic surface (a + bx + cy + e xy + f(x² − y²)) exactly."""
    x, y = np.meshgrid(np.arange(7) * 0.25, np.arange(5) * 0.4, indexing="ij")
    harmonic_um = 0.3 + 0.2 * x - 0.1 * y + 0.05 * x * y + 0.07 * (x ** 2 - y ** 2)
    path = tmp_path / "holes.xyz"
    path.write_text(xyz_lines(harmonic_um, 0.25, 0.4, skip={(3, 2), (4, 2)}))
    with pytest.raises(ValueError, match=r"2 missing heights .* of 35, the first at index \[3, 2\].*harmonic"):
        surfaces.HeightField.read(path, unit="um")
    with pytest.warns(surfaces.MissingDataWarning, match=r"invented 2 of its 35 heights \(5.7%, above 5%\)"):
        filled = surfaces.HeightField.read(path, unit="um", missing="harmonic")
    # the five-point Laplacian of the surface is zero, so the fill is exact to round-off (heights ~1e-6 m)
    np.testing.assert_allclose(filled.heights, harmonic_um * 1e-6, rtol=0, atol=1e-20)
    assert filled.metadata["missing_points"] == 2 and filled.metadata["filled_fraction"] == 2 / 35
    holed = harmonic_um.copy()
    holed[2, 1] = np.nan
    np.savetxt(tmp_path / "holed.txt", holed)
    with pytest.raises(ValueError, match="1 missing heights"):
        surfaces.HeightField.read(tmp_path / "holed.txt", pixel_size=(0.25e-6, 0.4e-6), unit="um")
    matrix = surfaces.HeightField.read(tmp_path / "holed.txt", pixel_size=(0.25e-6, 0.4e-6), unit="um",
                                       missing="harmonic")
    np.testing.assert_allclose(matrix.heights, harmonic_um * 1e-6, rtol=0, atol=1e-20)
    with pytest.raises(ValueError, match="every height is missing"):
        surfaces.heightfield.harmonic_fill(np.zeros((3, 3)), np.ones((3, 3), bool), (1.0, 1.0))


def test_binary_and_malformed_files_are_named_clearly(tmp_path):
    import zipfile
    with zipfile.ZipFile(tmp_path / "scan.x3p", "w") as archive:
        archive.writestr("main.xml", "<x/>")
    with pytest.raises(ValueError, match=r"scan.x3p is a zip container.*read_topography"):
        surfaces.HeightField.read(tmp_path / "scan.x3p", lengths=L)
    (tmp_path / "scan.sur").write_bytes(b"DIGITAL SURF\xff\xfe\x00\x01")
    with pytest.raises(ValueError, match=r"scan.sur is not UTF-8 text \(byte 12"):
        surfaces.HeightField.read(tmp_path / "scan.sur", lengths=L)
    (tmp_path / "header.csv").write_text("x,y,z\n0,0,1\n1,0,2\n")
    with pytest.raises(ValueError, match=r"header.csv, line 1: 'x,y,z' is not a row of numbers .*skiprows"):
        surfaces.HeightField.read(tmp_path / "header.csv")
    assert surfaces.HeightField.read(tmp_path / "header.csv", skiprows=1, unit="mm").grid.lengths == (2e-3, 1e-3)
    (tmp_path / "ragged.txt").write_text("1 2 3 4\n1 2 3\n")
    with pytest.raises(ValueError, match="line 2: 3 columns, but the first data row has 4"):
        surfaces.HeightField.read(tmp_path / "ragged.txt", lengths=L)
    with pytest.raises(ValueError, match="'inch' is not a known length unit"):
        surfaces.HeightField.read(tmp_path / "ragged.txt", lengths=L, unit="inch")
    with pytest.raises(ValueError, match="rows = 'z' is not valid"):
        surfaces.HeightField.read(tmp_path / "ragged.txt", lengths=L, rows="z")


def test_plane_detrend_removes_exactly_the_tilt():
    """A tilted plane plus a field orthogonal to {1, x, y} on the grid (a product of zero-sum cosines): the
    plane fit returns the field itself and the slopes; a mean detrend would leave the tilt."""
    grid = surfaces.Grid((12, 8), (L, 0.5 * L), periodic=False)
    x, y = grid.meshgrid()
    bumps = 1e-6 * np.cos(2 * np.pi * np.arange(12) / 12)[:, None] * np.cos(2 * np.pi * np.arange(8) / 8)[None, :]
    tilted = surfaces.HeightField(grid, bumps + 3e-6 + 2e-3 * x - 5e-3 * y)
    levelled = tilted.detrended("plane")
    np.testing.assert_allclose(levelled.heights, bumps, rtol=0, atol=1e-20)          # round-off of ~1e-5 m terms
    assert levelled.metadata["slopes"] == pytest.approx([2e-3, -5e-3], rel=1e-12)
    assert np.abs(tilted.detrended().heights - bumps).max() > 1e-6
    profile = surfaces.HeightField.from_array(4e-3 * np.arange(9.0) * 1e-4, 9e-4)
    np.testing.assert_allclose(profile.detrended("plane").heights, 0, atol=1e-20)
    with pytest.raises(ValueError, match="a tilted plane is not periodic"):
        surfaces.HeightField(GRID, np.zeros(GRID.shape)).detrended("plane")


def test_mirrored_window_is_periodic_without_edge_steps():
    window = surfaces.self_affine(surfaces.Grid((6, 5), (L, 0.8 * L), periodic=False), hurst=0.8, rms_height=1e-6,
                                  rng=3)
    mirrored = window.mirrored()
    assert mirrored.grid == surfaces.Grid((12, 10), (2 * L, 1.6 * L), periodic=True)
    h = mirrored.heights
    assert np.array_equal(h[:6, :5], window.heights) and np.array_equal(h[::-1, ::-1][:6, :5], window.heights)
    # the periodic repeat joins each edge pixel to itself: zero height step across both wrap-arounds
    assert np.array_equal(h[0], h[-1]) and np.array_equal(h[:, 0], h[:, -1])
    profile = surfaces.HeightField.from_array(np.arange(4.0) * 1e-6, 4e-6).mirrored()
    assert profile.grid.shape == (8, 1) and profile.heights[:, 0].tolist() == [0, 1e-6, 2e-6, 3e-6, 3e-6, 2e-6, 1e-6, 0]
    with pytest.raises(ValueError, match="already periodic"):
        mirrored.mirrored()


def test_saving_onto_a_directory_is_refused(tmp_path):
    # a directory given as the file to write used to write "<directory>.npz" beside it without a word
    with pytest.raises(IsADirectoryError, match="is a directory"):
        surfaces.io.save_npz(tmp_path, {"x": np.zeros(2)}, {"kind": "Something"})
    assert not tmp_path.with_suffix(".npz").exists()


# -- missing data: the measured window, the fill's warning and its memory bound (issue 36) ------------------------
def largest_rectangle_by_search(measured):
    """The area of the largest all-True rectangle, by trying every rectangle (the independent reference)."""
    n, m = measured.shape
    filled = np.pad(np.cumsum(np.cumsum(measured, 0), 1), ((1, 0), (1, 0)))      # summed-area table
    return max((i1 - i0) * (j1 - j0) for i0 in range(n) for i1 in range(i0 + 1, n + 1) for j0 in range(m)
               for j1 in range(j0 + 1, m + 1)
               if filled[i1, j1] - filled[i0, j1] - filled[i1, j0] + filled[i0, j0] == (i1 - i0) * (j1 - j0))


@pytest.mark.parametrize("density", [0.5, 0.8, 0.95])
def test_measured_window_is_the_largest_fully_measured_rectangle(density):
    rng = np.random.default_rng(int(100 * density))
    for shape in [(7, 9), (1, 6), (6, 1), (8, 8)]:
        for _ in range(20):
            measured = rng.random(shape) < density
            if not measured.any():
                continue
            (i0, i1), (j0, j1) = surfaces.heightfield.measured_window(measured)
            assert measured[i0:i1, j0:j1].all()
            assert (i1 - i0) * (j1 - j0) == largest_rectangle_by_search(measured)
    with pytest.raises(ValueError, match="no pixel of the 3 x 4 map is measured"):
        surfaces.heightfield.measured_window(np.zeros((3, 4), bool))


def bordered_scan(tmp_path, band=2, spikes=True):
    """A 12 x 10 matrix [µm] measured only inside rows 3..9, columns 2..8 (a border band missing, as an
    instrument leaves it around a sample), with two lone spike pixels of 300 µm measured in the band."""
    heights = np.add.outer(np.arange(12.0), 0.1 * np.arange(10.0))
    heights[:3], heights[10:], heights[:, :2], heights[:, 9:] = np.nan, np.nan, np.nan, np.nan
    if spikes:
        heights[0, 5] = heights[11, 0] = 300.0
    np.savetxt(tmp_path / "bordered.txt", heights)
    return tmp_path / "bordered.txt", heights


def test_missing_crop_keeps_the_measured_window_and_says_so(tmp_path):
    path, heights = bordered_scan(tmp_path)
    pixel = (1e-6, 2.5e-6)                                              # non-square pixels survive the crop
    with pytest.raises(ValueError, match=r"bordered.txt has 69 missing heights .* of 120.*missing='crop'.*pixels "
                                         r"3:10 x 2:9, 41% of the map.*missing='harmonic'"):
        surfaces.HeightField.read(path, pixel_size=pixel, unit="um")
    cropped = surfaces.HeightField.read(path, pixel_size=pixel, unit="um", missing="crop", periodic=True)
    np.testing.assert_array_equal(cropped.heights, heights[3:10, 2:9] * 1e-6)
    assert cropped.grid.shape == (7, 7) and cropped.grid.spacing == pytest.approx(pixel, rel=1e-15)
    assert cropped.grid.periodic == (False, False)                      # a cut window does not repeat
    assert cropped.metadata["crop"] == [[3, 10], [2, 9]] and cropped.metadata["filled_fraction"] == 0.0
    assert cropped.metadata["missing_points"] == 69 and cropped.metadata["kept_fraction"] == 49 / 120


def test_harmonic_fill_warns_above_five_percent_and_records_what_it_invented(tmp_path):
    """The fill of the border band spreads the two lone spikes into mounds a hundred times the measured relief:
    a MissingDataWarning with the fraction and the crop; below 5 % it is recorded, not warned."""
    path, heights = bordered_scan(tmp_path)
    with pytest.warns(surfaces.MissingDataWarning, match=r"invented 69 of its 120 heights \(57.5%.*pixels 3:10 x "
                                                         r"2:9, 41% of the map"):
        filled = surfaces.HeightField.read(path, pixel_size=1e-6, unit="um", missing="harmonic")
    assert filled.metadata["filled_fraction"] == 69 / 120
    measured = heights[3:10, 2:9]
    relief = measured.max() - measured.min()                            # 6.6 µm
    band = np.isnan(heights)
    assert (filled.heights[band] * 1e6 - measured.max()).max() > 10 * relief      # the spikes' mounds
    holed = np.add.outer(np.arange(8.0), np.arange(8.0))
    holed[3, 4] = holed[5, 1] = holed[6, 6] = np.nan                    # 3 of 64 = 4.7 %
    np.savetxt(tmp_path / "holed.txt", holed)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        few = surfaces.HeightField.read(tmp_path / "holed.txt", pixel_size=1e-6, missing="harmonic")
    assert few.metadata["filled_fraction"] == 3 / 64
    np.testing.assert_allclose(few.heights, np.add.outer(np.arange(8.0), np.arange(8.0)), rtol=1e-14)   # planar


def test_harmonic_fill_refuses_more_points_than_it_can_hold():
    """A 2048² map with 90 % missing (a compact hole) needed about 8 GB in scipy's sparse LU, and crashed the
    interpreter under a memory cap; it is refused before anything is allocated, naming the count and the limit."""
    missing = np.zeros((2048, 2048), bool)
    missing[100:2043, 100:2043] = True
    with pytest.raises(ValueError, match=r"3775249 missing heights of a 2048 x 2048 map exceed max_points = 524288"):
        surfaces.heightfield.harmonic_fill(np.zeros(missing.shape), missing, (1.0, 1.0))
    small = np.zeros((6, 6), bool)
    small[2:4, 2:4] = True
    with pytest.raises(ValueError, match="4 missing heights of a 6 x 6 map exceed max_points = 3"):
        surfaces.heightfield.harmonic_fill(np.zeros((6, 6)), small, (1.0, 1.0), max_points=3)
    assert surfaces.heightfield.harmonic_fill(np.ones((6, 6)), small, (1.0, 1.0), max_points=4) == \
        pytest.approx(np.ones((6, 6)), rel=1e-14)


# -- crop and resample ------------------------------------------------------------------------------------------
def test_cropped_by_pixels_and_by_metres():
    field = surfaces.self_affine(surfaces.Grid((12, 10), (1.2e-3, 2.5e-3), periodic=True), hurst=0.8,
                                 rms_height=1e-6, rng=4)                 # dx = 0.1 mm, dy = 0.25 mm
    part = field.cropped((2, 9), None)
    np.testing.assert_array_equal(part.heights, field.heights[2:9])
    assert part.grid.shape == (7, 10) and part.grid.periodic == (False, True)
    assert part.grid.lengths == pytest.approx((7e-4, 2.5e-3), rel=1e-15)
    assert part.metadata["x"] == [2, 9] and part.metadata["y"] == [0, 10]
    by_length = field.cropped((0.2e-3, 0.9e-3), (0.5e-3, 2.0e-3), by="metres")   # x = 2..8, y = 2..7 pixels
    np.testing.assert_array_equal(by_length.heights, field.heights[2:9, 2:8])
    assert by_length.grid.spacing == pytest.approx(field.grid.spacing, rel=1e-15)
    assert by_length.grid.periodic == (False, False)
    assert field.cropped((0.21e-3, 0.31e-3), None, by="metres").shape == (1, 10)   # pixel 3 only, at 0.3 mm
    with pytest.raises(ValueError, match=r"x = \(0.00021, 0.0003\) keeps no pixel"):     # [0.21, 0.3) mm: none
        field.cropped((0.21e-3, 0.3e-3), None, by="metres")
    profile = surfaces.HeightField.from_array(np.arange(8.0) * 1e-6, 8e-6)
    assert profile.cropped((3, 8)).heights[:, 0].tolist() == pytest.approx([3e-6, 4e-6, 5e-6, 6e-6, 7e-6])
    for bad, message in [(dict(x=(5, 5)), r"x = \(5, 5\) keeps no pixel"),
                         (dict(x=(0, 13)), r"x\[1\] must be .*\[0, 12\]"),
                         (dict(y=(1.5, 4)), r"y\[0\] must be an integer"), (dict(x=(0, 2, 4)), "pair"),
                         (dict(x=(0, 3e-3), by="metres"), r"x\[1\] = 0.003 is out of range"),
                         (dict(x=(0, 2), by="inches"), "by = 'inches' is not valid")]:
        with pytest.raises(ValueError, match=message):
            field.cropped(**bad)
    with pytest.raises(ValueError, match="crop a profile along x only"):
        profile.cropped(None, (0, 1))


def cell_average_by_repetition(heights, shape):
    """The area-weighted resampling by another route: split every old pixel into n_new sub-cells per axis and
    every new pixel into n_old, then average blocks (independent of the sparse overlap weights)."""
    (nx, ny), (mx, my) = heights.shape, shape
    fine = np.repeat(np.repeat(heights, mx, axis=0), my, axis=1)           # (nx mx, ny my)
    return fine.reshape(mx, nx, my, ny).mean(axis=(1, 3))


def test_resampled_takes_any_shape_and_keeps_the_mean():
    field = surfaces.self_affine(surfaces.Grid((30, 20), (3e-4, 5e-4), periodic=False), hurst=0.8,
                                 rms_height=1e-6, rng=2)
    for shape in [(7, 9), (30, 20), (45, 31), (1 + 30, 3)]:
        resampled = field.resampled(shape)
        assert resampled.grid == surfaces.Grid(shape, field.grid.lengths, periodic=False)
        # fractions of exact integer overlaps: round-off of a few ulp of the 1e-6 m heights
        np.testing.assert_allclose(resampled.heights, cell_average_by_repetition(field.heights, shape),
                                   rtol=0, atol=1e-20)
        assert resampled.heights.mean() == pytest.approx(field.heights.mean(), abs=1e-21)
    np.testing.assert_allclose(field.resampled((10, 5)).heights, field.coarsened(1).heights.reshape(10, 3, 5, 4)
                               .mean(axis=(1, 3)), rtol=0, atol=1e-21)
    np.testing.assert_allclose(field.resampled((15, 10)).heights, field.coarsened(2).heights, rtol=0, atol=1e-21)
    np.testing.assert_array_equal(field.resampled((60, 40)).heights[::2, ::2], field.heights)   # repeated pixels
    profile = surfaces.HeightField.from_array(np.arange(6.0) * 1e-6, 6e-6)
    four = profile.resampled((4, 1)).heights[:, 0]                     # each new pixel covers 1.5 old ones
    assert four == pytest.approx(np.array([1, 5, 10, 14]) / 3 * 1e-6, rel=1e-14)
    with pytest.raises(ValueError, match=r"turn a 2-D map of shape \(30, 20\) into a profile"):
        field.resampled((30, 1))
    with pytest.raises(ValueError, match=r"shape\[0\] must be an integer in \[1, inf\], got 0"):
        field.resampled((0, 3))
    with pytest.raises(ValueError, match=r"factor = 7.*resampled\(shape\) takes any shape"):
        field.coarsened(7)


def test_non_square_pixels_survive_reading_and_resample_to_square(tmp_path):
    """dy/dx = 2.5, as in real x3p files: the matrix and the column export keep the true spacings; resampling y
    to the x pixel gives square pixels on the same window."""
    heights = np.random.default_rng(9).standard_normal((10, 4))
    np.savetxt(tmp_path / "map.txt", heights)
    matrix = surfaces.HeightField.read(tmp_path / "map.txt", pixel_size=(0.4e-6, 1e-6), unit="um")
    (tmp_path / "map.xyz").write_text(xyz_lines(heights, 0.4, 1.0))
    export = surfaces.HeightField.read(tmp_path / "map.xyz", unit="um")
    for field in (matrix, export):
        assert field.grid.spacing == pytest.approx((0.4e-6, 1e-6), rel=1e-14)
        np.testing.assert_allclose(field.heights, heights * 1e-6, rtol=1e-15)
    square = matrix.resampled((10, 10))
    assert square.grid.spacing == pytest.approx((0.4e-6, 0.4e-6), rel=1e-14)
    assert square.grid.lengths == matrix.grid.lengths


# -- reading: the audit's rows of issue 36 ------------------------------------------------------------------------
def test_narrow_integer_matrices_are_not_taken_for_exports(tmp_path):
    """A matrix 2 or 3 pixels wide of integer heights has columns that can lie on a lattice: out of raster order
    it was read as a profile from its second column, sorted by its first; with a size given it was refused
    without a word of layout='matrix'. Now both name layout='matrix', which reads it."""
    (tmp_path / "two.txt").write_text("5 2\n1 4\n3 6\n")
    for size in ({}, {"pixel_size": 1e-6}):
        with pytest.raises(ValueError, match=r"two.txt has 2 columns .* not in raster order.*layout='matrix'"):
            surfaces.HeightField.read(tmp_path / "two.txt", **size)
    matrix = surfaces.HeightField.read(tmp_path / "two.txt", pixel_size=1e-6, layout="matrix")
    assert matrix.heights.tolist() == [[5, 2], [1, 4], [3, 6]]
    (tmp_path / "sorted.txt").write_text("1 2\n3 4\n5 6\n")             # in raster order: an x-z export ...
    with pytest.raises(ValueError, match=r"sorted.txt reads as a column export.*layout='matrix'"):
        surfaces.HeightField.read(tmp_path / "sorted.txt", pixel_size=1e-6)  # ... unless a size says otherwise
    (tmp_path / "three.txt").write_text("1 2 7\n3 4 8\n5 6 9\n")
    with pytest.raises(ValueError, match=r"most of its lattice absent; a height matrix 3 pixels wide needs "
                                         r"layout='matrix'\) has 6 missing heights"):
        surfaces.HeightField.read(tmp_path / "three.txt")
    (tmp_path / "shuffled.xyz").write_text("".join(np.random.default_rng(0).permutation(
        xyz_lines(MAP_UM, 0.25, 0.4).splitlines(keepends=True))))
    shuffled = surfaces.HeightField.read(tmp_path / "shuffled.xyz", unit="um", layout="columns")   # any order
    np.testing.assert_allclose(shuffled.heights, MAP_UM * 1e-6, rtol=1e-15)


def test_non_numbers_channels_and_saved_fields(tmp_path):
    np.save(tmp_path / "words.npy", np.array([["a", "b"], ["c", "d"]]))
    with pytest.raises(ValueError, match=r"words.npy holds values of dtype <U1, not numbers"):
        surfaces.HeightField.read(tmp_path / "words.npy", pixel_size=1e-6)
    np.save(tmp_path / "map.npy", MAP_UM)
    assert surfaces.HeightField.read(tmp_path / "map.npy", pixel_size=1e-6, channel=0).shape == (7, 5)
    with pytest.raises(ValueError, match=r"channel = 1 is out of range; map.npy holds one height map, channel 0"):
        surfaces.HeightField.read(tmp_path / "map.npy", pixel_size=1e-6, channel=1)
    saved = surfaces.HeightField.from_array(MAP_UM * 1e-6, pixel_size=1e-6).save(tmp_path / "map.npz")
    assert surfaces.HeightField.read(saved, unit="m").shape == (7, 5)
    with pytest.raises(ValueError, match=r"map.npz is a saved HeightField.*unit = 'um'"):
        surfaces.HeightField.read(saved, unit="um")
