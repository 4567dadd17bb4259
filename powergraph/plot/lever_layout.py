"""Where everything of a lever diagram goes, in points (pure: no matplotlib).

Each lever is a vertical line, its nodes at ``LEVER_HEIGHT`` points per unit of position;
each node's speed a horizontal arrow at ``ARROW_LENGTH`` points for the fastest node
(rightwards for a positive speed), every lever at one scale. Beside each lever two
columns of text that no arrow reaches:

- on the left, right-aligned, each node's name with the shift elements on it
  (``s1 [A]``) and, before it, a badge per port on its body (``engine``, ``MG1``);
- on the right, each node's speed in rpm, written where its row is.

Arrows stay between the columns (the left column starts beyond the longest arrow to the
left, the right one beyond the longest to the right and the ground symbol), so no arrow
crosses a text. Texts of nodes closer than a line are moved apart, in order, as little
as it takes (the rows of a power-flow diagram: isotonic regression). Levers are as far
apart as their columns need, so long names push the next lever away instead of running
into it (names are cut at :data:`~powergraph.plot.layout.geometry.MAX_NAME` characters).
Under the levers: a speed scale bar in rpm and the ports on no lever with their speeds.

Examples
--------
>>> nice_step(1910.0), nice_step(99.0), nice_step(0.3)
(1000.0, 50.0, 0.2)
"""
from __future__ import annotations

import math
from typing import Any

from powergraph.format import format_number
from powergraph.plot.layout.geometry import (MAX_NAME, Box, TextSize, estimate_text_size,
                                             shortened)
from powergraph.plot.layout.place import _project
from powergraph.records import record
from powergraph.units_si import rpm

LEVER_HEIGHT = 190.0      # points per unit of position on the tallest lever
ARROW_LENGTH = 50.0       # points for the fastest node's arrow
GAP = 6.0                 # between an arrow's reach and its column, between badges
LEVER_GAP = 16.0          # between one lever's columns and the next's
#: White round every name and speed (points): a dashed line joining two members of one
#: body stops this far from the texts it passes.
TEXT_PAD = 3.0
GROUND = 16.0             # how far right the ground symbol reaches
CLEAR = 4.0               # an arrow this near a text's row (half its head) keeps it out


@record
class LeverText:
    """One text: anchored at ``(x, y)`` (``ha`` left/right/center, centred vertically),
    of a ``kind`` (``name``, ``speed``, ``input``/``output``/``machine`` badges,
    ``carrier``, ``scale``, ``note``) and ``size`` points; ``box`` its extent."""

    text: str
    x: float
    y: float
    ha: str
    kind: str
    size: float
    box: Box
    lever: int = -1
    component: str | None = None


@record
class LeverNodePlace:
    lever: int
    component: str
    body: str
    x: float
    y: float
    grounded: bool
    roles: tuple[str, ...]


@record
class LeverLayout:
    """Every lever (x, top, bottom), node, arrow, text and line of a diagram, in points."""

    levers: tuple[tuple[float, float, float], ...]
    nodes: tuple[LeverNodePlace, ...]
    arrows: tuple[tuple[tuple[float, float], tuple[float, float]], ...]
    speed_lines: tuple[tuple[tuple[float, float], ...], ...]
    links: tuple[tuple[tuple[float, float], tuple[float, float]], ...]
    texts: tuple[LeverText, ...]
    scale: tuple[float, float, float] | None        # x0, x1, y of the scale bar
    bounds: Box
    font_size: float


def nice_step(value: float) -> float:
    """The largest 1, 2 or 5 times a power of ten not above ``value``."""
    power = 10.0 ** math.floor(math.log10(value))
    return max(k * power for k in (1.0, 2.0, 5.0) if k * power <= value * (1 + 1e-12))


def format_rpm(speed: float | None, zero: float = 0.0) -> str:
    """A node's speed (rad/s) written in rpm, four significant digits, with a minus sign
    (not a hyphen: a dashed line beside it is not read as one); ``idle`` for none.

    >>> format_rpm(-61.26), format_rpm(None)
    ('−585', 'idle')
    """
    return "idle" if speed is None else format_number(rpm(speed), 4, zero).replace("-", "−")


