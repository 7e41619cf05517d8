"""The multiscale fingerpad study: d_eq(F_N, U) and A_R(F_N, U) bottom-up from a scene (``docs/findings/equivalent_gap.md``).

For each normal force F_N and voltage U:

1. **Apparent scale** (:func:`~.apparent.apparent_contact`): the apparent area A0 and the nominal pressures over
   it — one uniform pressure F_N/A0 for the power law of seed Eq. 27, or the Hertz pressure averaged over
   ``rings`` rings of equal area for a fingertip cap.
2. **Ridge and roughness scales** (:func:`~.patch.patch_surface`, :func:`~.patch.patch_body`): a periodic patch of
   ``periods`` ridge periods with the ridges and the self-affine micro-roughness resolved in one grid, pressed at
   each nominal pressure with the electrostatic attraction acting (``roughcontact.solve_contact``; 0 V is the
   hard wall). A scene without roughness is solved for one realisation only (the others would be identical).
3. **Averages over the apparent area** (rings of equal area weigh equally): d_eq by seed Eq. 25
   (``DielectricStack.equivalent_gap`` of all gaps), the arithmetic mean gap, the real contact fraction, the
   ridge contact fraction A_R/A0 (:func:`~.patch.ridge_area_fraction`: the real contact closed morphologically
   with a disc of diameter ℓ, at ℓ and at the scene's sensitivity factors on it), the mean attraction σ̄_el of
   the scene's field model (``[screen] field``), the field-equivalent gap (Eq. 21 inverted at σ̄_el), σ̄_el of
   Eq. 21 pixel by pixel on the same gap and the ratio of the two, and the ridge-area equivalent gap d_eq,R
   with σ_el(d_eq,R) A_R = σ̄_el A0 (the gap that the seed's friction law, which applies σ_el on A_R, needs).
4. **Realisations**: ``realisations`` rough patches (rng seed + r); every reported number is a mean with a 95 %
   Student-t confidence interval (:func:`~.records.confidence_interval`) over the realisations whose solves
   converged (a solve that fails from its warm start is repeated from the solver's own start first).

**Drive frequency.** A scene with ``[screen] frequency`` solves every (F_N, U) at each drive frequency f (the
AC drive of ``docs/guide/ac_drive.md``, the time-averaged attraction at RMS U): one task per (r, j, k) and a
frequency axis on every point (:meth:`StudyResult.at_frequency` gives the loads × voltages study at one of them).

**Tasks.** The sweep is split into independent, deterministic tasks, one per (realisation r, voltage index j)
(:func:`~.resolved.solve_chain`): every load in order, each solve warm-started from the previous load's result
(``x0=``; cold solves with the preset's ``warm_start`` false). A task takes the scene, r, j and its FFT thread
count and returns one :class:`~.records.PatchRecord` per load; nothing passes between tasks, so a point's numbers
do not depend on where its tasks ran or in which order they finished. :func:`run_study` runs them in this
process, in a local process pool or on a dask.distributed cluster through one loop (submit, the highest voltages
first since their solves take longest, so that the workers end together; consume as completed, store), and
assembles the :class:`~.records.PointResult` of each (F_N, U) from the records of its
realisations.

**The plan.** :func:`~.plan.plan_study` works out once what the tasks share — the patch grid, the closing
lengths, the cut-off in use, a measured scan's patch — and keys every task by the SHA-256 of exactly the inputs
its records depend on (:class:`~.plan.StudyPlan`); the tasks run from the plan.

Finished tasks are stored as they arrive in a :class:`~.execution.TaskStore` by their keys (in the results
directory, :class:`~.execution.ResultsDirectory`, or a task directory that several scenes share), so an
interrupted run resumes without recomputing finished tasks, and a task whose inputs changed (a replaced scan
included) is solved again; a different scene in the same results directory is refused
(:class:`~.execution.SceneMismatch`). The results directory keeps a measured patch beside the scene, so
:func:`open_results` reads it back after the scan has moved.
"""
from __future__ import annotations

import dataclasses
import functools
import sys
from concurrent.futures.process import BrokenProcessPool
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from surfaces import HeightField
from surfaces.validation import check_integer

from ..io.provenance import output_directory
from .apparent import apparent_scale
from .coupled import coupled_chain
from .cost import run_estimate
from .execution import (PATCH_FILE, InProcess, ResultsDirectory, TaskStore, check_executor, make_executor,
                        task_store)
