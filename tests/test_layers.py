"""The package follows its layers: read every module's import-time imports with ``ast``.

Layers, earliest first (docs/architecture.md)::

    0 base        powergraph (the package facade: errors at import, the rest lazily),
                  powergraph.errors, powergraph.records, powergraph.result, powergraph.format (numbers for a
                  person), powergraph.display (repr, HTML, DataFrames), powergraph.gears
                  (involute geometry and mesh-loss physics that the model, statics and
                  analyses share)
    1 model       powergraph.model.*            (YAML, validation, units, graph)
    2 kinematics  powergraph.kinematics.*
    3 statics     powergraph.statics.*, powergraph.testing (checks of statics results),
                  powergraph.testing_trains (random valid trains for tests and benchmarks)
    4 methods     powergraph.methods.*          } the same rank: they may use each other,
    4 analyses    powergraph.analyses.*         } but only without cycles
    4 exchange    powergraph.exchange.*         (REXS and VECTO writers; the REXS reader is
                                                 the model layer's)
    5 plot        powergraph.plot.*             (including the pure layout, plot.layout)
    6 cli         powergraph.cli.*, powergraph.__main__ (``python -m powergraph``)

The import graph holds the imports that run when a module is imported: statements of the
module body (also inside ``try``/``if``), but not ``if TYPE_CHECKING:`` blocks nor imports
inside functions, which are lazy. Importing ``a.b.c`` also runs the packages ``a`` and
``a.b`` first; those parent-package runs are not edges (each package's own imports are).
That graph must follow the layers and have no cycle.

Counting every import (lazy and ``if TYPE_CHECKING:`` ones too) there must be no circle
either, but for ``CIRCLES_ALLOWED``: a result's ``text_report()`` or ``plot()`` may import
its report or drawing module lazily, and that module never imports the result's module
back (it works on the object it is given; annotations name the type as text).

Lazy imports (inside functions) must follow the layers too, but for an explicit allow-list
(``LAZY_ALLOWED``): a result's ``plot()`` method importing its drawing function from
:mod:`powergraph.plot`, the package facade's lazy attributes, and the command line (the
last layer). So no module of model, kinematics, statics or gears reaches the analyses,
the methods, the plots or the command line, even lazily.
"""
from __future__ import annotations

import ast
from functools import lru_cache
from pathlib import Path

import networkx as nx
import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "powergraph"

LAYERS = (("powergraph.cli", 6), ("powergraph.__main__", 6), ("powergraph.plot", 5), ("powergraph.methods", 4),
          ("powergraph.analyses", 4), ("powergraph.exchange", 4), ("powergraph.testing", 3),
          ("powergraph.testing_trains", 3), ("powergraph.statics", 3),
          ("powergraph.kinematics", 2), ("powergraph.model", 1), ("powergraph.errors", 0), ("powergraph.records", 0),
          ("powergraph.result", 0), ("powergraph.format", 0), ("powergraph.display", 0), ("powergraph.gears", 0), ("powergraph", 0))


def layer_of(module: str) -> int:
    """The layer of a dotted module name (first matching prefix of LAYERS)."""
    for prefix, layer in LAYERS:
        if module == prefix or module.startswith(prefix + "."):
            return layer
    raise AssertionError(f"{module}: no layer assigned")


def module_files() -> dict[str, Path]:
    """Dotted name -> file of every module of the package."""
    out = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts.pop()
        out[".".join(parts)] = path
    return out


@lru_cache(maxsize=None)
def _parsed(path: Path) -> ast.Module:
    return ast.parse(path.read_text(encoding="utf-8"), str(path))


