"""Sensitivity of a parameter study's outputs to its inputs (:mod:`.variants`).

The outputs (:data:`OUTPUTS`) are the realisation means of a variant's study at every load and voltage: d_eq
(seed Eq. 25), the field-equivalent gap d_field, the electrostatic force F_el = σ̄_el A0, the ridge contact
fraction A_R/A0 at the coarse-graining length and the bottom-up friction coefficient μ of the ridge-area recipe
(:func:`~.friction.bottom_up_friction`; NaN for a study of one load or with a point where no realisation
converged). :func:`analyse` measures how each input moves each output at each (F_N, U):

* **one at a time** (a tornado): the output at the input's lowest and highest level relative to the baseline,
  (y − y₀)/|y₀|, and its swing, (max − min)/|y₀| over the baseline and the input's levels (:data:`RANKED_BY`);
* **Morris** (SALib ``SALib.analyze.morris``): μ, μ* (the mean absolute elementary effect, for ranking), σ and
  the 95 % interval of μ*, per unit of the input's coordinate in [0, 1] (a log range per decade fraction);
* **Sobol'** (SALib ``SALib.analyze.sobol``, no second order): the first-order index S1, the total index ST
  (for ranking) and their 95 % intervals.

A point where the output is the same in every variant (F_el at 0 V) or not finite in some (a point whose solves
failed) has NaN measures.
"""
from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np

from .friction import bottom_up_friction, friction_computed
from .run import StudyResult
from .variants import DESIGNS, Variation, salib_problem

#: The outputs: name -> (symbol, unit).
OUTPUTS = {"equivalent_gap": ("d_eq", "m"), "field_equivalent_gap": ("d_field", "m"),
           "electrostatic_force": ("F_el", "N"), "ridge_area_fraction": ("A_R/A0", "1"),
           "friction_coefficient": ("μ", "1")}
#: The measures of each design, and the one that ranks the inputs.
MEASURES = {"one-at-a-time": ("low", "high", "swing"), "morris": ("mu", "mu_star", "sigma", "mu_star_conf"),
            "sobol": ("S1", "S1_conf", "ST", "ST_conf")}
RANKED_BY = {"one-at-a-time": "swing", "morris": "mu_star", "sobol": "ST"}


def study_outputs(result: StudyResult) -> dict:
    """``{output: array (loads, voltages)}`` of one study (:data:`OUTPUTS`; at its drive frequency, if it has
    one)."""
    if result.frequencies:
        result = result.at_frequency(0)
    forces, voltages = result.normal_forces, result.voltages
    values = {"equivalent_gap": result.summary("equivalent_gap")[0],
              "field_equivalent_gap": result.summary("field_equivalent_gap")[0],
              "electrostatic_force": result.summary("electrostatic_attraction")[0] * result.array("apparent_area"),
              "ridge_area_fraction": result.summary("ridge_area_fractions")[0][:, :, 0]}
    friction = np.full((forces.size, voltages.size), np.nan)
    if friction_computed(result):
        friction = bottom_up_friction(result).state(forces[:, None], voltages[None, :]).friction_coefficient
    values["friction_coefficient"] = np.asarray(friction, dtype=float)
    return values


@dataclass(frozen=True, eq=False)
class Sensitivity:
    """The sensitivity of each output to each input at each load and voltage: ``measures[name]`` of shape
    (outputs, inputs, loads, voltages) for the ``design``'s measures (:data:`MEASURES`); ``baseline`` the
    outputs of the baseline (one at a time; shape (outputs, loads, voltages)), else None."""

    design: str
    inputs: tuple
    outputs: tuple
    normal_forces: tuple
    voltages: tuple
    measures: dict
    baseline: np.ndarray | None = None

    @property
    def ranked_by(self) -> str:
        """The measure that ranks the inputs: the swing, Morris μ* or the total Sobol' index ST."""
        return RANKED_BY[self.design]

    def measure(self, name: str, output: str, normal_force: float, voltage: float) -> np.ndarray:
        """Measure ``name`` of every input for ``output`` at (``normal_force``, ``voltage``)."""
        if name not in self.measures:
            raise ValueError(f"measure = {name!r} is not one of the {self.design} design's: {', '.join(self.measures)}")
        return self.measures[name][self._index(output, normal_force, voltage)]

    def ranking(self, output: str, normal_force: float, voltage: float) -> tuple:
        """The inputs, the most influential on ``output`` at (``normal_force``, ``voltage``) first (by
        :attr:`ranked_by`, magnitude; NaN last)."""
        values = np.abs(self.measure(self.ranked_by, output, normal_force, voltage))
        order = sorted(range(len(self.inputs)), key=lambda i: (not np.isfinite(values[i]), -np.nan_to_num(values[i])))
        return tuple(self.inputs[i] for i in order)

    def _index(self, output, normal_force, voltage) -> tuple:
        if output not in self.outputs:
            raise ValueError(f"output = {output!r} is not one of {', '.join(self.outputs)}")
        for value, axis, name in ((normal_force, self.normal_forces, "normal_force"), (voltage, self.voltages,
                                                                                       "voltage")):
            if value not in axis:
                raise ValueError(f"{name} = {value!r} is not one of the study's: {list(axis)}")
        return (self.outputs.index(output), slice(None), self.normal_forces.index(normal_force),
                self.voltages.index(voltage))


