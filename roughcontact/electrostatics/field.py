"""The field of the layered capacitor over a gap field: the stratum corneum and the insulator couple the columns.

The seed's law (Eq. 21) treats every pixel as an independent parallel-plate capacitor. Here the two solid
layers are slabs with their exact lateral response and only the air gap is local (``docs/guide/electrostatics.md``):

* the insulator (thickness ``d_i``, permittivity ``eps_i``) lies flat on the screen electrode (potential 0);
* the stratum corneum (``d_sc``, ``eps_sc``) has a uniform thickness under the conductive tissue (potential U),
  both its faces following the skin surface;
* the air gap g(x) ≥ 0 between them is a column per pixel (g = 0 at contact), with the derivative-expansion
  factor of a tilted gap, 1 + |∇g|²/3 on its capacitance (exact to second order in the slope).

Unknown: the flux density D(x) [C/m²], the normal electric displacement through the air column (positive
for U > 0). A flux mode D̂(q) raises the insulator's surface potential by D̂ tanh(q d_i) / (ε0 eps_i q) and
drops the stratum corneum's by D̂ tanh(q d_sc) / (ε0 eps_sc q) (a flat slab's exact Dirichlet-to-Neumann
operator; d/(ε0 eps) at q = 0); the column drops D g / (ε0 eps_a). The three drops add up to U:

    (M + R) D = U,   M̂(q) = [tanh(q d_sc)/(eps_sc q) + tanh(q d_i)/(eps_i q)] / ε0,   M̂(0) = c / ε0,
                     R = diag(g / (ε0 eps_a (1 + |∇g|²/3))),   c = d_sc/eps_sc + d_i/eps_i,

symmetric positive definite for every g ≥ 0 (contact needs no special case). The interaction energy per unit
area at fixed voltage is the minimum of a quadratic form,

    W(g) = min_D  ½⟨D (M + R) D⟩ − U⟨D⟩  =  −½ U ⟨D⟩,

and the attraction on the skin is its derivative per pixel area, σ_el = N ∂W/∂g = ½ Σ_k D_k² ∂R_k/∂g (virtual
work; D² / (2 ε0 eps_a) — the air-side Maxwell stress — where the gap is flat). For a uniform gap D = ε0 U / h(g)
and σ_el is Eq. 21 exactly. ``model="parallel_plate"`` replaces M by its uniform value c/ε0 and drops the
slope factor (no lateral coupling): Eq. 21 pixel by pixel, the seed's assumption. The slope factor matters
only where the gap varies over lengths of the gap itself: it moves the second-order response of a 10 µm
sinusoid at a 2 µm mean gap by 13 % and the attraction of resolved skin profiles by < 0.1 %
(``docs/guide/electrostatics.md``).

Periodic grids take the slabs' operator on the grid itself; a free window is zero-padded to twice its size per
free axis, with no flux outside the window (the skin far from the screen there).

A model of the contact line (``contact_line``, :mod:`~roughcontact.electrostatics.contact_line`) gives the line a
finite strength: :class:`~roughcontact.electrostatics.contact_line.AirBreakdown` caps the air field at the
breakdown field by the charge a discharge deposits on the insulator (the broken columns an active set, found by
primal–dual active-set sweeps of the same conjugate gradients),
:class:`~roughcontact.electrostatics.contact_line.RoughnessFilm` adds a film of air to every column.
"""
from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field as dataclass_field

import numpy as np
from numba import njit

from surfaces import Grid, HeightField
from surfaces.validation import check_choice, check_finite_array, check_integer, check_real

from ..fft import make_backend
from ..io.results import ConvergenceWarning
from .air import LateralAirField
from .contact_line import AirBreakdown, RoughnessFilm, check_contact_line
from .stack import EPSILON_0, DielectricStack, check_voltage

MODELS = ("layered", "parallel_plate")
#: the models of :func:`solve_field`: also the air's lateral field on fixed gaps (:mod:`.air`)
FIELD_MODELS = MODELS + ("layered_air",)
DEFAULT_TOL = 1e-10       # relative residual of the field solve ‖U − (M + R) D‖ / (U √n)
#: active-set sweeps of an air-breakdown field solve before it is said to stall (a warm start needs 1–3)
ACTIVE_SET_SWEEPS = 50


def _elastance(stack: DielectricStack, q: np.ndarray, model: str) -> np.ndarray:
    """M̂(q) ε0 [m]: the solid layers' air-equivalent thickness seen by the flux mode q (q = 0: c)."""
    if model == "parallel_plate":
        return np.full(q.shape, stack.dielectric_offset)
    return stack.elastance(q)


