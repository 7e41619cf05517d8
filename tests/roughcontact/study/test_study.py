"""The fingerpad study on tiny patches: the 0 V chain is the hard-wall chain, the trends with load and voltage,
resume after an interruption, refusal of another scene, and `roughcontact run` end to end."""
import json
import os
import re

import numpy as np
import pytest
import xarray

import roughcontact.study.apparent as apparent
import roughcontact.study.resolved as resolved
from roughcontact.cli import main
from roughcontact.electrostatics import solve_field
from roughcontact.interactions import ElectrostaticInteraction
from roughcontact.io import read_csv
from roughcontact.macro import TabulatedArea
from roughcontact.solvers import solve_contact
from roughcontact.study.apparent import apparent_contact, apparent_scale
from roughcontact.study.execution import DirectoryInUse, ResultsDirectory, SceneMismatch, StaleTaskWarning
from roughcontact.study.friction import bottom_up_friction, friction_realisations
from roughcontact.study.patch import (patch_body, patch_surface, realisation_count, ridge_area_fraction,
                                      ridge_equivalent_gap, ridge_heights)
from roughcontact.study.plan import plan_study
from roughcontact.study.records import confidence_interval
from roughcontact.study.report import _range, positive_interval, report_text
from roughcontact.study.resolved import solve_chain
from roughcontact.study.run import open_results, run_study
from roughcontact.study.scene import Fingerpad, load_scene
from study_scenes import TINY



def test_zero_volt_study_is_the_hard_wall_chain():
    scene = load_scene(text=TINY.replace("voltages = [0.0, 150.0]", "voltages = [0.0]"), preset="draft")
    result = run_study(scene, workers=1)
    stack, body = scene.screen.stack(), patch_body(scene)
    for r in range(2):
        heights, previous = patch_surface(scene, r), None
        for i, force in enumerate(scene.loads.normal_forces):
            area, (pressure,) = apparent_contact(scene.fingerpad, force, 1)
            previous = solve_contact(heights, body, mean_pressure=pressure, tol=1e-6, x0=previous, warn=False)
            assert result.points[i][0].equivalent_gap[r] == stack.equivalent_gap(previous.gap)
            assert result.points[i][0].contact_fraction[r] == previous.contact_fraction
            assert result.points[i][0].electrostatic_attraction[r] == 0.0
    assert "One voltage (0 V) in the scene: its dependence on the voltage is not tested" in report_text(result)
    assert "No solve crossed an instability." in report_text(result)


def test_records_count_the_unstable_steps_of_their_solves(tiny, tiny_result):
    # the 150 V chain solved again by hand: each record's count is the sum over its solves (measured 0-6 at
    # 150 V with air breakdown at the contact lines, where the attraction snaps regions in), and the 0 V hard wall
    # has none
    stack, body = tiny.screen.stack(), patch_body(tiny)
    law = ElectrostaticInteraction(stack, 150.0)
    for r in range(2):
        heights, previous = patch_surface(tiny, r), None
        for i, force in enumerate(tiny.loads.normal_forces):
            _, (pressure,) = apparent_contact(tiny.fingerpad, force, 1)
            previous = solve_contact(heights, body, mean_pressure=pressure, interaction=law, tol=1e-6,
                                     x0=previous, warn=False)
            assert tiny_result.points[i][1].unstable_steps[r] == previous.unstable_steps
            assert tiny_result.points[i][0].unstable_steps[r] == 0
            # F_el of the record against an independent field solve of the same gap (the solver's field is
            # converged to 0.1 x its residual, tol 1e-6: measured agreement 1e-7; a per-pixel F_el is 30 % off)
            point, grid = tiny_result.points[i][1], body.grid
            field = solve_field(stack, previous.gap, grid.lengths, 150.0, tol=1e-10, contact_line=law.contact_line)
            assert point.electrostatic_attraction[r] == pytest.approx(field.mean_attraction, rel=1e-5)
            assert point.pixel_law_attraction[r] == pytest.approx(float(np.mean(stack.attraction(previous.gap, 150.0))),
                                                                rel=1e-12)
    assert sum(tiny_result.points[i][1].unstable_steps[r] for i in range(2) for r in range(2)) > 0
    assert "4 of 8 patch results came from solves that crossed an instability (concave steps, from 150 V on)" \
        in report_text(tiny_result)


