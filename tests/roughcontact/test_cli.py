"""The console command is a thin wrapper: it must run through the same library functions."""
import contextlib
import io
import json
import subprocess
import sys
import warnings
from concurrent.futures.process import BrokenProcessPool
from datetime import datetime, timedelta, timezone
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from roughcontact import __version__, study
from roughcontact.cli import DEFAULT_FIGURES_OUTPUT, info, main
from roughcontact.io import provenance
from roughcontact.io import read_csv
from roughcontact.paper import checkpoint_table
from roughcontact.study.execution import StaleTaskWarning

FIGURES = ["fig3_apparent_area", "fig4_ridge_area", "fig5_peeling", "fig9_area_reduction_gap",
           "fig10_tangential_force", "fig11_friction_coefficient"]


def test_version_flag(capsys):
    with pytest.raises(SystemExit) as exit_info:
        main(["--version"])
    assert exit_info.value.code == 0
    assert capsys.readouterr().out.strip() == f"roughcontact {__version__}"


def test_info_reports_installation():
    report = info()
    assert report["roughcontact"] == __version__
    assert report["numpy"] != "not installed"
    assert "numba cache dir" in report and "default FFT backend" in report


def test_info_command_does_not_import_numba():
    code = "import sys; from roughcontact.cli import main; main(['info']); print('numba' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip().splitlines()[-1] == "False"


def test_unknown_command_is_an_error(capsys):
    with pytest.raises(SystemExit) as exit_info:
        main(["frobnicate"])
    assert exit_info.value.code == 2
    assert len(capsys.readouterr().err.strip().splitlines()) == 1


@pytest.fixture(scope="module")
def figures_run(tmp_path_factory):
    """One run of ``roughcontact figures`` into a fresh directory: (directory, printed output)."""
    output = tmp_path_factory.mktemp("figures") / "out"                 # the last level is created
    printed = io.StringIO()
    with contextlib.redirect_stdout(printed):
        assert main(["figures", "--output", str(output)]) == 0
    return output, printed.getvalue()


def test_figures_command_runs_the_library_reproduction(figures_run):
    output, out = figures_run
    table = checkpoint_table()
    assert str(table) in out                                  # the checkpoint table is printed
    for name in FIGURES:
        assert (output / f"{name}.png").stat().st_size > 1000
        data = np.loadtxt(output / f"{name}.csv", delimiter=",", skiprows=2)     # provenance, header
        assert data.ndim == 2 and data.shape[0] >= 20 and np.isfinite(data).all()
    rows = read_csv(output / "checkpoints.csv")
    assert [r["quantity"] for r in rows] == [r.quantity for r in table.rows]
    assert float(rows[0]["computed"]) == table.rows[0].computed
    assert len(list(output.glob("*.png"))) == len(FIGURES)


def test_every_figures_output_carries_its_provenance(figures_run):
    output, _ = figures_run
    files = sorted(output.iterdir())
    assert {path.suffix for path in files} == {".csv", ".png"}
    for path in files:
        if path.suffix == ".csv":
            line = path.read_text().splitlines()[0]
            assert line.startswith("# ")
            line = line[2:]
        else:
            with Image.open(path) as image:
                line = image.text["Comment"]
                assert image.text["Software"] == f"roughcontact {__version__}"
        assert line.startswith(f"roughcontact {__version__}, ")
        date = line.split(", ")[1]
        assert abs(datetime.fromisoformat(date) - datetime.now(timezone.utc)) < timedelta(hours=1)
        command, parameters = line.split(", command: ")[1].split(", parameters: ")
        # a path outside the working directory is recorded by its name (no machine path in a shipped file)
        assert command == f"roughcontact figures --output {output.name}"
        assert json.loads(parameters) == {"command": "figures", "output": output.name}


def test_figures_csv_readers_skip_the_provenance(figures_run):
    output, _ = figures_run
    data = np.loadtxt(output / "fig10_tangential_force.csv", delimiter=",", skiprows=2)
    assert data.shape == (231, 6) and np.isfinite(data).all()
    rows = read_csv(output / "checkpoints.csv")
    assert rows[0]["quantity"].startswith("w at 200 V")


@pytest.mark.parametrize("make_output, message", [
    (lambda tmp: tmp / "file.txt", "is a file"),                                    # an existing file
    (lambda tmp: tmp / "missing" / "out", "does not exist"),                        # a deep path from a typo
    (lambda tmp: tmp / "file.txt" / "out", "file.txt, is a file, not a directory"),  # a file as parent
    (lambda tmp: "", "empty"),
])
def test_figures_output_mistakes_exit_2_with_one_line(tmp_path, capsys, make_output, message):
    (tmp_path / "file.txt").write_text("not a directory")
    with pytest.raises(SystemExit) as exit_info:
        main(["figures", "--output", str(make_output(tmp_path))])
    assert exit_info.value.code == 2
    error = capsys.readouterr().err
    assert len(error.strip().splitlines()) == 1 and message in error and "Traceback" not in error
    assert not (tmp_path / "missing").exists()                                      # nothing created


