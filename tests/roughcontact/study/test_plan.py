"""The study planned once: the patch is worked out once per study, a task's key is a hash of exactly the inputs
its records depend on (a scene changed where no record looks keeps the key and gives the same records, bit for
bit), a measured scan is keyed by its content (a replaced scan is solved again, never resumed; load_scene reads
it again), and a results directory stands without the scan's file."""
import collections
import dataclasses
import json
import shutil
import sys
import warnings

import numpy as np
import pytest

import surfaces
from roughcontact.cli import main
from roughcontact.study.execution import StaleTaskWarning
from roughcontact.study.plan import StudyPlan, plan_study, task_key
from roughcontact.study.resolved import solve_chain
from roughcontact.study.run import open_results, run_study
from roughcontact.study.scene import SECTIONS, load_scene
from study_scenes import TINY


def untimed(records):
    return [dataclasses.replace(record, seconds=0.0) for record in records]


def numbers(result):
    """Every number of a study but the solve times."""
    return [[dataclasses.replace(point, seconds=0.0) for point in row] for row in result.points]


# ---------------------------------------------------------------------------------------------------------
# The plan
# ---------------------------------------------------------------------------------------------------------
def test_the_plan_holds_what_the_tasks_share(tiny):
    plan = plan_study(tiny)
    assert isinstance(plan, StudyPlan) and plan.scene is tiny
    assert plan.grid.shape == (32, 32) and plan.grid.lengths == (4.5e-4, 4.5e-4)
    assert plan.closing_lengths == (6e-5, 1.2e-4)
    assert plan.short_cutoff == 3.0 * 4.5e-4 / 32             # 3 pixels: above the scene's 10 µm
    assert (plan.realisations, plan.normal_forces, plan.voltages, plan.frequencies) == (2, (0.5, 2.0), (0.0, 150.0), ())
    assert plan.topography is None and plan.topography_digest is None
    assert [task.index for task in plan.tasks] == [(0, 0), (1, 0), (0, 1), (1, 1)]
    assert len({task.key for task in plan.tasks}) == 4
    task = plan.task(1, 1)
    assert task.key == task_key(plan.inputs(1, 1)) and plan.describe(task) == "realisation 1 at 150 V"
    inputs = plan.inputs(1, 1)
    assert inputs["voltage"] == 150.0 and inputs["patch"]["stream"] == 1 and inputs["frequency"] is None
    assert json.loads(json.dumps(inputs)) == inputs                     # plain JSON values
    with pytest.raises(ValueError, match=r"task \(2, 0\) is not one of the study's \(2 realisation"):
        plan.task(2, 0)
    with pytest.raises(TypeError, match="scene must be a Scene"):
        plan_study({"loads": {}})


def test_the_patch_is_worked_out_once_per_study(tiny, tmp_path, monkeypatch):
    # every reference to these functions in the study's modules counts its calls: one study (planned, run,
    # stored, resumed) works the patch grid, the closing lengths and the cut-off out once
    calls = collections.Counter()

    def counting(name, function):
        def counted(*arguments, **keywords):
            calls[name] += 1
            return function(*arguments, **keywords)
        return counted

    for module in [module for name, module in sys.modules.items() if name.startswith("roughcontact.study.")]:
        for name in ("patch_grid", "closing_lengths", "resolved_short_cutoff", "measured_topography"):
            if callable(getattr(module, name, None)):
                monkeypatch.setattr(module, name, counting(name, getattr(module, name)))
    run_study(tiny, tmp_path, workers=1)
    assert calls == {"patch_grid": 1, "closing_lengths": 1, "resolved_short_cutoff": 1}
    calls.clear()
    assert run_study(tiny, tmp_path, workers=1).computed == 0
    assert calls == {"patch_grid": 1, "closing_lengths": 1, "resolved_short_cutoff": 1}


