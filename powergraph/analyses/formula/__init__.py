"""Closed-form ratio and efficiency of any train, derived from its graph.

From a model, :func:`derive_formulas` gives the ratio as a rational function of the tooth
numbers and the efficiency as a function of the tooth numbers and the basic efficiencies,
for the power-direction pattern that holds at the model's values, with the conditions
that keep that pattern (each driver keeps driving in its carrier's frame; no denominator
vanishes). It mirrors the numeric solver (docs/theory.md) with sympy: the
systems come from :mod:`~powergraph.analyses.formula.systems`, shared with the compiled
sweep.

Symbols: ``z_<component id>`` (tooth numbers), ``eta_<i>`` (basic efficiency of
``links[i]``: every mesh, and a coupling only when its efficiency is below 1),
``i_<i>`` (Willis' quotient of ``links[i]`` when the model gives ``ratio:``).

Examples
--------
>>> from powergraph.model import load_model
>>> f = derive_formulas(load_model("models/khv_involute.yaml"))    # doctest: +SKIP
>>> display(f.ratio), display(f.efficiency)                        # doctest: +SKIP
('z_p/(z_p - z_r)', 'eta_0*(z_r - z_p)/(z_r - eta_0*z_p)')
>>> f.lambdify()(eta_0=[0.99, 0.98])["efficiency"].round(4)        # doctest: +SKIP
array([0.9167, 0.8448])
"""
from __future__ import annotations

from powergraph.analyses.formula.compiled import CompiledFormula, compile_formula
from powergraph.analyses.formula.derive import derive_formulas
from powergraph.analyses.formula.readable import display, orient, readable, sign_factors
from powergraph.analyses.formula.report import latex_report, suggested_relations, text_report
from powergraph.analyses.formula.result import Condition, Direction, FormulaResult
from powergraph.analyses.formula.symbols import SymbolInfo, build_symbols

__all__ = ["CompiledFormula", "Condition", "Direction", "FormulaResult", "SymbolInfo",
           "build_symbols", "compile_formula", "derive_formulas", "display", "latex_report",
           "orient", "readable", "sign_factors", "suggested_relations", "text_report"]
