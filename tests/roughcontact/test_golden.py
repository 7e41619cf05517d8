"""Golden guard: the bytes of every array and the iteration counts of representative solves stay as recorded.

A refactoring that moves code (the package layout, an import) must not change a single bit of what the solvers
compute. Each case below runs a small solve and reduces its result to a record: the sha256 of every array field
(dtype, shape and bytes), the exact hex of every float, the integers (iterations, unstable steps) and the
strings; wall-clock times and the library version are left out. ``golden.json`` beside this file holds the
records; the test compares them field by field, so a failure names the case and the field that changed.

The cases run in a fresh interpreter with the FFT plans pinned (``ROUGHCONTACT_FFTW_PLANNER=FFTW_ESTIMATE``, one
FFT thread; the numba kernels are serial): in the test process, FFTW would reuse the wisdom of measured plans
that other tests made (``test_fft.py``), and an estimated plan can then differ from a fresh one in the last
bits. So the records are reproducible on one machine and library stack, whatever ran before. A change of numpy,
pyFFTW, numba or the CPU may change the last bits legitimately: regenerate the records on the reference stack
with

    python tests/roughcontact/test_golden.py --update

and review the diff of ``golden.json`` (only records that should change may change). A physics change that is
meant to change answers regenerates them the same way, in its own commit.
"""
import dataclasses
import hashlib
import json
import os
import runpy
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from surfaces import Grid, HeightField, self_affine
from roughcontact import (ContactProblem, ElasticHalfSpace, ElectrostaticInteraction, ExponentialAdhesion,
                          MaugisDugdale, load_path, solve_contact)
from roughcontact.electrostatics import DielectricStack
from roughcontact.solvers import ContactResult, load_cycle, pull_off
from roughcontact.study.coupled import interface_law
from roughcontact.study.patch import closing_lengths, patch_body, roughness_heights
from roughcontact.study.resolved import solve_chain
from roughcontact.study.scene import load_scene

GOLDEN = Path(__file__).with_name("golden.json")
ROOT = Path(__file__).resolve().parents[2]
PINNED = {"ROUGHCONTACT_FFTW_PLANNER": "FFTW_ESTIMATE", "ROUGHCONTACT_FFT_THREADS": "1", "NUMBA_NUM_THREADS": "1",
          "OMP_NUM_THREADS": "1"}
SKIPPED = {"wall_time", "seconds", "version"}            # clocks and the release string: not answers
STACK = DielectricStack()
#: The result attributes recorded beside its fields (they were fields before the typed SolverReport).
REPORT_ATTRIBUTES = ("iterations", "residuals", "converged", "message", "wall_time", "unstable_steps")


def report_record(result) -> dict:
    """The solver's settings and diagnostics of ``result`` as one dict, the record's ``params`` entry (the layout
    the records were first written in: the report's entries, the body's E*, the control and the law's class)."""
    report = result.solver
    record = {"E_star": report.kernel.get("E_star"), "grid": result.grid, "tol": report.tol,
              "maxiter": report.maxiter, "method": report.method, "start": report.start,
              "control": result.control, "requested": result.requested,
              "interaction": type(result.interaction).__name__, "kernel": report.kernel,
              "version": report.version, "fft_pairs": report.fft_pairs, **report.details}
    if report.method != "polonsky-keer":
        record["detached"] = report.detached
    return record


def digest(value):
    """A JSON-able record of ``value``: arrays as sha256 of dtype, shape and bytes; floats as exact hex."""
    if isinstance(value, np.ndarray):
        array = np.ascontiguousarray(value)
        payload = f"{array.dtype.str}{array.shape}".encode() + array.tobytes()
        return "sha256:" + hashlib.sha256(payload).hexdigest()
    if isinstance(value, ContactResult):     # recorded as before its SolverReport: the same numbers, one layout
        record = {f.name: getattr(value, f.name) for f in dataclasses.fields(value) if f.name not in ("grid", "solver")}
        record.update({name: getattr(value, name) for name in REPORT_ATTRIBUTES}, params=report_record(value))
        return {"__type__": "ContactResult", **{name: digest(v) for name, v in record.items() if name not in SKIPPED}}
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return {"__type__": type(value).__name__,
                **{f.name: digest(getattr(value, f.name)) for f in dataclasses.fields(value)
                   if f.name not in SKIPPED and not f.name.startswith("_")}}
    if isinstance(value, dict):
        return {str(k): digest(v) for k, v in value.items() if k not in SKIPPED}
    if isinstance(value, (list, tuple)):
        return [digest(v) for v in value]
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        return float(value).hex()
    if isinstance(value, Grid):
        return digest(value.to_dict())
    return repr(value)


