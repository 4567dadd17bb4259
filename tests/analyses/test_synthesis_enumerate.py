"""Enumeration of planetary gear train graphs (powergraph.analyses.synthesis.enumerate).

Expected counts: Yang W. & Ding H., "The complete set of one-degree-of-freedom planetary
gear trains with up to nine links", Journal of Mechanical Design 141(4), 2019 (abstract):
27 rotation graphs and 81 displacement graphs of 6 links, 152 and 647 of 7 links. For 3
and 4 links the count is derived by hand below; for 3 to 5 links an independent brute
force (every labelled tree, every level labelling, the fundamental-circuit rule walked on
tree paths, rigidity by the numerical rank of the Willis equations) must agree.
"""
from __future__ import annotations

import functools
import itertools
import json
import random

import numpy as np
import pytest

from powergraph.analyses.synthesis import TrainGraph
from powergraph.analyses.synthesis import enumerate_trains as _enumerate_trains
from powergraph.analyses.synthesis.canonical import (canonical_form, displacement_graph,
                                                     rotation_graph)
from powergraph.analyses.synthesis.enumerate import axes_of, d_graph, r_graph
from powergraph.analyses.synthesis.enumerate_models import model_document
from powergraph.errors import UsageError
from powergraph.kinematics import degrees_of_freedom
from powergraph.model import model_from_dict
from powergraph.statics import solve
from powergraph.testing import assert_conservation

# The results are frozen; the tests share them.
enumerate_trains = functools.lru_cache(maxsize=None)(_enumerate_trains)


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


def test_two_dof_fractionated_trains_are_kept_only_on_request() -> None:
    """Five links, two gear pairs, two DOF: a carrier 0 holding the pair 3-4, and a second
    carrier 1 on 0 holding the pair 0-2, shares only link 0 with it (fractionated: two
    1-DOF trains with one link in common), so it appears only with fractionated=True."""
    split = TrainGraph(5, ((0, 3, 0), (0, 4, 1), (0, 1, 2), (1, 2, 3)), ((0, 2, 1), (3, 4, 0)))
    assert enumerate_trains(5, 2).find(split) is None
    assert enumerate_trains(5, 2, fractionated=True).find(split) is not None


def test_every_two_dof_link_meshes_or_carries() -> None:
    for graph in enumerate_trains(6, 2).graphs:
        assert {x for pair in graph.gear_pairs for x in pair} == set(range(6))


def test_bad_sizes_are_usage_errors() -> None:
    for links, dof in [(2, 1), (10, 1), (5, 0), (5, 4), (5.0, 1), (True, 1)]:
        with pytest.raises(UsageError):
            _enumerate_trains(links, dof)


# --- every graph is a train powergraph solves --------------------------------------------
@pytest.mark.parametrize("links, dof", [(3, 1), (4, 1), (5, 1), (5, 2),
                                        pytest.param(6, 1, marks=pytest.mark.slow),
                                        pytest.param(6, 2, marks=pytest.mark.slow),
                                        pytest.param(6, 3, marks=pytest.mark.slow)])
def test_every_graph_solves_with_the_dof_it_claims(links: int, dof: int) -> None:
    """Placeholder teeth (distinct primes, external), a frame and ports among the coaxial
    links: the model is valid, has ``dof`` degrees of freedom, solves and conserves."""
    for graph in enumerate_trains(links, dof).graphs:
        assert graph.dof == dof
        model = model_from_dict(model_document(graph, mesh_efficiency=0.97))
        assert degrees_of_freedom(model) == dof
        assert_conservation(solve(model))


def test_the_model_document_says_its_teeth_are_placeholders() -> None:
    doc = model_document(enumerate_trains(4).graphs[0])
    assert "placeholder" in doc["description"]
    assert len({c["teeth"] for c in doc["components"].values() if "teeth" in c}) == 4