class StackField:
    """The operator M + R of one grid, built once (FFT plan, multiplier) and solved for many gap fields.

    ``grid`` gives shape, size and periodicity (a free axis is zero-padded to twice its length). Solutions are
    at unit voltage: D scales with U, the attraction with U².
    """

    def __init__(self, stack: DielectricStack, grid: Grid, model: str = "layered", backend: str = "pyfftw",
                 threads=None):
        if not isinstance(stack, DielectricStack):
            raise TypeError(f"stack must be a DielectricStack, got {type(stack).__name__}")
        if not isinstance(grid, Grid):
            raise TypeError(f"grid must be a surfaces.Grid, got {type(grid).__name__}")
        self.stack, self.grid = stack, grid
        self.model = check_choice("model", model, MODELS)
        self.padded_grid = Grid(tuple(n if p else 2 * n for n, p in zip(grid.shape, grid.periodic)),
                                tuple(length if p else 2 * length for length, p in zip(grid.lengths, grid.periodic)),
                                periodic=True)
        self.padded = self.padded_grid.shape != grid.shape
        q = np.hypot(*self.padded_grid.wavevectors(real=True))
        self._multiplier = _elastance(stack, q, model) / (EPSILON_0 * self.padded_grid.size)
        self._diagonal = float(np.mean(_elastance(stack, np.hypot(*self.padded_grid.wavevectors()), model))
                               / EPSILON_0)
        self._fft = make_backend(backend, self.padded_grid.shape, threads=threads)
        self._buffer = self._fft.empty()
        self._window = tuple(slice(0, n) for n in grid.shape)
        self._stencil = _stencil(grid, enabled=self.model == "layered")
        self._work = None
        self.active_set = None
        self.residual = None

    @property
    def pixel_elastance(self) -> float:
        """The diagonal of M [m²/F]: a pixel's own share of the solid layers' elastance (Jacobi preconditioner)."""
        return self._diagonal

    def apply_elastance(self, flux: np.ndarray, out: np.ndarray) -> np.ndarray:
        """out ← M D [V] for a flux D [C/m²] on the window (one FFT pair)."""
        if self.padded:
            self._buffer[...] = 0.0
            self._buffer[self._window] = flux
        else:
            self._buffer[...] = flux
        self._fft.forward(self._buffer)
        self._fft.spectrum *= self._multiplier
        self._fft.backward(self._buffer)
        out[...] = self._buffer[self._window]
        return out

    def slope_factor(self, gap: np.ndarray) -> np.ndarray:
        """1 + |∇g|²/3 per pixel (central differences; one-sided at a free window's edges); 1 for the plate."""
        factor = np.empty(gap.shape)
        _slope_factor_into(np.ascontiguousarray(gap, dtype=float), self._stencil, factor)
        return factor

    def column_elastance(self, gap: np.ndarray, factor=None) -> np.ndarray:
        """R = g / (ε0 eps_a (1 + |∇g|²/3)) [m²/F] per pixel: the air column's voltage per unit flux."""
        return gap / (EPSILON_0 * self.stack.eps_a * (self.slope_factor(gap) if factor is None else factor))

    def attraction(self, gap: np.ndarray, unit_flux: np.ndarray, factor=None) -> np.ndarray:
        """σ_el / U² = ½ Σ_k D₁,k² ∂R_k/∂g [Pa/V²] per pixel: the virtual work of opening the gap at each pixel
        at fixed voltage, for the unit-voltage flux D₁ of ``gap`` (``factor``: its slope factor, if known)."""
        out = np.empty(gap.shape)
        permittivity = EPSILON_0 * self.stack.eps_a
        _attraction_into(np.ascontiguousarray(gap, dtype=float), np.ascontiguousarray(unit_flux),
                         1.0 / (self.slope_factor(gap) if factor is None else factor), self._stencil,
                         0.5 / permittivity, -1.0 / (3.0 * permittivity), out)
        return out

    def solve_flux(self, gap, initial=None, tol: float = DEFAULT_TOL, maxiter=None) -> tuple:
        """The unit-voltage flux D₁ [C/m²/V] with (M + R) D₁ = 1 on the window, by Jacobi-preconditioned CG.

        ``initial`` is a warm start (a previous D₁). Returns ``(D₁, iterations, relative residual)``; the residual
        field 1 − (M + R) D₁ stays on ``self.residual``.
        """
        gap = check_finite_array("gap", gap, nonnegative=True)
        if gap.shape != self.grid.shape:
            raise ValueError(f"gap has shape {gap.shape}, the grid has {self.grid.shape}; they must match")
        tol = check_real("tol", tol, low=0.0, low_open=True)
        maxiter = None if maxiter is None else check_integer("maxiter", maxiter, low=1)
        return self.solve_columns(self.column_elastance(gap), initial, tol, maxiter)

    def solve_columns(self, column, initial=None, tol: float = DEFAULT_TOL, maxiter=None) -> tuple:
        """:meth:`solve_flux` for the column elastance R [m²/F] of a gap (checked and formed by the caller)."""
        maxiter = 10 * column.size if maxiter is None else maxiter
        if self.model == "parallel_plate":
            self.residual = np.zeros_like(column)
            return 1.0 / (self.stack.dielectric_offset / EPSILON_0 + column), 0, 0.0
        inverse_diagonal = 1.0 / (self._diagonal + column)
        flux = inverse_diagonal.copy() if initial is None else np.array(initial, dtype=float)
        iterations, residual = self.conjugate_gradients(column, inverse_diagonal, flux, tol, maxiter)
        return flux, iterations, residual

    def conjugate_gradients(self, column, inverse_diagonal, flux, tol: float, maxiter: int, rhs=None,
                            known_product: bool = False) -> tuple:
        """CG on (M + R) D₁ = 1 (or = ``rhs``) from ``flux`` (improved in place), preconditioned by
        ``inverse_diagonal`` = 1/(M_ii + R_ii); returns (iterations, relative residual ‖ρ₁‖/√n), the residual field
        ρ₁ on ``self.residual``. ``known_product``: the work array ``self.product`` holds M D₁ already (no FFT pair
        for the start)."""
        if self._work is None or self._work[0].shape != column.shape:
            self._work = tuple(np.empty(column.shape) for _ in range(4))       # allocated once per grid
        product, residual, z, direction = self._work
        if not known_product:
            self.apply_elastance(flux, product)
        rz, rr = cg_start(flux.reshape(-1), product.reshape(-1), column.reshape(-1), inverse_diagonal.reshape(-1),
                          residual.reshape(-1), z.reshape(-1), direction.reshape(-1),
                          None if rhs is None else rhs.reshape(-1))
        target = (tol * tol) * column.size
        iterations = 0
        while rr > target and iterations < maxiter:
            self.apply_elastance(direction, product)
            step = rz / cg_curvature(direction.reshape(-1), product.reshape(-1), column.reshape(-1))
            rz_old = rz
            rz, rr = cg_update(step, direction.reshape(-1), product.reshape(-1), flux.reshape(-1),
                                residual.reshape(-1), z.reshape(-1), inverse_diagonal.reshape(-1))
            cg_direction(direction.reshape(-1), z.reshape(-1), rz / rz_old)
            iterations += 1
        self.residual = residual
        return iterations, float(np.sqrt(rr / column.size))

    @property
    def product(self) -> np.ndarray:
        """The CG's work array of products M p (:meth:`conjugate_gradients`)."""
        return self._work[0]

    def active_set_solve(self, column, inverse_diagonal, inverse_factor, scale: float, gap, at_contact: bool, flux,
                         tol: float, maxiter: int) -> tuple:
        """The flux of the air-breakdown field (:class:`~roughcontact.electrostatics.contact_line.AirBreakdown`) at
        unit voltage, by primal–dual active-set sweeps from ``flux`` (improved in place).

        A column is broken where its flux D₁ exceeds D₁* = ε0 ε_a f E_bd/|U| (and, unless ``at_contact``, g > 0;
        ``inverse_factor`` 1/f, ``scale`` E_bd/|U|); a broken column drops E_bd g/|U| whatever its flux, an unbroken
        one R D₁ (``column`` R, ``inverse_diagonal`` 1/(M_ii + R)). Each sweep solves (M + R_u) D₁ = 1 − drop_b by
        CG for the present set (R_u: R of the unbroken columns, 0 of the broken; drop_b the broken columns' drops)
        and takes the set of its solution; the sweeps stop when the set repeats. This is the semismooth Newton
        method of the convex energy ½⟨D₁ M D₁⟩ + Σ ψ(D₁) − Σ D₁ whose column term ψ is ½ R D₁² below D₁* and
        continues linearly with slope E_bd g/|U| above it. While no column is broken the sweep is the plain field's
        solve, on its own arrays; a sweep after the first starts from M D₁ of the last one, rebuilt from its
        residual (rhs − ρ − R_u D₁: no FFT pair). Returns (CG iterations, sweeps, FFT pairs, relative residual,
        whether the set repeated, the system solved: None for the plain one, else ``self.active_set``, the reduced
        columns R_u, the right-hand side, 1/(M_ii + R_u) and the broken mask); the last sweep's residual field stays
        on ``self.residual``.
        """
        if self.active_set is None or self.active_set[0].shape != column.shape:
            self.active_set = tuple(np.empty(column.shape) for _ in range(3)) + (np.zeros(column.shape, np.bool_),)
        reduced, rhs, reduced_inverse, broken = (array.reshape(-1) for array in self.active_set)
        limits = (inverse_factor.reshape(-1), gap.reshape(-1), EPSILON_0 * self.stack.eps_a * scale, at_contact)
        broken[:] = False
        system = None if not _broken_changes(flux.reshape(-1), *limits, broken) else self.active_set
        if system is not None:
            _active_system_into(column.reshape(-1), flux.reshape(-1), *limits, scale, broken, reduced, rhs,
                                reduced_inverse, self._diagonal, flux.reshape(-1), flux.reshape(-1), False, False)
        iterations, pairs, residual = 0, 0, math.inf
        for sweep in range(1, ACTIVE_SET_SWEEPS + 1):
            matrix = (column, inverse_diagonal, None) if system is None else (system[0], system[2], system[1])
            steps, residual = self.conjugate_gradients(matrix[0], matrix[1], flux, tol, max(maxiter - iterations, 0),
                                                       matrix[2], known_product=sweep > 1)
            iterations += steps
            pairs += steps + (sweep == 1)
            if not _broken_changes(flux.reshape(-1), *limits, broken):
                return iterations, sweep, pairs, residual, True, system
            _active_system_into(column.reshape(-1), flux.reshape(-1), *limits, scale, broken, reduced, rhs,
                                reduced_inverse, self._diagonal, self.residual.reshape(-1), self.product.reshape(-1),
                                True, system is None)
            system = self.active_set
            if iterations >= maxiter:
                break
        return iterations, sweep, pairs, residual, False, system

    def solve_breakdown(self, gap, voltage: float, breakdown: AirBreakdown, tol: float = DEFAULT_TOL,
                        maxiter=None) -> tuple:
        """The air-breakdown field of ``gap`` [m] at ``voltage`` U [V] (:meth:`active_set_solve`, from the flux of the
        columns alone): ``(D₁, D₁ − ρ₁, CG iterations, sweeps, relative residual, whether the set repeated)`` with D₁
        the flux through the solid layers per volt and ρ₁ the deposited charge per volt [C/m²/V]."""
        gap = check_finite_array("gap", gap, nonnegative=True)
        if gap.shape != self.grid.shape:
            raise ValueError(f"gap has shape {gap.shape}, the grid has {self.grid.shape}; they must match")
        if self.model != "layered":
            raise ValueError(f"air breakdown needs model = 'layered', got {self.model!r}")
        maxiter = 10 * gap.size if maxiter is None else check_integer("maxiter", maxiter, low=1)
        factor = self.slope_factor(gap)
        column = self.column_elastance(gap, factor)
        flux = 1.0 / (self._diagonal + column)
        scale, inverse_factor = breakdown.field / abs(voltage), 1.0 / factor
        iterations, sweeps, _, residual, settled, _ = self.active_set_solve(
            column, flux.copy(), inverse_factor, scale, gap, breakdown.at_contact, flux, tol, maxiter)
        field_scale = EPSILON_0 * self.stack.eps_a * scale      # the broken columns as _is_broken finds them
        broken = (flux * inverse_factor > field_scale) & (breakdown.at_contact | (gap > 0))
        air = np.where(broken, field_scale / inverse_factor, flux)
        return flux, air, iterations, sweeps, residual, settled


