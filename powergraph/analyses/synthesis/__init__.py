"""Topology synthesis: planetary gear trains as graphs, enumerated and sized for a ratio.

:mod:`~powergraph.analyses.synthesis.graph` holds :class:`TrainGraph`, the graph of a
train (links as vertices; turning pairs with their axes and gear pairs with their carriers
as edges) and its conversion into a powergraph model (docs/synthesis.md);
:mod:`~powergraph.analyses.synthesis.enumerate` lists every non-isomorphic train graph of a
given size (:func:`enumerate_trains`).
"""
from __future__ import annotations

from powergraph.analyses.synthesis.enumerate import EnumerationResult, enumerate_trains
from powergraph.analyses.synthesis.graph import TrainGraph

__all__ = ["EnumerationResult", "TrainGraph", "enumerate_trains"]
