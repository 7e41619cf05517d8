"""Load and voltage sweeps: :func:`load_steps` solves a problem at a sequence of loads, each warm-started from a
prediction of its solution (:func:`~roughcontact.solvers.problem.load_path`); :func:`voltage_steps` at a
sequence of voltages of its electrostatic law, each from the last gap (:func:`~roughcontact.solvers.problem.
voltage_path`)."""
from __future__ import annotations

import dataclasses

import numpy as np

from surfaces.validation import check_choice

from ..interactions import ElectrostaticInteraction
from .projected_cg_gap import solved_on_the_gap
from .result import ContactResult


PREDICTORS = ("secant", "previous")


def _secant(last, before, load, field):
    """The ``field`` of the results (``"pressure"`` [Pa] or ``"gap"`` [m]) at mean pressure ``load`` [Pa]
    extrapolated linearly in load from the two previous results, clipped at 0: f_k + w (f_k − f_{k−1}),
    w = (P − P_k)/(P_k − P_{k−1}) with P their mean pressures (the last field if the two loads coincide)."""
    if last.mean_pressure == before.mean_pressure:
        return getattr(last, field)
    weight = (load - last.mean_pressure) / (last.mean_pressure - before.mean_pressure)
    prediction = np.subtract(getattr(last, field), getattr(before, field))
    prediction *= weight
    prediction += getattr(last, field)
    return np.maximum(prediction, 0.0, out=prediction)


def _secant_start(last, before, load):
    """The hard wall's warm start at mean pressure ``load`` [Pa] from the two previous results: the pressure's
    secant, or, where the last was solved on the gap (Polonsky–Keer was slow on this body), the last result with
    its gap [m] extrapolated the same way, from which the solve continues on the gap
    (:func:`~roughcontact.solvers.projected_cg_gap.solve_hard_wall_handing_over`)."""
    if solved_on_the_gap(last):
        return dataclasses.replace(last, gap=_secant(last, before, load, "gap"))
    return _secant(last, before, load, "pressure")


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
    starts = _start_results(start)
    check_choice("predictor", predictor, PREDICTORS)
    _check_sweep("load_path", ("mean_pressures", mean_pressures, "mean pressures [Pa]"), solver_options, start,
                 warm_start)
    return _load_steps(problem, mean_pressures, warm_start, starts, progress, predictor, solver_options)


def _check_sweep(path: str, steps: tuple, solver_options: dict, start, warm_start) -> None:
    """The checks a sweep ``path`` shares: no ``x0`` among the solver's options (the sweep sets it), no ``start``
    without a warm start, and ``steps`` (name, values, what they are) a sequence."""
    if "x0" in solver_options:
        raise ValueError(f"{path} sets x0 itself; pass warm_start=False to start every step cold, or start= "
                         "to warm-start the first step")
    if start is not None and not warm_start:
        raise ValueError("start= warm-starts the first step; it contradicts warm_start=False")
    name, values, what = steps
    if isinstance(values, (str, bytes)) or not np.iterable(values):
        raise TypeError(f"{name} must be a sequence of {what}, got {values!r:.60}")


def _load_steps(problem, mean_pressures, warm_start, starts, progress, predictor, solver_options):
    """The generator behind :func:`load_steps` (its arguments checked before the first step)."""
    from tqdm.auto import tqdm

    # a smooth law's warm start is the last result (its gap): a secant could carry it across an instability onto
    # another branch; the hard wall's is the secant of its pressure, or of its gap where the last load was solved on
    # the gap (docs/guide/solver.md, "Warm start")
    law = problem.interaction
    wall = not law.smooth or law.vanishes
    previous = starts[-1] if starts else None
    before = starts[0] if len(starts) == 2 else None
    steps = tqdm(mean_pressures, desc="load path", unit="step", disable=not progress)
    for mean_pressure in steps:
        x0 = previous if warm_start else None
        if warm_start and predictor == "secant" and before is not None and wall:
            x0 = _secant_start(previous, before, mean_pressure)
        result = problem.solve(mean_pressure=mean_pressure, x0=x0, **solver_options)
        previous, before = result, previous
        steps.set_postfix(contact_fraction=f"{result.contact_fraction:.4g}", iterations=result.iterations,
                          refresh=False)
        yield result


def voltage_steps(problem, voltages, warm_start=True, start=None, progress=False, solver_options=None):
    """The results of the checked ``problem``, whose law is an :class:`~roughcontact.interactions.
    ElectrostaticInteraction`, with that law at each of ``voltages`` [V] in order, at the control in
    ``solver_options`` (``mean_pressure=``, ``total_force=`` or ``penetration=``, with :func:`solve_contact`'s
    other keywords), each solve started from the last result (``start``, a ContactResult, for the first) as
    :func:`~roughcontact.solvers.problem.voltage_path` says; every voltage checked before the first step."""
    law = problem.interaction
    if not isinstance(law, ElectrostaticInteraction):
        raise TypeError(f"voltage_path sweeps the voltage of an ElectrostaticInteraction; the problem's law is "
                        f"{type(law).__name__}")
    solver_options = solver_options or {}
    if start is not None and not isinstance(start, ContactResult):
        raise TypeError(f"start must be a ContactResult (the last result of the sweep resumed), got {start!r:.60}")
    _check_sweep("voltage_path", ("voltages", voltages, "voltages [V]"), solver_options, start, warm_start)
    laws = [dataclasses.replace(law, voltage=voltage) for voltage in voltages]
    return _voltage_steps(problem, laws, warm_start, start, progress, solver_options)


def _voltage_steps(problem, laws, warm_start, previous, progress, solver_options):
    """The generator behind :func:`voltage_steps` (its arguments checked before the first step)."""
    from tqdm.auto import tqdm

    steps = tqdm(laws, desc="voltage path", unit="step", disable=not progress)
    for law in steps:
        result = problem.with_heights(problem.heights, law).solve(x0=previous if warm_start else None,
                                                                  **solver_options)
        previous = result
        steps.set_postfix(voltage=f"{law.voltage:.4g}", contact_fraction=f"{result.contact_fraction:.4g}",
                          iterations=result.iterations, refresh=False)
        yield result