def _stencil(grid: Grid, enabled: bool) -> tuple:
    """The central differences of the slope factor per axis: (ahead, behind) neighbour indices and 1/width [1/m]
    (periodic axes wrap, a free axis takes one-sided differences at its ends); an axis of at most two pixels,
    or ``enabled`` false, has 1/width = 0 (no slope)."""
    stencil = []
    for n, spacing, periodic in zip(grid.shape, grid.spacing, grid.periodic):
        index = np.arange(n)
        ahead, behind = (index + 1) % n, (index - 1) % n
        if not periodic:
            ahead[-1], behind[0] = n - 1, 0
        inverse_width = 1.0 / ((ahead - behind) % n * spacing) if n > 2 and enabled else np.zeros(n)
        stencil += [ahead, behind, inverse_width]
    return tuple(stencil)


THIRD = 1.0 / 3.0


@njit(cache=True)
def _slope_squares_into(gap, stencil, out):
    """out ← |∇g|² by the central differences of ``stencil`` (:func:`_stencil`), row by row: the x neighbours are
    whole rows, the y neighbours of a row's inner pixels its own next ones (contiguous, so the loops vectorise);
    only each row's two end pixels take the stencil's indices (the wrap of a periodic axis, the one-sided
    differences of a free one)."""
    ahead_x, behind_x, inverse_x, ahead_y, behind_y, inverse_y = stencil
    nx, ny = gap.shape
    inner = inverse_y[1] if ny > 2 else 0.0
    for i in range(nx):
        row, up, down, squares, width = gap[i], gap[ahead_x[i]], gap[behind_x[i]], out[i], inverse_x[i]
        for j in range(ny):
            slope = (up[j] - down[j]) * width
            squares[j] = slope * slope
        for j in range(1, ny - 1):
            slope = (row[j + 1] - row[j - 1]) * inner
            squares[j] += slope * slope
        for j in (0, ny - 1):
            slope = (row[ahead_y[j]] - row[behind_y[j]]) * inverse_y[j]
            squares[j] += slope * slope


