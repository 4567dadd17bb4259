"""The records of a laid-out power-flow diagram: style, placed nodes, arrow routes, the
whole layout and its combinatorial skeleton (pure data, no layout steps).

:mod:`powergraph.plot.layout.layout` computes the skeleton and calls
:mod:`powergraph.plot.layout.place` for its geometry; both build these records from here,
so the placing never imports the layout back (the layout re-exports them).

Examples
--------
>>> style = LayoutStyle(font_size=10.0)
>>> style.label_size, style.head(2.0)
(8.5, (6.4, 4.0))
"""
from __future__ import annotations

from dataclasses import field
from typing import Any, Mapping

from powergraph.plot.layout.geometry import Box, Shape, head_polygon, trim_end
from powergraph.plot.layout.nodes import NodeMap
from powergraph.plot.layout.view import FlowView
from powergraph.records import record
from powergraph.statics.flow import Flow, Node

WAYPOINT, LOSS_STUB = "waypoint", "loss stub"


@record
class LayoutStyle:
    """Sizes in points. ``font_size`` is the node font; labels use ``label_scale`` of it."""

    font_size: float = 9.0
    label_scale: float = 0.85
    layer_gap: float = 16.0
    row_gap: float = 16.0
    stub_length: float = 12.0
    max_width: float = 9.0
    min_width: float = 0.7
    zero_width: float = 0.8
    port_spacing: float = 5.0
    waypoint_height: float = 6.0
    margin: float = 6.0
    attempts: int = 8
    #: Width : height aimed at when long diagrams are folded onto bands
    #: (:mod:`powergraph.plot.layout.fold`), and the range a folding is stretched into;
    #: None draws every layer in one band.
    aspect: float | None = 16 / 9
    aspect_range: tuple[float, float] = (1.5, 2.1)

    @property
    def label_size(self) -> float:
        return self.font_size * self.label_scale

    def head(self, width: float) -> tuple[float, float]:
        """Arrowhead (length, half width) in points for an arrow ``width`` points wide."""
        return (5.0 + 0.7 * width, 2.8 + 0.6 * width)


@record
class NodePlace:
    """A drawn node: its symbol centred at ``(x, y)``, its caption underneath if any;
    ``kind`` is the kind drawn (a held body is drawn as ``frame``); ``band`` is the band
    its layer was folded onto (0 at the top)."""

    node: Node
    kind: str
    x: float
    y: float
    shape: Shape
    layer: int
    band: int = 0

    @property
    def name(self) -> str:
        return self.node.name

    @property
    def box(self) -> Box:
        return Box.around(self.x, self.y, self.shape.width, self.shape.height)

    @property
    def caption_box(self) -> Box | None:
        if not self.shape.caption:
            return None
        w, h = self.shape.caption_size
        return Box.around(self.x, self.y - self.shape.height / 2 - 2.0 - h / 2, w, h)

    @property
    def boxes(self) -> tuple[Box, ...]:
        caption = self.caption_box
        return (self.box,) if caption is None else (self.box, caption)


@record
class EdgeRoute:
    """One arrow: the path from ``flow.source`` to ``flow.target`` and its label spot."""

    flow: Flow
    vertices: tuple
    codes: tuple
    width: float
    zero: bool
    loop: bool
    loss: bool
    label: str
    label_xy: tuple[float, float]
    label_box: Box
    placed: bool = True
    head_size: tuple[float, float] = (0.0, 0.0)

    @property
    def key(self) -> tuple[Node, Node]:
        return self.flow.key

    @property
    def head(self) -> tuple[tuple[float, float], ...] | None:
        """The arrowhead triangle (tip, left, right) in points; None for a 0 W link."""
        if self.zero:
            return None
        return head_polygon(self.vertices, self.codes, *self.head_size)

    @property
    def shaft(self) -> tuple[tuple, tuple]:
        """Vertices and codes of the line, stopped where the arrowhead begins."""
        if self.zero:
            return self.vertices, self.codes
        return trim_end(self.vertices, self.codes, self.head_size[0] * 0.9)


@record
class FlowLayout:
    """Positions of every node, arrow and label of one diagram (points)."""

    view: FlowView
    nodes: Mapping[Node, NodePlace]
    edges: tuple[EdgeRoute, ...]
    bounds: Box
    style: LayoutStyle
    spread: float = 1.0
    #: The bands the layers were folded onto and the lanes between them
    #: (:class:`~powergraph.plot.layout.fold.Folding`).
    folding: Any = None

    @property
    def clean(self) -> bool:
        """True when every label found a spot clear of nodes and other labels."""
        return all(edge.placed for edge in self.edges)

    def edge(self, source: Node | str, target: Node | str) -> EdgeRoute:
        """The arrow from ``source`` to ``target`` (nodes, or names when unambiguous)."""
        return NodeMap({e.key: e for e in self.edges})[(source, target)]


@record
class Skeleton:
    """The combinatorial layout: layers (top to bottom), arrow chains, loss stubs."""

    layers: tuple[tuple[Node, ...], ...]
    layer_of: Mapping[Node, int]
    chains: Mapping[int, tuple[Node, ...]]       # flow index -> nodes left to right
    reversed: frozenset                           # flows drawn right to left
    stubs: Mapping[int, Node] = field(default_factory=dict)  # loss flow -> stub node
    side: frozenset = frozenset()                 # flows between nodes of one layer
