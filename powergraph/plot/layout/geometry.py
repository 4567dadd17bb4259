"""Shapes, routes and label spots of a power-flow diagram (pure numpy, in points).

Used by :mod:`powergraph.plot.layout.layout`; nothing here draws. Coordinates are
typographic points (1/72 inch) so that text sizes, measured or estimated, are in the
same unit as the positions; y grows upwards.

Examples
--------
>>> Box(0, 0, 10, 10).overlaps(Box(5, 5, 20, 20)), Box(0, 0, 10, 10).overlaps(Box(11, 0, 20, 5))
(True, False)
>>> estimate_text_size("2.27 kW\\n100 %", 9.0)
(39.06, 22.5)
"""
from __future__ import annotations

from typing import Callable, Sequence

import numpy as np

from powergraph.records import record

#: (text, font size in points) -> (width, height) in points.
TextSize = Callable[[str, float], "tuple[float, float]"]

# matplotlib.path.Path codes, repeated here so that this module needs no matplotlib.
MOVETO, LINETO, CURVE4 = 1, 2, 4


def estimate_text_size(text: str, size: float) -> tuple[float, float]:
    """A generous estimate of a text's extent (DejaVu Sans: about 0.62 em per character)."""
    lines = text.split("\n")
    return (round(max(len(line) for line in lines) * 0.62 * size, 2),
            round(len(lines) * 1.25 * size, 2))


@record
class Box:
    """An axis-aligned rectangle ``[x0, x1] × [y0, y1]`` in points."""

    x0: float
    y0: float
    x1: float
    y1: float

    @staticmethod
    def around(x: float, y: float, width: float, height: float) -> "Box":
        return Box(x - width / 2, y - height / 2, x + width / 2, y + height / 2)

    def overlaps(self, other: "Box", pad: float = 0.0) -> bool:
        return not (self.x1 + pad <= other.x0 or other.x1 + pad <= self.x0
                    or self.y1 + pad <= other.y0 or other.y1 + pad <= self.y0)

    def contains(self, points: np.ndarray) -> int:
        """How many of the points (n × 2) fall inside."""
        if len(points) == 0:
            return 0
        inside = ((points[:, 0] > self.x0) & (points[:, 0] < self.x1)
                  & (points[:, 1] > self.y0) & (points[:, 1] < self.y1))
        return int(inside.sum())

    def union(self, other: "Box") -> "Box":
        return Box(min(self.x0, other.x0), min(self.y0, other.y0),
                   max(self.x1, other.x1), max(self.y1, other.y1))

    @property
    def center(self) -> tuple[float, float]:
        return ((self.x0 + self.x1) / 2, (self.y0 + self.y1) / 2)


@record
class Shape:
    """Size of a node's symbol and of its caption (if written under the symbol).

    ``round`` symbols (meshes, motor, generator) attach arrows on their circle.
    """

    width: float
    height: float
    text: str
    round: bool = False
    caption: str | None = None
    caption_size: tuple[float, float] = (0.0, 0.0)

    @property
    def up(self) -> float:
        return self.height / 2

    @property
    def down(self) -> float:
        return self.height / 2 + (self.caption_size[1] + 2.0 if self.caption else 0.0)

    @property
    def half_width(self) -> float:
        return max(self.width, self.caption_size[0]) / 2


#: Longest node text drawn (characters per line); longer names are cut with "…".
MAX_NAME = 40


def shortened(name: str, limit: int = MAX_NAME) -> str:
    """``name`` with each line cut to ``limit`` characters (a long id would otherwise
    make its node, and the figure, as wide as the text).

    >>> shortened("S" * 50, 10), shortened("2/3")
    ('SSSSSSSSS…', '2/3')
    """
    lines = ["".join(" " if c < " " or c == "\x7f" else c for c in line)   # tabs...
             for line in name.split("\n")]
    return "\n".join(line if len(line) <= limit else line[:limit - 1] + "…" for line in lines)


def node_shape(name: str, kind: str, text_size: TextSize, font: float) -> Shape:
    """The symbol of a node: body box, mesh circle, coupling square, motor ⊙ ..."""
    name = shortened(name)
    if kind in ("motor", "generator", "ground"):
        caption_size = text_size(name, font * 0.9)
        width, height = (2.4 * font, 2.4 * font) if kind != "ground" else (3 * font, 1.3 * font)
        return Shape(width, height, "", round=kind != "ground", caption=name,
                     caption_size=caption_size)
    text = name.split(" ", 1)[1] if kind in ("mesh", "coupling") and " " in name else name
    if kind == "loss":
        text = "loss"
    w, h = text_size(text, font)
    if kind == "mesh":
        d = max(w + 0.9 * font, h + 0.6 * font, 2.6 * font)
        return Shape(d, d, text, round=True)
    if kind == "loss":
        return Shape(w + 0.8 * font, h + 0.5 * font, text)
    return Shape(max(w + 1.4 * font, 3 * font), h + 0.9 * font, text)


