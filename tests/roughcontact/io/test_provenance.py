"""The one writer of provenance-carrying outputs (roughcontact.io.provenance)."""
import json
import os
import re

import numpy as np
import pytest
from matplotlib.figure import Figure
from PIL import Image

from roughcontact import __version__
from roughcontact.io import (OutputPathError, Provenance, output_directory, read_csv, save_figure, write_atomic,
                             write_columns, write_csv)

PROVENANCE = Provenance.of_command("python studies/study.py", ["--output", "a b"], {"output": "a b", "n": 3})


def test_line_names_version_date_command_and_parameters():
    line = PROVENANCE.line
    assert line.startswith(f"roughcontact {__version__}, {PROVENANCE.date}, ")
    assert "command: python studies/study.py --output 'a b', parameters: " in line   # shell-quoted arguments
    assert json.loads(line.split("parameters: ")[1]) == {"output": "a b", "n": 3}


def test_csv_writers_lead_with_the_comment_that_readers_skip(tmp_path):
    write_csv(tmp_path / "rows.csv", [{"x": 1, "y": 2.5}, {"x": 2}], PROVENANCE)
    assert (tmp_path / "rows.csv").read_text().splitlines()[0] == f"# {PROVENANCE.line}"
    assert read_csv(tmp_path / "rows.csv") == [{"x": "1", "y": "2.5"}, {"x": "2", "y": ""}]
    write_columns(tmp_path / "columns.csv", ["a", "b"], [np.arange(3.0), np.ones(3)], PROVENANCE)
    np.testing.assert_array_equal(np.loadtxt(tmp_path / "columns.csv", delimiter=",", skiprows=2)[:, 0], [0, 1, 2])
    write_csv(tmp_path / "plain.csv", [{"x": 1}], None)                  # for readers that cannot skip a comment
    assert (tmp_path / "plain.csv").read_text().splitlines()[0] == "x"


@pytest.mark.parametrize("colors", [None, 16])                           # matplotlib's PNG, and a palette PNG
def test_png_metadata(tmp_path, colors):
    figure = Figure(figsize=(1, 1))
    figure.subplots().plot([0, 1])
    save_figure(figure, tmp_path / "f.png", PROVENANCE, dpi=50, colors=colors)
    with Image.open(tmp_path / "f.png") as image:
        assert image.text["Comment"] == PROVENANCE.line
        assert image.text["Software"] == f"roughcontact {__version__}"


def test_output_directory_creates_only_the_last_level(tmp_path):
    assert output_directory(tmp_path / "new") == tmp_path / "new" and (tmp_path / "new").is_dir()
    assert output_directory(tmp_path / "new") == tmp_path / "new"           # an existing directory is fine
    with pytest.raises(OutputPathError, match="does not exist"):
        output_directory(tmp_path / "missing" / "new")
    assert not (tmp_path / "missing").exists()


def test_output_directory_and_read_csv_name_a_bad_argument(tmp_path):
    for path in (None, 3):
        with pytest.raises(TypeError, match=f"the output path must be a str or os.PathLike, got {type(path).__name__}"):
            output_directory(path)
    latin1 = tmp_path / "points.csv"                       # re-saved by a spreadsheet in Latin-1
    latin1.write_bytes("# roughcontact\nload,unit\n1,µm\n".encode("latin-1"))
    with pytest.raises(ValueError, match=f"{re.escape(str(latin1))} is not UTF-8 text"):
        read_csv(latin1)


def test_write_atomic_syncs_the_file_before_renaming_it(tmp_path, monkeypatch):
    # a crash or power cut after the rename must not leave an empty file (a resumed study would read it)
    events, fsync, replace = [], os.fsync, os.replace
    monkeypatch.setattr(os, "fsync", lambda descriptor: events.append(("fsync", os.fstat(descriptor).st_size))
                        or fsync(descriptor))
    monkeypatch.setattr(os, "replace", lambda *paths: events.append(("replace",)) or replace(*paths))
    write_atomic(tmp_path / "record.json", '{"new": 1}')
    assert events[:2] == [("fsync", 10), ("replace",)]          # the whole text on disk, then renamed
    assert events[2:] == [("fsync", os.stat(tmp_path).st_size)]  # and the directory's entry after it


def test_write_atomic_replaces_the_file_whole(tmp_path):
    path = tmp_path / "record.json"
    path.write_text("old")
    assert write_atomic(path, '{"new": 1}') == path
    assert json.loads(path.read_text()) == {"new": 1}
    assert sorted(p.name for p in tmp_path.iterdir()) == ["record.json"]      # no .part left behind


def test_absolute_paths_are_recorded_relative_to_the_working_directory_or_by_name(tmp_path, monkeypatch):
    """A file made on one machine carries none of its directories: a path under the working directory is
    recorded relative to it, any other absolute path by its name alone; relative paths and other values stay."""
    monkeypatch.chdir(tmp_path)
    elsewhere = os.path.join(os.path.abspath(os.sep), "tmp", "res2", "resolution-out")
    provenance = Provenance.of_command(
        "python studies/x.py", ["--output", elsewhere, f"--scene={tmp_path / 'scenes' / 'a.toml'}", "rel/b.toml", "-3"],
        {"output": elsewhere, "scene": tmp_path / "scenes" / "a.toml", "files": [str(tmp_path)], "n": 3})
    scene = os.path.join("scenes", "a.toml")
    assert provenance.command == f"python studies/x.py --output resolution-out --scene={scene} rel/b.toml -3"
    assert provenance.parameters == {"output": "resolution-out", "scene": scene, "files": ["."], "n": 3}
    assert "res2" not in provenance.line and str(tmp_path) not in provenance.line


def test_the_shipped_tables_carry_no_machine_path():
    """The provenance lines of the CSV shipped with the library (as the writer now records them)."""
    import shlex
    from roughcontact.study.presets import TABLE_PATH
    lines = [line for line in TABLE_PATH.read_text(encoding="utf-8").splitlines() if line.startswith("#")]
    assert lines
    for line in lines:
        command, parameters = line.split(", command: ", 1)[1].split(", parameters: ", 1)
        values = shlex.split(command) + [str(value) for value in json.loads(parameters).values()]
        assert not [value for value in values if os.path.isabs(value.partition("=")[2] or value)], line
