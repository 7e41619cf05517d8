"""A parameter study run: every variant of a :class:`~.variants.VariantStudy` planned, their tasks solved on one
executor through one task store, and the sensitivity of the outputs to the inputs (:mod:`.sensitivity`).

Each variant is a scene planned with :func:`~.plan.plan_study`; its tasks keep their content keys, so a task
that several variants share (equal inputs: a variant equal to the baseline, a listed value equal to the
scene's own) is solved once, and a task that another run (of any scene or study sharing the task directory)
solved is read back. An interrupted run resumes with the missing tasks; a changed input, a replaced scan
included, is a new key, solved again.
"""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from surfaces import HeightField

from ..io.provenance import output_directory
from .apparent import apparent_scale
from .execution import PATCHES, TaskStore, VariantDirectory, check_executor, task_store
from .plan import plan_study
from .run import StudyResult, assemble_study_result, checked_plan, open_results as open_study_results, solve_plans
from .sensitivity import OUTPUTS, Sensitivity, analyse, study_outputs
from .variants import VariantStudy, has_variation, load_variant_study


@dataclass(frozen=True, eq=False)
class VariantStudyResult:
    """A finished parameter study: the ``study`` (base scene, variation, variants), one
    :class:`~.run.StudyResult` per variant in ``results``, the ``outputs`` of each (``{output: array (variants,
    loads, voltages)}``, :data:`~.sensitivity.OUTPUTS`) and their ``sensitivity`` to the inputs; ``tasks`` the
    distinct tasks of all variants, ``computed`` those solved in this run and ``solves`` its contact solves."""

    study: VariantStudy
    results: tuple
    outputs: dict
    sensitivity: Sensitivity
    tasks: int
    computed: int
    solves: int

    @property
    def variants(self) -> tuple:
        """The :class:`~.variants.Variant` of each result."""
        return self.study.variants

    @property
    def design(self) -> str:
        return self.study.design

    @property
    def base(self):
        """The base scene (the baseline)."""
        return self.study.base

    @property
    def normal_forces(self) -> np.ndarray:
        return np.array(self.base.loads.normal_forces)

    @property
    def voltages(self) -> np.ndarray:
        return np.array(self.base.loads.voltages)

    @property
    def point(self) -> tuple:
        """(F_N, U) of the report's sensitivity figure: the ``[vary] point``, else the first load at the highest
        voltage."""
        return self.study.variation.point or (float(self.normal_forces[0]), float(self.voltages[-1]))


def _apparent(scenes) -> list:
    """:func:`apparent_scale` of each scene, once per distinct fingerpad, skin, loads and rings."""
    found, scales = {}, []
    for scene in scenes:
        key = (scene.fingerpad, scene.skin, scene.loads, scene.preset.rings)
        if key not in found:
            found[key] = apparent_scale(scene)
        scales.append(found[key])
    return scales


def _assemble(study: VariantStudy, plans, apparents, records: dict, solved: set) -> VariantStudyResult:
    """The :class:`VariantStudyResult` of every task's ``records`` by key; ``solved`` the keys solved in this
    run."""
    results = tuple(assemble_study_result(plan, {task.index: records[task.key] for task in plan.tasks}, apparent,
                                  [task for task in plan.tasks if task.key in solved])
                    for plan, apparent in zip(plans, apparents))
    per_variant = [study_outputs(result) for result in results]
    outputs = {name: np.stack([values[name] for values in per_variant]) for name in OUTPUTS}
    sensitivity = analyse(study.variation, outputs, study.base.loads.normal_forces, study.base.loads.voltages,
                          study.unit_sample)
    distinct = {task.key for plan in plans for task in plan.tasks}
    return VariantStudyResult(study=study, results=results, outputs=outputs, sensitivity=sensitivity,
                              tasks=len(distinct), computed=len(solved),
                              solves=sum(record.solves for key in solved for record in records[key]))


def run_variants(study: VariantStudy, directory=None, progress: bool = False, workers: int | None = None,
                 dask: str | None = None, tasks=None) -> VariantStudyResult:
    """Run (or resume, with a ``directory``) the parameter study ``study`` (:func:`~.variants.load_variant_study`):
    every variant planned, the distinct tasks of all of them on one executor (``workers``, ``dask`` as in
    :func:`~.run.run_study`), stored in one task store (``directory/tasks``, or the shared directory ``tasks``),
    then the outputs and their sensitivity. ``directory`` (a :class:`~.execution.VariantDirectory`) refuses
    another study."""
    if not isinstance(study, VariantStudy):
        raise TypeError(f"study must be a VariantStudy (roughcontact.study.load_variant_study reads one), got "
                        f"{type(study).__name__}")
    if not isinstance(progress, bool):
        raise TypeError(f"progress must be True or False, got {progress!r}")
    check_executor(workers, dask)
    plans = plan_variants(study)
    results = None if directory is None else VariantDirectory(output_directory(directory), study, plans, tasks)
    store = task_store(results, tasks)
    try:
        apparents = _apparent(variant.scene for variant in study.variants)
        records, solved = solve_plans(list(zip(plans, apparents)), store, workers, dask, progress)
    finally:
        if results is not None:
            results.release()
    return _assemble(study, plans, apparents, records, solved)


def plan_variants(study: VariantStudy) -> list:
    """Every variant's plan, each checked as one scene is (:func:`~.run.checked_plan`); ValueError naming the
    variant whose patch or drive is refused."""
    plans = []
    for variant in study.variants:
        try:
            plans.append(checked_plan(variant.scene))
        except ValueError as error:
            raise ValueError(f"variant {variant.index} ({variant.label}): {error}") from error
    return plans


def open_variant_results(directory, tasks=None) -> VariantStudyResult:
    """The :class:`VariantStudyResult` of a finished parameter study's results directory, read from its
    ``scene.toml``, its variants' measured patches and its tasks (or the shared ``tasks``) without solving
    (``computed`` and ``solves`` are 0). ValueError naming the directory where tasks are missing."""
    path = Path(directory)
    study = load_variant_study(path / "scene.toml", read_scan=False)
    plans = []
    for index, variant in enumerate(study.variants):
        patch = path / PATCHES / f"{index}.npz"
        measured = variant.scene.roughness.topography and patch.exists()
        plans.append(plan_study(variant.scene, HeightField.load(patch) if measured else None))
    store = TaskStore(path / "tasks" if tasks is None else tasks)
    records, missing = {}, set()
    for plan in plans:
        for task in plan.tasks:
            if task.key in records or task.key in missing:
                continue
            if (done := store.load(plan, task)) is not None:
                records[task.key] = done
            else:
                missing.add(task.key)
    if missing:
        raise ValueError(f"directory = {str(path)!r} is not finished: {len(missing)} task files missing or unusable "
                         f"in {store.directory}; the same 'roughcontact run' command resumes it")
    return _assemble(study, plans, _apparent(variant.scene for variant in study.variants), records, set())



def open_results(directory, tasks=None) -> StudyResult | VariantStudyResult:
    """The results of a finished results directory (``roughcontact run --out DIR``) without solving: a parameter
    study's whole set (:func:`open_variant_results`), else the one study's (``run.open_results``)."""
    stored = Path(directory) / "scene.toml"
    if stored.is_file() and has_variation(stored):
        return open_variant_results(directory, tasks)
    return open_study_results(directory, tasks)