# ---------------------------------------------------------------------------------------------------------
# Content keys: exactly the inputs the records depend on
# ---------------------------------------------------------------------------------------------------------
def _candidates(value, check):
    """Other valid-looking values of a scene key: the other options of a choice, the other boolean, a number
    a quarter up or a fifth down (a zero made positive), a list with its last entry moved, a drive frequency."""
    if isinstance(value, bool):
        return [not value]
    if isinstance(value, str):
        return [option for option in getattr(check, "options", ()) if option != value]
    if value is None:
        return [(300.0,)]
    if isinstance(value, int):
        return [value + 1, value - 1]
    if isinstance(value, float):
        return [value * 1.25, value * 0.8] if value else [1e7]
    return [(*value[:-1], value[-1] * 1.25)] if value else []          # (an absent list: a measured scan's keys)


def _variants(scene):
    """``(key, scene)`` for each scene key (the sections and the preset in use) changed to its first valid
    other value."""
    for section in (*SECTIONS, "preset"):
        table = scene.preset if section == "preset" else getattr(scene, section)
        for field in dataclasses.fields(table):
            for value in _candidates(getattr(table, field.name), field.metadata["check"]):
                try:
                    changed = dataclasses.replace(table, **{field.name: value})
                except (TypeError, ValueError):
                    continue
                if section == "preset":
                    yield "preset." + field.name, dataclasses.replace(
                        scene, presets={**scene.presets, scene.study.preset: changed})
                else:
                    yield f"{section}.{field.name}", dataclasses.replace(scene, **{section: changed})
                break


def _shared_keys_solve_alike(base):
    """The scene keys whose change leaves a task's key as it was; for each, that task solved for the changed
    scene gives the records of the base scene's task with that key, bit for bit (so no input that a record
    depends on is missing from the key)."""
    plan, solved, shared = plan_study(base), {}, []
    by_key = {task.key: task for task in plan.tasks}
    for name, scene in _variants(base):
        try:
            variant = plan_study(scene)
        except ValueError:                                  # (e.g. a cut-off the preset cannot resolve)
            continue
        task = next((task for task in variant.tasks if task.key in by_key), None)
        if task is None:
            continue
        shared.append(name)
        same = by_key[task.key]
        if same.key not in solved:
            solved[same.key] = untimed(solve_chain(plan, *same.index, 1))
        assert untimed(solve_chain(variant, *task.index, 1)) == solved[same.key], name
    return shared


def test_a_key_changes_with_every_input_of_its_records(tiny):
    # the tiny scene: power-law fingerpad, ridges without pores, synthetic roughness with a raised cut-off (the
    # scene's 10 µm under the preset's 3 pixels of 14 µm): these keys are read by no task of it. The seed moves
    # the rng streams (realisation 0 of seed 1 is realisation 1 of seed 0) and another voltage list keeps the
    # tasks of the voltages both have. (fingerpad.layer = true is refused with the power law.)
    assert _shared_keys_solve_alike(tiny) == [
        "fingerpad.radius", "fingerpad.E_star", "fingerpad.layer_grid", "ridges.pore_diameter",
        "ridges.pore_depth", "roughness.short_cutoff", "roughness.boundary", "roughness.detrend", "roughness.missing",
        "loads.voltages", "study.seed", "preset.realisations", "preset.rings"]


def test_a_key_changes_with_every_key_of_a_leak():
    # under a drive each key of a leak across the interface changes what the records hold, so it changes the key
    # (two scenes that differ in the leak alone once shared their tasks in one task directory, and the second read
    # the first's records); a drive without a leak keys as before the leak's keys existed
    drive = load_scene(text=TINY.replace("voltages = [0.0, 150.0]", "voltages = [150.0]")
                       + "[screen]\nfrequency = [300.0]\n", preset="draft")
    keys = {task.key for task in plan_study(drive).tasks}
    for leak in ({"gap_conductance": 0.061}, {"gap_conductivity": 1.5e-8}, {"gap_cpe": 1e-3},
                 {"gap_cpe_exponent": 0.7}, {"contact_transfer": True},
                 {"surface_conductance": 1e-8, "contact_transfer": True}):
        leaky = dataclasses.replace(drive, screen=dataclasses.replace(drive.screen, **leak))
        assert not keys & {task.key for task in plan_study(leaky).tasks}, leak
    leaky = dataclasses.replace(drive, screen=dataclasses.replace(drive.screen, gap_conductivity=1.5e-8))
    records = [untimed(solve_chain(plan_study(scene), 0, 0, 1, frequency_index=0)) for scene in (drive, leaky)]
    assert records[0] != records[1]                    # what the key now tells apart, the records do
    inputs = plan_study(drive).inputs(0, 0, 0)["screen"]
    assert set(inputs) == {"d_sc", "eps_sc", "d_i", "eps_i", "eps_a", "field", "sigma_sc"}


