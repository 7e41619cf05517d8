"""Where the study's tasks run and where their records are kept: :class:`TaskStore` (finished tasks on disk by
their content key, shareable between scenes), :class:`ResultsDirectory` (one study's results: its scene, its
measured patch, its tasks; held by one run at a time, so that an interrupted run resumes) and the executors — in
this process, a local process pool, a dask.distributed cluster (``docs/guide/scaling.md``)."""
from __future__ import annotations

import dataclasses
import hashlib
import json
import math
import os
import warnings
from pathlib import Path

from surfaces import HeightField
from surfaces.validation import check_integer

from ..fft import THREADS_VARIABLE, available_cores
from ..io.pool import ProcessPool
from ..io.provenance import output_directory, write_atomic
from .plan import StudyPlan, Task, task_key
from .records import RECORD_FIELDS, PatchRecord
from .scene import load_scene
from .variants import has_variation, load_variant_study


class SceneMismatch(ValueError):
    """A results directory that holds another scene's results."""


class DirectoryInUse(ValueError):
    """A results directory that another running study is writing into."""


class StaleTaskWarning(UserWarning):
    """A stored task that cannot be reused (damaged, edited, of other inputs or another version's), or a
    results directory's measured patch that the scan no longer gives: the task is solved again."""


def _digest(records: list) -> str:
    return hashlib.sha256(json.dumps(records).encode("utf-8")).hexdigest()


#: The keys of a task file.
TASK_FILE_KEYS = ("key", "inputs", "digest", "records")


class TaskStore:
    """The records of finished tasks in the directory ``directory`` (an existing one to save into), one file ``{key}.json`` per task (its content key,
    :attr:`~.plan.Task.key`; written atomically and synced to disk) holding the key, the task's inputs
    (:meth:`~.plan.StudyPlan.inputs`), the records and their digest. Content-addressed: a task is found by what
    it depends on, not by the scene it came from, so any set of scenes may share one store (tasks with equal
    inputs are solved once), and a changed input is a new key, never a stored task reused. A file that is
    unreadable, edited, of other inputs or of another version is named in a :class:`StaleTaskWarning` and its
    task solved again. Files are written whole (a sibling ``.part`` renamed over), so runs that share the store
    one after the other, or read it while another writes, see whole files; two runs that solve the same task at
    the same moment may spoil its file, which the next run then names and solves again."""

    def __init__(self, directory):
        self.directory = Path(directory)

    def path(self, task: Task) -> Path:
        """The file of ``task``."""
        return self.directory / f"{task.key}.json"

    def load(self, plan: StudyPlan, task: Task) -> tuple | None:
        """The records of ``task`` of ``plan``, or None if it has not finished, or if its file cannot be reused
        (a :class:`StaleTaskWarning` names the file and the reason)."""
        path = self.path(task)
        try:
            text = path.read_text(encoding="utf-8")
        except FileNotFoundError:
            return None
        except (OSError, UnicodeDecodeError) as error:
            return _stale(path, f"cannot be read ({error})")
        try:
            stored = json.loads(text)
        except json.JSONDecodeError as error:
            return _stale(path, "empty" if not text.strip() else f"not valid JSON ({error})")
        if isinstance(stored, list):
            return _stale(path, "written by an older roughcontact, without the task's inputs")
        if not isinstance(stored, dict) or set(stored) != set(TASK_FILE_KEYS):
            return _stale(path, f"not a task file (its keys are not {', '.join(TASK_FILE_KEYS)})")
        if stored["key"] != task.key or _inputs_key(stored["inputs"]) != task.key:
            return _stale(path, "written for other inputs (its inputs do not hash to this task's key)")
        problem = _record_problem(stored["records"], plan)
        if problem is None and stored["digest"] != _digest(stored["records"]):
            problem = "its records do not match their digest (edited or damaged)"
        if problem is not None:
            return _stale(path, problem)
        return tuple(PatchRecord(**{key: tuple(value) if isinstance(value, list) else value
                                    for key, value in record.items()}) for record in stored["records"])

    def save(self, plan: StudyPlan, task: Task, records: tuple) -> None:
        """Store the ``records`` of ``task`` of ``plan``."""
        stored = [dataclasses.asdict(record) for record in records]
        write_atomic(self.path(task), json.dumps({"key": task.key, "inputs": plan.inputs(*task.index),
                                                  "digest": _digest(stored), "records": stored}))


