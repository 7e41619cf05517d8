"""Every Python block of README.md and of every page under docs/ runs, in order, in one namespace per page.

A block that cannot run in the tests (minutes of solves) is preceded by the line
``<!-- not run by the tests: <why, and which test covers the same code> -->``; the reason is required.
Blocks run in a fresh working directory. A page whose blocks read ``roughcontact-results/`` (what
``roughcontact run`` writes) finds there the results of a tiny study (32² patches).
"""
import re
import runpy
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
BLOCK = re.compile(r"^(?:(<!--[^\n]*-->)\n)?```python\n(.*?)^```", re.MULTILINE | re.DOTALL)
NOT_RUN = re.compile(r"<!-- not run by the tests: (.{20,}) -->")
PAGES = sorted(str(page.relative_to(ROOT)) for page in (ROOT / "docs").rglob("*.md")) + ["README.md"]
#: the modules of the optional extras (pyproject.toml): a page that needs one is skipped without it
OPTIONAL = {"felupe", "tensortrax", "skfem", "pyamg", "tamaas", "ContactMechanics", "distributed", "SurfaceTopography"}
#: the results a page reads from ``roughcontact run --out roughcontact-results`` come from the study tests'
#: tiny scene (32² patches), at the 0 and 200 V the tutorial reads
TINY_STUDY = runpy.run_path(str(ROOT / "tests" / "roughcontact" / "study" / "study_scenes.py"))["TINY"].replace(
    "voltages = [0.0, 150.0]", "voltages = [0.0, 200.0]")


def python_blocks(page):
    """``(code, reason)`` per Python block of ``page``; ``reason`` is None for a block that runs."""
    blocks = []
    for comment, code in BLOCK.findall((ROOT / page).read_text()):
        marker = NOT_RUN.fullmatch(comment) if comment else None
        assert not comment or marker or "not run" not in comment, f"{page}: a not-run marker without its reason"
        blocks.append((code, marker.group(1) if marker else None))
    return blocks


def write_tiny_results(directory):
    """``directory/roughcontact-results/results.nc`` of the tiny study (what ``roughcontact run`` writes)."""
    from roughcontact.study.dataset import dataset
    from roughcontact.study.run import run_study
    from roughcontact.study.scene import load_scene
    out = directory / "roughcontact-results"
    out.mkdir()
    dataset(run_study(load_scene(text=TINY_STUDY, preset="draft"), workers=1)).to_netcdf(
        out / "results.nc", engine="h5netcdf")


@pytest.mark.parametrize("page", [page for page in PAGES if any(reason is None for code, reason in python_blocks(page))])
def test_python_blocks_run(page, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    blocks = python_blocks(page)
    if any("roughcontact-results/" in code for code, reason in blocks if reason is None):
        write_tiny_results(tmp_path)
    namespace = {"__name__": f"docs_example_{Path(page).stem}"}
    for number, (code, reason) in enumerate(blocks, 1):
        if reason is not None:
            continue
        try:
            exec(compile(code, f"{page}, python block {number}", "exec"), namespace)
        except ModuleNotFoundError as error:
            if error.name.split(".")[0] not in OPTIONAL:
                raise
            pytest.skip(f"{page}, python block {number} needs the optional module {error.name}")


def test_not_run_blocks_are_few():
    """Skipping is the exception: at most one block in ten, over all pages."""
    blocks = [reason for page in PAGES for code, reason in python_blocks(page)]
    assert 10 * sum(reason is not None for reason in blocks) <= len(blocks)


def test_architecture_page_covers_the_data_path_and_is_linked():
    text = (ROOT / "docs/guide/architecture.md").read_text()
    steps = re.findall(r"^## \d\. (\w+)", text, re.MULTILINE)
    assert steps == ["Surface", "Elastic", "Interaction", "Solve", "Result", "Study", "Friction"]
    assert len(python_blocks("docs/guide/architecture.md")) == len(steps)
    assert "docs/index.md" in (ROOT / "README.md").read_text()
    assert "guide/architecture.md" in (ROOT / "docs/index.md").read_text()
