"""Layout of a power-flow diagram that follows the power (pure numpy/networkx).

The nodes of a :class:`~powergraph.plot.layout.view.FlowView` are put in layers by flow
order, motor on the left and generator on the right (a Sugiyama layout):

1. **Cycles broken deterministically.** Arrows are taken from the strongest down; one
   that would close a directed cycle (circulating power) is laid out reversed, so the
   weakest arrow of each loop is the one drawn backwards. Zero-power arrows come last.
2. **Layers** by longest path from the motor; a node fed by nothing (the housing's
   zero-power links, the world's reaction "ground") is pulled right to just before the
   first node it feeds; generators share the last layer. Arrows spanning several layers
   get a waypoint in each layer in between.
3. **Order within layers**: discovery order from the motor along the strongest arrows,
   then barycentre sweeps that keep the ordering with the fewest crossings.
4. **Rows**: each node is pulled towards its neighbours (weighted by power, so the main
   flow runs straight) under minimum-gap constraints, solved exactly per layer by
   isotonic regression (pool-adjacent-violators).
5. **Losses** are a sink drawn once per element, right under it (the paper's L1, L2).
6. **Bands**: a long row of layers is folded onto bands stacked top to bottom, near
   16 : 9 (:mod:`powergraph.plot.layout.fold`): each band read left to right, arrows
   between bands along nested lanes (``LayoutStyle(aspect=None)``: one band).
7. **Labels** ("2.06 kW / 90.9 %") are placed greedily, strongest flow first, on the
   first spot along the arrow that hits no node and no other label and covers the least
   of the other arrows (an arrow between bands: on its lane first); if one cannot be
   placed the layout is redone with more room.

Everything is deterministic: the same view gives the same positions, run after run.
Coordinates are points (1/72 in); draw at 1 data unit = 1 pt (or scale the fonts).

Examples
--------
>>> import powergraph as pg
>>> from powergraph.plot.layout.view import flow_view
>>> result = pg.solve(pg.load_model("models/rv40e_wang2021.yaml"))            # doctest: +SKIP
>>> layout = layout_flow(flow_view(result))                           # doctest: +SKIP
>>> [layout.nodes[n].band for n in ("motor", "2/3", "generator")]   # doctest: +SKIP
[0, 0, 1]
>>> layout.nodes["motor"].x < layout.nodes["2/3"].x                 # doctest: +SKIP
True

Nodes are flow-graph :class:`~powergraph.statics.flow.Node` s (kind and name); waypoints
and the loss sinks under elements are nodes of kinds no flow-graph node has (``waypoint``,
``loss stub``). ``layout.nodes`` also answers to an unambiguous name (``NodeMap``).
"""
from __future__ import annotations

from typing import Mapping

import networkx as nx
import numpy as np

from powergraph.plot.layout.geometry import TextSize, estimate_text_size
from powergraph.plot.layout.parts import (LOSS_STUB, WAYPOINT, EdgeRoute, FlowLayout,
                                            LayoutStyle, NodePlace, Skeleton)
from powergraph.plot.layout.place import place
from powergraph.plot.layout.view import FlowView
from powergraph.statics.flow import LOSS, Node

__all__ = ["LOSS_STUB", "WAYPOINT", "EdgeRoute", "FlowLayout", "LayoutStyle", "NodePlace",
           "Skeleton", "layout_flow", "skeleton_of"]


def layout_flow(view: FlowView, text_size: TextSize = estimate_text_size,
                style: LayoutStyle = LayoutStyle()) -> FlowLayout:
    """Lay out ``view``: node positions, arrow paths and label spots, in points.

    Parameters
    ----------
    view : FlowView
    text_size : callable, optional
        ``(text, font_size) -> (width, height)`` in points; the plot passes a measured
        one, the default estimates generously.
    style : LayoutStyle, optional
    """
    skeleton = skeleton_of(view)
    layout = None
    for attempt in range(style.attempts):
        layout = place(view, skeleton, text_size, style, spread=1.3 ** attempt)
        if layout.clean:
            break
    return layout