def test_a_key_changes_with_the_contact_line():
    # the layered law's model of the contact line changes what a voltage's records hold, so it changes the key
    # (a study of another breakdown field once read the default's records from a shared task directory)
    tiny = load_scene(text=TINY.replace("voltages = [0.0, 150.0]", "voltages = [150.0]"), preset="draft")
    keys = {task.key for task in plan_study(tiny).tasks}
    for line in ("none", "breakdown:7e+08", "film:5e-08"):
        other = dataclasses.replace(tiny, screen=dataclasses.replace(tiny.screen, contact_line=line))
        assert not keys & {task.key for task in plan_study(other).tasks}, line
    plain = dataclasses.replace(tiny, screen=dataclasses.replace(tiny.screen, contact_line="none"))
    records = [untimed(solve_chain(plan_study(scene), 0, 0, 1)) for scene in (tiny, plain)]
    assert records[0] != records[1]                    # what the key now tells apart, the records do
    assert plan_study(tiny).inputs(0, 0)["screen"]["contact_line"] == "breakdown"


def test_a_key_changes_with_every_input_of_a_fingertip_with_pores():
    # a fingertip cap (rings) over ridges with sweat pores and no roughness: the pores make the seed an input, the
    # unused power law's keys are not, and the rings are
    scene = load_scene(text=TINY.replace("long_cutoff = 1.5e-4", "long_cutoff = 1.5e-4\nenabled = false")
                       + '[fingerpad]\nmodel = "fingertip"\n[ridges]\npore_density = 1e7\npore_diameter = 6e-5\n',
                       preset="draft")
    shared = _shared_keys_solve_alike(scene)
    assert {"fingerpad.area_prefactor", "fingerpad.area_exponent", "fingerpad.layer_grid", "roughness.hurst",
            "study.seed", "preset.realisations", "preset.pixels_per_cutoff"} <= set(shared)
    assert not {"fingerpad.radius", "ridges.pore_diameter", "ridges.pore_depth", "preset.rings"} & set(shared)


# ---------------------------------------------------------------------------------------------------------
# A measured scan: keyed by its content, stored with the results
# ---------------------------------------------------------------------------------------------------------
SIDE, N = 1.2e-4, 16                                        # a 0.12 mm scan of 16² pixels


def _write_scan(path, rng):
    surfaces.self_affine(surfaces.Grid((N, N), (SIDE, SIDE), periodic=False), hurst=0.8, rms_height=3e-6,
                         short_cutoff=3e-5, rng=rng).save(path)


@pytest.fixture
def measured(tmp_path):
    """A scene file pointing at a saved HeightField (``scans/scan.npz``), its scan drawn with rng 4."""
    (tmp_path / "scans").mkdir()
    _write_scan(tmp_path / "scans" / "scan.npz", 4)
    (tmp_path / "scene.toml").write_text(
        '[ridges]\nenabled = false\n[roughness]\ntopography = "scans/scan.npz"\nboundary = "periodic"\n'
        'detrend = "mean"\n[loads]\nnormal_forces = [0.5, 2.0]\nvoltages = [0.0, 150.0]\n'
        "[ridge_area]\ncoarse_graining = 2e-5\nsensitivity = [2.0]\n")
    return tmp_path / "scene.toml"


