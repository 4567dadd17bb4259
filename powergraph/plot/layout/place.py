"""Coordinates, arrow paths and label spots for a :class:`Skeleton`.

See :mod:`powergraph.plot.layout.layout` for the steps (it calls :func:`place`; the
records both build are in :mod:`powergraph.plot.layout.parts`).

Examples
--------
>>> import powergraph as pg
>>> from powergraph.plot.layout.view import flow_view
>>> from powergraph.plot.layout.layout import skeleton_of
>>> view = flow_view(pg.solve(pg.load_model("models/rv40e_wang2021.yaml")))   # doctest: +SKIP
>>> place(view, skeleton_of(view)).clean                              # doctest: +SKIP
True
"""
from __future__ import annotations

from typing import Mapping

import numpy as np

from powergraph.plot.layout.geometry import (
    CURVE4, MOVETO, Box, Shape, TextSize, bounds, estimate_text_size, head_box,
    label_candidates, node_shape, place_label, port, port_offsets, sample, segments,
    straight, stub_candidates)
from powergraph.plot.layout.fold import fold
from powergraph.plot.layout.parts import (WAYPOINT, EdgeRoute, FlowLayout, LayoutStyle,
                                            NodePlace, Skeleton)
from powergraph.plot.layout.nodes import NodeMap
from powergraph.plot.layout.view import FlowView
from powergraph.statics.flow import Node

#: Padding (points) around a label's text: the plot draws its white box this far out.
LABEL_PAD = 1.5


def place(view: FlowView, skeleton: Skeleton, text_size: TextSize = estimate_text_size,
          style: LayoutStyle = LayoutStyle(), spread: float = 1.0) -> FlowLayout:
    """Geometry of ``skeleton`` with gaps scaled by ``spread`` (>= 1)."""
    shapes = {n: node_shape(view.text(n), view.kinds.get(n, "body"), text_size,
                            style.font_size)      # a port captioned with its name
              for n in skeleton.layer_of if n.kind != WAYPOINT}
    stub = node_shape("loss", "loss", text_size, style.font_size)
    stub_of = {view.flows[i].source_node: name for i, name in skeleton.stubs.items()}
    sizes = {i: _padded(text_size(view.label(f), style.label_size))
             for i, f in enumerate(view.flows)}
    stub_len = style.stub_length * spread
    extents = {n: _extent(shapes.get(n), n in stub_of, stub, stub_len, style)
               for n in skeleton.layer_of}
    y = rows(skeleton, extents, _weights(view, skeleton), style.row_gap * spread)
    x = _columns(skeleton, shapes, sizes, stub, stub_of, style, spread)
    folding = fold(skeleton, x, y, extents, _half_widths(skeleton, shapes),
                   max((h for _, h in sizes.values()), default=0.0),
                   style.max_width, style)
    points = {n: folding.point(skeleton.layer_of[n], y[n]) for n in skeleton.layer_of}
    nodes = {n: NodePlace(n, view.kinds.get(n, "body"), *points[n], shape,
                          skeleton.layer_of[n], folding.band_of[skeleton.layer_of[n]])
             for n, shape in shapes.items()}
    for owner, name in stub_of.items():
        o = nodes[owner]
        nodes[name] = NodePlace(name, "loss", o.x,
                                o.y - o.shape.height / 2 - stub_len - stub.height / 2,
                                stub, o.layer, o.band)
    paths = _paths(view, skeleton, nodes, points, stub_of, style, folding)
    return _labelled(view, skeleton, nodes, paths, sizes, style, spread, folding)


# --- rows: y of every node (step 4 of the layout) ---------------------------------------
def rows(skeleton: Skeleton, extents: Mapping[Node, tuple[float, float]],
         weights: Mapping[tuple[Node, Node], float], gap: float, sweeps: int = 30) -> dict:
    """y of every node: pulled towards its neighbours, at least ``gap`` apart.

    ``extents[n] = (up, down)`` is how far node ``n`` reaches above and below its y.
    """
    neighbours: dict[Node, list[tuple[Node, float]]] = {n: [] for n in skeleton.layer_of}
    for (a, b), w in weights.items():
        neighbours[a].append((b, w))
        neighbours[b].append((a, w))
    y: dict[Node, float] = {}
    for layer in skeleton.layers:
        seps = _separations(layer, extents, gap)
        offsets = np.concatenate([[0.0], np.cumsum(seps)])
        for n, off in zip(layer, offsets):
            y[n] = offsets[-1] / 2 - off
    count = len(skeleton.layers)
    for sweep in range(sweeps):
        span = range(count) if sweep % 2 == 0 else range(count - 1, -1, -1)
        for k in span:
            layer = skeleton.layers[k]
            target = [_pull(n, y, neighbours) for n in layer]
            y.update(zip(layer, _project(target, _separations(layer, extents, gap))))
    anchor = next((n for n in skeleton.layers[0]), None) if skeleton.layers else None
    shift = y[anchor] if anchor is not None else 0.0
    return {n: v - shift for n, v in y.items()}


