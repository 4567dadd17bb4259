"""The tooth-space search: branch and bound on the ratio, exact test at the leaves.

A layout's grid (:mod:`~powergraph.analyses.synthesis.teeth`) is the product of its
**factors**: the feasible rows of each planet block (already coaxial, clear of their
neighbours and, alone in their cluster, assemblable) and the tooth number of each K-H-V
stage. Each factor's rows are sorted and cut into aligned segments of ``2^L`` rows; a
**node** is one segment per factor, a box of the grid. Over a node every Willis ratio
``i_k`` lies in an interval (its smallest and largest value over the segment; for a
planet-planet mesh, from the two step ranges).

The ratio of two coaxial speeds is ``N(i) / D(i)`` in lowest terms, both **multilinear**
in the ``i_k`` (factors of cofactors of the Willis system, where each ratio enters one row
once; :func:`ratio_functions` checks it), so linear-fractional in each ``i_k``. If ``D``
keeps one strict sign on the ``2^G`` corners of the box, it keeps it on the whole box (a
multilinear function takes its extremes at corners), the ratio has no pole there, is
monotonic in each ``i_k``, and its range over the box lies between its smallest and
largest corner value. A planet block entering the speeds through one quotient
(:func:`quotient_pairs`) is sorted by it and bounded through it. A node whose range misses
``ratio (1 ± tolerance)`` for every working choice of fixed link, input and output holds
no hit and is dropped; otherwise it is split in two along its largest factor. Nodes
of at most :data:`LEAF` grid points are enumerated and every point passes the exact test of
:func:`~powergraph.analyses.synthesis.synthesize_search.exact_hits`, the test a plain grid
scan applies. The pruning only drops boxes that provably hold no hit (a slack of
``1e-6`` relative covers rounding), so the hits are exactly those of the full grid scan.

Examples
--------
>>> from powergraph.analyses.synthesis.synthesize_classics import CLASSICS
>>> graph = CLASSICS["2K-H"]
>>> hits = search_part(graph, 0, 0, 0, 1, 4.0, 0.001, (12, 40), 3)
>>> sorted({(h.fixed, h.input, h.output) for h in hits})     # ring 1 fixed: sun 0 in
[(1, 0, 3)]
"""
from __future__ import annotations

import functools

import numpy as np

from powergraph.analyses.synthesis.graph import TrainGraph
from powergraph.analyses.synthesis.synthesize_search import (Hits, exact_hits, graph_layouts,
                                                             ratio_functions,
                                                             speed_expressions,
                                                             willis_ratios, working)
from powergraph.analyses.synthesis.teeth import Layout
from powergraph.records import record

#: Nodes of at most this many grid points are enumerated and tested exactly.
LEAF = 64
#: Layouts of at most this many grid points are scanned whole (bounding would cost more).
SCAN = 1 << 18
#: Nodes bounded at once (bounds the memory of a search).
BATCH = 1 << 11
#: Relative slack of the bound test (rounding of the two evaluations of the ratio).
SLACK = 1e-6


@record
class Factor:
    """One factor of a layout's grid, its rows sorted, with per-level segment extremes.

    ``order[p]`` is the grid row at sorted position ``p``; ``low[q]`` / ``high[q]`` hold,
    level after level (``offsets``), the extremes of quantity ``q`` (``("i", k)``: Willis
    ratio of a pair of this factor alone; ``("z", k, side)``: a planet step of a
    planet-planet pair) over each aligned segment of ``2^L`` sorted rows.
    """

    size: int
    stride: int
    height: int
    order: np.ndarray
    offsets: np.ndarray
    low: dict
    high: dict


def _owners(layout: Layout) -> list[tuple[int, ...]]:
    """Per gear pair, the factors its teeth depend on (blocks, then K-H-V stages)."""
    st = layout.structure
    block_of = {b.planet: f for f, b in enumerate(layout.blocks)}
    out = []
    for k, (u, v, _) in enumerate(layout.graph.gear_pairs):
        if st.kinds[k] == "khv":
            out.append((len(layout.blocks) + layout.khv_pairs.index(k),))
        elif st.kinds[k] == "pp":
            out.append((block_of[u], block_of[v]))
        else:
            out.append((block_of[v if st.coaxial_side[k] == 0 else u],))
    return out


