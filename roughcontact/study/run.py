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

Finished tasks are stored as they arrive in a :class:`~.execution.TaskStore` directory, so an interrupted run
resumes without recomputing finished tasks; a different scene in the same directory is refused
(:class:`~.execution.SceneMismatch`).
"""
from __future__ import annotations

import dataclasses
from concurrent.futures.process import BrokenProcessPool
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from surfaces.validation import check_integer

from ..io.provenance import output_directory
from .apparent import apparent_scale
from .coupled import coupled_chain
from .execution import InProcess, TaskStore, check_executor, make_executor
from .patch import closing_lengths, realisation_count, resolved_short_cutoff
from .records import _PER_REALISATION, PointResult, confidence_interval, point_result
from .resolved import solve_chain
from .scene import Scene, load_scene


#: The fields of a point with one value per realisation (per closing length and realisation for the A_R).
SUMMARISED = (*_PER_REALISATION, "ridge_area_fractions")


@dataclass(frozen=True)
class StudyResult:
    """All points of a study; ``points[i][j]`` at ``normal_forces[i]``, ``voltages[j]`` (``points[i][j][k]`` at
    ``frequencies[k]`` [Hz] too where the scene sets a drive frequency; ``frequencies`` is empty otherwise);
    ``coarse_graining`` the A_R closing diameters [m] (the scene's first); ``computed`` points with a task solved
    in this run and ``solves`` the contact solves of this run; ``short_cutoff`` the micro-roughness cut-off in
    use [m]."""

    scene: Scene
    points: tuple
    coarse_graining: tuple
    short_cutoff: float
    computed: int
    solves: int
    frequencies: tuple = ()

    @property
    def normal_forces(self) -> np.ndarray:
        return np.array(self.scene.loads.normal_forces)

    @property
    def voltages(self) -> np.ndarray:
        return np.array(self.scene.loads.voltages)

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
              dask: str | None = None) -> StudyResult:
    """Run (or resume, with a ``directory``) the study of ``scene``; ``progress`` shows a tqdm bar of points.

    The tasks (:func:`solve_chain`, or :func:`roughcontact.study.coupled.coupled_chain` where the preset's ``scales``
    is "coupled"; one per realisation and voltage) run in a local pool of ``workers``
    processes (default: the cores this process may run on, at most one per task), each task with cores //
    workers FFT threads; ``workers=1`` runs them in this process. ``dask``, the address of a dask.distributed
    scheduler (``"tcp://host:8786"``), runs them on that cluster instead (one FFT thread per task; needs
    ``roughcontact[parallel]``). Every executor gives the same records for the same FFT plans. A script that
    uses the pool needs Python's ``if __name__ == "__main__":`` guard around its work (the workers import it).
    Interrupted (Ctrl-C), the waiting tasks are cancelled and the pool's workers stopped (a cluster's running
    tasks finish and are dropped); the finished ones stay in ``directory``.
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a Scene (roughcontact.study.load_scene reads one from a TOML file), got "
                        f"{type(scene).__name__}")
    if not isinstance(progress, bool):
        raise TypeError(f"progress must be True or False, got {progress!r}")
    check_executor(workers, dask)
    if scene.screen.frequency is not None and scene.preset.scales == "coupled":
        raise ValueError(f"screen.frequency = {list(scene.screen.frequency)!r} Hz with presets."
                         f"{scene.study.preset}.scales = 'coupled': the interface law of the micro-roughness is the "
                         "dielectric one; a drive frequency needs scales = \"resolved\"")
    store = None if directory is None else TaskStore(output_directory(directory), scene)
    forces, count = scene.loads.normal_forces, realisation_count(scene)
    order = task_keys(scene)
    records = {}
    if store is not None:
        records = {key: done for key in order if (done := store.load(*key)) is not None}
    todo = [key for key in order if key not in records]
    executor = make_executor(workers, dask, len(todo)) if todo else InProcess()
    bar = None
    task = solve_chain
    if scene.preset.scales == "coupled":            # the micro-roughness as an interface law (.coupled)
        task = coupled_chain
    apparent = apparent_scale(scene)                # once, for every task
    try:
        with executor:
            if progress and todo:                   # (once the executor runs: a refused one shows no bar)
                from tqdm import tqdm
                bar = tqdm(total=len(todo) * len(forces) / count, desc="roughcontact run", unit="point",
                           bar_format="{l_bar}{bar}| {n:.4g}/{total:.4g} [{elapsed}<{remaining}]")
            # the highest voltages first: their solves take the longest, so the workers finish together
            futures = {executor.submit(task, scene, *key[:2], executor.threads, apparent, *key[2:]): key
                       for key in sorted(todo, key=lambda key: -abs(scene.loads.voltages[key[1]]))}
            for future in executor.as_completed(list(futures)):
                key = futures[future]
                records[key] = future.result()
                if store is not None:
                    store.save(*key[:2], records[key], *key[2:])
                if bar is not None:
                    bar.update(len(forces) / count)
    except BrokenProcessPool as error:
        raise RuntimeError("a worker of the study's process pool ended abruptly: killed (e.g. out of memory), or, "
                           "in a script, the pool was started without the 'if __name__ == \"__main__\":' guard "
                           "around the script's work (the workers import the script); add the guard, or run "
                           "in this process with workers=1. Finished tasks are kept in the results "
                           "directory") from error
    finally:
        if bar is not None:
            bar.close()
        if store is not None:
            store.release()
    return _study_result(scene, records, apparent, todo)