# --- 1-3: cycles, layers, order ----------------------------------------------------------
def skeleton_of(view: FlowView) -> Skeleton:
    """Layers, waypoints and orders of ``view`` (no sizes involved)."""
    kinds, flows = view.kinds, view.flows
    nodes = sorted({n for f in flows for n in f.key if n.kind != LOSS})
    dag = _acyclic(view, nodes)
    layer = _layers(dag, kinds)
    _place_idle(view, nodes, layer)
    chains, layer_of, side = {}, dict(layer), []
    for index, flow in enumerate(flows):
        if flow.target_kind == LOSS:
            continue
        a, b = flow.key
        if layer[a] > layer[b] or (layer[a] == layer[b] and kinds.get(a) == "generator"):
            a, b = b, a
        if layer[a] == layer[b]:
            side.append(index)
        waypoints = tuple(Node(WAYPOINT, f"·{index}·{k}") for k in range(layer[a] + 1, layer[b]))
        for k, name in zip(range(layer[a] + 1, layer[b]), waypoints):
            layer_of[name] = k
        chains[index] = (a, *waypoints, b)
    reversed_ = frozenset(i for i, chain in chains.items() if chain[0] != flows[i].source_node)
    stubs = {i: Node(LOSS_STUB, f"loss@{f.source}") for i, f in enumerate(flows)
             if f.target_kind == LOSS}
    layers = _order(layer_of, {i: c for i, c in chains.items() if i not in side}, flows,
                    view)
    return Skeleton(layers, layer_of, chains, reversed_, stubs, frozenset(side))


def _acyclic(view: FlowView, nodes: list[Node]) -> nx.DiGraph:
    """A DAG of the arrows that carry power (strongest first; an arrow that would close
    a cycle is laid out reversed). Motors and generators are always in it."""
    kinds, flows = view.kinds, view.flows
    dag = nx.DiGraph()
    dag.add_nodes_from(n for n in nodes if kinds.get(n) in ("motor", "generator"))
    ranked = sorted((i for i, f in enumerate(flows)
                     if f.target_kind != LOSS and not view.is_zero(f)),
                    key=lambda i: (-flows[i].power, i))
    for i in ranked:
        a, b = flows[i].key
        if kinds.get(a) == "generator" or kinds.get(b) == "motor":
            a, b = b, a                      # motors stay left, generators right
        if a in dag and b in dag and nx.has_path(dag, b, a):
            a, b = b, a                      # closes a loop: laid out backwards
        dag.add_edge(a, b)
    return dag


def _layers(dag: nx.DiGraph, kinds: Mapping[Node, str]) -> dict[Node, int]:
    """Longest path from the motor; sources pulled right; generators last."""
    order = list(nx.lexicographical_topological_sort(dag, key=_sort_key))
    layer: dict[str, int] = {}
    for n in order:
        layer[n] = max((layer[p] + 1 for p in dag.predecessors(n)), default=0)
    for n in order:
        if dag.in_degree(n) == 0 and dag.out_degree(n) and kinds.get(n) != "motor":
            layer[n] = min(layer[s] for s in dag.successors(n)) - 1
    generators = [n for n in layer if kinds.get(n) == "generator"]
    if generators:
        last = max((v for n, v in layer.items() if n not in generators), default=0) + 1
        layer.update({n: last for n in generators})
    low = min(layer.values(), default=0)
    return {n: v - low for n, v in layer.items()}


def _sort_key(node: Node) -> str:
    """Names first, then kinds: plain ids keep the order they always had."""
    return f"{node.name}\x00{node.kind}"


def _place_idle(view: FlowView, nodes: list[Node], layer: dict[Node, int]) -> None:
    """Layers of the nodes joined only by zero-power arrows (the held frame, idle
    members). A connected group of them keeps its order in the actual flow (when the
    view has one) and is shifted as a block; each node avoids its neighbours' layers
    and sits as close to them as it can."""
    links: dict[Node, set[Node]] = {n: set() for n in nodes}
    for f in view.flows:
        if f.target_kind != LOSS:
            links[f.source_node].add(f.target_node)
            links[f.target_node].add(f.source_node)
    idle = [n for n in nodes if n not in layer]
    hint = _reference_layers(view) if view.reference else {}
    groups = nx.Graph()
    groups.add_nodes_from(idle)
    groups.add_edges_from((a, b) for a in idle for b in links[a] if b in groups)
    last = max(layer.values(), default=0)
    for group in sorted((sorted(c) for c in nx.connected_components(groups)),
                        key=lambda c: c[0]):
        placed = _shift_group(group, hint, links, layer, last)
        todo = list(group) if placed is None else []
        while todo:   # nodes next to a placed one first
            n = next((m for m in todo if links[m] & layer.keys()), todo[0])
            _place_one(n, links, layer, last)
            todo.remove(n)
        layer.update(placed or {})
    low = min(layer.values(), default=0)
    for n in layer:
        layer[n] -= low