def _is_type_checking(test: ast.expr) -> bool:
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or \
           (isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING")


def _import_time_statements(body: list[ast.stmt]):
    """Import statements that run at import: the body and its try/if/with blocks."""
    for node in body:
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            yield node
        elif isinstance(node, ast.If):
            if not _is_type_checking(node.test):
                yield from _import_time_statements(node.body)
            yield from _import_time_statements(node.orelse)
        elif isinstance(node, ast.Try):
            for block in (node.body, node.orelse, node.finalbody,
                          *(h.body for h in node.handlers)):
                yield from _import_time_statements(block)
        elif isinstance(node, ast.With):
            yield from _import_time_statements(node.body)


def _imported(node: ast.Import | ast.ImportFrom, package: str, known: set[str]) -> set[str]:
    """The powergraph modules one import statement loads (of ``known``)."""
    if isinstance(node, ast.Import):
        names = [alias.name for alias in node.names]
    else:
        base = node.module or ""
        if node.level:
            anchor = package.split(".")[:len(package.split(".")) - node.level + 1]
            base = ".".join(anchor + ([base] if base else []))
        subs = [f"{base}.{alias.name}" for alias in node.names]
        # ``from package import submodule`` runs the package's __init__ first, as
        # any import of a submodule does; like those parent-package runs, it is not
        # counted as an edge to the package (its own imports are counted there).
        names = subs + ([base] if any(sub not in known for sub in subs) else [])
    return {name for name in names if name in known}


def imports_of(module: str, path: Path, known: set[str]) -> set[str]:
    """powergraph modules that ``module`` imports at import time."""
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    found = set()
    for node in _import_time_statements(_parsed(path).body):
        found |= _imported(node, package, known)
    found.discard(module)
    return found


def every_import_of(module: str, path: Path, known: set[str]) -> set[str]:
    """powergraph modules that ``module`` names in any import statement: at import time,
    inside a function (lazy) or under ``if TYPE_CHECKING:``."""
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    found = set()
    for node in ast.walk(_parsed(path)):
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            found |= _imported(node, package, known)
    found.discard(module)
    return found


def _absolute(node: ast.ImportFrom | ast.Import, package: str) -> list[str]:
    """The dotted names an import statement names (the module and, for ``from``, each
    ``module.name``)."""
    if isinstance(node, ast.Import):
        return [alias.name for alias in node.names]
    base = node.module or ""
    if node.level:
        anchor = package.split(".")[:len(package.split(".")) - node.level + 1]
        base = ".".join(anchor + ([base] if base else []))
    return [base] + [f"{base}.{alias.name}" for alias in node.names]


def lazy_imports_of(module: str, path: Path, known: set[str]) -> set[tuple[str, str]]:
    """(function, imported module) of every powergraph import inside a function of
    ``module``; the function is its dotted name (``Class.method``, ``f.inner``)."""
    tree = _parsed(path)
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    found = set()

    def walk(node: ast.AST, scope: str, in_function: bool) -> None:
        for child in ast.iter_child_nodes(node):
            if isinstance(child, (ast.Import, ast.ImportFrom)) and in_function:
                found.update((scope, name) for name in _absolute(child, package)
                             if name in known and name != module)
            named = isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef))
            inner = f"{scope}.{child.name}".lstrip(".") if named else scope
            walk(child, inner, in_function or isinstance(
                child, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)))

    walk(tree, "", False)
    return found


#: Lazy imports of a later layer that are allowed: (importing module or package, function
#: name or "" for any, imported module prefix). A result's ``plot()`` delegates to its
#: drawing function; the package facade resolves its lazy attributes.
LAZY_ALLOWED = (("powergraph", "plot", "powergraph.plot"),
                ("powergraph", "__getattr__", "powergraph"))


def _lazy_allowed(module: str, function: str, target: str) -> bool:
    last = function.rpartition(".")[2]
    for where, name, what in LAZY_ALLOWED:
        if (where == "powergraph" and name == "__getattr__") and module != "powergraph":
            continue                             # only the facade's own __getattr__
        if (module == where or module.startswith(where + ".")) and last == name \
                and (target == what or target.startswith(what + ".")):
            return True
    return False


def wrong_lazy_imports() -> list[str]:
    """Every import inside a function that reaches a later layer and is not allowed."""
    files = module_files()
    known = set(files)
    return sorted(f"{module}.{function} (layer {layer_of(module)}) imports {target} "
                  f"(layer {layer_of(target)})"
                  for module, path in files.items()
                  for function, target in lazy_imports_of(module, path, known)
                  if layer_of(target) > layer_of(module)
                  and not _lazy_allowed(module, function, target))


def import_graph() -> nx.DiGraph:
    files = module_files()
    graph = nx.DiGraph()
    graph.add_nodes_from(files)
    for module, path in files.items():
        graph.add_edges_from((module, target) for target in imports_of(module, path, set(files)))
    return graph


@pytest.fixture(scope="module")
def graph() -> nx.DiGraph:
    return import_graph()


def test_every_module_has_a_layer(graph) -> None:
    assert len(graph) > 50                     # the walk found the package
    for module in graph:
        layer_of(module)


def test_the_checker_sees_imports(graph) -> None:
    """Known import-time edges are found (so the two tests below can fail)."""
    assert graph.has_edge("powergraph.statics.solver", "powergraph.kinematics")
    assert graph.has_edge("powergraph.plot.power_flow", "powergraph.plot.layout.view")
    assert graph.has_edge("powergraph.methods.method_comparison", "powergraph.methods.wang2021")


def test_lazy_and_type_checking_imports_do_not_count(tmp_path) -> None:
    source = ("from typing import TYPE_CHECKING\n"
              "from powergraph.errors import ModelError\n"
              "if TYPE_CHECKING:\n    from powergraph.plot import power_flow\n"
              "try:\n    import powergraph.model\nexcept ImportError:\n    pass\n"
              "def f():\n    from powergraph.cli import main\n")
    path = tmp_path / "probe.py"
    path.write_text(source)
    known = {"powergraph.errors", "powergraph.plot", "powergraph.plot.power_flow",
             "powergraph.model", "powergraph.cli", "powergraph.cli.main"}
    assert imports_of("powergraph.statics.probe", path, known) == {"powergraph.errors",
                                                                   "powergraph.model"}


