"""Self-affine roughness: spectrum moments, synthesis convention, refinement consistency, statistics, errors."""
import numpy as np
import pytest
from scipy import integrate

import surfaces
from surfaces.selfaffine import SelfAffinePSD

L = 1e-3


def fourier_modes(field):
    """``ĥ_q = fft2(h)/N`` (conventions.md)."""
    return np.fft.fft2(field.heights) / field.grid.size


# -- the spectrum object ------------------------------------------------------------------------------------
@pytest.mark.parametrize("profile", [False, True])
@pytest.mark.parametrize("hurst", [0.3, 0.5, 1.0])
def test_analytic_moments_match_quadrature(hurst, profile):
    """2π∫q^(2k+1)C dq (surface) / 2∫q^(2k)C₁ dq (profile), checked by adaptive quadrature (rtol 1e-8)."""
    spectrum = SelfAffinePSD(hurst, 2.5e-20, long_cutoff=1e-3, rolloff=2e-4, short_cutoff=3e-6, profile=profile)
    q_long, q_rolloff, q_short = spectrum.cutoff_wavevectors
    for order in range(3):
        power = 2 * order if profile else 2 * order + 1
        integrand = lambda q: q ** power * spectrum(q)           # noqa: E731
        pieces = [integrate.quad(integrand, a, b, epsrel=1e-11, limit=200)[0]
                  for a, b in ((q_long, q_rolloff), (q_rolloff, q_short))]
        expected = (2.0 if profile else 2 * np.pi) * sum(pieces)
        assert spectrum.moment(order) == pytest.approx(expected, rel=1e-8)
    assert spectrum.rms_height ** 2 == pytest.approx(spectrum.moment(0), rel=1e-14)
    assert spectrum.rms_curvature ** 2 == pytest.approx(spectrum.moment(2), rel=1e-14)


def test_spectrum_shape_and_scaling():
    spectrum = SelfAffinePSD(0.7, 1e-20, long_cutoff=1e-3, rolloff=1e-4, short_cutoff=1e-6)
    q_long, q_rolloff, q_short = spectrum.cutoff_wavevectors
    assert spectrum(0.5 * q_long) == 0 and spectrum(2 * q_short) == 0
    assert spectrum(q_long) == spectrum(0.9 * q_rolloff) == 1e-20             # plateau, lower edge included
    assert spectrum(10 * q_rolloff) == pytest.approx(1e-20 * 10 ** (-2 * 1.7), rel=1e-14)
    assert SelfAffinePSD(0.7, 1e-20, 1e-3, 1e-4, 1e-6, profile=True)(10 * q_rolloff) == \
        pytest.approx(1e-20 * 10 ** (-2.4), rel=1e-14)
    assert spectrum.scaled(rms_slope=0.3).rms_slope == pytest.approx(0.3, rel=1e-14)
    unbounded = SelfAffinePSD(0.7, 1e-20, long_cutoff=1e-3, rolloff=1e-4, short_cutoff=None)
    assert unbounded(1e12) > 0
    log_q = np.log(q_rolloff)             # ∫ q C dq = ∫ q² C d(ln q); 40 e-folds leave < e^-50 of the tail
    tail = integrate.quad(lambda t: np.exp(2 * t) * unbounded(np.exp(t)), log_q, log_q + 40, epsrel=1e-12)[0]
    plateau = 1e-20 * (q_rolloff ** 2 - q_long ** 2) / 2
    assert unbounded.moment(0) == pytest.approx(2 * np.pi * (plateau + tail), rel=1e-8)
    with pytest.raises(ValueError, match="short_cutoff"):
        unbounded.moment(1)                                         # the rms slope diverges for H <= 1
    assert spectrum.scaled(rms_height=2e-6).rms_height == pytest.approx(2e-6, rel=1e-14)


# -- the synthesis convention -------------------------------------------------------------------------------
def shell_stream(shells):
    """Canonical modes in the documented stream order, enumerated independently of the implementation."""
    modes = []
    for s in range(1, shells + 1):
        modes += [(s, 0)] + [(s, j) for j in range(1, s)] + [(i, s) for i in range(s, -s - 1, -1)] + \
                 [(-s, j) for j in range(s - 1, 0, -1)]
    return modes