@functools.lru_cache(maxsize=256)
def factors(graph: TrainGraph, layout_index: int, teeth: tuple[int, int], planets: int
            ) -> tuple[Factor, ...]:
    """The :class:`Factor` trees of one layout (cached per process)."""
    layout = graph_layouts(graph, teeth, planets)[layout_index]
    shape = layout.shape
    strides = [int(np.prod(shape[f + 1:], dtype=np.int64)) for f in range(len(shape))]
    owners = _owners(layout)
    moving = moving_pairs(graph)
    out = []
    for f, (size, stride) in enumerate(zip(shape, strides)):
        rows = np.arange(size, dtype=np.int64)
        z = layout.teeth(rows * stride)
        i = willis_ratios(layout, z)
        values = {("i", k): i[k] for k, own in enumerate(owners) if own == (f,)}
        ordering = [v for (_, k), v in values.items() if k in moving] or list(values.values())
        pairs = quotient_pairs(layout, f)
        if pairs is not None and set(pairs) <= moving:
            values = {("q",): _quotient(layout, pairs, i)}
            ordering = [values[("q",)]]
        for k, own in enumerate(owners):
            for side, g in enumerate(own if len(own) == 2 else ()):
                if g == f:
                    values[("z", k, side)] = z[(k, side)].astype(float)
        order = np.argsort(_morton(ordering), kind="stable") if ordering else rows
        height = max(0, int(size - 1).bit_length())
        low, high = {}, {}
        for q, v in values.items():
            low[q], high[q] = _levels(np.asarray(v, float)[order], height)
        offsets = np.concatenate([[0], np.cumsum([1 << (height - L) for L in range(height)])])
        out.append(Factor(size, stride, height, order, offsets.astype(np.int64), low, high))
    return tuple(out)


def quotient_pairs(layout: Layout, f: int) -> tuple[int, int] | None:
    """The two cp pairs ``(k1, k2)`` of factor ``f`` when it is a planet block whose speeds
    enter the coaxial ones through one quotient only: two meshes with coaxial gears, no
    planet-planet mesh, carrying nothing. Its Willis rows ``w_g - w_c = e_k (w_p - w_c)``
    (``e_k = i_k`` with the coaxial gear on side a, ``1 / i_k`` on side b) leave, the
    planet's own speed eliminated, ``w_g2 - w_c = (e_k2 / e_k1)(w_g1 - w_c)``: every
    coaxial speed depends on ``q = e_k2 / e_k1`` alone. Else None."""
    st = layout.structure
    if f >= len(layout.blocks):
        return None
    block = layout.blocks[f]
    if (len(block.cp_pairs) != 2 or st.phased(block.planet)
            or any(st.kinds[k] == "pp" for step in block.steps for k in step)):
        return None
    return block.cp_pairs[0], block.cp_pairs[1]


def _quotient(layout: Layout, pairs: tuple[int, int], i: list) -> np.ndarray:
    """``q = e_k2 / e_k1`` per row (:func:`quotient_pairs`)."""
    e = [i[k] if layout.structure.coaxial_side[k] == 0 else 1.0 / i[k] for k in pairs]
    return np.asarray(e[1] / e[0], dtype=float)


def _morton(values: list) -> np.ndarray:
    """Z-order key of each row over the ranks of (at most three of) its quantities: the
    rows of an aligned segment then span a small box in every quantity at once, not a
    strip (as a lexicographic order would)."""
    values = values[:3]
    key = np.zeros(len(values[0]) if values else 0, dtype=np.uint64)
    if not values:
        return key
    bits = 63 // len(values)
    ranks = []
    for v in values:
        _, rank = np.unique(np.asarray(v, float), return_inverse=True)
        scale = max(1, int(rank.max()) + 1)
        ranks.append((rank.astype(np.float64) * (1 << bits) / scale).astype(np.uint64))
    for b in range(bits):
        for d, r in enumerate(ranks):
            key |= ((r >> np.uint64(b)) & np.uint64(1)) << np.uint64(b * len(ranks) + d)
    return key


def _levels(values: np.ndarray, height: int) -> tuple[np.ndarray, np.ndarray]:
    """Segment minima and maxima of ``values`` (padded to ``2^height``), level 0 first."""
    lo = np.full(1 << height, np.inf)
    hi = np.full(1 << height, -np.inf)
    lo[:values.size], hi[:values.size] = values, values
    lows, highs = [lo], [hi]
    for _ in range(height):
        lo, hi = lo.reshape(-1, 2).min(axis=1), hi.reshape(-1, 2).max(axis=1)
        lows.append(lo)
        highs.append(hi)
    return np.concatenate(lows), np.concatenate(highs)


