"""The AC field with a leaky stratum corneum against the series circuit, the dielectric and DC limits, a direct
time integration of the columns' RC network, and the circuit's crossover on a rough gap with contact."""
import dataclasses
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from surfaces import Grid, self_affine
from roughcontact import ElasticHalfSpace, ElectrostaticInteraction, solve_contact
from roughcontact.electrostatics import (EPSILON_0, ACFieldSolution, DielectricStack, StackField, crossover_frequency,
                                         solve_ac_field, solve_field)
from roughcontact.electrostatics import ac
from roughcontact.io.results import ConvergenceWarning
from roughcontact.solvers import ContactResult

TABLE1 = DielectricStack()
HUMID = DielectricStack(d_sc=30e-6, eps_sc=1500.0, d_i=2e-6, eps_i=5.0, eps_a=1.7, sigma_sc=3e-3)


def circuit_flux(stack, gap, voltage, frequency):
    """D̂ [C/m²] of a uniform gap from impedances per unit area: the stratum corneum a resistor d_sc/σ_sc parallel
    to a capacitor ε0 ε_sc/d_sc, in series with the capacitor ε0/(g/ε_a + d_i/ε_i) of air and insulator; D̂ is the
    charge phasor I/(iω) (DC: the whole voltage across air and insulator)."""
    rest = EPSILON_0 / (gap / stack.eps_a + stack.d_i / stack.eps_i)
    if frequency == 0:
        return rest * voltage
    omega = 2 * math.pi * frequency
    skin = (1 / stack.d_sc) * (stack.sigma_sc + 1j * omega * EPSILON_0 * stack.eps_sc)       # admittance [S/m²]
    current = voltage / (1 / skin + 1 / (1j * omega * rest))
    return current / (1j * omega)


@pytest.fixture(scope="module")
def rough():
    """A hard-wall solved gap with contact: a 64² self-affine patch (0.5 mm, 3 µm rms) at 5 kPa, 17 % contact."""
    grid = Grid((64, 64), (0.5e-3, 0.5e-3), periodic=True)
    surface = self_affine(grid, hurst=0.8, rms_height=3e-6, short_cutoff=8 * 0.5e-3 / 64, rng=1)
    gap = solve_contact(surface, ElasticHalfSpace(grid, E_star=1e6), mean_pressure=5e3).gap
    assert 0.1 < np.mean(gap == 0) < 0.3
    return grid, gap


@pytest.mark.parametrize("stack", [TABLE1, HUMID], ids=["table1", "humid"])
@pytest.mark.parametrize("model", ["layered", "parallel_plate"])
@pytest.mark.parametrize("shape", [(16, 16), (24,)])
def test_uniform_gap_is_the_series_circuit(stack, model, shape):
    """At 1e-2 … 1e6 times the crossover, at DC and at ω = ∞: flux, time average and the complex 2ω amplitude
    D̂²/(2 ε0 ε_a) equal the circuit's to round-off (measured < 1e-15; asserted 1e-12, far below any physics:
    an amplitude instead of an RMS voltage is off by 2, a lost i in ε*_sc by 1e-3 … 1)."""
    gap = 1.5e-6
    crossover = crossover_frequency(stack, gap / stack.eps_a + stack.d_i / stack.eps_i)
    lengths = 1e-3 if len(shape) == 1 else (1e-3, 1e-3)
    for frequency in [*(crossover * 10.0 ** np.arange(-2, 7)), 0.0, math.inf]:
        solution = solve_ac_field(stack, np.full(shape, gap), lengths, 70.0, frequency=frequency, model=model)
        flux = circuit_flux(stack, gap, 70.0, frequency) if frequency < math.inf else \
            EPSILON_0 * 70.0 / stack.electrical_thickness(gap)
        assert solution.flux == pytest.approx(np.full(shape, flux), rel=1e-12, abs=0)
        assert solution.mean_attraction == pytest.approx(abs(flux) ** 2 / (2 * EPSILON_0 * stack.eps_a), rel=1e-12)
        oscillation = 0.0 if frequency == 0 else flux ** 2 / (2 * EPSILON_0 * stack.eps_a)
        assert np.mean(solution.oscillation) == pytest.approx(oscillation, rel=1e-12, abs=1e-12 * abs(oscillation))
        assert solution.ac_equivalent_gap == pytest.approx(gap, rel=1e-12)    # the circuit inverted
    # the RMS convention: at ω = ∞ the time average is the seed's Eq. 21 at U
    assert solution.mean_attraction == pytest.approx(float(stack.attraction(gap, 70.0)), rel=1e-12)


