"""Folding a layered power-flow diagram onto several bands, near 16 : 9 (pure numpy).

A train's flow graph is long and low: its layers, read left to right, made diagrams of
4.6-12 : 1 that a report can only print as a strip of tiny text. Here the layers are cut
into consecutive **bands** stacked top to bottom, each read left to right like a line of
text; an arrow from the last layer of a band to the first of the next leaves to the
right, runs back along a **lane** between the two bands and enters from the left, with
rounded corners. Lanes are nested so that they never cross one another (the topmost
arrow takes the outermost turn and the lowest lane), and are a label's height apart, so
that every label can sit on its own lane.

The cuts are chosen among all ways of cutting the layers into up to :data:`MAX_BANDS`
bands: the figure's aspect ratio near ``style.aspect`` (16 : 9), bands of even widths, few
arrows across a cut. When no choice falls in ``style.aspect_range`` the chosen one is
stretched into it (columns spread apart, or rows), never squeezed.

Examples
--------
>>> rounded([(0.0, 0.0), (10.0, 0.0), (10.0, -10.0)], 2.0)[1]
(1, 2, 4, 4, 4, 2)
"""
from __future__ import annotations

import itertools
import math
from typing import Mapping, Sequence

import numpy as np

from powergraph.plot.layout.geometry import CURVE4, LINETO, MOVETO
from powergraph.plot.layout.parts import LayoutStyle, Skeleton
from powergraph.records import record
from powergraph.statics.flow import Node

#: Most bands a diagram is folded onto, and most cut choices tried per band count.
MAX_BANDS, MAX_CHOICES = 6, 20000
#: Weight of uneven bands (the unused width of the shorter ones) in the choice of cuts.
BALANCE = 0.6
#: Circle approximation of a quarter turn by a cubic Bézier curve.
KAPPA = 0.5523
#: How far an arrow between nodes of one layer bulges to the right (place._side_path).
SIDE_BULGE = 42.0


@record
class Lane:
    """Where an arrow that crosses a cut turns: down at ``right`` (after its band), along
    ``y`` (between the bands), down at ``left`` (before the next band)."""

    right: float
    y: float
    left: float


@record
class Folding:
    """The bands of a diagram and where each layer and each band goes."""

    bands: tuple[tuple[int, int], ...]        # first and last layer of each band
    band_of: tuple[int, ...]                  # band of each layer
    x: tuple[float, ...]                      # x of each layer, in its band
    dy: tuple[float, ...]                     # y offset of each band
    y_scale: float
    lanes: Mapping[tuple[int, int], Lane]     # (flow index, step of its chain) -> lane
    radius: float = 6.0

    def point(self, layer: int, y: float) -> tuple[float, float]:
        """Where a node of ``layer`` at row ``y`` (unfolded) is drawn."""
        return (self.x[layer], self.y_scale * y + self.dy[self.band_of[layer]])

    def route(self, index: int, layers: Sequence[int],
              points: Sequence[tuple[float, float]]) -> tuple[tuple, tuple]:
        """Vertices and codes of flow ``index``'s arrow through ``points`` (one per layer
        of its chain): smooth curves with horizontal tangents inside a band, a lane
        between bands."""
        vertices, codes = [tuple(points[0])], [MOVETO]
        for step, (p, q) in enumerate(zip(points[:-1], points[1:])):
            lane = self.lanes.get((index, step))
            if lane is None or self.band_of[layers[step]] == self.band_of[layers[step + 1]]:
                k = (q[0] - p[0]) / 2
                vertices += [(p[0] + k, p[1]), (q[0] - k, q[1]), tuple(q)]
                codes += [CURVE4] * 3
                continue
            corners = [p, (lane.right, p[1]), (lane.right, lane.y), (lane.left, lane.y),
                       (lane.left, q[1]), q]
            more, more_codes = rounded(corners, self.radius)
            vertices += more[1:]
            codes += more_codes[1:]
        return tuple(vertices), tuple(codes)


def rounded(corners: Sequence[tuple[float, float]], radius: float) -> tuple[tuple, tuple]:
    """A polyline through ``corners`` with each corner rounded (quarter circles)."""
    points = [np.asarray(corners[0], dtype=float)]
    for c in corners[1:]:
        c = np.asarray(c, dtype=float)
        if np.hypot(*(c - points[-1])) > 1e-9:
            points.append(c)
    vertices, codes = [tuple(map(float, points[0]))], [MOVETO]
    for a, c, b in zip(points[:-2], points[1:-1], points[2:]):
        r = min(radius, np.hypot(*(c - a)) / 2, np.hypot(*(b - c)) / 2)
        start = c + (a - c) / np.hypot(*(a - c)) * r
        end = c + (b - c) / np.hypot(*(b - c)) * r
        for v, code in ((start, LINETO), (start + (c - start) * KAPPA, CURVE4),
                        (end + (c - end) * KAPPA, CURVE4), (end, CURVE4)):
            vertices.append(tuple(map(float, v)))
            codes.append(code)
    if len(points) > 1:
        vertices.append(tuple(map(float, points[-1])))
        codes.append(LINETO)
    return tuple(vertices), tuple(codes)