def test_load_scene_reads_a_replaced_scan_again(measured):
    first = load_scene(measured, preset="draft")
    before = plan_study(first)
    _write_scan(measured.parent / "scans" / "scan.npz", 5)           # the same path, another surface
    second = load_scene(measured, preset="draft")
    assert second == first                                            # (the scene text is the same)
    replaced = plan_study(second).topography
    expected = surfaces.HeightField.load(measured.parent / "scans" / "scan.npz").detrended("mean").heights
    np.testing.assert_array_equal(replaced.heights, expected)
    assert not np.array_equal(replaced.heights, before.topography.heights)
    assert replaced.metadata["sha256"] != before.topography.metadata["sha256"]
    assert plan_study(second).task(0, 0).key != before.task(0, 0).key


def test_a_replaced_scan_is_solved_again_never_resumed(measured, tmp_path, capsys):
    # the scene file unchanged, the scan replaced under the same path: the command solves every point again (it
    # resumed the old numbers before), says why, and gives a fresh run's numbers
    out = tmp_path / "results"
    first = run_study(load_scene(measured, preset="draft"), out, workers=1)
    assert first.computed == 4 and run_study(load_scene(measured, preset="draft"), out, workers=1).computed == 0
    _write_scan(measured.parent / "scans" / "scan.npz", 5)
    assert main(["run", str(measured), "--preset", "draft", "--out", str(out), "--workers", "1"]) == 0
    printed = capsys.readouterr()
    assert "4 points computed (4 contact solves), 0 resumed" in printed.out
    assert [line for line in printed.err.splitlines() if "warning" in line and "solved again" in line] == [
        f"roughcontact run: warning: {measured.parent.resolve() / 'scans' / 'scan.npz'}: the measured topography is "
        f"not the patch that the results in {out} were solved on ({out / 'patch.npz'}: the scan was replaced or read "
        "differently); its tasks are solved again"]
    fresh, back = run_study(load_scene(measured, preset="draft"), workers=1), open_results(out)
    assert numbers(back) == numbers(fresh) and numbers(back) != numbers(first)
    assert surfaces.HeightField.load(out / "patch.npz") == fresh.plan.topography


def test_results_stand_without_the_scan(measured, tmp_path):
    out = tmp_path / "results"
    result = run_study(load_scene(measured, preset="draft"), out, workers=1)
    stored = surfaces.HeightField.load(out / "patch.npz")                # the patch as solved, with its origin
    assert stored == result.plan.topography and stored.grid.periodic == (True, True)
    assert stored.metadata["sha256"] == result.plan.topography.metadata["sha256"]
    assert stored.metadata["source"] == str((measured.parent / "scans" / "scan.npz").resolve())
    shutil.move(measured.parent / "scans", tmp_path / "moved")
    back = open_results(out)
    assert back.points == result.points and back.plan.grid == result.plan.grid
    assert [task.key for task in back.plan.tasks] == [task.key for task in result.plan.tasks]
    with pytest.raises(ValueError, match=r"scene key roughness.topography: cannot read the topography "
                                         r".*scan.npz: no such file"):
        load_scene(out / "scene.toml")
    (out / "patch.npz").unlink()                            # (a directory of an older version): the scan is needed
    with pytest.raises(ValueError, match=r"cannot read the topography .*scan.npz: no such file"):
        open_results(out)


def test_a_damaged_patch_file_is_written_again(measured, tmp_path):
    out = tmp_path / "results"
    scene = load_scene(measured, preset="draft")
    first = run_study(scene, out, workers=1)
    (out / "patch.npz").write_bytes(b"")                     # (a write cut short): the same patch, no warning
    with warnings.catch_warnings():
        warnings.simplefilter("error", StaleTaskWarning)
        again = run_study(scene, out, workers=1)
    assert again.computed == 0 and again.points == first.points
    assert surfaces.HeightField.load(out / "patch.npz") == first.plan.topography
