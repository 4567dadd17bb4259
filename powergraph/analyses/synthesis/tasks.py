"""The synthesis as tasks: a survey of the layouts, then units of work, largest first.

A synthesis maps two functions over one cluster
(:func:`powergraph.analyses.parallel.cluster`: in this process, on local worker
processes, or on a Dask cluster):

1. :func:`survey` — per batch of graphs, each layout's grid size (which layouts are
   searched and which are over the limit). It also warms the worker's caches of block
   grids (:func:`~powergraph.analyses.synthesis.teeth.block_rows`).
2. :func:`run_unit` — per **unit**, the layouts of one graph: their search
   (:func:`~powergraph.analyses.synthesis.synthesize_bound.search_part`) and the
   evaluation of their arrangements (:func:`~powergraph.analyses.synthesis.rank.
   evaluate_hits`). Only rows travel back.

:func:`work_units` makes one unit of the layouts searched in each graph, so that a
graph's sympy derivations are made once, on one worker, and orders the units by their
grid points, largest first: the few large graphs then start at once instead of ending the
run alone (a worker takes the next unit as soon as it is free). Splitting a graph into
one unit per layout balanced no better on two workers and derived the split graphs
twice (21 s against 18 s for the units of the seven-link search, docs/synthesis.md).
The ranking orders rows totally (its last keys are the row's name and teeth), so the
result is the same however the units ran.

Examples
--------
>>> from powergraph.analyses.synthesis.synthesize_classics import CLASSICS
>>> (searched, skipped), = survey([(CLASSICS["2K-H"], 0)], (12, 60), 3, 10**7)
>>> [li for li, _ in searched], skipped
([0, 1, 2, 3, 4, 5], [])
>>> work_units([(searched, skipped)])[0][:2]
(0, (0, 1, 2, 3, 4, 5))
"""
from __future__ import annotations

from typing import Sequence

from powergraph.analyses.synthesis.graph import TrainGraph
from powergraph.analyses.synthesis.rank import SynthesisRow, evaluate_hits
from powergraph.analyses.synthesis.synthesize_bound import search_part
from powergraph.analyses.synthesis.synthesize_search import graph_layouts, workable

#: Graphs surveyed by one task.
SURVEY_BATCH = 32

Survey = tuple[list[tuple[int, int]], list[tuple[str, str, int]]]


def survey(batch: Sequence[tuple[TrainGraph, int]], teeth: tuple[int, int], planets: int,
           max_grid: int) -> list[Survey]:
    """Per graph of ``batch`` (graph, graph index): the layouts searched as
    ``(layout index, grid size)`` (empty grids left out) and those over ``max_grid`` as
    ``(graph name, layout name, grid size)``; neither for a graph that is not
    :func:`~powergraph.analyses.synthesis.synthesize_search.workable` (an idle gear in
    every arrangement)."""
    out = []
    for graph, gi in batch:
        searched, skipped = [], []
        if not workable(graph):           # no working train: nothing to search
            out.append((searched, skipped))
            continue
        for li, layout in enumerate(graph_layouts(graph, teeth, planets)):
            if layout.size > max_grid:
                skipped.append((graph.name or f"graph {gi}", layout.name, layout.size))
            elif layout.size:
                searched.append((li, layout.size))
        out.append((searched, skipped))
    return out


def work_units(surveys: Sequence[Survey]) -> list[tuple[int, tuple[int, ...], int]]:
    """``(graph index, layout indices, grid points)`` per unit, largest first (ties in
    graph and layout order)."""
    units = [(gi, tuple(li for li, _ in searched), sum(s for _, s in searched))
             for gi, (searched, _) in enumerate(surveys) if searched]
    return sorted(units, key=lambda unit: (-unit[2], unit[0], unit[1]))


def run_unit(item: tuple) -> list[SynthesisRow]:
    """One unit: its layouts searched, their arrangements evaluated; the rows."""
    graph, gi, layout_indices, ratio, tolerance, teeth, planets, mesh_efficiency = item
    out = []
    for li in layout_indices:
        for hits in search_part(graph, gi, li, 0, 1, ratio, tolerance, teeth, planets):
            row = evaluate_hits(graph, hits, ratio, teeth, planets, mesh_efficiency)
            if row is not None:
                out.append(row)
    return out

