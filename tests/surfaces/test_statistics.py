"""Statistics (rms height/slope/curvature, radially averaged PSD) against analytic fields and Parseval."""
import numpy as np
import pytest

import surfaces

L = 1e-3


def cosine_field(grid, modes):
    """Σ A cos(qx x + qy y + φ) for ``modes = [(A, kx, ky, φ), ...]`` (integer wavenumbers)."""
    x, y = grid.meshgrid()
    heights = sum(a * np.cos(2 * np.pi * (kx * x / grid.lengths[0] + ky * y / grid.lengths[1]) + phase)
                  for a, kx, ky, phase in modes)
    return surfaces.HeightField(grid, heights)


MODES = [(1e-6, 3, 1, 0.3), (0.4e-6, -2, 7, 1.1), (0.1e-6, 11, 0, -0.5)]
GRID = surfaces.Grid((40, 36), (L, 0.9 * L))


def analytic_moments(grid, modes):
    """(h_rms², <|∇h|²>, <(∇²h)²>, FD slope², FD compact-Laplacian²) for distinct cosine modes."""
    (lx, ly), (dx, dy) = grid.lengths, grid.spacing
    out = np.zeros(5)
    for a, kx, ky, _ in modes:
        qx, qy = 2 * np.pi * kx / lx, 2 * np.pi * ky / ly
        fd_gradient2 = (np.sin(qx * dx) / dx) ** 2 + (np.sin(qy * dy) / dy) ** 2      # central differences
        fd_laplacian = (2 - 2 * np.cos(qx * dx)) / dx ** 2 + (2 - 2 * np.cos(qy * dy)) / dy ** 2
        out += a ** 2 / 2 * np.array([1, qx ** 2 + qy ** 2, (qx ** 2 + qy ** 2) ** 2, fd_gradient2,
                                      fd_laplacian ** 2])
    return np.sqrt(out)


@pytest.mark.parametrize("modes", [MODES[:1], MODES])
def test_rms_values_of_cosine_fields(modes):
    """Single- and multi-mode fields: every rms value equals its closed form to 1e-12 (spectral and FD)."""
    field = cosine_field(GRID, modes)
    height, slope, curvature, fd_slope, fd_curvature = analytic_moments(GRID, modes)
    assert surfaces.rms_height(field) == pytest.approx(height, rel=1e-12)
    assert surfaces.rms_slope(field) == pytest.approx(slope, rel=1e-12)
    assert surfaces.rms_curvature(field) == pytest.approx(curvature, rel=1e-12)
    assert surfaces.rms_slope(field, method="finite-difference") == pytest.approx(fd_slope, rel=1e-12)
    assert surfaces.rms_curvature(field, method="finite-difference") == pytest.approx(fd_curvature, rel=1e-12)


def test_profile_rms_values_and_psd():
    grid = surfaces.Grid((64, 1), (L, L / 64))
    a, k = 2e-6, 5
    field = surfaces.HeightField(grid, a * np.cos(2 * np.pi * k * grid.meshgrid()[0] / L))
    q0 = 2 * np.pi * k / L
    assert surfaces.rms_height(field) == pytest.approx(a / np.sqrt(2), rel=1e-12)
    assert surfaces.rms_slope(field) == pytest.approx(a * q0 / np.sqrt(2), rel=1e-12)
    assert surfaces.rms_curvature(field) == pytest.approx(a * q0 ** 2 / np.sqrt(2), rel=1e-12)
    q, c1 = surfaces.psd(field)
    assert np.allclose(q, 2 * np.pi * np.arange(1, 33) / L, rtol=1e-14)
    expected = np.zeros(32)
    expected[k - 1] = a ** 2 / 4 * L / (2 * np.pi)            # |ĥ_±q|² = A²/4, C₁ = |ĥ|² L/(2π)
    assert np.allclose(c1, expected, rtol=1e-12, atol=1e-12 * expected.max())


