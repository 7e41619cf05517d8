"""Scenes: the default round-trips through TOML; every scene error names the key, its line and the valid values."""
import dataclasses
import re
from importlib import resources

import pytest

from roughcontact.cli import main
from roughcontact.study.scene import DEFAULT_SCENE_TOML, PRESETS, Ridges, load_scene


def test_default_scene_round_trips_through_toml():
    scene = load_scene()
    assert load_scene(text=scene.to_toml()) == scene
    assert load_scene(text=DEFAULT_SCENE_TOML) == scene
    assert scene.screen.stack().dielectric_offset == pytest.approx(0.33974e-6, rel=1e-4)   # seed Table 1
    changed = dataclasses.replace(scene, ridges=dataclasses.replace(scene.ridges, period=0.5e-3))
    assert load_scene(text=changed.to_toml()) == changed


def test_partial_scene_keeps_the_other_defaults_and_preset_override():
    scene = load_scene(text="[loads]\nnormal_forces = [1.0]\nvoltages = [0, 100]\n", preset="draft")
    assert scene.loads.normal_forces == (1.0,) and scene.loads.voltages == (0.0, 100.0)
    assert scene.ridges == load_scene().ridges
    assert scene.preset == scene.presets["draft"] and scene.preset.grid == 128
    assert set(scene.presets) == set(PRESETS)
    with pytest.raises(ValueError, match="preset = 'fast' is not one of"):
        load_scene(preset="fast")


@pytest.mark.parametrize("text, key, line, valid", [
    ("[ridges]\nperiod = 0.45e-3\n\n# comment\nperiode = 1\n", "ridges.periode", 5, "period, height"),
    ("[skin]\nE_star = \"soft\"\n", "skin.E_star", 2, "(0, inf)"),
    ("[ridges]\nheight = -1e-6\n", "ridges.height", 2, "[0, inf)"),
    ("[loads]\nnormal_forces = [1.0, 0.5]\n", "loads.normal_forces", 2, "strictly increasing"),
    ("[loads]\nvoltages = []\n", "loads.voltages", 2, "non-empty"),
    ("[fingerpad]\nmodel = \"sphere\"\n", "fingerpad.model", 2, '"power_law", "fingertip"'),
    ("[study]\npreset = \"quick\"\n", "study.preset", 2, '"draft", "standard", "reference"'),
    ("[presets.draft]\ngrid = 4\n", "presets.draft.grid", 2, "[8, 4096]"),
    ("[presets.quick]\ngrid = 64\n", "presets.quick", 1, '"draft", "standard", "reference"'),
    ("[roughness]\nenabled = 1\n", "roughness.enabled", 2, "true or false"),
    ("\n[ridgez]\nperiod = 1\n", "ridgez", 2, "fingerpad, ridges"),
    ("[roughness]\nshort_cutoff = 1e-4\n", "roughness.short_cutoff", 2, "below roughness.long_cutoff"),
    ("[presets.draft]\ndtype = \"float16\"\n", "presets.draft.dtype", 2, '"float64", "float32"'),
    ("[presets.standard]\nwarm_start = \"yes\"\n", "presets.standard.warm_start", 2, "true or false"),
    ("[presets.reference]\nscales = \"mixed\"\n", "presets.reference.scales", 2, '"resolved", "coupled"'),
    ("\n[study]\npreset = \"auto\"\n", "study.preset", 3, "[presets.auto]"),
    ("[presets.auto]\ngrid = 64\n", "presets.auto", 1, "missing keys periods, realisations"),
    ("[screen]\neps_a = 1.0\nfield = \"fem\"\n", "screen.field", 3, '"parallel_plate", "layered"'),
    ("[screen]\ncontact_line = \"paschen\"\n", "screen.contact_line", 2, '"breakdown", "breakdown:<E_bd in V/m>"'),
    ("[screen]\ncontact_line = \"film:-1e-7\"\n", "screen.contact_line", 2, "RoughnessFilm.thickness"),
    ("[screen]\ncontact_line = \"film:1e-7\"\nfield = \"parallel_plate\"\n", "screen.contact_line", 2,
     "layered field of the dielectric model only"),
])
def test_scene_errors_name_key_line_and_valid_values(text, key, line, valid):
    with pytest.raises(ValueError) as error:
        load_scene(text=text)
    message = str(error.value)
    assert f"scene key {key}" in message and f"line {line}:" in message and valid in message, message


