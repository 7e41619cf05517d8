"""Parameter studies of a scene ([vary]): the table is read and checked key by key, each variant is the scene
with its values substituted and gives the numbers of that scene studied alone, the variants' tasks run on one
executor through one task store (a task that variants share is solved once, an interrupted study resumes, a
cluster gives the local numbers, a replaced scan is solved again), and the sensitivity measures match analytic
references and rank the inputs as single studies do."""
import dataclasses
import re
import shutil
import sys

import numpy as np
import pytest
import xarray

import roughcontact.study
import surfaces
from roughcontact.cli import main
from roughcontact.study.execution import TaskStore
from roughcontact.study.run import open_results as open_study_results, run_study
from roughcontact.study.scene import load_scene
from roughcontact.study.sensitivity import analyse, one_at_a_time_indices
from roughcontact.study.variant_run import VariantStudyResult, open_results, run_variants
from roughcontact.study.variants import (Input, Variation, literature_ranges, load_variant_study, substitute,
                                         unit_sample, variable_keys)
from study_scenes import TINY

#: The tiny scene with one realisation (its roughness is still random: seed 0).
BASE = TINY.replace("realisations = 2", "realisations = 1")
#: Two inputs at two levels each, one at a time: 5 variants.
VARIED = BASE + """
[vary]
"skin.layer_E_star" = [3e7, 1e8]
"screen.eps_sc" = { low = 1e3, high = 1e4, scale = "log" }
"""


def numbers(result):
    """Every number of a study but the solve times."""
    return [[dataclasses.replace(point, seconds=0.0) for point in row] for row in result.points]


@pytest.fixture(scope="module")
def varied(tmp_path_factory):
    """The one-at-a-time study of VARIED, run in this process into a results directory."""
    directory = tmp_path_factory.mktemp("varied")
    study = load_variant_study(text=VARIED, preset="draft")
    return study, directory, run_variants(study, directory / "out", workers=1)


def test_the_scene_command_checks_every_variant_as_run_does(tmp_path, capsys):
    # a variant whose patch is refused (its long cut-off beyond the patch side of 0.45 mm): `roughcontact scene`
    # refuses the study in one line naming the variant, as `roughcontact run` does before any solve
    scene = tmp_path / "vary.toml"
    scene.write_text(BASE + '\n[vary]\n"roughness.long_cutoff" = [1e-4, 1e-3]\n')
    for command in (["scene", str(scene)], ["run", str(scene), "--out", str(tmp_path / "out")]):
        assert main(command) == 2
        error = capsys.readouterr().err
        assert error.count("\n") == 1 and ": error: variant 2 (roughness.long_cutoff = 0.001): roughness.long_cutoff " \
            "= 0.001 m exceeds the patch side 0.00045 m" in error


# ---------------------------------------------------------------------------------------------------------
# The [vary] table
# ---------------------------------------------------------------------------------------------------------
def test_the_table_makes_the_variants_and_reads_back_equal():
    study = load_variant_study(text=VARIED + '"ridges.period" = "literature"\n', preset="draft")
    assert [variant.label for variant in study.variants] == [
        "baseline", "skin.layer_E_star = 3e+07", "skin.layer_E_star = 1e+08", "screen.eps_sc = 1000",
        "screen.eps_sc = 10000", "ridges.period = 0.00043", "ridges.period = 0.00048"]
    assert study.variants[0].scene == study.base and study.variants[0].values == (1e7, 3000.0, 4.5e-4)
    assert study.variants[4].values == (1e7, 1e4, 4.5e-4) and study.variants[4].scene.screen.eps_sc == 1e4
    assert study.variants[5].scene.ridges.period == 4.3e-4
    assert study.inputs[2].source.startswith("adult mean ridge breadth") and study.inputs[2].source.endswith(
        "[literature]")
    again = load_variant_study(text=study.to_toml())          # every value explicit, the literature range too
    assert again == study and [v.scene for v in again.variants] == [v.scene for v in study.variants]
    # a dotted key written unquoted is the same input
    assert load_variant_study(text=VARIED.replace('"skin.layer_E_star"', "skin.layer_E_star"),
                              preset="draft") == load_variant_study(text=VARIED, preset="draft")
    with pytest.raises(ValueError, match=r"scene, line \d+: scene key vary: a \[vary\] table makes a parameter study"):
        load_scene(text=VARIED)