def test_the_crossover_separates_the_limits_as_a_lorentzian():
    """Uniform gap: (σ̄ − σ̄_∞)/(σ̄_0 − σ̄_∞) = 1/(1 + (f/f_c)²) with f_c of ``crossover_frequency`` (to 1e-9: the
    difference of limits 7 % apart loses 1.5 digits of the 1e-12 solves)."""
    gap = np.full((8, 8), 2e-6)
    rest = 2e-6 + TABLE1.d_i / TABLE1.eps_i
    limits = [solve_ac_field(TABLE1, gap, (1e-4, 1e-4), frequency=f).mean_attraction for f in (0.0, math.inf)]
    crossover = crossover_frequency(TABLE1, rest)
    for ratio in (0.1, 1.0, 3.0):
        mean = solve_ac_field(TABLE1, gap, (1e-4, 1e-4), frequency=ratio * crossover).mean_attraction
        assert (mean - limits[1]) / (limits[0] - limits[1]) == pytest.approx(1 / (1 + ratio ** 2), rel=1e-9)


@pytest.mark.parametrize("periodic", [True, False])
def test_limits_on_a_rough_gap_with_contact(rough, periodic):
    """ω → ∞ is ``solve_field`` and ω → 0 (and DC) is ``solve_field`` without the stratum corneum's elastance (ε_sc
    → 1e300), per pixel to 1e-10 of the largest attraction; all solved to a residual of 1e-13 (measured
    agreement < 2e-15; the limits differ from each other by 16–28 %). At 1e15 Hz the conduction's share is
    σ_sc/(ω ε0 ε_sc) ~ 1e-12, at 1e-12 Hz the capacitance's ω ε0 ε_sc/σ_sc ~ 1e-15."""
    grid, gap = rough
    lengths = grid.lengths

    def close(solution, reference):
        scale = reference.attraction.max()
        np.testing.assert_allclose(solution.attraction, reference.attraction, rtol=0, atol=1e-10 * scale)
        np.testing.assert_allclose(solution.flux, reference.flux, rtol=0, atol=1e-10 * np.abs(reference.flux).max())

    dielectric = solve_field(TABLE1, gap, lengths, 100.0, periodic=periodic, tol=1e-13)
    conductor = solve_field(dataclasses.replace(TABLE1, eps_sc=1e300), gap, lengths, 100.0, periodic=periodic,
                            tol=1e-13)
    for frequency, reference in ((math.inf, dielectric), (1e15, dielectric), (1e-12, conductor), (0.0, conductor)):
        solution = solve_ac_field(TABLE1, gap, lengths, 100.0, frequency=frequency, periodic=periodic, tol=1e-13)
        close(solution, reference)
    assert conductor.mean_attraction > 1.1 * dielectric.mean_attraction
    # a lossless stack and a sinusoid of vanishing frequency oscillate fully in phase; DC does not oscillate
    for frequency in (math.inf, 1e-12):
        solution = solve_ac_field(TABLE1, gap, lengths, 100.0, frequency=frequency, periodic=periodic, tol=1e-13)
        np.testing.assert_allclose(solution.oscillation, solution.attraction, rtol=0,
                                   atol=1e-10 * solution.attraction.max())
    assert not np.any(solve_ac_field(TABLE1, gap, lengths, 100.0, frequency=0.0, periodic=periodic).oscillation)


