"""Layered compliances Φ(q) against an independent numerical solution of the plane-strain boundary-value
problem per Fourier mode, and against their thin/thick-layer limits; the free-surface (real-space) layered
kernel against an independent Fourier-space construction, its thick-layer limit and Hertz."""
import numpy as np
import pytest
from scipy import integrate, signal

from roughcontact import ElasticHalfSpace, solve_contact
from roughcontact import reference as ref
from roughcontact.body import love_pixel_displacement
from roughcontact.body import (THICK_X, free_surface_correction, layer_on_half_space_compliance,
                               layer_on_rigid_base_compliance)
from surfaces import Grid, HeightField


# ---------------------------------------------------------------------------------------------------------
# Independent reference: general solution of Navier's equations for u_x = U(z) sin(qx), u_z = W(z) cos(qx)
# (q = 1 after scaling lengths by 1/q), four constants per layer; tractions from Hooke's law with λ and G;
# boundary and interface conditions assembled into a linear system and solved with numpy.linalg.solve.
# ---------------------------------------------------------------------------------------------------------

def general_solution(z, coeffs, G, nu, z_top, z_bottom):
    """U, W, σ_zz, σ_xz at depth z for coefficients (A, B) of the decaying and (C, D) of the growing part.

    Decaying part referenced at z_top, growing part at z_bottom (keeps the system well conditioned).
    """
    A, B, C, D = coeffs
    kappa = 3 - 4 * nu
    lam = 2 * G * nu / (1 - 2 * nu)
    zd, zg = z - z_top, z - z_bottom
    ed, eg = np.exp(-zd), np.exp(zg)
    U = (A + B * zd) * ed + (C + D * zg) * eg
    W = (A + kappa * B + B * zd) * ed + (-C + kappa * D - D * zg) * eg
    dU = (B - A - B * zd) * ed + (D + C + D * zg) * eg
    dW = (B - A - kappa * B - B * zd) * ed + (-D - C + kappa * D - D * zg) * eg
    # q = 1: div u = U + W',  σ_zz = λ div u + 2G W',  σ_xz = G (U' − W)   (times cos / sin)
    return np.array([U, W, lam * (U + dW) + 2 * G * dW, G * (dU - W)])


def rows(z, G, nu, z_top, z_bottom):
    """4×4 matrix: (U, W, σ_zz, σ_xz) at z as linear functions of the four coefficients."""
    return np.column_stack([general_solution(z, unit, G, nu, z_top, z_bottom) for unit in np.eye(4)])


def numerical_ratio_rigid(X, nu, bottom):
    """Φ E* q / 2 for a layer 0 < z < X on a rigid base; surface pressure cos(x) (σ_zz(0) = −1)."""
    G = 1.0
    top, bot = rows(0.0, G, nu, 0.0, X), rows(X, G, nu, 0.0, X)
    keep = [0, 1] if bottom == "bonded" else [1, 3]          # U = W = 0, or W = σ_xz = 0
    matrix = np.vstack([top[2:4], bot[keep]])
    coeffs = np.linalg.solve(matrix, [-1.0, 0.0, 0.0, 0.0])
    W0 = top[1] @ coeffs
    E_star = 2 * G / (1 - nu)
    return W0 * E_star / 2


def numerical_ratio_half_space(X, nu, substrate_ratio, nu0):
    """Φ E* q / 2 for a layer (G = 1) on a half-space (G0 = substrate_ratio): 8×8 system, the growing
    constants of the substrate set to zero (boundedness at depth)."""
    G, G0 = 1.0, substrate_ratio
    top, bot = rows(0.0, G, nu, 0.0, X), rows(X, G, nu, 0.0, X)
    sub = rows(X, G0, nu0, X, 2 * X)
    matrix = np.zeros((8, 8))
    rhs = np.zeros(8)
    matrix[0:2, 0:4], rhs[0] = top[2:4], -1.0                 # σ_zz(0) = −cos, σ_xz(0) = 0
    matrix[2:6, 0:4], matrix[2:6, 4:8] = bot, -sub            # continuity of U, W, σ_zz, σ_xz at z = X
    matrix[6, 6] = matrix[7, 7] = 1.0                         # no growing part in the half-space
    coeffs = np.linalg.solve(matrix, rhs)
    E_star = 2 * G / (1 - nu)
    return top[1] @ coeffs[:4] * E_star / 2