def test_field_gaps_and_ratio_carry_the_solved_attraction(tiny, tiny_result):
    stack = tiny.screen.stack()
    for i, row in enumerate(tiny_result.points):
        for point in row:
            for r in range(2):
                d_field, attraction = point.field_equivalent_gap[r], point.electrostatic_attraction[r]
                ratio = point.field_ratio[r]
                if point.voltage > 0:       # Eq. 21 at d_field is the solved attraction, the ratio F_el / F_el,pixel
                    assert stack.attraction(d_field, point.voltage) == pytest.approx(attraction, rel=1e-12)
                    assert ratio == pytest.approx(attraction / point.pixel_law_attraction[r], rel=1e-12)
                if point.voltage == 0:   # the small-voltage limit: the layered field attracts more than Eq. 21 per
                    assert 1.2 < ratio < 2.0 and d_field < point.equivalent_gap[r]    # pixel (measured 1.46-1.48)
                else:                    # 150 V: air breakdown holds its contacts at ε0 E_bd²/2 (measured 0.64-0.66)
                    assert 0.5 < ratio < 0.8 and d_field > point.equivalent_gap[r]
                # the friction law's gap: sigma_el(d_eq,R) A_R = F_el, or 0 where A_R cannot carry F_el
                area = point.ridge_area_fractions[0][r]
                unit = stack.attraction(max(d_field, 0.0), 1.0)
                if point.ridge_equivalent_gap[r] > 0:
                    assert stack.attraction(point.ridge_equivalent_gap[r], 1.0) * area == pytest.approx(unit, rel=1e-10)
                else:
                    assert stack.attraction(0.0, 1.0) * area <= unit
    # 0 V: the field gap is the hard-wall gap's in the small-voltage limit, independent of the voltage
    body = patch_body(tiny)
    heights, pressure = patch_surface(tiny, 1), apparent_contact(tiny.fingerpad, 0.5, 1)[1][0]
    hard_wall = solve_contact(heights, body, mean_pressure=pressure, tol=1e-6, warn=False)
    field = solve_field(stack, hard_wall.gap, body.grid.lengths, 10.0, tol=1e-10)
    assert tiny_result.points[0][0].field_equivalent_gap[1] == pytest.approx(
        stack.gap_for_attraction(field.mean_attraction, 10.0), rel=1e-6)


@pytest.mark.slow           # 16 s on the shared 2-core machine, like the end-to-end run (the CLI, every figure)
def test_parallel_plate_scene_and_a_single_load(tmp_path, capsys):
    # [screen] field = "parallel_plate": the seed's law, so the field gap is Eq. 25's and the ratio 1; one load:
    # the friction law (interpolated in F_N) is not computed and the report says so instead of listing its files
    scene = tmp_path / "one.toml"
    scene.write_text(TINY.replace("normal_forces = [0.5, 2.0]", "normal_forces = [2.0]")
                     + '[screen]\nfield = "parallel_plate"\n')
    out = tmp_path / "results"
    assert main(["run", str(scene), "--preset", "draft", "--out", str(out), "--workers", "1"]) == 0
    rows = read_csv(out / "points.csv")
    for row in rows:
        assert float(row["field_equivalent_gap_um"]) == pytest.approx(float(row["equivalent_gap_um"]), rel=1e-9)
        assert float(row["field_ratio_1"]) == pytest.approx(1.0, rel=1e-9)
        assert float(row["electrostatic_force_N"]) == pytest.approx(float(row["pixel_law_force_N"]), rel=1e-9)
    assert not (out / "friction.csv").exists() and not (out / "friction.png").exists()
    report = (out / "report.md").read_text()
    assert "friction.csv" not in report.split("## ")[1] and "## Friction\n\nNot computed" in report
    assert "`parallel_plate` field" in report
    stored = load_scene(out / "scene.toml", preset="draft")
    assert stored.screen.field == "parallel_plate" and stored.screen.stack() == load_scene().screen.stack()
    one = load_scene(scene, preset="draft")
    with pytest.raises(ValueError, match=r"loads.normal_forces = \[2.0\]: .* needs at least 2 loads"):
        bottom_up_friction(run_study(one, out, workers=1))


def test_trends_with_load_and_voltage(tiny_result):
    d_eq = tiny_result.summary("equivalent_gap")[0]
    area = tiny_result.summary("ridge_area_fractions")[0][:, :, 0]
    assert (np.diff(d_eq, axis=0) < 0).all()            # d_eq falls with load
    assert (np.diff(area, axis=0) > 0).all()            # A_R grows with load
    assert (np.diff(area, axis=1) > 0).all()            # and with voltage at a fixed load
    assert (np.diff(d_eq, axis=1) < 0).all()            # the attraction closes the gap
    assert tiny_result.array("converged").all()
    assert tiny_result.solves == 2 * 2 * 2 and tiny_result.computed == 4
    sigma = tiny_result.summary("electrostatic_attraction")[0]
    assert (sigma[:, 0] == 0).all() and (sigma[:, 1] > 0).all()


