"""Shull's compliance method for power-law contacts (seed Eqs. 1–14) and peeling (Eqs. 29–33)."""
import pickle

import numpy as np
import pytest

from roughcontact.macro import PowerLawContact, SavkoorBriggsPeeling, hutchinson_suo_toughness

R, E_STAR = 1e-2, 47.4e3          # the seed's Hertz fit of the finger (Fig. 3)
LAWS = {"hertz": PowerLawContact.hertz(R, E_STAR), "dzidek_apparent": PowerLawContact.dzidek_apparent(),
        "dzidek_ridge": PowerLawContact.dzidek_ridge(), "table1_ridge": PowerLawContact.table1_ridge()}


# -- Hertz -> JKR (Eqs. 12-14), exact -----------------------------------------------------------------------
@pytest.mark.parametrize("w", [1e-6, 0.132, 0.5212, 10.0])
def test_hertz_parameters_give_jkr_exactly(w):
    law = LAWS["hertz"]
    a = np.geomspace(1e-5, 1e-2, 50)
    # JKR force and approach (Eqs. 13-14); 1e-12: a few roundings of a difference of O(1) terms
    jkr_force = 4 * E_STAR * a ** 3 / (3 * R) - np.sqrt(8 * np.pi * E_STAR * w * a ** 3)
    jkr_delta = a ** 2 / R - np.sqrt(2 * np.pi * w * a / E_STAR)
    scale_f = 4 * E_STAR * a ** 3 / (3 * R) + np.sqrt(8 * np.pi * E_STAR * w * a ** 3)
    scale_d = a ** 2 / R + np.sqrt(2 * np.pi * w * a / E_STAR)
    assert np.all(np.abs(law.normal_force(np.pi * a ** 2, w) - jkr_force) <= 1e-12 * scale_f)
    assert np.all(np.abs(law.indentation(np.pi * a ** 2, w) - jkr_delta) <= 1e-12 * scale_d)
    pull_off = law.pull_off(w)
    assert pull_off.force == pytest.approx(-1.5 * np.pi * w * R, rel=1e-12)
    # JKR pull-off radius under load control a³ = 9πwR²/(8E*), zero-load radius a³ = 9πwR²/(2E*)
    assert pull_off.area == pytest.approx(np.pi * (9 * np.pi * w * R ** 2 / (8 * E_STAR)) ** (2 / 3), rel=1e-12)
    assert law.zero_load_area(w) == pytest.approx(np.pi * (9 * np.pi * w * R ** 2 / (2 * E_STAR)) ** (2 / 3),
                                                  rel=1e-12)


def test_hertz_preset_is_hertz():
    law = LAWS["hertz"]
    force = np.array([0.1, 1.0, 2.0])
    a = (3 * force * R / (4 * E_STAR)) ** (1 / 3)
    np.testing.assert_allclose(law.nonadhesive_area(force), np.pi * a ** 2, rtol=1e-14)
    np.testing.assert_allclose(law.nonadhesive_indentation(np.pi * a ** 2), a ** 2 / R, rtol=1e-14)


# -- errata (a), (b): Eqs. 3, 4, 9, 10 --------------------------------------------------------------------------
def printed_eq9(law, area, w, prefactor):
    m, n, alpha, beta = law.m, law.n, law.alpha, law.beta
    return alpha ** (-1 / m) * area ** (1 / m) - np.sqrt(
        2 * w * prefactor / (n - m) * beta ** (1 / n) * alpha ** (-1 / m) * area ** (1 + 1 / m - 1 / n))


def printed_eq10(law, area, w):
    m, n, alpha, beta = law.m, law.n, law.alpha, law.beta
    return beta ** (-1 / n) * area ** (1 / n) - np.sqrt(
        2 * w * m ** 2 / (n - m) * beta ** (-1 / n) * alpha ** (1 / m) * area ** (1 - 1 / m + 1 / n))


