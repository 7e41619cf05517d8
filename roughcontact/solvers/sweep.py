"""Load sweeps: :func:`load_steps` solves a problem at a sequence of loads, each warm-started from a prediction of
its pressure field (:func:`~roughcontact.solvers.problem.load_path`)."""
from __future__ import annotations

import numpy as np

from surfaces.validation import check_choice

from .projected_cg_gap import METHOD as PROJECTED_CG_GAP
from .result import ContactResult


PREDICTORS = ("secant", "previous")


def _secant_prediction(last, before, load):
    """Pressure field [Pa] at mean pressure ``load`` [Pa] extrapolated linearly in load from the two previous
    results, clipped at 0: p_k + w (p_k − p_{k−1}), w = (P − P_k)/(P_k − P_{k−1}) with P their mean pressures
    (the last field if the two loads coincide)."""
    if last.mean_pressure == before.mean_pressure:
        return last.pressure
    weight = (load - last.mean_pressure) / (last.mean_pressure - before.mean_pressure)
    prediction = np.subtract(last.pressure, before.pressure)
    prediction *= weight
    prediction += last.pressure
    return np.maximum(prediction, 0.0, out=prediction)


def _start_results(start) -> list:
    """The results a resumed sweep starts from: none, the last one, or the last two in order."""
    if start is None:
        return []
    starts = [start] if isinstance(start, ContactResult) else list(start) if isinstance(start, (list, tuple)) else []
    if not 1 <= len(starts) <= 2 or not all(isinstance(result, ContactResult) for result in starts):
        raise TypeError(f"start must be a ContactResult or a list of the last two, got {start!r:.60}")
    return starts


def load_steps(problem, mean_pressures, warm_start=True, start=None, progress=False, predictor="secant",
               solver_options=None):
    """The results of the checked ``problem`` (a :class:`~roughcontact.solvers.problem.ContactProblem`) at each of
    ``mean_pressures`` [Pa] in order, each solve warm-started as :func:`~roughcontact.solvers.problem.load_path`
    says (its arguments checked here, before the first step): ``problem.solve(mean_pressure=…, x0=…,
    **solver_options)``."""
    solver_options = solver_options or {}
    if "x0" in solver_options:
        raise ValueError("load_path sets x0 itself; pass warm_start=False to start every step cold, or start= "
                         "to warm-start the first step")
    starts = _start_results(start)
    if start is not None and not warm_start:
        raise ValueError("start= warm-starts the first step; it contradicts warm_start=False")
    check_choice("predictor", predictor, PREDICTORS)
    if isinstance(mean_pressures, (str, bytes)) or not np.iterable(mean_pressures):
        raise TypeError(f"mean_pressures must be a sequence of mean pressures [Pa], got {mean_pressures!r:.60}")
    return _load_steps(problem, mean_pressures, warm_start, starts, progress, predictor, solver_options)


def _load_steps(problem, mean_pressures, warm_start, starts, progress, predictor, solver_options):
    """The generator behind :func:`load_steps` (its arguments checked before the first step)."""
    from tqdm.auto import tqdm

    # a smooth law's warm start is the last result (its gap), as is the hard wall's on the gap, which sweeps faster on
    # a layered periodic body (docs/guide/solver.md, "Slow solves continue on the gap")
    smooth = problem.interaction.smooth or solver_options.get("method") == PROJECTED_CG_GAP
    previous = starts[-1] if starts else None
    before = starts[0] if len(starts) == 2 else None
    steps = tqdm(mean_pressures, desc="load path", unit="step", disable=not progress)
    for mean_pressure in steps:
        x0 = previous if warm_start else None
        if warm_start and predictor == "secant" and before is not None and not smooth:
            x0 = _secant_prediction(previous, before, mean_pressure)
        result = problem.solve(mean_pressure=mean_pressure, x0=x0, **solver_options)
        previous, before = result, previous
        steps.set_postfix(contact_fraction=f"{result.contact_fraction:.4g}", iterations=result.iterations,
                          refresh=False)
        yield result