def _inputs_key(inputs) -> str | None:
    """:func:`~.plan.task_key` of stored ``inputs``, None where they are not JSON values it can hash."""
    try:
        return task_key(inputs)
    except (TypeError, ValueError):
        return None


def _stale(path: Path, reason: str) -> None:
    warnings.warn(f"task file {path}: {reason}; its task is solved again", StaleTaskWarning, stacklevel=3)
    return None


def _record_problem(records, plan: StudyPlan) -> str | None:
    """What makes the stored ``records`` of a task unusable for ``plan`` (None if nothing): not one record of
    the fields of :class:`PatchRecord` per load, a value of the wrong type, a non-finite number in a converged
    solve."""
    forces, lengths = plan.normal_forces, plan.closing_lengths
    if not isinstance(records, list) or len(records) != len(forces):
        return f"not one record per load ({len(forces)} loads)"
    for index, (record, force) in enumerate(zip(records, forces)):
        where = f"record {index + 1} (F_N = {force:g} N)"
        if not isinstance(record, dict) or set(record) != RECORD_FIELDS:
            return f"{where} lacks the fields of a PatchRecord (another version's?)"
        if not isinstance(record["ridge_area_fractions"], list) or len(record["ridge_area_fractions"]) != len(lengths):
            return f"{where}: ridge_area_fractions is not a list of {len(lengths)} numbers (one per closing length)"
        for name, kind in _RECORD_TYPES.items():
            if kind is None:                                # (a field of another type: any JSON value)
                continue
            for value in record[name] if name == "ridge_area_fractions" else [record[name]]:
                number = isinstance(value, (int, float)) and not isinstance(value, bool)
                if not (number if kind is float else type(value) is kind):
                    return f"{where}: {name} = {value!r} is not of type {kind.__name__}"
                if kind is float and record["converged"] and not math.isfinite(value):
                    return f"{where}: {name} = {value!r} in a converged solve"
    return None


#: The JSON type of each field of a stored :class:`PatchRecord` (of each item for a tuple).
_RECORD_TYPES = {field.name: {"float": float, "tuple": float, "bool": bool, "int": int}.get(field.type)
                 for field in dataclasses.fields(PatchRecord)}


class ResultsDirectory:
    """The results directory of one study (``roughcontact run --out``): ``scene.toml``, the measured patch
    ``patch.npz`` (a measured topography's patch as solved: levelled, filled, with its boundary, so that the
    results stand without the scan's file) and the finished tasks, a :class:`TaskStore` in ``tasks/`` or in the
    shared directory ``tasks``. One run at a time holds it (an exclusive lock on ``run.lock``, which the system
    frees when that process ends, however it ends); :meth:`release` frees it.

    Another scene is refused (:class:`SceneMismatch`): the directory's scene file and report describe one scene
    (variant scenes share tasks through a common ``tasks`` directory instead, each with a results directory of
    its own). The same scene whose measured scan was replaced under the same path is solved again: its patch
    differs from ``patch.npz``, so its tasks have new keys; a :class:`StaleTaskWarning` names the scan, and the
    new patch replaces the stored one."""

    def __init__(self, directory, plan: StudyPlan, tasks=None):
        self.directory = Path(directory)
        self.lock = self.directory / "run.lock"
        self.plan = plan
        self.directory.mkdir(exist_ok=True)
        self._descriptor = _lock(self.lock)
        try:
            self._check_scene()
            self._keep_patch()
            self.tasks = TaskStore(output_directory(self.directory / "tasks" if tasks is None else tasks, "tasks"))
        except BaseException:
            self.release()
            raise

    def _check_scene(self) -> None:
        stored, scene = self.directory / "scene.toml", self.plan.scene
        if stored.exists() and stored.stat().st_size > 0:           # (an empty one: a write cut short)
            if has_variation(stored):
                raise SceneMismatch(f"{self.directory} holds the results of a parameter study (its scene.toml has "
                                    "a [vary] table); run into a new --out directory")
            old = load_scene(stored, read_scan=False)
            if old != scene:
                new, before = scene.flat(), old.flat()
                changed = [f"{key} = {before[key]!r} -> {new[key]!r}" for key in new if new[key] != before.get(key)]
                raise SceneMismatch(f"{self.directory} holds the results of another scene ({'; '.join(changed)}); "
                                    "run into a new --out directory, or delete this one to start over")
        else:
            write_atomic(stored, scene.to_toml())

    def _keep_patch(self) -> None:
        """Store the plan's measured patch as ``patch.npz`` (warning where it replaces another one)."""
        topography, path = self.plan.topography, self.directory / PATCH_FILE
        if topography is None:
            return
        if path.exists():
            try:
                if HeightField.load(path) == topography:
                    return
            except (ValueError, OSError):           # damaged: written again
                pass
            else:
                warnings.warn(f"{self.plan.scene.roughness.topography}: the measured topography is not the patch "
                              f"that the results in {self.directory} were solved on ({path}: the scan was replaced "
                              "or read differently); its tasks are solved again", StaleTaskWarning, stacklevel=3)
        part = topography.save(path.with_name("patch.part.npz"))
        os.replace(part, path)

    def release(self) -> None:
        """Free the directory for other runs."""
        if self._descriptor is not None:
            try:
                self.lock.unlink(missing_ok=True)      # before the lock is freed: a waiting run locks a new file
            except PermissionError:                    # (Windows removes no open file: the next run takes it over)
                pass
            os.close(self._descriptor)
            self._descriptor = None


