"""A local pool of worker processes that end with their client: the study's tasks and the FE fingertip's runs.

Workers are forked from a forkserver where the platform has one (``preload``: modules the server imports once,
so that each worker starts with them loaded), else spawned. A worker ignores Ctrl-C, which is the client's to
handle (interrupted, the pool cancels the waiting tasks and terminates its workers), and ends with the client
process even when that is killed: it holds the reading end of a pipe whose writing end only the client holds,
so it reads end-of-file once the client is gone, reaped or not (a worker would otherwise wait for tasks for
ever, holding the client's output pipes open). Light to import: no module of roughcontact.
"""
from __future__ import annotations

import multiprocessing
import os
import signal
import threading
from concurrent.futures import ProcessPoolExecutor, as_completed


class ProcessPool:
    """``workers`` processes as a context manager with ``submit(function, *arguments)`` and
    ``as_completed(futures)``; ``environment`` ({name: value}) is set in each worker where the variable is unset
    or empty; ``preload`` the modules of the forkserver (module docstring)."""

    def __init__(self, workers: int, preload=(), environment=None):
        self.workers, self.preload, self.environment = workers, tuple(preload), dict(environment or {})

    def __enter__(self):
        if "forkserver" in multiprocessing.get_all_start_methods():      # workers forked from a loaded server
            context = multiprocessing.get_context("forkserver")
            if self.preload:
                context.set_forkserver_preload(list(self.preload))
        else:
            context = multiprocessing.get_context("spawn")
        self.lifeline = context.Pipe(duplex=False)      # (reading, writing): only this process holds the writing end
        self.executor = ProcessPoolExecutor(self.workers, mp_context=context, initializer=_start_worker,
                                            initargs=(self.environment, self.lifeline[0]))
        return self

    def __exit__(self, kind, error, traceback):
        if kind is None:
            self.executor.shutdown()
        else:
            processes = list(self.executor._processes.values())  # (no public way to stop running tasks before 3.14)
            self.executor.shutdown(wait=False, cancel_futures=True)
            for process in processes:
                process.terminate()
            for process in processes:
                process.join()
        for end in self.lifeline:
            end.close()
        return False

    def submit(self, function, *arguments):
        return self.executor.submit(function, *arguments)

    def as_completed(self, futures):
        return as_completed(futures)


def _start_worker(environment: dict, client) -> None:
    """Pool worker start: ``environment`` where unset or empty; Ctrl-C ignored; the worker ends with the client
    (``client``: the reading end of the lifeline, module docstring)."""
    for name, value in environment.items():
        if not os.environ.get(name):
            os.environ[name] = value
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    threading.Thread(target=_end_with, args=(client,), daemon=True).start()


def _end_with(client) -> None:
    try:
        client.recv_bytes()                                  # nothing is ever sent: returns at the client's end
    except (EOFError, OSError):
        pass
    os._exit(1)