def test_identical_sub_problems_are_solved_once():
    smooth = load_scene(text=TINY.replace("long_cutoff = 1.5e-4", "long_cutoff = 1.5e-4\nenabled = false"),
                        preset="draft")
    result = run_study(smooth, workers=1)
    assert result.solves == 4 and result.array("equivalent_gap").shape == (2, 2, 1)


def test_apparent_contact_models():
    power = Fingerpad(model="power_law", area_prefactor=91.9e-6, area_exponent=0.37, radius=1e-2, E_star=47.4e3,
                      layer=False, layer_grid=128)
    area, pressures = apparent_contact(power, 1.0, 3)
    assert area == pytest.approx(91.9e-6) and pressures == (pytest.approx(1.0 / 91.9e-6),)
    tip = Fingerpad(model="fingertip", area_prefactor=91.9e-6, area_exponent=0.37, radius=1e-2, E_star=47.4e3,
                    layer=False, layer_grid=128)
    area, pressures = apparent_contact(tip, 1.0, 4)
    radius = (3 * 1e-2 / (4 * 47.4e3)) ** (1 / 3)
    assert area == pytest.approx(np.pi * radius ** 2)
    assert np.mean(pressures) * area == pytest.approx(1.0)          # equal-area rings carry the load
    assert list(pressures) == sorted(pressures, reverse=True)


def test_layered_fingertip_is_solved_once_for_all_tasks(monkeypatch):
    # fingerpad.layer: the apparent scale is the cap solved on the layered skin (fingertip_contact), computed once
    # per load by run_study, not per (realisation, voltage) task, and every task is solved at its ring pressures
    scene = load_scene(text=TINY + '[fingerpad]\nmodel = "fingertip"\nlayer = true\nlayer_grid = 32\n',
                       preset="draft")
    original, loads = apparent.fingertip_contact, []
    monkeypatch.setattr(apparent, "fingertip_contact",
                        lambda *arguments, **keywords: loads.append(arguments[2]) or original(*arguments, **keywords))
    result = run_study(scene, workers=1)
    assert loads == [0.5, 2.0]
    layered = original(scene.fingerpad, scene.skin, 2.0, 2, grid_points=32)
    point = result.points[1][1]
    assert point.apparent_area == layered.area and point.nominal_pressures == layered.pressures
    records = solve_chain(scene, 1, 1, 1, apparent_scale(scene))
    assert point.equivalent_gap[1] == records[1].equivalent_gap
    hertz = solve_chain(scene, 1, 1, 1, [apparent_contact(scene.fingerpad, force, 2) for force in (0.5, 2.0)])
    assert hertz[1].equivalent_gap != records[1].equivalent_gap            # the tasks used the layered pressures


def test_pores_make_each_realisation_a_patch_of_its_own():
    # ridges with two 60 µm sweat pores per patch and no roughness: the pores sit at random per realisation, so
    # each realisation is a patch of its own (without pores the scene is solved once), the plain ridges less the
    # dimples; the coupled path, which has no pores, refuses them
    pores = "[ridges]\npore_density = 1e7\npore_diameter = 6e-5\n"
    smooth = TINY.replace("long_cutoff = 1.5e-4", "long_cutoff = 1.5e-4\nenabled = false")
    scene = load_scene(text=smooth + pores, preset="draft")
    plain = ridge_heights(load_scene(text=smooth, preset="draft"))
    assert realisation_count(scene) == 2
    patches = [patch_surface(scene, r) for r in range(2)]
    assert not np.array_equal(*patches)
    for patch in patches:
        drop = plain - patch
        drop -= np.median(drop)                    # undo the mean shift by the dimples' volume
        assert drop.max() == pytest.approx(2e-5, rel=1e-9) and np.count_nonzero(drop > 1e-12) < 0.05 * drop.size
    result = run_study(scene, workers=1)
    assert result.array("equivalent_gap").shape == (2, 2, 2)
    with pytest.raises(ValueError, match="pore_density"):
        run_study(load_scene(text=TINY + 'scales = "coupled"\n' + pores, preset="draft"), workers=1)


