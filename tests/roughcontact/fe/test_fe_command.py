"""``roughcontact fingertip-fe`` without FElupe: a one-line error and exit code 2, no traceback."""
import sys

import pytest

from roughcontact.cli import main


def test_command_without_felupe_says_how_to_install(monkeypatch, tmp_path, capsys):
    monkeypatch.setitem(sys.modules, "felupe", None)          # import felupe raises ImportError
    assert main(["fingertip-fe", "--out", str(tmp_path / "out")]) == 2
    error = capsys.readouterr().err
    assert 'pip install "roughcontact[fe]"' in error and error.count("\n") == 1
    assert not (tmp_path / "out").exists()                    # nothing computed or written


def test_felupe_is_imported_only_inside_functions_of_roughcontact_fe():
    # the licence boundary: the MIT core never imports the GPL library, and roughcontact.fe only when a model
    # is built (parsed, nothing imported)
    import ast
    from pathlib import Path

    package = Path(__file__).resolve().parents[3] / "roughcontact"
    found = []
    for path in package.rglob("*.py"):
        tree = ast.parse(path.read_text())
        inside = {id(node) for scope in ast.walk(tree) if isinstance(scope, (ast.FunctionDef, ast.AsyncFunctionDef))
                  for node in ast.walk(scope)}
        for node in ast.walk(tree):
            names = ([alias.name for alias in node.names] if isinstance(node, ast.Import)
                     else [node.module or ""] if isinstance(node, ast.ImportFrom) else [])
            if any(name.split(".")[0] in ("felupe", "tensortrax") for name in names):
                found.append((path.relative_to(package).as_posix(), id(node) in inside))
    assert found and all(where.startswith("fe/") and in_function for where, in_function in found), found


@pytest.mark.parametrize("arguments, named", [
    (["--forces", "1e7"], "normal_force = 10000000.0 is out of range; valid range (0, 1000]"),
    (["--forces", "50", "nan"], "normal_force must be finite, got nan; valid range (0, 1000]"),
    (["--travel-step", "1e-12"], "travel_step = 1e-12 is out of range; valid range [3e-06, 0.001]"),
    (["--travel-step", "0.02"], "travel_step = 0.02 is out of range; valid range [3e-06, 0.001]"),
    (["--friction", "0"], "friction = 0.0 is out of range; valid range (0, 3]"),
    (["--friction", "0.26", "5"], "friction = 5.0 is out of range; valid range (0, 3]"),
    (["--workers", "0"], "workers"),
    (["--mesh", "huge"], "invalid choice: 'huge'")])
def test_bad_values_end_in_one_line_naming_the_value_and_its_range(arguments, named, tmp_path, capsys):
    # before anything is computed or written, with or without FElupe; never a traceback (the three first of
    # these ended in a RuntimeError, a 112 GiB allocation and a message about max_travel)
    try:
        code = main(["fingertip-fe", "--out", str(tmp_path / "out"), *arguments])
    except SystemExit as exit:                                   # argparse's own checks (--mesh)
        code = exit.code
    error = capsys.readouterr().err
    assert code == 2 and named in error and error.count("\n") == 1 and "Traceback" not in error
    assert "max_travel" not in error
    assert not (tmp_path / "out").exists()
