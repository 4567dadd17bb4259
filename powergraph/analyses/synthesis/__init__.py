"""Topology synthesis: planetary gear trains as graphs, enumerated and sized for a ratio.

:mod:`~powergraph.analyses.synthesis.graph` holds :class:`TrainGraph`, the graph of a
train (links as vertices; turning pairs with their axes and gear pairs with their carriers
as edges) and its conversion into a powergraph model (docs/synthesis.md);
:mod:`~powergraph.analyses.synthesis.enumerate` lists every non-isomorphic train graph of a
given size (:func:`enumerate_trains`); :mod:`~powergraph.analyses.synthesis.synthesize`
finds the trains and tooth numbers that give a ratio and ranks them (:func:`synthesize`).
"""
from __future__ import annotations

from powergraph.analyses.synthesis.enumerate import EnumerationResult, enumerate_trains
from powergraph.analyses.synthesis.graph import TrainGraph
from powergraph.analyses.synthesis.synthesize import SynthesisResult, synthesize

__all__ = ["EnumerationResult", "SynthesisResult", "TrainGraph", "enumerate_trains",
           "synthesize"]