def test_ridge_equivalent_gap_carries_the_same_attraction_over_the_ridge_area():
    # σ_el(d_eq,R) A_R = σ_el(d_eq) A0 (round-off: 1e-12), d_eq,R = d_eq over the whole area, and 0 where A_R/A0
    # is too small for a positive gap
    stack = load_scene().screen.stack()
    for fraction in (0.3, 0.7, 1.0):
        gap = ridge_equivalent_gap(stack, 2e-6, fraction)
        assert stack.attraction(gap, 200.0) * fraction == pytest.approx(stack.attraction(2e-6, 200.0), rel=1e-12)
    assert ridge_equivalent_gap(stack, 2e-6, 1.0) == pytest.approx(2e-6, rel=1e-12)
    assert ridge_equivalent_gap(stack, 1e-9, 1e-6) == 0.0


def test_ridge_area_fraction_closes_gaps_shorter_than_the_length():
    mask = np.zeros((40, 40), bool)
    mask[:, 2:20] = mask[:, 22:38] = True                            # gaps of 2 px, one across the periodic edge
    assert ridge_area_fraction(mask, 1.0, 0.5) == 34 / 40            # a disc under one pixel: the mask itself
    assert ridge_area_fraction(mask, 1.0, 6.0) == 1.0                # both gaps closed, through the edge too
    mask[:, 22:38] = False
    assert ridge_area_fraction(mask, 1.0, 6.0) == 18 / 40            # a 20 px gap stays open


def test_confidence_interval_leaves_out_nan():
    mean, half = confidence_interval([[1.0, 2.0, 3.0], [1.0, np.nan, 3.0], [np.nan, np.nan, 2.0]])
    assert mean.tolist() == [2.0, 2.0, 2.0]
    assert half[0] == pytest.approx(4.302653 / np.sqrt(3), rel=1e-6)
    assert half[1] == pytest.approx(12.706205, rel=1e-6) and np.isnan(half[2])     # t(1) sqrt(2)/sqrt(2)


def test_failed_warm_start_is_retried_cold_and_failures_leave_the_means(tiny, monkeypatch):
    import dataclasses
    solve = resolved.solve_contact

    def warm_fails(*args, x0=None, **kwargs):
        result = solve(*args, x0=x0, **kwargs)
        unconverged = dataclasses.replace(result, solver=dataclasses.replace(result.solver, converged=False))
        return unconverged if x0 is not None else result

    monkeypatch.setattr(resolved, "solve_contact", warm_fails)
    retried = run_study(tiny, workers=1)
    def voltage_fails(*args, **kwargs):
        result = solve(*args, **kwargs)
        converged = kwargs.get("interaction") is None
        return dataclasses.replace(result, solver=dataclasses.replace(result.solver, converged=converged))

    monkeypatch.setattr(resolved, "solve_contact", voltage_fails)
    failing = run_study(tiny, workers=1)
    monkeypatch.undo()
    cold = [[solve(patch_surface(tiny, r), patch_body(tiny), tol=1e-6, warn=False, interaction=None,
                   mean_pressure=apparent_contact(tiny.fingerpad, force, 1)[1][0]).contact_fraction
             for r in range(2)] for force in tiny.loads.normal_forces]
    assert retried.solves == 8 + 4 and retried.array("converged").all()        # 4 warm starts retried
    assert retried.array("contact_fraction")[:, 0, :].tolist() == cold       # the 0 V points: cold solves
    assert np.isnan(failing.summary("equivalent_gap")[0][:, 1]).all()        # every 150 V solve failed
    assert np.isfinite(failing.summary("equivalent_gap")[0][:, 0]).all()


@pytest.mark.parametrize("failed, named", [({(1, 1)}, "2 N at 150 V"),
                                           ({(0, 0), (0, 1), (1, 0), (1, 1)}, "0.5 N at 0 V, 0.5 N at 150 V")])
def test_a_point_without_a_converged_realisation_is_reported_not_raised(tiny_result, tmp_path, failed, named):
    """Points where no realisation converged (a float32 preset below its round-off floor left every point so):
    the results are written without a numpy warning, those points' means NaN, and report.md names them and says
    why the friction law is not computed; before, friction.csv raised friction_recipe's "ridge_gaps must be
    finite" as a traceback (and report.md numpy's all-NaN max)."""
    import dataclasses
    import warnings
    from roughcontact.io.provenance import Provenance
    from roughcontact.study.report import write_results
    points = tuple(tuple(dataclasses.replace(point, converged=(False, False)) if (i, j) in failed else point
                         for j, point in enumerate(row)) for i, row in enumerate(tiny_result.points))
    result = dataclasses.replace(tiny_result, points=points)
    with pytest.raises(ValueError, match=f"no realisation converged at {named}"):
        bottom_up_friction(result)
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        write_results(result, tmp_path, Provenance.of_command("roughcontact run", [], {}))
    report = (tmp_path / "report.md").read_text()
    assert f"none converged at {named}" in report and f"Not computed: no realisation converged at {named}" in report
    assert not (tmp_path / "friction.csv").exists() and not (tmp_path / "friction.png").exists()
    rows = read_csv(tmp_path / "points.csv")
    assert [row["equivalent_gap_um"] == "nan" for row in rows] == [(i, j) in failed for i in range(2) for j in range(2)]


