"""``roughcontact fingertip-fe`` without FElupe: a one-line error and exit code 2, no traceback."""
import sys

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
