"""Interaction laws between the elastic surface and the rigid counter-face, as functions of the gap g [m].

An interaction is described by three per-area quantities (``docs/conventions.md``; ``docs/solver.md``):

* ``energy(g)``     V(g) [J/m²], the interaction energy per unit area;
* ``traction(g)``   p_int(g) = −dV/dg [Pa], the normal traction it exerts on the elastic body, positive
                    compressive (repulsive); an attraction such as electroadhesion is negative;
* ``stiffness(g)``  k(g) = dp_int/dg [Pa/m], what a Newton step on the gap needs.

The hard wall (non-penetration, no adhesion) is the singular member of the family: V = 0 for g ≥ 0 and
+∞ for g < 0; its traction is not a function of the gap but the Lagrange multiplier that the constrained
conjugate-gradient solver computes, so ``HardWall.traction``/``stiffness`` are zero wherever it is smooth
(g > 0). Smooth laws (the dielectric stack's attraction −σ_el(g)) add their traction to the wall's
multiplier; ``docs/solver.md`` describes how the solver takes them.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from surfaces._checks import check_finite_array


class Interaction:
    """Base class: a gap-dependent interaction law (energy, traction, stiffness; see module docstring)."""

    #: True when the law contains the non-penetration constraint g ≥ 0.
    hard_wall: bool = False

    def energy(self, gap) -> np.ndarray:
        raise NotImplementedError

    def traction(self, gap) -> np.ndarray:
        raise NotImplementedError

    def stiffness(self, gap) -> np.ndarray:
        raise NotImplementedError


@dataclass(frozen=True)
class HardWall(Interaction):
    """Non-adhesive, impenetrable rigid flat: V(g) = 0 for g ≥ 0, +∞ for g < 0.

    The contact pressure is the multiplier of the constraint g ≥ 0, found by the solver (complementarity
    p ≥ 0, g ≥ 0, p g = 0); away from contact the wall exerts no traction.
    """

    hard_wall = True

    def energy(self, gap) -> np.ndarray:
        """V(g) [J/m²]: 0 where g ≥ 0, +inf where the wall is penetrated."""
        gap = check_finite_array("gap", gap)
        return np.where(gap >= 0, 0.0, np.inf)

    def traction(self, gap) -> np.ndarray:
        """p_int(g) = −dV/dg [Pa] for g > 0: zero (the contact pressure is the solver's multiplier)."""
        return np.zeros_like(check_finite_array("gap", gap, nonnegative=True))

    def stiffness(self, gap) -> np.ndarray:
        """k(g) = dp_int/dg [Pa/m] for g > 0: zero."""
        return np.zeros_like(check_finite_array("gap", gap, nonnegative=True))
