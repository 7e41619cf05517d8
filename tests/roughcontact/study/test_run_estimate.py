"""Before a study solves: the patch, its pixels, an estimate of the time and memory (roughcontact.study.cost), a
line when the numba kernels are compiled first; while it solves, the bar advances with every load of a task, in
this process and from a process pool's workers."""
import multiprocessing
import os
import subprocess
import sys
import time
from concurrent.futures import ProcessPoolExecutor

import numpy as np
import pytest

import surfaces
from roughcontact.solvers import solve_contact
from roughcontact.study import cost
from roughcontact.study.apparent import apparent_scale
from roughcontact.study.patch import PatchScaleWarning
from roughcontact.study.plan import plan_study
from roughcontact.study.progress import LoadProgress
from roughcontact.study.resolved import solve_chain
from roughcontact.study.run import run_study
from roughcontact.study.scene import load_scene


class Bar:
    """A stand-in for tqdm: records its updates."""

    def __init__(self, *arguments, **options):
        self.updates, self.n = [], 0.0

    def update(self, step):
        self.updates.append(step)
        self.n += step

    def close(self):
        pass


def test_the_model_bounds_the_counted_fft_pairs_of_a_task():
    """The model's Green-operator applications per solve are the FFT pairs of a solve times the cost of a pair
    inside a solve over a bare one (2.4-4.3 in the calibration): on the default scene's 256² patch, its four
    loads warm-started as a task solves them at 0 and 100 V (a calibration point), the counted pairs
    (deterministic) must lie between K/4 and K. A solver that needs far more or far fewer pairs than calibrated
    fails here: recalibrate with studies/study_cost.py."""
    scene = load_scene(text="[loads]\nvoltages = [0.0, 100.0]\n[presets.standard]\n"
                            "grid = 256\ntolerance = 1e-6\npixels_per_cutoff = 2.0\n", preset="standard")
    plan = plan_study(scene)
    heights, body = plan.surface(0), plan.body(1)
    for voltage in plan.voltages:
        law, latest, pairs = scene.screen.interaction(voltage), None, []
        for _, (pressure,) in apparent_scale(scene):
            latest = solve_contact(heights, body, mean_pressure=pressure, interaction=law, tol=1e-6, x0=latest,
                                   warn=False)
            pairs.append(latest.solver.fft_pairs)
        model = cost.operator_applications(256 ** 2, voltage)
        assert model / 4 <= np.mean(pairs) <= model, (voltage, pairs, model)


def test_the_estimate_names_the_patch_the_solves_the_time_and_the_memory(tmp_path):
    scan = surfaces.self_affine(surfaces.Grid((24, 20), (1.2e-4, 1e-4), periodic=False), hurst=0.8,
                                rms_height=3e-6, rng=2)
    scan.save(tmp_path / "scan.npz")
    scene = load_scene(text=f'[ridges]\nenabled = false\n[roughness]\ntopography = "{tmp_path / "scan.npz"}"\n'
                            "[loads]\nnormal_forces = [0.5, 1.0, 2.0]\nvoltages = [0.0, 100.0]\n", preset="draft")
    with pytest.warns(PatchScaleWarning):                         # (a 0.12 mm scan: no ridge period)
        plan = plan_study(scene)
    lines = cost.run_estimate([(plan, task) for task in plan.tasks], workers=2, seconds_per_application=0.01)
    assert lines[0] == "patch 48 x 40 pixels (0.00192 M; the 24 x 20 scan mirrored), 0.24 x 0.2 mm, periodic"
    # per task 3 solves x K(48 x 40, U) x 10 ms; two workers, two tasks: the longer one, at 100 V
    seconds = 3 * cost.operator_applications(48 * 40, 100.0) * 0.01
    assert 3 < seconds < 90
    assert lines[1].startswith(f"2 tasks, 6 solves: about {seconds:.0f} s on 2 workers (one Green-operator "
                               "application 10 ms; a model within a factor 2-3")
    memory = cost.worker_memory(48 * 40, periodic=True, attraction=True)
    assert memory == 0.2e9 + 8 * 48 * 40 * 51 and lines[1].endswith(f"memory about {memory / 1e9:.2g} GB per worker")
    # a 768 x 576 profilometer map mirrored: 1.77 M pixels, with the attraction 0.92 GB a worker
    assert cost.worker_memory(1536 * 1152, True, True) == pytest.approx(0.922e9, rel=1e-3)
    assert cost.run_estimate([], workers=1) == []                             # nothing to solve: nothing said