@pytest.mark.parametrize("n", [64, 63])
def test_profile_psd_parseval_including_nyquist(n):
    """2 Σ C₁ Δq = h_rms² exactly for white noise (which has Nyquist power when n is even)."""
    grid = surfaces.Grid((n, 1), (L, L / n))
    field = surfaces.HeightField(grid, np.random.default_rng(0).standard_normal((n, 1)) * 1e-6)
    q, c1 = surfaces.psd(field)
    assert 2 * c1.sum() * 2 * np.pi / L == pytest.approx(surfaces.rms_height(field) ** 2, rel=1e-12)


def test_psd_ring_average_of_a_single_mode():
    """Mode (3, 0) on 32²: its power 2·A²/4 is shared by the modes of the ring 2.5 <= |k| < 3.5 (1e-12)."""
    grid = surfaces.Grid((32, 32), (L, L))
    a = 1e-6
    q, c = surfaces.psd(cosine_field(grid, [(a, 3, 0, 0.0)]))
    i, j = np.meshgrid(np.arange(-16, 16), np.arange(-16, 16), indexing="ij")
    ring = (np.hypot(i, j) >= 2.5) & (np.hypot(i, j) < 3.5)
    expected = 2 * a ** 2 / 4 * L * L / (2 * np.pi) ** 2 / ring.sum()
    assert c[2] == pytest.approx(expected, rel=1e-12)
    assert q[2] == pytest.approx(2 * np.pi / L * np.hypot(i, j)[ring].mean(), rel=1e-12)
    assert np.all(np.delete(c, 2) < 1e-12 * expected)