@njit(cache=True)
def _slope_factor_into(gap, stencil, factor):
    """factor ← f = 1 + |∇g|²/3 (:func:`_slope_squares_into`)."""
    _slope_squares_into(gap, stencil, factor)
    for i in range(gap.shape[0]):
        row = factor[i]
        for j in range(gap.shape[1]):
            row[j] = 1.0 + row[j] * THIRD


@njit(cache=True)
def _attraction_into(gap, flux, inverse_factor, stencil, own, slope, out):
    """out ← own D²/f + Aᵀ(w A g) with w = slope D² g/f² (A the central differences of ``stencil``): with
    own = 1/(2ε) and slope = −1/(3ε), ½ Σ_k D_k² ∂R_k/∂g per pixel for R = g/(ε f) (the column's own D²/(2 ε f)
    and its neighbours' through their slopes). Multiplications only; row by row, each neighbour sum a contiguous
    pass (the y terms of a row's inner pixels shifted by one, its two end pixels by the stencil's indices)."""
    ahead_x, behind_x, inverse_x, ahead_y, behind_y, inverse_y = stencil
    nx, ny = gap.shape
    inner = inverse_y[1] * inverse_y[1] if ny > 2 else 0.0
    weight, along = np.empty(ny), np.empty(ny)
    for i in range(nx):
        target, d, f = out[i], flux[i], inverse_factor[i]
        for j in range(ny):
            target[j] = own * d[j] * d[j] * f[j]
    for i in range(nx):
        row, d, f = gap[i], flux[i], inverse_factor[i]
        up, down, width = gap[ahead_x[i]], gap[behind_x[i]], inverse_x[i] * inverse_x[i]
        for j in range(ny):
            weight[j] = slope * d[j] * d[j] * row[j] * f[j] * f[j]
        target = out[ahead_x[i]]                        # the x neighbours: whole rows
        for j in range(ny):
            target[j] += weight[j] * (up[j] - down[j]) * width
        target = out[behind_x[i]]
        for j in range(ny):
            target[j] -= weight[j] * (up[j] - down[j]) * width
        for j in range(1, ny - 1):                      # the y neighbours of the row's own pixels
            along[j] = weight[j] * (row[j + 1] - row[j - 1]) * inner
        for j in (0, ny - 1):
            along[j] = weight[j] * (row[ahead_y[j]] - row[behind_y[j]]) * (inverse_y[j] * inverse_y[j])
        target = out[i]
        for j in range(ny - 1):                         # ahead_y[j] = j + 1 below the last pixel
            target[j + 1] += along[j]
        for j in range(1, ny):                          # behind_y[j] = j − 1 above the first
            target[j - 1] -= along[j]
        target[ahead_y[ny - 1]] += along[ny - 1]
        target[behind_y[0]] -= along[0]


@njit(cache=True)
def _law_start_into(gap, stencil, inverse_permittivity, diagonal, warm, start_column, start_flux, inverse_factor,
                    column, inverse_diagonal, flux):
    """1/f, the column R = g/(ε f), 1/(M_ii + R_ii) and the starting flux of :class:`FieldLaw` in one pass: the
    start's flux updated column by column to first order, δD ≈ −δR D/(M_ii + R_ii), where ``warm``, else
    D = 1/(M_ii + R_ii). One division per pixel: with a = g/ε and b = M_ii f + a, 1/f = b/(f b) and
    1/(M_ii + R_ii) = f/b = f²/(f b)."""
    _slope_squares_into(gap, stencil, inverse_factor)
    nx, ny = gap.shape
    for i in range(nx):
        g, inverse_f, columns, inverse, d = gap[i], inverse_factor[i], column[i], inverse_diagonal[i], flux[i]
        old_column, old_flux = start_column[i], start_flux[i]
        for j in range(ny):
            f = 1.0 + inverse_f[j] * THIRD              # (the row holds |∇g|² until it takes 1/f)
            a = g[j] * inverse_permittivity
            b = diagonal * f + a
            reciprocal = 1.0 / (f * b)
            inverse_f[j] = b * reciprocal
            columns[j] = a * b * reciprocal
            inverse[j] = f * f * reciprocal
        if warm:
            for j in range(ny):
                d[j] = old_flux[j] * (diagonal + old_column[j]) * inverse[j]
        else:
            for j in range(ny):
                d[j] = inverse[j]


