"""The contact-state checks the solver tests share: complementarity on the raw gap, not on ``result.gap``.

``ContactResult.gap`` is clipped at 0 and zeroed wherever p > 0, so ``gap >= 0``, ``p·gap == 0`` and
``gap[contact] == 0`` hold on any result, converged or not. The raw gap ``g = s − h + u`` is rebuilt here from
the heights and the result's penetration (``s = max h − δ``) and displacement, so a wrong contact state fails.
"""
import numpy as np
import pytest

# The raw gap of a converged solve is the solver's residual: over the contact tests (test_contact_extremes,
# _westergaard, _rough.test_layered_contact; tol 1e-9 … 1e-12) |g| under pressure and −min g reach at most 2.0 × tol
# of the height range (Westergaard s = 0.95, tol 1e-10), so the bound is 10 × tol (margin 5). Two-step results
# leave 2.6e-4 (Westergaard) to 0.31 (layered) of the range: at least 2.6e5 times the bound at tol = 1e-10.
TOL_FACTOR = 10.0


def check_contact_state(heights, result):
    """Assert a physical contact state: finite p >= 0 and u; raw gap g >= 0 everywhere and g = 0 where p > 0
    (to TOL_FACTOR × the solve's tol × the height range); ``result.gap`` equal to g off the contact set."""
    h = np.asarray(getattr(heights, "heights", heights))
    raw = h.max() - result.penetration - h + result.displacement
    bound = TOL_FACTOR * result.solver.tol * np.ptp(h)
    assert np.isfinite(result.pressure).all() and np.isfinite(result.displacement).all()
    assert (result.pressure >= 0).all()
    assert raw.min() >= -bound, f"interpenetration: raw gap {raw.min():.3g} m < -{bound:.3g} m"
    loaded = result.pressure > 0
    worst = np.abs(raw[loaded]).max(initial=0.0)
    assert worst <= bound, f"complementarity: raw gap {worst:.3g} m under pressure > {bound:.3g} m"
    np.testing.assert_allclose(result.gap[~result.contact], raw[~result.contact], rtol=0, atol=bound)


def check_equilibrium(res, surface, half, tol_traction):
    """Force balance, u = K p, g = s − h + u ≥ 0 and complementarity from the result's raw fields; returns the
    largest traction imbalance on the open gap [Pa]."""
    atol = 1e-9 * np.ptp(surface.heights)
    recomputed = half.displacement(res.pressure) + half.uniform_compliance * res.mean_pressure
    np.testing.assert_allclose(res.displacement, recomputed, atol=atol)
    # the raw gap from the heights and u = K p recomputed here, not result.gap (clipped at 0, zeroed on contact)
    raw_gap = res.flat_position - surface.heights + recomputed
    np.testing.assert_allclose(res.gap, raw_gap, atol=atol)
    pressed = res.contact_pressure > tol_traction
    assert raw_gap.min() >= -atol, f"interpenetration: raw gap {raw_gap.min():.3g} m"
    assert np.abs(raw_gap[pressed]).max(initial=0.0) <= atol, "complementarity: the wall pushes across an open gap"
    assert res.contact_pressure.min() >= -tol_traction, f"the wall pulls: {res.contact_pressure.min():.3g} Pa"
    assert res.mean_pressure == pytest.approx(float(np.mean(res.pressure)), abs=1e-9 * abs(res.pressure).max())
    open_gap = ~res.contact
    return float(np.max(np.abs(res.pressure - res.interaction_traction)[open_gap], initial=0.0))
