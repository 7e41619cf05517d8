"""The package's imports run one way: from a layer to the layers below it, never up and never in a circle.

Every ``.py`` file under ``roughcontact/`` is parsed (``ast``, nothing is imported) and every import of a
roughcontact module is collected, at module level and inside functions, together with the names that a lazy
package ``__init__`` maps to its submodules (``_LAZY``). The layers (``docs/guide/architecture.md``, "Where the code
lives"):

    0  surfaces, roughcontact._version
    1  fft, io, electrostatics, reference     (FFT backends, results on disk, the stack's field, analytic solutions)
    2  body, interactions                      (the elastic body, the interaction laws)
    3  solvers, macro                          (contact solvers; the seed's macroscopic model)
    4  study, paper, fe                        (the fingerpad study; the seed's figures; its FE fingertip)
    5  cli, roughcontact/__init__             (the command; the lazy public API)

The checks: each module has a layer; no import goes to a higher layer; the import graph has no cycle (modules
and package ``__init__`` files as nodes); an import inside a function is of a third-party (optional or heavy)
module only, never of roughcontact or surfaces; no private name (``_x``, not a dunder) is imported from another
module, in roughcontact or in surfaces (a name two modules share is public, or it moves to the one that uses it).
A new module or package gets its layer in :data:`LAYERS`. And no function is longer than
:data:`LONGEST_FUNCTION` lines.
"""
import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[2] / "roughcontact"
SURFACES = PACKAGE.parent / "surfaces"

#: module name prefix -> layer (the longest matching prefix decides; "roughcontact" is its __init__ alone)
LAYERS = {
    "roughcontact._version": 0,
    "roughcontact.fft": 1, "roughcontact.io": 1, "roughcontact.electrostatics": 1, "roughcontact.reference": 1,
    "roughcontact.body": 2, "roughcontact.interactions": 2,
    "roughcontact.solvers": 3, "roughcontact.macro": 3,
    "roughcontact.study": 4, "roughcontact.paper": 4, "roughcontact.fe": 4,
    "roughcontact.cli": 5, "roughcontact": 5,
}
FIRST_PARTY = ("roughcontact", "surfaces")


