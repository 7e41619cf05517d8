"""Texture statistics against fields whose wavelength, orientation and pits are known by construction."""
import numpy as np
import pytest

import surfaces
from surfaces import HeightField

L = 5e-3            # 5 mm window
N = 256             # 19.5 µm pixels


def grid(periodic):
    return surfaces.Grid((N, N), (L, L), periodic)


def plane_wave(g, wavelength, angle):
    """cos of a plane wave whose crests run along ``angle`` (ridge direction from the x axis)."""
    x, y = g.meshgrid()
    return HeightField(g, 1e-5 * np.cos(2 * np.pi / wavelength * (-np.sin(angle) * x + np.cos(angle) * y)))


# -- dominant wavelength -----------------------------------------------------------------------------------
@pytest.mark.parametrize("wavelength", [0.41e-3, 0.45e-3, 0.47e-3, 0.5e-3])
@pytest.mark.parametrize("angle", [0.0, 0.3, 0.8])
def test_dominant_wavelength_interpolates_between_modes(wavelength, angle):
    # 5 mm / 0.45 mm = 11.1 periods: one mode spacing 2π/L is 9 % of q, and only 0.5 mm is a mode of the
    # window. The tapered centroid must land within 0.5 % (measured ≤ 0.25 %), i.e. < 1/18 bin.
    field = plane_wave(grid(False), wavelength, angle)
    assert surfaces.dominant_wavelength(field) == pytest.approx(wavelength, rel=5e-3)


def test_dominant_wavelength_of_a_grid_mode_is_exact():
    # a periodic field holding one mode (11 periods across Ly) has all its power at exactly q = 2π·11/L
    field = plane_wave(grid(True), L / 11, 0.0)
    assert surfaces.dominant_wavelength(field) == pytest.approx(L / 11, rel=1e-12)


def test_dominant_wavelength_of_concentric_rings():
    # cos(q0 r): isotropic ring spectrum, power density peaked at q0 (measured error 0.22 %)
    g = grid(False)
    x, y = g.meshgrid()
    field = HeightField(g, np.cos(2 * np.pi * np.hypot(x - L / 2, y - L / 2) / 0.45e-3))
    assert surfaces.dominant_wavelength(field) == pytest.approx(0.45e-3, rel=5e-3)


def test_dominant_wavelength_ignores_harmonics():
    # a flattened (non-sinusoidal) profile adds 2q, 3q harmonics; the peak band excludes them (measured 0.15 %)
    field = surfaces.parallel_ridges(grid(False), 0.45e-3, 50e-6, ridge_width_ratio=2.0, orientation=0.4)
    assert surfaces.dominant_wavelength(field) == pytest.approx(0.45e-3, rel=5e-3)


def test_dominant_wavelength_bad_input():
    with pytest.raises(ValueError, match="band"):
        surfaces.dominant_wavelength(plane_wave(grid(True), L / 11, 0.0), band=3.0)
    with pytest.raises(ValueError, match="flat"):
        surfaces.dominant_wavelength(HeightField(grid(True), np.zeros((N, N))))
    with pytest.raises(TypeError, match="HeightField"):
        surfaces.dominant_wavelength(np.zeros((N, N)))


# -- orientation -------------------------------------------------------------------------------------------
def check_straight_ridges(field, angle):
    estimate = surfaces.orientation_field(field)
    error = np.degrees(surfaces.angular_difference(estimate.angle, angle))
    # the structure tensor of a plane wave is rank one; central differences and (non-periodic) a window
    # reflected at the edge perturb it slightly: measured max 0.17°
    assert error.max() < 0.5
    assert np.median(estimate.coherence) > 0.99
    return estimate


@pytest.mark.parametrize("angle", [0.0, 0.25, np.pi / 2, 2.5])
def test_orientation_of_straight_ridges(angle):
    estimate = check_straight_ridges(plane_wave(grid(False), 0.45e-3, angle), angle)
    assert estimate.window == pytest.approx(0.45e-3, rel=1e-2)   # default window = dominant wavelength


@pytest.mark.parametrize("modes", [(0, 11), (3, 11), (11, 0), (-7, 8)])
def test_orientation_of_straight_ridges_periodic(modes):
    # a grid mode (mx, my) is periodic; its crests run perpendicular to q, at atan2(my, mx) + π/2
    g = grid(True)
    x, y = g.meshgrid()
    field = HeightField(g, np.cos(2 * np.pi / L * (modes[0] * x + modes[1] * y)))
    check_straight_ridges(field, np.arctan2(modes[1], modes[0]) + np.pi / 2)


