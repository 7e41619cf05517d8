"""The input checks that every contact solver shares: the body, the heights on its grid, the interaction law,
the default tolerance."""
from __future__ import annotations

import math

import numpy as np

from surfaces import HeightField
from surfaces.validation import check_finite_array

from ..body import ElasticHalfSpace
from ..interactions import HardWall, Interaction


def _check_body(body) -> None:
    if not isinstance(body, ElasticHalfSpace):
        raise TypeError(f"body must be an ElasticHalfSpace, got {type(body).__name__}")


def _heights(surface, body) -> np.ndarray:
    if isinstance(surface, HeightField):
        if surface.grid != body.grid:
            raise ValueError(f"surface.grid {surface.grid} differs from the body's grid {body.grid}")
        heights = surface.heights
    else:
        heights = check_finite_array("surface", surface)
        if heights.shape != body.grid.shape:
            raise ValueError(f"surface has shape {heights.shape}, but the body's grid has shape "
                             f"{body.grid.shape}")
    return np.ascontiguousarray(heights, dtype=body.dtype)


def default_tolerance(dtype, interaction=None) -> float:
    """The default relative tolerance of a solve in ``dtype``: 1e-8 in float64; in float32 1e-6 for the hard wall
    (its round-off floor is near 1e-7) and 1e-5 with a smooth law (the energy's round-off stops the line search
    near 4e-6)."""
    if np.dtype(dtype) == np.float64:
        return 1e-8
    return 1e-5 if interaction is not None and interaction.smooth and not interaction.vanishes else 1e-6


def _checked_interaction(interaction) -> Interaction:
    """The law to solve with (HardWall() for None), checked."""
    if interaction is None:
        return HardWall()
    if not isinstance(interaction, Interaction):
        raise TypeError(f"interaction must be an Interaction (roughcontact.interactions), got "
                        f"{type(interaction).__name__}")
    if type(interaction) is Interaction:
        raise ValueError("interaction = Interaction() is the abstract base class; pass a law such as HardWall(), "
                         "ElectrostaticInteraction(stack, voltage) or a subclass that implements energy, traction "
                         "and stiffness")
    if interaction.smooth:
        length = getattr(interaction, "length", None)
        if isinstance(length, bool) or not isinstance(length, (int, float, np.floating, np.integer)) \
                or not math.isfinite(length) or length <= 0:
            raise ValueError(f"interaction {type(interaction).__name__} needs length, the gap scale [m] over which "
                             f"it varies, a finite float > 0 (valid range (0, inf)); got {length!r}")
        strength = interaction.strength
        if strength is not None and not (isinstance(strength, (int, float, np.floating)) and strength >= 0):
            raise ValueError(f"interaction {type(interaction).__name__}.strength, its largest attraction [Pa], must "
                             f"be None or a float >= 0 (valid range [0, inf)); got {strength!r}")
    return interaction