def test_a_flat_scan_changes_d_eq_by_zero_percent(tmp_path):
    """A constant scan is flat after detrending: d_eq = 0 at both voltages, a change of 0 % (it read "+nan %",
    with numpy's "invalid value encountered in divide" on the console)."""
    import warnings
    from roughcontact.study.patch import PatchScaleWarning
    np.save(tmp_path / "flat.npy", np.full((16, 16), 3.0))
    (tmp_path / "flat.toml").write_text('[loads]\nnormal_forces = [0.5]\nvoltages = [0.0, 150.0]\n[ridges]\n'
                                        'enabled = false\n[roughness]\ntopography = "flat.npy"\nunit = "um"\n'
                                        "pixel_size = 2e-6\n[ridge_area]\ncoarse_graining = 1e-5\n")
    scene = load_scene(tmp_path / "flat.toml", preset="draft")
    with pytest.warns(PatchScaleWarning):
        result = run_study(scene, workers=1)
    assert np.all(result.summary("equivalent_gap")[0] == 0)
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        assert "d_eq changes by +0 % at 0.5 N." in report_text(result)


def test_tabulated_area_and_bottom_up_friction(tiny_result):
    table = TabulatedArea(np.array([1.0, 2.0]), np.array([[0.0, 1.0], [0.0, 2.0]]), np.array([[1.0, 3.0], [2.0, 4.0]]))
    assert table.area(1.0, 0.5) == pytest.approx(2.0) and table.area(1.5, 0.0) == pytest.approx(1.5)
    with pytest.raises(ValueError, match="valid range"):
        table.area(3.0, 0.0)
    model = bottom_up_friction(tiny_result)
    stack = tiny_result.scene.screen.stack()
    state = model.state(2.0, 150.0)
    point = tiny_result.points[1][1]
    # F_el = sigma_el(d_eq,R) A_R0 equals the solved mean attraction over A0
    assert float(stack.attraction(state.gap, 150.0) * state.initial_area) == pytest.approx(
        np.mean(point.electrostatic_attraction) * point.apparent_area, rel=0.05)
    assert model.state(2.0, 0.0).friction_coefficient == pytest.approx(0.26)


def test_friction_per_realisation(tiny_result):
    # the recipe fed one realisation's tables carries that realisation's solved F_el (sigma_el(d_eq,R) A_R0 =
    # its sigma_el A0, to the 5 % of the A_R interpolation in w); the spread over realisations is the interval
    stack = tiny_result.scene.screen.stack()
    point = tiny_result.points[1][1]
    samples = friction_realisations(tiny_result)
    for r in range(2):
        state = bottom_up_friction(tiny_result, realisation=r).state(2.0, 150.0)
        assert float(stack.attraction(state.gap, 150.0) * state.initial_area) == pytest.approx(
            point.electrostatic_attraction[r] * point.apparent_area, rel=0.05)
        assert samples["friction_coefficient"][1, 1, r] == state.friction_coefficient
        assert samples["tangential_force"][1, 1, r] == state.tangential_force
    assert np.all(samples["friction_coefficient"][:, 0] == 0.26)            # 0 V: mu0 in every realisation
    mean, half = confidence_interval(samples["friction_coefficient"])
    assert half[0, 1] > 0 and np.all(half[:, 0] == 0)
    with pytest.raises(ValueError, match=r"realisation = 2; valid: an integer in \[0, 1\]"):
        bottom_up_friction(tiny_result, realisation=2)