def test_the_contact_line_key_sets_the_layered_law_and_round_trips():
    from roughcontact.electrostatics import AirBreakdown, RoughnessFilm
    default = load_scene()
    assert default.screen.contact_line == "breakdown" and "contact_line" not in default.screen.items()
    assert default.screen.interaction(200.0).contact_line == AirBreakdown()
    film = load_scene(text="[screen]\ncontact_line = \"film:5e-8\"\n")
    assert film.screen.interaction(200.0).contact_line == RoughnessFilm(5e-8)
    assert load_scene(text=film.to_toml()) == film
    plain = load_scene(text="[screen]\ncontact_line = \"none\"\n")
    assert plain.screen.interaction(200.0).contact_line is None and plain.screen.interaction(0.0) is None
    per_pixel = load_scene(text="[screen]\nfield = \"parallel_plate\"\n")      # the default does not act on it
    assert per_pixel.screen.interaction(200.0).contact_line is None


def test_preset_knobs_default_to_float64_warm_resolved():
    for preset in load_scene().presets.values():
        assert (preset.dtype, preset.warm_start, preset.scales) == ("float64", True, "resolved")


def test_a_chosen_setting_is_held_as_presets_auto_and_round_trips():
    scene = load_scene()
    setting = dataclasses.replace(scene.presets["standard"], grid=128, realisations=3, dtype="float32",
                                  warm_start=False)
    auto = scene.with_setting(setting)
    assert auto.study.preset == "auto" and auto.preset == setting and auto.presets["draft"] == scene.presets["draft"]
    assert load_scene(text=auto.to_toml()) == auto                    # scene.toml of a results directory
    assert auto.flat()["presets.auto.grid"] == 128                    # the results' attributes
    assert load_scene(text=auto.to_toml(), preset="draft").preset == scene.presets["draft"]
    with pytest.raises(ValueError, match="preset = 'auto' is not one of the scene.s presets.*presets.auto_scene"):
        load_scene(preset="auto")


def test_invalid_toml_and_missing_file(tmp_path):
    with pytest.raises(ValueError, match="not valid TOML"):
        load_scene(text="[ridges\n")
    with pytest.raises(ValueError, match="cannot read the scene file"):
        load_scene(tmp_path / "missing.toml")
    latin1 = tmp_path / "latin1.toml"                              # a comment saved in Latin-1 by an editor
    latin1.write_bytes(b"[loads]\nvoltages = [0.0]\n# caf\xe9\n")
    with pytest.raises(ValueError, match=f"the scene file {re.escape(str(latin1))} is not UTF-8 text: byte 0xe9 "
                                         "at line 3, column 6.*TOML files are UTF-8"):
        load_scene(latin1)
    with pytest.raises(ValueError, match=f"cannot read the scene file {re.escape(str(tmp_path))}: Is a directory"):
        load_scene(tmp_path)
    with pytest.raises(TypeError, match="scene path must be a str or os.PathLike, got int"):
        load_scene(3)


def test_sections_validate_when_built_in_python():
    with pytest.raises(ValueError, match="ridges.width_ratio"):
        Ridges(enabled=True, period=4.5e-4, height=5e-5, width_ratio=5.0, pore_density=0.0, pore_diameter=1.2e-4,
               pore_depth=2e-5)


def test_the_default_scene_is_a_package_file():
    # read with importlib.resources, so it is found in an installed wheel (hatch packages roughcontact/ whole)
    text = resources.files("roughcontact.study").joinpath("default_scene.toml").read_text(encoding="utf-8")
    assert text == DEFAULT_SCENE_TOML and text.startswith("# roughcontact scene: the default fingerpad")
    assert load_scene(text=text) == load_scene()


def test_scene_command_shows_and_validates(tmp_path, capsys):
    assert main(["scene", "--show"]) == 0
    assert capsys.readouterr().out == DEFAULT_SCENE_TOML
    path = tmp_path / "scene.toml"
    path.write_text("[skin]\nE_star = 2e5\n")
    assert main(["scene", str(path), "--show"]) == 0
    assert load_scene(text=capsys.readouterr().out).skin.E_star == 2e5
    path.write_text("[skin]\nE_stra = 2e5\n")
    assert main(["scene", str(path)]) == 2
    assert "scene key skin.E_stra" in capsys.readouterr().err