def test_beyond_the_calibrated_patches_the_estimate_is_a_lower_bound():
    # a 1536 x 1152 measured-like scan's 200 V solves took about 3 times the estimate (docs/dev/benchmarks.md,
    # "A big measured-like scan"): beyond 512² pixels the run says the estimate is a lower bound
    plan = plan_study(load_scene(text="[presets.draft]\ngrid = 1024\n[loads]\nvoltages = [200.0]\n", preset="draft"))
    line = cost.run_estimate([(plan, plan.tasks[0])], workers=1, seconds_per_application=1e-3)[1]
    assert "a lower bound: the model is calibrated up to 512² pixels" in line and "factor 2-3" not in line


def test_a_cold_numba_cache_is_told_before_the_first_task(monkeypatch, tmp_path):
    empty = tmp_path / "numba-cache"
    empty.mkdir()
    script = "from roughcontact.study.cost import kernels_cached; print(kernels_cached())"
    environment = {**os.environ, "NUMBA_CACHE_DIR": str(empty), "PYTHONPATH": os.pathsep.join(sys.path)}
    answer = subprocess.run([sys.executable, "-c", script], env=environment, capture_output=True, text=True, check=True)
    assert answer.stdout.strip() == "False"                                   # nothing compiled into that cache
    plan = plan_study(load_scene(text="[presets.draft]\ngrid = 16\n[roughness]\nenabled = false\n", preset="draft"))
    monkeypatch.setattr(cost, "kernels_cached", lambda: False)
    assert cost.run_estimate([(plan, plan.tasks[0])], 1, 1e-5)[-1] == (
        "compiling the numba kernels (first run only, 20-30 s per worker) ...")
    monkeypatch.setattr(cost, "kernels_cached", lambda: True)
    assert "numba" not in cost.run_estimate([(plan, plan.tasks[0])], 1, 1e-5)[-1]


def test_a_task_reports_each_load(tiny):
    calls = []
    records = solve_chain(plan_study(tiny), 0, 1, 1, progress=lambda: calls.append(time.perf_counter()))
    assert len(calls) == len(records) == 2


def test_the_bar_advances_with_each_load_in_this_process(tiny, monkeypatch, capsys):
    bars = []
    monkeypatch.setattr("tqdm.tqdm", lambda *arguments, **options: bars.append(Bar()) or bars[-1])
    run_study(tiny, progress=True, workers=1)
    # 4 tasks (2 realisations x 2 voltages) of 2 loads; a load of one realisation is half a point
    assert bars[0].updates[:8] == [0.5] * 8 and bars[0].n == 4
    told = capsys.readouterr().err
    assert "roughcontact run: patch 32 x 32 pixels (0.00102 M), 0.45 x 0.45 mm, periodic" in told
    assert "roughcontact run: 4 tasks, 8 solves: under a second on 1 worker (one Green-operator application" in told


def _three_loads(reporter):
    for _ in range(3):
        reporter()
    return os.getpid()


def test_a_pool_worker_reports_its_loads_through_the_manager_queue():
    bar = Bar()
    context = multiprocessing.get_context("forkserver" if "forkserver" in multiprocessing.get_all_start_methods()
                                          else "spawn")
    with ProcessPoolExecutor(1, mp_context=context) as pool, LoadProgress(bar, pooled=True) as loads:
        reporter = loads.reporter("task-a", 4, 0.25)
        assert pool.submit(_three_loads, reporter).result() != os.getpid()        # ran in the worker
        deadline = time.monotonic() + 30
        while bar.n < 0.75 and time.monotonic() < deadline:                        # the reader thread's pace
            time.sleep(0.01)
        assert bar.updates == [0.25] * 3
        loads.finished("task-a")                                                   # the fourth load: credited
        loads._advance("task-a")                                                   # a late report: ignored
    assert bar.updates == [0.25] * 4 and bar.n == 1.0


def test_no_bar_no_reporter_and_a_cluster_counts_whole_tasks():
    assert LoadProgress(None, pooled=True).reporter("k", 2, 1.0) is None
    bar = Bar()
    cluster = LoadProgress(bar, pooled=False, local=False)
    assert cluster.reporter("k", 2, 0.5) is None
    cluster.finished("k")
    assert bar.updates == [1.0]
