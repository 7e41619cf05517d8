"""Where the study's tasks run and where their records are kept: :class:`TaskStore` (finished tasks on disk, so
an interrupted run resumes) and the executors — in this process, a local process pool, a dask.distributed
cluster (``docs/guide/scaling.md``)."""
from __future__ import annotations

import dataclasses
import json
import os
import signal
import threading
import time
from pathlib import Path

from surfaces.validation import check_integer

from ..fft import THREADS_VARIABLE, available_cores
from ..io.provenance import write_atomic
from .records import RECORD_FIELDS, PatchRecord
from .scene import Scene, load_scene


class SceneMismatch(ValueError):
    """A results directory that holds another scene's results."""


class DirectoryInUse(ValueError):
    """A results directory that another running study is writing into."""


class TaskStore:
    """The records of finished tasks in ``directory/tasks/`` (``R{r}_U{j}.json``, written atomically) beside
    ``directory/scene.toml``; refuses another scene, and a directory that a running process holds (``run.lock``
    with its process id; a lock of a process that no longer runs, e.g. one that was killed, is taken over).
    :meth:`release` frees the directory."""

    def __init__(self, directory, scene: Scene):
        self.directory = Path(directory)
        self.tasks = self.directory / "tasks"
        stored = self.directory / "scene.toml"
        if stored.exists():
            old = load_scene(stored)
            if old != scene:
                new, before = scene.flat(), old.flat()
                changed = [f"{key} = {before[key]!r} -> {new[key]!r}" for key in new if new[key] != before.get(key)]
                raise SceneMismatch(f"{self.directory} holds the results of another scene ({'; '.join(changed)}); "
                                    "run into a new --out directory, or delete this one to start over")
        else:
            self.directory.mkdir(exist_ok=True)
            write_atomic(stored, scene.to_toml())
        self.tasks.mkdir(exist_ok=True)
        self.lock = self.directory / "run.lock"
        try:
            descriptor = os.open(self.lock, os.O_CREAT | os.O_EXCL | os.O_WRONLY)     # atomic: one run wins
        except FileExistsError:
            try:
                holder = int(self.lock.read_text())
            except (OSError, ValueError):
                holder = None
            if holder is not None and holder != os.getpid() and _running(holder):
                raise DirectoryInUse(f"{self.directory} is being written by another roughcontact run (process "
                                     f"{holder}); wait for it to finish or choose another --out directory") from None
            write_atomic(self.lock, str(os.getpid()))                                # a stale lock: taken over
        else:
            with os.fdopen(descriptor, "w") as stream:
                stream.write(str(os.getpid()))

    def release(self) -> None:
        """Free the directory for other runs."""
        self.lock.unlink(missing_ok=True)

    def _path(self, realisation: int, voltage_index: int) -> Path:
        return self.tasks / f"R{realisation:03d}_U{voltage_index:03d}.json"

    def load(self, realisation: int, voltage_index: int) -> tuple | None:
        """The records of task (r, j), or None if it has not finished (or was written with other fields, by
        another version: solved again)."""
        path = self._path(realisation, voltage_index)
        if not path.exists():
            return None
        records = json.loads(path.read_text())
        if any(set(record) != RECORD_FIELDS for record in records):
            return None
        return tuple(PatchRecord(**{key: tuple(value) if isinstance(value, list) else value
                                    for key, value in record.items()}) for record in records)

    def save(self, realisation: int, voltage_index: int, records: tuple) -> None:
        write_atomic(self._path(realisation, voltage_index), json.dumps([dataclasses.asdict(r) for r in records]))


def _running(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:                     # it runs, under another user
        return True
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


def _start_worker(threads: int, client: int):
    """Pool worker start: ``threads`` FFT threads unless ``$ROUGHCONTACT_FFT_THREADS`` says otherwise; Ctrl-C is
    the client's to handle (it cancels the tasks and stops the workers); the worker ends with the client
    process ``client`` even when that is killed (a worker would otherwise wait for tasks for ever)."""
    if not os.environ.get(THREADS_VARIABLE):                 # (unset or empty)
        os.environ[THREADS_VARIABLE] = str(threads)
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    threading.Thread(target=_end_with, args=(client,), daemon=True).start()


def _end_with(client: int) -> None:
    while _running(client):
        time.sleep(1.0)
    os._exit(1)


class _Pool:
    """A local pool of ``workers`` spawned processes with ``fft_threads`` FFT threads each (the numba kernels
    are serial); interrupted, it cancels the waiting tasks and terminates the workers."""
    threads = None                                  # the worker's default, set by _start_worker

    def __init__(self, workers: int, fft_threads: int):
        self.workers, self.fft_threads = workers, fft_threads

    def __enter__(self):
        import multiprocessing
        from concurrent.futures import ProcessPoolExecutor
        if "forkserver" in multiprocessing.get_all_start_methods():      # workers forked from a loaded server
            context = multiprocessing.get_context("forkserver")
            context.set_forkserver_preload(["roughcontact.study.resolved", "roughcontact.study.coupled"])
        else:
            context = multiprocessing.get_context("spawn")
        self.executor = ProcessPoolExecutor(self.workers, mp_context=context,
                                            initializer=_start_worker, initargs=(self.fft_threads, os.getpid()))
        return self

    def __exit__(self, kind, error, traceback):
        if kind is None:
            self.executor.shutdown()
            return False
        processes = list(self.executor._processes.values())     # (no public way to stop running tasks before 3.14)
        self.executor.shutdown(wait=False, cancel_futures=True)
        for process in processes:
            process.terminate()
        for process in processes:
            process.join()
        return False

    def submit(self, function, *arguments):
        return self.executor.submit(function, *arguments)

    def as_completed(self, futures):
        from concurrent.futures import as_completed
        return as_completed(futures)


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
