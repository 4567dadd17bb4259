"""powergraph: power flow, losses and efficiency of gear trains described as graphs.

The top level holds the core: :func:`load_model`, :func:`model_from_dict`, :func:`solve`,
:func:`solve_speeds`, the errors, and :class:`Result` (the interface every result offers).
Each other feature has one import path:

- paper methods: :mod:`powergraph.methods` (Wang 2021);
- analyses: :mod:`powergraph.analyses.sweep`, :mod:`~powergraph.analyses.formula`,
  :mod:`~powergraph.analyses.backlash`, :mod:`~powergraph.analyses.cycloid`,
  :mod:`~powergraph.analyses.volume`, :mod:`~powergraph.analyses.compare`;
- drawing: :mod:`powergraph.plot`; test helpers: :mod:`powergraph.testing`.

This module is a facade of the base layer: at import it loads only the errors and the
result protocol; the core functions are imported on first use, so ``import powergraph``
stays cheap for the command line.

Examples
--------
>>> import powergraph as pg
>>> model = pg.load_model("models/rv40e_wang2021.yaml")          # doctest: +SKIP
>>> result = pg.solve(model)                             # doctest: +SKIP
>>> round(result.ratio, 6)                               # doctest: +SKIP
121.0
"""
from __future__ import annotations

from powergraph.errors import (
    KinematicsError,
    MethodNotApplicableError,
    ModelError,
    PowerGraphError,
    SolveError,
    StaticsError,
    UsageError,
)
from powergraph.result import NothingToDrawError, Result

__all__ = [
    "PowerGraphError", "ModelError", "KinematicsError", "StaticsError", "SolveError",
    "MethodNotApplicableError", "UsageError", "NothingToDrawError", "Result", "load_model",
    "model_from_dict", "solve", "solve_speeds",
]
__version__ = "0.1.0"


def __getattr__(name: str):
    # Lazy re-exports keep `import powergraph` cheap for the CLI.
    if name in ("load_model", "model_from_dict"):
        from powergraph import model
        return getattr(model, name)
    if name == "solve_speeds":
        from powergraph.kinematics import solve_speeds
        return solve_speeds
    if name == "solve":
        from powergraph.statics import solve
        return solve
    raise AttributeError(f"module 'powergraph' has no attribute {name!r}")