def test_time_average_against_a_time_integration_of_the_columns():
    """A 1-D profile with contact, integrated in time from rest as the linear network it is: per Fourier mode the
    stratum corneum passes the current (σ_sc + ε0 ε_sc ∂t) S⁻¹ v for its voltage drop v (S = tanh(q d_sc)/q, its
    slab response), which equals the air's displacement current ∂D/∂t, and v + (T_i/(ε0 ε_i) + R) D = U(t): a
    dense ODE in v, integrated by DOP853 (rtol 1e-13) over nine periods at the crossover (transients decay as
    e^{-2π·9}), then the instantaneous virtual-work force of the dielectric kernel sampled 64 times over the
    tenth period. Its mean and its 2ω Fourier coefficient match σ̄ and σ̂₂ of the phasor solve (measured 6e-15
    of the largest attraction; asserted 1e-9, the integrator's tolerance with margin)."""
    stack, n, length, voltage = TABLE1, 32, 200e-6, 100.0
    x = np.arange(n) * length / n
    gap = np.maximum(2e-6 * np.cos(2 * np.pi * x / length) + 0.3e-6 * np.sin(6 * np.pi * x / length) + 0.8e-6, 0)
    assert np.any(gap == 0)
    q = np.abs(2 * np.pi * np.fft.fftfreq(n, d=length / n))

    def circulant(symbol):
        return np.real(np.fft.ifft(symbol[:, None] * np.fft.fft(np.eye(n), axis=0), axis=0))

    def slab(thickness):
        return np.where(q > 0, np.tanh(q * thickness) / np.where(q > 0, q, 1.0), thickness)

    skin, insulator = circulant(slab(stack.d_sc)), circulant(slab(stack.d_i)) / (EPSILON_0 * stack.eps_i)
    field = StackField(stack, Grid((n, 1), (length, length / n)))
    columns = field.column_elastance(gap[:, None]).ravel()
    rest = np.linalg.inv(insulator + np.diag(columns))                   # D = rest (U − v)
    lhs = np.linalg.inv(skin @ rest + EPSILON_0 * stack.eps_sc * np.eye(n))
    drive, leak = lhs @ skin @ rest @ np.ones(n), stack.sigma_sc * lhs
    frequency = crossover_frequency(stack, EPSILON_0 * n / np.sum(rest))
    omega, period = 2 * math.pi * frequency, 1 / frequency

    def rate(t, v):              # (S rest + ε0 ε_sc) v' = S rest U'(t) − σ_sc v, U(t) = √2 U cos ωt
        return drive * (-math.sqrt(2) * voltage * omega * math.sin(omega * t)) - leak @ v

    integrated = solve_ivp(rate, (0, 10 * period), np.zeros(n), method="DOP853", rtol=1e-13, atol=1e-16,
                           dense_output=True)
    times = 9 * period + np.arange(64) * period / 64
    drops = integrated.sol(times)
    force = np.array([field.attraction(gap[:, None], (rest @ (math.sqrt(2) * voltage * math.cos(omega * t)
                                                                - drops[:, k]))[:, None]).ravel()
                      for k, t in enumerate(times)])
    mean, oscillation = force.mean(axis=0), 2 * np.mean(force * np.exp(-2j * omega * times)[:, None], axis=0)
    solution = solve_ac_field(stack, gap, length, voltage, frequency=frequency, tol=1e-13)
    scale = mean.max()
    np.testing.assert_allclose(solution.attraction, mean, rtol=0, atol=1e-9 * scale)
    np.testing.assert_allclose(solution.oscillation, oscillation, rtol=0, atol=1e-9 * scale)
    assert abs(np.angle(np.mean(oscillation))) > 1e-3       # the 2ω force lags: a check of the phase, too


def mean_attraction(stack, gap, lengths, frequency):
    return solve_ac_field(stack, gap, lengths, 100.0, frequency=frequency, tol=1e-12).mean_attraction