# -- the cases ----------------------------------------------------------------------------------------------
def rough(n=64, periodic=True, dtype=np.float64, **body):
    grid = Grid((n, n), (1e-3, 1e-3), periodic=periodic)
    surface = self_affine(grid, hurst=0.8, rms_height=3e-6, short_cutoff=8e-3 / n, rng=1)
    return surface, ElasticHalfSpace(grid, E_star=1e6, dtype=dtype, **body)


def sphere(n=32):
    grid = Grid((n, n), (0.8, 0.8), periodic=False)
    x = (np.arange(n) - n / 2 + 0.5) * 0.8 / n
    return HeightField(grid, -(x[:, None] ** 2 + x[None, :] ** 2) / 2.0), ElasticHalfSpace(grid, E_star=1.0)


def sinusoid(n=256):
    grid = Grid((n, 1), (1.0, 1.0 / n), periodic=True)
    x = (np.arange(n) + 0.5) / n - 0.5
    return HeightField(grid, -(1 - np.cos(2 * np.pi * x))[:, None]), ElasticHalfSpace(grid, E_star=1 / np.pi)


def tiny_scene():
    tiny = runpy.run_path(str(Path(__file__).with_name("study") / "study_scenes.py"))["TINY"]
    return load_scene(text=tiny.replace("realisations = 2", "realisations = 1"), preset="draft")


def hard_wall_periodic():
    return solve_contact(*rough(), mean_pressure=5e3)


def hard_wall_pk_unpreconditioned():
    return solve_contact(*rough(), mean_pressure=5e3, cold_start="pk", preconditioned=False, tol=1e-6)


def hard_wall_warm_start():
    surface, body = rough()
    first = solve_contact(surface, body, mean_pressure=5e3)
    return solve_contact(surface, body, mean_pressure=8e3, x0=first)


def hard_wall_free_surface():
    surface, body = sphere()
    return solve_contact(surface, body, penetration=0.01)


def hard_wall_layer_on_rigid_base():
    return solve_contact(*rough(thickness=2e-4, poisson=0.45), mean_pressure=5e3)


def hard_wall_layer_on_half_space_free():
    return solve_contact(*rough(32, periodic=False, thickness=1e-4, poisson=0.45, substrate_E_star=1e5,
                                substrate_poisson=0.49), mean_pressure=5e3)


def hard_wall_float32():
    return solve_contact(*rough(dtype=np.float32), mean_pressure=5e3)


def electrostatic_load_control():
    return solve_contact(*rough(), mean_pressure=1e3, interaction=ElectrostaticInteraction(STACK, 30.0, field="parallel_plate"))


def electrostatic_float32():
    return solve_contact(*rough(dtype=np.float32), mean_pressure=1e3,
                         interaction=ElectrostaticInteraction(STACK, 30.0, field="parallel_plate"))


def electrostatic_layered_field():
    return solve_contact(*rough(), mean_pressure=1e3,
                         interaction=ElectrostaticInteraction(STACK, 100.0, field="layered"))


def exponential_position_control():
    surface, body = rough()
    return solve_contact(surface, body, penetration=3e-6, interaction=ExponentialAdhesion(1e-3, 2e-7))


def maugis_dugdale_free_surface():
    surface, body = sphere()
    return solve_contact(surface, body, mean_pressure=0.0, interaction=MaugisDugdale(1e-3, 1e-2))


def load_path_hard_wall():
    return list(load_path(*rough(), [2e3, 4e3, 8e3]))