def test_general_solution_satisfies_navier():
    # central differences of the reference fields: G(U'' − U) − (λ+G)(U + W') = 0 and
    # G(W'' − W) + (λ+G)(U' + W'') = 0 (q = 1); h = 1e-4 gives O(h²) ≈ 1e-8 truncation.
    rng = np.random.default_rng(0)
    G, nu, h = 1.7, 0.27, 1e-4
    lam = 2 * G * nu / (1 - 2 * nu)
    coeffs = rng.normal(size=4)
    z = np.array([0.1, 0.4, 0.9])
    U = lambda z: general_solution(z, coeffs, G, nu, 0.0, 1.0)[0]
    W = lambda z: general_solution(z, coeffs, G, nu, 0.0, 1.0)[1]
    d1 = lambda f: (f(z + h) - f(z - h)) / (2 * h)
    d2 = lambda f: (f(z + h) - 2 * f(z) + f(z - h)) / h**2
    scale = np.abs(U(z)).max() + np.abs(W(z)).max()
    assert np.abs(G * (d2(U) - U(z)) - (lam + G) * (U(z) + d1(W))).max() < 1e-6 * scale
    assert np.abs(G * (d2(W) - W(z)) + (lam + G) * (d1(U) + d2(W))).max() < 1e-6 * scale


CASES_RIGID = [(X, nu) for X in (0.03, 0.4, 1.0, 3.5) for nu in (-0.4, 0.0, 0.3, 0.49)]


@pytest.mark.parametrize("bottom", ["bonded", "frictionless"])
@pytest.mark.parametrize("X, nu", CASES_RIGID)
def test_rigid_base_matches_boundary_value_problem(X, nu, bottom):
    # closed form vs 4×4 solve: both exact, differences are round-off (condition number < 1e3) -> 1e-10
    E_star, t = 3e6, 2e-4
    q = X / t
    ratio = layer_on_rigid_base_compliance(q, E_star, nu, t, bottom=bottom) * E_star * q / 2
    assert ratio == pytest.approx(numerical_ratio_rigid(X, nu, bottom), rel=1e-10)


CASES_HALF = [(0.05, 0.3, 1e-3, 0.49), (0.5, 0.45, 0.01, 0.3), (1.2, 0.2, 3.0, 0.4), (2.5, -0.3, 0.2, 0.0),
              (0.3, 0.49, 50.0, 0.1), (4.0, 0.35, 1e-2, 0.45)]


@pytest.mark.parametrize("X, nu, shear_ratio, nu0", CASES_HALF)
def test_half_space_matches_boundary_value_problem(X, nu, shear_ratio, nu0):
    # closed form vs 8×8 solve, relative 1e-10 (round-off only). shear_ratio = G0/G, with E* = 2G/(1−ν).
    t, G = 1e-4, 5e6
    E_star, E0_star = 2 * G / (1 - nu), 2 * G * shear_ratio / (1 - nu0)
    q = X / t
    ratio = layer_on_half_space_compliance(q, E_star, nu, t, E0_star, nu0) * E_star * q / 2
    assert ratio == pytest.approx(numerical_ratio_half_space(X, nu, shear_ratio, nu0), rel=1e-10)


def test_half_space_equal_materials_is_half_space_for_any_thickness():
    q = np.geomspace(1e1, 1e8, 50)
    for t in (1e-9, 1e-5, 1.0):
        phi = layer_on_half_space_compliance(q, 2e6, 0.4, t, 2e6, 0.4)
        np.testing.assert_allclose(phi, 2 / (2e6 * q), rtol=1e-14)