def layout_levers(diagram: Any, text_size: TextSize = estimate_text_size,
                  font_size: float = 9.0) -> LeverLayout:
    """Lay out ``diagram`` (a :class:`~powergraph.analyses.lever.LeverDiagram`)."""
    small = font_size * 0.9
    nodes_all = [n for lever in diagram.levers for n in lever.nodes]
    speeds = [abs(n.speed) for n in nodes_all if n.speed is not None]
    fastest = max(speeds, default=0.0)
    per = ARROW_LENGTH / fastest if fastest > 0 else 0.0      # points per rad/s
    zero = 1e-9 * fastest
    shown = bool(speeds)
    spans = [max(n.position for n in lev.nodes) - min(n.position for n in lev.nodes)
             for lev in diagram.levers]
    unit = LEVER_HEIGHT / max(max(spans, default=1.0), 1e-9)

    columns, x, previous_right = [], 0.0, None
    for k, lever in enumerate(diagram.levers):
        col = _columns(diagram, k, lever, unit, per, zero, shown, text_size, font_size, small)
        x = col["left"] if previous_right is None else \
            x + previous_right + LEVER_GAP + col["left"]
        previous_right = col["right"]
        columns.append((x, col))

    texts, nodes, arrows, lines, levers = [], [], [], [], []
    for k, (x, col) in enumerate(columns):
        lever = diagram.levers[k]
        ys = [unit * n.position for n in lever.nodes]
        levers.append((x, max(ys), min(ys)))
        tips = []
        for node, y in zip(lever.nodes, ys):
            roles = tuple(p.role for p in diagram.ports_on(node))
            nodes.append(LeverNodePlace(k, node.component, node.body, x, y, node.grounded,
                                        roles))
            if node.speed is not None and per and abs(node.speed) > zero:
                arrows.append(((x, y), (x + per * node.speed, y)))
            if node.speed is not None and per:
                tips.append((x + per * node.speed, y))
        if len(tips) >= 2:
            lines.append(tuple(tips))
        texts += [_moved(t, x) for t in col["texts"]]
    links = _links(nodes)
    bottom = min((b.y0 for t in texts for b in [t.box]), default=0.0)
    bottom = min([bottom] + [lev[2] for lev in levers]) - 6.0
    scale, more = _scale(columns, fastest, per, bottom, text_size, small)
    texts += more
    if texts:
        texts += _note(diagram, zero, shown, min(t.box.y0 for t in texts) - 4.0,
                       min(t.box.x0 for t in texts), text_size, small)
    bounds = _bounds(texts, levers, arrows, scale)
    return LeverLayout(tuple(levers), tuple(nodes), tuple(arrows),
                       tuple(lines), tuple(links), tuple(texts), scale, bounds, font_size)


def _columns(diagram, k, lever, unit, per, zero, shown, text_size, font, small) -> dict:
    """The texts of one lever at x = 0, and how far they reach left and right. Each text
    starts just beyond the arrows (and ground symbols) of the rows it spans."""
    ys = [unit * n.position for n in lever.nodes]
    lefts = [-per * n.speed if n.speed is not None and n.speed < 0 else 0.0
             for n in lever.nodes]
    rights = [max(per * n.speed if n.speed is not None and n.speed > 0 else 0.0,
                  GROUND if n.grounded else 0.0) for n in lever.nodes]

    def reach(y: float, h: float, side: list[float]) -> float:
        return max([0.0] + [r for r, yn in zip(side, ys) if abs(yn - y) < h / 2 + CLEAR])

    rows = []                               # [(text, kind, size, (w, h))] right to left
    for node in lever.nodes:
        name = _name(node)
        items = [(name, "name", font, _padded(text_size(name, font)))]
        for port in diagram.ports_on(node):
            badge = shortened(port.name)
            items.append((badge, port.role, small, _badge(text_size(badge, small))))
        rows.append(items)
    heights = [max(size[1] for *_, size in items) for items in rows]
    texts = []
    for y, h, items, node in zip(_separate(ys, heights), heights, rows, lever.nodes):
        right = -(reach(y, h, lefts) + GAP)
        for text, kind, size, (w, th) in items:
            box = Box(right - w, y - th / 2, right, y + th / 2)
            texts.append(LeverText(text, right - TEXT_PAD if kind == "name" else right - w / 2,
                                   y, "right" if kind == "name" else "center", kind, size,
                                   box, k, node.component))
            right -= w + 2.0
    if shown:
        speeds = [format_rpm(n.speed, zero) for n in lever.nodes]
        sizes = [_padded(text_size(text, small)) for text in speeds]
        for node, y, text, (w, h) in zip(lever.nodes, _separate(ys, [h for _, h in sizes]),
                                         speeds, sizes):
            start = reach(y, h, rights) + GAP
            texts.append(LeverText(text, start + TEXT_PAD, y, "left", "speed", small,
                                   Box(start, y - h / 2, start + w, y + h / 2), k,
                                   node.component))
    label = shortened(f"carrier {lever.carrier}")
    w, h = text_size(label, small)
    low = min([min(ys)] + [t.box.y0 for t in texts]) - 4.0 - h / 2
    texts.append(LeverText(label, 0.0, low, "center", "carrier", small,
                           Box(-w / 2, low - h / 2, w / 2, low + h / 2), k))
    left = max([-t.box.x0 for t in texts] + lefts) + 2.0
    right = max([t.box.x1 for t in texts] + rights) + 2.0
    return {"left": left, "right": right, "texts": texts}