@pytest.mark.parametrize("shape", [(16, 16), (15, 20)])
def test_modes_are_amplitude_times_shell_ordered_stream(shape):
    """ĥ_q = sqrt(C(q)(2π)²/A) ξ_q, ξ from one Generator in shell order, Hermitian, Nyquist empty (1e-12)."""
    grid = surfaces.Grid(shape, (L, 1.3 * L))
    spectrum = SelfAffinePSD(0.6, 1e-20, long_cutoff=1.3 * L, rolloff=1.3 * L, short_cutoff=2 * L / 15)
    field = surfaces.fourier_synthesis(grid, spectrum, rng=11)
    modes = fourier_modes(field)
    qx, qy = grid.wavevectors()
    amplitude = np.sqrt(spectrum(np.hypot(qx, qy)) * (2 * np.pi) ** 2 / grid.area)
    shells = max(shape) // 2
    xi = np.random.default_rng(11).standard_normal((2 * shells * (shells + 1), 2))
    xi = (xi[:, 0] + 1j * xi[:, 1]) / np.sqrt(2)
    expected = np.zeros(shape, dtype=complex)
    for (i, j), value in zip(shell_stream(shells), xi):
        if abs(i) < shape[0] / 2 and abs(j) < shape[1] / 2:                       # Nyquist rows stay empty
            expected[i, j] = amplitude[i, j] * value
            expected[-i, -j] = np.conj(expected[i, j])
    assert np.abs(modes - expected).max() <= 1e-12 * np.abs(expected).max()


def test_profile_modes_follow_the_one_dimensional_convention():
    """Profile: ĥ_k = sqrt(C₁(q) 2π/L) ξ_k with ξ_k the (k-1)-th stream value (1e-12)."""
    grid = surfaces.Grid((64, 1), (L, L / 64))
    field = surfaces.self_affine(grid, hurst=0.5, prefactor=1e-18, rng=4)
    spectrum = SelfAffinePSD(0.5, 1e-18, L, L, 2 * L / 64, profile=True)
    xi = np.random.default_rng(4).standard_normal((31, 2))
    k = np.arange(1, 32)
    expected = np.sqrt(spectrum(2 * np.pi * k / L) * 2 * np.pi / L) * (xi[:, 0] + 1j * xi[:, 1]) / np.sqrt(2)
    modes = fourier_modes(field)[:, 0]
    assert np.abs(modes[1:32] - expected).max() <= 1e-12 * np.abs(expected).max()
    tolerance = 1e-12 * np.abs(expected).max()
    assert abs(modes[32]) <= tolerance                                          # Nyquist: round-off only
    assert np.abs(modes[33:] - np.conj(expected[::-1])).max() <= tolerance     # Hermitian partner


