"""Compiled, vectorised design sweeps (docs/sweep.md).

Compile a model once into an evaluator over arrays of model values (tooth numbers, mesh
efficiencies, ratios, port speeds and loads) that returns arrays of ratio, efficiency,
losses and self-locking flags, by the same virtual-power physics as
:func:`powergraph.solve` — including each variant's own power directions.

Examples
--------
>>> import numpy as np
>>> from powergraph.model import load_model
>>> from powergraph.analyses.sweep import compile_sweep
>>> evaluate = compile_sweep(load_model("models/rv40e_wang2021.yaml"), ["links.1.efficiency"])
>>> r = evaluate({"links.1.efficiency": np.linspace(0.94, 1.0, 4)})
>>> np.round(r.efficiency, 4).tolist()
[0.2874, 0.3724, 0.532, 0.9405]
"""
from __future__ import annotations

from powergraph.analyses.sweep.compile import CompiledSweep
from powergraph.analyses.sweep.entry import compile_sweep, sweep
from powergraph.analyses.sweep.paths import (Parameter, cartesian, parse_path, parse_set,
                                             parse_sets)
from powergraph.analyses.sweep.result import STATUS, SweepResult

__all__ = ["CompiledSweep", "Parameter", "STATUS", "SweepResult", "cartesian",
           "compile_sweep", "parse_path", "parse_set", "parse_sets", "sweep"]
