"""The stack's field with the air's lateral field (model="layered_air") against exact references."""
import numpy as np
import pytest

from roughcontact.electrostatics import DielectricStack, solve_field
from roughcontact.reference.perturbation import second_order_attraction

STACK = DielectricStack()
VOLTAGE = 200.0


def _second_order(model, mean_gap, wavelength, columns=64):
    """S of a sinusoidal gap from the mean attraction at a = 0.05 g0 and 0.1 g0 (Richardson: the a⁴ term
    removed), as studies/field_check.py measures it."""
    x = np.arange(columns) * wavelength / columns
    shape = np.cos(2 * np.pi * x / wavelength)

    def mean(amplitude):
        return solve_field(STACK, mean_gap + amplitude * shape, wavelength, VOLTAGE, model=model,
                           tol=1e-12).mean_attraction
    amplitude = 0.05 * mean_gap
    excess = [mean(a) - mean(0.0) for a in (amplitude, 2 * amplitude)]
    return (16 * excess[0] - excess[1]) / (12 * amplitude ** 2)


def _rough_gap(shape, rng=1):
    """A periodic gap field with ~10-25 % contact: a smooth bump plus noise, shifted down and clipped [m]."""
    generator = np.random.default_rng(rng)
    x = np.arange(shape[0])[:, None] / shape[0]
    y = np.arange(shape[1])[None, :] / shape[1]
    bump = 1 - np.cos(2 * np.pi * x) * (np.cos(2 * np.pi * y) if shape[1] > 1 else 1.0)
    return np.maximum(1.5e-6 * bump + 0.3e-6 * generator.standard_normal(shape) - 0.4e-6, 0.0)


def test_uniform_gap_is_the_parallel_plate():
    """The lateral terms vanish on a uniform gap: Eq. 21 to rounding (1e-10 leaves room for the CG's 1e-12)."""
    solution = solve_field(STACK, np.full(32, 0.8e-6), 50e-6, VOLTAGE, model="layered_air", tol=1e-12)
    assert solution.mean_attraction == pytest.approx(float(STACK.attraction(0.8e-6, VOLTAGE)), rel=1e-10)
    assert solution.field_equivalent_gap == pytest.approx(0.8e-6, rel=1e-10)
    assert solution.energy == pytest.approx(float(STACK.energy(0.8e-6, VOLTAGE)), rel=1e-10)


@pytest.mark.parametrize("wavelength", [10e-6, 100e-6, 1e-3, 5e-3])
@pytest.mark.parametrize("mean_gap", [0.5e-6, 1e-6, 2e-6])
def test_sinusoid_against_the_exact_second_order_response(wavelength, mean_gap):
    """Issue bar: S within 3 % of the exact layered-stack response for λ = 10 µm – 5 mm, g0 = 0.5–2 µm. The linear
    air element approximates the slab's q coth(q g) to O((q g)⁴): measured worst 1.6 % at λ = 10 µm, g0 = 2 µm
    (q g0 = 1.26), 0.07 % or less from λ = 100 µm (the 64-pixel sinusoid's own error)."""
    exact = float(second_order_attraction(STACK, mean_gap, 2 * np.pi / wavelength, VOLTAGE))
    assert _second_order("layered_air", mean_gap, wavelength) / exact == pytest.approx(1.0, abs=0.03 if
                                                                                      wavelength < 20e-6 else 1e-3)


def test_air_columns_miss_the_short_sinusoid():
    """The reference discriminates: the column model (model="layered") is 5 % short at λ = 10 µm, g0 = 2 µm,
    the air-lateral model within 2 %."""
    exact = float(second_order_attraction(STACK, 2e-6, 2 * np.pi / 10e-6, VOLTAGE))
    assert _second_order("layered", 2e-6, 10e-6) / exact < 0.96
    assert abs(_second_order("layered_air", 2e-6, 10e-6) / exact - 1) < 0.02


def test_long_wavelengths_reduce_to_the_column_model():
    """As q g -> 0 the lateral terms reduce to the column model's slope factor: S equal to 1e-4 at λ = 1 mm
    (measured 2e-5; the two discretise the slope differently, central against edge differences)."""
    assert _second_order("layered_air", 1e-6, 1e-3) == pytest.approx(_second_order("layered", 1e-6, 1e-3),
                                                                     rel=1e-4)


@pytest.mark.parametrize("shape, lengths", [((48, 1), (40e-6, 40e-6 / 48)), ((24, 20), (40e-6, 33e-6))])
def test_attraction_is_the_energy_derivative(shape, lengths):
    """σ_el = N ∂W/∂g with W = −½ U ⟨D⟩, on open pixels by central differences (1e-6; measured ≤ 1e-7, the
    field solves at 1e-14) and on contact pixels by a one-sided second-order difference (1e-5: the step's
    second-order error, measured ≤ 3e-6). Fails without the lateral terms' opening derivative."""
    gap = _rough_gap(shape)
    solution = solve_field(STACK, gap, lengths, VOLTAGE, model="layered_air", tol=1e-13)

    def energy(changed):
        return solve_field(STACK, changed, lengths, VOLTAGE, model="layered_air", tol=1e-13).energy

    generator = np.random.default_rng(2)
    contact = np.flatnonzero(gap.ravel() == 0)
    open_ = np.flatnonzero(gap.ravel() > 1e-8)
    step = 1e-10
    for index in list(generator.choice(open_, 3, replace=False)) + list(generator.choice(contact, 2,
                                                                                         replace=False)):
        pixel = np.unravel_index(index, shape)

        def shifted(delta):
            changed = gap.copy()
            changed[pixel] += delta
            return energy(changed)
        if gap[pixel] > 0:
            derivative, tolerance = (shifted(step) - shifted(-step)) / (2 * step), 1e-6
        else:
            base = energy(gap)
            derivative = (4 * (shifted(step) - base) - (shifted(2 * step) - base)) / (2 * step)
            tolerance = 1e-5
        assert solution.attraction[pixel] == pytest.approx(gap.size * derivative, rel=tolerance)


def test_differs_from_columns_by_the_air_alone():
    """On a rough gap with contact the two models differ by the air's lateral field only: below 2 % here
    (measured 0.8 %), and not at all once the lateral terms vanish (a uniform gap, above)."""
    gap = _rough_gap((64, 1))
    air = solve_field(STACK, gap[:, 0], 40e-6, VOLTAGE, model="layered_air").mean_attraction
    columns = solve_field(STACK, gap[:, 0], 40e-6, VOLTAGE, model="layered").mean_attraction
    assert 0 < abs(air / columns - 1) < 0.02


def test_refuses_a_free_window_and_unknown_models():
    with pytest.raises(ValueError, match="periodic"):
        solve_field(STACK, np.full(16, 1e-6), 50e-6, VOLTAGE, model="layered_air", periodic=False)
    with pytest.raises(ValueError, match="model"):
        solve_field(STACK, np.full(16, 1e-6), 50e-6, VOLTAGE, model="air")
