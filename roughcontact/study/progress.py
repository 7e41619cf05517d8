"""The progress bar of a study advanced by each load a task finishes, not only by whole tasks: a task of a large
patch (four loads of a 1536 x 1152 scan) runs for many minutes, and its loads are the steps a user sees.

A task calls its reporter after each load (:func:`~.resolved.solve_chain`'s ``progress``). In this process the
reporter advances the bar itself; a pool's worker puts the task's key on a queue of a manager process (a proxy
travels with the task), which a thread of this process reads. A cluster's tasks get no reporter (a manager
queue is a local socket): the bar advances when each task ends. When a task ends, the loads it has not reported
are credited, and reports that arrive later are ignored, so the bar ends at its total whatever was lost."""
from __future__ import annotations

import functools
import signal
import threading


def _ignore_interrupt() -> None:
    """The manager process's start: SIGINT ignored (the run that started it shuts it down)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)


class _Report:
    """A pool worker's reporter: puts ``key`` on the manager ``queue`` (picklable, a proxy)."""

    def __init__(self, queue, key: str):
        self.queue, self.key = queue, key

    def __call__(self) -> None:
        self.queue.put(self.key)


class LoadProgress:
    """Advances ``bar`` (a tqdm bar; None: nothing is shown, and no reporter is made) by each load of each task.
    ``pooled``: the tasks run in a local process pool (reported through a manager queue); else in this process
    (``local``) or on a cluster (no reporter: ``local`` False and ``pooled`` False)."""

    def __init__(self, bar, pooled: bool = False, local: bool = True):
        self.bar, self.pooled, self.local = bar, pooled and bar is not None, local and bar is not None
        self.lock, self.tasks, self.manager, self.queue, self.reader = threading.Lock(), {}, None, None, None

    def start(self) -> LoadProgress:
        """Start the manager and the thread that reads its queue (a pool only); returns self."""
        if self.pooled and self.manager is None:
            import multiprocessing
            from multiprocessing.managers import SyncManager
            method = "forkserver" if "forkserver" in multiprocessing.get_all_start_methods() else "spawn"
            self.manager = SyncManager(ctx=multiprocessing.get_context(method))
            self.manager.start(_ignore_interrupt)       # Ctrl-C is this process's to handle, as for the pool
            self.queue = self.manager.Queue()
            self.reader = threading.Thread(target=self._read, daemon=True)
            self.reader.start()
        return self

    def close(self) -> None:
        """Stop the reader and the manager. After the pool has ended: a worker that is still unpickling a task
        connects to the manager for its reporter."""
        if self.manager is not None:
            try:
                self.queue.put(None)                    # the reader's end
                self.reader.join(timeout=5)
            finally:
                self.manager.shutdown()
                self.manager = None

    def __enter__(self) -> LoadProgress:
        return self.start()

    def __exit__(self, *exception) -> bool:
        self.close()
        return False

    def reporter(self, key: str, loads: int, step: float):
        """The reporter of the task ``key`` of ``loads`` loads, each worth ``step`` points of the bar (None where
        nothing is reported: no bar, or a cluster)."""
        if self.bar is None:
            return None
        with self.lock:
            self.tasks[key] = [loads, 0, step]             # loads, reported, points per load
        if self.pooled:
            return _Report(self.queue, key)
        return functools.partial(self._advance, key) if self.local else None

    def finished(self, key: str) -> None:
        """Task ``key`` ended: the bar gets the loads it did not report."""
        if self.bar is None:
            return
        with self.lock:
            loads, reported, step = self.tasks.pop(key)
            if reported < loads:
                self.bar.update((loads - reported) * step)

    def _advance(self, key: str) -> None:
        with self.lock:
            task = self.tasks.get(key)
            if task is not None and task[1] < task[0]:      # (a report after its task ended: credited already)
                task[1] += 1
                self.bar.update(task[2])

    def _read(self) -> None:
        while True:
            try:
                key = self.queue.get()
            except (EOFError, OSError):                     # the manager has gone
                return
            if key is None:
                return
            self._advance(key)