def test_half_space_thin_and_thick_limits():
    # stiff stratum corneum (E* 20 MPa) on soft viable skin (0.1 MPa): q t = 1e-9 and 40 are within
    # 1e-8 of the limits (corrections ∝ q t and ∝ e^{-2qt}·(qt)²)
    t, E, E0 = 3e-4, 2e7, 1e5
    q_thin, q_thick = 1e-9 / t, 40 / t
    assert layer_on_half_space_compliance(q_thin, E, 0.45, t, E0, 0.49) == pytest.approx(2 / (E0 * q_thin), rel=1e-7)
    assert layer_on_half_space_compliance(q_thick, E, 0.45, t, E0, 0.49) == pytest.approx(2 / (E * q_thick), rel=1e-12)
    # and the other way round (soft layer on stiff substrate)
    assert layer_on_half_space_compliance(q_thin, E0, 0.3, t, E, 0.2) == pytest.approx(2 / (E * q_thin), rel=1e-7)


def test_rigid_base_limits():
    t, E_star = 1e-3, 1e6
    for nu in (-0.5, 0.0, 0.3, 0.5):
        # q -> 0: uniaxial-strain column t(1−2ν)/(E*(1−ν)²) = t/M (bonded); t/E* (frictionless)
        column = t * (1 - 2 * nu) / (E_star * (1 - nu) ** 2)
        phi0 = layer_on_rigid_base_compliance(np.array([0.0, 1e-8 / t]), E_star, nu, t)
        np.testing.assert_allclose(phi0, column, rtol=1e-7, atol=1e-15 * t / E_star)   # ν = 0.5: column 0
        phi0 = layer_on_rigid_base_compliance(np.array([0.0, 1e-8 / t]), E_star, nu, t, bottom="frictionless")
        np.testing.assert_allclose(phi0, t / E_star, rtol=1e-7)
        for bottom in ("bonded", "frictionless"):
            q = 40 / t       # thick: half-space, corrections ∝ (qt)² e^{-2qt} ~ 1e-32
            assert layer_on_rigid_base_compliance(q, E_star, nu, t, bottom=bottom) == pytest.approx(
                2 / (E_star * q), rel=1e-13)


@pytest.mark.parametrize("nu", [-0.5, 0.0, 0.3, 0.49, 0.5])
def test_bonded_layer_small_qt_series(nu):
    # R = Φ E* q/2 = (1−2ν)/(2(1−ν)²) X + ν(4ν−1)/(6(1−ν)³) X³ + O(X⁴), X = q t (series of Eq. L1, from the
    # 4×4 solution by computer algebra). At ν = 0.5 the column term vanishes and R = 2X³/3: only a
    # cancellation-free form gets this at X = 1e-6 (the naive sinh/cosh form loses every digit).
    for X in (1e-6, 1e-3):
        series = (1 - 2 * nu) / (2 * (1 - nu) ** 2) * X + nu * (4 * nu - 1) / (6 * (1 - nu) ** 3) * X**3
        ratio = layer_on_rigid_base_compliance(X, 1.0, nu, 1.0) * X / 2
        assert ratio == pytest.approx(series, rel=1e-5, abs=1e-12 * X**3)


def test_stable_at_extreme_qt():
    # q t = 1e-8 (series regime), 1e3 (e^{-2qt} underflows to 0: exactly the layer half-space), 1e300
    q = np.array([1e-8, 1e3, 1e300])
    for phi, E_layer in ((layer_on_rigid_base_compliance(q, 1e6, 0.3, 1.0), 1e6),
                         (layer_on_rigid_base_compliance(q, 1e6, 0.5, 1.0, bottom="frictionless"), 1e6),
                         (layer_on_half_space_compliance(q, 1e7, 0.45, 1.0, 1e5, 0.49), 1e7),
                         (layer_on_half_space_compliance(q, 1e5, 0.45, 1.0, 1e7, 0.49), 1e5)):
        assert np.isfinite(phi).all() and (phi > 0).all()
        np.testing.assert_allclose(phi[1:], 2 / (E_layer * q[1:]), rtol=1e-15)
    assert layer_on_half_space_compliance(0.0, 1e7, 0.45, 1.0, 1e5, 0.49) == np.inf


