"""The tooth-space search (branch and bound) against a plain scan of every grid point.

Expected values: a brute force written here. It visits every point of every layout's
grid (nothing pruned), takes its Willis ratios ``i = -z_b/z_a`` (external) or ``+z_b/z_a``
(internal), the coaxial speeds from the closed forms, the ratio test
``|w_in / w_out / R - 1| <= tol`` and the conditions joining planets. The bounded search
must find exactly the same tooth sets, counted per layout and arrangement.
"""
from __future__ import annotations

import numpy as np
import pytest

from powergraph.analyses.synthesis import synthesize_bound
from powergraph.analyses.synthesis.synthesize import default_graphs, synthesize
from powergraph.analyses.synthesis.synthesize_bound import (ratio_functions, influential,
                                                            search_part)
from powergraph.analyses.synthesis.synthesize_classics import CLASSICS
from powergraph.analyses.synthesis.synthesize_search import (drivable, graph_layouts,
                                                             joint_conditions, speed_functions,
                                                             willis_ratios)


@pytest.fixture(autouse=True)
def always_bound(monkeypatch):
    """Small grids are scanned whole in production (``SCAN``): here every grid is bounded,
    and leaves are small, so the pruning is what is tested."""
    monkeypatch.setattr(synthesize_bound, "SCAN", 0)
    monkeypatch.setattr(synthesize_bound, "LEAF", 4)


def brute_force(graph, ratio, tolerance, teeth, planets, rank: bool = True) -> dict:
    """``{(layout, fixed, input, output): sorted grid indices}`` of every hit. With
    ``rank`` (the default): the Willis rows solved numerically point by point (numpy,
    batched) with the fixed link at rest and the input at speed 1, only where they fix
    every speed (:func:`regular`), and every :func:`idle` link fixed, input or output.
    Without: the closed forms' ratio (which also gives a value at locked sets)."""
    out = {}
    passive = idle(graph)
    for li, layout in enumerate(graph_layouts(graph, teeth, planets)):
        flat = np.arange(layout.size)
        z = layout.teeth(flat)
        i = [(1.0 if k in layout.internal else -1.0) * z[(k, 1)] / z[(k, 0)]
             for k in range(len(graph.gear_pairs))]
        for fixed, others, fn in speed_functions(graph):
            with np.errstate(divide="ignore", invalid="ignore"):
                w = [np.broadcast_to(np.asarray(v, dtype=float), flat.shape) for v in fn(*i)]
            for a, wa in zip(others, w):
                solved = solve_rows(graph, i, fixed, a) if rank else None
                for b, wb in zip(others, w):
                    if a == b or (rank and not passive <= {fixed, a, b}):
                        continue
                    with np.errstate(divide="ignore", invalid="ignore"):
                        value = 1.0 / solved[b] if rank else wa / wb
                        hit = flat[np.abs(value / ratio - 1.0) <= tolerance]
                    hit = hit[joint_conditions(layout, hit)]
                    if hit.size:
                        out[(li, fixed, a, b)] = hit
    return out


def solve_rows(graph, ratios, fixed, given) -> dict:
    """Every link's speed with ``fixed`` at rest and ``given`` at 1, from the rows
    ``(w_u - w_c) - i (w_v - w_c) = 0`` (``w_u - w_v = 0`` per coupling) solved point by
    point; NaN where they do not fix every speed (rank below the unknowns)."""
    unknown = [n for n in range(graph.links) if n not in (fixed, given)]
    points = ratios[0].shape[0]
    rows = np.zeros((points, len(graph.gear_pairs) + len(graph.couplings), graph.links))
    for r, ((u, v, c), i) in enumerate(zip(graph.gear_pairs, ratios)):
        rows[:, r, u] += 1.0
        rows[:, r, v] -= i
        rows[:, r, c] += i - 1.0
    for r, (u, v) in enumerate(graph.couplings, start=len(graph.gear_pairs)):
        rows[:, r, u], rows[:, r, v] = 1.0, -1.0
    matrix, rhs = rows[:, :, unknown], -rows[:, :, given]
    regular = np.linalg.matrix_rank(matrix) == len(unknown)
    speeds = np.full((points, len(unknown)), np.nan)
    if regular.any():
        speeds[regular] = np.linalg.solve(matrix[regular], rhs[regular][..., None])[..., 0]
    out = {n: speeds[:, j] for j, n in enumerate(unknown)}
    out[fixed], out[given] = np.zeros(points), np.ones(points)
    return out


