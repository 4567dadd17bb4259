"""Reproductions of published papers' own methods, beside the rigorous solver.

- :mod:`powergraph.methods.wang2021`: Wang (2021)'s split/virtual power efficiency of an
  RV reducer (``powergraph solve MODEL --method wang2021``), with its report
  (:mod:`~powergraph.methods.wang2021_report`) and equations
  (:mod:`~powergraph.methods.wang2021_equations`);
- :mod:`powergraph.methods.method_comparison`: that method and the virtual-power method
  side by side, and the equivalent cycloid-mesh efficiency (not to be confused with
  :mod:`powergraph.analyses.compare`, the table of several trains);
- :mod:`powergraph.methods.figures`: the data of the paper's Figs. 12–13 by both methods;
- :mod:`powergraph.methods.tuning`: the mesh efficiency at which a solve meets a target.

Inside the package the modules import one way only (roles, equations, tuning and
report before ``wang2021``, and ``wang2021`` before ``method_comparison``).

Imports are lazy so ``powergraph solve`` loads only what it uses.

Examples
--------
>>> from powergraph.methods import solve_wang2021          # doctest: +SKIP
"""
from __future__ import annotations

__all__ = ["MethodComparison", "PaperEquations", "RVRoles", "Wang2021Result",
           "compare_methods", "equivalent_cycloid_efficiency", "find_rv_roles",
           "paper_equations", "solve_wang2021"]

_HOME = {"MethodComparison": "method_comparison", "compare_methods": "method_comparison",
         "equivalent_cycloid_efficiency": "method_comparison", "RVRoles": "rv_roles",
         "find_rv_roles": "rv_roles", "PaperEquations": "wang2021_equations",
         "Wang2021Result": "wang2021", "paper_equations": "wang2021",
         "solve_wang2021": "wang2021"}


def __getattr__(name: str):
    if name in _HOME:
        import importlib

        return getattr(importlib.import_module(f"powergraph.methods.{_HOME[name]}"), name)
    raise AttributeError(f"module 'powergraph.methods' has no attribute {name!r}")