def test_the_variable_inputs_are_the_physical_numbers():
    keys = variable_keys()
    assert {"skin.layer_E_star", "skin.layer_thickness", "skin.E_star", "roughness.rms_height", "roughness.hurst",
            "roughness.long_cutoff", "roughness.short_cutoff", "ridges.period", "ridges.height", "screen.eps_sc",
            "screen.d_sc", "screen.sigma_sc", "screen.gap_conductance", "screen.gap_conductivity",
            "screen.frequency", "roughness.topography"} <= set(keys)
    assert not {key for key in keys if key.split(".")[0] in ("loads", "ridge_area", "study", "presets")}
    assert "fingerpad.layer_grid" not in keys and "screen.field" not in keys


@pytest.mark.parametrize("table, line, message", [
    ('"skin.layer_E_star" = [0.0, 1e9]', 16, r'\[vary\] "skin.layer_E_star" = \[0.0, 1000000000.0\]: '
     r"skin.layer_E_star = 0.0 is out of range; valid range \(0, inf\)"),
    ('"loads.voltages" = [1.0]', 16, r"the loads and voltages are the study's axes"),
    ('"skin.modulus" = [1.0]', 16, r'"skin.modulus" = \[1.0\]: unknown input; valid: the inputs fingerpad\.'),
    ('"presets.draft.grid" = [64]', 16, r"not a physical input"),
    ('"skin.E_star" = 2e5', 16, r'not a list, a range or "literature"; valid: a list of values'),
    ('"skin.E_star" = [1e5, 1e5]', 16, r"the list is empty or repeats a value"),
    ('"skin.E_star" = { low = 1e6, high = 1e5 }', 16, r"low = 1000000.0 must be below high = 100000.0"),
    ('"skin.E_star" = { low = 1e5, high = 1e6, scale = "ln" }', 16, r"scale = 'ln' is not \"linear\" or \"log\""),
    ('"skin.E_star" = { low = 1e5, top = 1e6 }', 16, r"unknown range key 'top'"),
    ('"skin.E_star" = { low = -1.0, high = 1e6, scale = "log" }', 16, r"skin.E_star = -1.0 is out of range"),
    ('"ridges.width_ratio" = "literature"', 16, r"no published range is known for this input; valid: a list"),
    ('"screen.sigma_sc" = "literature"', 16, r'"screen.sigma_sc" = \'literature\': screen.sigma_sc = 1e-05 S/m '
     r"acts only under a drive"),
    ('"roughness.short_cutoff" = [2e-4]', 16, r"must be below roughness.long_cutoff"),
    ('"screen.frequency" = [[10.0, 20.0]]', 16, r"screen.frequency of a variant is one frequency"),
    ('"roughness.topography" = { low = 1.0, high = 2.0 }', 16, r"not a list; valid: a list of files"),
    ('"roughness.topography" = ["scan.npz"]', 16, r"its ridges included, but ridges.enabled = true"),
    ('design = "latin"\n"skin.E_star" = [2e5]', 16, r'"design" = \'latin\': unknown design; valid: "one-at-a-time"'),
    ('samples = 4\n"skin.E_star" = [2e5]', 16, r"a one-at-a-time design has no sampler"),
    ('design = "sobol"\nsamples = 6\n"skin.E_star" = [2e5, 3e5]', 17, r"Sobol' points balance at powers of 2"),
    ('design = "morris"\n"skin.E_star" = [2e5, 3e5]', 15, r"a morris design needs samples"),
    ('design = "morris"\nsamples = 2\nlevels = 3\n"skin.E_star" = [2e5]', 18, r"an even number of levels"),
    ('point = [1.0, 150.0]\n"skin.E_star" = [2e5]', 16, r"not a load and a voltage of the scene; valid: \[F_N, U\] "
     r"with F_N one of \[0.5, 2.0\] N"),
    ('colour = 1\n"skin.E_star" = [2e5]', 16, r'"colour" = 1: unknown key; valid: the settings design'),
    ("", 15, r"no input varies"),
], ids=lambda value: value if isinstance(value, str) and len(value) < 40 else None)
def test_every_key_and_value_is_checked_with_its_line(table, line, message):
    text = BASE + "\n[vary]\n" + table + "\n"
    assert text.splitlines()[14] == "[vary]"
    with pytest.raises(ValueError, match=f"^scene, line {line}: .*" + message):
        load_variant_study(text=text, preset="draft")


