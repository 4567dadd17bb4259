"""Compiled, vectorised design sweeps: re-export of :mod:`powergraph.analyses.sweep`.

Examples
--------
>>> import powergraph.sweep as ps
>>> from powergraph.model import load_model
>>> r = ps.sweep(load_model("models/rv40e.yaml"), {"links.1.efficiency": [0.94, 0.998]})
>>> [round(float(e), 6) for e in r.efficiency]
[0.287376, 0.873043]
"""
from __future__ import annotations

from powergraph.analyses.sweep import (  # noqa: F401
    STATUS,
    CompiledSweep,
    Parameter,
    SweepResult,
    cartesian,
    compile_sweep,
    parse_path,
    parse_set,
    parse_sets,
    sweep,
)

__all__ = ["CompiledSweep", "Parameter", "STATUS", "SweepResult", "cartesian",
           "compile_sweep", "parse_path", "parse_set", "parse_sets", "sweep"]
