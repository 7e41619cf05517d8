"""What to solve, as one object: :class:`ContactProblem` (surface, body, interaction law), solved by
:func:`~roughcontact.solvers.dispatch.solve_contact` and swept by :func:`~roughcontact.solvers.sweep.load_path`."""
from __future__ import annotations

from dataclasses import dataclass

from surfaces import HeightField

from ..body import ElasticHalfSpace
from ..interactions import HardWall, Interaction
from .dispatch import solve_contact
from .inputs import _checked_interaction, _heights
from .result import ContactResult
from .sweep import load_path


@dataclass(frozen=True)
class ContactProblem:
    """What to solve: the topography ``surface`` h [m], the elastic ``body`` and the ``interaction`` law.

    ``problem.solve(mean_pressure=…)`` (or ``total_force=`` [N], ``penetration=`` [m]; solver options as in
    :func:`solve_contact`) returns a :class:`ContactResult`; ``problem.load_path(loads)`` sweeps the load.
    """

    surface: HeightField
    body: ElasticHalfSpace
    interaction: Interaction = HardWall()

    def __post_init__(self):
        if not isinstance(self.body, ElasticHalfSpace):
            raise TypeError(f"body must be an ElasticHalfSpace, got {type(self.body).__name__}")
        if not isinstance(self.surface, HeightField):
            object.__setattr__(self, "surface", HeightField(self.body.grid, _heights(self.surface, self.body)))
        elif self.surface.grid != self.body.grid:
            raise ValueError(f"surface.grid {self.surface.grid} differs from the body's grid {self.body.grid}")
        object.__setattr__(self, "interaction", _checked_interaction(self.interaction))

    def solve(self, **control_and_options) -> ContactResult:
        return solve_contact(self.surface, self.body, interaction=self.interaction, **control_and_options)

    def load_path(self, mean_pressures, **options):
        return load_path(self.surface, self.body, mean_pressures, interaction=self.interaction, **options)
