"""The layered field model (roughcontact.electrostatics.field) against closed forms, limits and finite differences."""
import numpy as np
import pytest

from roughcontact.electrostatics import EPSILON_0, DielectricStack, solve_field
from roughcontact.electrostatics.field import StackField
from surfaces import Grid

STACK = DielectricStack()


def rough_gap(shape, rng, contact=0.2, scale=2e-6):
    """A gap field with a contact fraction ``contact``: a smoothed random field shifted so that its lowest values
    touch (g = 0)."""
    frequency = np.add.outer(np.fft.fftfreq(shape[0]) ** 2, np.fft.rfftfreq(shape[1]) ** 2)
    noise = np.fft.irfft2(np.fft.rfft2(rng.standard_normal(shape)) * np.exp(-200 * frequency), shape)
    noise *= scale / noise.std()
    return np.maximum(noise - np.quantile(noise, contact), 0.0)


@pytest.mark.parametrize("model", ["layered", "parallel_plate"])
@pytest.mark.parametrize("shape", [(64,), (32, 48)])
@pytest.mark.parametrize("gap", [0.0, 0.4e-6, 7e-6])
def test_uniform_gap_is_eq21(model, shape, gap):
    # A uniform gap carries a uniform flux: both models are the series capacitor (Eq. 21), to round-off (the CG
    # solve's tolerance 1e-10 bounds the rest), and the equivalent gap is the gap.
    solution = solve_field(STACK, np.full(shape, gap), 1e-3 if len(shape) == 1 else (1e-3, 1.5e-3), 150.0,
                           model=model)
    assert solution.mean_attraction == pytest.approx(float(STACK.attraction(gap, 150.0)), rel=1e-10)
    assert np.allclose(solution.attraction, STACK.attraction(gap, 150.0), rtol=1e-10, atol=0)
    assert solution.field_equivalent_gap == pytest.approx(gap, abs=1e-10 * STACK.dielectric_offset)
    assert solution.energy == pytest.approx(float(STACK.energy(gap, 150.0)), rel=1e-10)


def test_parallel_plate_is_eq21_pixel_by_pixel():
    gap = rough_gap((48, 40), np.random.default_rng(1))
    solution = solve_field(STACK, gap, (1e-4, 1e-4), 80.0, model="parallel_plate")
    assert np.allclose(solution.attraction, STACK.attraction(gap, 80.0), rtol=1e-13, atol=0)
    assert solution.field_equivalent_gap == pytest.approx(STACK.equivalent_gap(gap), rel=1e-12)


@pytest.mark.parametrize("wavelength", [20e-6, 450e-6])
@pytest.mark.parametrize("mean_gap", [0.5e-6, 2e-6])
def test_sinusoid_against_the_models_perturbation_series(wavelength, mean_gap):
    # g = g0 + a cos(qx): (M + R) D = U expanded in a. With r = g/(ε0 ε_a (1 + s²/3)), s = −a k sin(qx) the
    # central difference of the sinusoid (k = sin(q Δx)/Δx), r = r0 + r1 cos(qx) + r2 with ⟨r2⟩ = −r0 a² k²/6;
    # m0, m_q the elastance of the modes 0 and q: D0 = U/(m0 + r0), D1 = −r1 D0/(m_q + r0), and the mean of the
    # second order ⟨D2⟩ = −(r1 D1/2 + ⟨r2⟩ D0)/(m0 + r0). This closed form tests the FFT multiplier, its
    # normalisation, the slope factor and the CG solve on one mode; at a/g0 = 1e-3 the O(a⁴) rest is 1e-6 of
    # the a² term, the tolerance 1e-4 of it. The mean attraction is the energy's derivative (next tests).
    n, amplitude, voltage = 64, 1e-3 * mean_gap, 100.0
    x = np.arange(n) * wavelength / n
    q = 2 * np.pi / wavelength
    slope = np.sin(q * wavelength / n) / (wavelength / n)
    solution = solve_field(STACK, mean_gap + amplitude * np.cos(q * x), wavelength, voltage)
    m0 = STACK.dielectric_offset / EPSILON_0
    mq = (np.tanh(q * STACK.d_sc) / (STACK.eps_sc * q) + np.tanh(q * STACK.d_i) / (STACK.eps_i * q)) / EPSILON_0
    r0, r1 = mean_gap / (EPSILON_0 * STACK.eps_a), amplitude / (EPSILON_0 * STACK.eps_a)
    d0 = voltage / (m0 + r0)
    d1 = -r1 * d0 / (mq + r0)
    d2 = -(r1 * d1 / 2 - r0 * (amplitude * slope) ** 2 / 6 * d0) / (m0 + r0)
    assert np.mean(solution.flux) - d0 == pytest.approx(d2, rel=1e-4)
    # the layered response differs from the per-pixel one (m_q < m0): the test distinguishes the two models
    per_pixel = solve_field(STACK, mean_gap + amplitude * np.cos(q * x), wavelength, voltage, model="parallel_plate")
    assert abs((np.mean(per_pixel.flux) - d0) / d2 - 1) > 1e-2


