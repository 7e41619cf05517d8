"""The API reference (docs/reference/api, Sphinx autodoc + napoleon over every public module) builds without a
warning. The ``dummy`` builder reads every docstring, and so reports every docutils and cross-reference
warning of the HTML build, without writing pages."""
from pathlib import Path

import pytest

API = Path(__file__).resolve().parents[1] / "docs" / "reference" / "api"


@pytest.mark.slow                                          # 6 CPU s: autodoc inspects every module
@pytest.mark.filterwarnings("ignore:The mapping interface for autodoc options:PendingDeprecationWarning")
def test_api_reference_builds_without_warnings(tmp_path):
    build = pytest.importorskip("sphinx.cmd.build", reason="the API reference needs Sphinx (the test extra)")
    warnings = tmp_path / "warnings.txt"
    status = build.build_main(["-E", "-W", "--keep-going", "-q", "-b", "dummy", "-w", str(warnings),
                               "-d", str(tmp_path / "doctrees"), str(API), str(tmp_path / "out")])
    assert status == 0, warnings.read_text()
    pages = {page.stem for page in (API / "generated").glob("*.rst")}
    assert {"surfaces", "roughcontact", "roughcontact.solvers.dispatch", "roughcontact.study.run"} <= pages
    assert not any(part.startswith("_") for page in pages for part in page.split("."))
