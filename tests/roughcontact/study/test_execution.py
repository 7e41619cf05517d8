"""The study's tasks run in this process, in a local process pool and on a dask.distributed cluster with the same
records, bit for bit (one FFT thread and FFTW_ESTIMATE plans everywhere, tests/conftest.py); an interrupted run
resumes with the missing tasks only, and a run that loses a worker completes with the same numbers."""
import dataclasses
import json
import multiprocessing
import os
import re
import shutil
import signal
import subprocess
import sys
import textwrap
import threading
import time
import warnings
from pathlib import Path

import pytest

from roughcontact.cli import main
from roughcontact.study.execution import StaleTaskWarning, TaskStore
from roughcontact.study.plan import plan_study
from roughcontact.study.resolved import solve_chain
from roughcontact.study.run import open_results, run_study
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
    store, plan = TaskStore(tmp_path / "tasks"), pooled.plan
    assert [task.index for task in plan.tasks] == [(0, 0), (1, 0), (0, 1), (1, 1)]
    for task in plan.tasks:                                 # the JSON round trip is exact
        assert untimed(store.load(plan, task)) == untimed(solve_chain(tiny, *task.index))


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
    plan = plan_study(tiny)
    first = TaskStore(tmp_path / "tasks").load(plan, next(task for task in plan.tasks if task.key == done))
    resumed = run_study(tiny, tmp_path, workers=2)
    assert resumed.solves == 8 - sum(record.solves for record in first)      # 3 tasks of 2 solves
    assert resumed.computed == 4                            # the other realisation of each point was missing
    assert numbers(resumed) == numbers(tiny_result)


@pytest.fixture(scope="module")
def finished(tiny, tmp_path_factory):
    """A results directory of the tiny study, run to the end."""
    directory = tmp_path_factory.mktemp("finished")
    run_study(tiny, directory, workers=1)
    return directory


def _nan_gap(text):
    stored = json.loads(text)
    stored["records"][1]["equivalent_gap"] = float("nan")
    return json.dumps(stored)


def _edited_gap(text):
    stored = json.loads(text)
    stored["records"][0]["equivalent_gap"] *= 1.01
    return json.dumps(stored)