def load_cycle_adhesive():
    surface, body = sinusoid()
    return load_cycle(ContactProblem(surface, body, ExponentialAdhesion(0.2 ** 2 * np.pi / 2, 0.05)),
                      [0.1, 0.3, 0.6, 0.0], keep_results=True, warn=False)


def pull_off_adhesive():
    surface, body = sinusoid()
    problem = ContactProblem(surface, body, ExponentialAdhesion(0.2 ** 2 * np.pi / 2, 0.05))
    return pull_off(problem, problem.solve(mean_pressure=0.1), step=0.05, tol=0.1)


def study_records():
    return solve_chain(tiny_scene(), 0, 1, threads=1)


def study_records_zero_volt():
    return solve_chain(tiny_scene(), 0, 0, threads=1)


def interface_law_tiny():
    scene = tiny_scene()
    return interface_law(roughness_heights(scene, 0), patch_body(scene, threads=1), scene.screen.stack(), 150.0,
                         tol=scene.preset.tolerance, coarse_graining=closing_lengths(scene))


CASES = [hard_wall_periodic, hard_wall_pk_unpreconditioned, hard_wall_warm_start, hard_wall_free_surface,
         hard_wall_layer_on_rigid_base, hard_wall_layer_on_half_space_free, hard_wall_float32,
         electrostatic_load_control, electrostatic_float32, electrostatic_layered_field,
         exponential_position_control, maugis_dugdale_free_surface, load_path_hard_wall, load_cycle_adhesive,
         pull_off_adhesive, study_records, study_records_zero_volt, interface_law_tiny]


def _differences(expected, actual, path=""):
    if isinstance(expected, dict) and isinstance(actual, dict):
        return [d for key in sorted(set(expected) | set(actual))
                for d in _differences(expected.get(key), actual.get(key), f"{path}.{key}")]
    if isinstance(expected, list) and isinstance(actual, list) and len(expected) == len(actual):
        return [d for i, (e, a) in enumerate(zip(expected, actual)) for d in _differences(e, a, f"{path}[{i}]")]
    return [] if expected == actual else [f"{path}: {expected!r} -> {actual!r}"]


def records() -> dict:
    """Every case's record, computed in a fresh interpreter with the FFT plans pinned (module docstring)."""
    environment = {**os.environ, **PINNED,
                   "PYTHONPATH": os.pathsep.join(filter(None, [str(ROOT), os.environ.get("PYTHONPATH")]))}
    run = subprocess.run([sys.executable, __file__, "--print"], capture_output=True, text=True, env=environment,
                         check=True)
    return json.loads(run.stdout)


@pytest.fixture(scope="module")
def computed():
    return records()


@pytest.mark.parametrize("case", CASES, ids=[case.__name__ for case in CASES])
def test_golden(case, computed):
    golden = json.loads(GOLDEN.read_text())
    assert case.__name__ in golden, f"no golden record for {case.__name__}: python {__file__} --update"
    differences = _differences(golden[case.__name__], computed[case.__name__])
    assert not differences, f"{case.__name__} changed:\n" + "\n".join(differences[:20])


def test_digest_sees_one_bit():
    # the guard must fail on the smallest change: one ulp in one array element, one more iteration
    result = hard_wall_periodic()
    pressure = result.pressure.copy()
    pressure.flat[7] = np.nextafter(pressure.flat[7], np.inf)
    changed = dataclasses.replace(result, pressure=pressure,
                                  solver=dataclasses.replace(result.solver, iterations=result.iterations + 1))
    assert {d.split(":")[0] for d in _differences(digest(result), digest(changed))} == {".pressure", ".iterations"}


if __name__ == "__main__":                 # --print: the records as JSON; --update: rewrite golden.json
    if "--print" in sys.argv:
        print(json.dumps({case.__name__: digest(case()) for case in CASES}))
    elif "--update" in sys.argv:
        GOLDEN.write_text(json.dumps(records(), indent=1, sort_keys=True) + "\n")
    else:
        sys.exit(f"usage: python {sys.argv[0]} --update")