def test_orientation_of_concentric_rings_is_tangential():
    g = grid(False)
    x, y = g.meshgrid()
    r = np.hypot(x - L / 2, y - L / 2)
    field = HeightField(g, np.cos(2 * np.pi * r / 0.45e-3))
    estimate = surfaces.orientation_field(field, window=0.3e-3)
    tangent = np.arctan2(y - L / 2, x - L / 2) + np.pi / 2
    far = (r > 2 * 0.45e-3) & (r < L / 2 - 0.45e-3)
    # ridges curve with radius ≥ 2 periods: the averaging window sees a slightly curved pattern (measured 0.13°)
    assert np.median(np.degrees(surfaces.angular_difference(estimate.angle, tangent))[far]) < 0.5


def test_angular_difference_is_modulo_pi():
    assert surfaces.angular_difference(0.1, np.pi - 0.1) == pytest.approx(0.2)
    assert surfaces.angular_difference(0.0, np.pi / 2) == pytest.approx(np.pi / 2)
    assert surfaces.angular_difference(3.0, 3.0 + 5 * np.pi) == pytest.approx(0.0, abs=1e-12)


def test_orientation_bad_input():
    with pytest.raises(ValueError, match="window"):
        surfaces.orientation_field(plane_wave(grid(True), L / 11, 0.0), window=-1e-4)
    profile = HeightField(surfaces.Grid((64, 1), (1e-3, 1e-3 / 64)), np.zeros((64, 1)))
    with pytest.raises(ValueError, match="2-D"):
        surfaces.orientation_field(profile)


# -- pores -------------------------------------------------------------------------------------------------
def ridges_with_pits(periodic, centres, depth=20e-6, diameter=120e-6):
    """Parallel ridges along x (period 0.5 mm, crests at y = 0.25 mm + k·0.5 mm) with quartic pits."""
    g = grid(periodic)
    field = surfaces.parallel_ridges(g, 0.5e-3, 50e-6, orientation=0.0, offset=0.25e-3)
    x, y = g.meshgrid()
    h = field.heights.copy()
    for cx, cy in centres:
        dx = np.mod(x - cx + L / 2, L) - L / 2 if periodic else x - cx
        rho2 = (dx ** 2 + (y - cy) ** 2) / (diameter / 2) ** 2
        h -= np.where(rho2 < 1, depth * (1 - rho2) ** 2, 0.0)
    return HeightField(g, h)


def test_detect_pores_finds_exactly_the_pits():
    centres = [(0.6e-3, 0.25e-3), (2.0e-3, 0.75e-3), (3.1e-3, 2.25e-3), (4.0e-3, 4.25e-3), (1.2e-3, 3.25e-3)]
    found = surfaces.detect_pores(ridges_with_pits(False, centres))
    assert found.count == len(centres)
    assert found.density == pytest.approx(len(centres) / L ** 2)
    for cx, cy in centres:   # each pit located at its lowest pixel: within one pixel of the true centre
        assert np.min(np.hypot(found.centres[:, 0] - cx, found.centres[:, 1] - cy)) <= np.sqrt(2) * L / N


def test_detect_pores_finds_nothing_on_plain_ridges_and_rings():
    assert surfaces.detect_pores(ridges_with_pits(True, [])).count == 0
    g = grid(False)
    x, y = g.meshgrid()
    rings = HeightField(g, 25e-6 * np.cos(2 * np.pi * np.hypot(x - L / 2, y - L / 2) / 0.45e-3))
    assert surfaces.detect_pores(rings).count == 0


def test_detect_pores_counts_a_pit_across_the_periodic_edge_once():
    found = surfaces.detect_pores(ridges_with_pits(True, [(0.0, 1.25e-3), (2.5e-3, 1.75e-3)]))
    assert found.count == 2


def test_detect_pores_ignores_shallow_pits():
    # a 3 µm dimple is below the default min_depth (5 µm) but above an explicit 1 µm
    field = ridges_with_pits(False, [(2.0e-3, 2.25e-3)], depth=3e-6)
    assert surfaces.detect_pores(field).count == 0
    assert surfaces.detect_pores(field, min_depth=1e-6).count == 1


def test_detect_pores_bad_input():
    field = ridges_with_pits(True, [])
    with pytest.raises(ValueError, match="pore_diameter"):
        surfaces.detect_pores(field, pore_diameter=0.0)
    with pytest.raises(ValueError, match="pore_diameter.*3 pixels"):
        surfaces.detect_pores(field, pore_diameter=50e-6)            # 2.6 pixels of 19.5 µm
    with pytest.raises(ValueError, match="min_depth"):
        surfaces.detect_pores(field, min_depth=float("nan"))