# -- refinement consistency ---------------------------------------------------------------------------------
@pytest.mark.parametrize("shape", [(32, 32), (33, 33), (24, 17), (64, 1), (63, 1)])
@pytest.mark.parametrize("factor", [2, 3])
def test_refinement_reproduces_coarse_fourier_modes(shape, factor):
    """Coarse field = Fourier truncation of the fine one, to 1e-12 of the largest mode. The default short
    cutoff (two pixels) lets the fine grid add modes beyond the coarse Nyquist wavevector."""
    coarse_grid = surfaces.Grid(shape, (L, 0.8 * L) if shape[1] > 1 else (L, L / shape[0]))
    fine_grid = coarse_grid.refined(factor)
    kwargs = dict(hurst=0.7, prefactor=3e-20, rng=123)
    coarse = fourier_modes(surfaces.self_affine(coarse_grid, **kwargs))
    fine = fourier_modes(surfaces.self_affine(fine_grid, **kwargs))
    kx, ky = coarse_grid.mode_indices()
    truncated = fine[kx[:, 0]][:, ky[0]]
    for axis, n in enumerate(shape):                    # the coarse grid's Nyquist row/column carries no power
        if n % 2 == 0:
            np.moveaxis(truncated, axis, 0)[n // 2] = 0
    assert np.abs(truncated - coarse).max() <= 1e-12 * np.abs(coarse).max()
    assert np.sum(np.abs(fine) ** 2) > 1.001 * np.sum(np.abs(truncated) ** 2)     # the fine grid adds modes


@pytest.mark.parametrize("periodic", [True, False])
def test_refinement_with_rms_normalisation_samples_the_same_surface(periodic):
    """Short cutoff resolved on the coarse grid: the fine field sampled on coarse pixels equals it (1e-12)."""
    coarse_grid = surfaces.Grid((33, 32), (L, L), periodic)
    kwargs = dict(hurst=0.8, rms_height=1e-6, rolloff=L / 4, short_cutoff=4 * L / 32, rng=7)
    coarse = surfaces.self_affine(coarse_grid, **kwargs).heights
    fine = surfaces.self_affine(coarse_grid.refined(2), **kwargs).heights
    assert np.abs(fine[::2, ::2] - coarse).max() <= 1e-12 * np.abs(coarse).max()


# -- determinism, RNG, amplitude --------------------------------------------------------------------------
def test_deterministic_and_global_rng_untouched():
    grid = surfaces.Grid((32, 32), (L, L))
    state = np.random.get_state()
    a = surfaces.self_affine(grid, hurst=0.8, rms_height=1e-6, rng=3)
    b = surfaces.self_affine(grid, hurst=0.8, rms_height=1e-6, rng=np.random.default_rng(3))
    c = surfaces.self_affine(grid, hurst=0.8, rms_height=1e-6, rng=4)
    d = surfaces.self_affine(grid, hurst=0.8, rms_height=1e-6)
    after = np.random.get_state()
    assert state[0] == after[0] and np.array_equal(state[1], after[1]) and state[2:] == after[2:]
    assert a == b and a != c
    assert a.metadata["seed"] == 3 and b.metadata["seed"] is None
    assert surfaces.self_affine(grid, hurst=0.8, rms_height=1e-6, rng=d.metadata["seed"]) == d
    sequence = surfaces.self_affine(grid, hurst=0.8, rms_height=1e-6, rng=np.random.SeedSequence(3))
    assert sequence == a and sequence.metadata["seed"] == 3          # normalised as numpy.random.default_rng
    spawned = np.random.SeedSequence(3).spawn(1)[0]
    assert surfaces.self_affine(grid, hurst=0.8, rms_height=1e-6, rng=spawned).metadata["seed"] is None
    assert surfaces.self_affine(grid, hurst=0.8, rms_height=1e-6, rng=np.random.PCG64(3)) == a


@pytest.mark.parametrize("shape, periodic", [((128, 128), True), ((96, 80), False), ((256, 1), True)])
def test_normalised_amplitude_is_exact(shape, periodic):
    grid = surfaces.Grid(shape, (L, L if shape[1] > 1 else L / shape[0]), periodic)
    field = surfaces.self_affine(grid, hurst=0.6, rms_height=2e-6, rng=1)
    if periodic:       # discrete spectral moment of the realisation = target (rounding only)
        assert surfaces.rms_height(field) == pytest.approx(2e-6, rel=1e-12)
        sloped = surfaces.self_affine(grid, hurst=0.6, rms_slope=0.2, rng=1)
        assert surfaces.rms_slope(sloped) == pytest.approx(0.2, rel=1e-12)
    else:              # normalised on the periodic parent (documented); the parent is reproduced by hand
        parent_grid = surfaces.Grid((2 * shape[0], 2 * shape[1]), (2 * L, 2 * L), True)
        parent = surfaces.self_affine(parent_grid, hurst=0.6, rms_height=2e-6, long_cutoff=L, rng=1)
        assert surfaces.rms_height(parent) == pytest.approx(2e-6, rel=1e-12)
        assert np.array_equal(field.heights, parent.heights[:shape[0], :shape[1]])
        assert field.metadata["padding"] == [2, 2]


def test_unnormalised_amplitude_matches_target_on_average():
    """normalise=False: prefactor from the analytic moment. The expected discrete moment Σ C (2π)²/A equals
    the target to 1 % (lattice-sum error, 0.3 % here), and an ensemble of 16 realisations agrees with that
    expectation within 4 standard errors."""
    grid = surfaces.Grid((128, 128), (L, L))
    kwargs = dict(hurst=0.8, rms_height=1e-6, rolloff=L / 8, short_cutoff=2 * L / 128, normalise=False)
    spectrum = SelfAffinePSD(0.8, 1, L, L / 8, 2 * L / 128).scaled(rms_height=1e-6)
    expected = np.sum(spectrum(grid.wavevector_magnitude())) * (2 * np.pi) ** 2 / grid.area
    assert np.sqrt(expected) == pytest.approx(1e-6, rel=1e-2)
    samples = np.array([surfaces.rms_height(surfaces.self_affine(grid, rng=seed, **kwargs)) ** 2
                        for seed in range(16)])
    assert abs(samples.mean() - expected) < 4 * samples.std(ddof=1) / 4


@pytest.mark.parametrize("hurst", [0.3, 0.5, 0.8])
def test_hurst_exponent_recovered_from_psd_fit(hurst):
    """Ensemble of 4 realisations on 256²: fit log C = a - 2(1+H) log q for 8 q_L <= q <= q_s/2 (±0.05)."""
    grid = surfaces.Grid((256, 256), (L, L))
    spectra = [surfaces.psd(surfaces.self_affine(grid, hurst=hurst, prefactor=1e-20, normalise=False, rng=seed))
               for seed in range(4)]
    q, c = spectra[0][0], np.mean([s[1] for s in spectra], axis=0)
    q_long, q_short = 2 * np.pi / L, np.pi / grid.spacing[0]
    fit = (q >= 8 * q_long) & (q <= q_short / 2)
    slope = np.polyfit(np.log(q[fit]), np.log(c[fit]), 1)[0]
    assert -slope / 2 - 1 == pytest.approx(hurst, abs=0.05)


def test_profile_hurst_exponent_recovered():
    """Profiles: C₁ ∝ q^-(1+2H); 64 profiles of 1024 points (±0.05)."""
    grid = surfaces.Grid((1024, 1), (L, L / 1024))
    spectra = [surfaces.psd(surfaces.self_affine(grid, hurst=0.5, prefactor=1e-20, rng=seed))
               for seed in range(64)]
    q, c = spectra[0][0], np.mean([s[1] for s in spectra], axis=0)
    fit = (q >= 8 * 2 * np.pi / L) & (q <= q.max() / 2)
    assert -np.polyfit(np.log(q[fit]), np.log(c[fit]), 1)[0] == pytest.approx(2.0, abs=0.1)


def step_rms(heights, axis):
    """rms of h(i+1) - h(i) for every i (the last is the step across the periodic boundary)."""
    steps = np.roll(heights, -1, axis) - heights
    return np.sqrt(np.mean(np.moveaxis(steps, axis, 0) ** 2, axis=1))


def test_periodic_field_is_continuous_across_the_boundary():
    """The wrap-around step is statistically an interior step: its rms lies within 4 standard deviations of
    the interior steps' rms values (a cropped, non-periodic field fails the same check by a wide margin)."""
    grid = surfaces.Grid((128, 128), (L, L))
    periodic = surfaces.self_affine(grid, hurst=0.8, rms_height=1e-6, rng=5).heights
    cropped = surfaces.self_affine(surfaces.Grid((128, 128), (L, L), False), hurst=0.8, rms_height=1e-6,
                                   rng=5).heights
    for axis in (0, 1):
        steps = step_rms(periodic, axis)
        assert abs(steps[-1] - steps[:-1].mean()) < 4 * steps[:-1].std()
        steps = step_rms(cropped, axis)
        assert steps[-1] - steps[:-1].mean() > 20 * steps[:-1].std()


def test_user_spectrum_callable():
    """Any C(q): a Gaussian-bump spectrum gives the requested rms slope and puts power only where C > 0."""
    grid = surfaces.Grid((64, 64), (L, L))
    q0 = 2 * np.pi * 10 / L
    field = surfaces.fourier_synthesis(grid, lambda q: np.exp(-((q - q0) / (0.1 * q0)) ** 2) * (q < 2 * q0),
                                       rng=2, rms_slope=0.05)
    assert surfaces.rms_slope(field) == pytest.approx(0.05, rel=1e-12)
    power = np.abs(fourier_modes(field)) ** 2
    assert power[grid.wavevector_magnitude() >= 2 * q0].max() < 1e-24 * power.max()     # FFT round-off


# -- bad input ----------------------------------------------------------------------------------------------
GRID = surfaces.Grid((32, 32), (L, L))


@pytest.mark.parametrize("kwargs, name", [
    (dict(hurst=0.0, rms_height=1e-6), "hurst"),
    (dict(hurst=1.2, rms_height=1e-6), "hurst"),
    (dict(hurst=float("nan"), rms_height=1e-6), "hurst"),
    (dict(hurst=0.8, rms_height=1e-6, short_cutoff=1.5 * L / 32), "short_cutoff"),
    (dict(hurst=0.8, rms_height=1e-6, short_cutoff=float("nan")), "short_cutoff"),
    (dict(hurst=0.8, rms_height=1e-6, long_cutoff=2 * L), "long_cutoff"),
    (dict(hurst=0.8, rms_height=1e-6, long_cutoff=L / 2, rolloff=0.8 * L), "rolloff"),
    (dict(hurst=0.8, rms_height=1e-6, rolloff=L / 8, short_cutoff=L / 4), "rolloff"),
    (dict(hurst=0.8, rms_height=1e-6, long_cutoff=L / 10, short_cutoff=L / 4), "long_cutoff"),
    (dict(hurst=0.8), "rms_height"),
    (dict(hurst=0.8, rms_height=1e-6, rms_slope=0.1), "rms_slope"),
    (dict(hurst=0.8, rms_slope=0.1, prefactor=1e-20), "prefactor"),
    (dict(hurst=0.8, rms_height=-1e-6), "rms_height"),
    (dict(hurst=0.8, prefactor=float("nan")), "prefactor"),
    (dict(hurst=0.8, rms_slope=0.1, normalise=False), "short_cutoff"),
])
def test_bad_input_names_parameter_and_range(kwargs, name):
    with pytest.raises(ValueError, match=name) as error:
        surfaces.self_affine(GRID, **kwargs)
    assert "range" in str(error.value) or "exactly one" in str(error.value)


def test_bad_spectrum_and_grid():
    with pytest.raises(ValueError, match="lengths"):
        surfaces.Grid((32, 32), (0.0, L))
    with pytest.raises(ValueError, match="profile"):
        surfaces.fourier_synthesis(GRID, SelfAffinePSD(0.8, 1, L, L, L / 8, profile=True), rng=0)
    with pytest.raises(ValueError, match="finite"):
        surfaces.fourier_synthesis(GRID, lambda q: -q, rng=0)
    with pytest.raises(TypeError, match="rng"):
        surfaces.self_affine(GRID, hurst=0.8, rms_height=1e-6, rng="seed")
    with pytest.raises(TypeError, match="profile must be True or False, got 'no'"):
        SelfAffinePSD(0.8, 1, L, L, L / 8, profile="no")
    with pytest.raises(TypeError, match="normalise must be True or False"):
        surfaces.self_affine(GRID, hurst=0.8, rms_height=1e-6, normalise="no", rng=0)
    with pytest.raises(ValueError, match="rng = -1 is a negative seed; valid range: int seeds >= 0"):
        surfaces.self_affine(GRID, hurst=0.8, rms_height=1e-6, rng=-1)
    for shape in ((1, 1), (2, 1), (2, 2)):              # no wavelength between two pixels and the window
        with pytest.raises(ValueError, match=r"grid shape .* too coarse.*at least 3 pixels") as error:
            surfaces.self_affine(surfaces.Grid(shape, (L, L)), hurst=0.8, rms_height=1e-6, rng=0)
        assert "long_cutoff" not in str(error.value)
    assert surfaces.self_affine(surfaces.Grid((3, 1), (L, L)), hurst=0.8, rms_height=1e-6, rng=0).heights.std() \
        == pytest.approx(1e-6, rel=1e-12)


def test_block_processing_does_not_change_the_field():
    """The spectrum is assembled in row blocks (256 by default); any block size gives the same field."""
    from surfaces.selfaffine import _synthesise_periodic
    grid = surfaces.Grid((37, 30), (L, L))
    spectrum = SelfAffinePSD(0.8, 1e-20, L, L / 4, None)
    whole, _ = _synthesise_periodic(grid, spectrum, np.random.default_rng(1), None, None)
    blocked, _ = _synthesise_periodic(grid, spectrum, np.random.default_rng(1), None, None, block_rows=5)
    assert np.array_equal(whole, blocked)