def module_name(path: Path, root: Path) -> str:
    parts = list(path.relative_to(root.parent).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def layer_of(module: str, layers=LAYERS):
    """The layer of ``module``: that of the longest prefix in ``layers`` (the bare package name only itself)."""
    matches = [prefix for prefix in layers
               if module == prefix or (module.startswith(prefix + ".") and "." in prefix)]
    return layers[max(matches, key=len)] if matches else None


class Import:
    """One import: ``source`` imports ``target`` (names ``names``), inside a function or not."""

    def __init__(self, source, target, names, in_function, line):
        self.source, self.target, self.names, self.in_function, self.line = source, target, names, in_function, line

    def __repr__(self):
        where = "in a function" if self.in_function else "at module level"
        return f"{self.source}:{self.line} imports {self.target} ({', '.join(self.names) or 'the module'}) {where}"


def collect(root: Path = PACKAGE) -> tuple:
    """``(modules, imports)`` of the package at ``root``: every module's name, and every import of a first-party
    module (relative imports resolved; ``from package import module`` names the module)."""
    files = {module_name(path, root): path for path in sorted(root.rglob("*.py"))}
    imports = []
    for source, path in files.items():
        package = source if path.name == "__init__.py" else source.rpartition(".")[0]
        tree = ast.parse(path.read_text(), str(path))
        functions = {id(node) for scope in ast.walk(tree) if isinstance(scope, (ast.FunctionDef, ast.AsyncFunctionDef))
                     for node in ast.walk(scope)}
        for node in ast.walk(tree):
            in_function = id(node) in functions
            if isinstance(node, ast.Import):
                for alias in node.names:
                    imports.append(Import(source, alias.name, (), in_function, node.lineno))
            elif isinstance(node, ast.ImportFrom):
                base = node.module or ""
                if node.level:
                    anchor = package.split(".")[:len(package.split(".")) - node.level + 1]
                    base = ".".join(anchor + ([node.module] if node.module else []))
                names = [alias.name for alias in node.names]
                submodules = [name for name in names if f"{base}.{name}" in files]
                for name in submodules:
                    imports.append(Import(source, f"{base}.{name}", (), in_function, node.lineno))
                rest = [name for name in names if name not in submodules]
                if rest:
                    imports.append(Import(source, base, tuple(rest), in_function, node.lineno))
            elif (isinstance(node, ast.Assign) and path.name == "__init__.py" and not in_function
                  and any(isinstance(t, ast.Name) and t.id == "_LAZY" for t in node.targets)):
                for value in node.value.values:                 # lazy_attributes: name -> submodule
                    if isinstance(value, ast.Call):             # **dict.fromkeys([names], submodule)
                        value = value.args[-1]
                    imports.append(Import(source, f"{source}.{value.value}", (), False, node.lineno))
    first_party = [i for i in imports if i.target.split(".")[0] in FIRST_PARTY]
    return set(files), first_party


def problems(root: Path = PACKAGE, layers=LAYERS) -> list:
    """Everything that breaks the layers' rules of the module docstring, one string each (private names:
    :func:`private_imports`)."""
    modules, imports = collect(root)
    found = [f"{module} has no layer" for module in sorted(modules) if layer_of(module, layers) is None]
    inside = [i for i in imports if i.target.split(".")[0] == "roughcontact"]
    for i in inside:
        source_layer, target_layer = layer_of(i.source, layers), layer_of(i.target, layers)
        if None not in (source_layer, target_layer) and target_layer > source_layer:
            found.append(f"upward (layer {source_layer} -> {target_layer}): {i}")
        if i.target not in modules:
            found.append(f"no such module: {i}")
    found += [f"first-party import inside a function: {i}" for i in imports if i.in_function]
    graph = {}
    for i in inside:
        graph.setdefault(i.source, set()).add(i.target)
    found += [f"import cycle: {' -> '.join(cycle)}" for cycle in cycles(graph)]
    return found


def private_imports(root: Path = PACKAGE) -> list:
    """Every import of a private name (``_x``, not a dunder) from another module of the package at ``root``."""
    _, imports = collect(root)
    return [f"private name across modules: {i}" for i in imports
            if any(name.startswith("_") and not name.startswith("__") for name in i.names)]


def cycles(graph: dict) -> list:
    """One cycle through each strongly connected component with more than one node (or a self-import)."""
    index, low, stack, on_stack, found, counter = {}, {}, [], set(), [], [0]

    def visit(node):                                           # Tarjan
        index[node] = low[node] = counter[0]
        counter[0] += 1
        stack.append(node)
        on_stack.add(node)
        for target in sorted(graph.get(node, ())):
            if target not in index:
                visit(target)
                low[node] = min(low[node], low[target])
            elif target in on_stack:
                low[node] = min(low[node], index[target])
        if low[node] == index[node]:
            component = []
            while True:
                member = stack.pop()
                on_stack.discard(member)
                component.append(member)
                if member == node:
                    break
            if len(component) > 1 or node in graph.get(node, ()):
                found.append(sorted(component) + [sorted(component)[0]])

    for node in sorted(graph):
        if node not in index:
            visit(node)
    return found


def test_imports_run_down_the_layers():
    found = problems()
    assert not found, "\n".join(found)


def test_no_private_name_crosses_a_module():
    found = private_imports(PACKAGE) + private_imports(SURFACES)
    assert not found, "\n".join(found)


def test_every_subpackage_is_seen():
    # the parser must see the package as it is: every subpackage, and the imports that dissolved the old circles
    modules, imports = collect()
    assert {"roughcontact.body.elastic", "roughcontact.solvers.dispatch", "roughcontact.study.coupled",
            "roughcontact.io.results", "roughcontact.electrostatics.stack"} <= modules
    edges = {(i.source, i.target) for i in imports}
    assert ("roughcontact.solvers.dispatch", "roughcontact.solvers.projected_cg_gap") in edges
    assert ("roughcontact.solvers.dispatch", "roughcontact.solvers.polonsky_keer") in edges
    assert ("roughcontact.study.run", "roughcontact.study.coupled") in edges
    assert ("roughcontact", "roughcontact.solvers") in edges                  # the lazy public API


@pytest.fixture
def bad_package(tmp_path):
    """A package with one of each fault: an upward import, a cycle, a first-party import inside a function and a
    private name taken from another package and from another module of the same package."""
    root = tmp_path / "roughcontact"
    files = {
        "__init__.py": "_LAZY = {'solve': 'solvers.run'}\n",
        "io/__init__.py": "",
        "io/results.py": "from ..solvers.run import solve\n",                       # layer 1 -> 3
        "io/provenance.py": "_private = 1\n",
        "solvers/__init__.py": "",
        "solvers/run.py": "from .steps import step\n\ndef solve():\n    from ..io import provenance\n",
        "solvers/steps.py": ("from .run import solve\nfrom ..io.provenance import _private\nfrom .run import _step\n"
                             "from .._version import __version__\n"),
        "_version.py": "__version__ = '0'\n",
    }
    for name, text in files.items():
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        (root / name).write_text(text)
    return root


def test_checks_fail_on_each_fault(bad_package):
    found = "\n".join(problems(bad_package))
    assert "upward (layer 1 -> 3): roughcontact.io.results:1 imports roughcontact.solvers.run" in found
    assert "import cycle: roughcontact.solvers.run -> roughcontact.solvers.steps -> roughcontact.solvers.run" in found
    assert "first-party import inside a function: roughcontact.solvers.run:4 imports roughcontact.io.provenance" in found
    private = "\n".join(private_imports(bad_package))
    assert "private name across modules: roughcontact.solvers.steps:2 imports roughcontact.io.provenance" in private
    assert "roughcontact.solvers.steps:3 imports roughcontact.solvers.run (_step)" in private
    assert len(private.splitlines()) == 2 and "__version__" not in private          # a dunder is not private
    unassigned = problems(bad_package, layers={k: v for k, v in LAYERS.items() if k != "roughcontact.io"})
    assert "roughcontact.io.results has no layer" in unassigned


#: The longest a function may be, in lines from its ``def`` to its last line (docstring included): a longer one
#: does several jobs and splits into named steps.
LONGEST_FUNCTION = 120


def long_functions(*roots, limit: int = LONGEST_FUNCTION) -> list:
    """``path:line name (n lines)`` of every function or method under ``roots`` longer than ``limit`` lines."""
    found = []
    for root in roots:
        for path in sorted(root.rglob("*.py")):
            for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
                if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                    length = node.end_lineno - node.lineno + 1
                    if length > limit:
                        found.append(f"{path.relative_to(root.parent)}:{node.lineno} {node.name} ({length} lines)")
    return found


def test_no_function_is_longer_than_the_limit():
    assert not long_functions(PACKAGE, SURFACES), "\n".join(long_functions(PACKAGE, SURFACES))


def test_the_length_check_finds_a_long_function(tmp_path):
    root = tmp_path / "roughcontact"
    root.mkdir()
    (root / "long.py").write_text("def short():\n    pass\n\n\ndef long():\n" + "    x = 1\n" * LONGEST_FUNCTION)
    assert long_functions(root) == [f"roughcontact/long.py:5 long ({LONGEST_FUNCTION + 1} lines)"]
