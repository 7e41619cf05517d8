"""Analytic references checked against independent integrals and limits (quadrature, not re-typed formulas)."""
import numpy as np
import pytest
from scipy import integrate

from roughcontact import reference as ref

R, E_STAR = 5e-3, 2e6
LAMBDA, H0 = 1e-3, 2e-6


def test_hertz_is_self_consistent():
    force = 0.3
    a = ref.hertz_contact_radius(force, R, E_STAR)
    delta = ref.hertz_penetration(force, R, E_STAR)
    assert ref.hertz_force(delta, R, E_STAR) == pytest.approx(force, rel=1e-14)
    # the pressure integrates to the force
    total = integrate.quad(lambda r: 2 * np.pi * r * ref.hertz_pressure(r, force, R, E_STAR), 0, a)[0]
    assert total == pytest.approx(force, rel=1e-9)
    assert ref.hertz_pressure(1.01 * a, force, R, E_STAR) == 0.0
    # energy = ∫ F dδ along loading
    work = integrate.quad(lambda d: ref.hertz_force(d, R, E_STAR), 1e-30, delta)[0]
    assert ref.hertz_elastic_energy(force, R, E_STAR) == pytest.approx(work, rel=1e-9)


@pytest.mark.parametrize("s", [0.01, 0.3, 0.9])
def test_westergaard_pressure_integrates_to_the_load(s):
    p_star = ref.westergaard_full_contact_pressure(H0, LAMBDA, E_STAR)
    a = ref.westergaard_contact_half_width(s * p_star, H0, LAMBDA, E_STAR)
    mean = integrate.quad(lambda x: ref.westergaard_pressure(x, s * p_star, H0, LAMBDA, E_STAR), -a, a,
                          epsabs=0, epsrel=1e-11)[0] / LAMBDA
    assert mean == pytest.approx(s * p_star, rel=1e-8)
    assert np.sin(np.pi * a / LAMBDA) ** 2 == pytest.approx(s, rel=1e-14)


@pytest.mark.parametrize("s", [0.05, 0.5, 0.95])
def test_westergaard_mean_gap_and_energy_from_the_gap_profile(s):
    """ḡ from the gap profile (references §4.1) and U = ∫ p̄ d(approach) = −∫ p̄ dḡ along loading."""
    p_star = ref.westergaard_full_contact_pressure(H0, LAMBDA, E_STAR)
    a = ref.westergaard_contact_half_width(s * p_star, H0, LAMBDA, E_STAR) / LAMBDA
    sin_a = np.sin(np.pi * a)

    def gap(x):   # x from the contact centre in units of λ, a < x ≤ 1/2
        root = np.sqrt(max(np.sin(np.pi * x) ** 2 - sin_a ** 2, 0.0))
        return 2 * H0 * (np.sin(np.pi * x) * root - sin_a ** 2 * np.log((np.sin(np.pi * x) + root) / sin_a))

    mean_gap = 2 * integrate.quad(gap, a, 0.5, epsabs=0, epsrel=1e-11)[0]
    assert ref.westergaard_mean_gap(s * p_star, H0, LAMBDA, E_STAR) == pytest.approx(mean_gap, rel=1e-8)
    step = 1e-7
    slope = lambda t: -(ref.westergaard_mean_gap((t + step) * p_star, H0, LAMBDA, E_STAR)
                        - ref.westergaard_mean_gap((t - step) * p_star, H0, LAMBDA, E_STAR)) / (2 * step)
    energy = integrate.quad(lambda t: t * p_star * slope(t), 2 * step, s, limit=200)[0]
    assert ref.westergaard_elastic_energy_density(s * p_star, H0, LAMBDA, E_STAR) == pytest.approx(energy, rel=1e-5)


def test_westergaard_limits():
    p_star = ref.westergaard_full_contact_pressure(H0, LAMBDA, E_STAR)
    assert p_star == pytest.approx(np.pi * E_STAR * H0 / LAMBDA, rel=1e-15)
    assert ref.westergaard_mean_gap(0.0, H0, LAMBDA, E_STAR) == pytest.approx(H0)      # crest touching
    assert ref.westergaard_mean_gap(2 * p_star, H0, LAMBDA, E_STAR) == 0.0
    assert ref.westergaard_contact_half_width(2 * p_star, H0, LAMBDA, E_STAR) == pytest.approx(LAMBDA / 2)


