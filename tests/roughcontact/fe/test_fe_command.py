"""``roughcontact fingertip-fe`` without FElupe: a one-line error and exit code 2, no traceback."""
import sys

from roughcontact.cli import main


def test_command_without_felupe_says_how_to_install(monkeypatch, tmp_path, capsys):
    monkeypatch.setitem(sys.modules, "felupe", None)          # import felupe raises ImportError
    assert main(["fingertip-fe", "--out", str(tmp_path / "out")]) == 2
    error = capsys.readouterr().err
    assert 'pip install "roughcontact[fe]"' in error and error.count("\n") == 1
    assert not (tmp_path / "out").exists()                    # nothing computed or written
