"""Analytic reference solutions for frictionless contact of an elastic body (contact modulus E*) with a rigid
flat, used to validate the FFT boundary-element solver. SI units. Formulas and sources: docs/references.md §4.

* Hertz (sphere of radius R): Johnson (1985), Contact Mechanics, §4.2.
* Westergaard (1939) 1-D sinusoid h(x) = h0 cos(2πx/λ) (profile 2 h0 sin²(πx/λ) below its crest), plane strain:
  Johnson (1985) §13.2; mean gap and energy as in docs/references.md §4.1.
* Bi-sinusoid h0 cos(2πx/λ) cos(2πy/λ): Johnson, Greenwood & Higginson (1985), Int. J. Mech. Sci. 27:383;
  low- and high-load asymptotes of the contact area (docs/references.md §4.2).
"""
from __future__ import annotations

import numpy as np

from surfaces.validation import check_finite_array, check_positive


# -- Hertz ----------------------------------------------------------------------------------------------------
def hertz_contact_radius(force, radius, E_star):
    """Contact radius a = (3 F R / (4 E*))^(1/3) [m] for force F [N], sphere radius R [m], E* [Pa]."""
    return (3 * check_positive("force", force) * check_positive("radius", radius)
            / (4 * check_positive("E_star", E_star))) ** (1 / 3)


def hertz_penetration(force, radius, E_star):
    """Rigid approach δ = a²/R [m]."""
    return hertz_contact_radius(force, radius, E_star) ** 2 / radius


def hertz_force(penetration, radius, E_star):
    """Force F = (4/3) E* R^(1/2) δ^(3/2) [N] at penetration δ [m]."""
    return (4 / 3) * check_positive("E_star", E_star) * np.sqrt(check_positive("radius", radius)) \
        * check_positive("penetration", penetration) ** 1.5


def hertz_pressure(r, force, radius, E_star):
    """Pressure p(r) = p0 √(1 − r²/a²) inside r < a, 0 outside [Pa]; p0 = 3F/(2πa²)."""
    r = np.abs(check_finite_array("r", r))
    a = hertz_contact_radius(force, radius, E_star)
    p0 = 3 * force / (2 * np.pi * a ** 2)
    return p0 * np.sqrt(np.clip(1 - (r / a) ** 2, 0.0, None))


def hertz_elastic_energy(force, radius, E_star):
    """Stored elastic energy U = ½∫p u dA = (2/5) F δ [J] (= ∫F dδ = (8/15) E* R^(1/2) δ^(5/2))."""
    return 0.4 * force * hertz_penetration(force, radius, E_star)


# -- Westergaard 1-D sinusoid ---------------------------------------------------------------------------------
def westergaard_full_contact_pressure(amplitude, wavelength, E_star):
    """p* = π E* h0 / λ [Pa]: the mean pressure that flattens the sinusoid of amplitude h0 completely."""
    return np.pi * check_positive("E_star", E_star) * check_positive("amplitude", amplitude) \
        / check_positive("wavelength", wavelength)


def _load_fraction(mean_pressure, amplitude, wavelength, E_star):
    s = check_finite_array("mean_pressure", mean_pressure, nonnegative=True) \
        / westergaard_full_contact_pressure(amplitude, wavelength, E_star)
    return np.minimum(s, 1.0)


def westergaard_contact_half_width(mean_pressure, amplitude, wavelength, E_star):
    """Half-width a = (λ/π) arcsin √(p̄/p*) [m] of each contact strip (λ/2 at and beyond full contact)."""
    s = _load_fraction(mean_pressure, amplitude, wavelength, E_star)
    return wavelength / np.pi * np.arcsin(np.sqrt(s))


def westergaard_mean_gap(mean_pressure, amplitude, wavelength, E_star):
    """Mean gap ḡ = h0 [1 − s + s ln s], s = p̄/p* [m] (0 at full contact, 2 h0·½ = h0 at s → 0)."""
    s = _load_fraction(mean_pressure, amplitude, wavelength, E_star)
    return amplitude * (1 - s + np.where(s > 0, s * np.log(np.where(s > 0, s, 1.0)), 0.0))


def westergaard_pressure(x, mean_pressure, amplitude, wavelength, E_star):
    """Pressure p(x) [Pa] at distance x [m] from a contact centre (crest), for partial contact p̄ < p*.

    p = (2 p̄ cos(πx/λ) / sin²(πa/λ)) √(sin²(πa/λ) − sin²(πx/λ)) for |x| < a (periodic in λ), else 0.
    """
    x = check_finite_array("x", x)
    a = westergaard_contact_half_width(mean_pressure, amplitude, wavelength, E_star)
    x = (x + wavelength / 2) % wavelength - wavelength / 2        # nearest crest
    sin_a2 = np.sin(np.pi * a / wavelength) ** 2
    radicand = np.clip(sin_a2 - np.sin(np.pi * x / wavelength) ** 2, 0.0, None)
    return np.where(np.abs(x) < a, 2 * mean_pressure * np.cos(np.pi * x / wavelength) / sin_a2 * np.sqrt(radicand),
                    0.0)


