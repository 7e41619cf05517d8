"""The console command is a thin wrapper: it must run through the same library functions."""
import subprocess
import sys

import pytest

from roughcontact import __version__
from roughcontact.cli import info, main


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


def test_unknown_command_is_an_error():
    with pytest.raises(SystemExit) as exit_info:
        main(["frobnicate"])
    assert exit_info.value.code == 2


def test_figures_command_runs_the_library_reproduction(tmp_path, capsys):
    assert main(["figures", "--fast", "--output", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "| quantity | quoted | computed |" in out          # the checkpoint table is printed
    assert (tmp_path / "checkpoints.csv").exists()
    assert len(list(tmp_path.glob("*.png"))) >= 6