@njit(cache=True)
def _law_outputs_into(gap, flux, inverse_factor, column, inverse_diagonal, residual, stencil, inverse_permittivity,
                      squared_voltage, traction, stiffness, flux_out, column_out):
    """traction −U² σ_el/U², stiffness U² (D₁/(ε f))² / (M_ii + R_ii), the flux and the columns into the solver's
    arrays; returns Σ D₁ + Σ D₁ ρ₁ (the energy's sum, ρ₁ the residual)."""
    _attraction_into(gap, flux, inverse_factor, stencil, -0.5 * squared_voltage * inverse_permittivity,
                     squared_voltage * inverse_permittivity / 3.0, traction)
    total = 0.0
    nx, ny = gap.shape
    for i in range(nx):
        for j in range(ny):
            d = flux[i, j]
            column_field = d * inverse_permittivity * inverse_factor[i, j]
            stiffness[i, j] = squared_voltage * column_field * column_field * inverse_diagonal[i, j]
            flux_out[i, j] = d
            column_out[i, j] = column[i, j]
            total += d + d * residual[i, j]
    return total


@njit(cache=True)
def cg_start(flux, product, column, inverse_diagonal, residual, z, direction, rhs=None):
    """residual ← 1 − (M D + R D) (``product`` holds M D; ``rhs`` in place of 1 where given), z = direction ←
    P⁻¹ residual; returns (r·z, r·r)."""
    rz, rr = 0.0, 0.0
    for i in range(flux.size):
        value = (1.0 if rhs is None else rhs[i]) - product[i] - column[i] * flux[i]
        residual[i] = value
        z[i] = direction[i] = inverse_diagonal[i] * value
        rz += value * z[i]
        rr += value * value
    return rz, rr


@njit(cache=True)
def _is_broken(flux, inverse_factor, gap, field_scale, at_contact) -> bool:
    """Whether a column's air is broken down: D₁ > D₁* = ``field_scale``/(1/f) (field_scale = ε0 ε_a E_bd/|U|), and
    g > 0 unless ``at_contact``."""
    return flux * inverse_factor > field_scale and (at_contact or gap > 0.0)


@njit(cache=True)
def _broken_changes(flux, inverse_factor, gap, field_scale, at_contact, broken):
    """How many columns of ``flux`` changed sides against the set ``broken``, which takes the new sides
    (:func:`_is_broken`). Reads three arrays: the sweeps' light check."""
    changes = 0
    for i in range(flux.size):
        now = _is_broken(flux[i], inverse_factor[i], gap[i], field_scale, at_contact)
        if now != broken[i]:
            changes += 1
            broken[i] = now
    return changes


@njit(cache=True)
def _active_system_into(column, flux, inverse_factor, gap, field_scale, at_contact, drop_scale, broken, reduced,
                        rhs, inverse_diagonal, diagonal, residual, product, rebuild, from_plain):
    """The system of the set ``broken``: R_u (0 where broken, else ``column`` R), the right-hand side
    1 − ``drop_scale``·g (1 where unbroken) and 1/(M_ii + R_u). With ``rebuild`` (after a sweep) first ``product`` ←
    M D₁ = rhs − ``residual`` − R_u D₁ of the sweep's system (``from_plain``: the plain one, rhs 1 and R), the next
    sweep's start."""
    for i in range(flux.size):
        if rebuild:
            product[i] = (1.0 - residual[i] - column[i] * flux[i] if from_plain
                          else rhs[i] - residual[i] - reduced[i] * flux[i])
        if broken[i]:
            reduced[i] = 0.0
            rhs[i] = 1.0 - drop_scale * gap[i]
        else:
            reduced[i] = column[i]
            rhs[i] = 1.0
        inverse_diagonal[i] = 1.0 / (diagonal + reduced[i])


@njit(cache=True)
def _breakdown_outputs_into(gap, flux, inverse_factor, column, inverse_diagonal, field_scale, drop_scale, residual,
                            rhs, reduced, plain, accepted_charge, at_contact, inverse_permittivity, squared_voltage,
                            stiffness, flux_out, column_out, air, charge):
    """The air-breakdown field's pointwise outputs (:class:`FieldLaw`): the air flux D₁ − ρ₁ and the charge ρ₁ (D₁*
    = ``field_scale``·f where :func:`_is_broken`, the broken drop ``drop_scale``·g), the stiffness
    U² (D₁/(ε f))²/(M_ii + R) of the unbroken columns (0 of the broken: their Maxwell stress does not follow the
    gap; the merit's curvature there,
    E_bd²/M_ii, is that of the saturating air's energy, which the attraction is not, and taken as the model's
    curvature it sends the solve round a cycle), the flux and the columns; returns (the energy sum
    Σ ½ D₁ (M D₁) + ψ(D₁) − D₁ with M D₁ = rhs − ρ − R_u D₁ from the last sweep's residual ρ (``plain``: its
    system was the plain field's, rhs 1 and R), Σ ρ₁ drop, Σ ρ̄₁ drop for the ``accepted_charge`` ρ̄₁)."""
    energy, credit, accepted_credit = 0.0, 0.0, 0.0
    nx, ny = gap.shape
    for i in range(nx):
        for j in range(ny):
            d = flux[i, j]
            drop = drop_scale * gap[i, j]
            broken = _is_broken(d, inverse_factor[i, j], gap[i, j], field_scale, at_contact)
            a = field_scale / inverse_factor[i, j] if broken else d
            rho = d - a
            if plain:
                product = 1.0 - residual[i, j] - column[i, j] * d
            else:
                product = rhs[i, j] - residual[i, j] - reduced[i, j] * d
            energy += 0.5 * d * product + drop * rho + 0.5 * column[i, j] * a * a - d
            credit += rho * drop
            accepted_credit += accepted_charge[i, j] * drop
            field = a * inverse_permittivity * inverse_factor[i, j]
            stiffness[i, j] = 0.0 if broken else squared_voltage * field * field * inverse_diagonal[i, j]
            flux_out[i, j] = d
            column_out[i, j] = column[i, j]
            air[i, j] = a
            charge[i, j] = rho
    return energy, credit, accepted_credit