def test_long_wavelengths_and_bare_electrodes_recover_the_parallel_plate():
    # Two limits in which the columns decouple: wavelengths far above d_sc (M -> c/ε0, relative difference
    # O((q d_sc)²) = 1e-3 here), and a stack without solid layers' lateral response (a vanishing insulator
    # and an almost conducting stratum corneum: M -> 0, so D = U/R column by column, the derivative expansion
    # ε0 U (1 + |∇g|²/3)/g of bare conductors).
    rng = np.random.default_rng(2)
    gap = rough_gap((64, 1), rng, contact=0.0) + 1e-6
    wide = 2 * np.pi * STACK.d_sc / 0.03                  # q d_sc = 0.03 at the fundamental
    layered = solve_field(STACK, gap[:, 0], wide, 100.0).mean_attraction
    plate = solve_field(STACK, gap[:, 0], wide, 100.0, model="parallel_plate").mean_attraction
    assert layered == pytest.approx(plate, rel=2e-3)
    bare = DielectricStack(d_sc=1e-9, eps_sc=1e6, d_i=1e-12, eps_i=1.0)
    flux = solve_field(bare, gap[:, 0], 1e-4, 100.0).flux
    slope = (np.roll(gap[:, 0], -1) - np.roll(gap[:, 0], 1)) / (2 * 1e-4 / gap.shape[0])
    assert np.allclose(flux, EPSILON_0 * 100.0 * (1 + slope ** 2 / 3) / gap[:, 0], rtol=1e-5)


@pytest.mark.parametrize("periodic", [True, False])
def test_attraction_is_the_energy_derivative(periodic):
    # σ_el,i = N ∂W/∂g_i (W per unit area of the window, N pixels; dV/dd = σ_el as in DielectricStack.energy):
    # differences of the solved energy at a contact pixel (one-sided, second order: g >= 0), a near-contact
    # pixel and an open one (central). Step 2e-10 m: truncation O(step²) ~ 1e-6 relative at contact
    # (h ~ 0.34 µm), the solves' round-off (tol 1e-13) ~ 1e-13 U ⟨D⟩ N / step ~ 1e-8; 1e-5 is asserted. A
    # one-sided first-order difference is off by 6e-4 at the contact pixel: the test resolves that.
    rng = np.random.default_rng(3)
    gap = rough_gap((32, 24), rng, contact=0.3)
    lengths, voltage, step = (60e-6, 45e-6), 120.0, 2e-10
    solution = solve_field(STACK, gap, lengths, voltage, periodic=periodic, tol=1e-13)

    def energy(index, shift):
        shifted = gap.copy()
        shifted[index] += shift
        return solve_field(STACK, shifted, lengths, voltage, periodic=periodic, tol=1e-13).energy * gap.size

    order = np.argsort(gap, axis=None)
    for flat in (order[0], order[int(0.32 * gap.size)], order[-1]):
        index = np.unravel_index(flat, gap.shape)
        if gap[index] == 0:
            derivative = (-3 * energy(index, 0.0) + 4 * energy(index, step) - energy(index, 2 * step)) / (2 * step)
        else:
            derivative = (energy(index, step) - energy(index, -step)) / (2 * step)
        assert derivative == pytest.approx(solution.attraction[index], rel=1e-5)


def test_layered_attraction_exceeds_the_per_pixel_law_at_microcontacts():
    # The stratum corneum is laterally almost a conductor at these scales: a contact pixel sees nearly the whole
    # voltage across the insulator, (c ε_i/d_i)² = 1.76 times Eq. 23 for the seed's stack, and more where the
    # insulator's own field fringes around a small contact; the per-pixel law gives exactly Eq. 23 there.
    rng = np.random.default_rng(4)
    gap = rough_gap((64, 64), rng, contact=0.05, scale=5e-6)
    solution = solve_field(STACK, gap, (2e-4, 2e-4), 100.0)
    contact = gap == 0
    ratio = solution.attraction[contact] / STACK.strong_troxel_attraction(100.0)
    assert np.all(ratio > 1.0) and np.median(ratio) > 1.5
    assert solution.mean_attraction > solve_field(STACK, gap, (2e-4, 2e-4), 100.0,
                                                model="parallel_plate").mean_attraction


