"""The layered stack with the air gap's own lateral field: the potential linear in z across the gap.

The production field model (:mod:`~roughcontact.electrostatics.field`) keeps the air gap as local columns, with
only the derivative-expansion slope factor 1 + |∇g|²/3. Where the gap varies over lengths comparable with the
gap itself the air also carries flux sideways; this module adds it, for fixed gap fields (``solve_field(...,
model="layered_air")``), as the measure of what the columns leave out (``docs/guide/electrostatics.md``).

Unknowns: the potentials of the insulator's surface φ_i(x) and of the stratum corneum's face φ_s(x) = φ_i + Δ;
the insulator and the stratum corneum are the same exact slabs as in the column model (K = ε q coth(q d) per
Fourier mode, ε/d at q = 0); the potential across the air is linear in z between them, so the air's energy per
unit area is the exact integral over the gap of that potential's |∇φ|²,

    ε0 ε_a/2 ∫₀^g |∇φ|² dz = ε0 ε_a/2 [Δ²/g + g Σ_α (a_α² + a_α b_α + b_α²/3)],
    a_α = ∂_α φ_i,   b_α = ∂_α Δ − Δ ∂_α g / g,

(α the lateral axes; the b² term holds the slope factor, Δ²|∇g|²/(3g)). The field energy at fixed voltage U,

    W(g) = min over φ_i, Δ of  ½⟨φ_i K_i φ_i⟩ + ½⟨(U − φ_s) K_sc (U − φ_s)⟩ + air,   Δ = 0 where g = 0,

is the column model's plus the air's lateral terms, and the attraction per pixel is σ_el = −N ∂W/∂g at the
minimum (its explicit derivative: the column term ε0 ε_a Δ²/(2g²), at contact the flux D²/(2 ε0 ε_a) that holds
Δ = 0, and the lateral terms' derivatives). On the grid the lateral terms sit on the edges between neighbouring
pixels (forward differences, g and Δ averaged onto the edge), a sum of squares: a² + ab + b²/3 =
(a + b/2)² + b²/12 ≥ 0, so the quadratic form stays positive definite. Exact for a uniform gap (Eq. 21); its
second-order response to a sinusoid is that of the linear air element, which approximates the exact slab's
q coth(q g) to O((q g)⁴) (``docs/validation/field_check.md``).

Solved by conjugate gradients preconditioned with the column model's exact inverse (one inner flux solve,
(M + R) D = M_sc f_s − M_i f_i, per outer step): tens of outer steps at sub-µm pixels, so this model is a
check on fixed gaps, not a law inside the contact solve. Periodic grids only.
"""
from __future__ import annotations

import numpy as np

from surfaces import Grid

from ..fft import make_backend
from .stack import EPSILON_0, DielectricStack, slab_elastance

#: relative residual of the inner column-model solves inside the preconditioner (it must act as a fixed operator)
INNER_TOL = 1e-13
#: outer conjugate-gradient steps before the solve is reported as stalled, and restarts from the last iterate
MAX_OUTER = 2000
RESTARTS = 4


