"""Contact length of a node-to-plane contact, the fit of seed Eq. 34 and power laws (numpy only).

Contact length. The plate carries the nodal forces f_i of the contact nodes at the deformed abscissae x_i.
The tributary length of node i is half the distance between its neighbours, so its mean pressure is
p_i = f_i / ℓ_i. At the edge of a smooth (non-conforming) contact the pressure falls as √(distance to the
edge), so p² is linear in x there: the edge is the zero of the straight line through p² of the outermost two
loaded nodes, kept between the outermost loaded node and its open neighbour. This converges faster with the
mesh than the zero crossing of the linearly interpolated gap (``edge="gap"``), which the penalty method
places just outside the last penetrating node.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np


def _tributary_lengths(x: np.ndarray) -> np.ndarray:
    """Half the distance between each node's neighbours along x (sorted x) [m]."""
    padded = np.concatenate([[x[0] - (x[1] - x[0])], x, [x[-1] + (x[-1] - x[-2])]])
    return (padded[2:] - padded[:-2]) / 2


def contact_pressure(x, force) -> np.ndarray:
    """Nodal pressure p_i = f_i/ℓ_i [Pa] of normal nodal forces per unit width ``force`` [N/m] at the sorted
    abscissae ``x`` [m]."""
    return np.asarray(force, float) / _tributary_lengths(np.asarray(x, float))


def _edge_pressure(x, p2, last, outside):
    """Zero of the line through p² at nodes ``last`` and its inner neighbour, clipped to [x_last, x_outside]."""
    inner = last - np.sign(outside - last)
    slope = (p2[last] - p2[inner]) / (x[last] - x[inner])
    edge = x[last] - p2[last] / slope if slope != 0 else x[last]
    low, high = sorted((x[last], x[outside]))
    return float(np.clip(edge, low, high))


def _edge_gap(x, gap, last, outside):
    """Zero crossing of the gap interpolated linearly between nodes ``last`` (g ≤ 0) and ``outside`` (g > 0)."""
    share = -gap[last] / (gap[outside] - gap[last])
    return float(x[last] + share * (x[outside] - x[last]))


def contact_edges(x, force, gap, edge: str = "pressure") -> tuple:
    """Trailing and leading edge (x_min, x_max) [m] of the contact of nodes at abscissae ``x`` [m] with normal
    forces ``force`` [N/m] (> 0 in contact) and gaps ``gap`` [m]; ``edge`` "pressure" (module docstring) or
    "gap". (nan, nan) without contact."""
    x, force, gap = (np.asarray(a, float) for a in (x, force, gap))
    order = np.argsort(x)
    x, force, gap = x[order], force[order], gap[order]
    loaded = np.flatnonzero(force > 0)
    if loaded.size == 0:
        return float("nan"), float("nan")
    first, last = loaded[0], loaded[-1]
    if first == 0 or last == x.size - 1:
        raise ValueError("the contact reaches the end of the candidate nodes; extend the candidate surface")
    if edge == "gap":
        return _edge_gap(x, gap, first, first - 1), _edge_gap(x, gap, last, last + 1)
    if edge != "pressure":
        raise ValueError(f"edge must be 'pressure' or 'gap', got {edge!r}")
    if loaded.size < 2:
        return float(x[first]), float(x[first])
    p2 = contact_pressure(x, np.where(force > 0, force, 0.0)) ** 2
    return _edge_pressure(x, p2, first, first - 1), _edge_pressure(x, p2, last, last + 1)


def contact_length(x, force, gap, edge: str = "pressure") -> float:
    """Contact length L = x_max − x_min [m] (:func:`contact_edges`); 0 without contact."""
    low, high = contact_edges(x, force, gap, edge)
    return 0.0 if np.isnan(low) else high - low


@dataclass(frozen=True)
class LinearFit:
    """Least-squares line y = intercept + slope·t with standard errors (``*_error``) and the root-mean-square
    residual ``rms`` (units of y)."""

    intercept: float
    slope: float
    intercept_error: float
    slope_error: float
    rms: float


def linear_fit(t, y) -> LinearFit:
    """Ordinary least squares of y on t with the standard errors of σ² (XᵀX)⁻¹, σ² from the residuals."""
    t, y = np.asarray(t, float), np.asarray(y, float)
    if t.size < 3:
        raise ValueError(f"a fit with standard errors needs at least 3 points, got {t.size}")
    design = np.column_stack([np.ones_like(t), t])
    coefficients, *_ = np.linalg.lstsq(design, y, rcond=None)
    residual = y - design @ coefficients
    variance = residual @ residual / (t.size - 2)
    errors = np.sqrt(np.diag(variance * np.linalg.inv(design.T @ design)))
    return LinearFit(float(coefficients[0]), float(coefficients[1]), float(errors[0]), float(errors[1]),
                     float(np.sqrt(np.mean(residual ** 2))))


def fit_eq34(tangential_force, length) -> LinearFit:
    """Seed Eq. 34, L(f_T) = L0 − ξ f_T², as a line in f_T²: ``intercept`` L0 [m], ``slope`` −ξ [m³/N²]
    (per unit width: f_T [N/m])."""
    return linear_fit(np.asarray(tangential_force, float) ** 2, length)


def power_law_fit(x, y) -> LinearFit:
    """y = C x^k as the line ln y = ln C + k ln x: ``slope`` k with its standard error."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    if (x <= 0).any() or (y <= 0).any():
        raise ValueError("a power-law fit needs positive x and y")
    return linear_fit(np.log(x), np.log(y))