@njit(cache=True)
def cg_curvature(direction, product, column):
    """product ← M p + R p (``product`` holds M p); returns p·(M + R) p."""
    total = 0.0
    for i in range(direction.size):
        product[i] += column[i] * direction[i]
        total += direction[i] * product[i]
    return total


@njit(cache=True)
def cg_update(step, direction, product, flux, residual, z, inverse_diagonal):
    """D += α p, r −= α (M + R) p, z ← P⁻¹ r; returns (r·z, r·r)."""
    rz, rr = 0.0, 0.0
    for i in range(flux.size):
        flux[i] += step * direction[i]
        value = residual[i] - step * product[i]
        residual[i] = value
        z[i] = inverse_diagonal[i] * value
        rz += value * z[i]
        rr += value * value
    return rz, rr


@njit(cache=True)
def cg_direction(direction, z, beta):
    """direction ← z + β direction (the next conjugate direction)."""
    for i in range(direction.size):
        direction[i] = z[i] + beta * direction[i]


@dataclass(frozen=True)
class FieldSolution:
    """The field of the stack over one gap field at one voltage (``solve_field``). SI units.

    ``flux`` D [C/m²] (through the air column; for ``"layered_air"`` the flux leaving the stratum corneum; with
    air breakdown the flux through the solid layers, the air's being D − ``charge``) and ``attraction`` σ_el [Pa]
    (N ∂W/∂g; with air breakdown the Maxwell stress, :class:`AirBreakdown`) per pixel, shaped like the gap given;
    ``traction`` −σ_el in the contact solver's convention (positive compressive). ``mean_attraction`` and
    ``energy`` (W = −½ U ⟨D⟩ [J/m²]) are averages over the window (the apparent area). ``contact_line`` is the
    model of the contact line solved with, ``charge`` the surface charge ρ [C/m²] that air breakdown deposits on
    the insulator (None without breakdown).
    """

    model: str
    voltage: float
    stack: DielectricStack
    grid: Grid
    flux: np.ndarray
    attraction: np.ndarray
    iterations: int
    residual: float
    contact_line: object = dataclass_field(default=None, kw_only=True)
    charge: np.ndarray | None = dataclass_field(default=None, kw_only=True)

    @property
    def traction(self) -> np.ndarray:
        """−σ_el [Pa]: the attraction as a traction on the skin (positive compressive)."""
        return -self.attraction

    @property
    def mean_attraction(self) -> float:
        """⟨σ_el⟩ [Pa] over the window: F_el / A0."""
        return float(np.mean(self.attraction))

    @property
    def electrostatic_force(self) -> float:
        """F_el = ⟨σ_el⟩ A0 [N] on the window (per unit length [N/m] for a profile: ⟨σ_el⟩ L)."""
        length_x, length_y = self.grid.lengths
        return self.mean_attraction * (length_x if self.grid.is_profile else length_x * length_y)

    @property
    def energy(self) -> float:
        """W = −½ U ⟨D⟩ [J/m²]: the interaction energy per unit area at fixed voltage (−w of Eq. 22). Air breakdown
        has none (its discharges dissipate): ``ValueError``."""
        if isinstance(self.contact_line, AirBreakdown):
            raise ValueError("a field with air breakdown has no interaction energy: the discharges that deposit its "
                             "charge dissipate (roughcontact.electrostatics.contact_line.AirBreakdown)")
        return float(-0.5 * self.voltage * np.mean(self.flux))

    @property
    def field_equivalent_gap(self) -> float:
        """The uniform gap d [m] whose Eq. 21 attraction equals ⟨σ_el⟩ (independent of the voltage).

        Negative where the mean attraction exceeds full contact's (Eq. 23); ``nan`` only at U = 0 (no field).
        """
        if self.voltage == 0.0:
            return float("nan")
        return self.stack.gap_for_attraction(self.mean_attraction, self.voltage)


def solve_field(stack: DielectricStack, gap, lengths=None, voltage: float = 1.0, model: str = "layered",
                periodic=True, tol: float = DEFAULT_TOL, maxiter=None, backend: str = "pyfftw",
                contact_line=None) -> FieldSolution:
    """The field of ``stack`` over the air-gap field ``gap`` [m] at ``voltage`` U [V] (module docstring).

    ``gap`` is a 1-D profile or a 2-D field [m] (g ≥ 0), or a :class:`~surfaces.HeightField` (its grid then
    gives ``lengths`` and ``periodic``). ``lengths`` is the window's size [m] (a scalar for a profile);
    ``periodic`` a bool or one per axis (a free axis is zero-padded). ``model`` is ``"layered"`` (the slabs'
    lateral field, air columns: the law inside the contact solve), ``"layered_air"`` (also the air's own lateral
    field, periodic grids only: :mod:`~roughcontact.electrostatics.air`) or ``"parallel_plate"`` (Eq. 21 per
    pixel). ``tol`` bounds the field solve's relative residual. ``contact_line`` is None, a
    :class:`~roughcontact.electrostatics.contact_line.RoughnessFilm` (any model: the gap seen is g + t) or an
    :class:`~roughcontact.electrostatics.contact_line.AirBreakdown` (``model="layered"``).
    """
    shape = np.shape(gap.heights if isinstance(gap, HeightField) else gap)
    grid, gap = grid_and_gap(gap, lengths, periodic)
    voltage = check_voltage(voltage)
    model = check_choice("model", model, FIELD_MODELS)
    tol = check_real("tol", tol, low=0.0, low_open=True)
    maxiter = None if maxiter is None else check_integer("maxiter", maxiter, low=1)
    contact_line = check_contact_line(contact_line)
    if isinstance(contact_line, RoughnessFilm):
        gap = gap + contact_line.thickness
    charge = None
    if isinstance(contact_line, AirBreakdown):
        if model != "layered":
            raise ValueError(f"air breakdown (contact_line = {contact_line!r}) needs model = 'layered', got "
                             f"model = {model!r}")
        flux, attraction, charge, iterations, residual = _breakdown_field(stack, grid, gap, voltage, contact_line,
                                                                          tol, maxiter, backend)
    elif model == "layered_air":
        flux, attraction, iterations, residual = LateralAirField(stack, grid, backend=backend).solve_flux(
            gap, voltage, tol, maxiter)
    else:
        field = StackField(stack, grid, model=model, backend=backend, threads=1)
        unit_flux, iterations, residual = field.solve_flux(gap, tol=tol, maxiter=maxiter)
        flux, attraction = voltage * unit_flux, voltage ** 2 * field.attraction(gap, unit_flux)
    if residual > tol:
        warnings.warn(f"field solve stopped at relative residual {residual:.3g} > tol = {tol:g} after "
                      f"{iterations} iterations", ConvergenceWarning, stacklevel=2)
    return FieldSolution(model=model, voltage=voltage, stack=stack, grid=grid, flux=flux.reshape(shape),
                         attraction=attraction.reshape(shape), iterations=iterations, residual=residual,
                         contact_line=contact_line, charge=None if charge is None else charge.reshape(shape))