def idle(graph) -> set[int]:
    """Links with one mesh that hold no gear pair and no coupling: their one mesh force is
    zero unless the link takes an external torque (its moment balance about its axis)."""
    meshes = {n: 0 for n in range(graph.links)}
    for u, v, _ in graph.gear_pairs:
        meshes[u] += 1
        meshes[v] += 1
    holders = {c for *_, c in graph.gear_pairs} | {x for pair in graph.couplings for x in pair}
    return {n for n, m in meshes.items() if m == 1 and n not in holders}


def regular(graph, ratios, fixed, given) -> bool:
    """The train with ``fixed`` held and ``given`` driven has one speed per link: its
    rows ``(w_u - w_c) - i (w_v - w_c) = 0`` (``w_u - w_v = 0`` per coupling), over the
    links other than those two, have full rank (numpy's SVD rank)."""
    unknown = [n for n in range(graph.links) if n not in (fixed, given)]
    rows = []
    for (u, v, c), i in zip(graph.gear_pairs, ratios):
        row = dict.fromkeys(range(graph.links), 0.0)
        row[u] += 1.0
        row[v] -= i
        row[c] += i - 1.0
        rows.append([row[n] for n in unknown])
    for u, v in graph.couplings:
        rows.append([1.0 if n == u else -1.0 if n == v else 0.0 for n in unknown])
    return np.linalg.matrix_rank(np.array(rows)) == len(unknown)


def bounded(graph, ratio, tolerance, teeth, planets, parts: int = 1) -> dict:
    out: dict = {}
    for li, _ in enumerate(graph_layouts(graph, teeth, planets)):
        for part in range(parts):
            for h in search_part(graph, 0, li, part, parts, ratio, tolerance, teeth, planets):
                key = (li, h.fixed, h.input, h.output)
                out[key] = np.sort(np.concatenate([out.get(key, h.flat[:0]), h.flat]))
    return out


def assert_same(expected: dict, found: dict) -> None:
    assert sorted(found) == sorted(expected)
    for key, flat in expected.items():
        np.testing.assert_array_equal(found[key], flat)


@pytest.mark.parametrize("name, ratio, tolerance, teeth", [
    ("2K-H", 4.0, 0.01, (12, 60)),
    ("2K-H", -3.0, 0.01, (12, 60)),
    ("2K-H", 12.0, 0.005, (12, 40)),          # stepped planets only
    ("double planet", 2.5, 0.01, (12, 40)),
    ("Wolfrom 3K", 60.0, 0.01, (12, 60)),
    ("Wolfrom 3K", -30.0, 0.01, (12, 60)),
    ("RV (2K-H + K-H-V)", 80.0, 0.01, (12, 40)),
])
def test_bounded_search_finds_exactly_the_brute_force_hits(name, ratio, tolerance, teeth):
    graph = CLASSICS[name]
    expected = brute_force(graph, ratio, tolerance, teeth, 3)
    assert expected, "a case without hits would not test anything"
    assert_same(expected, bounded(graph, ratio, tolerance, teeth, 3))


def test_parts_of_a_layout_together_find_the_same_hits() -> None:
    graph = CLASSICS["Wolfrom 3K"]
    expected = brute_force(graph, 20.0, 0.01, (12, 60), 3)
    assert expected
    assert_same(expected, bounded(graph, 20.0, 0.01, (12, 60), 3, parts=5))