def test_resume_after_interruption_recomputes_nothing_done(tiny, tmp_path, monkeypatch):
    solve = resolved.solve_contact
    calls = []

    def interrupted(*args, **kwargs):
        if len(calls) == 5:
            raise KeyboardInterrupt
        calls.append(1)
        return solve(*args, **kwargs)

    monkeypatch.setattr(resolved, "solve_contact", interrupted)
    with pytest.raises(KeyboardInterrupt):
        run_study(tiny, tmp_path / "run", workers=1)
    done = sorted(path.name for path in (tmp_path / "run" / "tasks").glob("*.json"))
    # 2 tasks of 2 loads = 4 solves, the highest voltage's first (the longest, so that a pool's workers end together)
    plan = plan_study(tiny)
    assert done == sorted(f"{plan.task(r, 1).key}.json" for r in range(2))
    monkeypatch.setattr(resolved, "solve_contact", solve)
    resumed = run_study(tiny, tmp_path / "run", workers=1)
    assert resumed.computed == 2 and resumed.solves == 4
    again = run_study(tiny, tmp_path / "run", workers=1)
    assert again.computed == 0 and again.solves == 0 and again.points == resumed.points
    # a task file written with other record fields (another version's) is named and solved again, not misread
    stale = tmp_path / "run" / "tasks" / f"{plan.task(0, 1).key}.json"
    stored = json.loads(stale.read_text())
    stored["records"] = [{key: value for key, value in record.items() if key != "unstable_steps"}
                         for record in stored["records"]]
    stale.write_text(json.dumps(stored))
    with pytest.warns(StaleTaskWarning, match=rf"{stale.name}: record 1 \(F_N = 0.5 N\) lacks the fields of a "
                                              "PatchRecord"):
        refreshed = run_study(tiny, tmp_path / "run", workers=1)
    assert refreshed.computed == 2 and refreshed.solves == 2            # its two loads' points, one solve each
    for row, resumed_row in zip(refreshed.points, resumed.points):
        assert [point.equivalent_gap for point in row] == [point.equivalent_gap for point in resumed_row]
        assert [point.unstable_steps for point in row] == [point.unstable_steps for point in resumed_row]


def test_another_scene_and_a_running_study_are_refused(tiny, tmp_path):
    plan = plan_study(tiny)
    ResultsDirectory(tmp_path, plan).release()
    other = load_scene(text=TINY.replace("grid = 32", "grid = 64"), preset="draft")
    with pytest.raises(SceneMismatch, match=r"presets.draft.grid = 32 -> 64"):
        ResultsDirectory(tmp_path, plan_study(other))
    fcntl = pytest.importorskip("fcntl", reason="the lock test holds the lock with flock (POSIX)")
    with open(tmp_path / "run.lock", "w") as held:                     # a running process holds the directory
        fcntl.flock(held, fcntl.LOCK_EX)
        held.write("4242")
        held.flush()
        with pytest.raises(DirectoryInUse, match=f"another roughcontact run \\(process 4242 holds "
                                                 f"{re.escape(str(tmp_path / 'run.lock'))}\\)"):
            ResultsDirectory(tmp_path, plan)
    (tmp_path / "run.lock").write_text("1")          # a killed run's lock, its process id reused: taken over
    held = ResultsDirectory(tmp_path, plan)                          # the same scene resumes
    assert (tmp_path / "run.lock").read_text() == str(os.getpid())
    with pytest.raises(DirectoryInUse, match=f"process {os.getpid()} holds"):
        ResultsDirectory(tmp_path, plan)                             # held by this process: refused as well
    held.release()
    assert not (tmp_path / "run.lock").exists()
    ResultsDirectory(tmp_path, plan).release()                       # free again


@pytest.mark.parametrize("call, error, message", [
    (lambda tiny, path: run_study({"loads": {}}), TypeError, "scene must be a Scene .*load_scene.*got dict"),
    (lambda tiny, path: run_study(str(path)), TypeError, "scene must be a Scene .*got str"),
    (lambda tiny, path: run_study(tiny, progress="yes"), TypeError, "progress must be True or False, got 'yes'"),
    (lambda tiny, path: run_study(tiny, path / "file.txt"), ValueError, "file.txt is a file, not a directory"),
    (lambda tiny, path: run_study(tiny, path / "missing" / "out"), ValueError, "missing, does not exist"),
    (lambda tiny, path: run_study(tiny, ""), ValueError, "the output path is empty"),
])
def test_run_study_refuses_bad_arguments_naming_them(tiny, tmp_path, call, error, message):
    (tmp_path / "file.txt").write_text("not a directory")
    with pytest.raises(error, match=message):
        call(tiny, tmp_path)
    assert sorted(path.name for path in tmp_path.iterdir()) == ["file.txt"]      # nothing written


