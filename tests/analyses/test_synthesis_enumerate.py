"""Enumeration of planetary gear train graphs (powergraph.analyses.synthesis.enumerate).

Expected counts: Yang W. & Ding H., "The complete set of one-degree-of-freedom planetary
gear trains with up to nine links", Journal of Mechanical Design 141(4), 2019 (abstract):
27 rotation graphs and 81 displacement graphs of 6 links, 152 and 647 of 7 links. For 3
and 4 links the count is derived by hand below; for 3 to 5 links an independent brute
force (every labelled tree, every level labelling, the fundamental-circuit rule walked on
tree paths, rigidity by the numerical rank of the Willis equations) must agree.
"""
from __future__ import annotations

import itertools
import json
import random

import numpy as np
import pytest

from powergraph.analyses.synthesis import TrainGraph, enumerate_trains
from powergraph.analyses.synthesis.canonical import (canonical_form, displacement_graph,
                                                     rotation_graph)
from powergraph.analyses.synthesis.enumerate import axes_of, d_graph, r_graph
from powergraph.analyses.synthesis.enumerate_models import model_document
from powergraph.errors import UsageError
from powergraph.kinematics import degrees_of_freedom
from powergraph.model import model_from_dict
from powergraph.statics import solve
from powergraph.testing import assert_conservation


# --- counts ------------------------------------------------------------------------------
def test_three_links_one_gear_pair() -> None:
    """By hand: one gear pair needs a carrier holding both gears on two axes, so the tree
    is the path gear-carrier-gear on two axes: one r-graph, one d-graph (the ordinary gear
    pair, or the K-H core of a K-H-V drive: eccentric carrier, planet, fixed ring)."""
    result = enumerate_trains(3)
    assert (result.rotation_graphs, result.displacement_graphs) == (1, 1)


def test_four_links_by_hand() -> None:
    """By hand, 4 links and 2 gear pairs. Axis structures: 3+2 coaxial links (one carrier
    with two coaxial links and one off-axis) allows only the planet meshing both coaxial
    links: the simple planetary. Three 2-link axes as a star on link 0: two of the three
    pairs among 1, 2, 3 carried by 0 (an ordinary three-gear train) - the same r-graph as
    the simple planetary (link 2 meshing 1 and 3, carried by 0) with other levels. Three
    2-link axes as a path 0-1-2-3: pairs 0-2 carried by 1 and 1-3 carried by 2 (nested
    planets), a second r-graph. A 4-link axis allows no mesh. So 2 r-graphs, 3 d-graphs."""
    result = enumerate_trains(4)
    assert (result.rotation_graphs, result.displacement_graphs) == (2, 3)


def test_six_links_published_counts() -> None:
    result = enumerate_trains(6)
    assert (result.rotation_graphs, result.displacement_graphs) == (27, 81)


@pytest.mark.slow
def test_seven_links_published_counts() -> None:
    result = enumerate_trains(7)
    assert (result.rotation_graphs, result.displacement_graphs) == (152, 647)


def _brute_force(links: int, dof: int) -> tuple[int, int]:
    """Counts by a different road: labelled trees (Pruefer codes) with every grouping of
    their edges into levels, gear pairs by walking tree paths (the levels change exactly
    once, at the transfer vertex), rigidity by the rank of random Willis equations."""
    rng = np.random.default_rng(7)
    d_forms, r_forms = set(), set()
    for code in itertools.product(range(links), repeat=links - 2):
        edges = _pruefer_tree(list(code), links)
        for levels in _level_labellings(edges):
            adjacency = {n: [] for n in range(links)}
            for (a, b), level in zip(edges, levels):
                adjacency[a].append((b, level))
                adjacency[b].append((a, level))
            circuits = []
            for u, v in itertools.combinations(range(links), 2):
                path = _path(adjacency, u, v)           # [(vertex, level of edge to it)]
                seq = [lv for _, lv in path[1:]]         # the levels of the edges
                change = [j for j in range(1, len(seq)) if seq[j] != seq[j - 1]]
                if len(change) == 1:                     # vertex between edges j-1, j
                    circuits.append((u, v, path[change[0]][0]))
            for gears in itertools.combinations(circuits, links - 1 - dof):
                axes = [{x for (a, b), lv in zip(edges, levels) if lv == level
                         for x in (a, b)} for level in set(levels)]
                if _numerically_sound(links, axes, gears, dof, rng):
                    d_forms.add(canonical_form(displacement_graph(links, axes, gears)))
                    r_forms.add(canonical_form(rotation_graph(links, gears)))
    return len(r_forms), len(d_forms)


def _pruefer_tree(code: list[int], n: int) -> list[tuple[int, int]]:
    degree = [1] * n
    for x in code:
        degree[x] += 1
    edges = []
    for x in code:
        leaf = min(i for i in range(n) if degree[i] == 1)
        edges.append((leaf, x))
        degree[leaf] -= 1
        degree[x] -= 1
    u, v = [i for i in range(n) if degree[i] == 1]
    return edges + [(u, v)]


def _level_labellings(edges):
    """Restricted-growth labellings whose equal labels form connected subtrees."""
    def grow(prefix):
        if len(prefix) == len(edges):
            yield tuple(prefix)
            return
        for label in range(max(prefix, default=-1) + 2):
            yield from grow(prefix + [label])
    for labels in grow([]):
        if all(len({x for e, lv in zip(edges, labels) if lv == level for x in e})
               == labels.count(level) + 1 for level in set(labels)):
            yield labels


def _path(adjacency, u, v):
    stack = [(u, [])]
    seen = {u}
    while stack:
        node, path = stack.pop()
        if node == v:
            return [(u, None)] + path
        for other, level in adjacency[node]:
            if other not in seen:
                seen.add(other)
                stack.append((other, path + [(other, level)]))
    raise AssertionError("a tree is connected")


def _numerically_sound(links, axes, gears, dof, rng) -> bool:
    """Willis rows w_u - w_c - k (w_v - w_c) = 0 with random k: the whole chain has
    ``dof`` freedoms, every connected proper sub-chain at least one. A sub-chain is
    connected through its coaxial links (k of them on one level turn relative to each other
    about one axis: k - 1 turning pairs), whichever of them carries the bearing."""
    for size in range(2, links + 1):
        for subset in itertools.combinations(range(links), size):
            inside = set(subset)
            if sum(max(0, len(inside & axis) - 1) for axis in axes) != size - 1:
                continue
            rows = []
            for u, v, c in gears:
                if {u, v, c} <= inside:
                    row = np.zeros(links)
                    k = rng.uniform(0.3, 3.0)
                    row[u], row[v], row[c] = 1.0, -k, k - 1.0
                    rows.append(row)
            rank = np.linalg.matrix_rank(np.array(rows)) if rows else 0
            freedom = size - 1 - rank
            if freedom != dof if size == links else freedom < 1:
                return False
    return True


@pytest.mark.parametrize("links", [3, 4])
def test_agrees_with_an_independent_brute_force(links: int) -> None:
    result = enumerate_trains(links)
    assert _brute_force(links, 1) == (result.rotation_graphs, result.displacement_graphs)


@pytest.mark.slow
def test_five_links_agree_with_the_brute_force() -> None:
    result = enumerate_trains(5)
    assert _brute_force(5, 1) == (result.rotation_graphs, result.displacement_graphs)