@pytest.mark.slow
def test_ravigneaux_matches_the_brute_force() -> None:
    # one layout of 6.5e6 points: the plain scan takes seconds
    graph = CLASSICS["Ravigneaux"]
    expected = brute_force(graph, -30.0, 0.01, (12, 36), 3)
    assert sum(v.size for v in expected.values()) > 100
    assert_same(expected, bounded(graph, -30.0, 0.01, (12, 36), 3))


@pytest.mark.slow
@pytest.mark.parametrize("ratio", [7.0, -20.0, 45.0])
def test_every_five_link_graph_matches_the_brute_force(ratio) -> None:
    graphs = [g for g in default_graphs(5) if g.links == 5]
    total = 0
    for graph in graphs:
        expected = brute_force(graph, ratio, 0.01, (12, 30), 3)
        assert_same(expected, bounded(graph, ratio, 0.01, (12, 30), 3))
        total += sum(v.size for v in expected.values())
    assert total > 0


TWO_STAGES_LOCKED = [np.array([1 / 3]), np.array([-1.0]), np.array([-1.0]), np.array([-1.0])]


def test_a_locked_stage_is_not_drivable() -> None:
    """The rows of the set below are singular (docstring of the next test); halving the
    second stage's ratios (steps 24 and 12 teeth against suns of 12) makes them regular."""
    graph = CLASSICS["two 2K-H stages"]
    assert not drivable(graph, TWO_STAGES_LOCKED, 0, 1)[0]
    assert not regular(graph, [x[0] for x in TWO_STAGES_LOCKED], 0, 1)
    moving = [np.array([1 / 3]), np.array([-1.0]), np.array([-0.5]), np.array([-0.5])]
    assert drivable(graph, moving, 0, 1)[0] and regular(graph, [x[0] for x in moving], 0, 1)


@pytest.mark.slow
def test_tooth_sets_that_lock_a_stage_are_no_trains() -> None:
    """Two 2K-H stages, the second with a stepped planet meshing two suns (links 3 and 0,
    carrier 5). Its rows give ``w_3 - w_5 = i_2 i_3 (w_0 - w_5)``; with equal suns and
    steps, ``i_2 = i_3 = -1`` so ``w_3 = w_0``: holding link 0 holds carrier 3 of the first
    stage, whose ring is link 0 too, so sun 1 cannot be driven. The simplified closed
    forms still give a finite ratio there (they cancel the common factor); the search
    must leave these sets out, as the brute force above does (the rank of the rows)."""
    graph = CLASSICS["two 2K-H stages"]
    expected = brute_force(graph, 5.0, 0.005, (12, 20), 3)
    with_locked = brute_force(graph, 5.0, 0.005, (12, 20), 3, rank=False)
    assert sum(v.size for v in with_locked.values()) > sum(v.size for v in expected.values())
    assert_same(expected, bounded(graph, 5.0, 0.005, (12, 20), 3))


@pytest.mark.slow
def test_synthesis_runs_where_an_arrangements_first_set_locks() -> None:
    # Before the test above was met, a model was built of each arrangement's first hit,
    # a locked one here, and the synthesis stopped on the error.
    result = synthesize(40, graphs=[CLASSICS["two 2K-H stages"]], teeth=(12, 60), top=None)
    assert result.rows


def test_ratios_are_multilinear_so_the_bounds_apply() -> None:
    # Every ratio is N / D with each Willis ratio of degree at most one (factors of
    # Cramer's rule on rows each linear in one ratio); without it the search could not prune.
    for graph in default_graphs(5):
        assert all(linear for *_, linear in ratio_functions(graph)), graph.name