from .plan import StudyPlan, plan_study
from .progress import LoadProgress
from .records import PER_REALISATION, PointResult, confidence_interval, point_result
from .resolved import solve_chain
from .scene import Scene, load_scene
from .variants import has_variation


#: The fields of a point with one value per realisation (per closing length and realisation for the A_R).
SUMMARISED = (*PER_REALISATION, "ridge_area_fractions")


@dataclass(frozen=True)
class StudyResult:
    """All points of a study and the :class:`~.plan.StudyPlan` they were solved from; ``points[i][j]`` at
    ``normal_forces[i]``, ``voltages[j]`` (``points[i][j][k]`` at ``frequencies[k]`` [Hz] too where the scene sets
    a drive frequency; ``frequencies`` is empty otherwise); ``computed`` points with a task solved in this run and
    ``solves`` the contact solves of this run."""

    plan: StudyPlan
    points: tuple
    computed: int
    solves: int
    frequencies: tuple = ()

    @property
    def scene(self) -> Scene:
        return self.plan.scene

    @property
    def coarse_graining(self) -> tuple:
        """The A_R closing diameters [m] (the scene's coarse-graining length first)."""
        return self.plan.closing_lengths

    @property
    def short_cutoff(self) -> float:
        """The micro-roughness short cut-off in use [m] (NaN without synthetic roughness)."""
        return self.plan.short_cutoff

    @property
    def normal_forces(self) -> np.ndarray:
        return np.array(self.plan.normal_forces)

    @property
    def voltages(self) -> np.ndarray:
        return np.array(self.plan.voltages)

    def array(self, name: str) -> np.ndarray:
        """Field ``name`` of every point (a field of :class:`~.records.PointResult`): shape (loads, voltages,
        realisations), or (…, lengths, realisations) for ``ridge_area_fractions``, or (loads, voltages) for
        scalars; with a frequency axis (loads, voltages, frequencies, …)."""
        names = [field.name for field in dataclasses.fields(PointResult)]
        if name not in names:
            raise ValueError(f"name = {name!r} is not a field of the study's points; valid: {', '.join(names)}")
        if self.frequencies:
            return np.array([[[getattr(point, name) for point in cell] for cell in row] for row in self.points],
                            dtype=float)
        return np.array([[getattr(point, name) for point in row] for row in self.points], dtype=float)

    def at_frequency(self, index: int) -> StudyResult:
        """The loads × voltages study at drive frequency ``frequencies[index]`` (no frequency axis)."""
        if not self.frequencies:
            raise ValueError("the study has no frequency axis (its scene sets no [screen] frequency)")
        check_integer("index", index, low=0, high=len(self.frequencies) - 1)
        return dataclasses.replace(self, points=tuple(tuple(cell[index] for cell in row) for row in self.points),
                                   frequencies=())

    def summary(self, name: str) -> tuple:
        """``(mean, 95 % half-width)`` of field ``name`` (one value per realisation) over the realisations whose
        solves converged."""
        if name not in SUMMARISED:
            raise ValueError(f"name = {name!r} is not a field with one value per realisation; valid: "
                             f"{', '.join(SUMMARISED)} (array(name) gives any field of the points)")
        values, converged = self.array(name), self.array("converged").astype(bool)
        if converged.ndim < values.ndim:                       # ridge_area_fractions: (…, lengths, realisations)
            converged = converged[..., None, :]
        return confidence_interval(np.where(converged, values, np.nan))

    @property
    def ridge_area(self) -> np.ndarray:
        """A_R/A0 at the scene's coarse-graining length, shape (loads, voltages, [frequencies,] realisations)."""
        return self.array("ridge_area_fractions")[..., 0, :]