@pytest.mark.parametrize("thickness", [1e6, 1e9, 1e30, 1e300])
def test_thick_layer_is_exactly_the_half_space(thickness):
    """Beyond q t = THICK_X = 25 every kernel returns 2/(E* q) itself (docs/guide/layered.md), also where q t overflows
    (1e300 m × 1e10 rad/m was NaN); just below it the formula agrees to round-off (measured 1.1e-15, bound 4e-15)."""
    q = np.array([1e2, 1e4, 1e10])
    for phi in (layer_on_rigid_base_compliance(q, 1e6, 0.3, thickness),
                layer_on_rigid_base_compliance(q, 1e6, 0.3, thickness, bottom="frictionless"),
                layer_on_half_space_compliance(q, 1e6, 0.3, thickness, 1e3, 0.49)):
        np.testing.assert_array_equal(phi, 2 / (1e6 * q))
    below = THICK_X * (1 - 1e-9)
    for phi in (layer_on_rigid_base_compliance(1.0, 1.0, 0.3, below),
                layer_on_half_space_compliance(1.0, 1.0, 0.3, below, 1e-3, 0.49)):
        assert phi == pytest.approx(2.0, rel=4e-15)


@pytest.mark.parametrize("kernel", ["bonded", "frictionless", "stiff layer", "soft layer"])
def test_compliance_increases_with_thickness(kernel):
    # thicker soft material (or thinner stiff skin) => more compliant, at every q (up to 4 ulp once
    # e^{-2qt} has underflowed and Φ is the layer's half-space value)
    q = np.geomspace(1e2, 1e6, 30)
    thickness = np.geomspace(1e-7, 1e-1, 25)
    if kernel in ("bonded", "frictionless"):
        phi = [layer_on_rigid_base_compliance(q, 1e6, 0.4, t, bottom=kernel) for t in thickness]
        sign = 1
    elif kernel == "stiff layer":
        phi = [layer_on_half_space_compliance(q, 1e7, 0.45, t, 1e5, 0.49) for t in thickness]
        sign = -1
    else:
        phi = [layer_on_half_space_compliance(q, 1e5, 0.45, t, 1e7, 0.49) for t in thickness]
        sign = 1
    phi = np.array(phi)
    assert (sign * np.diff(phi, axis=0) >= -4 * np.finfo(float).eps * phi[1:]).all()


@pytest.mark.parametrize("kwargs, name", [
    (dict(E_star=0.0), "E_star"), (dict(poisson=0.51), "poisson"), (dict(poisson=-1.0), "poisson"),
    (dict(thickness=-1e-3), "thickness"), (dict(q=np.array([1.0, np.nan])), "q"), (dict(q=-1.0), "q"),
])
def test_invalid_input_names_parameter(kwargs, name):
    args = dict(q=1.0, E_star=1e6, poisson=0.3, thickness=1e-3) | kwargs
    with pytest.raises(ValueError, match=name):
        layer_on_rigid_base_compliance(**args)
    with pytest.raises(ValueError, match="bottom"):
        layer_on_rigid_base_compliance(1.0, 1e6, 0.3, 1e-3, bottom="glued")
    with pytest.raises(ValueError, match="substrate_E_star"):
        layer_on_half_space_compliance(1.0, 1e6, 0.3, 1e-3, -1.0, 0.3)
    with pytest.raises(ValueError, match="substrate_poisson"):
        layer_on_half_space_compliance(1.0, 1e6, 0.3, 1e-3, 1e5, 0.6)


