"""What a study's solving will cost, told before it starts (``roughcontact run`` prints it): the patch, its pixels,
an estimate of the time and of each worker's memory, and whether this run compiles the numba kernels.

**The model** (calibrated with ``studies/study_cost.py``, ``docs/dev/benchmarks.md`` "The study's cost": the
default scene's patch on 64²–512² pixels and as a free 128²–256² window, at 0, 100 and 200 V, loads solved in
order and warm-started as a task solves them, four (0.5–2 N) and two (0.5 and 2 N), tolerance 1e-6, one FFT
thread, CPU seconds):

* a contact solve costs :func:`operator_applications` K(T, U) applications of the skin's Green operator (an FFT
  pair and its multiplier) on the transform grid of T pixels (the patch's; a free grid's is four times it),
  K = (400 + 600 U/100 V) (T/512²)^¼: the FFT pairs of a solve (the contact solver's and the field's, the
  layered law with air breakdown at its contact lines, the default; 100-115 / 300-350 / 515-590 per solve at
  512², 0 / 100 / 200 V, growing little from 256²) times the cost of a pair inside a solve over one timed alone
  (2.4-4.3). Against the calibration's mean cost per solve it is within 25 % at 256²–512² but for the 0 V
  solves (0.4-2x) and the free 256² window at 200 V (+47 %); below 256² it underestimates (fixed costs per
  iteration), where a task takes seconds anyway; another tolerance changes the pair count. (The plain layered
  law, ``contact_line = "none"``, took 3-4 times the pairs at 200 V: 1590-2120 per solve at 512².)
* one application is timed on the patch's own grid before the run (:func:`operator_seconds`: best of three,
  a fraction of a second at 1536 x 1152 pixels, where FFTW also plans the transforms the workers reuse).
* memory per worker (:func:`worker_memory`): the peak traced memory of a task, 31 float64 arrays of the patch
  at 0 V and 51 with the attraction on a periodic grid, 24 and 124 on a free one, plus 0.2 GB for the
  interpreter and its libraries (a worker's resident size after its first task on a 32² patch: 0.18 GB).

Checked on a 384 x 288 scan mirrored to 768 x 576 pixels, 0.5 and 2 N at 0 and 200 V, one process (``roughcontact
run`` with ``--workers 1``, ``/usr/bin/time -v``): estimated 30 s and 0.37 GB, measured 37 s of CPU for the whole
run (imports, results and figures included) and 0.35 GB resident. A 768 x 576 profilometer map, mirrored to
1536 x 1152 pixels, costs about 11 400 applications per solve at 200 V; one application took 37 ms on the shared
machine of the calibration (2.4 ms at 768 x 576: the larger arrays leave the cache), so the same four points
take about 15 min in one process, at 0.87 GB. The estimate is of CPU time: on a machine that other jobs share
the wall time is longer.
"""
from __future__ import annotations

import os
import time

import numpy as np

from ..body import elastic
from ..electrostatics import ac, field
from ..solvers import polonsky_keer, projected_cg_gap
from .apparent import ring_count

#: Green-operator applications per solve at 512² pixels, at 0 V and per 100 V (the model above).
APPLICATIONS_0V, APPLICATIONS_PER_100V = 400.0, 600.0
#: The transform grid of the calibration's largest patch, and the growth of the applications with it.
CALIBRATION_PIXELS, APPLICATIONS_EXPONENT = 512 ** 2, 0.25
#: Peak float64 arrays of the patch per task: (hard wall, with the attraction), periodic and free grid.
PATCH_ARRAYS = {True: (31, 51), False: (24, 124)}
#: A worker's interpreter, numpy, numba, FFTW and the compiled kernels [bytes].
WORKER_BASELINE = 0.2e9
#: The modules whose numba kernels a task runs (their cache is checked by :func:`kernels_cached`).
KERNEL_MODULES = (polonsky_keer, projected_cg_gap, elastic, field, ac)


def operator_applications(transform_pixels: int, voltage: float) -> float:
    """K(T, U): Green-operator applications that one contact solve costs on a transform grid of
    ``transform_pixels`` T at ``voltage`` U [V] (the model of the module docstring)."""
    scale = (transform_pixels / CALIBRATION_PIXELS) ** APPLICATIONS_EXPONENT
    return (APPLICATIONS_0V + APPLICATIONS_PER_100V * abs(voltage) / 100.0) * scale


def operator_seconds(body, repeat: int = 3) -> float:
    """Wall seconds of one application of ``body``'s Green operator (an FFT pair and the multiplier), the best
    of ``repeat`` after one untimed."""
    pressure, out = body.empty(), body.empty()
    pressure[...] = 1.0
    body.displacement_into(pressure, out)
    best = np.inf
    for _ in range(repeat):
        start = time.perf_counter()
        body.displacement_into(pressure, out)
        best = min(best, time.perf_counter() - start)
    return best


