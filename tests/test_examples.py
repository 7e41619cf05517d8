"""Every script in examples/ runs as ``__main__`` and prints what it computes; every one is listed in the
gallery's README with a title line."""
import runpy
from pathlib import Path

import pytest

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
SCRIPTS = sorted(path.name for path in EXAMPLES.glob("*.py"))


def test_gallery_lists_every_example():
    readme = (EXAMPLES / "README.md").read_text()
    assert 6 <= len(SCRIPTS) <= 8
    for name in SCRIPTS:
        assert f"[{name}]({name})" in readme
        title = (EXAMPLES / name).read_text().split("\n")[0]
        assert title.startswith('"""') and title.endswith(".")          # a one-line title in the docstring


@pytest.mark.parametrize("name", SCRIPTS)
def test_example_runs(name, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    runpy.run_path(str(EXAMPLES / name), run_name="__main__")
    assert len(capsys.readouterr().out.splitlines()) >= 2                # a header or several results