#: The measured patch in a results directory (:class:`ResultsDirectory`).
PATCH_FILE = "patch.npz"
#: The measured patches of a parameter study's variants, ``patches/{variant index}.npz`` (:class:`VariantDirectory`).
PATCHES = "patches"


class VariantDirectory(ResultsDirectory):
    """The results directory of a parameter study (:mod:`.variants`): ``scene.toml`` holds the base scene and its
    ``[vary]`` table, ``patches/{index}.npz`` the measured patch of each variant with a topography, and one task
    store (``tasks/``, or the shared ``tasks``) all the variants' tasks. Locked as a :class:`ResultsDirectory`;
    another study or a single scene in it is refused (:class:`SceneMismatch`). ``plans``: the variants' plans,
    in the study's order."""

    def __init__(self, directory, study, plans, tasks=None):
        self.study, self.plans = study, plans
        super().__init__(directory, plans[0], tasks)

    def _check_scene(self) -> None:
        stored = self.directory / "scene.toml"
        if stored.exists() and stored.stat().st_size > 0:
            if not has_variation(stored):
                raise SceneMismatch(f"{self.directory} holds the results of one scene, not of a parameter study; "
                                    "run into a new --out directory")
            old = load_variant_study(stored, read_scan=False)
            if old != self.study:
                new, before = self.study.base.flat(), old.base.flat()
                changed = [f"{key} = {before[key]!r} -> {new[key]!r}" for key in new if new[key] != before.get(key)]
                if old.variation != self.study.variation:
                    changed.append("the [vary] table")
                raise SceneMismatch(f"{self.directory} holds the results of another parameter study "
                                    f"({'; '.join(changed)}); run into a new --out directory, or delete this one "
                                    "to start over")
        else:
            write_atomic(stored, self.study.to_toml())

    def _keep_patch(self) -> None:
        """Store each variant's measured patch as ``patches/{index}.npz``."""
        for index, plan in enumerate(self.plans):
            if plan.topography is not None:
                path = self.directory / PATCHES / f"{index}.npz"
                path.parent.mkdir(exist_ok=True)
                if not path.exists() or HeightField.load(path) != plan.topography:
                    os.replace(plan.topography.save(path.with_name(f"{index}.part.npz")), path)


def task_store(results: ResultsDirectory | None, tasks) -> TaskStore | None:
    """Where a run keeps its tasks: the task store of its results directory ``results``, else the directory
    ``tasks`` (checked and created as "tasks"), else none (the records stay in memory)."""
    if results is not None:
        return results.tasks
    return None if tasks is None else TaskStore(output_directory(tasks, "tasks"))


def _lock(path: Path) -> int:
    """An open descriptor of ``path`` holding the exclusive lock of a results directory (the system frees it
    when this process ends, killed or not; the process id in the file is for messages only). Raises
    :class:`DirectoryInUse` naming the file and its holder if another process holds it."""
    while True:
        descriptor = os.open(path, os.O_CREAT | os.O_RDWR, 0o644)
        if not _try_lock(descriptor, path):
            holder = os.read(descriptor, 32).decode("ascii", "replace").strip() or "unknown"
            os.close(descriptor)
            raise DirectoryInUse(f"{path.parent} is being written by another roughcontact run (process {holder} "
                                 f"holds {path}); wait for it to finish or choose another --out directory")
        try:
            current = os.path.samestat(os.fstat(descriptor), os.stat(path))
        except FileNotFoundError:
            current = False
        if current:
            break
        os.close(descriptor)                         # released (and removed) while this run opened it: again
    os.ftruncate(descriptor, 0)
    os.write(descriptor, str(os.getpid()).encode("ascii"))
    return descriptor