# ---------------------------------------------------------------------------------------------------------
# Free surface: the real-space influence coefficients (docs/guide/layered.md, "The free-surface kernel")
# ---------------------------------------------------------------------------------------------------------
FREE_LAYERS = {   # (Φ, layer E*, b = lim q ΔΦ): a 40 µm layer on 10 µm pixels
    "stiff on soft": (lambda q: layer_on_half_space_compliance(q, 1e7, 0.5, 4e-5, 5e4, 0.5), 1e7, 2 / 5e4 - 2 / 1e7),
    "rigid bonded": (lambda q: layer_on_rigid_base_compliance(q, 1e7, 0.3, 4e-5), 1e7, -2 / 1e7),
}


def periodic_pixel_correction(compliance, E_star, size, dx):
    """The multiplier of ΔΦ = Φ − 2/(E* q) for pixel-uniform pressure sampled at pixel centres on a periodic
    size² grid: Σ_G ΔΦ(|q + G|) sinc(q_x dx/2) sinc(q_y dx/2) over the aliases G = 2π m/dx (|m| ≤ 1 suffice:
    ΔΦ = 0 beyond q t = 25, i.e. beyond 2π/dx here). The q = 0 mode is set to 0."""
    q1 = 2 * np.pi * np.fft.fftfreq(size, dx)
    total = np.zeros((size, size))
    for mx in (-1, 0, 1):
        for my in (-1, 0, 1):
            qx, qy = q1[:, None] + 2 * np.pi * mx / dx, q1[None, :] + 2 * np.pi * my / dx
            q = np.hypot(qx, qy)
            safe = np.where(q > 0, q, 1.0)
            excess = np.where(q > 0, compliance(safe) - 2 / (E_star * safe), 0.0)
            total += excess * np.sinc(qx * dx / (2 * np.pi)) * np.sinc(qy * dx / (2 * np.pi))
    return total


@pytest.mark.parametrize("layer", FREE_LAYERS)
def test_free_surface_correction_is_the_periodic_one_without_images(layer):
    """The real-space correction (Hankel transform + closed form, pixel-averaged) against the periodic multiplier
    of ΔΦ on grids M = 4 and 8 times the window: they differ by the periodic images, a smooth field that falls as
    the period⁻³ (measured, of the largest correction, with the mean removed: stiff on soft 3.6e-3 → 4.7e-4,
    rigid base 1.2e-3 → 1.6e-4). With a sixth-degree polynomial fitted out (the images' smooth field) what is
    left is the kernel's own error, the same at both periods: measured 3.9e-8 (stiff on soft) and 1.6e-8
    (rigid), bound 1.5e-7."""
    compliance, E_star, slope = FREE_LAYERS[layer]
    n, dx = 32, 1e-5
    pressure = np.zeros((n, n))
    pressure[12:20, 12:20] = np.random.default_rng(0).random((8, 8))
    offsets = np.arange(n) * dx
    half = free_surface_correction(compliance, E_star, slope, 4e-5, offsets, offsets, dx, dx)
    full = np.block([[half[:0:-1, :0:-1], half[:0:-1]], [half[:, :0:-1], half]])     # offsets −(n−1) … n−1
    free = signal.fftconvolve(pressure, full, mode="same")
    x, y = (c.ravel() / n for c in np.indices((n, n)))
    polynomial = np.stack([x ** i * y ** j for i in range(7) for j in range(7 - i)], axis=1)
    images = []
    for multiple in (4, 8):
        padded = np.zeros((multiple * n,) * 2)
        padded[:n, :n] = pressure
        multiplier = periodic_pixel_correction(compliance, E_star, multiple * n, dx)
        periodic = np.fft.ifft2(np.fft.fft2(padded) * multiplier).real[:n, :n]
        difference = (free - periodic).ravel()
        images.append(np.abs(difference - difference.mean()).max() / np.abs(free).max())
        fit = np.linalg.lstsq(polynomial, difference, rcond=None)[0]
        assert np.abs(difference - polynomial @ fit).max() < 1.5e-7 * np.abs(free).max()
    assert images[1] < 1e-3 and 6 < images[0] / images[1] < 10                     # period⁻³: 8 per doubling