def run_study(scene: Scene, directory=None, progress: bool = False, workers: int | None = None,
              dask: str | None = None, tasks=None) -> StudyResult:
    """Run (or resume, with a ``directory``) the study of ``scene``; ``progress`` shows a tqdm bar of points.

    The tasks (:func:`solve_chain`, or :func:`roughcontact.study.coupled.coupled_chain` where the preset's ``scales``
    is "coupled"; one per realisation and voltage) run from the scene's :class:`~.plan.StudyPlan` in a local pool
    of ``workers`` processes (default: the cores this process may run on, at most one per task), each task with
    cores // workers FFT threads; ``workers=1`` runs them in this process. ``dask``, the address of a
    dask.distributed scheduler (``"tcp://host:8786"``), runs them on that cluster instead (one FFT thread per
    task; needs ``roughcontact[parallel]``). Every executor gives the same records for the same FFT plans. A
    script that uses the pool needs Python's ``if __name__ == "__main__":`` guard around its work (the workers
    import it). Interrupted (Ctrl-C), the waiting tasks are cancelled and the pool's workers stopped (a cluster's
    running tasks finish and are dropped); the finished ones stay in the task store. ``tasks``: a task directory
    that several studies share (tasks with equal inputs are solved once; default: ``directory/tasks``, none
    without a ``directory``); with ``tasks`` and no ``directory`` the study keeps its tasks there and writes
    nothing else.
    """
    if not isinstance(progress, bool):
        raise TypeError(f"progress must be True or False, got {progress!r}")
    plan = checked_plan(scene)
    check_executor(workers, dask)
    results = None if directory is None else ResultsDirectory(output_directory(directory), plan, tasks)
    store = task_store(results, tasks)
    apparent = apparent_scale(scene)                # once, for every task
    try:
        records, solved = solve_plans([(plan, apparent)], store, workers, dask, progress)
    finally:
        if results is not None:
            results.release()
    return assemble_study_result(plan, {task.index: records[task.key] for task in plan.tasks}, apparent,
                         [task for task in plan.tasks if task.key in solved])


def checked_plan(scene) -> StudyPlan:
    """The study's plan of ``scene`` (:func:`~.plan.plan_study`, with the patch's checks) and the drive's check:
    what ``roughcontact run`` and ``roughcontact scene`` refuse before any solve."""
    plan = plan_study(scene)
    check_drive(plan)
    return plan


def check_drive(plan: StudyPlan) -> None:
    """Refuse a drive frequency on the coupled scale path (its interface law is the dielectric one)."""
    scene = plan.scene
    if plan.frequencies and scene.preset.scales == "coupled":
        raise ValueError(f"screen.frequency = {list(plan.frequencies)!r} Hz with presets."
                         f"{scene.study.preset}.scales = 'coupled': the interface law of the micro-roughness is the "
                         "dielectric one; a drive frequency needs scales = \"resolved\"")


def solve_plans(plans, store: TaskStore | None, workers: int | None = None, dask: str | None = None,
                progress: bool = False) -> tuple:
    """``(records, solved)``: the records of every task of ``plans`` (pairs of a :class:`~.plan.StudyPlan` and
    its :func:`~.apparent.apparent_scale`) by task key, and the set of keys solved in this call. A task found in
    ``store`` is read back; the others run on one executor (:func:`run_study`'s ``workers`` and ``dask``), each
    distinct key once however many plans hold it, and are stored as they finish."""
    jobs = {}
    for plan, apparent in plans:
        for task in plan.tasks:
            jobs.setdefault(task.key, (plan, task, apparent))
    records = {}
    if store is not None:
        records = {key: done for key, (plan, task, _) in jobs.items() if (done := store.load(plan, task)) is not None}
    todo = [job for key, job in jobs.items() if key not in records]
    executor = make_executor(workers, dask, len(todo)) if todo else InProcess()
    bar, loads = None, LoadProgress(None)
    try:
        with executor:
            if progress and todo:                   # (once the executor runs: a refused one shows no bar)
                from tqdm import tqdm
                _tell(run_estimate([(plan, task) for plan, task, _ in todo],    # what the tasks will cost
                                   getattr(executor, "workers", 1) if dask is None else None))
                bar = tqdm(total=sum(_points(plan) for plan, _, _ in todo), desc="roughcontact run", unit="point",
                           bar_format="{l_bar}{bar}| {n:.4g}/{total:.4g} [{elapsed}<{remaining}]")
            # reported per load: from a local pool's workers through a queue, in this process directly
            loads = LoadProgress(bar, pooled=dask is None and not isinstance(executor, InProcess),
                                 local=isinstance(executor, InProcess)).start()
            # the highest voltages first: their solves take the longest, so the workers finish together
            futures = {executor.submit(_reporting(plan, loads.reporter(task.key, len(plan.normal_forces),
                                                                       1 / plan.realisations)),
                                       plan, *task.index[:2], executor.threads, apparent, *task.index[2:]):
                       (plan, task) for plan, task, apparent in
                       sorted(todo, key=lambda job: -abs(job[0].voltages[job[1].voltage_index]))}
            for future in executor.as_completed(list(futures)):
                plan, task = futures[future]
                records[task.key] = future.result()
                if store is not None:
                    store.save(plan, task, records[task.key])
                loads.finished(task.key)
    except BrokenProcessPool as error:
        raise RuntimeError("a worker of the study's process pool ended abruptly: killed (e.g. out of memory), or, "
                           "in a script, the pool was started without the 'if __name__ == \"__main__\":' guard "
                           "around the script's work (the workers import the script); add the guard, or run "
                           "in this process with workers=1. Finished tasks are kept in the results "
                           "directory") from error
    finally:
        loads.close()                               # after the pool: a worker may still unpickle a reporter
        if bar is not None:
            bar.close()
    return records, {task.key for _, task, _ in todo}


