"""Finite-element field solve of the full layered stack over a 1-D gap profile: the independent reference.

A 2-D x–z problem (``docs/validation/field_check.md``): electrode at z = -d_i (potential 0), insulator (eps_i), air gap
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

import itertools
import math
import warnings
from dataclasses import dataclass, field as dataclass_field

import numpy as np

from surfaces.validation import (check_choice, check_finite_array, check_integer, check_positive,
                                 check_real)

from ..io.results import ConvergenceWarning
from ..electrostatics.stack import EPSILON_0, DielectricStack, check_voltage


#: Gaps up to this fraction of the air-equivalent offset eps_a c are contact (merged air rows).
CONTACT_GAP = 1e-9
#: Active-set sweeps of the deposited charge (air breakdown) before the solve is reported as not converged.
BREAKDOWN_SWEEPS = 60


@dataclass(frozen=True)
class PatchFieldSolution:
    """Field solve over a 2-D gap field (x, y, z); SI units.

    ``mean_attraction`` σ̄ [Pa] (virtual work, positive = attraction), ``attraction`` the attraction per column
    [Pa] (the virtual work of moving one column of skin nodes, over its tributary area; shaped like the gap, its
    area-weighted mean is σ̄), ``gap`` [m], ``energy`` E [J], ``nodes``, ``elements`` (simplices kept),
    ``unknowns``, and the solver's ``converged``, ``iterations`` and relative ``residual``.
    """

    mean_attraction: float
    attraction: np.ndarray
    gap: np.ndarray
    energy: float
    nodes: int
    elements: int
    unknowns: int
    converged: bool
    iterations: int
    residual: float


@dataclass(frozen=True)
class ProfileFieldSolution(PatchFieldSolution):
    """Field solve over a 1-D gap profile (x, z); the fields of :class:`PatchFieldSolution` per unit depth in y
    (``attraction`` per column over its tributary width, ``energy`` E [J/m]), and ``x`` the column positions
    [m]. ``maxwell_attraction`` [Pa] is the independent air-side Maxwell traction on the skin per interval between
    columns (the field of the air triangle under it; the zero-area ones at contact take their limiting field),
    ``mean_maxwell_attraction`` its mean; it converges to σ̄ with the mesh. ``charge`` [C/m²] is the charge air
    breakdown deposits on the insulator per column (None without breakdown).
    """

    x: np.ndarray
    maxwell_attraction: np.ndarray
    mean_maxwell_attraction: float
    charge: np.ndarray | None = dataclass_field(default=None, kw_only=True)


@dataclass(frozen=True)
class _Mesh:
    """Terrain-following mesh of simplices in ``dim`` = 2 (x, z) or 3 (x, y, z) dimensions. Node (node column
    c, row k) has index ``c * rows + k``; node columns run over the lateral nodes in C order, with the periodic
    images of the first column(s) at the end of each axis; ``column`` maps every node to its distinct column."""

    points: np.ndarray          # (dim, nodes)
    velocity: np.ndarray        # dz/dδ per node
    simplices: np.ndarray       # (dim + 1, elements): vertices 0, 1 the vertical edge (bottom, top), then the rest
    permittivity: np.ndarray    # relative permittivity per simplex
    column: np.ndarray          # distinct column of each node
    air_rows: range             # node rows of the air layer (insulator top ... stratum-corneum bottom)
    rows: int
    node_shape: tuple           # lateral node columns per axis (with the periodic images)
    columns: int                # distinct columns


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


def _build_mesh(stack: DielectricStack, gap, spacing, periodic, insulator_rows, air_rows, sc_rows,
                sc_first, nodes=None, insulator_first=None) -> _Mesh:
    """The mesh over the lateral gap array ``gap`` (1-D or 2-D) at ``spacing`` [m] per axis, or at the lateral node
    coordinates ``nodes`` (one array per axis, the periodic image included); the insulator's rows uniform, or
    geometric from ``insulator_first`` [m] at its face down to the electrode. Every lateral cell × row is cut into
    dim! simplices along the paths of Kuhn's triangulation (one per order of the unit steps), so that every
    simplex has exactly one vertical edge; in 2-D these are the two triangles of a quad."""
    node_shape = tuple(n + 1 if periodic else n for n in gap.shape)
    g = np.pad(gap, [(0, 1)] * gap.ndim, mode="wrap") if periodic else gap
    if nodes is None:
        nodes = [np.arange(m) * h for m, h in zip(node_shape, spacing)]
    lateral = np.meshgrid(*nodes, indexing="ij")
    insulator = np.linspace(-stack.d_i, 0.0, insulator_rows + 1) if insulator_first is None else \
        -_stratum_corneum_rows(stack.d_i, insulator_first, insulator_rows)[::-1]
    air = np.linspace(0.0, 1.0, air_rows + 1)[1:]
    sc = _stratum_corneum_rows(stack.d_sc, sc_first, sc_rows)[1:]
    rows = insulator_rows + air_rows + sc_rows + 1
    g = g.reshape(-1, 1)
    z = np.concatenate([np.broadcast_to(insulator, (g.shape[0], insulator_rows + 1)), g * air, g + sc], axis=1)
    velocity = np.concatenate([np.zeros(insulator_rows + 1), air, np.ones(sc_rows)])
    points = np.stack([np.repeat(x.ravel(), rows) for x in lateral] + [z.ravel()])
    distinct = np.meshgrid(*[np.arange(m) % n for m, n in zip(node_shape, gap.shape)], indexing="ij")
    column = np.repeat(np.ravel_multi_index([i.ravel() for i in distinct], gap.shape), rows)
    # cells: lateral corner (node_shape - 1 per axis) × row; unit steps along each lateral axis and up
    dim = gap.ndim + 1
    corners = np.meshgrid(*[np.arange(m - 1) for m in node_shape], np.arange(rows - 1), indexing="ij")
    base = (np.ravel_multi_index([c.ravel() for c in corners[:-1]], node_shape) * rows + corners[-1].ravel())
    stride = [int(np.prod(node_shape[a + 1:])) * rows for a in range(gap.ndim)] + [1]
    simplices = []
    for order in itertools.permutations(range(dim)):
        path = [base]
        for axis in order:
            path.append(path[-1] + stride[axis])
        up = order.index(dim - 1) + 1                           # the vertical step: path[up - 1] -> path[up]
        simplices.append(np.stack([path[up - 1], path[up]] + [p for i, p in enumerate(path) if i not in (up - 1, up)]))
    layer_of_row = np.concatenate([np.full(insulator_rows, stack.eps_i), np.full(air_rows, stack.eps_a),
                                   np.full(sc_rows, stack.eps_sc)])
    permittivity = np.tile(layer_of_row[corners[-1].ravel()], len(simplices))
    return _Mesh(points, np.tile(velocity, g.shape[0]), np.concatenate(simplices, axis=1), permittivity, column,
                 range(insulator_rows, insulator_rows + air_rows + 1), rows, node_shape, gap.size)


def _gradients(points, simplices):
    """Signed volumes times dim! (elements,) and the P1 basis gradients (elements, dim + 1, dim); zero-volume
    simplices get zero gradients."""
    p = points[:, simplices].transpose(2, 1, 0)                 # (elements, dim + 1, dim)
    edges = p[:, 1:] - p[:, :1]                                  # rows e_j = p_j - p_0
    determinant = np.linalg.det(edges)
    flat = determinant == 0
    inverse = np.linalg.inv(np.where(flat[:, None, None], np.eye(edges.shape[1]), edges))
    grads = np.zeros(p.shape)
    grads[:, 1:] = inverse.transpose(0, 2, 1)                   # ∇φ_i = column i of E⁻¹
    grads[:, 0] = -grads[:, 1:].sum(axis=1)
    grads[flat] = 0.0
    return determinant, grads


def _unknowns(mesh: _Mesh, collapsed: np.ndarray):
    """Unknown index per node (-1 bottom electrode, -2 tissue) merging the air rows of collapsed columns
    and the periodic images."""
    row = np.arange(mesh.points.shape[1]) % mesh.rows
    in_air = (row >= mesh.air_rows[0]) & (row <= mesh.air_rows[-1])
    key = mesh.column * mesh.rows + np.where(collapsed.ravel()[mesh.column] & in_air, mesh.air_rows[0], row)
    key[row == 0], key[row == mesh.rows - 1] = -1, -2
    free = np.unique(key[key >= 0])
    index = np.full(mesh.columns * mesh.rows, -1)
    index[free] = np.arange(free.size)
    return np.where(key >= 0, index[np.maximum(key, 0)], key), free.size


def _solve(matrix, rhs, solver, tol, maxiter):
    """(solution, converged, iterations, relative residual ‖b - Ax‖/‖b‖) of the SPD system.

    ``"direct"``: sparse LU (SuperLU, minimum-degree order on Aᵀ + A), exact to rounding; fast in 2-D, slow in
    3-D (10 s for 32² columns × 33 rows). ``"amg"``: conjugate gradients preconditioned by classical
    (Ruge–Stüben) AMG, 10 iterations there; it copes with the thin rows better than smoothed aggregation but
    can stall on the 3000:1 permittivity contrast of some 2-D meshes (then warned).
    """
    if solver == "direct":
        from scipy.sparse.linalg import splu

        solution = splu(matrix.tocsc(), permc_spec="MMD_AT_PLUS_A").solve(rhs)
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
    """Per column, the one-sided dE/dδ (δ -> 0+) of the zero-volume air simplices at collapsed columns, and
    the limiting gradient ∇u (degenerate simplices, dim) in them.

    A zero-volume simplex has its vertical edge (Δr of the air, Δz = δ Δr) on a collapsed column and its other
    vertices at lateral offsets H (rows) from it; its air field G = ∂u/∂z and the lateral gradient α - β G
    (H α = Δu, H β = Δz to those vertices) give it the energy per δ ½ ε Δr |det H|/dim! [G² + |α - β G|²]. Per
    air row segment of a collapsed column, with T the flux leaving its upper node group (the sum of the
    non-degenerate residuals above it), the energy per δ is the sum of these plus T Δr G, minimised over G.
    """
    rows, points = mesh.rows, mesh.points
    share = np.zeros(mesh.columns)
    dim = points.shape[0]
    if not np.any(degenerate):
        return share, np.zeros((0, dim))
    air_bottom, air_count = mesh.air_rows[0], len(mesh.air_rows) - 1
    step = 1.0 / air_count
    bottom, others = mesh.simplices[0, degenerate], mesh.simplices[2:, degenerate]
    lateral = (points[:-1, others] - points[:-1, bottom][:, None]).transpose(2, 1, 0)      # (el, dim-1, dim-1)
    alpha = np.linalg.solve(lateral, (potential[others] - potential[bottom]).T[..., None])[..., 0]
    beta = np.linalg.solve(lateral, (points[-1, others] - points[-1, bottom]).T[..., None])[..., 0]
    weight = (0.5 * EPSILON_0 * mesh.permittivity[degenerate] * step * np.abs(np.linalg.det(lateral))
              / math.factorial(dim))
    segment = bottom % rows - air_bottom                      # air row segment 0 .. air_count-1
    slot = mesh.column[bottom] * air_count + segment
    size = mesh.columns * air_count
    quadratic = np.bincount(slot, weight * (1 + np.sum(beta ** 2, axis=1)), size)
    linear = np.bincount(slot, weight * 2 * np.sum(alpha * beta, axis=1), size)
    constant = np.bincount(slot, weight * np.sum(alpha ** 2, axis=1), size)
    # flux T through each segment: residuals of the air nodes above it, summed over the column's images
    node_row = np.arange(points.shape[1]) % rows - air_bottom
    in_air = (node_row >= 0) & (node_row <= air_count)
    above = np.zeros((mesh.columns, air_count + 1))
    np.add.at(above, (mesh.column[in_air], node_row[in_air]), residual[in_air])
    flux = np.cumsum(above[:, ::-1], axis=1)[:, ::-1][:, 1:].ravel()       # Σ_{m > r} R_m
    used = quadratic > 0
    shifted = linear[used] - flux[used] * step
    minimum = constant[used] - shifted ** 2 / (4 * quadratic[used])
    np.add.at(share, np.flatnonzero(used) // air_count, minimum)
    vertical = np.zeros(size)
    vertical[used] = shifted / (2 * quadratic[used])                       # the minimising G
    return share, np.concatenate([alpha - beta * vertical[slot][:, None], vertical[slot][:, None]], axis=1)


def _maxwell_attraction(mesh, gradient, eps_air):
    """Air-side Maxwell traction on the skin per interval between columns [Pa], attractive positive:
    ``ε0 eps_a [½ (E_z² - E_x²) - E_x E_z g']`` from the top air row's triangle under each interval."""
    intervals, rows = mesh.node_shape[0] - 1, mesh.rows
    top_row = mesh.air_rows[-1] - 1
    upper = intervals * (rows - 1) + np.arange(intervals) * (rows - 1) + top_row   # (corner, up, right+1)
    ex, ez = gradient[upper].T
    slope = np.diff(mesh.points[1, mesh.air_rows[-1]::rows]) / np.diff(mesh.points[0, ::rows])
    return EPSILON_0 * eps_air * (0.5 * (ez ** 2 - ex ** 2) - ex * ez * slope)


@dataclass(frozen=True)
class _Solved:
    """What both solves share: the mesh, the nodal potential, energy [J/m or J], the skin-shift derivative per
    column, the gradient per simplex (degenerate ones: their limit) and the solver's record."""

    mesh: _Mesh
    energy: float
    derivative: np.ndarray
    gradient: np.ndarray
    elements: int
    unknowns: int
    converged: bool
    iterations: int
    residual: float
    charge: np.ndarray | None = None


def _check_options(rows: dict, solver, sc_first, spacing):
    for name, value in rows.items():
        check_integer(name, value, low=1)
    check_choice("solver", solver, ("direct", "amg"))
    return check_positive("sc_first", min(spacing) if sc_first is None else sc_first)


def _deposited_charge(matrix, rhs, insulator, insulator_fixed, bottom, top, limit, candidate) -> tuple:
    """Air breakdown on the merged system ``matrix`` u = ``rhs`` + P q: a discharge in column j moves the charge
    q_j ≥ 0 [C/m] from the stratum corneum's face (its unknown ``top``[j]) to the insulator's (``bottom``[j]); the
    two coincide at contact. The air's flux into the insulator's face is F_j = (K_ins u)_j − q_j (``insulator``
    the merged stiffness of the insulator, ``insulator_fixed`` its Dirichlet part), at most ``limit`` (ε0 ε_a E_bd
    times the column's width), and q_j = 0 wherever F_j stays below (complementarity); only the ``candidate``
    columns may break down. Active sets: the broken columns' charges are unknowns beside u with F_j = limit_j as
    their equations, sparse LU solves, and the set is updated (q < 0 leaves it, F above the limit joins it) until
    it repeats. Returns (solution, charge per column, sweeps, the last system's relative residual; inf if the set
    did not repeat)."""
    from scipy import sparse
    from scipy.sparse.linalg import splu

    count = bottom.size
    columns = np.arange(count)
    transfer = sparse.csr_matrix((np.concatenate([np.ones(count), -np.ones(count)]),
                                  (np.concatenate([bottom, top]), np.concatenate([columns, columns]))),
                                 shape=(matrix.shape[0], count))
    lateral = insulator[bottom]                                   # rows of K_ins at the insulator's face
    active, charge = np.zeros(count, np.bool_), np.zeros(count)
    for sweep in range(1, BREAKDOWN_SWEEPS + 1):
        broken = np.flatnonzero(active)
        system = sparse.bmat([[matrix, -transfer[:, broken]],
                              [lateral[broken], -sparse.identity(broken.size)]], format="csc")
        right = np.concatenate([rhs, limit[broken] - insulator_fixed[bottom][broken]])
        solution = splu(system, permc_spec="MMD_AT_PLUS_A").solve(right)
        residual = float(np.linalg.norm(right - system @ solution) / np.linalg.norm(right))
        charge[:] = 0.0
        charge[broken] = solution[matrix.shape[0]:]
        potential = solution[:matrix.shape[0]]
        inflow = lateral @ potential + insulator_fixed[bottom] - charge
        now = np.where(active, charge > 0, inflow > limit) & candidate
        if np.array_equal(now, active):
            return potential, charge, sweep, residual
        active = now
    return potential, charge, sweep, math.inf


def _solve_stack(stack, gap, spacing, periodic, voltage, rows: dict, sc_first, solver, tol, maxiter,
                 caller, nodes=None, breakdown=None, widths=None, insulator_first=None) -> _Solved:
    """Mesh, assemble (scikit-fem), solve and differentiate (module docstring) over the gap array ``gap``; with
    ``breakdown`` (an :class:`~roughcontact.electrostatics.contact_line.AirBreakdown`, direct solver) the charge on
    the insulator's surface nodes of :func:`_deposited_charge`, the columns' ``widths`` [m] setting their limits."""
    from scipy import sparse
    from skfem import Basis, BilinearForm, ElementTetP1, ElementTriP1, MeshTet, MeshTri, asm
    from skfem.helpers import dot, grad

    # a gap below 1e-9 of the air-equivalent offset is contact: such a sliver of air (a rounding residue of
    # g = 0) would make the matrix singular to working precision; σ_el changes by < 2e-9 relative there
    collapsed = gap <= CONTACT_GAP * stack.eps_a * stack.dielectric_offset
    gap = np.where(collapsed, 0.0, gap)
    mesh = _build_mesh(stack, gap, spacing, periodic, rows["insulator_rows"], rows["air_rows"], rows["sc_rows"],
                       sc_first, nodes, insulator_first)
    determinant, grads = _gradients(mesh.points, mesh.simplices)
    degenerate = determinant == 0
    kept = ~degenerate
    mesh_type, element = (MeshTri, ElementTriP1) if gap.ndim == 1 else (MeshTet, ElementTetP1)
    basis = Basis(mesh_type(mesh.points, mesh.simplices[:, kept], sort_t=False, validate=False), element())

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
    charge, sources = None, 0.0
    if breakdown is None:
        solution, converged, iterations, residual = _solve(matrix, -merge.T @ (stiffness @ fixed), solver, tol,
                                                           maxiter)
    else:
        in_insulator = mesh.simplices[0, kept] % mesh.rows < rows["insulator_rows"]
        insulator = asm(laplace, basis, eps=np.where(in_insulator[:, None], permittivity, 0.0)).tocsr()
        row = np.arange(index.size) % mesh.rows
        faces = []
        for face in (rows["insulator_rows"], rows["insulator_rows"] + rows["air_rows"]):
            nodes = np.flatnonzero(row == face)
            unknown = np.zeros(mesh.columns, int)
            unknown[mesh.column[nodes]] = index[nodes]
            faces.append(unknown)
        solution, charge, iterations, residual = _deposited_charge(
            matrix, -merge.T @ (stiffness @ fixed), (merge.T @ insulator @ merge).tocsr(),
            merge.T @ (insulator @ fixed),
            *faces, EPSILON_0 * stack.eps_a * breakdown.field * widths, breakdown.at_contact | ~collapsed.ravel())
        converged = residual <= tol
        # the charges as nodal sources of the unmerged mesh: +q on the insulator's face, −q on the stratum corneum's
        sources = np.zeros(index.size)
        for face, sign in ((rows["insulator_rows"], 1.0), (rows["insulator_rows"] + rows["air_rows"], -1.0)):
            nodes = np.flatnonzero(row == face)
            first = nodes[np.unique(mesh.column[nodes], return_index=True)[1]]       # one node per column
            sources[first] = sign * charge[mesh.column[first]]
    if not converged:
        warnings.warn(f"{caller}: relative residual {residual:.2e} > tol = {tol:g} after {iterations} "
                      "iterations", ConvergenceWarning, stacklevel=3)
    potential = merge @ solution + fixed
    energy = 0.5 * float(potential @ (stiffness @ potential))

    # virtual work of the kept simplices: Σ_n V_n ∂E_e/∂z_n, booked to the node's column
    simplices, g_kept = mesh.simplices[:, kept], grads[kept]
    field = np.einsum("eij,ie->ej", g_kept, potential[simplices])          # ∇u (el, dim)
    half_eps_volume = (0.5 * EPSILON_0 * mesh.permittivity[kept] * np.abs(determinant[kept])
                       / math.factorial(mesh.points.shape[0]))
    per_vertex = half_eps_volume[:, None] * (np.sum(field ** 2, axis=1)[:, None] * g_kept[:, :, -1]
                                             - 2 * field[:, -1:] * np.einsum("eij,ej->ei", g_kept, field))
    derivative = np.bincount(mesh.column[simplices.T].ravel(), (per_vertex * mesh.velocity[simplices.T]).ravel(),
                             mesh.columns)
    opening, degenerate_gradient = _opening_derivative(mesh, degenerate, potential, stiffness @ potential - sources)
    gradient = np.zeros((mesh.simplices.shape[1], mesh.points.shape[0]))
    gradient[kept], gradient[degenerate] = field, degenerate_gradient
    return _Solved(mesh, energy, derivative + opening, gradient, int(kept.sum()), int(unknowns), bool(converged),
                   int(iterations), residual, charge)


def _tributary(count: int, spacing: float, periodic: bool) -> np.ndarray:
    """Width of each node's share of an axis [m]: the spacing, halved at the ends of a free window."""
    width = np.full(count, spacing)
    if not periodic:
        width[[0, -1]] = spacing / 2
    return width


def field_solve_profile(stack: DielectricStack, gap, length: float, voltage: float, periodic: bool = True,
                        insulator_rows: int = 4, air_rows: int = 4, sc_rows: int = 24, sc_first=None,
                        solver: str = "direct", tol: float = 1e-9, maxiter: int = 500, positions=None,
                        insulator_first=None, breakdown=None) -> ProfileFieldSolution:
    """Solve the stack's field over the gap profile ``gap`` [m] (1-D, >= 0) on a window ``length`` [m].

    ``gap`` holds the air gap at equally spaced columns (spacing length/n when ``periodic``, the window's ends
    included otherwise), linear in between, or at the column ``positions`` [m] given (increasing; in [0, length)
    when ``periodic``, from 0 to ``length`` otherwise): a mesh graded towards a contact line keeps its cells
    unsheared where the gap rises steeply (:func:`graded_positions`). ``voltage`` U [V]. Rows per layer:
    ``insulator_rows`` (uniform, or geometric from ``insulator_first`` [m] at its face: the field of a contact line
    concentrates there), ``air_rows`` (uniform), ``sc_rows`` (geometric from ``sc_first`` [m], default the
    smallest column spacing). ``tol``: relative residual of the linear solve, by ``solver`` ``"direct"`` (sparse
    LU) or ``"amg"`` (CG + pyamg, at most ``maxiter`` iterations); ``ConvergenceWarning`` and ``converged=False``
    if it is not met.

    ``breakdown`` (an :class:`~roughcontact.electrostatics.contact_line.AirBreakdown`, direct solver) deposits
    charge on the insulator's surface nodes wherever the air's flux into a node would exceed ε0 ε_a E_bd per unit
    width of the node's column (contact columns too when ``breakdown.at_contact``): the same condition as the
    layered field's columns on the normal field of the air at the insulator, found by active sets. The attraction
    is the virtual work of the rigid shift at fixed charge (the charge sits on the insulator, which does not move);
    ``charge`` holds it per column [C/m²].
    """
    gap = check_finite_array("gap", gap, nonnegative=True)
    if gap.ndim != 1 or gap.size < 2:
        raise ValueError(f"gap must be a 1-D profile of at least 2 values; got shape {gap.shape}")
    length = check_positive("length", length)
    voltage = check_voltage(voltage)
    nodes = _profile_nodes(gap.size, length, periodic, positions)
    widths = _widths(nodes, periodic)
    rows = dict(insulator_rows=insulator_rows, air_rows=air_rows, sc_rows=sc_rows)
    sc_first = _check_options(rows, solver, sc_first, (float(np.min(np.diff(nodes))),))
    if breakdown is not None and solver != "direct":
        raise ValueError(f"air breakdown needs solver = 'direct', got solver = {solver!r}")
    # the attraction is even in U: a broken field solved at |U|
    solved = _solve_stack(stack, gap, None, periodic, abs(voltage) if breakdown else voltage, rows, sc_first,
                          solver, tol, maxiter, "field_solve_profile", (nodes,), breakdown, widths,
                          None if insulator_first is None else check_positive("insulator_first", insulator_first))
    mesh = solved.mesh
    maxwell = _maxwell_attraction(mesh, solved.gradient, stack.eps_a)
    return ProfileFieldSolution(
        mean_attraction=-float(solved.derivative.sum()) / length, attraction=-solved.derivative / widths,
        x=nodes[:gap.size], gap=gap.copy(),
        energy=solved.energy, nodes=int(mesh.points.shape[1]), elements=solved.elements, unknowns=solved.unknowns,
        converged=solved.converged, iterations=solved.iterations, residual=solved.residual,
        maxwell_attraction=maxwell, mean_maxwell_attraction=float(maxwell @ np.diff(nodes)) / length,
        charge=None if solved.charge is None else solved.charge / widths)


def _profile_nodes(count: int, length: float, periodic: bool, positions) -> np.ndarray:
    """The lateral node coordinates [m] of a profile's ``count`` columns (the periodic image of the first at the
    end when ``periodic``): equally spaced, or ``positions`` checked."""
    if positions is None:
        spacing = length / (count if periodic else count - 1)
        return np.arange(count + 1 if periodic else count) * spacing
    positions = check_finite_array("positions", positions)
    if positions.shape != (count,) or np.any(np.diff(positions) <= 0):
        raise ValueError(f"positions must be {count} increasing column positions (one per gap value); got shape "
                         f"{positions.shape}")
    if periodic and (positions[0] < 0 or positions[-1] >= length):
        raise ValueError(f"positions must lie in [0, length) on a periodic window; got {positions[0]!r} … "
                         f"{positions[-1]!r} for length = {length!r}")
    if not periodic and (positions[0] != 0 or positions[-1] != length):
        raise ValueError(f"positions of a free window must run from 0 to length = {length!r}; got "
                         f"{positions[0]!r} … {positions[-1]!r}")
    return np.append(positions, positions[0] + length) if periodic else positions


def _widths(nodes: np.ndarray, periodic: bool) -> np.ndarray:
    """Each column's share of the axis [m] (half the distance between its neighbours; the ends of a free window
    half their interval)."""
    intervals = np.diff(nodes)
    if periodic:
        return 0.5 * (intervals + np.roll(intervals, 1))
    return 0.5 * (np.append(intervals, 0.0) + np.append(0.0, intervals))


def graded_positions(length: float, edges, finest: float, coarsest: float, ratio: float = 1.15) -> np.ndarray:
    """Column positions [m] on a periodic window of ``length`` [m] graded towards the contact lines at ``edges``
    [m]: the spacing is ``finest`` at a line and grows by ``ratio`` per column away from it up to ``coarsest``, the
    columns nearest a line ``finest``/2 from it on either side. Near a crack-like edge (g ∝ √s) the relative rise of
    the gap across a column, Δx g'/g = Δx/(2s), then stays about (ratio − 1)/2 down to ``finest``."""
    length = check_positive("length", length)
    finest, coarsest = check_positive("finest", finest), check_positive("coarsest", coarsest)
    ratio = check_real("ratio", ratio, low=1.0, low_open=True)
    if coarsest < finest:
        raise ValueError(f"coarsest = {coarsest!r} m must be at least finest = {finest!r} m")
    edges = np.mod(np.atleast_1d(np.asarray(edges, dtype=float)), length)
    steps = [finest]
    while steps[-1] < coarsest:
        steps.append(min(steps[-1] * ratio, coarsest))
    offsets = 0.5 * finest + np.concatenate([[0.0], np.cumsum(steps[1:])])     # distances from a line
    zone = offsets[-1]

    def distance(x):                                               # to the nearest line, periodically
        gaps = np.abs(np.subtract.outer(x, edges)) % length
        return np.min(np.minimum(gaps, length - gaps), axis=-1)

    uniform = np.arange(0.0, length, coarsest)
    points = [uniform[distance(uniform) > zone + 0.5 * coarsest]]
    points += [edge + sign * offsets for edge in edges for sign in (-1.0, 1.0)]
    points = np.unique(np.mod(np.concatenate(points), length))
    spacing = np.minimum(coarsest, np.maximum(finest, (ratio - 1.0) * distance(points) + 0.5 * finest))
    keep = [0]
    for index in range(1, points.size):                             # drop a column crowding the last one kept
        if points[index] - points[keep[-1]] >= 0.5 * min(spacing[index], spacing[keep[-1]]):
            keep.append(index)
    if points[keep[0]] + length - points[keep[-1]] < 0.5 * min(spacing[keep[0]], spacing[keep[-1]]):
        keep.pop()
    return points[keep]
def field_solve_patch(stack: DielectricStack, gap, lengths, voltage: float, periodic: bool = True,
                      insulator_rows: int = 4, air_rows: int = 4, sc_rows: int = 24, sc_first=None,
                      solver: str = "amg", tol: float = 1e-9, maxiter: int = 500) -> PatchFieldSolution:
    """Solve the stack's field over the 2-D gap field ``gap`` [m] (>= 0) on a window ``lengths`` (Lx, Ly) [m].

    The 3-D counterpart of :func:`field_solve_profile`: the same terrain-following rows under every lateral
    node, each hexahedron cut into six P1 tetrahedra (Kuhn), contact columns merged, the attraction by virtual
    work including the one-sided opening at contact. Periodic in x and y, or free (field-parallel side walls;
    there the four corner columns share their virtual work unevenly through the split, ±1/3 of a uniform gap's,
    while every other column and the sum are exact). The default solver is ``"amg"`` (LU fills in 3-D).
    """
    gap = check_finite_array("gap", gap, nonnegative=True)
    if gap.ndim != 2 or min(gap.shape) < 2:
        raise ValueError(f"gap must be a 2-D field of at least 2 × 2 values; got shape {gap.shape}")
    if np.ndim(lengths) != 1 or len(lengths) != 2:
        raise ValueError(f"lengths must be (Lx, Ly) in m; got {lengths!r}")
    lengths = tuple(check_positive("lengths", value) for value in lengths)
    voltage = check_voltage(voltage)
    spacing = tuple(length / (n if periodic else n - 1) for length, n in zip(lengths, gap.shape))
    rows = dict(insulator_rows=insulator_rows, air_rows=air_rows, sc_rows=sc_rows)
    sc_first = _check_options(rows, solver, sc_first, spacing)
    solved = _solve_stack(stack, gap, spacing, periodic, voltage, rows, sc_first, solver, tol, maxiter,
                          "field_solve_patch")
    area = np.outer(*[_tributary(n, h, periodic) for n, h in zip(gap.shape, spacing)])
    return PatchFieldSolution(
        mean_attraction=-float(solved.derivative.sum()) / (lengths[0] * lengths[1]),
        attraction=-solved.derivative.reshape(gap.shape) / area, gap=gap.copy(), energy=solved.energy,
        nodes=int(solved.mesh.points.shape[1]), elements=solved.elements, unknowns=solved.unknowns,
        converged=solved.converged, iterations=solved.iterations, residual=solved.residual)