def test_unwritable_output_exits_2(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(provenance.os, "access", lambda path, mode: False)        # root may write anywhere
    with pytest.raises(SystemExit) as exit_info:
        main(["figures", "--output", str(tmp_path)])
    assert exit_info.value.code == 2
    error = capsys.readouterr().err.strip()
    assert error == f"roughcontact figures: error: the output directory {tmp_path} is not writable"


def test_bad_option_exits_2_with_one_line(capsys):
    with pytest.raises(SystemExit) as exit_info:
        main(["figures", "--fast"])                                                 # removed: it was not faster
    assert exit_info.value.code == 2
    assert len(capsys.readouterr().err.strip().splitlines()) == 1


def test_help_shows_defaults_without_markup(capsys):
    with pytest.raises(SystemExit):
        main(["figures", "--help"])
    out = capsys.readouterr().out
    assert "(default: roughcontact-figures)" in out and "``" not in out and ":func:" not in out


def test_default_output_directory_is_git_ignored():
    gitignore = Path(__file__).resolve().parents[2] / ".gitignore"
    assert f"{DEFAULT_FIGURES_OUTPUT}/" in gitignore.read_text().split()


@pytest.mark.parametrize("options, message", [
    (["--workers", "0"], "roughcontact run: error: workers must be an integer in [1, inf], got 0"),
    (["--workers", "2", "--dask", "tcp://127.0.0.1:8786"], "argument --dask: not allowed with argument --workers"),
    (["--dask", "tcp://127.0.0.1:8786"], "needs dask.distributed: pip install 'roughcontact[parallel]'"),
])
def test_run_executor_mistakes_exit_2_with_one_line(tmp_path, capsys, monkeypatch, options, message):
    monkeypatch.setitem(sys.modules, "distributed", None)                 # as without roughcontact[parallel]
    with contextlib.suppress(SystemExit):
        assert main(["run", "--preset", "draft", "--out", str(tmp_path / "out"), *options]) == 2
    error = capsys.readouterr().err
    assert len(error.strip().splitlines()) == 1 and message in error
    assert not (tmp_path / "out" / "scene.toml").exists()                  # refused before the study starts


def test_ctrl_c_exits_130_with_one_line(tmp_path, capsys, monkeypatch):
    def interrupted(*arguments, **options):
        raise KeyboardInterrupt

    monkeypatch.setattr(study, "run_study", interrupted)
    with pytest.raises(SystemExit) as exit_info:
        main(["run", "--out", str(tmp_path / "out")])
    assert exit_info.value.code == 130
    assert capsys.readouterr().err.splitlines() == [
        f"roughcontact run: interrupted; finished tasks are kept in {tmp_path / 'out'} (the same command resumes)"]


def test_a_warning_is_one_line(tmp_path, capsys, monkeypatch):
    def warned(*arguments, **options):
        warnings.warn("task file R000_U000.json: empty; its task is solved again", StaleTaskWarning)
        raise ValueError("stop here")

    monkeypatch.setattr(study, "run_study", warned)
    assert main(["run", "--out", str(tmp_path / "out")]) == 2
    assert capsys.readouterr().err.splitlines() == [
        "roughcontact run: warning: task file R000_U000.json: empty; its task is solved again",
        "roughcontact run: error: stop here"]


def test_a_broken_pool_is_one_line(tmp_path, capsys, monkeypatch):
    # (a worker killed by the system, e.g. out of memory): run_study's RuntimeError, one line, exit code 1
    def broken(*arguments, **options):
        try:
            raise BrokenProcessPool("A process in the process pool was terminated abruptly")
        except BrokenProcessPool as error:
            raise RuntimeError("a worker of the study's process pool ended abruptly") from error

    monkeypatch.setattr(study, "run_study", broken)
    assert main(["run", "--out", str(tmp_path / "out")]) == 1
    assert capsys.readouterr().err.splitlines() == [
        "roughcontact run: error: a worker of the study's process pool ended abruptly"]


def test_a_full_disk_under_the_standard_output_is_one_line(capsys, monkeypatch):
    def full(*arguments, **options):
        raise OSError(28, "No space left on device")        # (writing to /dev/full: no file name)

    monkeypatch.setattr("builtins.print", full)
    with pytest.raises(SystemExit) as exit_info:
        main(["info"])
    assert exit_info.value.code == 2
    assert capsys.readouterr().err == "roughcontact info: error: cannot write the output: No space left on device\n"