def _separations(layer, extents, gap) -> list[float]:
    return [extents[a][1] + gap + extents[b][0] for a, b in zip(layer[:-1], layer[1:])]


def _pull(n, y, neighbours) -> tuple[float, float]:
    nbrs = neighbours[n]
    total = sum(w for _, w in nbrs)
    if not total:
        return (y[n], 1e-3)
    return (sum(w * y[m] for m, w in nbrs) / total, total)


def _project(target: list[tuple[float, float]], seps: list[float]) -> list[float]:
    """Closest (weighted least squares) y, top to bottom, with y[i] - y[i+1] >= seps[i]."""
    offsets = np.concatenate([[0.0], np.cumsum(seps)])
    blocks: list[list[float]] = []            # [value, weight, count]
    for (value, weight), off in zip(target, offsets):
        blocks.append([value + off, weight, 1])
        while len(blocks) > 1 and blocks[-2][0] < blocks[-1][0]:
            v2, w2, c2 = blocks.pop()
            v1, w1, c1 = blocks.pop()
            blocks.append([(v1 * w1 + v2 * w2) / (w1 + w2), w1 + w2, c1 + c2])
    z = [v for v, _, c in blocks for _ in range(int(c))]
    return [float(zi - off) for zi, off in zip(z, offsets)]


# --- columns, arrows, labels ----------------------------------------------------------
def _padded(size: tuple[float, float]) -> tuple[float, float]:
    return (size[0] + 2 * LABEL_PAD, size[1] + 2 * LABEL_PAD)


def _extent(shape: Shape | None, has_stub: bool, stub: Shape, stub_len: float,
            style: LayoutStyle) -> tuple[float, float]:
    if shape is None:
        return (style.waypoint_height / 2, style.waypoint_height / 2)
    down = shape.down
    if has_stub:
        down = max(down, shape.height / 2 + stub_len + stub.height)
    return (shape.up, down)


def _weights(view: FlowView, skeleton: Skeleton) -> dict[tuple[Node, Node], float]:
    largest = view.largest or 1.0
    weights: dict[tuple[Node, Node], float] = {}
    for i, chain in skeleton.chains.items():
        flow = view.flows[i]
        w = 0.3 if view.is_zero(flow) else 1.0 + 3.0 * flow.power / largest
        for a, b in zip(chain[:-1], chain[1:]):
            weights[(a, b)] = weights.get((a, b), 0.0) + w
    return weights


def _half_widths(skeleton, shapes) -> list[float]:
    return [max((shapes[n].half_width for n in layer if n in shapes), default=2.0)
            for layer in skeleton.layers]


def _columns(skeleton, shapes, sizes, stub, stub_of, style, spread) -> list[float]:
    """x of each layer: room for the widest node and the widest label in each gap."""
    count = len(skeleton.layers)
    half = _half_widths(skeleton, shapes)
    need = [0.0] * count
    for i, chain in skeleton.chains.items():
        for a in chain[:-1]:
            k = skeleton.layer_of[a]
            need[k] = max(need[k], sizes[i][0])
    owner_of = {name: owner for owner, name in stub_of.items()}
    for i, name in skeleton.stubs.items():
        k = skeleton.layer_of[owner_of[name]]
        need[k] = max(need[k], 4.0 + sizes[i][0])
    x = [0.0]
    for k in range(count - 1):
        x.append(x[-1] + half[k] + need[k] + 2 * style.layer_gap * spread + half[k + 1])
    return x


def _ports(skeleton: Skeleton, points: Mapping[Node, tuple[float, float]],
           nodes: Mapping[Node, NodePlace], style: LayoutStyle) -> dict:
    """Offset of every arrow end on its node's side, ordered so they do not cross."""
    ends: dict[tuple[Node, int], list[tuple[float, int, str]]] = {}
    for i, chain in skeleton.chains.items():
        back = +1 if i in skeleton.side else -1
        ends.setdefault((chain[0], +1), []).append((points[chain[1]][1], i, "start"))
        ends.setdefault((chain[-1], back), []).append((points[chain[-2]][1], i, "end"))
    offsets = {}
    for (node, _side), items in ends.items():
        items.sort(key=lambda t: (-t[0], t[1]))
        for off, (_, i, which) in zip(port_offsets(len(items), nodes[node].shape,
                                                   style.port_spacing), items):
            offsets[(i, which)] = off
    return offsets


