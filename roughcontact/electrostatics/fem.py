"""Finite-element field solve of the full layered stack over a 1-D gap profile: the independent reference.

A 2-D x–z problem (``docs/field_check.md``): electrode at z = -d_i (potential 0), insulator (eps_i), air gap
0 < z < g(x) (eps_a), stratum corneum g(x) < z < g(x) + d_sc (eps_sc, uniform vertical thickness), tissue on
its top face (potential U); ``div(ε0 ε grad φ) = 0``, periodic in x or with field-parallel (zero-flux) side
walls. The mesh is terrain-following: every column of nodes has the same rows (uniform in the insulator and
the air, geometric in the stratum corneum from its lower face); each quad is cut into two P1 triangles. At a
contact column (g = 0) the air rows coincide and their nodes are merged into one unknown; the triangles of
zero area are dropped.

The attraction is the exact derivative of the discrete energy E = ½ uᵀ K u [J/m] (per unit depth) under a
rigid normal shift δ of the skin (stratum corneum and tissue nodes move by δ, air node r of n_a by δ r/n_a):
``σ̄ = -(1/L) dE/dδ``, positive = attractive (at fixed potentials the mechanical potential is -E; for a
uniform gap this is seed Eq. 21 exactly, because P1 holds the 1-D solution). With u fixed (virtual work),
``∂E_e/∂z_n = ½ ε0 ε A (|∇u|² ∂_z φ_n - 2 ∂_z u ∇φ_n·∇u)`` per triangle e and vertex n. At a contact column
the shift opens a new air layer: the one-sided derivative (δ -> 0+) of the energy of the unmerged mesh is, per
collapsed air row, the minimum over its limiting air field G of the zero-area triangles' energy per δ plus
the flux through the row times G/n_a (derivation in the docs). scikit-fem assembles; a sparse LU solves, or
optionally conjugate gradients preconditioned by pyamg's classical AMG. scikit-fem and pyamg are the optional
extra ``fieldcheck``, imported here lazily.
"""
from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np

from surfaces.validation import (check_choice, check_finite_array, check_integer, check_positive,
                                 check_real)

from .stack import EPSILON_0, DielectricStack


#: Gaps up to this fraction of the air-equivalent offset eps_a c are contact (merged air rows).
CONTACT_GAP = 1e-9


@dataclass(frozen=True)
class ProfileFieldSolution:
    """Field solve over a 1-D gap profile; SI units, per unit depth in y.

    ``mean_pressure`` σ̄ [Pa] (virtual work, positive = attraction), ``pressure`` the attraction per column
    [Pa] (the virtual work of moving one column of skin nodes, over its tributary width; its width-weighted
    mean is σ̄), ``x`` the column positions [m], ``gap`` the gap at the columns [m], ``energy`` E [J/m],
    ``nodes``, ``elements`` (triangles kept), ``unknowns``, and the solver's ``converged``, ``iterations`` and
    relative ``residual``. ``maxwell_pressure`` [Pa] is the independent air-side Maxwell traction on the
    skin per interval between columns (the field of the air triangle under it; the zero-area ones at contact
    take their limiting field), ``mean_maxwell_pressure`` its mean; it converges to σ̄ with the mesh.
    """

    mean_pressure: float
    pressure: np.ndarray
    x: np.ndarray
    gap: np.ndarray
    energy: float
    nodes: int
    elements: int
    unknowns: int
    converged: bool
    iterations: int
    residual: float
    maxwell_pressure: np.ndarray
    mean_maxwell_pressure: float


@dataclass(frozen=True)
class _Mesh:
    """Terrain-following mesh: node (column j, row k) has index ``j * rows + k``; ``column_of`` maps every
    node column to its unknowns' column (the periodic image of the last column is column 0)."""

    points: np.ndarray          # (2, nodes)
    velocity: np.ndarray        # dz/dδ per node
    triangles: np.ndarray       # (3, elements), vertex 0-1-2; vertices 0, 1 on the triangle's vertical edge
    permittivity: np.ndarray    # relative permittivity per triangle
    air_rows: range             # node rows of the air layer (insulator top ... stratum-corneum bottom)
    rows: int
    columns: int                # node columns (with the periodic image)
    period_columns: int         # distinct columns


def _stratum_corneum_rows(d_sc: float, first: float, count: int) -> np.ndarray:
    """Row heights above the stratum corneum's lower face: ``count`` rows from ``first`` growing geometrically
    to d_sc (uniform when ``count * first >= d_sc``)."""
    if count * first >= d_sc:
        return np.linspace(0.0, d_sc, count + 1)
    low, high = 1.0, 2.0
    while first * (high ** count - 1) / (high - 1) < d_sc:
        high *= 2
    for _ in range(200):                                       # bisection on the growth ratio
        ratio = 0.5 * (low + high)
        if first * (ratio ** count - 1) / (ratio - 1) < d_sc:
            low = ratio
        else:
            high = ratio
    heights = np.concatenate([[0.0], np.cumsum(first * ratio ** np.arange(count))])
    return heights * (d_sc / heights[-1])


