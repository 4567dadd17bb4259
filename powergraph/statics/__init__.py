"""Statics and power flow: torques, directions, losses, flow graph (docs/theory.md)."""
from __future__ import annotations

from powergraph.statics.flow import (Flow, Node, circulating_power, flow_edges, flow_graph,
                                     split_powers)
from powergraph.statics.result import ElementFlow, PowerFlowResult
from powergraph.statics.solver import solve

__all__ = ["ElementFlow", "Flow", "Node", "PowerFlowResult", "circulating_power", "flow_edges",
           "flow_graph", "solve", "split_powers"]
