"""Sphinx configuration of the API reference: a front page (``index.rst``) with the top-level names and one
autosummary table per stage, and one page per public module of ``surfaces`` and ``roughcontact``, generated from
the numpydoc docstrings (autodoc + napoleon + autosummary). Build it with warnings as errors:

    python -m sphinx -W --keep-going -b html docs/reference/api docs/reference/api/_build

(``tests/test_api_reference.py`` runs the same build with the ``dummy`` builder, which reads every docstring
and reports the same warnings without writing pages.)
"""
import importlib
import pkgutil
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]
sys.path.insert(0, str(ROOT))

project = "roughcontact"
author = "roughcontact developers"
extensions = ["sphinx.ext.autodoc", "sphinx.ext.autosummary", "sphinx.ext.napoleon", "sphinx.ext.mathjax"]
autosummary_generate = False                   # the tables link to the module pages; no page per object
napoleon_google_docstring = False
napoleon_numpy_docstring = True
autodoc_member_order = "bysource"
autodoc_typehints = "none"                     # the docstrings state types and units
exclude_patterns = ["_build"]
html_theme = "alabaster"
html_title = "roughcontact API reference"
PACKAGES = ("surfaces", "roughcontact")


def public_modules():
    """Every importable module of the two packages whose dotted name has no private part."""
    names = []
    for package in PACKAGES:
        names.append(package)
        module = importlib.import_module(package)
        for info in pkgutil.walk_packages(module.__path__, prefix=f"{package}."):
            if not any(part.startswith("_") for part in info.name.split(".")):
                names.append(info.name)
    return sorted(names)


def module_page(name):
    """A module's page: its docstring, and for a module (not a package, whose names its modules document) the
    members it defines."""
    title = f"``{name}``"
    lines = [title, "=" * len(title), "", f".. automodule:: {name}"]
    if not hasattr(importlib.import_module(name), "__path__"):
        lines.append("   :members:")
    return "\n".join(lines) + "\n"


def write_pages(app):
    """Write ``generated/<module>.rst`` per public module and the table of contents they hang from."""
    out = Path(app.srcdir) / "generated"
    out.mkdir(exist_ok=True)
    names = public_modules()
    for name in names:
        page = out / f"{name}.rst"
        text = module_page(name)
        if not page.exists() or page.read_text() != text:
            page.write_text(text)
    for stale in set(out.glob("*.rst")) - {out / f"{name}.rst" for name in names}:
        stale.unlink()


#: spans where reStructuredText takes a backslash literally: inline literals and math roles
VERBATIM = re.compile(r"(``.+?``|:math:`[^`]+`)")


def literal_bars(app, what, name, obj, options, lines):
    """The docstrings write |x| for an absolute value or norm, as in the physics; reStructuredText would read a
    substitution. Escape every bar outside inline literals and math (no docstring uses substitutions)."""
    for index, line in enumerate(lines):
        parts = VERBATIM.split(line)
        lines[index] = "".join(part if number % 2 else part.replace("|", r"\|") for number, part in enumerate(parts))


def setup(app):
    app.connect("builder-inited", write_pages)
    app.connect("autodoc-process-docstring", literal_bars)
