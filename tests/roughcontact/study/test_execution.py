"""The study's tasks run in this process, in a local process pool and on a dask.distributed cluster with the same
records, bit for bit (one FFT thread and FFTW_ESTIMATE plans everywhere, tests/conftest.py); an interrupted run
resumes with the missing tasks only, and a run that loses a worker completes with the same numbers."""
import dataclasses
import multiprocessing
import os
import signal
import subprocess
import sys
import textwrap
import threading
import time
from pathlib import Path

import pytest

from roughcontact.study.execution import TaskStore
from roughcontact.study.resolved import solve_chain
from roughcontact.study.run import run_study
from roughcontact.study.scene import load_scene
from study_scenes import TINY


def numbers(result):
    """Every number of a study but the solve times."""
    return [[dataclasses.replace(point, seconds=0.0) for point in row] for row in result.points]


def untimed(records):
    return [dataclasses.replace(record, seconds=0.0) for record in records]


@pytest.fixture(scope="module")
def cluster():
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as local:
        yield local


def test_local_pool_stores_the_in_process_records(tiny, tiny_result, tmp_path):
    pooled = run_study(tiny, tmp_path, workers=2)
    assert numbers(pooled) == numbers(tiny_result)
    assert pooled.solves == tiny_result.solves == 8 and pooled.computed == 4
    store = TaskStore(tmp_path, tiny)
    for r in range(2):
        for j in range(2):                                  # the JSON round trip is exact
            assert untimed(store.load(r, j)) == untimed(solve_chain(tiny, r, j))
    store.release()


def test_interrupted_pool_keeps_finished_tasks_and_resume_solves_the_rest(tiny, tiny_result, tmp_path, monkeypatch):
    save = TaskStore.save

    def interrupted(self, *args):
        save(self, *args)
        raise KeyboardInterrupt                             # Ctrl-C once the first task is stored

    monkeypatch.setattr(TaskStore, "save", interrupted)
    running = set(multiprocessing.active_children())
    with pytest.raises(KeyboardInterrupt):
        run_study(tiny, tmp_path, workers=2)
    assert set(multiprocessing.active_children()) <= running          # the workers were stopped
    assert not (tmp_path / "run.lock").exists()
    (done,) = [path.stem for path in (tmp_path / "tasks").glob("*.json")]
    monkeypatch.undo()
    store = TaskStore(tmp_path, tiny)
    first = store.load(int(done[1:4]), int(done[6:9]))
    store.release()
    resumed = run_study(tiny, tmp_path, workers=2)
    assert resumed.solves == 8 - sum(record.solves for record in first)      # 3 tasks of 2 solves
    assert resumed.computed == 4                            # the other realisation of each point was missing
    assert numbers(resumed) == numbers(tiny_result)


@pytest.mark.slow
def test_the_pool_ends_with_a_killed_client(tmp_path):
    psutil = pytest.importorskip("psutil")
    script = tmp_path / "study.py"
    script.write_text(textwrap.dedent(f"""\
        import sys
        sys.path[:0] = [{str(Path(__file__).parents[3])!r}, {str(Path(__file__).parent)!r}]
        from study_scenes import TINY
        from roughcontact.study.run import run_study
        from roughcontact.study.scene import load_scene
        if __name__ == "__main__":
            scene = load_scene(text=TINY.replace("realisations = 2", "realisations = 500"), preset="draft")
            run_study(scene, {str(tmp_path / "out")!r}, workers=2)
        """))
    client = subprocess.Popen([sys.executable, str(script)])
    try:
        while not any((tmp_path / "out" / "tasks").glob("*.json")):          # the workers have started
            assert client.poll() is None
            time.sleep(0.05)
        pool = psutil.Process(client.pid).children(recursive=True)          # forkserver, workers, tracker
    finally:
        client.kill()                                                        # SIGKILL: no clean-up runs
        client.wait()
    assert len(pool) >= 3
    gone, alive = psutil.wait_procs(pool, timeout=30)
    assert alive == []