def test_a_combination_that_breaks_a_relation_is_named():
    # each cut-off alone is valid; the global design's combinations put the short one above the long one
    text = BASE + ('\n[vary]\ndesign = "sobol"\nsamples = 4\n"roughness.short_cutoff" = { low = 1e-5, high = 1.4e-4 }'
                   '\n"roughness.long_cutoff" = { low = 2e-5, high = 1.5e-4 }\n')
    pytest.importorskip("SALib", reason="the Sobol' design samples with SALib (roughcontact[sensitivity])")
    with pytest.raises(ValueError, match=r"scene, line 15: \[vary\]: variant \d+ \(sample \d+; roughness.short_cutoff "
                                         r"= .*\): roughness.short_cutoff = .* must be below roughness.long_cutoff"):
        load_variant_study(text=text, preset="draft")


def test_the_literature_ranges_are_valid_values_of_the_default_scene():
    ranges = literature_ranges()
    assert {"skin.layer_E_star", "skin.E_star", "screen.d_sc", "screen.eps_sc", "screen.sigma_sc",
            "roughness.hurst", "roughness.rms_height"} <= set(ranges)
    driven = load_scene(text="[screen]\nfrequency = 1000.0\n")
    for name, known in ranges.items():
        assert name in variable_keys() and known.low < known.high and known.scale in ("linear", "log"), name
        assert known.tag in ("literature", "recalled", "estimate") and known.source and known.unit, name
        for value in (known.low, known.high):
            assert substitute(driven, {name: value}).flat()[name] == value, name
    # the table of docs/references.md, section 12
    documented = {"skin.layer_E_star": (1e7, 1e9, "log"), "skin.layer_thickness": (1e-5, 3e-4, "log"),
                  "skin.E_star": (5e4, 2e6, "log"), "skin.poisson": (0.48, 0.5, "linear"),
                  "screen.d_sc": (2e-4, 5e-4, "linear"), "screen.eps_sc": (1e3, 1e4, "log"),
                  "screen.sigma_sc": (1e-5, 1e-3, "log"), "roughness.hurst": (0.7, 0.9, "linear"),
                  "roughness.rms_height": (1e-6, 1e-5, "log"), "ridges.period": (4.3e-4, 4.8e-4, "linear"),
                  "ridges.height": (5e-5, 1e-4, "linear")}
    assert {name: (known.low, known.high, known.scale) for name, known in ranges.items()} == documented


def test_an_input_maps_the_unit_interval_onto_its_values():
    log = Input("skin.E_star", low=1e4, high=1e6, scale="log")
    assert (log.at(0.0), log.at(1.0)) == (1e4, 1e6) and log.at(0.5) == pytest.approx(1e5, rel=1e-14)
    linear = Input("skin.poisson", low=0.4, high=0.5)
    assert linear.at(0.25) == pytest.approx(0.425, rel=1e-15)
    listed = Input("screen.eps_sc", values=(1e3, 3e3, 1e4))
    assert [listed.at(u) for u in (0.0, 0.33, 0.34, 0.99, 1.0)] == [1e3, 1e3, 3e3, 1e4, 1e4]


# ---------------------------------------------------------------------------------------------------------
# Running: variants are single studies, their shared tasks solved once
# ---------------------------------------------------------------------------------------------------------
def _alone(text, name, value):
    """The scene of ``text`` with ``name`` set to ``value`` by editing the TOML (not by the study's
    substitution), at the draft preset."""
    section, key = name.split(".")
    return load_scene(text=text + f"[{section}]\n{key} = {value!r}\n" if f"[{section}]" not in text else
                      text.replace(f"[{section}]\n", f"[{section}]\n{key} = {value!r}\n", 1), preset="draft")