def _points(plan: StudyPlan) -> float:
    """The points a task of ``plan`` finishes: its loads, shared by the realisations."""
    return len(plan.normal_forces) / plan.realisations


def _points(plan: StudyPlan) -> float:
    """The points a task of ``plan`` finishes: its loads, shared by the realisations."""
    return len(plan.normal_forces) / plan.realisations


def _reporting(plan: StudyPlan, reporter):
    """The chain of ``plan``'s tasks, reporting each load to ``reporter`` (:class:`~.progress.LoadProgress`; the
    resolved chain only: the coupled path's tasks count when they end)."""
    if plan.scene.preset.scales == "coupled":
        return coupled_chain
    return solve_chain if reporter is None else functools.partial(solve_chain, progress=reporter)


def _tell(lines) -> None:
    """Print the lines of the run's estimate (:func:`~.cost.run_estimate`) where the progress bar goes."""
    for line in lines:
        print(f"roughcontact run: {line}", file=sys.stderr, flush=True)


def assemble_study_result(plan: StudyPlan, records: dict, apparent, todo) -> StudyResult:
    """The :class:`StudyResult` of every task's ``records`` ({(r, j) or (r, j, k): records per load}); ``todo``
    the tasks solved in this run."""
    forces, voltages, frequencies = plan.normal_forces, plan.voltages, plan.frequencies

    def point(i, *drive):
        return point_result(forces[i], voltages[drive[0]], *apparent[i],
                            [records[(r, *drive)][i] for r in range(plan.realisations)])

    if frequencies:
        table = tuple(tuple(tuple(point(i, j, k) for k in range(len(frequencies))) for j in range(len(voltages)))
                      for i in range(len(forces)))
    else:
        table = tuple(tuple(point(i, j) for j in range(len(voltages))) for i in range(len(forces)))
    return StudyResult(plan=plan, points=table, computed=len({task.index[1:] for task in todo}) * len(forces),
                       solves=sum(record.solves for task in todo for record in records[task.index]),
                       frequencies=frequencies)


def open_results(directory, tasks=None) -> StudyResult:
    """The :class:`StudyResult` of a finished results directory (``roughcontact run --out DIR`` or
    ``run_study(scene, DIR)``), read from its ``scene.toml``, its measured patch (``patch.npz``, so the scan's
    file is not needed) and its tasks (or the shared task directory ``tasks`` it was run with) without solving
    anything (``computed`` and ``solves`` are 0). ``roughcontact.study.bottom_up_friction(open_results(DIR))``
    is the friction model of that run. ``ValueError`` naming the directory when it holds no scene or misses tasks
    (the same ``roughcontact run`` command resumes it), or that holds a parameter study
    (:func:`roughcontact.study.open_results` reads either)."""
    path = Path(directory)
    stored = path / "scene.toml"
    if not stored.is_file():
        raise ValueError(f"directory = {str(path)!r} holds no scene.toml: not a results directory of "
                         "'roughcontact run --out' or run_study(scene, directory)")
    if has_variation(stored):
        raise ValueError(f"directory = {str(path)!r} holds a parameter study (its scene.toml has a [vary] table): "
                         "roughcontact.study.open_results reads it")
    scene = load_scene(stored, read_scan=False)
    patch = path / PATCH_FILE
    topography = HeightField.load(patch) if scene.roughness.topography and patch.exists() else None
    plan = plan_study(scene, topography)             # (a directory without patch.npz: the scan is read)
    store = TaskStore(path / "tasks" if tasks is None else tasks)
    records = {task.index: done for task in plan.tasks if (done := store.load(plan, task)) is not None}
    missing = [task for task in plan.tasks if task.index not in records]
    if missing:
        named = ", ".join(f"{plan.describe(task)}: {store.path(task).name}" for task in missing[:3])
        raise ValueError(f"directory = {str(path)!r} is not finished: {len(missing)} of {len(plan.tasks)} task files "
                         f"missing or unusable in {store.directory} ({named}{', ...' if len(missing) > 3 else ''}); "
                         "the same 'roughcontact run' command resumes it")
    return assemble_study_result(plan, records, apparent_scale(scene), [])
