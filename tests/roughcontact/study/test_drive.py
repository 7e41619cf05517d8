"""The AC drive in scenes and in the study: the `[screen] frequency` and `sigma_sc` keys, a tiny frequency sweep
against direct `solve_contact` calls under the same interaction, resume with the new keys, the sweep's report,
and a scene without a frequency unchanged."""
import hashlib
import math
from pathlib import Path

import numpy as np
import pytest
import xarray

from roughcontact.cli import main
from roughcontact.electrostatics import DielectricStack, LeakyStack, crossover_frequency, solve_ac_field
from roughcontact.interactions import ElectrostaticInteraction
from roughcontact.io import read_csv
from roughcontact.solvers import solve_contact
from roughcontact.study.apparent import apparent_scale
from roughcontact.study.execution import SceneMismatch
from roughcontact.study.friction import bottom_up_friction
from roughcontact.study.patch import patch_body, patch_surface
from roughcontact.study.plan import plan_study
from roughcontact.study.run import open_results, run_study
from roughcontact.study.scene import load_scene
from study_scenes import TINY

FREQUENCIES = [0.0, 300.0, 3000.0]          # DC, below and above the crossover (about 1 kHz)
SWEEP = TINY.replace("[loads]", f"[screen]\nfrequency = {FREQUENCIES}\nsigma_sc = 3e-4\n[loads]")


@pytest.fixture(scope="module")
def sweep_result():
    """The tiny sweep solved in this process (its scene: ``sweep_result.scene``)."""
    return run_study(load_scene(text=SWEEP, preset="draft"), workers=1)


@pytest.fixture(scope="module")
def sweep(sweep_result):
    return sweep_result.scene


# ---------------------------------------------------------------------------------------------------------
# Scene keys
# ---------------------------------------------------------------------------------------------------------
def test_drive_keys_parse_and_round_trip(sweep):
    screen = sweep.screen
    assert screen.frequency == (0.0, 300.0, 3000.0) and screen.sigma_sc == 3e-4
    assert screen.stack() == DielectricStack(sigma_sc=3e-4)
    law = screen.interaction(100.0, 300.0)
    assert law == ElectrostaticInteraction(DielectricStack(sigma_sc=3e-4), 100.0, field="layered", frequency=300.0)
    assert screen.interaction(0.0, 300.0) is None
    assert load_scene(text=sweep.to_toml()) == sweep
    one = load_scene(text="[screen]\nfrequency = 1000\n")          # a scalar (an integer too) is a one-point sweep
    assert one.screen.frequency == (1000.0,) and one.screen.stack().sigma_sc == DielectricStack().sigma_sc
    assert "frequency = [1000.0]" in one.to_toml() and load_scene(text=one.to_toml()) == one


@pytest.mark.parametrize("text, kind, message", [
    ("frequency = -1.0", ValueError, r"screen.frequency = -1.0 is out of range; valid range \[0, inf\)"),
    ("frequency = inf", ValueError, r"screen.frequency must be finite"),
    ("frequency = [10.0, 10.0]", ValueError, r"screen.frequency = \[10.0, 10.0\] is not strictly increasing"),
    ("frequency = [10.0, -5.0]", ValueError, r"screen.frequency\[1\] = -5.0 is out of range"),
    ("frequency = []", ValueError, r"screen.frequency must be a non-empty, strictly increasing list"),
    ('frequency = "1 kHz"', ValueError, r"screen.frequency must be a real number, got '1 kHz'.*valid: a number in "
                                        r"\[0, inf\) \[Hz\]"),
    ("frequency = true", ValueError, r"screen.frequency must be a real number"),
    ("frequency = 10.0\nsigma_sc = -1e-4", ValueError, r"screen.sigma_sc = -0.0001 is out of range; valid range "
                                                       r"\[0, inf\)"),
    ("sigma_sc = 1e-3", ValueError, r"screen.sigma_sc = 0.001 S/m acts only under a drive, but screen.frequency is "
                                    "not set"),
    ('frequency = 10.0\nfield = "parallel_plate"', ValueError, r'screen.frequency = \[10.0\] Hz needs screen.field '
                                                              r'= "layered"'),
])
def test_bad_drive_keys_are_refused_naming_them(text, kind, message):
    with pytest.raises(kind, match=r"line \d+: scene key screen\.") as error:
        load_scene(text="[screen]\n" + text + "\n")
    assert error.match(message)


LEAK = ("frequency = [10.0, 1000.0]\ngap_conductivity = 1.2e-7\ngap_conductance = 0.01\ngap_cpe = 1e-5\n"
        "gap_cpe_exponent = 0.7\nsurface_conductance = 1e-8\ncontact_transfer = true\n")