def measured_crossover(stack, gap, lengths):
    """The frequency [Hz] at which ⟨σ̄⟩ is halfway between its DC and dielectric limits (root in log f)."""
    middle = 0.5 * sum(mean_attraction(stack, gap, lengths, f) for f in (0.0, math.inf))
    return 10 ** brentq(lambda log_f: mean_attraction(stack, gap, lengths, 10 ** log_f) - middle, -1, 6,
                        xtol=1e-12)


def capacitance_thickness(stack, gap, lengths):
    """h_rest [m]: the air-equivalent thickness of air + insulator from their DC capacitance, ε0 U/⟨D̂_DC⟩."""
    return EPSILON_0 * 100.0 / np.mean(solve_ac_field(stack, gap, lengths, 100.0, frequency=0.0, tol=1e-12).flux.real)


def test_rough_gap_attraction_falls_monotonically_through_the_crossover(rough):
    """⟨σ̄⟩ falls strictly from the DC to the dielectric limit over 1e-2 … 1e3 times the crossover (each step
    >> the 1e-12 solves' error), and the measured half-way frequency is the circuit's f_c with h_rest from the
    DC capacitance of air + insulator within 5 % (measured +1.9 %: the stratum corneum's lateral modes, see the
    next test). The seed's ε_sc alone (+13 %) or h_rest from the arithmetic mean gap (+9 %) are outside."""
    grid, gap = rough
    measured = measured_crossover(TABLE1, gap, grid.lengths)
    frequencies = measured * np.logspace(-2, 3, 21)
    means = [mean_attraction(TABLE1, gap, grid.lengths, f) for f in (0.0, *frequencies, math.inf)]
    assert np.all(np.diff(means) < -1e-9 * means[0])
    predicted = crossover_frequency(TABLE1, capacitance_thickness(TABLE1, gap, grid.lengths))
    assert predicted == pytest.approx(measured, rel=0.05)
    assert TABLE1.sigma_sc / (2 * math.pi * EPSILON_0 * TABLE1.eps_sc) > 1.1 * measured
    assert crossover_frequency(TABLE1, gap.mean() + TABLE1.d_i / TABLE1.eps_i) > 1.08 * measured


def test_rough_gap_crossover_is_the_circuits_for_a_laterally_uniform_stratum_corneum(rough, monkeypatch):
    """With the stratum corneum's response reduced to its uniform mode (q = 0) the flux is the DC pattern times
    one scalar, so ⟨σ̄⟩(f) is exactly the series circuit's Lorentzian with h_rest the DC capacitance thickness:
    measured f_c to 1e-13, asserted 1e-9 (the root finder's 1e-12 in log f and the 1e-12 solves)."""
    grid, gap = rough
    slab_elastance = ac.slab_elastance

    def uniform_mode_only(q, thickness, permittivity):
        response = slab_elastance(q, thickness, permittivity)
        return np.where(q == 0, response, 0.0) if thickness == TABLE1.d_sc else response

    monkeypatch.setattr(ac, "slab_elastance", uniform_mode_only)
    predicted = crossover_frequency(TABLE1, capacitance_thickness(TABLE1, gap, grid.lengths))
    assert measured_crossover(TABLE1, gap, grid.lengths) == pytest.approx(predicted, rel=1e-9)


@pytest.mark.parametrize("periodic", [True, False])
def test_scipy_backend_agrees(rough, periodic):
    """The complex operator through scipy.fft (strided real and imaginary parts copied by the backend) gives the
    pyFFTW solve's attraction to 1e-12 of its largest value (both solved to 1e-13; measured < 2e-15)."""
    grid, gap = rough
    solutions = [solve_ac_field(TABLE1, gap, grid.lengths, 100.0, frequency=1e3, periodic=periodic, tol=1e-13,
                                backend=backend) for backend in ("pyfftw", "scipy")]
    np.testing.assert_allclose(solutions[1].attraction, solutions[0].attraction, rtol=0,
                               atol=1e-12 * solutions[0].attraction.max())
    np.testing.assert_allclose(solutions[1].oscillation, solutions[0].oscillation, rtol=0,
                               atol=1e-12 * solutions[0].attraction.max())


