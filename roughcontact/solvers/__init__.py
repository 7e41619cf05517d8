"""Contact solvers. Layer 3: imports the body, the interaction laws and io below it.

Inside, imports run one way: :mod:`.result` (what every solver returns) ← :mod:`.inputs` (the checks, and the
:class:`Control` of a solve) ← :mod:`.polonsky_keer` (the hard wall) ← :mod:`.starts` (a smooth law's start: the
hard-wall solve) ← :mod:`.projected_cg_gap` (smooth laws) ← :mod:`.deferred_correction` (an AC drive, around the
smooth solve) ← :mod:`.dispatch` (the registry of methods) ← :mod:`.sweep` (a problem's load and voltage steps) ←
:mod:`.problem` (:class:`ContactProblem`, checked once, with :func:`solve_contact`, :func:`load_path` and
:func:`voltage_path`) ← :mod:`.continuation` (approach/retract paths and pull-off). The methods take a checked
problem and control and check nothing again.
"""
from __future__ import annotations

from .continuation import JUMP_AREA, LoadCycle, PullOff, load_cycle, pull_off
from .inputs import Control, default_tolerance
from .problem import ContactProblem, load_path, solve_contact, voltage_path
from .result import PERIMETER_CORRECTION, ContactResult, SolverReport, SolverState, boundary_edges
from .sweep import PREDICTORS

__all__ = ["ContactProblem", "ContactResult", "Control", "JUMP_AREA", "LoadCycle", "PERIMETER_CORRECTION",
           "PREDICTORS", "PullOff", "SolverReport", "SolverState", "boundary_edges", "default_tolerance",
           "load_cycle", "load_path", "pull_off", "solve_contact", "voltage_path"]