def test_each_variant_gives_the_numbers_of_its_scene_studied_alone(varied):
    study, _, result = varied
    assert isinstance(result, VariantStudyResult) and result.design == "one-at-a-time"
    assert result.variants == study.variants and len(result.results) == 5
    singles = [run_study(load_scene(text=BASE, preset="draft"), workers=1)]
    for name, levels in (("skin.layer_E_star", (3e7, 1e8)), ("screen.eps_sc", (1e3, 1e4))):
        singles += [run_study(_alone(BASE, name, level), workers=1) for level in levels]
    for variant, single, alone in zip(result.variants, result.results, singles):
        assert numbers(single) == numbers(alone), variant.label
    # cost: 2k + 1 single studies of 2 tasks (1 realisation x 2 voltages), 2 loads each
    assert result.tasks == result.computed == 5 * 2 and result.solves == 5 * 2 * 2
    assert result.solves == sum(single.solves for single in singles)


def test_the_sensitivity_ranks_the_inputs_as_single_studies_do(varied):
    study, _, result = varied
    singles = {"baseline": run_study(load_scene(text=BASE, preset="draft"), workers=1)}
    for name, levels in (("skin.layer_E_star", (3e7, 1e8)), ("screen.eps_sc", (1e3, 1e4))):
        singles[name] = [run_study(_alone(BASE, name, level), workers=1) for level in levels]
    base_force = singles["baseline"].summary("electrostatic_attraction")[0] * singles["baseline"].array("apparent_area")
    swings = {}
    for name in ("skin.layer_E_star", "screen.eps_sc"):
        forces = [base_force] + [s.summary("electrostatic_attraction")[0] * s.array("apparent_area")
                                 for s in singles[name]]
        swings[name] = (np.max(forces, axis=0) - np.min(forces, axis=0))[0, 1] / base_force[0, 1]
    expected = tuple(sorted(swings, key=lambda name: -swings[name]))
    assert result.sensitivity.ranking("electrostatic_force", 0.5, 150.0) == expected == ("skin.layer_E_star",
                                                                                          "screen.eps_sc")
    swing = result.sensitivity.measure("swing", "electrostatic_force", 0.5, 150.0)
    np.testing.assert_allclose(swing, [swings[name] for name in study.variation.names], rtol=1e-12)
    # the stiffer layer lowers the attraction (fewer, smaller contacts): the tornado's sign
    assert result.sensitivity.measure("high", "electrostatic_force", 0.5, 150.0)[0] < 0
    assert np.all(np.isnan(result.sensitivity.measure("swing", "electrostatic_force", 0.5, 0.0)))   # F_el = 0


def test_a_variant_equal_to_another_solves_nothing_new(varied, tmp_path):
    _, directory, result = varied
    # the baseline's own value in the list: that variant is the baseline, its tasks are the baseline's
    study = load_variant_study(text=BASE + '[vary]\n"skin.layer_E_star" = [1e7, 3e7]\n', preset="draft")
    assert study.variants[1].scene == study.variants[0].scene
    alone = run_variants(study, workers=1)
    assert alone.tasks == 2 * 2 and alone.solves == 2 * 2 * 2          # 3 variants, 2 distinct of them
    assert numbers(alone.results[1]) == numbers(alone.results[0])
    # another study whose variants all are the first study's: nothing to solve through the shared task store
    again = run_variants(study, tmp_path / "b", workers=1, tasks=directory / "out" / "tasks")
    assert (again.computed, again.solves) == (0, 0)
    assert numbers(again.results[2]) == numbers(result.results[1])


def test_an_interrupted_study_resumes_with_the_missing_tasks(varied, tmp_path, monkeypatch):
    study, _, result = varied
    save = TaskStore.save

    def interrupted(self, *args):
        save(self, *args)
        raise KeyboardInterrupt                             # Ctrl-C once the first task is stored

    monkeypatch.setattr(TaskStore, "save", interrupted)
    with pytest.raises(KeyboardInterrupt):
        run_variants(study, tmp_path, workers=1)
    monkeypatch.undo()
    assert len(list((tmp_path / "tasks").glob("*.json"))) == 1 and not (tmp_path / "run.lock").exists()
    resumed = run_variants(study, tmp_path, workers=1)
    assert resumed.computed == result.tasks - 1 and resumed.solves == result.solves - 2
    assert [numbers(r) for r in resumed.results] == [numbers(r) for r in result.results]