def one_at_a_time_indices(variation: Variation) -> tuple:
    """The variant indices of each input's levels in a one-at-a-time design (the baseline is variant 0)."""
    indices, start = [], 1
    for item in variation.inputs:
        indices.append(tuple(range(start, start + len(item.levels))))
        start += len(item.levels)
    return tuple(indices)


def analyse(variation: Variation, values: dict, normal_forces, voltages, unit_sample=None) -> Sensitivity:
    """The :class:`Sensitivity` of the outputs ``values`` (``{output: array (variants, loads, voltages)}``, the
    variants in the design's order) to the inputs of ``variation``; ``unit_sample`` the sampler's points of a
    global design (variants × inputs)."""
    outputs = tuple(values)
    stacked = np.stack([np.asarray(values[name], dtype=float) for name in outputs])   # (outputs, variants, i, j)
    if variation.design == DESIGNS[0]:
        measures, baseline = _tornado(variation, stacked), stacked[:, 0]
    else:
        measures, baseline = _global(variation, stacked, np.asarray(unit_sample, dtype=float)), None
    return Sensitivity(design=variation.design, inputs=variation.names, outputs=outputs,
                       normal_forces=tuple(float(f) for f in normal_forces),
                       voltages=tuple(float(v) for v in voltages), measures=measures, baseline=baseline)


def _tornado(variation: Variation, stacked: np.ndarray) -> dict:
    """Relative changes at each input's lowest and highest level and its swing (module docstring)."""
    baseline = stacked[:, 0]
    shape = (stacked.shape[0], len(variation.inputs), *stacked.shape[2:])
    low, high, swing = (np.full(shape, np.nan) for _ in range(3))
    with np.errstate(divide="ignore", invalid="ignore"):
        for i, (item, indices) in enumerate(zip(variation.inputs, one_at_a_time_indices(variation))):
            ordered = list(indices)
            if not isinstance(item.levels[0], str):
                ordered = [index for _, index in sorted(zip(item.levels, indices))]
            scale = np.abs(baseline)
            scale = np.where(scale > 0, scale, np.nan)
            low[:, i] = (stacked[:, ordered[0]] - baseline) / scale
            high[:, i] = (stacked[:, ordered[-1]] - baseline) / scale
            group = stacked[:, [0, *indices]]
            swing[:, i] = (np.max(group, axis=1) - np.min(group, axis=1)) / scale
    return {"low": low, "high": high, "swing": swing}


def _global(variation: Variation, stacked: np.ndarray, unit: np.ndarray) -> dict:
    """Morris or Sobol' measures at every output, load and voltage (SALib)."""
    from SALib.analyze import morris, sobol
    names = MEASURES[variation.design]
    shape = (stacked.shape[0], len(variation.inputs), *stacked.shape[2:])
    measures = {name: np.full(shape, np.nan) for name in names}
    problem = salib_problem(variation.names)
    for index in np.ndindex(stacked.shape[0], *stacked.shape[2:]):
        y = stacked[index[0], :, index[1], index[2]]
        if not np.all(np.isfinite(y)) or np.ptp(y) <= 1e-12 * np.max(np.abs(y)):
            continue
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            if variation.design == "morris":
                found = morris.analyze(problem, unit, y, num_levels=variation.levels, seed=variation.seed)
            else:
                found = sobol.analyze(problem, y, calc_second_order=False, seed=variation.seed)
        for name in names:
            measures[name][index[0], :, index[1], index[2]] = np.asarray(found[name], dtype=float)
    return measures