def test_bisinusoid_low_load_is_independent_hertz_peaks():
    """Two Hertz peaks per λ² cell, curvature radius λ²/(4π²Δ), each carrying p̄λ²/2."""
    delta, s = 1e-6, 1e-3
    p_star = ref.bisinusoid_full_contact_pressure(delta, LAMBDA, E_STAR)
    a = ref.hertz_contact_radius(s * p_star * LAMBDA ** 2 / 2, LAMBDA ** 2 / (4 * np.pi ** 2 * delta), E_STAR)
    assert ref.bisinusoid_area_low_load(s) == pytest.approx(2 * np.pi * a ** 2 / LAMBDA ** 2, rel=1e-12)
    assert ref.bisinusoid_area_low_load(1.0) == pytest.approx(0.7616, abs=1e-4)
    assert ref.bisinusoid_area_near_full_contact(1.0) == 1.0
    assert ref.bisinusoid_area_near_full_contact(0.9) == pytest.approx(1 - 0.3 / (2 * np.pi) * 1.0, rel=1e-14)


@pytest.mark.parametrize("call, word", [
    (lambda: ref.hertz_contact_radius(-1.0, R, E_STAR), "force"),
    (lambda: ref.hertz_penetration(1.0, R, 0.0), "E_star"),
    (lambda: ref.westergaard_mean_gap(-1.0, H0, LAMBDA, E_STAR), "mean_pressure"),
    (lambda: ref.westergaard_full_contact_pressure(H0, 0.0, E_STAR), "wavelength"),
    (lambda: ref.bisinusoid_area_low_load(np.nan), "load_fraction"),
])
def test_bad_input(call, word):
    with pytest.raises(ValueError, match=word):
        call()


def test_maugis_dugdale_limits_are_dmt_and_jkr():
    # λ → 0: DMT, pull-off −2 π w R; λ → ∞: JKR, −3/2 π w R, and the load curve P̄ = Ā³ − √(6 Ā³) of JKR
    # (F = K a³/R − √(6π w K a³) in Maugis' units); measured −1.9983 at λ = 0.01 and −1.500016 at λ = 100
    assert ref.maugis_dugdale_pull_off(0.01) == pytest.approx(-2.0, abs=2e-3)
    assert ref.maugis_dugdale_pull_off(100.0) == pytest.approx(-1.5, abs=1e-4)
    lambdas = [0.1, 0.3, 1.0, 3.0, 10.0]
    assert np.all(np.diff([ref.maugis_dugdale_pull_off(lam) for lam in lambdas]) > 0)
    load, area = ref.maugis_dugdale_load(1 + np.geomspace(3e-10, 3e-8, 5), 1e4)      # Ā from 24 to 0.24
    # measured relative difference 3.1e-8 at λ = 1e4 (the cohesive zone's width, m − 1 ~ 1e-8)
    np.testing.assert_allclose(load, area ** 3 - np.sqrt(6 * area ** 3), rtol=1e-6)


def test_johnson_sinusoid_limits():
    # α = 0 is Westergaard's p̄/p* = sin²(πa/λ); at α_c = (3/4)^(3/4) (1/2)^(1/2) ≈ 0.570 the curve touches
    # p̄ = 0 at πa/λ = π/3 (the spontaneous jump to full contact at zero load begins there)
    half_widths = np.linspace(1e-4, 0.4999, 20001)
    np.testing.assert_allclose(ref.johnson_sinusoid_load(half_widths, 1.0, 0.0), np.sin(np.pi * half_widths) ** 2)
    critical = 0.75 ** 0.75 * 0.5 ** 0.5
    loads = ref.johnson_sinusoid_load(half_widths, 1.0, critical)
    assert loads.max() == pytest.approx(0.0, abs=1e-8)
    assert half_widths[np.argmax(loads)] == pytest.approx(1 / 3, abs=1e-3)
    assert ref.johnson_sinusoid_load(half_widths, 1.0, 0.99 * critical).max() > 0


def test_maugis_cohesive_stress_inverts_the_parameter():
    # Maugis' λ = 2 σ0 (R / (π w K²))^(1/3) with K = 4E*/3: doubling λ doubles σ0, and σ0 ∝ E*^(2/3) w^(1/3) R^(-1/3)
    base = ref.maugis_cohesive_stress(1.0, 0.05, 1e-3, 1e6)
    assert ref.maugis_cohesive_stress(2.0, 0.05, 1e-3, 1e6) == pytest.approx(2 * base, rel=1e-14)
    assert ref.maugis_cohesive_stress(1.0, 0.4, 8e-3, 8e6) == pytest.approx(base * 4 * 2 / 2, rel=1e-14)
    assert base == pytest.approx(0.5 * (np.pi * 0.05 * (4e6 / 3) ** 2 / 1e-3) ** (1 / 3), rel=1e-14)