@pytest.mark.parametrize("name", sorted(LAWS))
def test_eq9_needs_n_squared_and_eq10_is_right(name):
    law, w = LAWS[name], 0.132
    area = np.geomspace(1e-7, 2e-4, 30)
    ours = law.normal_force(area, w)
    np.testing.assert_allclose(ours, printed_eq9(law, area, w, law.n ** 2), rtol=1e-10, atol=1e-15)
    # the printed m² is wrong wherever m != n (always): its adhesive term is m/n times ours
    assert not np.allclose(ours, printed_eq9(law, area, w, law.m ** 2), rtol=1e-3)
    np.testing.assert_allclose(law.indentation(area, w), printed_eq10(law, area, w), rtol=1e-10, atol=1e-18)


@pytest.mark.parametrize("name", sorted(LAWS))
def test_compliance_method_corrected_eqs_3_4(name):
    """F₁ − F = S √(2w/(dS/dA)) and δ₁ − δ = √(2w/(dS/dA)): G = w in Eq. 1 (erratum (a))."""
    law, w = LAWS[name], 0.3
    area = np.geomspace(1e-6, 1e-4, 20)
    stiffness, slope = law.stiffness(area), law.stiffness_derivative(area)
    np.testing.assert_allclose(law.nonadhesive_force(area) - law.normal_force(area, w),
                               stiffness * np.sqrt(2 * w / slope), rtol=1e-12)
    np.testing.assert_allclose(law.nonadhesive_indentation(area) - law.indentation(area, w),
                               np.sqrt(2 * w / slope), rtol=1e-12)
    # energy release rate of Eq. 1, both forms, equals w at the solution
    g_force = (law.nonadhesive_force(area) - law.normal_force(area, w)) ** 2 / (2 * stiffness ** 2) * slope
    g_delta = (law.nonadhesive_indentation(area) - law.indentation(area, w)) ** 2 / 2 * slope
    np.testing.assert_allclose(g_force, w, rtol=1e-12)
    np.testing.assert_allclose(g_delta, w, rtol=1e-12)


@pytest.mark.parametrize("name", sorted(LAWS))
def test_stiffness_eqs_7_8_by_finite_differences(name):
    law = LAWS[name]
    area, h = 5e-5, 1e-4        # relative step 1e-4, central differences: error ~1e-8
    up, down = area * (1 + h), area * (1 - h)
    fd_stiffness = ((law.nonadhesive_force(up) - law.nonadhesive_force(down))
                    / (law.nonadhesive_indentation(up) - law.nonadhesive_indentation(down)))
    assert law.stiffness(area) == pytest.approx(fd_stiffness, rel=1e-7)
    fd_slope = (law.stiffness(up) - law.stiffness(down)) / (up - down)
    assert law.stiffness_derivative(area) == pytest.approx(fd_slope, rel=1e-7)


@pytest.mark.parametrize("n", [0.8, 1.0, 1.41, 3.0])
def test_eq11_half_space_exponents_give_s_proportional_to_sqrt_a(n):
    """m = 2n/(n + 2) (Eq. 11) makes S ∝ √A via Eq. 7, as for any compact axisymmetric half-space contact."""
    law = PowerLawContact(m=2 * n / (n + 2), alpha=1e-4, n=n, beta=1e-3)
    area = np.geomspace(1e-8, 1e-3, 7)
    ratio = law.stiffness(area) / np.sqrt(area)
    np.testing.assert_allclose(ratio, ratio[0], rtol=1e-12)


# -- inversion, pull-off, zero load ----------------------------------------------------------------------------
@pytest.mark.parametrize("name", sorted(LAWS))
@pytest.mark.parametrize("w", [0.0, 1e-6, 0.132, 10.0])
def test_area_inverts_eq9_on_the_stable_branch(name, w):
    law = LAWS[name]
    pull_off = law.pull_off(w)
    force = np.concatenate([pull_off.force * np.array([1.0, 0.999999, 0.5, 0.0]), [1e-9, 0.1, 1.0, 2.3, 100.0]])
    area = law.area(force, w)
    assert area.shape == force.shape
    assert np.all(area >= pull_off.area * (1 - 1e-12))           # stable branch
    scale = np.maximum(np.abs(force), np.abs(pull_off.force))
    # near pull-off A(F) ~ √(F − F_c): the root is only known to √eps; F itself comes back to ~1e-12
    assert np.all(np.abs(law.normal_force(area, w) - force) <= 1e-11 * scale + 1e-300)