def _counts(tree: tuple[Factor, ...], level: np.ndarray, index: np.ndarray) -> np.ndarray:
    """Rows of each node's segment per factor, shape (nodes, factors)."""
    sizes = np.array([f.size for f in tree], dtype=np.int64)
    width = np.left_shift(1, level.astype(np.int64))
    return np.clip(np.minimum(width, sizes - index * width), 0, None)


def _intervals(layout: Layout, tree, level, index) -> tuple[list, list]:
    """Each Willis ratio's smallest and largest value over each node."""
    owners = _owners(layout)
    lows, highs = [], []
    for k, own in enumerate(owners):
        def extremes(q, f):
            at = tree[f].offsets[level[:, f]] + index[:, f]
            return tree[f].low[q][at], tree[f].high[q][at]

        pairs = quotient_pairs(layout, own[0]) if ("q",) in tree[own[0]].low else None
        if pairs is not None and k == pairs[0]:     # e_k1 = 1: i_k1 = 1
            lo = hi = np.ones(level.shape[0])
        elif pairs is not None:                     # e_k2 = q (q keeps one sign)
            lo, hi = extremes(("q",), own[0])
            if layout.structure.coaxial_side[k] == 1:
                lo, hi = 1.0 / hi, 1.0 / lo
        elif len(own) == 1:
            lo, hi = extremes(("i", k), own[0])
        else:                       # planet-planet: i = -z_b / z_a, both teeth positive
            (a0, a1), (b0, b1) = extremes(("z", k, 0), own[0]), extremes(("z", k, 1), own[1])
            lo, hi = -b1 / a0, -b0 / a1
        lows.append(lo)
        highs.append(hi)
    return lows, highs


def may_hit(graph: TrainGraph, lows: list, highs: list, band: tuple[float, float]
            ) -> np.ndarray:
    """False where no ratio of any working arrangement can reach ``band`` over the box
    ``lows .. highs`` of the Willis ratios (module docstring). Both ``w_in / w_out`` and
    its inverse are bounded: a large ratio lies near a pole of the first (the output
    nearly still), where only the second can be bounded."""
    n = lows[0].shape[0] if lows else 1
    corners = 1 << len(lows)
    args = [np.concatenate([hi if (c >> k) & 1 else lo for c in range(corners)])
            for k, (lo, hi) in enumerate(zip(lows, highs))]
    inverse = tuple(sorted((1.0 / band[0], 1.0 / band[1])))
    alive = np.zeros(n, dtype=bool)
    for fixed, pairs, fn, linear in ratio_functions(graph):
        if not linear:
            return np.ones(n, dtype=bool)
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            p = [np.broadcast_to(np.asarray(v, float), (corners * n,)).reshape(corners, n)
                 for v in fn(*args)]
            for j, (a, b) in enumerate(pairs):
                for x, y, top, bottom in ((a, b, p[2 * j], p[2 * j + 1]),
                                          (b, a, p[2 * j + 1], p[2 * j])):
                    if working(graph, fixed, x, y):
                        alive |= _reaches(top, bottom, band) & _reaches(bottom, top, inverse)
    return alive


def _reaches(numerator: np.ndarray, denominator: np.ndarray, band: tuple[float, float]
             ) -> np.ndarray:
    """Whether ``numerator / denominator`` (corner values, axis 0) may reach ``band``:
    unknown (True) where the denominator does not keep one strict sign."""
    strict = (denominator > 0).all(axis=0) | (denominator < 0).all(axis=0)
    r = numerator / denominator
    return ~strict | ((r.max(axis=0) >= band[0]) & (r.min(axis=0) <= band[1]))


@functools.lru_cache(maxsize=256)
def influential(graph: TrainGraph, layout_index: int, teeth: tuple[int, int], planets: int
                ) -> np.ndarray:
    """Per factor, whether some speed depends on it (an idle planet's teeth move no
    ratio: its factor is enumerated whole at the leaves, never split)."""
    layout = graph_layouts(graph, teeth, planets)[layout_index]
    out = np.zeros(len(layout.shape), dtype=bool)
    for k, own in enumerate(_owners(layout)):
        if k in moving_pairs(graph):
            out[list(own)] = True
    return out