class LateralAirField:
    """The stack's field with the air's lateral field on one periodic grid (module docstring).

    :meth:`solve_flux` returns, for a gap field [m] and a voltage [V], the flux leaving the stratum corneum D [C/m²]
    (so that W = −½ U ⟨D⟩ at fixed voltage), the attraction σ_el [Pa] per pixel, the outer steps and the relative
    residual.
    """

    def __init__(self, stack: DielectricStack, grid: Grid, backend: str = "pyfftw"):
        if not isinstance(stack, DielectricStack):
            raise TypeError(f"stack must be a DielectricStack, got {type(stack).__name__}")
        if not all(grid.periodic):
            raise ValueError(f"model 'layered_air' needs a periodic grid; got periodic={grid.periodic}")
        self.stack, self.grid = stack, grid
        q = np.hypot(*grid.wavevectors(real=True))
        insulator = slab_elastance(q, stack.d_i, stack.eps_i)
        stratum_corneum = slab_elastance(q, stack.d_sc, stack.eps_sc)
        n = grid.size
        self._elastance = (insulator / n, stratum_corneum / n, (insulator + stratum_corneum) / n)
        self._stiffness = (1 / (insulator * n), 1 / (stratum_corneum * n))
        full = np.hypot(*grid.wavevectors())
        self._pixel_elastance = float(np.mean(stack.elastance(full)))
        self._fft = make_backend(backend, grid.shape, threads=1)
        self._axes = [axis for axis, n_axis in enumerate(grid.shape) if n_axis > 2]

    def _fourier(self, multiplier, x) -> np.ndarray:
        out = np.empty(self.grid.shape)
        self._fft.forward(np.ascontiguousarray(x))
        self._fft.spectrum *= multiplier
        self._fft.backward(out)
        return out

    def _edges(self, gap) -> list:
        """Per lateral axis: (axis, spacing, ε_a g on the edge, ∂g/g on the edge (0 where the edge's g is 0))."""
        edges = []
        for axis in self._axes:
            ahead = np.roll(gap, -1, axis)
            edge_gap = 0.5 * (gap + ahead)
            spacing = self.grid.spacing[axis]
            safe = np.where(edge_gap > 0, edge_gap, 1.0)
            edges.append((axis, spacing, self.stack.eps_a * edge_gap,
                          np.where(edge_gap > 0, (ahead - gap) / (spacing * safe), 0.0)))
        return edges

    @staticmethod
    def _differences(axis, spacing, relative_slope, phi, delta) -> tuple:
        """a = ∂φ_i and b = ∂Δ − Δ ∂g/g on the edges of ``axis``."""
        delta_ahead = np.roll(delta, -1, axis)
        return ((np.roll(phi, -1, axis) - phi) / spacing,
                (delta_ahead - delta) / spacing - relative_slope * 0.5 * (delta + delta_ahead))

    def _lateral(self, edges, phi, delta) -> tuple:
        """The lateral terms' gradients with respect to φ_i and Δ (per pixel, × N/ε0)."""
        grad_phi, grad_delta = np.zeros(self.grid.shape), np.zeros(self.grid.shape)
        for axis, spacing, weight, relative_slope in edges:
            a, b = self._differences(axis, spacing, relative_slope, phi, delta)
            on_a, on_b = weight * (a + 0.5 * b), weight * (0.5 * a + b / 3)
            grad_phi += (np.roll(on_a, 1, axis) - on_a) / spacing
            scaled = relative_slope * on_b
            grad_delta += (np.roll(on_b, 1, axis) - on_b) / spacing - 0.5 * (scaled + np.roll(scaled, 1, axis))
        return grad_phi, grad_delta

    def solve_flux(self, gap: np.ndarray, voltage: float, tol: float, maxiter=None) -> tuple:
        """(D [C/m²], σ_el [Pa], outer steps, relative residual) of the gap field ``gap`` [m] (checked by the
        caller) at ``voltage`` [V]."""
        # scipy's CG only here: a fixed-gap check, so importing the field model does not load scipy.sparse
        from scipy.sparse.linalg import LinearOperator, cg
        shape, n = self.grid.shape, self.grid.size
        eps_a = self.stack.eps_a
        open_ = gap > 0
        column = np.where(open_, eps_a / np.where(open_, gap, 1.0), 0.0)     # ε_a/g: the column's capacitance/ε0
        resistance = gap / eps_a
        edges = self._edges(gap)
        stiff_i, stiff_sc = self._stiffness
        elastance_i, elastance_sc, elastance = self._elastance

        def apply(x):
            phi, delta = x[:n].reshape(shape), x[n:].reshape(shape)
            sc = self._fourier(stiff_sc, phi + delta)
            lateral_phi, lateral_delta = self._lateral(edges, phi, delta)
            out_phi = self._fourier(stiff_i, phi) + sc + lateral_phi
            out_delta = np.where(open_, sc + column * delta + lateral_delta, 0.0)
            return np.concatenate([out_phi.ravel(), out_delta.ravel()])

        inverse_diagonal = 1.0 / (self._pixel_elastance + resistance.ravel())
        inner = LinearOperator((n, n), dtype=float,
                               matvec=lambda d: (self._fourier(elastance, d.reshape(shape)) + resistance
                                                 * d.reshape(shape)).ravel())
        jacobi = LinearOperator((n, n), dtype=float, matvec=lambda r: inverse_diagonal * r)

        def precondition(r):          # the column model's exact inverse (module docstring)
            load_sc = np.where(open_, r[n:].reshape(shape), 0.0)
            load_i = r[:n].reshape(shape) - load_sc
            rhs = self._fourier(elastance_sc, load_sc) - self._fourier(elastance_i, load_i)
            flux, _ = cg(inner, rhs.ravel(), rtol=INNER_TOL, atol=0.0, M=jacobi, maxiter=10 * n)
            flux = flux.reshape(shape)
            phi = self._fourier(elastance_i, load_i + flux)
            phi_sc = self._fourier(elastance_sc, load_sc - flux)
            return np.concatenate([phi.ravel(), np.where(open_, phi_sc - phi, 0.0).ravel()])

        drive = voltage * self.stack.eps_sc / self.stack.d_sc          # K_sc U: the q = 0 stiffness times U
        rhs = np.concatenate([np.full(n, drive), np.where(open_, drive, 0.0).ravel()])
        operator = LinearOperator((2 * n, 2 * n), dtype=float, matvec=apply)
        preconditioner = LinearOperator((2 * n, 2 * n), dtype=float, matvec=precondition)
        maxiter = MAX_OUTER if maxiter is None else maxiter
        steps, solution, residual = [0], None, np.inf
        for _ in range(RESTARTS):       # CG stops on its recurred residual; restart until the true one is below tol
            solution, _ = cg(operator, rhs, x0=solution, rtol=tol, atol=0.0, M=preconditioner,
                             maxiter=maxiter - steps[0], callback=lambda _: steps.__setitem__(0, steps[0] + 1))
            residual = float(np.linalg.norm(rhs - apply(solution)) / np.linalg.norm(rhs))
            if residual <= tol or steps[0] >= maxiter:
                break
        phi, delta = solution[:n].reshape(shape), solution[n:].reshape(shape)
        flux_sc = self._fourier(stiff_sc, voltage - phi - delta)                  # K_sc (U − φ_s), × 1/ε0
        column_flux = flux_sc - self._lateral(edges, phi, delta)[1]             # the flux that holds Δ = 0 at contact
        safe = np.where(open_, gap, 1.0)
        attraction = np.where(open_, eps_a * delta ** 2 / (2 * safe ** 2), column_flux ** 2 / (2 * eps_a))
        attraction -= self._lateral_opening(edges, phi, delta)
        return EPSILON_0 * flux_sc, EPSILON_0 * attraction, steps[0], residual

    def _lateral_opening(self, edges, phi, delta) -> np.ndarray:
        """∂/∂g_k of the lateral terms at fixed potentials (× N/ε0): each edge's energy ½ w (a² + ab + b²/3)
        depends on g through its mean g_e (in w and in b) and its difference δg (in b)."""
        out = np.zeros(self.grid.shape)
        for axis, spacing, weight, relative_slope in edges:
            a, b = self._differences(axis, spacing, relative_slope, phi, delta)
            edge_delta = 0.5 * (delta + np.roll(delta, -1, axis))
            edge_gap = weight / self.stack.eps_a
            safe = np.where(edge_gap > 0, edge_gap, 1.0)
            along_b = (a + 2 * b / 3) * edge_delta          # ∂(a² + ab + b²/3)/∂b · Δ_e
            # ∂b/∂g_e = Δ_e (∂g/g)/g_e and ∂b/∂δg = −Δ_e/(h g_e), with w = ε_a g_e
            by_mean = np.where(edge_gap > 0, 0.5 * self.stack.eps_a * (a * a + a * b + b * b / 3)
                               + 0.5 * weight * along_b * relative_slope / safe, 0.0)
            by_difference = np.where(edge_gap > 0, -0.5 * self.stack.eps_a * along_b / spacing, 0.0)
            out += 0.5 * by_mean - by_difference + np.roll(0.5 * by_mean + by_difference, 1, axis)
        return out
