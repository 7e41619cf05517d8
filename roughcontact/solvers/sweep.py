"""Load sweeps: :func:`load_path` solves a sequence of loads, each warm-started from a prediction of its
pressure field."""
from __future__ import annotations

import numpy as np

from surfaces.validation import check_choice

from ..body import ElasticHalfSpace
from .dispatch import solve_contact
from .inputs import _checked_interaction
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


def load_path(surface, body: ElasticHalfSpace, mean_pressures, warm_start=True, start=None, progress=False,
              predictor="secant", **solver_options):
    """Yield :func:`solve_contact` results for each of ``mean_pressures`` [Pa] in order.

    With ``warm_start`` each solve starts from a prediction of its pressure field, which the solver rescales
    to the new load: ``predictor="secant"`` (default) extrapolates linearly in load from the two previous
    results (:func:`_secant_prediction`; exact where p is linear in load, e.g. in full contact), ``"previous"``
    takes the last field as it is; the first warm step has only one result and takes it. ``start`` warm-starts
    the first step, so a sweep resumes where it stopped: a ``ContactResult`` (e.g. the last one saved by an
    interrupted sweep) or the last two in order, with which the secant predictor continues exactly as if
    uninterrupted. ``progress`` shows a tqdm bar with the contact fraction and iterations of the
    last step. ``solver_options`` go to :func:`solve_contact`. (docs/guide/solver.md, "Warm start", measures the
    predictors and lists the variants that did not shorten warm solves.)
    """
    if "x0" in solver_options:
        raise ValueError("load_path sets x0 itself; pass warm_start=False to start every step cold, or start= "
                         "to warm-start the first step")
    starts = _start_results(start)
    if start is not None and not warm_start:
        raise ValueError("start= warm-starts the first step; it contradicts warm_start=False")
    check_choice("predictor", predictor, PREDICTORS)
    if isinstance(mean_pressures, (str, bytes)) or not np.iterable(mean_pressures):
        raise TypeError(f"mean_pressures must be a sequence of mean pressures [Pa], got {mean_pressures!r:.60}")
    smooth = _checked_interaction(solver_options.get("interaction")).smooth   # (its warm start is the last gap)
    return _load_steps(surface, body, mean_pressures, warm_start, starts, progress, predictor, smooth,
                       solver_options)


def _load_steps(surface, body, mean_pressures, warm_start, starts, progress, predictor, smooth, solver_options):
    """The generator behind :func:`load_path` (its arguments checked before the first step)."""
    from tqdm.auto import tqdm

    previous = starts[-1] if starts else None
    before = starts[0] if len(starts) == 2 else None
    steps = tqdm(mean_pressures, desc="load path", unit="step", disable=not progress)
    for mean_pressure in steps:
        x0 = previous if warm_start else None
        if warm_start and predictor == "secant" and before is not None and not smooth:
            x0 = _secant_prediction(previous, before, mean_pressure)
        result = solve_contact(surface, body, mean_pressure=mean_pressure, x0=x0, **solver_options)
        previous, before = result, previous
        steps.set_postfix(contact_fraction=f"{result.contact_fraction:.4g}", iterations=result.iterations,
                          refresh=False)
        yield result