def test_an_idle_planet_moves_no_ratio() -> None:
    # 5-link d-graph 2: planet 4 meshes only planet 3 (an idler): its teeth enter no speed.
    graph = next(g for g in default_graphs(5) if g.name.startswith("5-link d-graph 2 "))
    layout = graph_layouts(graph, (12, 30), 3)[0]
    moving = influential(graph, 0, (12, 30), 3)
    idle = [f for f, b in enumerate(layout.blocks) if b.planet == 4]
    assert idle and not moving[idle].any() and moving.sum() == len(moving) - 1


def test_search_reports_no_layout_skipped_by_default() -> None:
    result = synthesize(121, graphs=[CLASSICS["Wolfrom 3K"]], top=1)
    assert result.skipped == () and result.feasible > 0


@pytest.mark.slow
@pytest.mark.parametrize("ratio", [7.0, 12.0])
def test_a_block_locked_by_equal_ratios_does_not_defeat_the_bound(monkeypatch, ratio) -> None:
    """Two rings on a stepped planet lock it wherever their two ratios are equal
    (``q = 1``, about one row in twenty here): both coaxial speeds then share a vanishing
    factor. Over a common denominator every box holding such rows bounds the ratio as
    ``0/0`` and is enumerated (about 30 to 50 points tested per hit, measured while
    writing this); in lowest terms (:func:`ratio_functions`) the search tests few points
    that are not hits, and still finds every hit of a scan of the whole grid."""
    graph = next(g for g in default_graphs(6) if g.name.startswith("Simpson"))
    teeth = (12, 50)
    layout = graph_layouts(graph, teeth, 3)[35]
    assert layout.name == "stepped+stepped"
    assert all(len(block.internal) == 2 for block in layout.blocks)     # two rings each
    tested = []
    plain = synthesize_bound.exact_hits

    def counting(graph_, layout_, flat, *args):
        tested.append(flat.size)
        return plain(graph_, layout_, flat, *args)

    monkeypatch.setattr(synthesize_bound, "exact_hits", counting)
    hits = search_part(graph, 0, 35, 0, 1, ratio, 0.01, teeth, 3)
    found = sum(h.flat.size for h in hits)
    scan = plain(graph, layout, np.arange(layout.size), ratio, 0.01)   # every point
    assert found == sum(v.size for v in scan.values()) > 1000
    assert sum(tested) <= 4 * found


def test_a_planet_block_enters_the_speeds_through_one_quotient() -> None:
    """The premise of the blocks' one-quantity order: with ``e_k1 = 1`` and
    ``e_k2 = q`` (:func:`~powergraph.analyses.synthesis.synthesize_bound.quotient_pairs`)
    every coaxial speed is that of the block's own tooth numbers."""
    graph = CLASSICS["two 2K-H stages"]
    compared = 0
    for li, layout in enumerate(graph_layouts(graph, (12, 40), 3)):
        flat = np.arange(0, layout.size, max(1, layout.size // 2000))
        i = willis_ratios(layout, layout.teeth(flat))
        substituted = list(i)
        for f in range(len(layout.blocks)):
            pairs = synthesize_bound.quotient_pairs(layout, f)
            assert pairs is not None
            e = [i[k] if layout.structure.coaxial_side[k] == 0 else 1 / i[k] for k in pairs]
            substituted[pairs[0]] = np.ones_like(e[0])
            q = e[1] / e[0]
            substituted[pairs[1]] = q if layout.structure.coaxial_side[pairs[1]] == 0 else 1 / q
        for _, _, fn in speed_functions(graph):
            with np.errstate(divide="ignore", invalid="ignore"):
                speeds = list(zip(fn(*i), fn(*substituted)))
            for plain, reduced in speeds:
                plain, reduced = (np.broadcast_to(v, flat.shape) for v in (plain, reduced))
                # not at locked sets (infinite, or 1 / round-off)
                finite = (np.abs(plain) < 1e9) & (np.abs(reduced) < 1e9)
                compared += int(finite.sum())
                np.testing.assert_allclose(reduced[finite], plain[finite], rtol=1e-12,
                                           atol=1e-12)
    assert compared > 100_000
