"""Macroscopic shapes: the fingertip cap.

Heights are positive towards the counter-face (``docs/reference/conventions.md``): the apex is the maximum, at
height 0, and the cap falls away from it. Finger-pad radii of curvature are ~7–10 mm (docs/references.md §1;
8 mm is the common model value).
"""
from __future__ import annotations

import numpy as np

from .validation import check_choice, check_positive, check_real
from .grid import Grid
from .heightfield import HeightField


def fingertip(grid: Grid, radii=(8e-3, 8e-3), centre=None, shape: str = "paraboloid",
              depth=None) -> HeightField:
    """Fingertip cap with apex radii of curvature ``radii = (Rx, Ry)`` [m], apex (height 0) at ``centre``.

    ``shape='paraboloid'``: ``h = -(x-x0)²/(2 Rx) - (y-y0)²/(2 Ry)``.
    ``shape='ellipsoid'``: ``h = c (sqrt(1 - (x-x0)²/a² - (y-y0)²/b²) - 1)`` with semi-axes
    ``a = sqrt(Rx c)``, ``b = sqrt(Ry c)`` (so the apex radii are Rx, Ry) and depth ``c`` [m]
    (default ``sqrt(Rx Ry)``: a sphere when Rx = Ry); outside the footprint the height is ``-c``.
    ``centre`` (x0, y0) [m] defaults to pixel ``(nx//2, ny//2)``, the grid centre. A profile grid
    ``(n, 1)`` gives the x section. The grid is normally non-periodic (a periodic grid repeats the cap).
    """
    if not isinstance(grid, Grid):
        raise TypeError(f"grid must be a surfaces.Grid, got {type(grid).__name__}")
    check_choice("shape", shape, {"paraboloid", "ellipsoid"})
    if np.ndim(radii) != 1 or len(radii) != 2:
        raise ValueError(f"radii must be two radii of curvature (Rx, Ry) in m, got {radii!r}")
    radius_x, radius_y = (check_positive(f"radii[{axis}]", r) for axis, r in enumerate(radii))
    if centre is None:
        centre = tuple((n // 2) * d for n, d in zip(grid.shape, grid.spacing))
    if np.ndim(centre) != 1 or len(centre) != 2:
        raise ValueError(f"centre must be (x0, y0) in m, got {centre!r}")
    x0, y0 = (check_real(f"centre[{axis}]", c) for axis, c in enumerate(centre))
    x, y = grid.coordinates()
    dx2, dy2 = ((x - x0) ** 2)[:, None], ((y - y0) ** 2)[None, :]
    metadata = {"generator": "fingertip", "shape": shape, "radii": [radius_x, radius_y], "centre": [x0, y0]}
    if shape == "paraboloid":
        if depth is not None:
            raise ValueError(f"depth applies to shape='ellipsoid' only, got depth={depth!r} with a paraboloid")
        heights = -dx2 / (2 * radius_x) - dy2 / (2 * radius_y)
    else:
        depth = np.sqrt(radius_x * radius_y) if depth is None else check_positive("depth", depth)
        inside = 1 - dx2 / (radius_x * depth) - dy2 / (radius_y * depth)
        heights = depth * (np.sqrt(np.maximum(inside, 0.0)) - 1)
        metadata["depth"] = float(depth)
    return HeightField(grid, heights, metadata)