def port(x: float, y: float, shape: Shape, side: int, offset: float) -> tuple[float, float]:
    """Where an arrow meets a node: on its right (side=+1) or left (-1) edge, ``offset``
    above its centre (on the circle for round symbols)."""
    half = shape.width / 2
    if shape.round:
        offset = float(np.clip(offset, -0.8 * half, 0.8 * half))
        return (x + side * float(np.sqrt(half * half - offset * offset)), y + offset)
    offset = float(np.clip(offset, -0.45 * shape.height, 0.45 * shape.height))
    return (x + side * half, y + offset)


def port_offsets(count: int, shape: Shape, spacing: float) -> list[float]:
    """Offsets (top first) of ``count`` arrows sharing one side of a node."""
    if count <= 1:
        return [0.0] * count
    span = min(spacing * (count - 1), 0.8 * shape.height)
    return list(np.linspace(span / 2, -span / 2, count))


def bezier_chain(points: Sequence[tuple[float, float]]) -> tuple[tuple, tuple]:
    """Vertices and path codes of a smooth chain through ``points`` with horizontal
    tangents at every point (layered drawings read left to right)."""
    vertices = [tuple(points[0])]
    codes = [MOVETO]
    for (x0, y0), (x1, y1) in zip(points[:-1], points[1:]):
        k = (x1 - x0) / 2
        vertices += [(x0 + k, y0), (x1 - k, y1), (x1, y1)]
        codes += [CURVE4] * 3
    return tuple(vertices), tuple(codes)


def straight(points: Sequence[tuple[float, float]]) -> tuple[tuple, tuple]:
    """Vertices and codes of a polyline."""
    return tuple(tuple(p) for p in points), (MOVETO,) + (LINETO,) * (len(points) - 1)


def sample(vertices: Sequence[tuple[float, float]], codes: Sequence[int],
           per_segment: int = 24) -> np.ndarray:
    """Points along a path made of MOVETO, LINETO and CURVE4 codes (n × 2)."""
    v = np.asarray(vertices, dtype=float)
    t = np.linspace(0.0, 1.0, per_segment)[:, None]
    out = [v[:1]]
    i = 1
    while i < len(v):
        if codes[i] == CURVE4:
            p0, p1, p2, p3 = v[i - 1], v[i], v[i + 1], v[i + 2]
            out.append((1 - t) ** 3 * p0 + 3 * (1 - t) ** 2 * t * p1
                       + 3 * (1 - t) * t ** 2 * p2 + t ** 3 * p3)
            i += 3
        else:
            out.append(v[i - 1] + t * (v[i] - v[i - 1]))
            i += 1
    return np.vstack(out)


def segments(vertices: Sequence[tuple[float, float]], codes: Sequence[int]) -> list[np.ndarray]:
    """The path cut at its through-points: one array of sampled points per piece."""
    v = np.asarray(vertices, dtype=float)
    pieces, i = [], 1
    while i < len(v):
        step = 3 if codes[i] == CURVE4 else 1
        pieces.append(sample(v[i - 1:i + step], (MOVETO,) + tuple(codes[i:i + step])))
        i += step
    return pieces


def label_candidates(pieces: list[np.ndarray], size: tuple[float, float],
                     gap: float = 3.0, ordered: bool = False) -> list[tuple[float, float]]:
    """Label centres along a route, best first: on the line near the middle of the
    middle piece (the first piece if ``ordered``), then further along it, then on other
    pieces, then beside the line (``gap`` from its centre line to the label's edge)."""
    w, h = size
    order = list(range(len(pieces))) if ordered else \
        sorted(range(len(pieces)), key=lambda k: (abs(k - (len(pieces) - 1) / 2), k))
    fractions = (0.5, 0.38, 0.62, 0.26, 0.74, 0.15, 0.85)
    on_line, beside = [], []
    for k in order:
        piece = pieces[k]
        for f in fractions:
            x, y = piece[int(round(f * (len(piece) - 1)))]
            on_line.append((float(x), float(y)))
            beside += [(float(x), float(y + h / 2 + gap)), (float(x), float(y - h / 2 - gap))]
    return on_line + beside