def fold(skeleton: Skeleton, x: Sequence[float], y: Mapping[Node, float],
         extents: Mapping[Node, tuple[float, float]], half: Sequence[float],
         label_height: float, widest: float, style: LayoutStyle) -> Folding:
    """The bands of ``skeleton`` whose layers are at ``x`` and nodes at rows ``y``.

    ``extents[n]`` is how far node ``n`` reaches (up, down), ``half[k]`` the half width
    of layer ``k``'s widest node; lanes are ``label_height`` apart and turns ``widest``
    (the widest arrow) apart.
    """
    count = len(skeleton.layers)
    crossing = _crossings(skeleton)
    geometry = _Geometry(skeleton, x, y, extents, half, crossing, label_height, widest)
    bands = ((0, count - 1),)
    if style.aspect is not None and count > 1:
        bands = _best_bands(geometry, count, style)
    extra, scale = 0.0, 1.0
    if style.aspect is not None:
        extra, scale = _stretch(geometry, bands, style)
    return geometry.folding(bands, extra, scale)


def _crossings(skeleton: Skeleton) -> dict[int, list[tuple[int, int]]]:
    """Chain steps from layer k to layer k + 1, by k: (flow index, step)."""
    out: dict[int, list[tuple[int, int]]] = {}
    for i, chain in skeleton.chains.items():
        if i in skeleton.side:
            continue
        for step, a in enumerate(chain[:-1]):
            out.setdefault(skeleton.layer_of[a], []).append((i, step))
    return out


class _Geometry:
    """Sizes of candidate bands (widths, heights at a row scale) and of the gaps."""

    def __init__(self, skeleton, x, y, extents, half, crossing, label_height, widest):
        self.skeleton, self.crossing = skeleton, crossing
        self.x, self.half = list(map(float, x)), list(map(float, half))
        self.base = label_height / 2 + 6.0          # band edge to the nearest lane
        self.lane_gap = label_height + 3.0          # lane to lane
        self.turn_gap = widest + 5.0                # turn to turn
        self.bulge = [SIDE_BULGE if any(skeleton.layer_of[skeleton.chains[i][0]] == k
                                        for i in skeleton.side) else 0.0
                      for k in range(len(skeleton.layers))]
        self.rows = [np.array([(y[n], *extents[n]) for n in layer] or [(0.0, 0.0, 0.0)])
                     for layer in skeleton.layers]
        self.y = y
        count = len(self.rows)
        self._spans = {}                             # (first, last) -> (top, bottom) at 1
        for first in range(count):
            top, bottom = -np.inf, np.inf
            for last in range(first, count):
                rows = self.rows[last]
                top = max(top, float(np.max(rows[:, 0] + rows[:, 1])))
                bottom = min(bottom, float(np.min(rows[:, 0] - rows[:, 2])))
                self._spans[(first, last)] = (top, bottom)

    def lanes(self, cut: int) -> int:
        return len(self.crossing.get(cut, ()))

    def turn(self, cut: int) -> float:
        """Room a cut's turns take beside a band."""
        return self.base + max(self.lanes(cut) - 1, 0) * self.turn_gap + 6.0

    def gap(self, cut: int) -> float:
        return 2 * self.base + max(self.lanes(cut) - 1, 0) * self.lane_gap

    def width(self, first: int, last: int, extra: float) -> float:
        return (self.x[last] - self.x[first] + (last - first) * extra + self.half[first]
                + self.half[last] + self.bulge[last])

    def span(self, first: int, last: int, scale: float) -> tuple[float, float]:
        """(top, bottom) of the band's nodes with rows scaled by ``scale``."""
        if scale == 1.0:
            return self._spans[(first, last)]
        rows = np.vstack(self.rows[first:last + 1])
        return (float(np.max(scale * rows[:, 0] + rows[:, 1])),
                float(np.min(scale * rows[:, 0] - rows[:, 2])))

    def size(self, bands, extra: float = 0.0, scale: float = 1.0) -> tuple[float, float, list]:
        """Width, height and the band widths of a folding."""
        widths, height = [], 0.0
        for b, (first, last) in enumerate(bands):
            w = self.width(first, last, extra)
            if b > 0:
                w += self.turn(first - 1)
                height += self.gap(first - 1)
            if b < len(bands) - 1:
                w += self.turn(last)
            top, bottom = self.span(first, last, scale)
            widths.append(w)
            height += top - bottom
        return max(widths), height, widths

    def folding(self, bands, extra: float, scale: float) -> Folding:
        band_of = [0] * len(self.x)
        xs = [0.0] * len(self.x)
        for b, (first, last) in enumerate(bands):
            for k in range(first, last + 1):
                band_of[k] = b
                xs[k] = self.x[k] - self.x[first] + (k - first) * extra
        dy, bottom = [], 0.0
        for b, (first, last) in enumerate(bands):
            top, low = self.span(first, last, scale)
            offset = 0.0 if b == 0 else bottom - self.gap(first - 1) - top
            dy.append(offset)
            bottom = low + offset
        folding = Folding(tuple(bands), tuple(band_of), tuple(xs), tuple(dy), scale, {})
        lanes = {}
        for b, (first, last) in enumerate(bands[:-1]):
            lanes.update(self._lanes(folding, b, last, bands[b + 1][0]))
        return Folding(tuple(bands), tuple(band_of), tuple(xs), tuple(dy), scale, lanes)

    def _lanes(self, folding: Folding, band: int, last: int, first: int) -> dict:
        skeleton = self.skeleton
        steps = self.crossing.get(last, [])

        def at(node: Node) -> float:
            return folding.point(skeleton.layer_of[node], self.y[node])[1]
        steps = sorted(steps, key=lambda s: (-at(skeleton.chains[s[0]][s[1]]),
                                             -at(skeleton.chains[s[0]][s[1] + 1]), s))
        first_band, _ = folding.bands[band]
        right = max(folding.x[k] + self.half[k] + self.bulge[k] for k in range(first_band,
                                                                                 last + 1))
        left = folding.x[first] - self.half[first]
        top = self.span(first, folding.bands[band + 1][1], folding.y_scale)[0] \
            + folding.dy[band + 1]
        m = len(steps)
        return {s: Lane(right=right + self.base + (m - 1 - t) * self.turn_gap,
                        y=top + self.base + t * self.lane_gap,
                        left=left - self.base - t * self.turn_gap)
                for t, s in enumerate(steps)}


