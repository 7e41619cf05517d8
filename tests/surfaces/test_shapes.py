"""Fingertip cap: apex position and sign, curvature radii, ellipsoid geometry, composition, bad input."""
import numpy as np
import pytest

import surfaces

L = 4e-3
GRID = surfaces.Grid((64, 48), (L, 0.75 * L), periodic=False)


@pytest.mark.parametrize("shape", ["paraboloid", "ellipsoid"])
def test_apex_is_the_maximum_at_the_grid_centre(shape):
    cap = surfaces.fingertip(GRID, radii=(8e-3, 6e-3), shape=shape)
    assert np.unravel_index(np.argmax(cap.heights), GRID.shape) == (32, 24)
    assert cap.heights[32, 24] == 0 and np.all(cap.heights <= 0)            # positive towards the screen
    assert cap.metadata["radii"] == [8e-3, 6e-3]


def test_paraboloid_heights_and_curvature():
    """h = -(x-x0)²/(2Rx) - (y-y0)²/(2Ry) at any pixel (1e-14); rms Laplacian 1/Rx + 1/Ry (1e-9)."""
    rx, ry, centre = 8e-3, 5e-3, (1.1e-3, 2.0e-3)
    cap = surfaces.fingertip(GRID, radii=(rx, ry), centre=centre)
    x, y = GRID.meshgrid()
    assert np.allclose(cap.heights, -(x - centre[0]) ** 2 / (2 * rx) - (y - centre[1]) ** 2 / (2 * ry),
                       rtol=1e-14, atol=0)
    assert surfaces.rms_curvature(cap) == pytest.approx(1 / rx + 1 / ry, rel=1e-9)


def test_ellipsoid_geometry():
    """Rx = Ry = R gives the sphere sqrt(R² - r²) - R; unequal radii keep the apex curvature radii (quadratic
    fit over ±3 pixels, where the quartic term is < 1e-4 relative); outside the footprint h = -depth."""
    r = 3e-3
    sphere = surfaces.fingertip(GRID, radii=(r, r), shape="ellipsoid")
    x, y = GRID.meshgrid()
    rho2 = (x - 32 * GRID.spacing[0]) ** 2 + (y - 24 * GRID.spacing[1]) ** 2
    expected = np.where(rho2 < r ** 2, np.sqrt(np.maximum(r ** 2 - rho2, 0)) - r, -r)
    assert np.allclose(sphere.heights, expected, rtol=0, atol=1e-15)
    cap = surfaces.fingertip(GRID, radii=(20e-3, 10e-3), shape="ellipsoid")
    for axis, radius in enumerate((20e-3, 10e-3)):
        offsets = np.arange(-3, 4)
        section = cap.heights[32 + offsets, 24] if axis == 0 else cap.heights[32, 24 + offsets]
        curvature = -2 * np.polyfit(offsets * GRID.spacing[axis], section, 2)[0]
        assert 1 / curvature == pytest.approx(radius, rel=1e-4)
    shallow = surfaces.fingertip(GRID, radii=(2e-3, 2e-3), shape="ellipsoid", depth=0.1e-3)
    assert shallow.heights.min() == pytest.approx(-0.1e-3, rel=1e-14) and shallow.metadata["depth"] == 0.1e-3


def test_profile_section_and_composition():
    profile_grid = surfaces.Grid((101, 1), (L, L / 101), periodic=False)
    section = surfaces.fingertip(profile_grid, radii=(8e-3, 8e-3))
    x = profile_grid.coordinates()[0]
    assert np.allclose(section.heights[:, 0], -(x - 50 * L / 101) ** 2 / 16e-3, rtol=1e-14, atol=0)
    cap = surfaces.fingertip(GRID, radii=(8e-3, 8e-3))
    rough = surfaces.self_affine(GRID, hurst=0.8, rms_height=0.5e-6, rng=0)
    pad = cap + rough
    assert pad.grid == GRID and np.array_equal(pad.heights, cap.heights + rough.heights)
    assert [part["generator"] for part in pad.metadata["parts"]] == ["fingertip", "self_affine"]


@pytest.mark.parametrize("kwargs, name", [
    (dict(radii=(8e-3, -1e-3)), "radii"),
    (dict(radii=(8e-3,)), "radii"),
    (dict(radii=(8e-3, float("nan"))), "radii"),
    (dict(radii=(8e-3, 8e-3), shape="sphere"), "shape"),
    (dict(radii=(8e-3, 8e-3), depth=1e-3), "depth"),
    (dict(radii=(8e-3, 8e-3), shape="ellipsoid", depth=0.0), "depth"),
    (dict(radii=(8e-3, 8e-3), centre=(0.0,)), "centre"),
])
def test_bad_input(kwargs, name):
    with pytest.raises(ValueError, match=name):
        surfaces.fingertip(GRID, **kwargs)
