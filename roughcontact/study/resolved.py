"""The resolved chain, one task of the study: the patch with ridges and micro-roughness in one grid, solved with
the electrostatic attraction of the scene's field model (``[screen] field``) at one voltage under every load in
order (``docs/findings/equivalent_gap.md``)."""
from __future__ import annotations

import time

from ..solvers import solve_contact
from .apparent import apparent_scale, ring_count
from .plan import as_plan
from .records import patch_record


def solve_chain(plan, realisation: int, voltage_index: int, threads: int | None = None,
                apparent: tuple | None = None, frequency_index: int | None = None, progress=None) -> tuple:
    """One task of the study: the patch of ``realisation`` at voltage ``loads.voltages[voltage_index]`` (under
    the drive at ``screen.frequency[frequency_index]`` where the scene sets a frequency) under every load of the
    scene in order, each ring's solve warm-started from its result at the previous load (cold with the preset's
    ``warm_start`` false; a warm start that fails is repeated cold). ``plan``: the study's
    :class:`~.plan.StudyPlan`, or a Scene (planned here). ``threads`` FFT threads (default:
    ``roughcontact.fft.default_threads``); ``apparent``, the scene's :func:`apparent_scale` (computed when not
    given); ``progress``, called with no argument after each load (:class:`~.progress.LoadProgress`). Returns one
    :class:`PatchRecord` per load; deterministic, so the records do not depend on where the task runs."""
    plan = as_plan(plan)
    scene = plan.scene
    stack = scene.screen.stack()
    voltage = plan.voltages[voltage_index]
    frequency = None if frequency_index is None else plan.frequencies[frequency_index]
    law = scene.screen.interaction(voltage, frequency)       # the scene's field model; None at 0 V: the hard wall
    heights, body = plan.surface(realisation), plan.body(threads)
    lengths, spacing = plan.closing_lengths, plan.grid.spacing
    warm_start = scene.preset.warm_start
    latest = [None] * ring_count(scene)                         # each ring's last result: the next load's x0
    records = []
    for _, pressures in apparent_scale(scene) if apparent is None else apparent:
        start, solves = time.perf_counter(), 0
        for k, pressure in enumerate(pressures):
            x0 = latest[k] if warm_start else None
            result = solve_contact(heights, body, mean_pressure=pressure, interaction=law,
                                   tol=scene.preset.tolerance, x0=x0, warn=False)
            solves += 1
            if not result.converged and x0 is not None:          # a failed warm start: the solver's own start
                result = solve_contact(heights, body, mean_pressure=pressure, interaction=law,
                                       tol=scene.preset.tolerance, warn=False)
                solves += 1
            latest[k] = result
        records.append(patch_record(stack, scene.screen.field, voltage, latest, lengths, spacing, solves,
                                     time.perf_counter() - start, frequency))
        if progress is not None:
            progress()
    return tuple(records)