def stub_candidates(start: tuple[float, float], end: tuple[float, float],
                    size: tuple[float, float], clear: float, sink: Box,
                    gap: float = 3.0) -> list[tuple[float, float]]:
    """Label centres beside a short vertical arrow (a loss stub) and around its sink
    box, best first; ``clear`` is the half width of the symbols at its ends."""
    w, h = size
    x, y = (start[0] + end[0]) / 2, (start[1] + end[1]) / 2
    spots = []
    for dy in (0.0, -h / 4, -h / 2, h / 4, -h, h / 2):
        for side in (+1, -1):
            spots.append((x + side * (clear + gap + w / 2), y + dy))
    below = sink.y0 - gap - h / 2
    spots += [(x, below), (x + w / 2, below), (x - w / 2, below)]
    return spots


def place_label(candidates: list[tuple[float, float]], size: tuple[float, float],
                obstacles: list[Box], ink: np.ndarray, pad: float = 2.0):
    """The candidate whose box hits no obstacle and covers the fewest ink points
    (ties: the earlier candidate). Returns ``(centre, box)`` or None if all collide."""
    best, best_cost = None, None
    for rank, (x, y) in enumerate(candidates):
        box = Box.around(x, y, *size)
        if any(box.overlaps(o, pad) for o in obstacles):
            continue
        cost = (box.contains(ink), rank)
        if best_cost is None or cost < best_cost:
            best, best_cost = ((x, y), box), cost
            if cost[0] == 0:
                break
    return best


def head_polygon(vertices: Sequence[tuple[float, float]], codes: Sequence[int],
                 length: float, half_width: float) -> tuple[tuple[float, float], ...]:
    """The triangle of an arrowhead ending at the path's end: (tip, left, right)."""
    points = sample(vertices, codes)
    tip = points[-1]
    back = next((p for p in points[::-1] if np.hypot(*(tip - p)) >= length), points[0])
    direction = (tip - back) / max(float(np.hypot(*(tip - back))), 1e-9)
    normal = np.array([-direction[1], direction[0]])
    base = tip - direction * length
    return tuple((float(x), float(y)) for x, y in
                 (tip, base + normal * half_width, base - normal * half_width))


def head_box(vertices: Sequence[tuple[float, float]], codes: Sequence[int],
             length: float, half_width: float) -> Box:
    """The box around an arrowhead of the given size at the end of a path."""
    corners = np.array(head_polygon(vertices, codes, length, half_width))
    return Box(*corners.min(axis=0), *corners.max(axis=0))


def trim_end(vertices: Sequence[tuple[float, float]], codes: Sequence[int],
             length: float) -> tuple[tuple, tuple]:
    """The path without its last ``length`` points (where the arrowhead goes): the last
    piece is cut at the parameter found by bisection (de Casteljau for curves)."""
    v = [np.asarray(p, dtype=float) for p in vertices]
    step = 3 if codes[-1] == CURVE4 else 1
    piece, tip = v[-step - 1:], v[-1]
    if float(np.hypot(*(tip - piece[0]))) <= length:
        return tuple(vertices), tuple(codes)
    lo, hi = 0.0, 1.0
    for _ in range(40):
        mid = (lo + hi) / 2
        if float(np.hypot(*(tip - _split(piece, mid)[-1]))) > length:
            lo = mid
        else:
            hi = mid
    kept = _split(piece, lo)
    out = [tuple(map(float, p)) for p in v[:-step]] + [tuple(map(float, p)) for p in kept[1:]]
    return tuple(out), tuple(codes)


def _split(piece: list[np.ndarray], t: float) -> list[np.ndarray]:
    """Control points of the part [0, t] of a line or cubic Bezier (de Casteljau)."""
    if len(piece) == 2:
        return [piece[0], piece[0] + t * (piece[1] - piece[0])]
    p0, p1, p2, p3 = piece
    a, b, c = p0 + t * (p1 - p0), p1 + t * (p2 - p1), p2 + t * (p3 - p2)
    d, e = a + t * (b - a), b + t * (c - b)
    return [p0, a, d, d + t * (e - d)]


def bounds(boxes: list[Box], points: np.ndarray, margin: float) -> Box:
    """The smallest box around every box and point, plus a margin."""
    total = boxes[0]
    for box in boxes[1:]:
        total = total.union(box)
    if len(points):
        total = total.union(Box(*points.min(axis=0), *points.max(axis=0)))
    return Box(total.x0 - margin, total.y0 - margin, total.x1 + margin, total.y1 + margin)
