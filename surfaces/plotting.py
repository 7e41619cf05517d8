"""Plotting helpers for height fields: map, profile and PSD.

Each takes ``ax=None`` (a new figure is made only then) and returns the matplotlib artist it drew.
matplotlib is imported lazily; nothing here calls ``plt.show`` or edits ``rcParams``. Axes are labelled in
mm and heights in µm (conversion at this boundary only; the fields are in metres).
"""
from __future__ import annotations

import numpy as np

from .validation import check_choice, check_integer
from .heightfield import HeightField
from .statistics import psd

_MM, _UM = 1e3, 1e6


def _axes(ax):
    if ax is None:
        import matplotlib.pyplot as plt
        ax = plt.subplots()[1]
    return ax


def _field(field) -> HeightField:
    if not isinstance(field, HeightField):
        raise TypeError(f"field must be a surfaces.HeightField, got {type(field).__name__}")
    return field


def plot_map(field: HeightField, ax=None, cmap: str = "viridis", colorbar: bool = True):
    """Height map ``h(x, y)`` in µm over x, y in mm; returns the ``AxesImage`` (x horizontal)."""
    field = _field(field)
    ax = _axes(ax)
    (lx, ly), (dx, dy) = field.grid.lengths, field.grid.spacing
    image = ax.imshow(field.heights.T * _UM, origin="lower", cmap=cmap, interpolation="nearest",
                      extent=(-0.5 * dx * _MM, (lx - 0.5 * dx) * _MM, -0.5 * dy * _MM, (ly - 0.5 * dy) * _MM))
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    if colorbar:
        ax.figure.colorbar(image, ax=ax, label="height [µm]")
    return image


def plot_profile(field: HeightField, ax=None, axis: int = 0, index=None, **line_kwargs):
    """Height profile in µm along ``axis`` (0: x, 1: y) through row/column ``index`` (default: middle);
    returns the ``Line2D``."""
    field = _field(field)
    check_choice("axis", axis, {0, 1})
    other = 1 - axis
    n_other = field.grid.shape[other]
    index = n_other // 2 if index is None else index
    check_integer("index", index, low=0, high=n_other - 1)
    ax = _axes(ax)
    heights = np.take(field.heights, index, axis=other)
    (line,) = ax.plot(field.grid.coordinates()[axis] * _MM, heights * _UM, **line_kwargs)
    ax.set_xlabel(f"{'xy'[axis]} [mm]")
    ax.set_ylabel("height [µm]")
    return line


def plot_psd(field: HeightField, ax=None, **line_kwargs):
    """Radially averaged PSD ``C(q)`` [m^4] (profile: ``C₁`` [m^3]) against ``q`` [rad/m], log–log;
    returns the ``Line2D``."""
    field = _field(field)
    q, spectrum = psd(field)
    ax = _axes(ax)
    (line,) = ax.loglog(q, spectrum, **line_kwargs)
    ax.set_xlabel("q [rad/m]")
    ax.set_ylabel("C₁(q) [m³]" if field.grid.is_profile else "C(q) [m⁴]")
    return line
