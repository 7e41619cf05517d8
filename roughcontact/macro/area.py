"""Ridge area from a table: A_R(F_N, w), the role of seed Eq. 9 in the friction law when the area comes from a
bottom-up study instead of the power law."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from surfaces.validation import check_broadcast, check_finite_array

from .gap import locate, table_axis


@dataclass(frozen=True)
class TabulatedArea:
    """Ridge area A_R(F_N, w) [m²] from a table, the role of seed Eq. 9 in the friction law.

    ``normal_forces`` [N] (strictly increasing, >= 2), ``works`` w [J/m²] and ``areas`` [m²] of shape
    (len(normal_forces), k), ``works`` non-decreasing along each row (w grows with the voltage at a fixed load).
    Linear in w within a row (clamped at the row's ends) and linear in F_N between rows; F_N outside the table
    raises ``ValueError``.
    """

    normal_forces: np.ndarray
    works: np.ndarray
    areas: np.ndarray

    def __post_init__(self):
        forces = table_axis("normal_forces", self.normal_forces, 2)
        works = check_finite_array("works", self.works, nonnegative=True)
        areas = check_finite_array("areas", self.areas, nonnegative=True)
        if works.shape != areas.shape or works.shape[0] != forces.size or works.ndim != 2:
            raise ValueError(f"works {works.shape} and areas {areas.shape} must both have shape "
                             f"(len(normal_forces), k) = ({forces.size}, k)")
        if (np.diff(works, axis=1) < 0).any():
            raise ValueError("works must be non-decreasing along each row (increasing voltage)")
        for name, value in (("normal_forces", forces), ("works", works), ("areas", areas)):
            object.__setattr__(self, name, value)

    def area(self, normal_force, work_of_adhesion) -> np.ndarray:
        force, w = check_broadcast(normal_force=normal_force, work_of_adhesion=work_of_adhesion)
        index, u = locate("normal_force", self.normal_forces, force)     # the gap table's rule
        rows = np.array([np.interp(w, self.works[i], self.areas[i]) for i in range(self.normal_forces.size)])
        low = np.take_along_axis(rows, index[None], 0)[0]
        high = np.take_along_axis(rows, (index + 1)[None], 0)[0]
        return (1 - u) * low + u * high