def _reference_layers(view: FlowView) -> dict[Node, int]:
    actual = FlowView(view.name, None, view.reference, view.kinds, None, view.input_power,
                      0.0, frozenset())
    return _layers(_acyclic(actual, sorted(view.kinds)), view.kinds)


def _shift_group(group, hint, links, layer, last) -> dict[Node, int] | None:
    """The group at its reference layers plus the shift that keeps it nearest its placed
    neighbours without sharing a layer with one (None if it has no reference)."""
    if len(group) < 2 or any(n not in hint for n in group):
        return None
    best = None
    for shift in range(-max(hint.values()) - 1, last + 1):
        at = {n: hint[n] + shift for n in group}
        if min(at.values()) < 0 or max(at.values()) > max(last - 1, 0):
            continue
        near = [(at[n], layer[m]) for n in group for m in links[n] if m in layer]
        if any(a == b for a, b in near):
            continue
        cost = (sum(abs(a - b) for a, b in near), abs(shift))
        if best is None or cost < best[0]:
            best = (cost, at)
    return None if best is None else best[1]


def _place_one(n, links, layer, last) -> None:
    near = [layer[m] for m in sorted(links[n]) if m in layer]
    mean = sum(near) / len(near) if near else 0.0
    free = [k for k in range(0, max(last, 1)) if k not in near] or [min(near) - 1]
    layer[n] = min(free, key=lambda k: (abs(k - mean), k))


def _segments(chains: Mapping[int, tuple[Node, ...]]) -> list[tuple[Node, Node, int]]:
    return [(a, b, i) for i, chain in chains.items() for a, b in zip(chain[:-1], chain[1:])]


def _order(layer_of, chains, flows, view) -> tuple[tuple[Node, ...], ...]:
    """Top-to-bottom order in each layer: discovery order, then barycentre sweeps."""
    segs = _segments(chains)
    count = max(layer_of.values(), default=0) + 1
    rank = _discovery(layer_of, segs, flows, view)
    layers = [sorted((n for n, v in layer_of.items() if v == k), key=rank.__getitem__)
              for k in range(count)]
    preds = {n: [a for a, b, _ in segs if b == n] for n in layer_of}
    succs = {n: [b for a, b, _ in segs if a == n] for n in layer_of}
    best, best_cross = [list(x) for x in layers], _crossings(layers, segs)
    for sweep in range(12):
        down = sweep % 2 == 0
        span = range(1, count) if down else range(count - 2, -1, -1)
        for k in span:
            ref = {n: i for i, n in enumerate(layers[k - 1 if down else k + 1])}
            pos = {n: i for i, n in enumerate(layers[k])}

            def bary(n, ref=ref, pos=pos, down=down):
                nbrs = [ref[m] for m in (preds[n] if down else succs[n]) if m in ref]
                return (sum(nbrs) / len(nbrs) if nbrs else pos[n], pos[n])
            layers[k] = sorted(layers[k], key=bary)
        cross = _crossings(layers, segs)
        if cross < best_cross:
            best, best_cross = [list(x) for x in layers], cross
    return tuple(tuple(x) for x in best)


def _discovery(layer_of, segs, flows, view) -> dict[Node, int]:
    """Depth-first discovery order from the motor(s) along the strongest arrows."""
    adjacency: dict[Node, list[tuple[float, Node]]] = {n: [] for n in layer_of}
    for a, b, i in segs:
        power = flows[i].power
        adjacency[a].append((-power, b))
        adjacency[b].append((-power, a))
    starts = sorted(n for n in layer_of if view.kinds.get(n) == "motor") + sorted(layer_of)
    rank: dict[str, int] = {}
    for start in starts:
        stack = [start]
        while stack:
            n = stack.pop()
            if n in rank:
                continue
            rank[n] = len(rank)
            stack += [m for _, m in sorted(adjacency[n], reverse=True) if m not in rank]
    return rank


def _crossings(layers, segs) -> int:
    pos = {n: i for layer in layers for i, n in enumerate(layer)}
    total = 0
    by_layer: dict[int, list[tuple[int, int]]] = {}
    level = {n: k for k, layer in enumerate(layers) for n in layer}
    for a, b, _ in segs:
        by_layer.setdefault(level[a], []).append((pos[a], pos[b]))
    for pairs in by_layer.values():
        arr = np.array(pairs)
        da = arr[:, None, 0] - arr[None, :, 0]
        db = arr[:, None, 1] - arr[None, :, 1]
        total += int(((da * db) < 0).sum()) // 2
    return total