@functools.lru_cache(maxsize=64)
def moving_pairs(graph: TrainGraph) -> frozenset[int]:
    """The gear pairs whose Willis ratio enters some speed."""
    import sympy as sp

    used = {str(s) for *_, expressions in speed_expressions(graph)
            for e in expressions for s in sp.sympify(e).free_symbols}
    return frozenset(k for k in range(len(graph.gear_pairs)) if f"i_{k}" in used)


def _split(tree, level, index, counts) -> tuple[np.ndarray, np.ndarray]:
    """Each node cut in two along its factor with the most rows (``counts`` zeroed where
    a factor is not to be split)."""
    f = np.argmax(counts, axis=1)
    rows = np.arange(level.shape[0])
    level = level.copy()
    level[rows, f] -= 1
    left, right = index.copy(), index.copy()
    left[rows, f] = 2 * index[rows, f]
    right[rows, f] = 2 * index[rows, f] + 1
    level, index = np.concatenate([level, level]), np.concatenate([left, right])
    keep = (_counts(tree, level, index) > 0).all(axis=1)
    return level[keep], index[keep]


def _points(tree, level, index, counts) -> np.ndarray:
    """The flat grid indices of the leaf nodes, sorted."""
    per = np.prod(counts, axis=1)
    node = np.repeat(np.arange(per.size), per)
    local = np.arange(node.size) - np.repeat(np.cumsum(per) - per, per)
    flat = np.zeros(node.size, dtype=np.int64)
    for f in reversed(range(len(tree))):
        offset = local % counts[node, f]
        local //= counts[node, f]
        position = (index[node, f] << level[node, f].astype(np.int64)) + offset
        flat += tree[f].order[position] * tree[f].stride
    return np.sort(flat)


def roots(tree: tuple[Factor, ...], parts: int) -> tuple[np.ndarray, np.ndarray]:
    """The whole grid as one node, split (without bounds) into at least ``parts`` nodes
    when it can be."""
    level = np.array([[f.height for f in tree]], dtype=np.int64)
    index = np.zeros_like(level)
    while level.shape[0] < parts and (level > 0).any():
        level, index = _split(tree, level, index, _counts(tree, level, index))
    return level, index


def search_part(graph: TrainGraph, graph_index: int, layout_index: int, part: int,
                parts: int, ratio: float, tolerance: float, teeth: tuple[int, int],
                planets: int) -> list[Hits]:
    """Hits of part ``part`` of ``parts`` of one layout's grid (every ``parts``-th node
    of :func:`roots`), found by branch and bound (module docstring)."""
    layout = graph_layouts(graph, teeth, planets)[layout_index]
    if layout.size == 0:
        return []
    tree = factors(graph, layout_index, teeth, planets)
    band = tuple(sorted((ratio * (1 - tolerance), ratio * (1 + tolerance))))
    slack = SLACK * abs(ratio)
    band = (band[0] - slack, band[1] + slack)
    moving = influential(graph, layout_index, teeth, planets)
    limit = SCAN if layout.size <= SCAN else LEAF
    found: dict[tuple[int, int, int], list[np.ndarray]] = {}
    level, index = roots(tree, parts)
    stack = [(level[part::parts], index[part::parts])]
    while stack:
        level, index = stack.pop()
        if level.shape[0] > BATCH:
            stack += [(level[s:s + BATCH], index[s:s + BATCH])
                      for s in range(0, level.shape[0], BATCH)]
            continue
        counts = _counts(tree, level, index)
        if tree:
            lows, highs = _intervals(layout, tree, level, index)
            keep = may_hit(graph, lows, highs, band)
            level, index, counts = level[keep], index[keep], counts[keep]
        split = np.where(moving, counts, 0)
        leaf = (np.prod(counts.astype(float), axis=1) <= limit) | (split <= 1).all(axis=1)
        if leaf.any():
            flat = _points(tree, level[leaf], index[leaf], counts[leaf])
            for key, hits in exact_hits(graph, layout, flat, ratio, tolerance).items():
                found.setdefault(key, []).append(hits)
        if (~leaf).any():
            stack.append(_split(tree, level[~leaf], index[~leaf], split[~leaf]))
    return [Hits(graph_index, layout_index, *key, flat=np.sort(np.concatenate(parts_)))
            for key, parts_ in sorted(found.items())]