def _breakdown_field(stack, grid, gap, voltage, breakdown, tol, maxiter, backend) -> tuple:
    """(D, σ_el, ρ, CG iterations, relative residual) of the air-breakdown field at ``voltage`` (zero at 0 V); a
    field whose broken set did not settle is reported by its residual (inf)."""
    if voltage == 0.0:
        zeros = np.zeros(gap.shape)
        return zeros, zeros.copy(), zeros.copy(), 0, 0.0
    field = StackField(stack, grid, backend=backend, threads=1)
    unit_flux, air, iterations, sweeps, residual, settled = field.solve_breakdown(gap, voltage, breakdown, tol,
                                                                                  maxiter)
    if not settled:
        warnings.warn(f"the air-breakdown field's broken set did not settle in {sweeps} sweeps", ConvergenceWarning,
                      stacklevel=3)
    attraction = voltage ** 2 * field.attraction(gap, air)
    if breakdown.traction == "energy":
        attraction += breakdown.field * abs(voltage) * (unit_flux - air)
    return voltage * unit_flux, attraction, voltage * (unit_flux - air), iterations, residual if settled else math.inf


def grid_and_gap(gap, lengths, periodic) -> tuple:
    """(Grid, 2-D gap array) from a HeightField or an array with its window ``lengths`` and ``periodic``."""
    if isinstance(gap, HeightField):
        if lengths is not None:
            raise ValueError("lengths is given by the HeightField's grid; pass lengths=None")
        return gap.grid, np.asarray(gap.heights, dtype=float)
    values = check_finite_array("gap", gap, nonnegative=True)
    if values.ndim == 1:
        values = values[:, None]
    if values.ndim != 2:
        raise ValueError(f"gap must be a 1-D profile or a 2-D field, got {values.ndim} dimensions")
    if values.size == 0:
        raise ValueError(f"gap must have at least one pixel per axis, got shape {values.shape}")
    if lengths is None:
        raise ValueError("lengths (the window's size in m) is required for a gap array")
    if np.ndim(lengths) == 0:
        length = check_real("lengths", lengths, low=0.0, low_open=True)
        lengths = (length, length / values.shape[0]) if values.shape[1] == 1 else (length, length)
    periodic = (periodic, True) if values.shape[1] == 1 and np.ndim(periodic) == 0 else periodic
    return Grid(values.shape, tuple(lengths), periodic=periodic), values


class FieldSolveStalled(FloatingPointError):
    """A field solve of :class:`FieldLaw` did not reach its tolerance: the contact solver reports it (not converged,
    warned) with the last accepted state. ``energy`` is Σ V [J/m² per pixel, summed] of the flux the solve reached,
    whose traction, stiffness and flux :meth:`FieldLaw.evaluate` wrote as for a solved field (None where nothing
    was written)."""

    def __init__(self, message: str, energy: float | None = None):
        super().__init__(message)
        self.energy = energy