def test_leak_keys_parse_and_round_trip():
    """The leak's keys make the screen's stack a LeakyStack, written back only where set; without them the stack is
    the DielectricStack and the scene's text has none of them (its fingerprint above is unchanged)."""
    scene = load_scene(text="[screen]\n" + LEAK)
    stack = scene.screen.stack()
    assert stack == LeakyStack(gap_conductance=0.01, gap_conductivity=1.2e-7, gap_cpe=1e-5, gap_cpe_exponent=0.7,
                               surface_conductance=1e-8, contact_transfer=True)
    assert scene.screen.interaction(100.0, 10.0).stack == stack
    assert load_scene(text=scene.to_toml()) == scene and "contact_transfer = true" in scene.to_toml()
    plain = load_scene(text="[screen]\nfrequency = 10.0\n")
    assert type(plain.screen.stack()) is DielectricStack and "gap_" not in plain.to_toml()


@pytest.mark.parametrize("text, message", [
    ("gap_conductance = 0.061", r"screen.gap_conductance = 0.061 is a leak across the interface, which acts only "
                                r"under a drive, but screen.frequency is not set"),
    ("frequency = 10.0\ngap_conductivity = -1e-7", r"screen.gap_conductivity = -1e-07 is out of range; valid range "
                                                   r"\[0, inf\)"),
    ("frequency = 10.0\ngap_cpe_exponent = 1.5", r"screen.gap_cpe_exponent = 1.5 is out of range; valid range "
                                                 r"\(0, 1\]"),
    ("frequency = 10.0\ncontact_transfer = 1", r"screen.contact_transfer must be true or false"),
    ("frequency = 10.0\nsurface_conductance = 1e-8", r"surface_conductance = 1e-08 S needs contact_transfer = True"),
])
def test_bad_leak_keys_are_refused_naming_them(text, message):
    with pytest.raises(ValueError, match=r"line \d+: scene key screen\.") as error:
        load_scene(text="[screen]\n" + text + "\n")
    assert error.match(message)


def test_a_coupled_preset_with_a_frequency_is_refused(sweep):
    coupled = load_scene(text=SWEEP + 'scales = "coupled"\n', preset="draft")
    with pytest.raises(ValueError, match=r"screen.frequency = \[0.0, 300.0, 3000.0\] Hz with presets.draft.scales "
                                         "= 'coupled'"):
        run_study(coupled, workers=1)


def test_a_scene_without_a_frequency_is_unchanged():
    # The SHA-256 of the scene's TOML text (scene.toml of a results directory) as the version before the drive
    # keys wrote it: neither key appears, so nothing written changes; its tasks' inputs have no drive either.
    def fingerprint(scene):
        return hashlib.sha256(scene.to_toml().encode("utf-8")).hexdigest()
    assert fingerprint(load_scene()) == "3f4d9b6c1811ecd4431dac696c6d9666b12acb6249df48802bc449a0685bebf7"
    tiny = load_scene(text=TINY, preset="draft")
    assert fingerprint(tiny) == "34a8d18b04270371db1ed46932b764aa768bd71cee4a0471cdb8ed56063ed4bd"
    assert tiny.screen.frequency is None and tiny.screen.interaction(150.0).frequency is None
    inputs = plan_study(tiny).inputs(0, 1)
    assert inputs["frequency"] is None and "sigma_sc" not in inputs["screen"]