def test_a_cluster_gives_the_local_numbers(varied):
    distributed = pytest.importorskip("distributed")
    study, _, result = varied
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as local:
        on_cluster = run_variants(study, dask=local.scheduler_address)
    assert [numbers(r) for r in on_cluster.results] == [numbers(r) for r in result.results]
    for name, values in result.sensitivity.measures.items():
        np.testing.assert_array_equal(on_cluster.sensitivity.measures[name], values)


# ---------------------------------------------------------------------------------------------------------
# The command and the results directory
# ---------------------------------------------------------------------------------------------------------
def test_the_command_runs_resumes_and_reopens_a_parameter_study(varied, tmp_path, capsys):
    _, directory, result = varied
    scene = tmp_path / "vary.toml"
    scene.write_text(VARIED)
    command = ["run", str(scene), "--preset", "draft", "--out", str(tmp_path / "out"), "--workers", "1",
               "--tasks", str(directory / "out" / "tasks")]
    assert main(command) == 0
    assert "5 variants (one-at-a-time): 0 of 10 distinct tasks solved (0 contact solves), 10 read back" in \
        capsys.readouterr().out
    opened = open_results(tmp_path / "out", tasks=directory / "out" / "tasks")
    assert isinstance(opened, VariantStudyResult) and opened.study == result.study
    assert roughcontact.study.open_results is open_results
    with pytest.raises(ValueError, match=r"holds a parameter study \(its scene.toml has a \[vary\] table\): "
                                         r"roughcontact.study.open_results reads it"):
        open_study_results(tmp_path / "out")
    assert [numbers(r) for r in opened.results] == [numbers(r) for r in result.results]
    np.testing.assert_array_equal(opened.sensitivity.measures["swing"], result.sensitivity.measures["swing"])
    report = (tmp_path / "out" / "report.md").read_text()
    assert "# Parameter study: 5 variants of the scene (one-at-a-time)" in report
    assert "| `screen.eps_sc` | 3000 | 1000 to 10000 (log) | the scene file |" in report
    assert report.count("| 3: screen.eps_sc = 1000 |") == 4                       # 2 loads x 2 voltages
    for name in ("variants.csv", "sensitivity.csv", "sensitivity.png", "results.nc"):
        assert (tmp_path / "out" / name).is_file(), name
    with xarray.open_dataset(tmp_path / "out" / "results.nc", engine="h5netcdf") as data:
        assert data.sizes["variant"] == 5 and list(data["screen.eps_sc"].values) == [3e3, 3e3, 3e3, 1e3, 1e4]
        np.testing.assert_array_equal(data["sensitivity_swing"].values, result.sensitivity.measures["swing"])
        assert data.attrs["design"] == "one-at-a-time" and "[vary]" in data.attrs["scene_toml"]
    # another study or a single scene into the same directory: refused in one line
    scene.write_text(VARIED.replace("[3e7, 1e8]", "[3e7, 2e8]"))
    assert main(command) == 2
    assert re.fullmatch(r"roughcontact run: error: \S+ holds the results of another parameter study \(the \[vary\] "
                        r"table\); run into a new --out directory, or delete this one to start over\n",
                        capsys.readouterr().err)
    single = tmp_path / "single.toml"
    single.write_text(BASE)
    assert main(["run", str(single), "--preset", "draft", "--out", str(tmp_path / "out"), "--workers", "1"]) == 2
    assert "holds the results of a parameter study" in capsys.readouterr().err