def _build_mesh(stack: DielectricStack, gap, length, periodic, insulator_rows, air_rows, sc_rows,
                sc_first) -> _Mesh:
    n = gap.size
    columns = n + 1 if periodic else n
    x = np.arange(columns) * (length / n if periodic else length / (n - 1))
    g = np.concatenate([gap, gap[:1]]) if periodic else gap
    insulator = np.linspace(-stack.d_i, 0.0, insulator_rows + 1)
    air = np.linspace(0.0, 1.0, air_rows + 1)[1:]
    sc = _stratum_corneum_rows(stack.d_sc, sc_first, sc_rows)[1:]
    rows = insulator_rows + air_rows + sc_rows + 1
    z = np.concatenate([np.broadcast_to(insulator, (columns, insulator_rows + 1)), g[:, None] * air,
                        g[:, None] + sc], axis=1)
    velocity = np.concatenate([np.zeros(insulator_rows + 1), air, np.ones(sc_rows)])
    points = np.stack([np.repeat(x, rows), z.ravel()])
    j, k = np.meshgrid(np.arange(columns - 1), np.arange(rows - 1), indexing="ij")
    corner = (j * rows + k).ravel()
    right, up = corner + rows, corner + 1
    # triangle (right, right+1, corner): vertical edge on column j+1; (corner, up, right+1): on column j
    triangles = np.concatenate([np.stack([right, right + 1, corner]), np.stack([corner, up, right + 1])], axis=1)
    layer_of_row = np.concatenate([np.full(insulator_rows, stack.eps_i), np.full(air_rows, stack.eps_a),
                                   np.full(sc_rows, stack.eps_sc)])
    permittivity = np.tile(np.broadcast_to(layer_of_row, (columns - 1, rows - 1)).ravel(), 2)
    return _Mesh(points, np.tile(velocity, columns), triangles, permittivity,
                 range(insulator_rows, insulator_rows + air_rows + 1), rows, columns, n)


def _gradients(points, triangles):
    """Twice the signed areas (elements,) and the P1 basis gradients (elements, 3 vertices, 2)."""
    p = points[:, triangles]                                   # (2, 3, elements)
    e1, e2 = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]
    twice_area = e1[0] * e2[1] - e1[1] * e2[0]
    safe = np.where(twice_area == 0, 1.0, twice_area)
    # grad φ_i = rot90(opposite edge) / (2A)
    opposite = np.stack([p[:, 2] - p[:, 1], p[:, 0] - p[:, 2], p[:, 1] - p[:, 0]], axis=1)   # (2, 3, el)
    grads = np.stack([-opposite[1], opposite[0]], axis=-1) / safe[None, :, None]            # (3, el, 2)
    return twice_area, grads.transpose(1, 0, 2)


def _unknowns(mesh: _Mesh, collapsed: np.ndarray):
    """Unknown index per node (-1 bottom electrode, -2 tissue) merging the air rows of collapsed columns
    and the periodic image column."""
    rows = mesh.rows
    column = np.arange(mesh.columns) % mesh.period_columns
    row = np.arange(rows)
    key_row = np.where(collapsed[column][:, None] & (row >= mesh.air_rows[0]) & (row <= mesh.air_rows[-1]),
                       mesh.air_rows[0], row[None, :])
    key = column[:, None] * rows + key_row
    key[:, 0], key[:, -1] = -1, -2
    free = np.unique(key[key >= 0])
    index = np.full(mesh.period_columns * rows, -1)
    index[free] = np.arange(free.size)
    return np.where(key >= 0, index[np.maximum(key, 0)], key).ravel(), free.size


def _solve(matrix, rhs, solver, tol, maxiter):
    """(solution, converged, iterations, relative residual ‖b - Ax‖/‖b‖) of the SPD system.

    ``"direct"``: sparse LU (SuperLU, nested-dissection order), exact to rounding and fast in 2-D.
    ``"amg"``: conjugate gradients preconditioned by classical (Ruge–Stüben) AMG; it copes with the thin
    rows better than smoothed aggregation but can stall on the 3000:1 permittivity contrast (then warned).
    """
    if solver == "direct":
        from scipy.sparse.linalg import splu

        solution = splu(matrix.tocsc()).solve(rhs)
        iterations = 0
    else:
        import pyamg

        residuals = []
        solution = pyamg.ruge_stuben_solver(matrix).solve(rhs, tol=tol, accel="cg", maxiter=maxiter,
                                                           residuals=residuals)
        iterations = len(residuals) - 1
    relative = float(np.linalg.norm(rhs - matrix @ solution) / np.linalg.norm(rhs))
    return solution, relative <= tol, iterations, relative