# --- isomorphism ---------------------------------------------------------------------------
def _relabelled(graph: TrainGraph, rng: random.Random) -> TrainGraph:
    """Links renumbered, axis labels renumbered, each axis journalled as another tree
    (every coaxial link on one of them, chosen at random): the same train."""
    links = list(range(graph.links))
    rng.shuffle(links)
    labels = list(range(len(axes_of(graph))))
    rng.shuffle(labels)
    turning = []
    for label, axis in zip(labels, axes_of(graph)):
        hub = rng.choice(sorted(axis))
        turning += [(links[hub], links[x], label) for x in sorted(axis) if x != hub]
    gears = [(links[u], links[v], links[c]) for u, v, c in graph.gear_pairs]
    rng.shuffle(turning)
    rng.shuffle(gears)
    return TrainGraph(graph.links, tuple(turning), tuple(gears))


def test_relabelled_links_give_the_same_canonical_form_and_graph() -> None:
    rng = random.Random(11)
    result = enumerate_trains(5)
    for index, graph in enumerate(result.graphs):
        other = _relabelled(graph, rng)
        assert canonical_form(d_graph(other)) == canonical_form(d_graph(graph))
        assert canonical_form(r_graph(other)) == canonical_form(r_graph(graph))
        assert result.find(other) == index


@pytest.mark.slow
def test_the_graphs_are_pairwise_non_isomorphic_by_the_canonical_form() -> None:
    """An exact certificate, independent of the VF2 matcher used by the enumeration."""
    result = enumerate_trains(6)
    assert len({canonical_form(d_graph(g)) for g in result.graphs}) == 81
    assert len({canonical_form(r_graph(g)) for g in result.graphs}) == 27
    classes = {}
    for graph, index in zip(result.graphs, result.rotation_index):
        classes.setdefault(index, set()).add(canonical_form(r_graph(graph)))
    assert all(len(forms) == 1 for forms in classes.values())


def test_bearing_arrangement_is_not_a_new_train() -> None:
    """Pseudo-isomorphism: the sun journalled in the frame or in the carrier (a different
    labelled tree) is the same simple planetary."""
    in_frame = TrainGraph(4, ((0, 1, 0), (0, 2, 0), (2, 3, 1)), ((1, 3, 2), (0, 3, 2)))
    in_carrier = TrainGraph(4, ((0, 2, 0), (2, 1, 0), (2, 3, 1)), ((1, 3, 2), (0, 3, 2)))
    assert canonical_form(d_graph(in_frame)) == canonical_form(d_graph(in_carrier))


def test_same_rotation_graph_different_trains() -> None:
    """Pseudo-isomorphism the other way: the simple planetary and the ordinary three-gear
    train (gears 1 and 3 not coaxial) mesh alike about the same carrier - one r-graph - but
    are different trains (d-graphs)."""
    planetary = TrainGraph(4, ((0, 1, 0), (0, 3, 0), (0, 2, 1)), ((1, 2, 0), (2, 3, 0)))
    ordinary = TrainGraph(4, ((0, 1, 0), (0, 2, 1), (0, 3, 2)), ((1, 2, 0), (2, 3, 0)))
    assert canonical_form(r_graph(planetary)) == canonical_form(r_graph(ordinary))
    assert canonical_form(d_graph(planetary)) != canonical_form(d_graph(ordinary))
    result = enumerate_trains(4)
    a, b = result.find(planetary), result.find(ordinary)
    assert None not in (a, b) and a != b
    assert result.rotation_index[a] == result.rotation_index[b]