def test_the_command_names_a_bad_vary_key_in_one_line(tmp_path, capsys):
    scene = tmp_path / "vary.toml"
    scene.write_text(BASE + '\n[vary]\n"skin.layer_E_star" = [-1.0]\n')
    assert main(["run", str(scene), "--out", str(tmp_path / "out")]) == 2
    assert capsys.readouterr().err == (f"roughcontact run: error: {scene}, line 16: [vary] \"skin.layer_E_star\" = "
                                       "[-1.0]: skin.layer_E_star = -1.0 is out of range; valid range (0, inf)\n")
    assert main(["scene", str(scene)]) == 2 and "line 16" in capsys.readouterr().err
    scene.write_text(VARIED)
    assert main(["scene", str(scene)]) == 0
    assert "valid parameter study (preset standard, 2 loads x 2 voltages; design one-at-a-time, 5 variants of " \
           "skin.layer_E_star, screen.eps_sc)" in capsys.readouterr().out


# ---------------------------------------------------------------------------------------------------------
# A varied measured scan
# ---------------------------------------------------------------------------------------------------------
def _write_scan(path, rng):
    surfaces.self_affine(surfaces.Grid((16, 16), (1.2e-4, 1.2e-4), periodic=False), hurst=0.8, rms_height=3e-6,
                         short_cutoff=3e-5, rng=rng).save(path)


def test_a_varied_scan_that_changes_is_solved_again(tmp_path):
    for name, rng in (("a.npz", 1), ("b.npz", 2)):
        _write_scan(tmp_path / name, rng)
    scene = tmp_path / "vary.toml"
    scene.write_text('[ridges]\nenabled = false\n[roughness]\ntopography = "a.npz"\nboundary = "periodic"\n'
                     'detrend = "mean"\n[loads]\nnormal_forces = [0.5, 2.0]\nvoltages = [0.0, 150.0]\n'
                     '[ridge_area]\ncoarse_graining = 2e-5\nsensitivity = [2.0]\n'
                     '[vary]\n"roughness.topography" = ["a.npz", "b.npz"]\n')
    text = scene.read_text()
    scene.write_text(text.replace('"b.npz"]', '"c.npz"]'))
    with pytest.raises(ValueError, match=rf"{re.escape(str(scene))}, line 14: \[vary\] \"roughness.topography\" = "
                                         r"\['a.npz', 'c.npz'\]: cannot read the topography \S+c.npz: no such file"):
        load_variant_study(scene, preset="draft")
    scene.write_text(text)
    study = load_variant_study(scene, preset="draft")
    assert [variant.label for variant in study.variants] == ["baseline", "roughness.topography = a.npz",
                                                             "roughness.topography = b.npz"]
    first = run_variants(study, tmp_path / "out", workers=1)
    assert (first.tasks, first.computed) == (4, 4)                         # the scan a's variant is the baseline
    assert sorted(path.name for path in (tmp_path / "out" / "patches").iterdir()) == ["0.npz", "1.npz", "2.npz"]
    _write_scan(tmp_path / "b.npz", 3)                                      # the same path, another surface
    again = run_variants(load_variant_study(scene, preset="draft"), tmp_path / "out", workers=1)
    assert (again.computed, again.solves) == (2, 4)                         # b's two tasks, never resumed
    assert numbers(again.results[0]) == numbers(first.results[0])
    assert numbers(again.results[2]) != numbers(first.results[2])
    shutil.move(tmp_path / "b.npz", tmp_path / "moved.npz")               # the results stand without the scans
    opened = open_results(tmp_path / "out")
    assert [numbers(r) for r in opened.results] == [numbers(r) for r in again.results]


# ---------------------------------------------------------------------------------------------------------
# Global designs (SALib)
# ---------------------------------------------------------------------------------------------------------
def _linear_study(design, samples):
    """Outputs y = 3 x₁ − 5 x₂ of two linear ranges x₁ in [1, 3], x₂ in [10, 11] on a global design."""
    variation = Variation(inputs=(Input("skin.E_star", low=1.0, high=3.0), Input("screen.eps_sc", low=10.0,
                                                                                  high=11.0)),
                          design=design, samples=samples, seed=1)
    unit = unit_sample(variation)
    x = np.array([[item.at(u) for item, u in zip(variation.inputs, row)] for row in unit])
    return analyse(variation, {"y": (3 * x[:, 0] - 5 * x[:, 1])[:, None, None]}, [1.0], [0.0], unit)