@pytest.mark.parametrize("substrate", [{}, {"substrate_E_star": 2e4, "substrate_poisson": 0.49}])
def test_free_surface_layer_much_thicker_than_the_window(substrate):
    """A layer t ≫ L on a free surface is the layer's half-space plus a uniform shift F Δw(0) from the far base
    (Δw(0) = (1/2π) ∫ [q Φ − 2/E*] dq, by quad), up to O((L/t)³): measured 1.1e-10 (rigid base) and 1.5e-9
    (soft substrate) of the largest displacement at t = 1 m on a 1 mm window; bound 1e-8. The shift itself is
    −3.8e-4 and +1.3e-2 of it (a dropped correction fails)."""
    grid = Grid((32, 32), (1e-3, 1e-3), periodic=False)
    pressure = np.random.default_rng(1).random(grid.shape) * 1e3
    force = pressure.sum() * grid.pixel_area
    half = ElasticHalfSpace(grid, 2e6).displacement(pressure)
    t = 1.0
    body = ElasticHalfSpace(grid, 2e6, thickness=t, poisson=0.3, **substrate)
    shift = integrate.quad(lambda X: X / t * body.compliance(X / t) - 1e-6, 0, np.inf, epsabs=0, epsrel=1e-12,
                           limit=200)[0] / (2 * np.pi * t) * force
    assert abs(shift) > 3e-4 * half.max()
    np.testing.assert_allclose(body.displacement(pressure) - half, shift, rtol=0, atol=1e-8 * half.max())


def test_free_surface_layered_operator_is_the_linear_convolution_and_positive():
    """The padded FFT applies exactly Love's coefficients plus the correction (direct summation, 1e-12), its
    multiplier is positive; a layer 1000 times stiffer than its substrate on a coarse grid needs the wider,
    tapered padding (3n here), which leaves the window's convolution unchanged."""
    for n, layer, shape in ((7, dict(poisson=0.3), (14, 14)),
                            (16, dict(poisson=0.5, substrate_E_star=1e3, substrate_poisson=0.5), (48, 48))):
        grid = Grid((n, n), (n * 1e-5, n * 1e-5), periodic=False)
        body = ElasticHalfSpace(grid, 1e6, thickness=1e-5 if n == 7 else 3e-6, **layer)
        assert body.transform_shape == shape and body._multiplier.min() > 0
        dx = grid.spacing[0]
        offsets = np.arange(n) * dx
        coefficients = (love_pixel_displacement(offsets[:, None], offsets[None, :], dx, dx, 1e6)
                        + free_surface_correction(body.compliance, 1e6, -2e-6 if n == 7 else 2e-3 - 2e-6,
                                                  body.layer["thickness"], offsets, offsets, dx, dx))
        pressure = np.random.default_rng(2).random(grid.shape) * 1e4
        i, j = np.indices(grid.shape)
        direct = sum(pressure[a, b] * coefficients[np.abs(i - a), np.abs(j - b)] for a, b in np.ndindex(n, n))
        np.testing.assert_allclose(body.displacement(pressure), direct, rtol=1e-12)


def _hertz_cap(n=64, length=1e-3, radius=10e-3):
    grid = Grid((n, n), (length, length), periodic=False)
    x = (np.arange(n) - n / 2 + 0.5) * length / n
    return HeightField(grid, -(x[:, None] ** 2 + x[None, :] ** 2) / (2 * radius))