def test_psd_parseval_over_rings():
    """Σ_rings C̄ · (modes in ring) · (2π)²/A = h_rms² for white noise on a square grid (1e-12)."""
    n = 24
    grid = surfaces.Grid((n, n), (L, L))
    field = surfaces.HeightField(grid, np.random.default_rng(1).standard_normal((n, n)) * 1e-6)
    q, c = surfaces.psd(field)
    i, j = np.meshgrid(np.arange(-n // 2, n // 2), np.arange(-n // 2, n // 2), indexing="ij")
    ring = np.floor(np.hypot(i, j) + 0.5).astype(int)       # ring b holds b - 1/2 <= |k| < b + 1/2
    counts = np.bincount(ring.ravel())[1:]
    assert len(counts) == len(c)
    total = np.sum(c * counts) * (2 * np.pi) ** 2 / grid.area
    assert total == pytest.approx(surfaces.rms_height(field) ** 2, rel=1e-12)


def test_psd_with_bins_keeps_parseval():
    """One bin holds every q > 0 mode: its mean C times their number times (2π)²/A is h_rms² (Parseval;
    measured 2e-16 relative, bound 1e-13), and its q the mean |q| over those modes."""
    n = 24
    grid = surfaces.Grid((n, n), (L, L))
    field = surfaces.HeightField(grid, np.random.default_rng(3).standard_normal((n, n)) * 1e-6)
    q, c = surfaces.psd(field, bins=1)
    modes = grid.wavevector_magnitude()[grid.wavevector_magnitude() > 0]
    assert c.shape == (1,) and q[0] == pytest.approx(modes.mean(), rel=1e-13)
    assert c[0] * modes.size * (2 * np.pi) ** 2 / grid.area == pytest.approx(surfaces.rms_height(field) ** 2,
                                                                             rel=1e-13)
    q5, c5 = surfaces.psd(field, bins=5)
    assert len(q5) == 5 and np.all(np.diff(q5) > 0) and q5[0] >= 2 * np.pi / L and q5[-1] <= modes.max()


def test_hann_window_leaves_a_periodic_grid_alone():
    """The window tapers only non-periodic axes: on a periodic grid 'hann' is 'none', bit for bit."""
    field = cosine_field(GRID, MODES)
    for hann, plain in zip(surfaces.psd(field, window="hann"), surfaces.psd(field, window="none")):
        assert np.array_equal(hann, plain)


@pytest.mark.parametrize("scale", [1e300, 1e200, 1e-200, 1e-300])
def test_statistics_are_scale_safe(scale):
    """Heights of 1e±300 m: rms height and slope scale exactly (no overflow to inf, no underflow to 0);
    measured 2e-16 relative, bound 1e-14."""
    field = cosine_field(GRID, MODES)
    big = field * (scale / 1e-6)
    assert surfaces.rms_height(big) == pytest.approx(surfaces.rms_height(field) * scale / 1e-6, rel=1e-14)
    for method in ("spectral", "finite-difference"):
        assert surfaces.rms_slope(big, method=method) == pytest.approx(
            surfaces.rms_slope(field, method=method) * scale / 1e-6, rel=1e-14)


def test_moments_of_a_generated_field_are_sums_over_its_modes():
    """h_rms² = Σ|ĥ|², h'_rms² = Σ q²|ĥ|², h''_rms² = Σ q⁴|ĥ|² with q from numpy.fft.fftfreq (1e-12)."""
    grid = surfaces.Grid((64, 48), (L, 0.75 * L))
    field = surfaces.self_affine(grid, hurst=0.7, rms_slope=0.1, short_cutoff=8 * L / 64, rng=9)
    power = np.abs(np.fft.fft2(field.heights) / grid.size) ** 2
    q2 = ((2 * np.pi * np.fft.fftfreq(64, L / 64))[:, None] ** 2
          + (2 * np.pi * np.fft.fftfreq(48, 0.75 * L / 48))[None, :] ** 2)
    assert surfaces.rms_height(field) ** 2 == pytest.approx(power.sum(), rel=1e-12)
    assert surfaces.rms_slope(field) ** 2 == pytest.approx(np.sum(q2 * power), rel=1e-12)
    assert surfaces.rms_curvature(field) ** 2 == pytest.approx(np.sum(q2 ** 2 * power), rel=1e-12)
    # finite differences underestimate by sin(q dx)/(q dx) >= sin(π/8)/(π/8) = 0.974 at the 8-pixel cutoff
    fd = surfaces.rms_slope(field, method="finite-difference")
    assert 0.974 * surfaces.rms_slope(field) < fd < surfaces.rms_slope(field)


def test_non_periodic_finite_differences_are_exact_for_polynomials():
    """Second-order one-sided edges: a plane has exact rms slope, a quadratic exact rms curvature."""
    grid = surfaces.Grid((30, 20), (L, 0.5 * L), periodic=False)
    x, y = grid.meshgrid()
    plane = surfaces.HeightField(grid, 0.03 * x - 0.04 * y)
    assert surfaces.rms_slope(plane) == pytest.approx(0.05, rel=1e-12)
    bowl = surfaces.HeightField(grid, x ** 2 / (2 * 5e-3) + y ** 2 / (2 * 2e-3))
    assert surfaces.rms_curvature(bowl) == pytest.approx(1 / 5e-3 + 1 / 2e-3, rel=1e-9)
    with pytest.raises(ValueError, match="periodic"):
        surfaces.rms_slope(plane, method="spectral")


def test_windowed_psd_keeps_the_power_of_white_noise():
    """Non-periodic: the power-normalised Hann window keeps <C> = σ² A/((2π)² N) (16 samples: ±3 %)."""
    grid = surfaces.Grid((64, 64), (L, L), periodic=False)
    sigma = 1e-6
    rng = np.random.default_rng(2)
    mean_c = np.mean([surfaces.psd(surfaces.HeightField(grid, sigma * rng.standard_normal((64, 64))))[1].mean()
                      for _ in range(16)])
    assert mean_c == pytest.approx(sigma ** 2 * grid.area / (2 * np.pi) ** 2 / grid.size, rel=0.03)


def test_bad_input():
    field = cosine_field(GRID, MODES)
    with pytest.raises(ValueError, match="window"):
        surfaces.psd(field, window="hamming")
    with pytest.raises(ValueError, match="bins"):
        surfaces.psd(field, bins=0)
    with pytest.raises(ValueError, match="bins"):
        surfaces.psd(field, bins=2.5)
    with pytest.raises(ValueError, match="method"):
        surfaces.rms_slope(field, method="exact")
    with pytest.raises(TypeError, match="HeightField"):
        surfaces.rms_height(field.heights)