def test_flux_scales_with_voltage_and_warm_start_converges_at_once():
    rng = np.random.default_rng(5)
    gap = rough_gap((32, 32), rng)
    grid = Grid(gap.shape, (1e-4, 1e-4))
    field = StackField(STACK, grid)
    flux, iterations, residual = field.solve_flux(gap)
    assert iterations > 3 and residual <= 1e-10
    again, restart_iterations, _ = field.solve_flux(gap, initial=flux)
    assert restart_iterations <= 1 and np.allclose(again, flux, rtol=1e-12)
    assert np.allclose(solve_field(STACK, gap, grid.lengths, 30.0).flux, 30.0 * flux, rtol=1e-9)


def test_free_window_carries_no_flux_outside():
    # On a free window the slabs extend beyond it but no flux enters outside: a strip of contact in the middle of a
    # wide open window is attracted like the same strip on a periodic window whose images are far apart.
    n = 256
    gap = np.full(n, 20e-6)
    gap[n // 2 - 4: n // 2 + 4] = 0.0
    free = solve_field(STACK, gap, 4e-3, 100.0, periodic=False)
    periodic = solve_field(STACK, gap, 4e-3, 100.0)
    # the strip's force is set by the slab's response within ~d_sc of it (window 16 d_sc): the two agree to 1e-3
    assert free.attraction[n // 2] == pytest.approx(periodic.attraction[n // 2], rel=1e-3)


@pytest.mark.parametrize("kwargs, message", [
    (dict(gap=-np.ones(4)), "gap"),
    (dict(gap=np.full(4, np.nan)), "gap"),
    (dict(gap=np.ones(4), lengths=None), "lengths"),
    (dict(gap=np.ones((2, 2, 2))), "1-D profile or a 2-D field"),
    (dict(gap=np.ones(4), model="fem"), "model"),
    (dict(gap=np.ones(4), voltage=np.inf), "voltage"),
    (dict(gap=np.ones(4), tol=0.0), "tol"),
    (dict(gap=np.ones(4), lengths=-1.0), "lengths"),
])
def test_bad_input_names_the_parameter(kwargs, message):
    arguments = dict(stack=STACK, lengths=1e-3, voltage=10.0) | kwargs
    with pytest.raises((ValueError, TypeError), match=message):
        solve_field(**arguments)


def test_field_law_is_the_field_and_its_warm_start_agrees():
    # FieldLaw (the contact solver's layered law) against solve_field's attraction on the same gap, and its warm
    # start (the previous gap's flux, updated column by column) against a cold evaluation. At tol 1e-12 the
    # field solve's error enters the traction and energy at ~1e-12 relative (bound 1e-9); the stiffness is the
    # diagonal estimate U² (D₁/ε_a ε0 f)² / (M_ii + R_ii), checked from the flux. The step is a late solver
    # step (2e-10 m): returning the previous gap's law unchanged would fail the warm check by 5e-3.
    from roughcontact.electrostatics.field import FieldLaw
    grid = Grid((48, 40), (1e-4, 1e-4), periodic=True)
    rng = np.random.default_rng(3)
    before = rough_gap(grid.shape, rng)
    after = np.maximum(before + 2e-10 * rng.standard_normal(grid.shape), 0.0)
    voltage = 120.0

    def evaluate(law, gap, start=None):
        arrays = [np.zeros(grid.shape) for _ in range(4)]        # traction, stiffness, flux, columns
        return law.evaluate(gap, *arrays, start=start), arrays

    law = FieldLaw(STACK, voltage, grid, tol=1e-12)
    energy, (traction, stiffness, flux, columns) = evaluate(law, before)
    reference = solve_field(STACK, before, grid.lengths, voltage, tol=1e-12)
    scale = np.max(reference.attraction)
    assert np.max(np.abs(traction - reference.traction)) < 1e-9 * scale
    assert energy / before.size == pytest.approx(reference.energy, rel=1e-9)
    field = StackField(STACK, grid)
    column_field = flux / (EPSILON_0 * STACK.eps_a * field.slope_factor(before))
    assert np.allclose(stiffness, voltage ** 2 * column_field ** 2 / (field.pixel_elastance + columns),
                       rtol=1e-12, atol=0)
    pairs = law.fft_pairs
    warm_energy, warm = evaluate(law, after, start=(columns, flux))
    cold_law = FieldLaw(STACK, voltage, grid, tol=1e-12)
    cold_energy, cold = evaluate(cold_law, after)
    assert warm_energy == pytest.approx(cold_energy, rel=1e-9)
    assert np.max(np.abs(warm[0] - cold[0])) < 1e-9 * scale
    assert np.max(np.abs(traction - cold[0])) > 1e-6 * scale       # the step is seen
    assert law.fft_pairs - pairs < cold_law.fft_pairs