def test_area_closed_form_for_n_equal_1():
    """n = 1 (Dzidek apparent): F = F₁ − k√F₁ is quadratic in √F₁."""
    law, w = LAWS["dzidek_apparent"], 0.132
    k = law.adhesion_coefficient(w)
    force = np.linspace(float(law.pull_off(w).force) * 0.9, 3.0, 41)
    force_1 = ((k + np.sqrt(k ** 2 + 4 * force)) / 2) ** 2
    np.testing.assert_allclose(law.area(force, w), law.alpha * force_1 ** law.m, rtol=1e-12)


def test_area_without_adhesion_is_eq5_exactly():
    law = LAWS["dzidek_ridge"]
    force = np.array([0.0, 1e-9, 0.5, 2.0])
    np.testing.assert_array_equal(law.area(force, 0.0), law.alpha * force ** law.m)


@pytest.mark.parametrize("name", sorted(LAWS))
def test_pull_off_is_the_global_minimum_of_a_brute_force_scan(name):
    law = LAWS[name]
    works = np.geomspace(1e-6, 10.0, 8)
    pull_off = law.pull_off(works)
    # dense log scan of A over 16 decades (1e-16 to 1 m²), independent of the closed form; Δ ln A = 9.2e-5
    area = np.geomspace(1e-16, 1.0, 400001)
    for w, force_c, area_c in zip(works, pull_off.force, pull_off.area):
        force = law.normal_force(area, w)
        i = force.argmin()
        assert 0 < i < area.size - 1                                    # an interior minimum
        assert force[i] >= force_c * (1 + 1e-12)                      # nothing lower than the closed form
        # flat minimum: F = F_c (1 − O(p²)(Δ ln A/2)²) with exponents p <= 2.7, i.e. <= 2e-8 relative
        assert force[i] == pytest.approx(force_c, rel=2e-8)
        assert area[i] == pytest.approx(area_c, rel=1e-4)              # within one grid step


@pytest.mark.parametrize("name", sorted(LAWS))
def test_zero_load_area(name):
    law, w = LAWS[name], np.array([1e-6, 0.132, 10.0])
    area = law.zero_load_area(w)
    np.testing.assert_allclose(law.normal_force(area, w), 0.0, atol=1e-13 * law.nonadhesive_force(area).max())
    np.testing.assert_allclose(law.area(0.0, w), area, rtol=1e-12)
    assert np.all(area > law.pull_off(w).area)


def test_below_pull_off_raises():
    law = LAWS["dzidek_ridge"]
    force_c = float(law.pull_off(0.132).force)
    with pytest.raises(ValueError, match="pull-off") as error:
        law.area(1.01 * force_c, 0.132)
    assert "np." not in str(error.value)                             # plain numbers, not np.float64(...)
    with pytest.raises(ValueError, match="pull-off"):
        law.area([-1e-6, 1.0], 0.0)


def test_area_iteration_limits():
    """maxiter = 0 is fine where no Newton step is needed (w = 0: A = α F_N^m; F_N = 0 without adhesion) and
    a RuntimeError naming maxiter where one is; bad maxiter / rtol are refused with their range."""
    law = LAWS["dzidek_ridge"]
    assert law.area([0.5, 0.0], 0.0, maxiter=0) == pytest.approx([law.alpha * 0.5 ** law.m, 0.0], rel=1e-15)
    with pytest.raises(RuntimeError, match="maxiter = 0"):
        law.area(0.5, 0.1, maxiter=0)
    assert law.area(0.5, 0.1, rtol=1e-6) == pytest.approx(law.area(0.5, 0.1), rel=1e-10)
    for kwargs, message in ((dict(maxiter=-1), r"maxiter must be an integer in \[0, inf\], got -1"),
                            (dict(maxiter=2.5), "maxiter"), (dict(rtol=-1.0), r"rtol = -1.0 .* range \(0, 1\)"),
                            (dict(rtol=0.0), "rtol"), (dict(rtol=float("nan")), "rtol")):
        with pytest.raises(ValueError, match=message):
            law.area(0.5, 0.1, **kwargs)
    with pytest.raises(ValueError, match=r"normal_force \(3,\), work_of_adhesion \(2,\)"):
        law.area(np.ones(3), np.full(2, 0.1))


