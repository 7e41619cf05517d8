"""A_R on non-square pixels: the closing disc is a disc in metres, an ellipse in pixels, so the same surface sampled
on square and on 1 x 2.5 pixels (as real x3p files are) gives the same ridge area within the sampling error."""
from types import SimpleNamespace

import numpy as np
import pytest

import surfaces
from roughcontact.study.patch import ridge_area_fraction
from roughcontact.study.records import patch_record
from roughcontact.study.scene import load_scene

SIDE, PERIOD, BAND, SPOT, PITCH, CLOSING = 1.0e-3, 200e-6, 50e-6, 8e-6, 25e-6, 120e-6


def stripes(dx, dy):
    """Contact spots of radius 8 µm on a 25 µm lattice filling bands 50 µm wide (spot centres; 66 µm with the
    spots), one band every 200 µm along y: a 120 µm closing merges the spots of a band (9 µm apart) and never two
    bands (134 µm apart). Sampled at the points (i dx, j dy) of a 1 mm square."""
    x, y = np.arange(round(SIDE / dx)) * dx, np.arange(round(SIDE / dy)) * dy
    x, y = np.meshgrid(x, y, indexing="ij")
    across = np.mod(y - 25e-6, PERIOD)
    centre = np.clip(np.round(across / PITCH) * PITCH, 0.0, BAND)
    return (x - np.round(x / PITCH) * PITCH) ** 2 + (across - centre) ** 2 <= SPOT ** 2


def test_ridge_area_on_non_square_pixels_is_that_of_the_same_surface_on_square_ones():
    """The same surface on 2 x 2 µm, 2 x 5 µm and 5 x 2 µm pixels (dy/dx = 2.5, as real x3p files have) against
    1 x 1 µm. Sampling error: a closed band's edge moves by up to one pixel across the bands, two edges per
    200 µm period, so A_R may move by 2 d/200 µm (0.05 at 5 µm, 0.02 at 2 µm). The closing in pixels of dx, as
    before, bridged the bands on the 2 x 5 µm pixels (a 120 x 300 µm ellipse): A_R = 1 against 0.28."""
    reference = ridge_area_fraction(stripes(1e-6, 1e-6), (1e-6, 1e-6), CLOSING)
    assert 0.25 < reference < 66e-6 / PERIOD                  # the bands' share, less the spots' scallops
    for dx, dy in ((2e-6, 2e-6), (2e-6, 5e-6), (5e-6, 2e-6)):
        fraction = ridge_area_fraction(stripes(dx, dy), (dx, dy), CLOSING)
        assert fraction == pytest.approx(reference, abs=2 * dy / PERIOD), (dx, dy)
    assert ridge_area_fraction(stripes(2e-6, 5e-6), 2e-6, CLOSING) == 1.0     # the disc in pixels of dx
    # square pixels: the pair and the one number are the same disc, bit for bit
    assert ridge_area_fraction(stripes(2e-6, 2e-6), (2e-6, 2e-6), CLOSING) == ridge_area_fraction(
        stripes(2e-6, 2e-6), 2e-6, CLOSING)


def test_a_disc_holding_one_pixel_leaves_the_mask_as_it_is():
    mask = stripes(5e-6, 12.5e-6)
    assert ridge_area_fraction(mask, (5e-6, 12.5e-6), 9.9e-6) == mask.mean()          # radius under dx: one pixel
    assert ridge_area_fraction(mask, (12.5e-6, 5e-6), 9.9e-6) == mask.mean()          # under dy: one pixel
    assert ridge_area_fraction(mask, (5e-6, 12.5e-6), 10.1e-6) > mask.mean()           # two neighbours along x


def stand_in(contact, gap, spacing, force):
    """A solved patch as patch_record reads it."""
    grid = surfaces.Grid(contact.shape, (contact.shape[0] * spacing[0], contact.shape[1] * spacing[1]))
    return SimpleNamespace(gap=gap, contact=contact, grid=grid, contact_fraction=float(contact.mean()),
                           converged=True, iterations=1, unstable_steps=0, electrostatic_force=force)


def test_the_study_closes_with_both_pixel_sizes():
    stack = load_scene().screen.stack()
    contact = stripes(2e-6, 5e-6)
    result = stand_in(contact, np.where(contact, 0.0, 1e-6), (2e-6, 5e-6), 1e-3)
    record = patch_record(stack, "layered", 150.0, [result], (CLOSING,), (2e-6, 5e-6), 1, 0.0)
    assert record.ridge_area_fractions[0] == ridge_area_fraction(contact, (2e-6, 5e-6), CLOSING) < 0.35
