"""``powergraph.formula``: closed-form ratio and efficiency of any train (sympy).

A thin re-export of :mod:`powergraph.analyses.formula`; see there.

Examples
--------
>>> from powergraph.formula import derive_formulas
>>> from powergraph.model import load_model
>>> derive_formulas(load_model("models/planetary_2kh_sun_to_ring.yaml")).efficiency  # doctest: +SKIP
eta_0*eta_1
"""
from __future__ import annotations

from powergraph.analyses.formula import *  # noqa: F401,F403
from powergraph.analyses.formula import __all__  # noqa: F401
