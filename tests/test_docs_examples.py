"""Every Python block of the pages that teach the API runs, in order, in one namespace per page."""
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PAGES = ["README.md", "docs/architecture.md", "docs/interactions.md", "docs/electrostatics.md"]
BLOCK = re.compile(r"^```python\n(.*?)^```", re.MULTILINE | re.DOTALL)


def python_blocks(page):
    return BLOCK.findall((ROOT / page).read_text())


@pytest.mark.parametrize("page", PAGES)
def test_python_blocks_run(page, capsys):
    blocks = python_blocks(page)
    assert blocks, f"{page} has no python block"
    namespace = {"__name__": f"docs_example_{Path(page).stem}"}
    for number, code in enumerate(blocks, 1):
        exec(compile(code, f"{page}, python block {number}", "exec"), namespace)
    assert capsys.readouterr().out                      # the examples print what they compute


def test_architecture_page_covers_the_data_path_and_is_linked():
    text = (ROOT / "docs/architecture.md").read_text()
    steps = re.findall(r"^## \d\. (\w+)", text, re.MULTILINE)
    assert steps == ["Surface", "Elastic", "Interaction", "Solve", "Result", "Study", "Friction"]
    assert len(python_blocks("docs/architecture.md")) == len(steps)
    assert "docs/architecture.md" in (ROOT / "README.md").read_text()