#: Room (points) round a badge's text for the rounded frame drawn round it.
BADGE_PAD = 2.0


def _name(node) -> str:
    """``s1 [A, B]``: the member and the shift elements on it, on two lines when that is
    longer than a name may be, each cut to that length."""
    elements = f"[{', '.join(node.elements)}]" if node.elements else ""
    name = f"{node.component} {elements}".strip()
    if len(name) <= MAX_NAME:
        return shortened(name)
    return shortened(node.component) + (f"\n{shortened(elements)}" if elements else "")


def _padded(size: tuple[float, float]) -> tuple[float, float]:
    return (size[0] + 2 * TEXT_PAD, size[1] + 2 * TEXT_PAD)


def _badge(size: tuple[float, float]) -> tuple[float, float]:
    """A badge's box: its text with room for its frame."""
    return (size[0] + 2 * BADGE_PAD, size[1] + 2 * BADGE_PAD)


def _separate(targets: list[float], heights: list[float], pad: float = 1.5) -> list[float]:
    """Rows of texts at ``targets`` moved apart as little as it takes (any order)."""
    order = sorted(range(len(targets)), key=lambda i: (-targets[i], i))
    seps = [(heights[a] + heights[b]) / 2 + pad for a, b in zip(order[:-1], order[1:])]
    moved = _project([(targets[i], 1.0) for i in order], seps)
    out = [0.0] * len(targets)
    for i, y in zip(order, moved):
        out[i] = y
    return out


def _moved(text: LeverText, dx: float) -> LeverText:
    b = text.box
    return LeverText(text.text, text.x + dx, text.y, text.ha, text.kind, text.size,
                     Box(b.x0 + dx, b.y0, b.x1 + dx, b.y1), text.lever, text.component)


def _links(nodes: list[LeverNodePlace]) -> list:
    """Dashed lines joining the nodes of one body on different levers, lever by lever."""
    by_body: dict[str, list[LeverNodePlace]] = {}
    for node in nodes:
        by_body.setdefault(node.body, []).append(node)
    links = []
    for members in by_body.values():
        if all(node.grounded for node in members):
            continue                  # the housing: each is marked held already
        for a, b in zip(members[:-1], members[1:]):
            if a.lever != b.lever:
                links.append(((a.x, a.y), (b.x, b.y)))
    return links


def _scale(columns, fastest, per, bottom, text_size, small):
    """The speed scale bar (x0, x1, y) under the first lever, captioned on its left and
    with its length in rpm on its right."""
    texts: list[LeverText] = []
    if not per:
        return None, texts
    step = nice_step(rpm(fastest))
    x0 = columns[0][0]
    x1 = x0 + per * step / rpm(1.0)
    y = bottom - 10.0
    for text, x, ha in (("speed scale", x0 - 6.0, "right"),
                        (f"{format_number(step, 4)} rpm", x1 + 6.0, "left")):
        w, h = text_size(text, small)
        x_left = x - w if ha == "right" else x
        texts.append(LeverText(text, x, y, ha, "scale", small,
                               Box(x_left, y - h / 2, x_left + w, y + h / 2)))
    return (x0, x1, y), texts


def _note(diagram, zero, shown, top, x, text_size, small) -> list[LeverText]:
    """One line naming the ports on no lever (wheels behind a final drive), with their
    speeds."""
    off = diagram.ports_off
    if not off:
        return []
    parts = [p.name + (f" ({p.role})" if p.name != p.role else "") + f" on {p.component}"
             + (f": {format_rpm(p.speed, zero)} rpm" if shown else "") for p in off]
    text = shortened("not on a lever: " + ", ".join(parts), 120)
    w, h = text_size(text, small)
    return [LeverText(text, x, top - h / 2, "left", "note", small,
                      Box(x, top - h, x + w, top))]


def _bounds(texts, levers, arrows, scale) -> Box:
    xs = [x for lev in levers for x in (lev[0] - 10, lev[0] + 10)]
    ys = [y for lev in levers for y in lev[1:]]
    for t in texts:
        xs += [t.box.x0, t.box.x1]
        ys += [t.box.y0, t.box.y1]
    for (a, b) in arrows:
        xs += [a[0], b[0]]
    if scale is not None:
        xs += [scale[0], scale[1]]
        ys += [scale[2]]
    margin = 6.0
    return Box(min(xs) - margin, min(ys) - margin, max(xs) + margin, max(ys) + margin)