def test_free_surface_layered_hertz_limits():
    """A sphere (R = 10 mm, a = 0.15 mm on a 1 mm, 64² window) against the half-space solved on the same grid
    (Hertz itself to the grid's pixel error: radius +1.8 %, penetration −0.31 %). A 10 mm layer (t = 67 a) on a
    10× softer substrate: the same contact set, and the penetration less the far substrate's uniform shift F Δw(0)
    is the layer's half-space's (measured 2.6e-6: O((a/t)³); bound 1e-5), pressure within 8.7e-6 of its peak
    (bound 3e-5). A 1 µm layer 100× stiffer than its substrate (a = 150 t, ℓ = t (E*/E0*)^⅓ = 4.6 µm, below the
    15.6 µm pixel): the substrate's Hertz — same contact set, penetration within 6.9e-6 (bound 3e-5), pressure
    within 0.88 % of the peak (bound 1.5 %)."""
    cap = _hertz_cap()
    radius, a = 10e-3, 0.15e-3
    for layer_E, substrate_E, t in ((1e6, 1e5, 1e-2), (1e6, 1e4, 1e-6)):
        reference_E = layer_E if t > a else substrate_E
        force = 4 * reference_E * a ** 3 / (3 * radius)
        half = solve_contact(cap, ElasticHalfSpace(cap.grid, reference_E), total_force=force, tol=1e-10)
        assert half.penetration == pytest.approx(ref.hertz_penetration(force, radius, reference_E), rel=4e-3)
        body = ElasticHalfSpace(cap.grid, layer_E, thickness=t, poisson=0.5, substrate_E_star=substrate_E,
                                substrate_poisson=0.5)
        layered = solve_contact(cap, body, total_force=force, tol=1e-10)
        assert layered.converged
        np.testing.assert_array_equal(layered.contact, half.contact)
        if t > a:
            shift = integrate.quad(lambda X: X / t * body.compliance(X / t) - 2 / layer_E, 0, np.inf, epsabs=0,
                                   epsrel=1e-12, limit=200)[0] / (2 * np.pi * t) * force
            assert layered.penetration - shift == pytest.approx(half.penetration, rel=1e-5)
            assert np.abs(layered.pressure - half.pressure).max() < 3e-5 * half.pressure.max()
        else:
            assert layered.penetration == pytest.approx(half.penetration, rel=3e-5)
            assert np.abs(layered.pressure - half.pressure).max() < 1.5e-2 * half.pressure.max()


@pytest.mark.parametrize("layer", [dict(thickness=1e-4, poisson=0.3),
                                   dict(thickness=3e-5, poisson=0.5, substrate_E_star=1e4, substrate_poisson=0.5)])
def test_free_surface_layered_body_in_every_solver(layer):
    """The smooth-law solver (padded body) at a vanishing law gives the hard-wall answer (measured: the same
    contact set, pressure within 3.8e-9 / 5.4e-9 of its peak; bound 1e-6, as for the half-space), and the
    float32 body converges to its tolerance 1e-5 and to the float64 answer (measured 4.0e-4 / 2.5e-4 of the
    peak; bound 2e-3)."""
    from roughcontact import DielectricStack, ElectrostaticInteraction
    cap = _hertz_cap(length=1e-3, radius=5e-3)
    body = ElasticHalfSpace(cap.grid, 1e6, **layer)
    hard = solve_contact(cap, body, total_force=1e-3, tol=1e-10)
    faint = solve_contact(cap, body, total_force=1e-3, interaction=ElectrostaticInteraction(DielectricStack(), 1e-6),
                          tol=1e-10)
    assert hard.converged and faint.converged
    np.testing.assert_array_equal(faint.contact, hard.contact)
    assert np.abs(faint.pressure - hard.pressure).max() < 1e-6 * hard.pressure.max()
    single = solve_contact(cap, ElasticHalfSpace(cap.grid, 1e6, dtype=np.float32, **layer), total_force=1e-3,
                           tol=1e-5)
    assert single.converged and single.pressure.dtype == np.float32
    assert np.abs(single.pressure - hard.pressure).max() < 2e-3 * hard.pressure.max()