def task_keys(scene: Scene) -> list:
    """The study's tasks in order: (r, j) per realisation and voltage index, (r, j, k) with the frequency index
    k where the scene sets a drive frequency."""
    realisations, voltages = range(realisation_count(scene)), range(len(scene.loads.voltages))
    if scene.screen.frequency is None:
        return [(r, j) for j in voltages for r in realisations]
    return [(r, j, k) for j in voltages for k in range(len(scene.screen.frequency)) for r in realisations]


def _study_result(scene: Scene, records: dict, apparent, todo) -> StudyResult:
    """The :class:`StudyResult` of every task's ``records`` ({(r, j) or (r, j, k): records per load}); ``todo``
    the tasks solved in this run."""
    forces, voltages = scene.loads.normal_forces, scene.loads.voltages
    count = realisation_count(scene)
    cutoff = resolved_short_cutoff(scene) if scene.roughness.enabled else float("nan")

    def point(i, *drive):
        return point_result(forces[i], voltages[drive[0]], *apparent[i],
                            [records[(r, *drive)][i] for r in range(count)])

    frequencies = scene.screen.frequency or ()
    if frequencies:
        table = tuple(tuple(tuple(point(i, j, k) for k in range(len(frequencies))) for j in range(len(voltages)))
                      for i in range(len(forces)))
    else:
        table = tuple(tuple(point(i, j) for j in range(len(voltages))) for i in range(len(forces)))
    return StudyResult(scene=scene, points=table, coarse_graining=closing_lengths(scene), short_cutoff=cutoff,
                       computed=len({key[1:] for key in todo}) * len(forces),
                       solves=sum(record.solves for key in todo for record in records[key]),
                       frequencies=frequencies)


def open_results(directory) -> StudyResult:
    """The :class:`StudyResult` of a finished results directory (``roughcontact run --out DIR`` or
    ``run_study(scene, DIR)``), read from its ``scene.toml`` and ``tasks/`` without solving anything
    (``computed`` and ``solves`` are 0). ``roughcontact.study.bottom_up_friction(open_results(DIR))`` is the
    friction model of that run. ``ValueError`` naming the directory when it holds no scene or misses tasks (the
    same ``roughcontact run`` command resumes it)."""
    path = Path(directory)
    stored = path / "scene.toml"
    if not stored.is_file():
        raise ValueError(f"directory = {str(path)!r} holds no scene.toml: not a results directory of "
                         "'roughcontact run --out' or run_study(scene, directory)")
    scene = load_scene(stored)
    store = TaskStore(path, scene)
    try:
        order = task_keys(scene)
        records = {key: done for key in order if (done := store.load(*key)) is not None}
    finally:
        store.release()
    missing = [store._path(*key).name for key in order if key not in records]
    if missing:
        raise ValueError(f"directory = {str(path)!r} is not finished: {len(missing)} of {len(order)} task files "
                         f"missing or unusable in {store.tasks} ({', '.join(missing[:3])}"
                         f"{', ...' if len(missing) > 3 else ''}); the same 'roughcontact run' command resumes it")
    return _study_result(scene, records, apparent_scale(scene), [])
