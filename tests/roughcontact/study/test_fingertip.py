"""The fingertip cap on the layered skin (roughcontact.study.fingertip): Hertz in the half-space limit, the wiring of
the layer and the tissue, the window's growth, the default skin's effect and bad input."""
import dataclasses

import numpy as np
import pytest

from roughcontact.study.apparent import apparent_contact
from roughcontact.study.fingertip import FingertipContact, fingertip_contact
from roughcontact.study.scene import load_scene

SCENE = load_scene()
FINGERPAD = dataclasses.replace(SCENE.fingerpad, model="fingertip")     # R = 1 cm, E* = 47.4 kPa
SKIN = SCENE.skin                                                       # 30 µm of 10 MPa
HALF_SPACE = dataclasses.replace(SKIN, layer_thickness=0.0)


@pytest.mark.parametrize("grid_points, area_error, ring_errors", [
    (64, 0.013, (0.0016, 0.0068, 0.050)),
    (128, 0.0051, (0.0005, 0.0022, 0.023)),
])
def test_half_space_limit_is_hertz(grid_points, area_error, ring_errors):
    """Without the layer: Hertz (study.apparent_contact) to the grid's resolution. The pixelated rim makes the
    errors first order in the pixel (measured, at 64² / 128² / 256²: area +1.27 / +0.50 / +0.23 %, outer ring
    mean −4.9 / −2.2 / −0.90 %, inner rings −0.16 / −0.04 / −0.03 % and −0.67 / −0.21 / −0.12 %), the same at
    every force (the window scales with the Hertz radius); bounds: the measured values, rounded up by 1-3 %."""
    for force in (0.5, 2.0):
        result = fingertip_contact(FINGERPAD, HALF_SPACE, force, 3, grid_points=grid_points)
        area, pressures = apparent_contact(FINGERPAD, force, 3)
        assert isinstance(result, FingertipContact) and result.converged
        assert 0 < result.area / area - 1 < area_error
        for mean, hertz, bound in zip(result.pressures, pressures, ring_errors):
            assert abs(mean / hertz - 1) < bound
        unpacked_area, unpacked_pressures = result
        assert unpacked_area == result.area and unpacked_pressures == result.pressures
        assert result.radius == pytest.approx(np.sqrt(result.area / np.pi), rel=1e-15)


def test_layer_of_the_tissue_itself_is_the_half_space():
    """A layer of the tissue's own modulus is the half-space to round-off (the correction vanishes): the layer's
    and the tissue's moduli go where they belong (measured: identical area, ring means to 4e-16)."""
    same = dataclasses.replace(SKIN, layer_E_star=FINGERPAD.E_star)
    layered = fingertip_contact(FINGERPAD, same, 1.0, 3, grid_points=64)
    half = fingertip_contact(FINGERPAD, HALF_SPACE, 1.0, 3, grid_points=64)
    assert layered.area == half.area
    np.testing.assert_allclose(layered.pressures, half.pressures, rtol=1e-12)


def test_default_skin_shrinks_the_footprint():
    """The scene's 30 µm, 10 MPa layer on 47.4 kPa tissue at 1 N: A0 −2.88 % and the outer ring's mean pressure
    +12.0 % against the half-space (measured at 64²; at 128² −2.90 / +12.3 %, at 256² −3.31 / +13.9 %,
    docs/findings/equivalent_gap.md); bounds ±0.5 % and ±1.5 %. The layer's half-space alone (the correction dropped) would
    shrink A0 35-fold."""
    layered = fingertip_contact(FINGERPAD, SKIN, 1.0, 3, grid_points=64)
    half = fingertip_contact(FINGERPAD, HALF_SPACE, 1.0, 3, grid_points=64)
    assert layered.converged
    assert layered.area / half.area - 1 == pytest.approx(-0.0288, abs=0.005)
    assert layered.pressures[2] / half.pressures[2] - 1 == pytest.approx(0.120, abs=0.015)
    assert layered.peak_pressure == pytest.approx(half.peak_pressure, rel=1e-3)


def test_contact_wider_than_the_estimate_grows_the_window():
    """A 10 cm layer 10× softer than the tissue spreads the contact beyond the window sized for the tissue's Hertz
    radius: the window doubles, and the answer is Hertz with the layer's modulus (t = 11 a; measured area +0.83 %,
    outer ring −3.5 %, the 64² pixel errors)."""
    soft = dataclasses.replace(SKIN, layer_E_star=FINGERPAD.E_star / 10, layer_thickness=0.1)
    result = fingertip_contact(FINGERPAD, soft, 1.0, 3, grid_points=64)
    area, pressures = apparent_contact(dataclasses.replace(FINGERPAD, E_star=FINGERPAD.E_star / 10), 1.0, 3)
    assert result.pixel == pytest.approx(4 * 1.25 * (3 * 1.0 * 0.01 / (4 * FINGERPAD.E_star)) ** (1 / 3) / 64)
    assert result.area / area - 1 == pytest.approx(0.0083, abs=0.005)
    np.testing.assert_allclose(result.pressures, pressures, rtol=0.05)


@pytest.mark.parametrize("kwargs, match", [
    (dict(normal_force=0.0), "normal_force"),
    (dict(rings=0), "rings"),
    (dict(grid_points=4), "grid_points"),
    (dict(rings=400, grid_points=16), "rings"),
    (dict(tissue_E_star=-1.0), "tissue_E_star"),
])
def test_bad_input(kwargs, match):
    arguments = dict(normal_force=1.0, rings=3) | kwargs
    with pytest.raises(ValueError, match=match):
        fingertip_contact(FINGERPAD, HALF_SPACE, **arguments)