def _paths(view, skeleton, nodes, points, stub_of, style, folding) -> dict[int, tuple]:
    """Vertices and codes of every arrow, from its source to its target."""
    offsets = _ports(skeleton, points, nodes, style)
    paths = {}
    for i, chain in skeleton.chains.items():
        a, b = nodes[chain[0]], nodes[chain[-1]]
        if i in skeleton.side:
            paths[i] = _side_path(a, b, offsets[(i, "start")], offsets[(i, "end")],
                                  i in skeleton.reversed)
            continue
        route = [port(a.x, a.y, a.shape, +1, offsets[(i, "start")]),
                 *(points[w] for w in chain[1:-1]),
                 port(b.x, b.y, b.shape, -1, offsets[(i, "end")])]
        vertices, codes = folding.route(i, [skeleton.layer_of[n] for n in chain], route)
        if i in skeleton.reversed:
            vertices = vertices[::-1]
        paths[i] = (vertices, codes)
    for i, name in skeleton.stubs.items():
        owner, sink = nodes[view.flows[i].source_node], nodes[name]
        paths[i] = straight([(owner.x, owner.y - owner.shape.height / 2),
                             (sink.x, sink.y + sink.shape.height / 2)])
    return paths


def _side_path(a: NodePlace, b: NodePlace, off_a: float, off_b: float,
               backwards: bool) -> tuple:
    """An arrow between two nodes of one layer: out of ``a``'s right side, bulging
    right, back into ``b``'s right side."""
    start, end = port(a.x, a.y, a.shape, +1, off_a), port(b.x, b.y, b.shape, +1, off_b)
    bulge = max(start[0], end[0]) + float(np.clip(abs(start[1] - end[1]) / 2, 14.0, 40.0))
    vertices = (start, (bulge, start[1]), (bulge, end[1]), end)
    codes = (MOVETO, CURVE4, CURVE4, CURVE4)
    return (vertices[::-1] if backwards else vertices), codes


def _lanes_first(pieces: list[np.ndarray], index: int, folding) -> list[np.ndarray]:
    """The pieces of a folded arrow with its lanes (between bands) first: a label sits
    best on the long run back."""
    heights = {round(lane.y, 6) for (i, _), lane in folding.lanes.items() if i == index}
    if not heights:
        return pieces
    on_lane = [p for p in pieces if np.ptp(p[:, 1]) < 1e-6 and np.ptp(p[:, 0]) > 1.0
               and round(float(p[0, 1]), 6) in heights]
    on_lane.sort(key=lambda p: -np.ptp(p[:, 0]))
    return on_lane + [p for p in pieces if not any(p is q for q in on_lane)]


def _width(view: FlowView, power: float, style: LayoutStyle, zero: bool) -> float:
    if zero:
        return style.zero_width
    return max(style.min_width, style.max_width * power / (view.largest or 1.0))


def _labelled(view, skeleton, nodes, paths, sizes, style, spread, folding) -> FlowLayout:
    """Place every label (loss stubs first, then strongest first) and assemble."""
    samples = {i: sample(*paths[i]) for i in paths}
    owners = np.concatenate([[i] * len(s) for i, s in samples.items()]) if samples else []
    ink = np.vstack(list(samples.values())) if samples else np.zeros((0, 2))
    obstacles = [b for node in nodes.values() for b in node.boxes]
    flows = view.flows
    widths = {i: _width(view, f.power, style, view.is_zero(f)) for i, f in enumerate(flows)}
    obstacles += [head_box(*paths[i], *style.head(widths[i])) for i in paths
                  if not view.is_zero(flows[i])]
    order = sorted(paths, key=lambda i: (view.is_zero(flows[i]), i in skeleton.stubs,
                                         -flows[i].power, i))
    spots: dict[int, tuple] = {}
    lanes = {i for i, _ in folding.lanes}
    for i in order:
        vertices, codes = paths[i]
        if i in skeleton.stubs:
            clear = max(nodes[flows[i].source_node].shape.width,
                        nodes[skeleton.stubs[i]].shape.width)
            candidates = stub_candidates(vertices[0], vertices[-1], sizes[i], clear / 2,
                                         nodes[skeleton.stubs[i]].box)
        else:
            candidates = label_candidates(_lanes_first(segments(vertices, codes), i,
                                                       folding), sizes[i],
                                          gap=2.0 + widths[i] / 2, ordered=i in lanes)
        found = place_label(candidates, sizes[i], obstacles, ink[owners != i])
        placed = found is not None
        if not placed:
            found = (candidates[0], Box.around(*candidates[0], *sizes[i]))
        spots[i] = (found, placed)
        obstacles.append(found[1])
    edges = []
    for i, flow in enumerate(flows):
        (xy, box), placed = spots[i]
        zero = view.is_zero(flow)
        edges.append(EdgeRoute(flow, *paths[i], width=widths[i],
                               zero=zero, loop=flow.key in view.loop_edges,
                               loss=i in skeleton.stubs, label=view.label(flow),
                               label_xy=xy, label_box=box, placed=placed,
                               head_size=style.head(widths[i])))
    boxes = [b for node in nodes.values() for b in node.boxes] + [e.label_box for e in edges]
    return FlowLayout(view, NodeMap(nodes), tuple(edges), bounds(boxes, ink, style.margin),
                      style, spread, folding)
