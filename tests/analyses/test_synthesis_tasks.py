"""The synthesis as tasks: shared block grids, units of work and their order.

Expected values: the block grids as computed with the graph's own pair numbers (the
uncached function), the definition of a unit (the searched layouts of one graph, largest
first, ties in graph order), and the result of the ordinary
run, which must not depend on the order the units ran in.
"""
from __future__ import annotations

import importlib

import numpy as np
import pytest

from powergraph.analyses.synthesis import teeth as teeth_module
from powergraph.analyses.synthesis.synthesize import synthesize
from powergraph.analyses.synthesis.synthesize_classics import CLASSICS
from powergraph.analyses.synthesis.tasks import survey, work_units
from powergraph.analyses.synthesis.teeth import layouts, structure

synthesize_module = importlib.import_module("powergraph.analyses.synthesis.synthesize")


def test_shared_block_grids_equal_those_of_the_graphs_own_pair_numbers() -> None:
    """Every planet block of every layout of the classic trains (simple, stepped and
    double planets, a K-H-V stage): the grid shared under renamed pairs equals the one
    computed with the graph's pair numbers."""
    compute = teeth_module._tuples.__wrapped__          # the computation, without cache
    checked = 0
    for graph in CLASSICS.values():
        st = structure(graph)
        for layout in layouts(graph, (12, 24), 3):
            for block in layout.blocks:
                alone = not any(st.kinds[k] == "pp" for k in block.steps[0])
                own = compute(block.steps, block.cp_pairs, block.internal, (12, 24), 3,
                              alone, st.phased(block.planet))
                np.testing.assert_array_equal(block.tuples, own)
                checked += 1
    assert checked > 40


def test_blocks_of_one_shape_share_one_grid() -> None:
    """A sun-and-ring stepped block numbered (3, 5) in one graph and (1, 4) in another."""
    a = teeth_module.block_rows(((3,), (5,)), (3, 5), frozenset({5}), (12, 40), 3, True, False)
    b = teeth_module.block_rows(((1,), (4,)), (1, 4), frozenset({4}), (12, 40), 3, True, False)
    assert a is b


def test_units_hold_each_graphs_searched_layouts_largest_first() -> None:
    surveys = [([(0, 100), (1, 5000), (2, 100)], []),
               ([(0, 9000)], [("g1", "stepped", 10**9)]),
               ([], [("g2", "stepped", 10**9)]),
               ([(0, 5200)], [])]
    assert work_units(surveys) == [(1, (0,), 9000), (0, (0, 1, 2), 5200), (3, (0,), 5200)]


def test_survey_lists_layouts_over_the_limit() -> None:
    graph = CLASSICS["2K-H"]
    sizes = [layout.size for layout in layouts(graph, (12, 60), 3)]
    limit = sorted(sizes)[len(sizes) // 2]
    (searched, skipped), = survey([(graph, 0)], (12, 60), 3, limit)
    assert [size for _, size in searched] == [s for s in sizes if 0 < s <= limit]
    assert [n for *_, n in skipped] == [s for s in sizes if s > limit]


@pytest.mark.slow
def test_the_result_does_not_depend_on_the_order_the_units_ran_in(monkeypatch) -> None:
    """The ranking orders the rows totally: with the units run in reverse, the result
    (rows, counts, mirror images left out) is the same."""
    graphs = [CLASSICS[name] for name in ("2K-H", "Wolfrom 3K", "two 2K-H stages")]
    ordinary = synthesize(40, graphs=graphs, teeth=(12, 40), top=None).to_dict()
    plain = work_units
    monkeypatch.setattr(synthesize_module, "work_units",
                        lambda surveys: list(reversed(plain(surveys))))
    reversed_run = synthesize(40, graphs=graphs, teeth=(12, 40), top=None).to_dict()
    assert reversed_run == ordinary
    assert ordinary["rows"]