def test_no_module_imports_a_later_layer(graph) -> None:
    wrong = sorted(f"{a} (layer {layer_of(a)}) imports {b} (layer {layer_of(b)})"
                   for a, b in graph.edges if layer_of(b) > layer_of(a))
    assert wrong == []


def test_import_graph_has_no_cycles(graph) -> None:
    cycles = list(nx.simple_cycles(graph))
    assert cycles == []
    assert nx.is_directed_acyclic_graph(graph)


#: Circles through lazy or TYPE_CHECKING imports still allowed, each a set of modules.
CIRCLES_ALLOWED: tuple = ()


def circles() -> list[list[str]]:
    """Groups of modules that reach each other through any imports (lazy and TYPE_CHECKING
    ones too), each sorted, but for CIRCLES_ALLOWED."""
    files = module_files()
    graph = nx.DiGraph()
    graph.add_nodes_from(files)
    for module, path in files.items():
        graph.add_edges_from((module, target)
                             for target in every_import_of(module, path, set(files)))
    return sorted(sorted(group) for group in nx.strongly_connected_components(graph)
                  if len(group) > 1 and group not in CIRCLES_ALLOWED)


def test_every_import_counts_for_circles(tmp_path) -> None:
    source = ("from typing import TYPE_CHECKING\n"
              "if TYPE_CHECKING:\n    from powergraph.statics.result import PowerFlowResult\n"
              "def f():\n    from powergraph.plot import power_flow\n")
    path = tmp_path / "probe.py"
    path.write_text(source)
    known = {"powergraph.statics.result", "powergraph.plot", "powergraph.plot.power_flow"}
    assert every_import_of("powergraph.statics.probe", path, known) == {
        "powergraph.statics.result", "powergraph.plot.power_flow"}


def test_no_circles_through_lazy_or_type_checking_imports() -> None:
    """A result's method may import its report or its drawing function lazily; that
    module works on the object it is given and never imports the result's module back,
    not even under ``if TYPE_CHECKING:`` (its annotations name the type as text). What
    both need (labels, a shared helper) sits in a module lower down."""
    assert circles() == []


def test_the_lazy_checker_sees_imports_inside_functions(tmp_path) -> None:
    source = ("def f():\n    from powergraph.analyses import sweep\n"
              "class R:\n    def plot(self):\n        from powergraph.plot import power_flow\n"
              "    def g(self):\n        import powergraph.cli.main\n"
              "from powergraph.errors import ModelError\n")
    path = tmp_path / "probe.py"
    path.write_text(source)
    known = {"powergraph.analyses", "powergraph.analyses.sweep", "powergraph.plot",
             "powergraph.plot.power_flow", "powergraph.cli.main", "powergraph.errors"}
    found = lazy_imports_of("powergraph.statics.probe", path, known)
    assert found == {("f", "powergraph.analyses"), ("f", "powergraph.analyses.sweep"),
                     ("R.plot", "powergraph.plot"), ("R.plot", "powergraph.plot.power_flow"),
                     ("R.g", "powergraph.cli.main")}
    assert _lazy_allowed("powergraph.statics.probe", "R.plot", "powergraph.plot.power_flow")
    assert not _lazy_allowed("powergraph.statics.probe", "f", "powergraph.analyses.sweep")
    assert not _lazy_allowed("powergraph.statics.probe", "R.g", "powergraph.cli.main")
    assert not _lazy_allowed("powergraph.statics.probe", "__getattr__", "powergraph.plot")


def test_no_function_imports_a_later_layer() -> None:
    """Imports inside functions follow the layers too, but for LAZY_ALLOWED; in
    particular model, kinematics, statics and gears never reach analyses, methods, plot
    or cli (loading a model with tolerances does not pull in the sweep)."""
    assert wrong_lazy_imports() == []


MODEL_WITH_TOLERANCES = """\
name: pair
components: {0: {role: frame}, 1: {teeth: 20}, 2: {teeth: 60}}
links: [{type: mesh, between: [1, 2], efficiency: 0.98}]
ports: [{component: 1, role: input}, {component: 2, role: output}]
tolerances:
  links.0.efficiency: {distribution: uniform, min: 0.97, max: 0.99}
"""


def test_loading_a_model_with_tolerances_imports_no_later_layer() -> None:
    """In a fresh interpreter, a model with ``tolerances:`` loads without importing the
    statics, the analyses, the methods or the plots (the block is parsed in the model)."""
    import subprocess
    import sys

    code = ("import sys\nfrom powergraph.model import loads_model\n"
            f"m = loads_model({MODEL_WITH_TOLERANCES!r})\nassert len(m.tolerances) == 1\n"
            "print(sorted(n for n in sys.modules if n.startswith(('powergraph.analyses', "
            "'powergraph.statics', 'powergraph.methods', 'powergraph.plot'))))\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, cwd=PACKAGE.parent)
    assert out.stdout.strip() == "[]"