class FieldLaw:
    """The layered attraction as a non-local interaction law on one grid, for the energy-based contact solver.

    :meth:`evaluate` solves the field at a gap (warm-started from a previous flux) and returns the interaction
    energy Σ V = N Φ(D) with Φ(D) = ½⟨D (M + R) D⟩ − U⟨D⟩, exact to second order in the field solve's error
    (and never below the exact minimum), the traction p_int = −σ_el (:meth:`StackField.attraction`) and the
    diagonal stiffness k = ∂p_int/∂g ≈ G_ii (D ∂R_ii/∂g_i)², with G_ii ≈ 1/(M_ii + R_ii) (exact for the
    parallel plate).

    ``contact_line`` (:mod:`~roughcontact.electrostatics.contact_line`): a :class:`RoughnessFilm` evaluates the law
    at g + t. With :class:`AirBreakdown` the field is the minimiser of the saturating air's convex energy
    H = ½⟨D M D⟩ + Σ ψ(D) − U⟨D⟩ (:meth:`StackField.active_set_solve`) and the traction its Maxwell stress, which is
    not the derivative of an energy: ∂H/∂g_i exceeds it by E_bd ρ_i, the work a discharge dissipates per unit
    opening. The solver's line search then runs on a merit that has the traction as its gradient at the accepted
    gap, N [H(g) − E_bd ⟨ρ̄ g⟩] + C, with ρ̄ the charge of the accepted gap; the constant C keeps the merit
    continuous from one accepted gap to the next (it sums the work E_bd g Δρ̄ of the charge deposited at each
    accepted gap), so that each line search starts where the last one ended. An evaluation is accepted when the
    solver starts the next from its arrays (``start``): the solver passes the accepted evaluation's columns and
    flux. Σ V returned is that merit, not an energy. ``traction="energy"`` returns N H itself and its derivative.
    """

    def __init__(self, stack: DielectricStack, voltage: float, grid: Grid, tol: float = DEFAULT_TOL,
                 backend: str = "pyfftw", threads=None, contact_line=None):
        self.field = StackField(stack, grid, model="layered", backend=backend, threads=threads)
        self.voltage, self.tol = float(voltage), tol
        self.contact_line = check_contact_line(contact_line)
        self._work = tuple(np.zeros(grid.shape) for _ in range(4))   # 1/f, R, 1/(M_ii + R_ii), D₁
        self._film = np.empty(grid.shape) if isinstance(self.contact_line, RoughnessFilm) else None
        self._breakdown = None
        if isinstance(self.contact_line, AirBreakdown) and self.voltage != 0.0:
            # D₁ − ρ₁, and ρ₁ of the last evaluation and of the accepted one
            self._breakdown = tuple(np.zeros(grid.shape) for _ in range(3))
            self._last = None                  # (address of the last evaluation's flux output, its merit, its own)
            self._offset = 0.0
        self.fft_pairs = 0                     # over all evaluations: one per CG iteration and per start
        self.evaluations = 0

    def evaluate(self, gap, traction, stiffness, flux, columns, start=None) -> float:
        """traction, stiffness, the unit-voltage flux and the column elastance (grid-shaped) ← the law at
        ``gap``; returns Σ V [J/m² per pixel, summed].

        ``start``: (columns, flux) of a nearby evaluation, whose flux starts the field solve (with air breakdown:
        the accepted evaluation's). A solve that misses ``tol`` (or whose residual is not a number; with air
        breakdown also one whose broken set did not settle) writes the flux it reached and raises
        :class:`FieldSolveStalled` with its Σ V."""
        field, work = self.field, self._work
        if self._film is not None:
            gap = np.add(gap, self.contact_line.thickness, out=self._film)
        inverse_permittivity = 1.0 / (EPSILON_0 * field.stack.eps_a)
        start_column, start_flux = (work[1], work[3]) if start is None else start
        if self._breakdown is not None:
            self._accept(start)
        _law_start_into(gap, field._stencil, inverse_permittivity, field.pixel_elastance, start is not None,
                        start_column, start_flux, *work)
        inverse_factor, column, inverse_diagonal, unit_flux = work
        if self._breakdown is not None:
            return self._evaluate_breakdown(gap, traction, stiffness, flux, columns, start is None)
        iterations, residual = field.conjugate_gradients(column, inverse_diagonal, unit_flux, self.tol,
                                                         10 * unit_flux.size)
        self.fft_pairs += iterations + 1
        self.evaluations += 1
        squared_voltage = self.voltage ** 2
        total = _law_outputs_into(gap, unit_flux, inverse_factor, column, inverse_diagonal, field.residual,
                                  field._stencil, inverse_permittivity, squared_voltage, traction, stiffness, flux,
                                  columns)
        # Φ = U² (−½⟨D₁⟩ − ½⟨D₁ ρ₁⟩) with ρ₁ = 1 − (M + R) D₁ the residual of the unit-voltage solve
        energy = -0.5 * squared_voltage * total
        if not residual <= self.tol:
            raise FieldSolveStalled(f"the layered field's solve stalled at relative residual {residual:.3g} "
                                    f"(tol {self.tol:g}) after {iterations} iterations", energy)
        return energy

    def _accept(self, start):
        """Air breakdown: where ``start`` holds the last evaluation's flux, the solver accepted that evaluation: its
        charge becomes the accepted one and the merit's constant keeps the merit continuous there."""
        if start is None or self._last is None or start[1].ctypes.data != self._last[0]:
            return
        air, charge, accepted = self._breakdown
        self._breakdown = (air, accepted, charge)
        self._offset = self._last[1] - self._last[2]

    def _evaluate_breakdown(self, gap, traction, stiffness, flux, columns, cold: bool) -> float:
        """:meth:`evaluate` with air breakdown from the start that ``work`` holds (class docstring)."""
        field, breakdown = self.field, self.contact_line
        inverse_factor, column, inverse_diagonal, unit_flux = self._work
        air, charge, accepted = self._breakdown
        inverse_permittivity = 1.0 / (EPSILON_0 * field.stack.eps_a)
        scale = breakdown.field / abs(self.voltage)
        iterations, sweeps, pairs, residual, settled, system = field.active_set_solve(
            column, inverse_diagonal, inverse_factor, scale, gap, breakdown.at_contact, unit_flux, self.tol,
            10 * unit_flux.size)
        self.fft_pairs += pairs
        self.evaluations += 1
        squared_voltage = self.voltage ** 2
        reduced, rhs = field.active_set[:2]
        energy, credit, accepted_credit = _breakdown_outputs_into(
            gap, unit_flux, inverse_factor, column, inverse_diagonal, EPSILON_0 * field.stack.eps_a * scale, scale,
            field.residual, rhs, reduced, system is None, accepted, breakdown.at_contact, inverse_permittivity,
            squared_voltage, stiffness, flux, columns, air, charge)
        _attraction_into(gap, air, inverse_factor, field._stencil, -0.5 * squared_voltage * inverse_permittivity,
                         squared_voltage * inverse_permittivity / 3.0, traction)
        if breakdown.traction == "energy":
            traction -= squared_voltage * scale * charge
            merit = own = squared_voltage * energy
        else:
            own = squared_voltage * (energy - credit)
            if cold:
                accepted[...] = charge
                self._offset, merit = 0.0, own
            else:
                merit = squared_voltage * (energy - accepted_credit) + self._offset
        self._last = (flux.ctypes.data, merit, own)
        if not (residual <= self.tol and settled):
            raise FieldSolveStalled(f"the air-breakdown field's solve stalled at relative residual {residual:.3g} "
                                    f"(tol {self.tol:g}) after {iterations} iterations and {sweeps} active-set "
                                    f"sweeps" + ("" if settled else " (the broken set did not settle)"), merit)
        return merit
