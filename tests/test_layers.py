"""The package follows its layers: read every module's import-time imports with ``ast``.

Layers, earliest first (docs/architecture.md)::

    0 base        powergraph (the package facade: errors at import, the rest lazily),
                  powergraph.errors, powergraph.result, powergraph.format (numbers for a
                  person), powergraph.display (repr, HTML, DataFrames), powergraph.gears
                  (involute geometry and mesh-loss physics that the model, statics and
                  analyses share)
    1 model       powergraph.model.*            (YAML, validation, units, graph)
    2 kinematics  powergraph.kinematics.*
    3 statics     powergraph.statics.*, powergraph.testing (checks of statics results),
                  powergraph.testing_trains (random valid trains for tests and benchmarks)
    4 methods     powergraph.methods.*          } the same rank: they may use each other,
    4 analyses    powergraph.analyses.*         } but only without cycles
    5 plot        powergraph.plot.*             (including the pure layout, plot.layout)
    6 cli         powergraph.cli.*, powergraph.__main__ (``python -m powergraph``)

Only imports that run when a module is imported count: statements of the module body
(also inside ``try``/``if``), but not ``if TYPE_CHECKING:`` blocks nor imports inside
functions, which are lazy. Importing ``a.b.c`` also runs the packages ``a`` and ``a.b``
first; those parent-package runs are not edges (each package's own imports are). The one
sanctioned lazy crossing is a result's ``plot()`` method importing its drawing function
from :mod:`powergraph.plot`.
"""
from __future__ import annotations

import ast
from pathlib import Path

import networkx as nx
import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "powergraph"

LAYERS = (("powergraph.cli", 6), ("powergraph.__main__", 6), ("powergraph.plot", 5), ("powergraph.methods", 4),
          ("powergraph.analyses", 4), ("powergraph.testing", 3),
          ("powergraph.testing_trains", 3), ("powergraph.statics", 3),
          ("powergraph.kinematics", 2), ("powergraph.model", 1), ("powergraph.errors", 0),
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


def imports_of(module: str, path: Path, known: set[str]) -> set[str]:
    """powergraph modules that ``module`` imports at import time."""
    tree = ast.parse(path.read_text(encoding="utf-8"), str(path))
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    found = set()
    for node in _import_time_statements(tree.body):
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
        found |= {name for name in names if name in known}
    found.discard(module)
    return found


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