def test_study_fields_are_checked_by_name(tiny_result):
    with pytest.raises(ValueError, match="name = 'bogus' is not a field of the study's points; valid: normal_force"):
        tiny_result.array("bogus")
    for name in ("bogus", "seconds", "nominal_pressures"):        # (per point or per ring, not per realisation)
        with pytest.raises(ValueError, match=f"name = '{name}' is not a field with one value per realisation; "
                                             "valid: equivalent_gap, .*ridge_area_fractions"):
            tiny_result.summary(name)
    assert tiny_result.array("seconds").shape == (2, 2)


def test_run_command_end_to_end(tmp_path, capsys):
    scene = tmp_path / "tiny.toml"
    scene.write_text(TINY)
    out = tmp_path / "results"
    assert main(["run", str(scene), "--preset", "draft", "--out", str(out), "--workers", "1"]) == 0
    printed = capsys.readouterr().out
    assert "4 points computed" in printed
    seconds = re.search(r"; (\d+) s\n", printed).group(1)
    assert f"Run time {seconds} s, tables and figures included" in (out / "report.md").read_text()
    for name in ("report.md", "points.csv", "realisations.csv", "ridge_area_sensitivity.csv", "friction.csv",
                 "equivalent_gap.png", "voltage_dependence.png", "field_ratio.png", "friction.png", "scene.toml"):
        assert (out / name).is_file(), name
    rows = read_csv(out / "points.csv")
    assert len(rows) == 4 and float(rows[0]["equivalent_gap_um"]) > 0
    report = (out / "report.md").read_text()
    assert "Where the equivalent-gap assumption holds and where it fails" in report
    assert "## How wrong is the per-pixel field assumption" in report and "`layered` field" in report
    with xarray.open_dataset(out / "results.nc", engine="h5netcdf") as data:
        assert data["equivalent_gap"].attrs["units"] == "m" and data.attrs["preset"] == "draft"
        assert data.attrs["scene.presets.draft.grid"] == 32 and "roughcontact_version" in data.attrs
        assert data["equivalent_gap"].shape == (2, 2, 2) and data.attrs["field"] == "layered"
        assert data["bottom_up_friction_coefficient_ci95"].shape == (2, 2)
        for name, unit in (("field_equivalent_gap", "m"), ("pixel_law_attraction", "Pa"), ("field_ratio", "1")):
            assert data[name].attrs["units"] == unit and data[name].shape == (2, 2, 2)
    # the finished directory gives the run's friction model back without solving: friction.csv's mu and F_T
    # (written with 17 significant digits) are the recipe's on the study read back
    back = open_results(out)
    assert (back.computed, back.solves) == (0, 0)
    model = bottom_up_friction(back)
    for row in read_csv(out / "friction.csv"):
        state = model.state(float(row["normal_force_N"]), float(row["voltage_V"]))
        assert float(row["bottom_up_friction_coefficient"]) == pytest.approx(float(state.friction_coefficient), rel=1e-12)
        assert float(row["bottom_up_tangential_force_N"]) == pytest.approx(float(state.tangential_force), rel=1e-12)
    # their intervals: the study's 95 % Student-t half-width of the recipe evaluated per realisation
    half = confidence_interval(friction_realisations(back)["friction_coefficient"])[1].ravel()
    assert [float(row["bottom_up_friction_coefficient_ci95"]) for row in read_csv(out / "friction.csv")] == \
        pytest.approx(half, rel=1e-12, abs=1e-15)
    assert half[1] > 0                                     # 0.5 N, 150 V: the realisations differ
    assert main(["run", str(scene), "--preset", "draft", "--out", str(out)]) == 0
    assert "0 points computed" in capsys.readouterr().out
    key = plan_study(load_scene(scene, preset="draft")).task(1, 1).key
    (out / "tasks" / f"{key}.json").unlink()
    with pytest.raises(ValueError, match=rf"is not finished: 1 of 4 task files missing .*\(realisation 1 at 150 V: "
                                         rf"{key}.json\)"):
        open_results(out)
    with pytest.raises(ValueError, match="holds no scene.toml"):
        open_results(tmp_path)
    assert main(["run", str(scene), "--preset", "standard", "--out", str(out)]) == 2
    assert "holds the results of another scene" in capsys.readouterr().err
    scene.write_text("[ridges]\nperod = 1\n")
    assert main(["run", str(scene), "--out", str(tmp_path / "other")]) == 2
    assert "line 2: scene key ridges.perod" in capsys.readouterr().err