# -- bad input, presets, pickling, import cost -----------------------------------------------------------
@pytest.mark.parametrize("kwargs, name", [
    (dict(m=1.0, alpha=1e-4, n=1.0, beta=1e-3), "m"),
    (dict(m=1.2, alpha=1e-4, n=1.0, beta=1e-3), "m"),
    (dict(m=0.5, alpha=0.0, n=1.0, beta=1e-3), "alpha"),
    (dict(m=0.5, alpha=1e-4, n=1.0, beta=-1.0), "beta"),
    (dict(m=float("nan"), alpha=1e-4, n=1.0, beta=1e-3), "m"),
    (dict(m=0.5, alpha=float("inf"), n=1.0, beta=1e-3), "alpha"),
    (dict(m=2.0, alpha=1e-4, n=3.0, beta=1e-3), "1/m"),
])
def test_bad_parameters_raise(kwargs, name):
    with pytest.raises(ValueError, match=name.replace("/", ".")):
        PowerLawContact(**kwargs)


@pytest.mark.parametrize("call", [lambda l: l.area(np.nan, 0.1), lambda l: l.area(1.0, -0.1),
                                  lambda l: l.normal_force(-1e-6, 0.1), lambda l: l.pull_off(np.inf)])
def test_bad_arrays_raise(call):
    with pytest.raises(ValueError):
        call(LAWS["dzidek_ridge"])


def test_presets_in_si():
    law = PowerLawContact.dzidek_ridge()
    assert (law.m, law.n) == (0.52, 1.41)
    assert law.alpha == pytest.approx(54.9e-6, rel=1e-15)
    assert law.beta == pytest.approx(33.3 * 1e-3 ** 0.59, rel=1e-14)         # mm^(2-n) (erratum (c))
    # A = 1 mm² at δ₁ = (1/33.3)^(1/1.41) mm, in metres
    assert law.nonadhesive_indentation(1e-6) == pytest.approx(1e-3 * (1 / 33.3) ** (1 / 1.41), rel=1e-13)
    table1 = PowerLawContact.table1_ridge()
    assert (table1.alpha, table1.beta) == pytest.approx((74e-6, 43.5 * 1e-3 ** 0.59), rel=1e-14)
    apparent = PowerLawContact.dzidek_apparent()
    assert (apparent.m, apparent.alpha, apparent.n, apparent.beta) == pytest.approx((0.37, 91.9e-6, 1.0, 64.4e-3))


def test_pickle_round_trip(tmp_path):
    law = PowerLawContact.table1_ridge()
    assert pickle.loads(pickle.dumps(law)) == law
    pull_off = law.pull_off([0.1, 0.2])
    for copy in (pickle.loads(pickle.dumps(pull_off)), type(pull_off).load(pull_off.save(tmp_path / "p.npz"))):
        for field in ("force", "area", "indentation", "work_of_adhesion"):
            np.testing.assert_array_equal(getattr(copy, field), getattr(pull_off, field))
    peeling = SavkoorBriggsPeeling.incompressible_on_rigid(R, E_STAR)
    assert pickle.loads(pickle.dumps(peeling)) == peeling


# -- peeling (Eqs. 29-33) ------------------------------------------------------------------------------------
PEELING = SavkoorBriggsPeeling.incompressible_on_rigid(R, E_STAR)


def test_incompressible_shear_ratio_from_eq30():
    nu = 0.5
    E = E_STAR * (1 - nu ** 2)                 # E* = E/(1-ν²) against a rigid flat
    G = E / (2 * (1 + nu))
    assert 1 / ((2 - nu) / (4 * G)) == pytest.approx(PEELING.G_star, rel=1e-14)


@pytest.mark.parametrize("force", [-0.002, 0.0, 0.5, 2.0])
def test_peeling_area_solves_g_equals_w(force):
    w = 0.132
    critical = float(PEELING.critical_tangential_force(force, w))
    tangential = np.linspace(0.0, critical, 11)
    area = PEELING.area(tangential, force, w)
    # Eq. 31 against Eq. 29 with the Eq. 30 stiffnesses: G(A) = w
    np.testing.assert_allclose(PEELING.energy_release_rate(area, force, tangential), w, rtol=1e-9)
    # no tangential force: the JKR area of Eq. 9
    assert area[0] == pytest.approx(float(PEELING.hertz.area(force, w)), rel=1e-12)
    assert np.all(np.diff(area) < 0)                         # peeling shrinks the area
    with pytest.raises(ValueError, match="critical"):
        PEELING.area(1.001 * critical, force, w)