# --- the classic trains are among the graphs -----------------------------------------------
CLASSIC = {
    # K-H core of a K-H-V drive: fixed ring 0, eccentric carrier 1, planet (disc) 2.
    "K-H (of K-H-V)": TrainGraph(3, ((0, 1, 0), (1, 2, 1)), ((0, 2, 1),)),
    # 2K-H: ring 0 (frame), sun 1, carrier 2, planet 3.
    "2K-H simple planetary": TrainGraph(4, ((0, 1, 0), (0, 2, 0), (2, 3, 1)),
                                        ((1, 3, 2), (0, 3, 2))),
    # Stepped planet: sun 1 meshes step a, ring 0 meshes step b of one planet link 3.
    "2K-H stepped planet": TrainGraph(4, ((0, 2, 0), (1, 2, 0), (2, 3, 1)),
                                      ((1, 3, 2), (3, 0, 2))),
    # Wolfrom (3K): fixed ring 0, sun 1, output ring 2, free carrier 3, stepped planet 4.
    "Wolfrom 3K": TrainGraph(5, ((0, 1, 0), (0, 2, 0), (0, 3, 0), (3, 4, 1)),
                             ((1, 4, 3), (0, 4, 3), (2, 4, 3))),
    # Ravigneaux, large sun 0 held: small sun 1, ring 2, carrier 3, short planet 4 (meshes
    # the small sun and the long planet), long planet 5 (large sun, ring).
    "Ravigneaux (large sun held)": TrainGraph(
        6, ((0, 1, 0), (0, 2, 0), (0, 3, 0), (3, 4, 1), (3, 5, 2)),
        ((1, 4, 3), (4, 5, 3), (0, 5, 3), (2, 5, 3))),
    # Simpson, rear carrier 0 held: common sun 1, front ring 2, front carrier + rear ring 3,
    # front planet 4 (on 3), rear planet 5 (on 0).
    "Simpson (rear carrier held)": TrainGraph(
        6, ((0, 1, 0), (0, 2, 0), (0, 3, 0), (3, 4, 1), (0, 5, 2)),
        ((1, 4, 3), (2, 4, 3), (1, 5, 0), (3, 5, 0))),
}


@pytest.mark.parametrize("name", list(CLASSIC))
def test_classic_trains_are_enumerated(name: str) -> None:
    train = CLASSIC[name]
    assert enumerate_trains(train.links, train.dof).find(train) is not None


def test_simple_and_stepped_planet_are_one_graph() -> None:
    """A graph does not tell one gear on a link from two: the stepped planet is the simple
    planetary's graph (the tooth numbers tell them apart)."""
    result = enumerate_trains(4)
    assert result.find(CLASSIC["2K-H simple planetary"]) == \
        result.find(CLASSIC["2K-H stepped planet"])


def test_a_housing_that_only_holds_shafts_is_not_a_second_freedom() -> None:
    """The 2K-H differential with its housing 4 on the main axis (5 links, 2 gear pairs,
    2 DOF by mobility): the housing neither meshes nor carries, so it only adds the free
    turning of the whole gear set; the train is the 4-link 1-DOF graph (whose frame may be
    any member), not a 5-link 2-DOF one."""
    differential = TrainGraph(5, ((4, 0, 0), (4, 1, 0), (4, 2, 0), (2, 3, 1)),
                              ((1, 3, 2), (0, 3, 2)))
    assert differential.dof == 2
    assert enumerate_trains(5, 2).find(differential) is None
    assert enumerate_trains(4).find(CLASSIC["2K-H simple planetary"]) is not None


# --- the result ----------------------------------------------------------------------------
def test_result_protocol() -> None:
    import matplotlib.pyplot as plt

    result = enumerate_trains(5)
    data = json.loads(json.dumps(result.to_dict()))
    assert set(data) == {"links", "dof", "rotation_graphs", "displacement_graphs", "graphs"}
    assert (data["rotation_graphs"], data["displacement_graphs"]) == (6, 13)
    assert len(data["graphs"]) == 13 and all(len(g["gear_pairs"]) == 3 for g in data["graphs"])
    assert "displacement graphs (d-graphs)  13" in result.text_report()
    _, ax = plt.subplots()
    assert result.plot(ax=ax) is ax
    plt.close(ax.figure)


def test_six_link_report_quotes_the_published_counts() -> None:
    report = enumerate_trains(6).text_report()
    assert "rotation graphs (r-graphs)      27   (published: 27)" in report


@pytest.mark.parametrize("links", [4, 5, 6])
def test_tree_automorphisms_equal_the_vf2_self_isomorphisms(links: int) -> None:
    from networkx.algorithms.isomorphism import GraphMatcher

    from powergraph.analyses.synthesis.canonical import (automorphisms, edge_match,
                                                         incidence_graph, node_match)
    from powergraph.analyses.synthesis.rules import axis_structures

    for axes in axis_structures(links):
        graph = incidence_graph(links, list(axes))
        matcher = GraphMatcher(graph, graph, node_match=node_match, edge_match=edge_match)
        vf2 = {tuple(m[(0, n)][1] for n in range(links)) for m in matcher.isomorphisms_iter()}
        assert sorted(automorphisms(links, axes)) == sorted(vf2)