# ---------------------------------------------------------------------------------------------------------
# The sweep against direct solves
# ---------------------------------------------------------------------------------------------------------
def test_sweep_records_are_the_direct_solves_under_the_same_drive(sweep, sweep_result):
    """Every (load, voltage, frequency) record of realisation 1 against a chain of solve_contact calls with
    ElectrostaticInteraction(stack with sigma_sc, U, frequency=f), warm-started along the loads as the preset
    says; and the drive must matter (the dielectric solve differs), or the study could ignore it unseen."""
    stack = DielectricStack(sigma_sc=3e-4)
    heights, body = patch_surface(sweep, 1), patch_body(sweep)
    pressures = [pressure for _, (pressure,) in apparent_scale(sweep)]     # one ring per load (power law)
    assert sweep_result.frequencies == tuple(FREQUENCIES)
    assert sweep_result.array("equivalent_gap").shape == (2, 2, 3, 2)
    for j, voltage in enumerate(sweep.loads.voltages):
        for k, frequency in enumerate(FREQUENCIES):
            law = None if voltage == 0 else ElectrostaticInteraction(stack, voltage, frequency=frequency)
            previous = None
            for i, pressure in enumerate(pressures):
                direct = solve_contact(heights, body, mean_pressure=pressure, interaction=law, tol=1e-6, x0=previous,
                                       warn=False)
                previous = direct
                point = sweep_result.points[i][j][k]
                assert point.voltage == voltage and direct.converged and point.converged[1]
                area = direct.grid.area
                assert point.equivalent_gap[1] == stack.equivalent_gap(direct.gap)
                assert point.contact_fraction[1] == direct.contact_fraction
                if voltage > 0:
                    # (the record forms F_el/(A U²) U²: round-off apart, the same number)
                    assert point.electrostatic_attraction[1] == pytest.approx(direct.electrostatic_force / area,
                                                                            rel=1e-14)
                    dielectric = solve_contact(heights, body, mean_pressure=pressure,
                                               interaction=ElectrostaticInteraction(stack, voltage), tol=1e-6,
                                               warn=False)
                    # the leak moves voltage onto the gap: F_el differs from the dielectric solve's at every f here
                    assert abs(direct.electrostatic_force / dielectric.electrostatic_force - 1) > 1e-3
                else:
                    # 0 V: the hard wall at every frequency; the field-equivalent gap is that of the drive's field
                    # on the hard-wall gap in the small-voltage limit
                    solution = solve_ac_field(stack, np.asarray(direct.gap), direct.grid.lengths, 1.0,
                                              frequency=frequency)
                    assert point.field_equivalent_gap[1] == pytest.approx(
                        stack.gap_for_attraction(solution.mean_attraction, 1.0), rel=1e-12)   # the same solve
    # at 0 V nothing depends on the frequency but the small-voltage field
    gaps = sweep_result.array("equivalent_gap")[:, 0]
    assert np.all(gaps == gaps[:, :1])
    fields = sweep_result.array("field_equivalent_gap")[:, 0]
    assert np.all(fields[:, 0] < fields[:, 2])                  # DC attracts more: a smaller equivalent gap


def test_at_frequency_is_the_loads_by_voltages_study(sweep_result):
    view = sweep_result.at_frequency(2)
    assert view.frequencies == () and view.array("equivalent_gap").shape == (2, 2, 2)
    assert np.array_equal(view.array("electrostatic_attraction"),
                          sweep_result.array("electrostatic_attraction")[:, :, 2])
    assert np.array_equal(view.ridge_area, sweep_result.ridge_area[:, :, 2])
    mean = sweep_result.summary("ridge_area_fractions")[0]
    assert np.array_equal(mean[:, :, 2], view.summary("ridge_area_fractions")[0], equal_nan=True)
    with pytest.raises(ValueError, match=r"index must be an integer in \[0, 2\], got 3"):
        sweep_result.at_frequency(3)
    # the friction law has no drive frequency: a sweep is refused, one frequency of it is a study like any other
    with pytest.raises(ValueError, match=r"screen.frequency = .*at_frequency"):
        bottom_up_friction(sweep_result)


def test_resume_with_the_drive_keys(sweep, sweep_result, tmp_path):
    first = run_study(sweep, tmp_path, workers=1)
    plan = first.plan
    names = sorted(path.name for path in (tmp_path / "tasks").glob("*.json"))
    assert len(names) == 12 and names == sorted(f"{task.key}.json" for task in plan.tasks)
    # one task per (realisation, voltage, frequency), each keyed by its own frequency and sigma_sc
    assert [task.index for task in plan.tasks[:3]] == [(0, 0, 0), (1, 0, 0), (0, 0, 1)]
    inputs = plan.inputs(1, 1, 2)
    assert inputs["frequency"] == 3000.0 and inputs["screen"]["sigma_sc"] == 3e-4 and inputs["voltage"] == 150.0
    assert first.points == _untimed(sweep_result.points, first.points)
    (tmp_path / "tasks" / f"{plan.task(1, 1, 2).key}.json").unlink()
    resumed = run_study(sweep, tmp_path, workers=1)
    assert resumed.computed == 2 and resumed.solves == 2             # one task: two loads, one solve each
    assert [p.equivalent_gap for row in resumed.points for cell in row for p in cell] == \
        [p.equivalent_gap for row in first.points for cell in row for p in cell]
    assert open_results(tmp_path).points == resumed.points and open_results(tmp_path).frequencies == tuple(FREQUENCIES)
    for changed in (SWEEP.replace("sigma_sc = 3e-4", "sigma_sc = 2e-4"),
                    SWEEP.replace("3000.0]", "3000.0, 10000.0]"), TINY):
        with pytest.raises(SceneMismatch):
            run_study(load_scene(text=changed, preset="draft"), tmp_path, workers=1)