def worker_memory(pixels: int, periodic: bool, attraction: bool) -> float:
    """Bytes a worker holds solving a task on a patch of ``pixels``, on a ``periodic`` grid or a free one, with
    the ``attraction`` acting or not."""
    return WORKER_BASELINE + 8.0 * pixels * PATCH_ARRAYS[periodic][attraction]


def kernels_cached() -> bool:
    """Whether numba's cache holds every kernel of :data:`KERNEL_MODULES`, as an earlier run left it: each
    kernel's index file exists and is not older than its source. False: this run compiles them (20–30 s per
    process, once). True where numba compiles nothing (``NUMBA_DISABLE_JIT``)."""
    from numba.core.registry import CPUDispatcher
    for module in KERNEL_MODULES:
        source = os.path.getmtime(module.__file__)
        for kernel in vars(module).values():
            if not isinstance(kernel, CPUDispatcher) or type(kernel._cache).__name__ != "FunctionCache":
                continue
            try:
                index = kernel._cache._cache_file._index_path             # (numba's, no public name)
            except AttributeError:
                return False
            if not os.path.exists(index) or os.path.getmtime(index) < source:
                return False
    return True


def _duration(seconds: float) -> str:
    if seconds < 1:
        return "under a second"
    if seconds < 90:
        return f"about {seconds:.0f} s"
    if seconds < 5400:
        return f"about {seconds / 60:.0f} min"
    return f"about {seconds / 3600:.1f} h"


def patch_line(plan) -> str:
    """The patch of ``plan`` (a :class:`~.plan.StudyPlan`) in words: pixels, their count, a measured scan's own
    size, the lengths and the boundary."""
    grid, roughness = plan.grid, plan.scene.roughness
    (nx, ny), measured = grid.shape, plan.topography is not None
    origin = (f"; the {nx // 2} x {ny // 2} scan mirrored" if measured and roughness.boundary == "mirrored"
              else "; the scan" if measured else "")
    return (f"patch {nx} x {ny} pixels ({nx * ny / 1e6:.3g} M{origin}), {grid.lengths[0] * 1e3:.3g} x "
            f"{grid.lengths[1] * 1e3:.3g} mm, {'periodic' if all(grid.periodic) else 'free'}")


def run_estimate(jobs, workers: int | None, seconds_per_application: float | None = None) -> list:
    """The lines printed before the tasks ``jobs`` (pairs of a :class:`~.plan.StudyPlan` and one of its tasks)
    are solved on ``workers`` processes (None: a cluster's): each distinct patch, the tasks and solves, the
    estimated time and the memory per worker, and a line when the numba kernels are compiled first.
    ``seconds_per_application``: one Green-operator application (timed on each distinct transform grid with
    :func:`operator_seconds` when not given)."""
    if not jobs:
        return []
    lines = list(dict.fromkeys(patch_line(plan) for plan, _ in jobs))
    resolved = [(plan, task) for plan, task in jobs if plan.scene.preset.scales != "coupled"]
    if len(resolved) < len(jobs):
        lines.append(f"{len(jobs) - len(resolved)} tasks of the coupled path (an interface law, then the ridges): "
                     "no estimate")
    if resolved:
        timed, shapes, costs, memory, solves = {}, {}, [], 0.0, 0
        for plan, task in resolved:
            if id(plan) not in shapes:                   # one body per plan, one timing per transform grid
                body = plan.body(1)
                shapes[id(plan)] = shape = (tuple(body.transform_shape), plan.scene.preset.dtype)
                if shape not in timed:
                    timed[shape] = (operator_seconds(body) if seconds_per_application is None
                                    else seconds_per_application)
            shape = shapes[id(plan)]
            count, voltage = len(plan.normal_forces) * ring_count(plan.scene), plan.voltages[task.voltage_index]
            costs.append(count * operator_applications(int(np.prod(shape[0])), voltage) * timed[shape])
            solves += count
            memory = max(memory, worker_memory(plan.grid.size, all(plan.grid.periodic), voltage > 0))
        parallel = 1 if workers is None else min(workers, len(costs))
        wall = max(max(costs), sum(costs) / parallel)
        where = (f"on {parallel} worker{'s' if parallel > 1 else ''}" if workers is not None else
                 "of CPU on the cluster")
        applications = ", ".join(f"{seconds * 1e3:.3g} ms" for seconds in timed.values())
        calibrated = all(np.prod(shape) <= CALIBRATION_PIXELS for shape, _ in timed)
        model = ("a model within a factor 2-3" if calibrated else
                 "a lower bound: the model is calibrated up to 512² pixels")
        lines.append(f"{len(resolved)} task{'s' if len(resolved) > 1 else ''}, {solves} solves: "
                     f"{_duration(wall if workers is not None else sum(costs))} {where} (one Green-operator "
                     f"application {applications}; {model}: roughcontact.study.cost), memory "
                     f"about {memory / 1e9:.2g} GB per worker")
    if not kernels_cached():
        lines.append("compiling the numba kernels (first run only, 20-30 s per worker) ...")
    return lines