@pytest.mark.parametrize("change", [
    ("voltages = [0.0, 150.0]", "voltages = [0.0, 2000.0]"),         # far beyond the seed's range: full contact
    ("voltages = [0.0, 150.0]", "voltages = [0.0]"),                 # no electrostatics at all
    ("[roughness]", "[roughness]\nrms_height = 3e-5"),                # very rough skin
    ("[roughness]", "[roughness]\nrms_height = 1e-9"),                # very smooth skin
])
def test_extreme_scenes_run_to_finite_results(change):
    scene = load_scene(text=TINY.replace(*change), preset="draft")
    result = run_study(scene, workers=1)
    for name in ("equivalent_gap", "contact_fraction"):
        values = result.array(name)
        assert np.isfinite(values).all() and (values >= 0).all()
    fraction = result.array("contact_fraction")
    assert (fraction <= 1).all()
    if "2000.0" in change[1]:
        # 2 kV: air breakdown saturates the attraction at ε0 E_bd²/2 (0.54 MPa), which closes the patches to 62-68 %
        # (without it they closed completely)
        assert np.all((fraction[:, -1] > 0.5) & (fraction[:, -1] < 1.0))


def test_zero_load_scene_is_refused_naming_the_key():
    with pytest.raises(ValueError, match="loads.normal_forces"):
        load_scene(text=TINY.replace("normal_forces = [0.5, 2.0]", "normal_forces = [0.0, 2.0]"), preset="draft")


def test_the_preset_chooses_cold_starts_and_the_dtype():
    cold = load_scene(text=TINY + "warm_start = false\ndtype = \"float32\"\n", preset="draft")   # [presets.draft]
    assert patch_body(cold).dtype == np.float32
    records = solve_chain(cold, 0, 0, 1)
    body = patch_body(cold)
    for record, force in zip(records, cold.loads.normal_forces):       # each load solved from the solver's start
        result = solve_contact(patch_surface(cold, 0), body, tol=1e-6, warn=False,
                               mean_pressure=apparent_contact(cold.fingerpad, force, 1)[1][0])
        assert record.solves == 1 and record.iterations == result.iterations
        assert record.contact_fraction == result.contact_fraction


def test_positive_interval_is_the_log_scale_student_t_interval():
    # two realisations 1 and 4: ln x has mean ln 2 and standard deviation ln 4/sqrt 2, t(1 dof, 97.5 %) = 12.7062;
    # the interval exp(ln 2 -+ t ln 4/2) stays above 0 where the plain one (2.5 -+ 19.06) does not
    low, high = positive_interval([[1.0, 4.0]])
    t = 12.706204736174707
    assert low[0] == pytest.approx(2 * np.exp(-t * np.log(4) / 2), rel=1e-12) and low[0] > 0
    assert high[0] == pytest.approx(2 * np.exp(t * np.log(4) / 2), rel=1e-12)
    mean, half = confidence_interval([[1.0, 4.0]])
    assert mean[0] - half[0] < 0                            # what the figures drew before
    # a zero sample (d_eq,R clipped, full contact): the Student-t interval clipped at 0
    low, high = positive_interval([[0.0, 2.0]])
    assert low[0] == 0 and high[0] == pytest.approx(1 + t, rel=1e-12)
    assert np.isnan(positive_interval([[3.0]])[0][0])       # one realisation: no interval
    # a fraction (bounded by 1), 0.2 and 0.6: the interval of the log-odds ln 0.25 and ln 1.5, inside (0, 1)
    low, high = positive_interval([[0.2, 0.6]], upper=1.0)
    centre, spread = np.log(np.sqrt(0.25 * 1.5)), t * np.log(1.5 / 0.25) / 2
    assert low[0] == pytest.approx(1 / (1 + np.exp(spread - centre)), rel=1e-12)
    assert high[0] == pytest.approx(1 / (1 + np.exp(-centre - spread)), rel=1e-12) and high[0] < 1
    assert positive_interval([[0.2, 0.6]])[1][0] > 1        # (the log scale alone would pass 100 %)


def test_report_sentences_do_not_degenerate(tiny_result):
    assert _range(np.array([0.3712, 0.3749]), ".2f") == "0.37" and _range(np.array([0.2, 0.5]), ".1f") == "0.2 to 0.5"
    report = report_text(tiny_result)
    assert "at no voltage" not in report and " 0.37 to 0.37" not in report
    assert ("at every voltage above 0 V it is off by more than 10 % at some load" in report
            or "it stays within 10 % at every load for 150 V" in report)
    assert "[95% confidence interval over N = 2 realisations, Student-t on the log scale" in report
    assert "## Ridge contact fraction A_R/A0 [%]" in report and "## Real contact fraction [%]" in report