def _untimed(points, like):
    """``points`` with the solve times of ``like`` (the only field that differs between two runs)."""
    import dataclasses
    return tuple(tuple(tuple(dataclasses.replace(p, seconds=q.seconds) for p, q in zip(cell, other))
                       for cell, other in zip(row, other_row)) for row, other_row in zip(points, like))


# ---------------------------------------------------------------------------------------------------------
# The command and the sweep's report
# ---------------------------------------------------------------------------------------------------------
def test_sweep_command_writes_the_frequency_tables_and_report(tmp_path, capsys):
    scene = tmp_path / "sweep.toml"
    scene.write_text(SWEEP)
    out = tmp_path / "results"
    assert main(["run", str(scene), "--preset", "draft", "--out", str(out), "--workers", "1"]) == 0
    assert "12 points computed" in capsys.readouterr().out
    for name in ("report.md", "points.csv", "realisations.csv", "ridge_area_sensitivity.csv", "frequency_sweep.png"):
        assert (out / name).is_file(), name
    assert not (out / "friction.csv").exists() and not (out / "equivalent_gap.png").exists()
    rows = read_csv(out / "points.csv")
    assert len(rows) == 12 and list(rows[0])[:3] == ["normal_force_N", "voltage_V", "frequency_Hz"]
    assert [float(row["frequency_Hz"]) for row in rows[:3]] == FREQUENCIES
    assert len(read_csv(out / "realisations.csv")) == 24 and len(read_csv(out / "ridge_area_sensitivity.csv")) == 24
    report = (out / "report.md").read_text()
    assert "friction step" in report and "σ_sc = 0.0003 S/m" in report
    # the crossover of each load at 150 V, from points.csv's field-equivalent gap at 3 kHz, independently
    stack = DielectricStack(sigma_sc=3e-4)
    for row in rows:
        if float(row["voltage_V"]) == 150.0 and float(row["frequency_Hz"]) == 3000.0:
            rest = float(row["field_equivalent_gap_um"]) * 1e-6 + stack.d_i / stack.eps_i
            expected = stack.sigma_sc / (2 * math.pi * 8.8541878128e-12 * (stack.eps_sc + stack.d_sc / rest))
            assert expected == pytest.approx(crossover_frequency(stack, rest), rel=1e-9)
            assert (f"## F_N = {float(row['normal_force_N']):g} N, U = 150 V RMS: crossover f_c = {expected:.0f} Hz "
                    f"(h_rest = {rest * 1e6:.3f} µm)") in report
    with xarray.open_dataset(out / "results.nc", engine="h5netcdf") as data:
        assert data["equivalent_gap"].dims == ("normal_force", "voltage", "frequency", "realisation")
        assert list(data["frequency"].values) == FREQUENCIES and data["frequency"].attrs["units"] == "Hz"
        assert data["apparent_area"].dims == ("normal_force",)
        assert data.attrs["scene.screen.sigma_sc"] == 3e-4


EXAMPLE = Path(__file__).resolve().parents[3] / "examples" / "ac_sweep.toml"


def test_the_example_sweep_scene_is_the_documented_one():
    scene = load_scene(EXAMPLE)
    assert scene.screen.frequency == (0.0, 10.0, 30.0, 100.0, 300.0, 1000.0, 3000.0, 10000.0)
    assert scene.loads.normal_forces == (1.0,) and scene.loads.voltages == (100.0,)
    assert scene.study.preset == "draft" and scene.preset.grid == 128 and scene.preset.realisations == 3


def test_the_example_sweep_gives_the_documented_table():
    """docs/guide/ac_drive.md, "The drive in a study": F_el [N], the paired ratio and d_eq [µm] at DC, 1 kHz and
    10 kHz to the digits printed there (24 solves on 128², about 2 s)."""
    result = run_study(load_scene(EXAMPLE), workers=1)
    area = result.array("apparent_area")[0, 0, :, None]
    force = area * result.array("electrostatic_attraction")[0, 0]                  # (frequencies, realisations)
    ratio = np.mean(force / force[-1], axis=-1)
    d_eq = np.mean(result.array("equivalent_gap")[0, 0], axis=-1) * 1e6
    for k, (fel, paired, gap) in {0: (0.927, 1.067, 2.416), 5: (0.907, 1.044, 2.420),
                                  7: (0.867, 1.000, 2.440)}.items():
        assert (round(np.mean(force[k]), 3), round(ratio[k], 3), round(d_eq[k], 3)) == (fel, paired, gap)
    assert np.all(np.diff(force, axis=0) <= 0)                # falls with frequency in each realisation
    stack = result.scene.screen.stack()
    rest = np.mean(result.array("field_equivalent_gap")[0, 0, -1]) + stack.d_i / stack.eps_i
    assert round(crossover_frequency(stack, rest)) == 1152
