"""Tolerance analysis: lost motion, ratio fluctuation and efficiency of a million units.

A model's top-level ``tolerances:`` block gives a distribution to model values (a mesh's
play, the over-pin M, runout and bearing clearance of a ``backlash:`` block, a cycloid
disc's profile error, mesh efficiencies). :func:`tolerance_analysis` samples them
(Monte Carlo), evaluates every unit with one vectorised evaluator
(:class:`ToleranceEvaluator`), and reports the outputs' statistics, the yield of each
specification with its 95 % Wilson interval, and first-order and total Sobol indices
(SALib). Method: docs/tolerance.md.

Examples
--------
>>> from powergraph.model import load_model
>>> rv = load_model("models/rv40e_tolerances.yaml")                     # doctest: +SKIP
>>> r = tolerance_analysis(rv, samples=10**6, seed=1,
...                        specs=["lost_motion<=1arcmin"])               # doctest: +SKIP
>>> r.yields[0].fraction, r.ranked()[0][0]                               # doctest: +SKIP
"""
from __future__ import annotations

from powergraph.analyses.tolerance.analysis import tolerance_analysis
from powergraph.analyses.tolerance.evaluate import (FluctuationTable, ToleranceEvaluator,
                                                    fluctuation_table)
from powergraph.analyses.tolerance.result import ToleranceResult
from powergraph.analyses.tolerance.stats import (Spec, Yield, parse_spec, summary,
                                                 wilson_interval)
from powergraph.model.block_tolerances import Tolerance, Tolerances, validate_tolerances
from powergraph.model.distributions import Distribution, it_tolerance, parse_distribution
from powergraph.model.tolerance_paths import Target, resolve_path

__all__ = ["Distribution", "FluctuationTable", "Spec", "Target", "Tolerance", "Tolerances",
           "ToleranceEvaluator", "ToleranceResult", "Yield", "fluctuation_table",
           "it_tolerance", "parse_distribution", "parse_spec", "resolve_path", "summary",
           "tolerance_analysis", "validate_tolerances", "wilson_interval"]
