"""The contact-state check the solver tests share: complementarity on the raw gap, not on ``result.gap``.

``ContactResult.gap`` is clipped at 0 and zeroed wherever p > 0, so ``gap >= 0``, ``p·gap == 0`` and
``gap[contact] == 0`` hold on any result, converged or not. The raw gap ``g = s − h + u`` is rebuilt here from
the heights and the result's penetration (``s = max h − δ``) and displacement, so a wrong contact state fails.
"""
import numpy as np

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
    bound = TOL_FACTOR * result.params["tol"] * np.ptp(h)
    assert np.isfinite(result.pressure).all() and np.isfinite(result.displacement).all()
    assert (result.pressure >= 0).all()
    assert raw.min() >= -bound, f"interpenetration: raw gap {raw.min():.3g} m < -{bound:.3g} m"
    loaded = result.pressure > 0
    worst = np.abs(raw[loaded]).max(initial=0.0)
    assert worst <= bound, f"complementarity: raw gap {worst:.3g} m under pressure > {bound:.3g} m"
    np.testing.assert_allclose(result.gap[~result.contact], raw[~result.contact], rtol=0, atol=bound)
