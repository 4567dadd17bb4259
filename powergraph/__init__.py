"""powergraph: power flow, losses and efficiency of gear trains described as graphs.

Examples
--------
>>> import powergraph as pg
>>> model = pg.load_model("models/rv40e.yaml")          # doctest: +SKIP
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

__all__ = [
    "PowerGraphError", "ModelError", "KinematicsError", "StaticsError", "SolveError",
    "MethodNotApplicableError", "UsageError", "load_model", "model_from_dict", "solve",
    "solve_speeds",
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