def test_local_cluster_gives_the_in_process_records(tiny, tiny_result, cluster):
    on_cluster = run_study(tiny, dask=cluster.scheduler_address)
    assert numbers(on_cluster) == numbers(tiny_result) and on_cluster.solves == 8


def test_a_worker_lost_mid_run_costs_only_its_tasks(cluster, tmp_path):
    import dask
    import distributed
    scene = load_scene(text=TINY.replace("realisations = 2", "realisations = 6"), preset="draft")
    expected = run_study(scene, workers=1)
    killed = []

    def kill_a_busy_worker():
        with distributed.Client(cluster.scheduler_address, set_as_default=False) as client:
            while not any((tmp_path / "tasks").glob("*.json")):               # the first result arrived
                time.sleep(0.005)
            busy = [address for address, keys in client.processing().items() if keys]
            pid = client.run(os.getpid, workers=busy[:1])[busy[0]]
            os.kill(pid, signal.SIGKILL)
            killed.append(pid)

    killer = threading.Thread(target=kill_a_busy_worker)
    killer.start()
    result = run_study(scene, tmp_path, dask=cluster.scheduler_address)
    killer.join()
    assert killed                                           # a worker with a task in flight died
    assert dask.config.get("scheduler", None) is None       # the user's dask configuration is left alone
    assert numbers(result) == numbers(expected) and result.computed == 4
    assert len(list((tmp_path / "tasks").glob("*.json"))) == 12


def test_dask_without_the_extra_names_it(tiny, tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "distributed", None)                  # import distributed fails
    with pytest.raises(ImportError, match=r"pip install 'roughcontact\[parallel\]'"):
        run_study(tiny, tmp_path / "out", dask="tcp://127.0.0.1:8786")
    assert not (tmp_path / "out").exists()                                 # refused before anything is written


def test_an_unreachable_scheduler_is_named(tiny, tmp_path):
    dask = pytest.importorskip("dask")
    pytest.importorskip("distributed")
    with dask.config.set({"distributed.comm.timeouts.connect": "1s"}):
        with pytest.raises(ValueError, match=r"dask = 'tcp://127.0.0.1:9': Timed out trying to connect"):
            run_study(tiny, tmp_path, dask="tcp://127.0.0.1:9")
    assert not (tmp_path / "run.lock").exists() and not any((tmp_path / "tasks").iterdir())


@pytest.mark.parametrize("workers, dask, message", [
    (0, None, r"workers must be an integer in \[1, inf\], got 0"),
    (2.0, None, r"workers must be an integer"),
    (2, "tcp://127.0.0.1:8786", r"workers = 2 with dask = 'tcp://127.0.0.1:8786'"),
])
def test_bad_executor_choices_are_refused(tiny, workers, dask, message):
    with pytest.raises(ValueError, match=message):
        run_study(tiny, workers=workers, dask=dask)


def test_a_script_without_the_main_guard_gets_a_clear_error(tmp_path):
    # the pool's workers import the script (forkserver); without the guard they fail to start, which surfaces
    # as one RuntimeError naming the guard and workers=1, not only the workers' own tracebacks
    script = tmp_path / "study_script.py"
    script.write_text(textwrap.dedent(f"""
        import sys
        sys.path.insert(0, {str(Path(__file__).parent)!r})
        from study_scenes import TINY
        from roughcontact.study.run import run_study
        from roughcontact.study.scene import load_scene
        run_study(load_scene(text=TINY, preset="draft"), workers=2)
    """))
    done = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, timeout=300)
    assert done.returncode != 0
    raised = [line for line in done.stderr.splitlines()      # (the resource tracker may warn after it at exit)
              if line.startswith("RuntimeError: a worker of the study's process pool")]
    assert len(raised) == 1 and "__main__" in raised[0] and "workers=1" in raised[0]