def test_cocg_converges_and_reports_when_it_does_not(rough):
    grid, gap = rough
    solution = solve_ac_field(TABLE1, gap, grid.lengths, 100.0, frequency=1e3)
    assert solution.residual <= 1e-10 and 3 < solution.iterations < 40
    with pytest.warns(ConvergenceWarning, match="AC field solve stopped"):
        stalled = solve_ac_field(TABLE1, gap, grid.lengths, 100.0, frequency=1e3, maxiter=1)
    assert stalled.residual > 1e-10 and np.all(np.isfinite(stalled.attraction))
    assert isinstance(solution, ACFieldSolution)
    assert solution.mean_oscillation <= np.mean(solution.oscillation_amplitude) * (1 + 1e-12)
    assert solution.field_equivalent_gap == pytest.approx(TABLE1.gap_for_attraction(solution.mean_attraction, 100.0))
    dielectric = solve_ac_field(TABLE1, gap, grid.lengths, 100.0, frequency=math.inf)
    assert dielectric.ac_equivalent_gap == pytest.approx(dielectric.field_equivalent_gap, rel=1e-12)
    # the lossy stratum corneum attracts more than the dielectric at the same gap: its own circuit's gap is larger
    assert solution.ac_equivalent_gap > solution.field_equivalent_gap
    with pytest.raises(AttributeError, match="no energy"):
        solution.energy


@pytest.mark.parametrize("frequency, error", [(-1.0, ValueError), (math.nan, ValueError), (-math.inf, ValueError),
                                              ("50 Hz", TypeError), (True, TypeError)])
def test_bad_frequency(rough, frequency, error):
    grid, gap = rough
    with pytest.raises(error, match="frequency"):
        solve_ac_field(TABLE1, gap, grid.lengths, 1.0, frequency=frequency)


@pytest.mark.parametrize("value, error", [(-1e-4, ValueError), (math.nan, ValueError), (math.inf, ValueError),
                                          ("dry", TypeError)])
def test_bad_conductivity(value, error):
    with pytest.raises(error, match="sigma_sc"):
        DielectricStack(sigma_sc=value)


def test_the_conductivity_changes_no_dielectric_number_and_round_trips(tmp_path):
    """The stack's Eq. 21 and the dielectric field ignore σ_sc; a result holding the stack saves and loads it."""
    lossless = dataclasses.replace(TABLE1, sigma_sc=0.0)
    gap = np.random.default_rng(3).exponential(1e-6, (16, 16))
    assert np.array_equal(TABLE1.attraction(gap, 50.0), lossless.attraction(gap, 50.0))
    assert np.array_equal(solve_field(TABLE1, gap, (1e-4, 1e-4), 50.0).attraction,
                          solve_field(lossless, gap, (1e-4, 1e-4), 50.0).attraction)
    # σ_sc = 0: the stratum corneum is a dielectric at every frequency, DC included
    np.testing.assert_allclose(solve_ac_field(lossless, gap, (1e-4, 1e-4), 50.0, frequency=0.0).attraction,
                               solve_field(TABLE1, gap, (1e-4, 1e-4), 50.0).attraction, rtol=1e-9)
    grid = Grid((16, 16), (1e-4, 1e-4))
    surface = self_affine(grid, hurst=0.8, rms_height=1e-6, rng=0)
    stack = dataclasses.replace(HUMID, sigma_sc=1.25e-3)
    result = solve_contact(surface, ElasticHalfSpace(grid, E_star=1e6), mean_pressure=1e3,
                           interaction=ElectrostaticInteraction(stack, 10.0))
    loaded = ContactResult.load(result.save(tmp_path / "result.npz"))
    assert loaded.interaction.stack == stack
