"""roughcontact.study.patch.profile_surface: one ridge period of the study's patch as a 1-D profile across the
ridges. Checked against the 2-D patch it stands for: its ridges are the patch's cross-section, its roughness has
the rms height, cut-offs and line spectrum of the patch's rows, and every pixel size samples the same profile."""
import numpy as np
import pytest

from roughcontact.study.patch import (patch_grid, profile_grid, profile_roughness_spectrum, profile_surface,
                                      ridge_heights)
from roughcontact.study.scene import load_scene
from surfaces import Grid, self_affine

SCENE = load_scene()
PERIOD = SCENE.ridges.period


def roughness_of(heights, n):
    """The profile minus the ridge cross-section on ``n`` pixels."""
    return heights[:, 0] - profile_surface(load_scene(text="[roughness]\nenabled = false\n"), PERIOD / n)[0][:, 0]


def test_ridges_are_the_patch_cross_section_and_the_body_is_the_skin_in_plane_strain():
    heights, grid, body = profile_surface(SCENE, PERIOD / 256)
    assert grid.shape == (256, 1) and grid.lengths[0] == PERIOD and grid.periodic == (True, True)
    assert body.grid == grid
    ridges = ridge_heights(SCENE)                                   # the standard patch: 256² over one period
    assert patch_grid(SCENE).shape == (256, 256)
    flat = load_scene(text="[roughness]\nenabled = false\n")
    np.testing.assert_array_equal(profile_surface(flat, PERIOD / 256)[0][:, 0], ridges[0, :])
    assert np.ptp(heights) > SCENE.ridges.height                    # ridges plus roughness


def test_every_pixel_samples_the_same_band_limited_profile():
    fine, coarse = (profile_surface(SCENE, PERIOD / n, realisation=2)[0][:, 0] for n in (4096, 128))
    # the same Fourier modes, drawn per wavenumber: equal to rounding (heights ~ 1e-5 m)
    np.testing.assert_allclose(fine[::32], coarse, rtol=0, atol=1e-18)
    other = profile_surface(SCENE, PERIOD / 128, realisation=3)[0][:, 0]
    assert np.max(np.abs(other - coarse)) > 1e-6                    # another realisation is another profile


def test_roughness_keeps_the_rms_height_and_the_short_cutoff():
    n = 1024
    roughness = roughness_of(profile_surface(SCENE, PERIOD / n)[0], n)
    assert np.std(roughness) == pytest.approx(SCENE.roughness.rms_height, rel=1e-12)
    power = np.abs(np.fft.rfft(roughness)) ** 2
    shortest = round(PERIOD / SCENE.roughness.short_cutoff)         # 45 periods: λ = 10 µm
    assert power[shortest:].max() < 1e-20 * power.max()
    assert power[shortest - 1] > 0


def test_line_spectrum_is_that_of_the_rows_of_the_2d_patch():
    """The rows of independent 2-D patches of the scene's spectrum (surfaces.self_affine) against C₁ (both as
    fractions of their total power, C₁ being unnormalised): averaged over the rows, the power at k_x sums
    |ĥ(k_x, k_y)|² over ~2·45 modes k_y per realisation, so 12 realisations leave ~4 % scatter per k_x and
    ~1.5-3 % per band; 8 % tolerates that. The plateau below the long cut-off (k_x < 7.5) holds the oblique
    modes: a 1-D power law between the cut-offs (surfaces.self_affine on the profile grid) has none there, and
    C₁ ∝ q^-(1+2H) within them would put 2.6 times the power of the rows into the 20-44 band relative to 8-19."""
    roughness, n = SCENE.roughness, 128
    grid = Grid((n, n), (PERIOD, PERIOD), periodic=True)
    rows = np.mean([np.mean(np.abs(np.fft.rfft(self_affine(
        grid, roughness.hurst, rms_height=roughness.rms_height, long_cutoff=roughness.long_cutoff,
        short_cutoff=roughness.short_cutoff, normalise=False, rng=seed).heights, axis=0)) ** 2, axis=1)
        for seed in range(12)], axis=0)
    expected = profile_roughness_spectrum(SCENE, PERIOD)(2 * np.pi * np.arange(rows.size) / PERIOD)
    assert np.all(expected[45:] == 0)
    # k_x = 0 (modes along the ridges only) is each row's mean height, which a profile does not hold
    rows, expected = rows[1:] / rows[1:].sum(), expected[1:] / expected[1:].sum()
    for band in (slice(0, 7), slice(7, 19), slice(19, 44)):         # k_x = 1-7, 8-19, 20-44
        assert np.sum(rows[band]) == pytest.approx(np.sum(expected[band]), rel=0.08)
    assert np.sum(expected[:7]) > 0.4                              # the plateau carries 45 % of the power


@pytest.mark.parametrize("pixel, message", [(PERIOD / 4, "leaves 4 pixels"), (-1.0, "pixel"),
                                            (6e-6, "does not resolve roughness.short_cutoff")])
def test_profile_refuses_a_pixel_out_of_range(pixel, message):
    with pytest.raises(ValueError, match=message):
        profile_surface(SCENE, pixel)


def test_profile_grid_rounds_to_whole_pixels():
    assert profile_grid(SCENE, 3.5e-6).shape == (129, 1)