def _best_bands(geometry: _Geometry, count: int, style: LayoutStyle):
    """The cut choice of least cost (aspect, balance, arrows across cuts)."""
    best, best_cost = ((0, count - 1),), None
    for n in range(1, min(count, MAX_BANDS) + 1):
        if math.comb(count - 1, n - 1) > MAX_CHOICES:
            break
        for cuts in itertools.combinations(range(count - 1), n - 1):
            bands = _bands(cuts, count)
            if n > 1 and any(first == last for first, last in bands):
                continue                         # a lone layer is no line to read
            width, height, widths = geometry.size(bands)
            cost = _cost(width / height, style) \
                + BALANCE * (1.0 - float(np.mean(widths)) / width) \
                + 0.04 * sum(geometry.lanes(c) for c in cuts)
            if best_cost is None or cost < best_cost - 1e-12:
                best, best_cost = bands, cost
    return best


def _bands(cuts: Sequence[int], count: int) -> tuple[tuple[int, int], ...]:
    edges = [-1, *cuts, count - 1]
    return tuple((a + 1, b) for a, b in zip(edges[:-1], edges[1:]))


def _cost(aspect: float, style: LayoutStyle) -> float:
    """Distance from the aspect aimed at; spreading columns apart (whitespace between
    every layer) counts double, spreading rows apart once."""
    lo, hi = style.aspect_range
    stretch = 2 * math.log(lo / aspect) if aspect < lo else \
        math.log(aspect / hi) if aspect > hi else 0.0
    within = min(max(aspect, lo), hi)
    return stretch + abs(math.log(within / style.aspect))


def _stretch(geometry: _Geometry, bands, style: LayoutStyle) -> tuple[float, float]:
    """(extra column gap, row scale) that bring the folding's aspect into range."""
    lo, hi = style.aspect_range
    width, height, _ = geometry.size(bands)
    if width / height < lo:
        low, high = 0.0, 10 * max(width, height)
        for _ in range(50):
            mid = (low + high) / 2
            w, h, _ = geometry.size(bands, extra=mid)
            low, high = (mid, high) if w / h < lo else (low, mid)
        return high, 1.0
    if width / height > hi:
        low, high = 1.0, 1.0
        while geometry.size(bands, scale=high)[0] / geometry.size(bands, scale=high)[1] > hi:
            if high > 1e3:
                return 0.0, 1.0                  # rows that do not grow: left as they are
            low, high = high, high * 2
        for _ in range(50):
            mid = (low + high) / 2
            w, h, _ = geometry.size(bands, scale=mid)
            low, high = (mid, high) if w / h > hi else (low, mid)
        return 0.0, high
    return 0.0, 1.0
