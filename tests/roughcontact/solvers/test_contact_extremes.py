"""Extreme and invalid inputs of the contact solver: it must stay right, or report, or refuse loudly."""
import warnings

import numpy as np
import pytest

from roughcontact import ElasticHalfSpace, load_path, solve_contact
from roughcontact import reference as ref
from roughcontact.interactions import HardWall, Interaction
from roughcontact.io import ConvergenceWarning
from surfaces import Grid, HeightField

from contact_checks import check_contact_state

E_STAR = 1e6


def bump(grid, radius):
    """Paraboloid cap h = −r²/(2R) [m] with its apex on the central pixel (n//2, m//2)."""
    x, y = grid.meshgrid()
    (dx, dy), (nx, ny) = grid.spacing, grid.shape
    return HeightField(grid, -((x - nx // 2 * dx) ** 2 + (y - ny // 2 * dy) ** 2) / (2 * radius))


def check_physics(field, result):
    """Complementarity on the raw gap s − h + u (contact_checks), a non-negative load and a finite energy."""
    check_contact_state(field, result)
    assert result.mean_pressure >= 0 and np.isfinite(result.elastic_energy)


@pytest.mark.parametrize("periodic", [True, False])
def test_single_contact_point(periodic):
    """A tiny load on a sphere touches one pixel; force balance still holds to round-off."""
    grid = Grid((33, 33), (1e-3, 1e-3), periodic=periodic)
    field = bump(grid, 1e-2)
    result = solve_contact(field, ElasticHalfSpace(grid, E_star=E_STAR), mean_pressure=1e-6, tol=1e-10)
    assert result.converged and np.count_nonzero(result.contact) == 1
    assert result.contact[16, 16] and result.mean_pressure == pytest.approx(1e-6, rel=1e-12)
    check_physics(field, result)


@pytest.mark.parametrize("shape, periodic", [((63, 45), False), ((45, 63), True), ((31, 64), False),
                                             ((17, 3), True)])
def test_odd_and_non_square_grids(shape, periodic):
    """Odd and non-square grids give the Hertz answer where the contact is resolved (a = 2.9–3.2 px): the peak
    pressure p0 = 3F/(2πa²) (measured within 1.2 %, assert 2.5 %) and on a free surface the force from the
    penetration, F = (4/3) E* R^½ δ^(3/2) (measured 0.8 %, assert 1.5 %; the periodic images shift δ by 10 %).
    The 17 × 3 grid (a = 0.55 px) is only checked for symmetry. Transposing the grid transposes the answer."""
    length = 1e-3 * np.array(shape) / max(shape)
    grid = Grid(shape, tuple(length), periodic=periodic)
    field = bump(grid, 5e-3)
    half = ElasticHalfSpace(grid, E_star=E_STAR)
    result = solve_contact(field, half, mean_pressure=50.0, tol=1e-10)
    assert result.converged and 0 < result.contact_fraction < 1
    assert result.mean_pressure == pytest.approx(50.0, rel=1e-12)
    check_physics(field, result)
    force, radius = result.total_force, 5e-3
    if ref.hertz_contact_radius(force, radius, E_STAR) > 2 * grid.spacing[0]:
        p0 = 3 * force / (2 * np.pi * ref.hertz_contact_radius(force, radius, E_STAR) ** 2)
        assert result.pressure.max() == pytest.approx(p0, rel=2.5e-2)
        if not periodic:
            assert ref.hertz_force(result.penetration, radius, E_STAR) == pytest.approx(force, rel=1.5e-2)
    transposed = solve_contact(HeightField(Grid(shape[::-1], tuple(length[::-1]), periodic), field.heights.T),
                               ElasticHalfSpace(Grid(shape[::-1], tuple(length[::-1]), periodic), E_star=E_STAR),
                               mean_pressure=50.0, tol=1e-10)
    np.testing.assert_allclose(transposed.pressure, result.pressure.T, rtol=0, atol=1e-7 * result.pressure.max())


def test_flat_surface_periodic_is_uniform_full_contact():
    grid = Grid((16, 12), (1e-3, 1e-3), periodic=True)
    result = solve_contact(HeightField(grid, np.full(grid.shape, 3e-6)), ElasticHalfSpace(grid, E_star=E_STAR),
                           mean_pressure=1e3)
    assert result.converged and result.contact_fraction == 1.0 and result.iterations == 0
    np.testing.assert_allclose(result.pressure, 1e3, rtol=1e-15)
    assert result.mean_gap == 0.0 and result.elastic_energy == pytest.approx(0.0, abs=1e-30)


def test_flat_punch_free_surface():
    """A flat window pressed on a free half-space is a rigid punch: full contact, pressure rising to the edges,
    and a uniform displacement."""
    grid = Grid((32, 32), (1e-3, 1e-3), periodic=False)
    result = solve_contact(HeightField(grid, np.zeros(grid.shape)), ElasticHalfSpace(grid, E_star=E_STAR),
                           mean_pressure=1e3, tol=1e-10)
    assert result.converged and result.contact_fraction == 1.0
    assert result.pressure[0, 0] > result.pressure[0, 16] > result.pressure[16, 16]
    np.testing.assert_allclose(result.displacement, result.displacement.mean(), rtol=1e-8)


def test_near_full_contact_rough():
    grid = Grid((64, 64), (1e-3, 1e-3), periodic=True)
    rng = np.random.default_rng(3)
    smooth = np.fft.irfft2(np.fft.rfft2(rng.standard_normal(grid.shape))
                           * (np.hypot(*grid.wavevectors(real=True)) < 2 * np.pi * 8 / 1e-3))
    field = HeightField(grid, 1e-7 * smooth / smooth.std())
    result = solve_contact(field, ElasticHalfSpace(grid, E_star=E_STAR), mean_pressure=5e3, tol=1e-9)
    assert result.converged and 0.97 < result.contact_fraction < 1.0
    check_physics(field, result)


def test_huge_height_ratio():
    """1 mm waviness plus 1 nm ripples: nanometre features survive the rounding (float64) and change the
    pressure; the solution stays physical."""
    n = 128
    grid = Grid((n, 1), (1e-2, 1e-2 / n), periodic=True)
    x = grid.coordinates()[0][:, None]
    coarse = HeightField(grid, 1e-3 * np.cos(2 * np.pi * x / 1e-2))
    fine = coarse + HeightField(grid, 1e-9 * np.cos(2 * np.pi * 16 * x / 1e-2))
    half = ElasticHalfSpace(grid, E_star=E_STAR)
    p_star = ref.westergaard_full_contact_pressure(1e-3, 1e-2, E_STAR)
    results = [solve_contact(f, half, mean_pressure=0.5 * p_star, tol=1e-12) for f in (coarse, fine)]
    for field, result in zip((coarse, fine), results):
        assert result.converged
        check_physics(field, result)
    # inside the contact the ripple is flattened: Δp = (E* q/2) h_ripple cos(qx) (Φ = 2/(E* q) inverted), here
    # 5.0 Pa on 1.6e5 Pa; within |x| < a/2 measured to 0.76 % of the amplitude (the finite contact's correction
    # grows towards the edges), assert 1.5 %
    q = 2 * np.pi * 16 / 1e-2
    ripple = E_STAR * q * 1e-9 / 2
    a = ref.westergaard_contact_half_width(0.5 * p_star, 1e-3, 1e-2, E_STAR)
    core = np.abs((x[:, 0] + 5e-3) % 1e-2 - 5e-3) < 0.5 * a
    change = (results[1].pressure - results[0].pressure)[core, 0]
    np.testing.assert_allclose(change, ripple * np.cos(q * x[core, 0]), rtol=0, atol=1.5e-2 * ripple)


def test_non_convergence_is_reported_and_warned():
    grid = Grid((64, 64), (1e-3, 1e-3), periodic=True)
    field = bump(grid, 1e-3)
    with pytest.warns(ConvergenceWarning, match="not converged after 2 iterations"):
        result = solve_contact(field, ElasticHalfSpace(grid, E_star=E_STAR), mean_pressure=1e3, maxiter=2)
    assert not result.converged and result.iterations == 2 and len(result.residuals) == 3
    assert "not converged" in result.message
    with pytest.raises(AssertionError, match="complementarity|interpenetration"):
        check_physics(field, result)               # raw gap 0.16 of the height range under pressure (tol 1e-8)
    assert (result.gap >= 0).all() and np.all(result.pressure * result.gap == 0)   # result.gap cannot tell
    assert result.mean_pressure == pytest.approx(1e3, rel=1e-12)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        solve_contact(field, ElasticHalfSpace(grid, E_star=E_STAR), mean_pressure=1e3, maxiter=2, warn=False)


def test_no_contact_for_non_positive_penetration():
    grid = Grid((16, 16), (1e-3, 1e-3), periodic=False)
    result = solve_contact(bump(grid, 1e-2), ElasticHalfSpace(grid, E_star=E_STAR), penetration=0.0)
    assert result.converged and result.contact_fraction == 0 and not result.pressure.any()


@pytest.mark.parametrize("heights, word", [(np.nan, "surface"), (np.inf, "surface")])
def test_nan_and_inf_heights(heights, word):
    grid = Grid((8, 8), (1e-3, 1e-3))
    values = np.zeros(grid.shape)
    values[3, 4] = heights
    with pytest.raises(ValueError, match=word):
        solve_contact(values, ElasticHalfSpace(grid, E_star=E_STAR), mean_pressure=1.0)


def test_complex_heights_are_refused():
    """A complex array was cast to its real part with only a ComplexWarning."""
    grid = Grid((8, 8), (1e-3, 1e-3))
    with pytest.raises(TypeError, match="surface must be real, got complex"):
        solve_contact(np.zeros(grid.shape, complex), ElasticHalfSpace(grid, E_star=E_STAR), mean_pressure=1.0)


@pytest.mark.parametrize("kwargs, exc, word", [
    ({"mean_pressure": 0.0}, ValueError, "mean_pressure"),
    ({"mean_pressure": -1.0}, ValueError, "mean_pressure"),
    ({"total_force": float("nan")}, ValueError, "total_force"),
    ({"mean_pressure": 1.0, "penetration": 1e-6}, ValueError, "exactly one"),
    ({}, ValueError, "exactly one"),
    ({"mean_pressure": 1.0, "tol": 0.0}, ValueError, "tol"),
    ({"mean_pressure": 1.0, "maxiter": -1}, ValueError, "maxiter"),
    ({"mean_pressure": 1.0, "x0": np.ones((4, 4))}, ValueError, "x0"),
    ({"mean_pressure": 1.0, "x0": -np.ones((8, 8))}, ValueError, "x0"),
    ({"mean_pressure": 1.0, "callback": 3}, TypeError, "callback"),
    ({"mean_pressure": 1.0, "interaction": Interaction()}, ValueError, "interaction"),
])
def test_bad_solver_input(kwargs, exc, word):
    grid = Grid((8, 8), (1e-3, 1e-3))
    with pytest.raises(exc, match=word):
        solve_contact(np.zeros(grid.shape), ElasticHalfSpace(grid, E_star=E_STAR), **kwargs)


def test_grid_mismatch_and_wrong_half_space():
    grid = Grid((8, 8), (1e-3, 1e-3))
    other = HeightField(Grid((8, 8), (2e-3, 2e-3)), np.zeros((8, 8)))
    with pytest.raises(ValueError, match="grid"):
        solve_contact(other, ElasticHalfSpace(grid, E_star=E_STAR), mean_pressure=1.0)
    with pytest.raises(TypeError, match="body must be an ElasticHalfSpace"):
        solve_contact(other, E_STAR, mean_pressure=1.0)


def test_hard_wall_interaction_law():
    wall = HardWall()
    assert wall.hard_wall
    np.testing.assert_array_equal(wall.energy([0.0, 1e-9, -1e-12]), [0.0, 0.0, np.inf])
    np.testing.assert_array_equal(wall.traction([0.0, 1e-6]), [0.0, 0.0])
    np.testing.assert_array_equal(wall.stiffness([1e-6]), [0.0])
    with pytest.raises(ValueError, match="gap"):
        wall.traction([-1e-9])


@pytest.mark.parametrize("periodic", [True, False])
def test_nested_cold_start_levels_and_fallbacks(periodic):
    """The nested start coarsens while the coarse grid keeps NESTED_MIN = 64 pixels per axis, gives the PK
    start's answer, and falls back to the PK start where the grid does not halve or the flat misses the
    coarse surface (whose averaged peak is lower)."""
    radius = 2e-3
    grid = Grid((256, 256), (1e-3, 1e-3), periodic=periodic)
    half = ElasticHalfSpace(grid, E_star=E_STAR)
    field = bump(grid, radius)
    nested = solve_contact(field, half, penetration=2e-6, tol=1e-10)
    pk = solve_contact(field, half, penetration=2e-6, tol=1e-10, cold_start="pk")
    assert nested.solver.start == "nested" and len(nested.solver.details["nested_iterations"]) == 2   # 64², 128²
    coarse = half.coarsened()
    assert coarse.grid == grid.coarsened(2) and coarse.description == half.description | {
        "transform_shape": [n // 2 for n in half.transform_shape]}
    assert nested.converged and pk.converged and np.array_equal(nested.contact, pk.contact)
    # two solves stopped at tol 1e-10 from different starts: measured 1.1e-7 (periodic), 2e-8 of max p
    np.testing.assert_allclose(nested.pressure, pk.pressure, rtol=0, atol=1e-6 * pk.pressure.max())
    # the coarse 2 × 2 mean (0, a, a, 2a), a = Δx²/(2R), lowers the apex by a = 3.8e-9 m: 5e-10 m misses it
    shallow = solve_contact(field, half, penetration=5e-10, tol=1e-10)
    assert shallow.solver.start == "pk" and shallow.solver.details["nested_iterations"] == []
    # an all-zero warm start carries no information: the cold start, bit for bit (heights given as an array)
    zero = solve_contact(field.heights, half, penetration=2e-6, tol=1e-10, x0=np.zeros(grid.shape))
    assert zero.solver.start == "nested" and np.array_equal(zero.pressure, nested.pressure)
    odd = Grid((255, 256), (1e-3, 1e-3), periodic=periodic)
    result = solve_contact(bump(odd, radius), ElasticHalfSpace(odd, E_star=E_STAR), penetration=2e-6, tol=1e-10)
    assert result.converged and result.solver.start == "pk"
    with pytest.raises(ValueError, match="cold_start"):
        solve_contact(field, half, penetration=2e-6, cold_start="uniform")


# -- detect, don't iterate ---------------------------------------------------------------------------------------
def bench_like(dtype=np.float64):
    grid = Grid((64, 64), (1e-3, 1e-3), periodic=True)
    surface = HeightField(grid, np.random.default_rng(3).normal(0, 1e-6, grid.shape))
    return surface, ElasticHalfSpace(grid, E_star=E_STAR, dtype=dtype)


def test_penetration_beyond_the_mean_plane_is_refused():
    surface, half = bench_like()
    limit = surface.heights.max() - surface.heights.mean()
    with pytest.raises(ValueError, match="penetration .* max\\(h\\) − ⟨h⟩"):
        solve_contact(surface, half, penetration=1.01 * limit)
    assert solve_contact(surface, half, penetration=0.99 * limit).converged
    flat = HeightField(surface.grid, np.zeros(surface.grid.shape))
    with pytest.raises(ValueError, match="penetration"):
        solve_contact(flat, half, penetration=1e-6)
    assert solve_contact(flat, half, penetration=-1e-6).contact_fraction == 0.0


def test_far_beyond_full_contact_is_exact_at_once():
    surface, half = bench_like()
    res = solve_contact(surface, half, mean_pressure=1e30)
    assert res.converged and res.iterations == 0 and res.solver.details["full_contact"] and res.contact_fraction == 1.0
    check_contact_state(surface, res)


def test_float32_default_tolerance_and_stall():
    surface, half = bench_like(np.float32)
    res = solve_contact(surface, half, mean_pressure=1e3)
    assert res.converged and res.solver.tol == 1e-6
    # a tolerance below float32's round-off floor is warned of up front; the residual stops falling and the
    # solve ends STALL_LIMIT steps after its last minimum, not at maxiter
    with pytest.warns(UserWarning, match="stalled"), \
            pytest.warns(ConvergenceWarning, match="tol = 1e-12 is below float32's round-off floor"):
        stalled = solve_contact(surface, half, mean_pressure=1e3, tol=1e-12)
    assert not stalled.converged and stalled.iterations < 1000
    assert stalled.solver.start != "x0" and "warm_start_stalled_at" not in stalled.solver.details
    # a warm-started solve that stalls is solved again from the cold start (which a warm start's cycle can miss)
    with pytest.warns(UserWarning, match="stalled"), pytest.warns(ConvergenceWarning, match="round-off floor"):
        retried = solve_contact(surface, half, mean_pressure=2e3, tol=1e-12, x0=res)
    assert retried.solver.details["warm_start_stalled_at"] > 0 and retried.solver.start != "x0"


def test_flags_and_sweeps_are_checked_when_called():
    surface, half = bench_like()
    with pytest.raises(TypeError, match="preconditioned"):
        solve_contact(surface, half, mean_pressure=1e3, preconditioned="no")
    with pytest.raises(TypeError, match="mean_pressures"):
        load_path(surface, half, 1e3)                       # not a generator's first next(): at once


def test_a_preconditioned_cycle_is_solved_again_without_the_preconditioner():
    """The default scene's ridge profile at 0.25 µm pixels, 2 N (realisation 1): the K⁻¹-preconditioned PK cycles
    from step 5 at a residual of 3e-4 (6.9 % contact against 2.1 %); the solve is repeated unpreconditioned and
    converges, and the equilibrium is checked independently."""
    from roughcontact.study.apparent import apparent_scale
    from roughcontact.study.patch import profile_surface
    from roughcontact.study.scene import load_scene
    scene = load_scene(preset="draft")
    pressure = dict(zip(scene.loads.normal_forces, (scale[1][0] for scale in apparent_scale(scene))))[2.0]
    heights, _, body = profile_surface(scene, 0.25e-6, realisation=1)
    result = solve_contact(heights, body, mean_pressure=pressure, preconditioned=True)
    assert result.converged and result.solver.details["preconditioned_stalled_at"] >= 200
    assert not result.solver.details["preconditioned"]
    check_contact_state(heights, result)


def test_profiles_are_unpreconditioned_by_default():
    """The K⁻¹ preconditioner saves no steps on 1-D profiles (studies/bench_profiles.py): off there by default, on
    for 2-D grids; an explicit choice is kept."""
    grid = Grid((256, 1), (1e-3, 1e-3 / 256), periodic=True)
    x = (np.arange(256) + 0.5) / 256 - 0.5
    profile = HeightField(grid, (-(x * 1e-3) ** 2 / 2e-3)[:, None])
    body = ElasticHalfSpace(grid, E_star=1e6)
    assert not solve_contact(profile, body, mean_pressure=1e3).solver.details["preconditioned"]
    assert solve_contact(profile, body, mean_pressure=1e3, preconditioned=True).solver.details["preconditioned"]
    surface, half = bench_like(np.float64)
    assert solve_contact(surface, half, mean_pressure=1e3).solver.details["preconditioned"]
