"""Contact solvers. Layer 3: imports the body, the interaction laws and io below it.

Inside, imports run one way: :mod:`.inputs` and :mod:`.result` (what every solver takes and returns) ←
:mod:`.polonsky_keer` (the hard wall) ← :mod:`.projected_cg_gap` (smooth laws; its cold start is a hard-wall
solve) ← :mod:`.deferred_correction` (an AC drive, around the smooth solve) ← :mod:`.dispatch`
(:func:`solve_contact`, which picks the method) ← :mod:`.sweep` (:func:`load_path`) ←
:mod:`.problem` (:class:`ContactProblem`) ← :mod:`.continuation` (approach/retract paths and pull-off).
"""
from __future__ import annotations

from .continuation import JUMP_AREA, LoadCycle, PullOff, load_cycle, pull_off
from .dispatch import solve_contact
from .inputs import default_tolerance
from .problem import ContactProblem
from .result import PERIMETER_CORRECTION, ContactResult, SolverReport, SolverState, boundary_edges
from .sweep import PREDICTORS, load_path

__all__ = ["ContactProblem", "ContactResult", "JUMP_AREA", "LoadCycle", "PERIMETER_CORRECTION", "PREDICTORS", "PullOff",
           "SolverReport", "SolverState", "boundary_edges", "default_tolerance", "load_cycle", "load_path", "pull_off",
           "solve_contact"]
