"""The API reference (docs/reference/api, Sphinx autodoc + autosummary + napoleon) builds without a warning, and its
front page is in xarray's shape: the top-level names with their docstrings first, then one autosummary table per
stage of the data path, each row a name with its docstring's summary. The ``dummy`` builder reads every docstring,
and so reports every docutils and cross-reference warning of the HTML build, without writing pages; the front
page's content is read from its pickled doctree."""
import importlib
import inspect
import pickle
import re
from pathlib import Path

import pytest

API = Path(__file__).resolve().parents[1] / "docs" / "reference" / "api"
#: the names most programs need, documented in full at the top of the front page (where each is importable from)
TOP_LEVEL = ("roughcontact.solve_contact", "roughcontact.electrostatics.solve_field",
             "roughcontact.ElectrostaticInteraction", "roughcontact.DielectricStack", "roughcontact.run_study",
             "roughcontact.study.open_results", "surfaces.HeightField", "surfaces.read_topography")
#: the stages of the data path, each a section with one autosummary table
STAGES = ("Surfaces", "Electrostatics", "Elastic bodies", "Interaction laws", "Solvers", "The fingerpad study",
          "The macroscopic model", "Results on disk", "Independent references")


def words(text):
    """The words of a docstring or of its rendering, without markup (roles, literals, emphasis)."""
    return re.findall(r"[A-Za-z0-9]+", re.sub(r":\w+:", "", text))


@pytest.fixture(scope="module")
def build(tmp_path_factory):
    """Build the reference once with warnings as errors; ``(status, warnings, doctrees)``."""
    build = pytest.importorskip("sphinx.cmd.build", reason="the API reference needs Sphinx (the test extra)")
    out = tmp_path_factory.mktemp("api")
    warnings = out / "warnings.txt"
    status = build.build_main(["-E", "-W", "--keep-going", "-q", "-b", "dummy", "-w", str(warnings),
                               "-d", str(out / "doctrees"), str(API), str(out / "out")])
    return status, warnings.read_text(), out / "doctrees"


@pytest.mark.slow                                          # 10 CPU s: autodoc inspects every module
@pytest.mark.filterwarnings("ignore:The mapping interface for autodoc options:PendingDeprecationWarning")
def test_api_reference_builds_without_warnings(build):
    status, warnings, doctrees = build
    assert status == 0, warnings
    pages = {page.stem for page in (API / "generated").glob("*.rst")}
    assert {"surfaces", "roughcontact", "roughcontact.solvers.dispatch", "roughcontact.study.run"} <= pages
    assert not any(part.startswith("_") for page in pages for part in page.split("."))


@pytest.mark.slow
@pytest.mark.filterwarnings("ignore:The mapping interface for autodoc options:PendingDeprecationWarning")
def test_front_page_lists_the_top_level_names_and_a_table_per_stage(build):
    from docutils import nodes
    from sphinx import addnodes
    status, warnings, doctrees = build
    assert status == 0, warnings
    front = pickle.loads((doctrees / "index.doctree").read_bytes())
    documented = {node["ids"][0]: node.parent for node in front.findall(addnodes.desc_signature) if node["ids"]}
    assert list(documented)[:len(TOP_LEVEL)] == list(TOP_LEVEL)            # first, in this order
    for name in TOP_LEVEL:
        module, _, attribute = name.rpartition(".")
        docstring = inspect.getdoc(getattr(importlib.import_module(module), attribute))
        content = next(documented[name].findall(addnodes.desc_content)).astext()
        summary = words(docstring.split("\n\n")[0])
        assert len(summary) >= 5 and " ".join(summary) in " ".join(words(content)), name
    sections = {section[0].astext(): section for section in front.findall(nodes.section)}
    for stage in STAGES:
        rows = list(sections[stage].findall(nodes.row))
        assert len(rows) >= 5, stage
        for row in rows:                                    # a name and its docstring's summary line
            name, summary = (entry.astext() for entry in row.findall(nodes.entry))
            assert name and len(words(summary)) >= 3, (stage, name)
