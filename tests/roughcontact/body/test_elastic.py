"""ElasticHalfSpace: periodic multiplier, free-surface Love coefficients, energy, backends, bad input."""
import pickle

import numpy as np
import pytest
from scipy import integrate

from roughcontact import ElasticHalfSpace, solve_contact
from roughcontact.body import BOTTOMS, love_pixel_displacement
from surfaces import Grid, self_affine

E_STAR = 2.0e6


@pytest.mark.parametrize("backend", ["pyfftw", "scipy"])
def test_periodic_cosine_pressure_gives_exact_displacement(backend):
    """p = p0 cos(q·x) → u = 2 p0 cos(q·x)/(E* |q|) (Johnson 1985 §2; references §4), exact on the grid."""
    grid = Grid((32, 24), (2e-3, 1.5e-3), periodic=True)
    x, y = grid.meshgrid()
    qx, qy = 2 * np.pi * 3 / grid.lengths[0], 2 * np.pi * 2 / grid.lengths[1]
    pressure = 1e3 * np.cos(qx * x + qy * y)
    u = ElasticHalfSpace(grid, E_star=E_STAR, backend=backend).displacement(pressure)
    expected = 2 * pressure / (E_STAR * np.hypot(qx, qy))
    np.testing.assert_allclose(u, expected, rtol=0, atol=1e-12 * np.abs(expected).max())


def test_profile_is_plane_strain_and_uniform_pressure_gives_zero_mean():
    grid = Grid((64, 1), (1e-3, 1e-3 / 64), periodic=True)
    x = grid.coordinates()[0][:, None]
    q = 2 * np.pi * 5 / grid.lengths[0]
    half = ElasticHalfSpace(grid, E_star=E_STAR)
    u = half.displacement(500.0 + 1e3 * np.sin(q * x))
    np.testing.assert_allclose(u, 2e3 * np.sin(q * x) / (E_STAR * q), atol=1e-12 * 2e3 / (E_STAR * q))


@pytest.mark.parametrize("x, y", [(0.0, 0.0), (1.0e-6, 0.6e-6), (3.2e-6, -2.1e-6), (0.5e-6, 0.3e-6),
                                  (40e-6, 25e-6)])
def test_love_pixel_coefficient_matches_quadrature(x, y):
    """Closed form vs numerical ∫∫ dA'/(π E* r) over the pixel (1e-9: quadrature accuracy)."""
    dx, dy = 1.0e-6, 0.6e-6
    expected = 0.0
    # split the pixel at the field point so the 1/r singularity sits on a corner (integrable, accurate)
    xs = sorted({-dx / 2, dx / 2, min(max(x, -dx / 2), dx / 2)})
    ys = sorted({-dy / 2, dy / 2, min(max(y, -dy / 2), dy / 2)})
    for x0, x1 in zip(xs[:-1], xs[1:]):
        for y0, y1 in zip(ys[:-1], ys[1:]):
            expected += integrate.dblquad(lambda b, a: 1 / np.hypot(a - x, b - y), x0, x1, y0, y1,
                                          epsabs=0, epsrel=1e-12)[0]
    expected /= np.pi * E_STAR
    assert love_pixel_displacement(x, y, dx, dy, E_STAR) == pytest.approx(expected, rel=1e-9)


def test_free_surface_is_the_linear_convolution():
    """Zero-padded FFT = direct summation of Love coefficients (odd, non-square grid)."""
    grid = Grid((7, 5), (7e-6, 4e-6), periodic=False)
    dx, dy = grid.spacing
    pressure = np.random.default_rng(0).random(grid.shape) * 1e4
    i, j = np.indices(grid.shape)
    direct = np.zeros(grid.shape)
    for a, b in np.ndindex(grid.shape):
        direct += pressure[a, b] * love_pixel_displacement((i - a) * dx, (j - b) * dy, dx, dy, E_STAR)
    u = ElasticHalfSpace(grid, E_star=E_STAR).displacement(pressure)
    np.testing.assert_allclose(u, direct, rtol=1e-12)