def test_morris_and_sobol_measures_of_a_linear_function():
    pytest.importorskip("SALib", reason="the global designs sample and analyse with SALib (roughcontact[sensitivity])")
    morris = _linear_study("morris", 10)
    # an elementary effect across the whole unit range is the output's change over the input's range: 3 x 2, 5 x 1
    np.testing.assert_allclose(morris.measure("mu_star", "y", 1.0, 0.0), [6.0, 5.0], rtol=1e-12)
    np.testing.assert_allclose(morris.measure("mu", "y", 1.0, 0.0), [6.0, -5.0], rtol=1e-12)
    np.testing.assert_allclose(morris.measure("sigma", "y", 1.0, 0.0), [0.0, 0.0], atol=1e-12)
    assert morris.ranking("y", 1.0, 0.0) == ("skin.E_star", "screen.eps_sc")
    sobol = _linear_study("sobol", 1024)
    # additive and uniform: S1 = ST = a_i² Δ_i² / Σ a_k² Δ_k² = 36/61, 25/61; 1024 Sobol' points give ~1e-3
    np.testing.assert_allclose(sobol.measure("S1", "y", 1.0, 0.0), [36 / 61, 25 / 61], atol=2e-3)
    np.testing.assert_allclose(sobol.measure("ST", "y", 1.0, 0.0), [36 / 61, 25 / 61], atol=2e-3)
    assert sobol.ranked_by == "ST" and sobol.ranking("y", 1.0, 0.0)[0] == "skin.E_star"


def test_a_tornado_of_a_known_table():
    variation = Variation(inputs=(Input("skin.E_star", values=(3.0, 1.0)), Input("screen.eps_sc", low=1.0,
                                                                                   high=2.0)))
    assert one_at_a_time_indices(variation) == ((1, 2), (3, 4))
    y = np.array([2.0, 5.0, 1.0, 1.5, 2.2])[:, None, None]                # baseline, E 3 and 1, eps 1 and 2
    tornado = analyse(variation, {"y": y}, [1.0], [0.0])
    np.testing.assert_allclose(tornado.measure("low", "y", 1.0, 0.0), [-0.5, -0.25])     # at E = 1, eps = 1
    np.testing.assert_allclose(tornado.measure("high", "y", 1.0, 0.0), [1.5, 0.1])       # at E = 3, eps = 2
    np.testing.assert_allclose(tornado.measure("swing", "y", 1.0, 0.0), [2.0, 0.35])
    assert tornado.ranking("y", 1.0, 0.0) == ("skin.E_star", "screen.eps_sc")


def test_morris_on_the_tiny_scene_ranks_as_single_studies(varied):
    pytest.importorskip("SALib", reason="the Morris design samples with SALib (roughcontact[sensitivity])")
    _, directory, result = varied
    text = VARIED.replace("design", "").replace('"skin.layer_E_star" = [3e7, 1e8]',
                                                'design = "morris"\nsamples = 2\nseed = 3\n'
                                                '"skin.layer_E_star" = { low = 1e7, high = 1e8, scale = "log" }')
    study = load_variant_study(text=text, preset="draft")
    assert len(study.variants) == 2 * 3 and study.unit_sample.shape == (6, 2)
    morris = run_variants(study, workers=1, tasks=directory / "out" / "tasks")
    assert morris.sensitivity.ranking("electrostatic_force", 0.5, 150.0) == \
        result.sensitivity.ranking("electrostatic_force", 0.5, 150.0) == ("skin.layer_E_star", "screen.eps_sc")
    assert morris.sensitivity.ranking("equivalent_gap", 2.0, 150.0)[0] == "skin.layer_E_star"


def test_a_global_design_without_salib_names_the_extra(monkeypatch):
    monkeypatch.setitem(sys.modules, "SALib", None)
    monkeypatch.setitem(sys.modules, "SALib.sample", None)
    with pytest.raises(ImportError, match=r"\[vary\] design = 'sobol' samples with SALib: pip install "
                                          r"'roughcontact\[sensitivity\]'"):
        load_variant_study(text=BASE + '[vary]\ndesign = "sobol"\nsamples = 2\n"skin.E_star" = [1e5, 2e5]\n')