def _try_lock(descriptor: int, path: Path) -> bool:
    """Take the exclusive lock of ``path``, open as ``descriptor``, if no other open file holds it."""
    try:
        import fcntl
    except ImportError:                              # Windows
        import msvcrt
        try:
            msvcrt.locking(descriptor, msvcrt.LK_NBLCK, 1)
        except OSError:
            return False
        return True
    try:
        fcntl.flock(descriptor, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except BlockingIOError:
        return False
    except OSError as error:                         # e.g. a file system without locks
        os.close(descriptor)
        raise OSError(error.errno, error.strerror, str(path)) from None
    return True


class _Deferred:
    """A task of :class:`InProcess`: run when its result is asked for."""

    def __init__(self, function, arguments):
        self.function, self.arguments = function, arguments

    def result(self):
        return self.function(*self.arguments)


class InProcess:
    """Tasks run one after the other in this process, as their results are consumed; FFT threads by
    ``roughcontact.fft``'s default."""
    threads = None

    def __enter__(self):
        return self

    def __exit__(self, *exception):
        return False

    def submit(self, function, *arguments):
        return _Deferred(function, arguments)

    def as_completed(self, futures):
        return iter(futures)


class _Pool(ProcessPool):
    """A local pool of ``workers`` processes (:class:`~roughcontact.io.pool.ProcessPool`, forked from a server that
    has loaded the patch solvers) with ``fft_threads`` FFT threads each unless ``$ROUGHCONTACT_FFT_THREADS`` says
    otherwise (the numba kernels are serial)."""
    threads = None                                  # the worker's default, set from its environment

    def __init__(self, workers: int, fft_threads: int):
        super().__init__(workers, preload=("roughcontact.study.resolved", "roughcontact.study.coupled"),
                         environment={THREADS_VARIABLE: str(fft_threads)})


class _Dask:
    """The dask.distributed scheduler at ``address``: one FFT thread per task (a worker runs one task per
    thread). The scheduler reruns the tasks of a worker that is lost (up to its ``allowed-failures``);
    interrupted, the client cancels the tasks it submitted."""
    threads = 1

    def __init__(self, address: str):
        try:
            import distributed
        except ImportError:
            raise ImportError("running on a dask cluster needs dask.distributed: pip install 'roughcontact[parallel]'"
                              ) from None
        if not isinstance(address, str):
            raise TypeError(f"dask must be a scheduler address such as 'tcp://host:8786', got {type(address).__name__}")
        try:
            distributed.comm.resolve_address(address)          # its form (a Client would fail, then hang at exit)
        except ValueError as error:
            raise ValueError(f"dask = {address!r} is not a scheduler address (tcp://host:port): {error}") from None
        except OSError as error:
            raise ValueError(f"dask = {address!r}: its host cannot be resolved ({error.strerror})") from None
        self.distributed, self.address, self.futures = distributed, address, []

    def __enter__(self):
        try:
            self.client = self.distributed.Client(self.address, set_as_default=False)   # dask's config untouched
        except OSError as error:                                 # no scheduler answers (after its connect timeout)
            raise ValueError(f"dask = {self.address!r}: {error}") from None
        return self

    def __exit__(self, kind, error, traceback):
        if kind is not None:
            self.client.cancel(self.futures)
        self.client.close()
        return False

    def submit(self, function, *arguments):
        future = self.client.submit(function, *arguments)        # pure: a rerun gives the same records
        self.futures.append(future)
        return future

    def as_completed(self, futures):
        return self.distributed.as_completed(futures, loop=self.client.loop)


def check_executor(workers, dask) -> None:
    """Refuse a bad ``workers`` or both executors (see :func:`run_study`), and ``dask`` without the extra."""
    if workers is not None:
        check_integer("workers", workers, low=1)
    if dask is not None:
        if workers is not None:
            raise ValueError(f"workers = {workers!r} with dask = {dask!r}: the cluster has its own workers; give "
                             "one of the two")
        _Dask(dask)


def make_executor(workers, dask, tasks: int):
    """The executor of ``tasks`` tasks (see :func:`run_study`)."""
    if dask is not None:
        return _Dask(dask)
    cores = available_cores()
    workers = min(cores, tasks) if workers is None else workers
    if workers == 1 or tasks <= 1:
        return InProcess()
    return _Pool(workers, max(1, cores // workers))