def _opening_derivative(mesh, degenerate, potential, residual):
    """Per column, the one-sided dE/dδ (δ -> 0+) of the zero-area air triangles at collapsed columns, and
    the limiting gradient ∇u (degenerate triangles, 2) in them.

    For each air row segment of a collapsed column, with G its limiting vertical air field and T the flux
    leaving its upper node group (the sum of the non-degenerate residuals above it), the energy per δ is
    Σ ¼ ε |Δx| Δr [G² + (α - β G)²] + T Δr G (α = Δu/Δx, β = Δz/Δx to the third vertex), minimised
    over G.
    """
    rows, points = mesh.rows, mesh.points
    share = np.zeros(mesh.period_columns)
    if not np.any(degenerate):
        return share, np.zeros((0, 2))
    air_bottom, air_count = mesh.air_rows[0], len(mesh.air_rows) - 1
    step = 1.0 / air_count
    bottom, top, third = mesh.triangles[:, degenerate]
    eps = EPSILON_0 * mesh.permittivity[degenerate]
    dx = points[0, third] - points[0, bottom]
    alpha = (potential[third] - potential[bottom]) / dx
    beta = (points[1, third] - points[1, bottom]) / dx
    weight = 0.25 * eps * np.abs(dx) * step
    column = (bottom // rows) % mesh.period_columns
    segment = bottom % rows - air_bottom                      # air row segment 0 .. air_count-1
    slot = column * air_count + segment
    size = mesh.period_columns * air_count
    quadratic = np.bincount(slot, weight * (1 + beta ** 2), size)
    linear = np.bincount(slot, weight * 2 * alpha * beta, size)
    constant = np.bincount(slot, weight * alpha ** 2, size)
    # flux T through each segment: residuals of the air nodes above it, summed over the column's images
    node_column = (np.arange(points.shape[1]) // rows) % mesh.period_columns
    node_row = np.arange(points.shape[1]) % rows - air_bottom
    above = np.zeros((mesh.period_columns, air_count + 1))
    in_air = (node_row >= 0) & (node_row <= air_count)
    np.add.at(above, (node_column[in_air], node_row[in_air]), residual[in_air])
    flux = np.cumsum(above[:, ::-1], axis=1)[:, ::-1][:, 1:].ravel()       # Σ_{m > r} R_m
    used = quadratic > 0
    shifted = linear[used] - flux[used] * step
    minimum = constant[used] - shifted ** 2 / (4 * quadratic[used])
    np.add.at(share, np.flatnonzero(used) // air_count, minimum)
    vertical = np.zeros(size)
    vertical[used] = shifted / (2 * quadratic[used])                       # the minimising G
    return share, np.stack([alpha - beta * vertical[slot], vertical[slot]], axis=1)


def _maxwell_pressure(mesh, gradient, eps_air):
    """Air-side Maxwell traction on the skin per interval between columns [Pa], attractive positive:
    ``ε0 eps_a [½ (E_z² - E_x²) - E_x E_z g']`` from the top air row's triangle under each interval."""
    intervals, rows = mesh.columns - 1, mesh.rows
    top_row = mesh.air_rows[-1] - 1
    upper = intervals * (rows - 1) + np.arange(intervals) * (rows - 1) + top_row   # (corner, up, right+1)
    ex, ez = gradient[upper].T
    slope = np.diff(mesh.points[1, mesh.air_rows[-1]::rows]) / np.diff(mesh.points[0, ::rows])
    return EPSILON_0 * eps_air * (0.5 * (ez ** 2 - ex ** 2) - ex * ez * slope)


def field_solve_profile(stack: DielectricStack, gap, length: float, voltage: float, periodic: bool = True,
                        insulator_rows: int = 4, air_rows: int = 4, sc_rows: int = 24, sc_first=None,
                        solver: str = "direct", tol: float = 1e-9,
                        maxiter: int = 500) -> ProfileFieldSolution:
    """Solve the stack's field over the gap profile ``gap`` [m] (1-D, >= 0) on a window ``length`` [m].

    ``gap`` holds the air gap at equally spaced columns (spacing length/n when ``periodic``, the window's ends
    included otherwise), linear in between; ``voltage`` U [V]. Rows per layer: ``insulator_rows``, ``air_rows``
    (uniform), ``sc_rows`` (geometric from ``sc_first`` [m], default the column spacing). ``tol``: relative
    residual of the linear solve, by ``solver`` ``"direct"`` (sparse LU) or ``"amg"`` (CG + pyamg, at most
    ``maxiter`` iterations); ``ConvergenceWarning`` and ``converged=False`` if it is not met.
    """
    gap = check_finite_array("gap", gap, nonnegative=True)
    if gap.ndim != 1 or gap.size < 2:
        raise ValueError(f"gap must be a 1-D profile of at least 2 values; got shape {gap.shape}")
    length = check_positive("length", length)
    solver = check_choice("solver", solver, ("direct", "amg"))
    voltage = check_real("voltage", voltage)
    for name, value in (("insulator_rows", insulator_rows), ("air_rows", air_rows), ("sc_rows", sc_rows)):
        check_integer(name, value, low=1)
    spacing = length / (gap.size if periodic else gap.size - 1)
    sc_first = check_positive("sc_first", spacing if sc_first is None else sc_first)
    from skfem import Basis, BilinearForm, ElementTriP1, MeshTri, asm
    from skfem.helpers import dot, grad
    from scipy import sparse

    # a gap below 1e-9 of the air-equivalent offset is contact: such a sliver of air (a rounding residue of
    # g = 0) would make the matrix singular to working precision; σ_el changes by < 2e-9 relative there
    collapsed = gap <= CONTACT_GAP * stack.eps_a * stack.dielectric_offset
    gap = np.where(collapsed, 0.0, gap)
    mesh = _build_mesh(stack, gap, length, periodic, insulator_rows, air_rows, sc_rows, sc_first)
    twice_area, grads = _gradients(mesh.points, mesh.triangles)
    degenerate = twice_area == 0
    kept = ~degenerate
    fe_mesh = MeshTri(mesh.points, mesh.triangles[:, kept], sort_t=False, validate=False)
    basis = Basis(fe_mesh, ElementTriP1())

    @BilinearForm
    def laplace(u, v, w):
        return EPSILON_0 * w["eps"] * dot(grad(u), grad(v))

    permittivity = np.broadcast_to(mesh.permittivity[kept][:, None], (kept.sum(), basis.X.shape[-1]))
    stiffness = asm(laplace, basis, eps=permittivity).tocsr()
    index, unknowns = _unknowns(mesh, collapsed)
    free = index >= 0
    merge = sparse.csr_matrix((np.ones(free.sum()), (np.flatnonzero(free), index[free])),
                              shape=(index.size, unknowns))
    fixed = np.where(index == -2, voltage, 0.0)
    matrix = (merge.T @ stiffness @ merge).tocsr()
    rhs = -merge.T @ (stiffness @ fixed)
    solution, converged, iterations, residual = _solve(matrix, rhs, solver, tol, maxiter)
    if not converged:
        from ..results import ConvergenceWarning
        warnings.warn(f"field_solve_profile: relative residual {residual:.2e} > tol = {tol:g} after "
                      f"{iterations} iterations", ConvergenceWarning, stacklevel=2)
    potential = merge @ solution + fixed
    energy = 0.5 * float(potential @ (stiffness @ potential))

    # virtual work of the kept triangles: Σ_n V_n ∂E_e/∂z_n, booked to the node's column
    t = mesh.triangles[:, kept]
    g_kept = grads[kept]                                                  # (el, 3, 2)
    field = np.einsum("eij,ie->ej", g_kept, potential[t])                  # ∇u (el, 2)
    half_eps_area = 0.25 * EPSILON_0 * mesh.permittivity[kept] * np.abs(twice_area[kept])
    per_vertex = half_eps_area[:, None] * (np.sum(field ** 2, axis=1)[:, None] * g_kept[:, :, 1]
                                           - 2 * field[:, 1:2] * np.einsum("eij,ej->ei", g_kept, field))
    node_column = (t.T // mesh.rows) % mesh.period_columns
    derivative = np.bincount(node_column.ravel(), (per_vertex * mesh.velocity[t.T]).ravel(),
                             mesh.period_columns)
    opening, degenerate_gradient = _opening_derivative(mesh, degenerate, potential, stiffness @ potential)
    derivative += opening
    gradient = np.zeros((mesh.triangles.shape[1], 2))
    gradient[kept], gradient[degenerate] = field, degenerate_gradient
    maxwell = _maxwell_pressure(mesh, gradient, stack.eps_a)
    x = mesh.points[0, ::mesh.rows][:mesh.period_columns]
    width = np.full(mesh.period_columns, spacing)
    if not periodic:
        width[[0, -1]] = spacing / 2
    return ProfileFieldSolution(mean_pressure=-float(derivative.sum()) / length, pressure=-derivative / width,
                                x=x, gap=gap.copy(), energy=energy, nodes=int(mesh.points.shape[1]),
                                elements=int(kept.sum()), unknowns=int(unknowns), converged=bool(converged),
                                iterations=int(iterations), residual=residual, maxwell_pressure=maxwell,
                                mean_maxwell_pressure=float(maxwell.sum() * spacing / length))