def test_free_surface_uniform_disc_centre_displacement():
    """Uniform p on a disc of radius a: u(0) = 2 p a / E* (Johnson 1985, Eq. 3.27).

    The pixelated disc (radius 32 px) differs from the circle only at its rim; measured error 0.1 %, so 0.5 %.
    """
    n, radius = 96, 32
    grid = Grid((n, n), (n * 1e-6, n * 1e-6), periodic=False)
    i, j = np.indices(grid.shape)
    inside = np.hypot(i - n // 2, j - n // 2) <= radius
    u = ElasticHalfSpace(grid, E_star=E_STAR).displacement(np.where(inside, 1e3, 0.0))
    assert u[n // 2, n // 2] == pytest.approx(2 * 1e3 * radius * 1e-6 / E_STAR, rel=5e-3)


def test_backends_and_precisions_agree():
    for periodic in (True, False):
        grid = Grid((20, 12), (2e-5, 1.2e-5), periodic=periodic)
        pressure = np.random.default_rng(5).random(grid.shape) * 1e4
        reference = ElasticHalfSpace(grid, E_star=E_STAR, backend="scipy").displacement(pressure)
        fftw = ElasticHalfSpace(grid, E_star=E_STAR, threads=2).displacement(pressure)
        single = ElasticHalfSpace(grid, E_star=E_STAR, dtype=np.float32).displacement(pressure)
        scale = np.abs(reference).max()
        # measured 7.4e-16 (FFTW vs pocketfft) and 2.6e-7 (float32, eps 6e-8 over two transforms) of the
        # largest displacement; bounds with a margin of 7 and 2
        np.testing.assert_allclose(fftw, reference, rtol=0, atol=5e-15 * scale)
        assert single.dtype == np.float32
        np.testing.assert_allclose(single, reference, rtol=0, atol=5e-7 * scale)


def test_elastic_energy_equals_fourier_space_energy():
    """½ ∫ p u dA = ½ A Σ_q Φ(q) |p̂_q|², p̂ = fft2(p)/N, Φ = 2/(E* q) (Parseval)."""
    grid = Grid((16, 10), (1e-3, 0.7e-3), periodic=True)
    pressure = np.random.default_rng(6).random(grid.shape) * 1e4
    half = ElasticHalfSpace(grid, E_star=E_STAR)
    q = grid.wavevector_magnitude()
    power = np.abs(np.fft.fft2(pressure) / pressure.size) ** 2
    fourier = 0.5 * grid.area * np.sum(np.divide(2 * power, E_STAR * q, out=np.zeros_like(q), where=q > 0))
    assert half.elastic_energy(pressure, half.displacement(pressure)) == pytest.approx(fourier, rel=1e-12)


def test_displacement_into_and_pickle():
    grid = Grid((16, 16), (1e-3, 1e-3), periodic=False)
    half = ElasticHalfSpace(grid, E_star=E_STAR, backend="scipy")
    pressure = np.random.default_rng(7).random(grid.shape)
    out = half.empty()
    assert half.displacement_into(pressure, out) is out
    clone = pickle.loads(pickle.dumps(half))
    assert clone.E_star == half.E_star and clone.grid == grid and clone.backend == "scipy"
    np.testing.assert_array_equal(clone.displacement(pressure), out)
    np.testing.assert_array_equal(half.displacement(pressure), out)   # padding re-zeroed between calls


@pytest.mark.parametrize("grid, kwargs, exc, word", [
    (Grid((8, 8), (1.0, 1.0)), {"E_star": 0.0}, ValueError, "E_star"),
    (Grid((8, 8), (1.0, 1.0)), {"E_star": -1.0}, ValueError, "E_star"),
    (Grid((8, 8), (1.0, 1.0)), {"E_star": float("nan")}, ValueError, "E_star"),
    (Grid((8, 8), (1.0, 1.0), periodic=(True, False)), {"E_star": 1.0}, ValueError, "mixed periodicity"),
    (Grid((8, 1), (1.0, 1.0), periodic=False), {"E_star": 1.0}, ValueError, "profile"),
    (Grid((8, 8), (1.0, 1.0)), {"E_star": 1.0, "poisson": 0.3}, ValueError, "thickness"),
    (Grid((8, 8), (1.0, 1.0)), {"E_star": 1.0, "thickness": 1e-3, "poisson": 0.7}, ValueError, "poisson"),
    (Grid((8, 8), (1.0, 1.0)), {"E_star": 1.0, "thickness": 1e-3, "poisson": 0.3, "bottom": "glued"},
     ValueError, "bottom"),
    (Grid((8, 8), (1.0, 1.0)), {"E_star": 1.0, "backend": "numpy"}, ValueError, "backend"),
])
def test_bad_input(grid, kwargs, exc, word):
    with pytest.raises(exc, match=word):
        ElasticHalfSpace(grid, **kwargs)


def test_grid_type_and_pressure_shape():
    with pytest.raises(TypeError, match="grid"):
        ElasticHalfSpace((8, 8), E_star=1.0)
    half = ElasticHalfSpace(Grid((8, 8), (1.0, 1.0)), E_star=1.0)
    with pytest.raises(ValueError, match="shape"):
        half.displacement(np.zeros((8, 4)))
    with pytest.raises(ValueError, match="pressure"):
        half.displacement(np.full((8, 8), np.nan))
    with pytest.raises(TypeError, match="complex"):
        half.displacement(np.zeros((8, 8), complex))
    with pytest.raises(ValueError, match=r"pressure has shape \(8, 4\), but grid.shape is \(8, 8\)"):
        half.displacement_into(np.zeros((8, 4)), half.empty())
    with pytest.raises(ValueError, match=r"out has shape \(64,\), but grid.shape is \(8, 8\)"):
        half.displacement_into(np.zeros((8, 8)), np.zeros(64))


@pytest.mark.parametrize("grid, kwargs", [
    (Grid((32, 24), (1e-3, 0.7e-3)), {}),
    (Grid((31, 20), (1e-3, 0.7e-3)), {"backend": "scipy"}),
    (Grid((64, 1), (1e-3, 1e-3)), {}),
    (Grid((24, 17), (1e-3, 0.7e-3), periodic=False), {}),
    (Grid((24, 17), (1e-3, 0.7e-3), periodic=False), {"dtype": np.float32}),
    (Grid((32, 32), (1e-3, 1e-3)), {"thickness": 1e-4, "poisson": 0.3}),
    (Grid((24, 17), (1e-3, 0.7e-3), periodic=False), {"thickness": 1e-4, "poisson": 0.3}),
])
def test_pixel_compliance_is_the_diagonal_of_K(grid, kwargs):
    """The displacement of a pixel under unit pressure on it alone: against K applied to the unit impulse
    (measured: equal to 2e-16, float32 to 1e-7), against Love's coefficient on a free surface (same) and
    against (1/N) Σ_q Φ(q) by hand on a periodic half-space (2e-16); bounds 1e-14 (float32: 1e-6). Reading it
    between quadratic_form and pending_displacement_into does no transform and keeps the pending K p."""
    half = ElasticHalfSpace(grid, E_star=E_STAR, **kwargs)
    rtol = 1e-6 if half.dtype == np.float32 else 1e-14
    unit = np.zeros(grid.shape)
    unit[0, 0] = 1.0
    assert half.pixel_compliance == pytest.approx(float(half.displacement(unit)[0, 0]), rel=rtol)
    if not half.periodic and not kwargs.get("thickness"):
        assert half.pixel_compliance == pytest.approx(love_pixel_displacement(0.0, 0.0, *grid.spacing, E_STAR),
                                                      rel=rtol)
    elif not kwargs.get("thickness"):
        q = grid.wavevector_magnitude()
        by_hand = np.sum(2 / (E_STAR * q[q > 0])) / grid.size
        assert half.pixel_compliance == pytest.approx(by_hand, rel=1e-14)
    pressure = np.random.default_rng(3).random(grid.shape).astype(half.dtype)
    half.quadratic_form(pressure)
    assert half.pixel_compliance > 0
    np.testing.assert_allclose(half.pending_displacement_into(half.empty()), half.displacement(pressure),
                               rtol=0, atol=rtol * np.abs(half.displacement(pressure)).max())


def test_compliance_values_and_coarsened_body():
    """compliance(q) is the multiplier the operator applies: 2/(E* q) for the half-space and the layered kernel
    for a layer; a cosine pressure gives u = Φ(q) p on the grid and on the coarsened body (its q is on both grids),
    measured to 3e-16, bound 1e-13; coarsened keeps every parameter and refuses odd pixel counts."""
    grid = Grid((32, 32), (1e-3, 1e-3))
    x, y = grid.meshgrid()
    q = 2 * np.pi * 3 / grid.lengths[0]
    pressure = 1e3 * np.cos(q * x)
    for layer in ({}, {"thickness": 1e-4, "poisson": 0.3, "bottom": "frictionless"},
                  {"thickness": 2e-4, "poisson": 0.3, "substrate_E_star": 2e4, "substrate_poisson": 0.49}):
        half = ElasticHalfSpace(grid, E_star=E_STAR, dtype=np.float64, backend="scipy", **layer)
        if not layer:
            assert half.compliance(q) == 2 / (E_STAR * q)
        else:
            assert half.compliance([q])[0] != pytest.approx(2 / (E_STAR * q), rel=1e-2)     # the layer matters
        coarse = half.coarsened()
        assert coarse.grid == grid.coarsened(2) and coarse.layer == half.layer and coarse.backend == "scipy"
        for body, p in ((half, pressure), (coarse, pressure[::2, ::2])):
            np.testing.assert_allclose(body.displacement(p), body.compliance(q) * p, rtol=0,
                                       atol=1e-13 * np.abs(body.compliance(q) * p).max())
    with pytest.raises(ValueError, match="multiple"):
        ElasticHalfSpace(Grid((31, 32), (1e-3, 1e-3)), E_star=E_STAR).coarsened()


@pytest.mark.parametrize("thickness", [1e6, 1e9, 1e30])
def test_layer_much_thicker_than_the_window_is_the_half_space(thickness):
    """docs/guide/layered.md, "A layer much thicker than the window": every q > 0 mode is the half-space's to
    round-off (q t > 25 here) and the rigid base's column t/M (> 6.7e7 times the compliance of the longest
    wavelength) takes the half-space convention ⟨u⟩ = 0, so the operator is the half-space's bit for bit and a
    contact solve gives the half-space answer (before: 0-step 'converged' full contact at 1e30 m, no convergence at
    1e6 and 1e9 m). A 10 m layer keeps its column."""
    grid = Grid((32, 32), (1e-3, 1e-3))
    half = ElasticHalfSpace(grid, E_star=E_STAR)
    for bottom in BOTTOMS:
        thick = ElasticHalfSpace(grid, E_star=E_STAR, thickness=thickness, poisson=0.3, bottom=bottom)
        assert thick.layer["uniform_mode"] == "half-space" and thick.uniform_compliance == 0.0
        pressure = np.random.default_rng(4).random(grid.shape) * 1e3
        np.testing.assert_array_equal(thick.displacement(pressure), half.displacement(pressure))
        assert thick.compliance([2 * np.pi / 1e-3, 1e10])[1] == 2 / (E_STAR * 1e10)
    on_substrate = ElasticHalfSpace(grid, E_star=E_STAR, thickness=thickness, poisson=0.3, substrate_E_star=1e3,
                                    substrate_poisson=0.49)
    np.testing.assert_array_equal(on_substrate.displacement(pressure), half.displacement(pressure))
    heights = self_affine(grid, hurst=0.8, rms_slope=0.1, short_cutoff=grid.lengths[0] / 8, rng=1)
    solved = [solve_contact(heights, body, mean_pressure=0.01 * E_STAR) for body in (half, thick)]
    assert solved[1].converged and solved[1].iterations == solved[0].iterations
    np.testing.assert_array_equal(solved[1].pressure, solved[0].pressure)
    kept = ElasticHalfSpace(grid, E_star=E_STAR, thickness=10.0, poisson=0.3)
    assert kept.layer["uniform_mode"] == "column" and kept.uniform_compliance > 0


def test_layered_limits_equal_half_space_results():
    """Thick layer → half-space of the layer; thin stiff layer on a soft half-space → the substrate."""
    grid = Grid((32, 32), (1e-3, 1e-3), periodic=True)
    pressure = np.random.default_rng(8).random(grid.shape) * 1e3
    layer_E, substrate_E = 5e6, 5e4
    half_layer = ElasticHalfSpace(grid, E_star=layer_E).displacement(pressure)
    half_substrate = ElasticHalfSpace(grid, E_star=substrate_E).displacement(pressure)
    thick = ElasticHalfSpace(grid, E_star=layer_E, thickness=1.0, poisson=0.3).displacement(pressure)
    thick_on_soft = ElasticHalfSpace(grid, E_star=layer_E, thickness=1.0, poisson=0.3,
                                     substrate_E_star=substrate_E, substrate_poisson=0.49).displacement(pressure)
    thin_on_soft = ElasticHalfSpace(grid, E_star=layer_E, thickness=1e-9, poisson=0.3,
                                    substrate_E_star=substrate_E, substrate_poisson=0.49).displacement(pressure)
    # the thick layer (1 m ≫ 1 mm wavelengths) differs from the half-space by e^{-2qt} = 0 plus the uniform
    # compression of the layer on a rigid base (its q = 0 mode) — compare the fluctuating parts. Measured
    # (of the largest displacement): 5.3e-12 on the rigid base (round-off of subtracting the column, ~1e4 times
    # the fluctuation), 1.5e-17 on the soft substrate (round-off); the thin layer differs physically, by
    # O(q t E*/E0*) = 2.7e-6. Bounds: margin 10 (4 on the thin layer).
    for u, reference, bound in ((thick, half_layer, 5e-11), (thick_on_soft, half_layer, 1e-15),
                                (thin_on_soft, half_substrate, 1e-5)):
        np.testing.assert_allclose(u - u.mean(), reference, rtol=0, atol=bound * np.abs(reference).max())


@pytest.mark.parametrize("periodic", [True, False])
def test_stiffness_inverts_the_displacement(periodic):
    """K⁻¹ K p = p: exactly on a periodic grid (up to the mean, which K maps to zero); on a free surface the
    inverse of the padded operator is not the inverse on the window, so only the window's interior is close."""
    grid = Grid((24, 16), (1e-3, 0.7e-3), periodic=periodic)
    pressure = np.random.default_rng(9).random(grid.shape) * 1e4
    half = ElasticHalfSpace(grid, E_star=E_STAR)
    recovered = half.stiffness_into(half.displacement(pressure), half.empty())
    if periodic:
        np.testing.assert_allclose(recovered, pressure - pressure.mean(), rtol=0, atol=1e-9 * pressure.max())
    else:
        interior = (slice(4, -4), slice(4, -4))    # measured correlation 0.996 here, 0.38 over the window
        assert np.corrcoef(recovered[interior].ravel(), pressure[interior].ravel())[0, 1] > 0.99


@pytest.mark.parametrize("bottom", ["bonded", "frictionless"])
@pytest.mark.parametrize("poisson", [0.3, 0.5])
def test_layer_on_rigid_base_uniform_compression(bottom, poisson):
    """A uniform pressure on a periodic layer on a rigid base compresses it in uniaxial strain:
    ⟨u⟩ = p t/M, M = E(1 − ν)/((1 + ν)(1 − 2ν)) = E*(1 − ν)²/(1 − 2ν) (0 for ν = 0.5), for either bottom."""
    grid = Grid((16, 16), (1e-3, 1e-3), periodic=True)
    thickness, pressure = 1e-4, 1e3
    young = E_STAR * (1 - poisson ** 2)
    constrained = young * (1 - poisson) / ((1 + poisson) * (1 - 2 * poisson)) if poisson < 0.5 else np.inf
    half = ElasticHalfSpace(grid, E_star=E_STAR, thickness=thickness, poisson=poisson, bottom=bottom)
    u = half.displacement(np.full(grid.shape, pressure))
    np.testing.assert_allclose(u, pressure * thickness / constrained, rtol=1e-12, atol=1e-25)


@pytest.mark.parametrize("shape, periodic, layer, backend", [
    ((32, 24), True, {}, "pyfftw"),
    ((33, 25), True, {}, "scipy"),                                     # odd last axis: no Nyquist column
    ((64, 1), True, {}, "pyfftw"),                                     # plane-strain profile
    ((24, 17), False, {}, "pyfftw"),                                   # free surface: 48 × 34 padded transform
    ((32, 32), True, {"thickness": 1e-4, "poisson": 0.3}, "pyfftw"),   # Φ(0) > 0 on a rigid base
    ((24, 17), False, {"thickness": 1e-4, "poisson": 0.3}, "scipy"),   # free-surface layered kernel
])
def test_quadratic_form_is_parseval_of_the_convolution(shape, periodic, layer, backend):
    """⟨p, K p⟩ from the forward transform alone (Parseval, half-spectrum columns weighted 1 or 2) equals the
    real-space Σ p (K p), and the pending backward transform completes K p. 1e-12: round-off of two FFTs."""
    grid = Grid(shape, (1e-3, 1e-3 * shape[1] / shape[0]), periodic=periodic)
    half = ElasticHalfSpace(grid, E_star=E_STAR, backend=backend, **layer)
    pressure = np.random.default_rng(4).random(shape) * 1e4              # nonzero mean: the q = 0 mode counts
    displacement = half.displacement(pressure)
    expected = float(np.sum(pressure * displacement))
    assert half.quadratic_form(pressure.copy()) == pytest.approx(expected, rel=1e-12)
    pending = half.pending_displacement_into(np.empty(shape))
    np.testing.assert_allclose(pending, displacement, rtol=0, atol=1e-12 * np.abs(displacement).max())
    with pytest.raises(RuntimeError, match="quadratic_form"):           # consumed: nothing pending any more
        half.pending_displacement_into(np.empty(shape))
    half.quadratic_form(pressure)
    half.displacement(pressure)                                           # another transform discards it
    with pytest.raises(RuntimeError, match="quadratic_form"):
        half.pending_displacement_into(np.empty(shape))


def test_displacement_into_refuses_non_finite_pressure():
    half = ElasticHalfSpace(Grid((8, 8), (1e-3, 1e-3), periodic=True), E_star=1e6)
    pressure = half.empty()
    pressure[...] = 1.0
    pressure[2, 3] = np.nan
    with pytest.raises(ValueError, match="pressure must be finite"):
        half.displacement_into(pressure, half.empty())


@pytest.mark.parametrize("layer, backend", [({}, "pyfftw"), ({"thickness": 1e-4, "poisson": 0.3}, "scipy")])
def test_padded_operator_is_the_free_surface_on_its_padded_grid(layer, backend):
    """The free surface's padded operator K_T: a traction on the window alone gives the window the free surface's
    displacement K p (the padded convolution is the linear one) and the padding the rest of the linear
    convolution; K_T⁻¹ inverts it exactly on the whole padded grid (the window's own inverse does not, see
    test_stiffness_inverts_the_displacement); Φ_T(0) is the padded grid's response to a uniform traction; the
    largest Φ_T(q) bounds every mode. 1e-12: round-off of two FFTs."""
    grid = Grid((24, 17), (1e-3, 0.7e-3), periodic=False)
    half = ElasticHalfSpace(grid, E_star=E_STAR, backend=backend, **layer)
    padded = half.padded_operator()
    assert padded.shape == half.transform_shape and padded.dtype == half.dtype
    pressure = np.random.default_rng(5).random(grid.shape) * 1e4
    traction = padded.empty()
    traction[...] = 0.0
    traction[:24, :17] = pressure
    displacement = padded.displacement_into(traction, padded.empty())
    expected = half.displacement(pressure)
    scale = np.abs(expected).max()
    np.testing.assert_allclose(displacement[:24, :17], expected, rtol=0, atol=1e-12 * scale)
    assert np.abs(displacement[24:, :]).max() > 1e-3 * scale           # the padding moves: it is not the window
    recovered = padded.stiffness_into(displacement, padded.empty())
    np.testing.assert_allclose(recovered, traction, rtol=0, atol=1e-9 * pressure.max())
    uniform = padded.empty()
    uniform[...] = 1e3
    np.testing.assert_allclose(padded.displacement_into(uniform, padded.empty()), 1e3 * padded.uniform_compliance,
                               rtol=1e-12)
    assert padded.uniform_compliance > 0 and padded.largest_compliance >= padded.uniform_compliance
    assert padded.pixel_compliance == half.pixel_compliance


def test_padded_operator_refuses_a_periodic_body_and_bad_arrays():
    with pytest.raises(ValueError, match="periodic"):
        ElasticHalfSpace(Grid((8, 8), (1e-3, 1e-3), periodic=True), E_star=1e6).padded_operator()
    padded = ElasticHalfSpace(Grid((8, 8), (1e-3, 1e-3), periodic=False), E_star=1e6).padded_operator()
    with pytest.raises(ValueError, match=r"pressure has shape \(8, 8\), but the transform grid's shape is \(16, 16\)"):
        padded.displacement_into(np.zeros((8, 8)), padded.empty())
    pressure = np.zeros(padded.shape)
    pressure[3, 3] = np.inf
    with pytest.raises(ValueError, match="pressure must be finite"):
        padded.displacement_into(pressure, padded.empty())