@pytest.mark.parametrize("damage, reason", [
    (lambda text: "", "empty"),
    (lambda text: text[:len(text) // 2], "not valid JSON"),
    (lambda text: text.encode("utf-8")[:5] + b"\xff\xfe", "cannot be read"),
    (lambda text: "[1, 2]", "written by an older roughcontact"),
    (lambda text: '{"records": 3}', "not a task file"),
    (lambda text: text.replace('"records": [{', '"records": [3, {', 1), r"not one record per load \(2 loads\)"),
    (lambda text: text.replace('"converged": true', '"converged": "yes"', 1),
     r"record 1 \(F_N = 0.5 N\): converged = 'yes' is not of type bool"),
    (_nan_gap, r"record 2 \(F_N = 2 N\): equivalent_gap = nan in a converged solve"),
    (_edited_gap, r"its records do not match their digest \(edited or damaged\)"),
], ids=["empty", "truncated", "not UTF-8", "old list", "wrong keys", "record count", "wrong type", "NaN", "edited"])
def test_a_damaged_task_file_is_named_and_solved_again(tiny, tiny_result, finished, tmp_path, damage, reason):
    directory = shutil.copytree(finished, tmp_path / "run")
    path = directory / "tasks" / f"{plan_study(tiny).task(1, 1).key}.json"
    damaged = damage(path.read_text())
    path.write_bytes(damaged if isinstance(damaged, bytes) else damaged.encode("utf-8"))
    with pytest.warns(StaleTaskWarning, match=f"task file {re.escape(str(path))}: {reason}.*; its task is solved "
                                              "again"):
        resumed = run_study(tiny, directory, workers=1)
    assert resumed.computed == 2 and resumed.solves == 2                # that task's two loads, solved again
    assert numbers(resumed) == numbers(tiny_result)
    again = run_study(tiny, directory, workers=1)                       # rewritten whole: reused, no warning
    assert again.computed == 0 and numbers(again) == numbers(tiny_result)


def test_another_scene_in_a_directory_without_its_scene_file_solves_everything_again(tiny, finished, tmp_path):
    # scene.toml deleted: the tasks are keyed by their inputs, so another scene's tasks (other loads) are other
    # files; none is reused, none is taken for damaged, and the old ones stay beside the new
    directory = shutil.copytree(finished, tmp_path / "run")
    (directory / "scene.toml").unlink()
    other = load_scene(text=TINY.replace("normal_forces = [0.5, 2.0]", "normal_forces = [1.0, 3.0]"),
                       preset="draft")
    with warnings.catch_warnings():
        warnings.simplefilter("error", StaleTaskWarning)
        result = run_study(other, directory, workers=1)
    assert result.computed == 4
    assert numbers(result) == numbers(run_study(other, workers=1))
    assert load_scene(directory / "scene.toml") == other
    assert len(list((directory / "tasks").glob("*.json"))) == 8


def test_a_task_file_of_other_inputs_is_named_and_solved_again(tiny, tiny_result, finished, tmp_path):
    # a task file copied over another's (its key and inputs are those of realisation 0): not reused
    directory = shutil.copytree(finished, tmp_path / "run")
    plan = plan_study(tiny)
    target = directory / "tasks" / f"{plan.task(1, 1).key}.json"
    shutil.copyfile(directory / "tasks" / f"{plan.task(0, 1).key}.json", target)
    with pytest.warns(StaleTaskWarning, match=f"task file {re.escape(str(target))}: written for other inputs"):
        resumed = run_study(tiny, directory, workers=1)
    assert resumed.computed == 2 and numbers(resumed) == numbers(tiny_result)
    stored = json.loads(target.read_text())                     # the inputs of an edited file do not hash to it
    stored["key"], stored["inputs"]["voltage"] = plan.task(1, 1).key, 100.0
    target.write_text(json.dumps(stored))
    with pytest.warns(StaleTaskWarning, match="written for other inputs"):
        assert run_study(tiny, directory, workers=1).computed == 2


def test_variant_scenes_share_one_task_directory(tiny, tiny_result, tmp_path):
    # two scenes differing in their second voltage: run into results directories of their own with one task
    # directory, the second solves only its 100 V tasks (the 0 V tasks have equal inputs, so equal keys)
    shared = tmp_path / "tasks"
    first = run_study(tiny, tmp_path / "a", workers=1, tasks=shared)
    variant = load_scene(text=TINY.replace("voltages = [0.0, 150.0]", "voltages = [0.0, 100.0]"), preset="draft")
    second = run_study(variant, tmp_path / "b", workers=1, tasks=shared)
    assert (first.computed, second.computed) == (4, 2) and second.solves == 4      # 2 realisations x 2 loads
    assert numbers(second) == numbers(run_study(variant, workers=1))
    assert [point.equivalent_gap for row in second.points for point in row[:1]] == \
        [point.equivalent_gap for row in tiny_result.points for point in row[:1]]
    assert len(list(shared.glob("*.json"))) == 6 and not (tmp_path / "a" / "tasks").exists()
    assert numbers(open_results(tmp_path / "b", tasks=shared)) == numbers(second)
    # a task directory alone (no results directory): the tasks are kept there and nothing else is written
    alone = run_study(load_scene(text=TINY.replace("150.0]", "150.0, 200.0]"), preset="draft"), workers=1,
                      tasks=shared)
    assert alone.computed == 2 and sorted(path.name for path in tmp_path.iterdir()) == ["a", "b", "tasks"]
    assert len(list(shared.glob("*.json"))) == 8


def test_the_command_shares_a_task_directory(tiny, tmp_path, capsys):
    run_study(tiny, tmp_path / "a", workers=1, tasks=tmp_path / "tasks")
    variant = tmp_path / "variant.toml"
    variant.write_text(TINY.replace("voltages = [0.0, 150.0]", "voltages = [0.0, 100.0]"))
    assert main(["run", str(variant), "--preset", "draft", "--out", str(tmp_path / "b"), "--tasks",
                 str(tmp_path / "tasks"), "--workers", "1"]) == 0
    assert "2 points computed (4 contact solves), 2 resumed" in capsys.readouterr().out
    assert not (tmp_path / "b" / "tasks").exists() and len(list((tmp_path / "tasks").glob("*.json"))) == 6


def test_an_empty_scene_file_is_written_again(tiny, tiny_result, finished, tmp_path):
    # (a write cut short by a crash before write_atomic synced its files): the tasks' fingerprints decide
    directory = shutil.copytree(finished, tmp_path / "run")
    (directory / "scene.toml").write_text("")
    resumed = run_study(tiny, directory, workers=1)
    assert resumed.computed == 0 and numbers(resumed) == numbers(tiny_result)
    assert load_scene(directory / "scene.toml") == tiny


@pytest.mark.slow
def test_the_pool_ends_with_a_killed_client(tmp_path):
    psutil = pytest.importorskip("psutil")
    script = tmp_path / "study.py"
    script.write_text(textwrap.dedent(f"""\
        import sys
        sys.path[:0] = [{str(Path(__file__).parents[3])!r}, {str(Path(__file__).parent)!r}]
        from study_scenes import TINY
        from roughcontact.study.run import open_results, run_study
        from roughcontact.study.scene import load_scene
        if __name__ == "__main__":
            scene = load_scene(text=TINY.replace("realisations = 2", "realisations = 500"), preset="draft")
            run_study(scene, {str(tmp_path / "out")!r}, workers=2)
        """))
    # the client's output goes to a pipe, as under subprocess.run(capture_output=True): its reader waits for
    # every holder of the pipe, the workers included, to end
    client = subprocess.Popen([sys.executable, str(script)], stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    try:
        while not any((tmp_path / "out" / "tasks").glob("*.json")):          # the workers have started
            assert client.poll() is None
            time.sleep(0.05)
        pool = psutil.Process(client.pid).children(recursive=True)          # forkserver, workers, tracker
    finally:
        client.kill()                       # SIGKILL: no clean-up runs; not reaped yet, so it stays a zombie
    assert len(pool) >= 3
    while psutil.Process(client.pid).status() != psutil.STATUS_ZOMBIE:        # (the signal is delivered)
        time.sleep(0.01)
    gone, alive = psutil.wait_procs(pool, timeout=30)
    assert alive == []
    ended = threading.Thread(target=client.stdout.read, daemon=True)       # end of file: no process holds it
    ended.start()
    ended.join(timeout=30)
    assert not ended.is_alive()
    client.wait()


@pytest.mark.slow
def test_ctrl_c_stops_the_command_and_its_pool_with_one_line(tmp_path):
    psutil = pytest.importorskip("psutil")
    scene = tmp_path / "scene.toml"
    scene.write_text(TINY.replace("realisations = 2", "realisations = 500"))
    command = [sys.executable, "-m", "roughcontact.cli", "run", str(scene), "--preset", "draft", "--out",
               str(tmp_path / "out"), "--workers", "2"]
    # the command as a terminal's foreground job: Ctrl-C reaches it. A shell starts a background job (a test run
    # launched with '&') with SIGINT ignored, and the command would inherit that and run to its end.
    client = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                              cwd=Path(__file__).parents[3], start_new_session=True,
                              preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    try:
        while not any((tmp_path / "out" / "tasks").glob("*.json")):          # the workers have started
            assert client.poll() is None
            time.sleep(0.05)
        pool = psutil.Process(client.pid).children(recursive=True)
        os.killpg(client.pid, signal.SIGINT)                 # Ctrl-C: the terminal signals the whole group
        out, err = client.communicate(timeout=60)
    finally:
        client.kill()
    assert client.returncode == 130 and "Traceback" not in err
    assert err.splitlines()[-1] == (f"roughcontact run: interrupted; finished tasks are kept in {tmp_path / 'out'} "
                                    "(the same command resumes)")
    assert psutil.wait_procs(pool, timeout=30)[1] == []
    assert not (tmp_path / "out" / "run.lock").exists()


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


@pytest.mark.parametrize("address, message", [
    ("nonsense", r"dask = 'nonsense' is not a scheduler address \(tcp://host:port\): missing port number"),
    ("tcp://host:port", r"dask = 'tcp://host:port' is not a scheduler address"),
    ("foo://host:1", r"dask = 'foo://host:1' is not a scheduler address \(tcp://host:port\): unknown address scheme"),
])
def test_a_malformed_scheduler_address_is_refused_at_once(address, message, tmp_path):
    pytest.importorskip("distributed")
    with pytest.raises(ValueError, match=message):
        run_study(load_scene(text=TINY, preset="draft"), tmp_path, dask=address)
    assert not (tmp_path / "scene.toml").exists()                         # refused before anything is written
    with pytest.raises(TypeError, match="dask must be a scheduler address such as 'tcp://host:8786', got int"):
        run_study(load_scene(text=TINY, preset="draft"), dask=8786)


def test_the_command_with_a_malformed_scheduler_address_ends_at_once(tmp_path):
    # a distributed.Client that failed on the address kept its event loop and hung the interpreter's exit for
    # 60 s, then printed a traceback
    pytest.importorskip("distributed")
    command = ["run", "--out", str(tmp_path / "out"), "--dask", "nonsense"]
    done = subprocess.run([sys.executable, "-m", "roughcontact.cli", *command], capture_output=True, text=True,
                          timeout=45, cwd=Path(__file__).parents[3])
    assert done.returncode == 2 and done.stderr.strip().splitlines() == [
        "roughcontact run: error: dask = 'nonsense' is not a scheduler address (tcp://host:port): missing port "
        "number in address 'nonsense'"]


def test_the_command_with_an_unreachable_scheduler_prints_one_line(tmp_path, capsys):
    dask = pytest.importorskip("dask")
    pytest.importorskip("distributed")
    scene = tmp_path / "scene.toml"
    scene.write_text(TINY)
    with dask.config.set({"distributed.comm.timeouts.connect": "1s"}):
        assert main(["run", str(scene), "--preset", "draft", "--out", str(tmp_path / "out"), "--dask",
                     "tcp://127.0.0.1:9"]) == 2
    assert capsys.readouterr().err.splitlines() == [       # (no progress bar before the refusal)
        "roughcontact run: error: dask = 'tcp://127.0.0.1:9': Timed out trying to connect to tcp://127.0.0.1:9 "
        "after 1 s"]


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
        from roughcontact.study.run import open_results, run_study
        from roughcontact.study.scene import load_scene
        run_study(load_scene(text=TINY, preset="draft"), workers=2)
    """))
    done = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, timeout=300)
    assert done.returncode != 0
    raised = [line for line in done.stderr.splitlines()      # (the resource tracker may warn after it at exit)
              if line.startswith("RuntimeError: a worker of the study's process pool")]
    assert len(raised) == 1 and "__main__" in raised[0] and "workers=1" in raised[0]