def westergaard_elastic_energy_density(mean_pressure, amplitude, wavelength, E_star):
    """Elastic energy per unit area U/A = h0 p* (¼ − ½ ln s) s² [J/m²], s = p̄/p* ≤ 1 (docs/references.md §4.1)."""
    s = _load_fraction(mean_pressure, amplitude, wavelength, E_star)
    p_star = westergaard_full_contact_pressure(amplitude, wavelength, E_star)
    return amplitude * p_star * (0.25 - 0.5 * np.log(np.where(s > 0, s, 1.0))) * s ** 2


# -- bi-sinusoid ---------------------------------------------------------------------------------------------------
def bisinusoid_full_contact_pressure(amplitude, wavelength, E_star):
    """p* = √2 π E* Δ / λ [Pa] for h = Δ cos(2πx/λ) cos(2πy/λ) (Johnson, Greenwood & Higginson 1985)."""
    return np.sqrt(2) * np.pi * check_positive("E_star", E_star) * check_positive("amplitude", amplitude) \
        / check_positive("wavelength", wavelength)


def bisinusoid_area_low_load(load_fraction):
    """Low-load asymptote A/λ² = π (3/(8π))^(2/3) (p̄/p*)^(2/3) ≈ 0.7616 (p̄/p*)^(2/3) (independent Hertz peaks)."""
    s = check_finite_array("load_fraction", load_fraction, nonnegative=True)
    return np.pi * (3 / (8 * np.pi)) ** (2 / 3) * s ** (2 / 3)


def bisinusoid_area_near_full_contact(load_fraction):
    """Near-full-contact asymptote A/λ² = 1 − (3/(2π)) (1 − p̄/p*) (penny-shaped gaps at the valleys)."""
    s = check_finite_array("load_fraction", load_fraction, nonnegative=True)
    return 1 - 3 / (2 * np.pi) * (1 - s)


# -- adhesive contact -----------------------------------------------------------------------------------------
def maugis_cohesive_stress(maugis_lambda, work_of_adhesion, radius, E_star):
    """The Dugdale stress σ0 [Pa] of Maugis' λ = 2 σ0 (R / (π w K²))^(1/3), K = 4E*/3 (Maugis 1992;
    docs/references.md §4.4), for a sphere of radius R [m], work of adhesion w [J/m²] and contact modulus E* [Pa]."""
    K = 4 * check_positive("E_star", E_star) / 3
    return check_positive("maugis_lambda", maugis_lambda) / 2 * (
        np.pi * check_positive("work_of_adhesion", work_of_adhesion) * K ** 2 / check_positive("radius", radius)
    ) ** (1 / 3)


def maugis_dugdale_load(m, maugis_lambda):
    """Normalised load P̄ = F/(π w R) and contact radius Ā = a (K/(π w R²))^(1/3) of the Maugis–Dugdale sphere at
    the ratio m = c/a > 1 of the cohesive-zone and contact radii (Maugis 1992, Eqs. as in docs/references.md §4.4):
    ½λĀ²[μ + (m² − 2) atan μ] + (4/3)λ²Ā[μ atan μ − m + 1] = 1 solved for Ā > 0, μ = √(m² − 1);
    P̄ = Ā³ − λĀ²(μ + m² atan μ)."""
    m = np.asarray(m, dtype=float)
    lam = check_positive("maugis_lambda", maugis_lambda)
    mu = np.sqrt(m * m - 1)
    atan = np.arctan(mu)
    quadratic = 0.5 * lam * (mu + (m * m - 2) * atan)
    linear = (4 / 3) * lam ** 2 * (mu * atan - m + 1)
    area = 2 / (linear + np.sqrt(linear ** 2 + 4 * quadratic))       # the positive root, cancellation-free
    return area ** 3 - lam * area ** 2 * (mu + m * m * atan), area


def maugis_dugdale_pull_off(maugis_lambda):
    """Normalised pull-off load P̄ = F/(π w R) of the Maugis–Dugdale sphere under load control: the smallest load
    along the equilibrium curve (−2 in the DMT limit λ → 0, −3/2 in the JKR limit λ → ∞)."""
    from scipy.optimize import minimize_scalar

    log_m = np.linspace(-12, 8, 4001)              # m − 1 = e^x spans both limits
    loads = maugis_dugdale_load(1 + np.exp(log_m), maugis_lambda)[0]
    best = int(np.argmin(loads))
    low, high = log_m[max(best - 1, 0)], log_m[min(best + 1, log_m.size - 1)]
    found = minimize_scalar(lambda x: float(maugis_dugdale_load(1 + np.exp(x), maugis_lambda)[0]),
                            bounds=(low, high), method="bounded", options={"xatol": 1e-12})
    return float(min(found.fun, loads[best]))


def johnson_sinusoid_load(half_width, wavelength, alpha):
    """p̄/p* of Johnson's (1995) adhesive sinusoid in the JKR limit at the contact half-width a [m]:
    sin²(πa/λ) − α √tan(πa/λ), with p* = π E* h/λ and α = (√2/π)(λ/h)√(w/(E*λ)) (docs/references.md §4.5)."""
    phase = np.pi * np.asarray(half_width, dtype=float) / check_positive("wavelength", wavelength)
    return np.sin(phase) ** 2 - alpha * np.sqrt(np.tan(phase))