def test_critical_tangential_force_is_where_dg_da_vanishes():
    """At F_T,c the stable and unstable branches of Eq. 31 merge: dG/dA = 0 at the area of F_T,c."""
    w, force = 0.132, 0.5
    critical = float(PEELING.critical_tangential_force(force, w))
    area = float(PEELING.area(critical, force, w))
    h = 1e-5
    slope = (PEELING.energy_release_rate(area * (1 + h), force, critical)
             - PEELING.energy_release_rate(area * (1 - h), force, critical)) / (2 * h * area)
    assert abs(slope * area / w) < 1e-4


def test_mixed_mode_area_reduces_to_eq31_and_solves_g_equals_w_tilde():
    w, force = 0.132, 0.5
    critical = float(PEELING.critical_tangential_force(force, w))
    tangential = np.linspace(0.0, 0.95 * critical, 5)
    for form in (1, 2, 3):
        # λ = 1: f ≡ 1, Eq. 31; bisection to machine precision, area ∝ P₁^(2/3)
        np.testing.assert_allclose(PEELING.mixed_mode_area(tangential, force, w, 1.0, form),
                                   PEELING.area(tangential, force, w), rtol=1e-12)
        # λ = 0.3: G(A) = w f(ψ(A)) from the independent Eq. 29 and Eq. 33 evaluations
        area = PEELING.mixed_mode_area(tangential, force, w, 0.3, form)
        psi = PEELING.mode_mixity_angle(area, force, tangential)
        np.testing.assert_allclose(PEELING.energy_release_rate(area, force, tangential),
                                   w * hutchinson_suo_toughness(psi, 0.3, form), rtol=1e-9)
        assert np.all(area >= PEELING.area(tangential, force, w) * (1 - 1e-12))   # toughening resists peeling
    # mode-II toughening lets the contact survive beyond the Savkoor-Briggs critical force
    assert np.isfinite(PEELING.mixed_mode_area(1.05 * critical, force, w, 0.3, 2))
    with pytest.raises(ValueError, match="critical"):
        PEELING.mixed_mode_area(1.05 * critical, force, w, 1.0, 1)
    assert PEELING.mixed_mode_area(0.0, force, 0.0, 0.5) == pytest.approx(float(PEELING.hertz.nonadhesive_area(force)),
                                                                         rel=1e-14)


def test_mode_mixity_angle():
    area = float(PEELING.hertz.area(0.5, 0.132))
    deficit = float(PEELING.hertz.nonadhesive_force(area)) - 0.5
    assert PEELING.mode_mixity_angle(area, 0.5, 0.1) == pytest.approx(np.arctan(0.1 / deficit), rel=1e-14)


@pytest.mark.parametrize("form", [1, 2, 3])
def test_hutchinson_suo_limits(form):
    psi = np.linspace(-1.4, 1.4, 15)
    np.testing.assert_allclose(hutchinson_suo_toughness(psi, 1.0, form), 1.0, rtol=1e-14)
    # λ = 0: only the mode-I part G cos²ψ must reach G_Ic, so f = 1/cos²ψ in all three forms
    np.testing.assert_allclose(hutchinson_suo_toughness(psi, 0.0, form), 1 / np.cos(psi) ** 2, rtol=1e-12)
    assert hutchinson_suo_toughness(0.0, 0.3, form) == 1.0
    values = hutchinson_suo_toughness(np.linspace(0, 1.4, 8), 0.3, form)
    assert np.all(np.diff(values) > 0)                       # mode II toughens the interface


def test_hutchinson_suo_bad_input():
    with pytest.raises(ValueError, match="lam"):
        hutchinson_suo_toughness(0.1, 1.5)
    with pytest.raises(ValueError, match="form"):
        hutchinson_suo_toughness(0.1, 0.5, form=4)
    with pytest.raises(ValueError, match="psi"):
        hutchinson_suo_toughness(2.0, 0.5)
