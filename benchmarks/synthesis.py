"""Synthesis for a ratio: candidates evaluated per second, against one solve per candidate.

A **candidate** is one tooth set of one layout of one graph with one choice of fixed
link, input and output: ``synthesize`` evaluates every grid point of a layout for every
choice at once. The run:

(a) ``synthesize(RATIO, graphs=classic_graphs(6))`` in this process, wall-clock from
    the call to the result, after a warm-up run (``synthesis_cold_s``: that first run,
    with the sympy derivations of the speeds and the layouts' grids, which the process
    then keeps; ``--cold`` skips it);
(b) the naive way, one model and one ``powergraph.solve`` per candidate, on ``--loop``
    candidates drawn at random from the same grids (seeded), extrapolated; the time of
    the solves alone is also given (the models built beforehand);
(c) the same synthesis on a Dask ``LocalCluster`` of 2 worker processes
    (``workers=2``); ``dask_matches`` says whether its result equals (a)'s exactly
    (``to_dict()`` compared), ``dask_s`` its wall-clock time (cluster start included).

``speedup`` is candidates per second of (a) over (b) with model building,
``speedup_solve_only`` over the solves alone. Times are single runs (``time.perf_counter``)
on a shared machine, so noisy.

Usage: python benchmarks/synthesis.py [--json] [--ratio R] [--loop N] [--no-dask]
"""
from __future__ import annotations

import argparse
import json
import sys
import time

import numpy as np

from powergraph.analyses.synthesis.synthesize import MAX_GRID, synthesize
from powergraph.analyses.synthesis.synthesize_classics import classic_graphs
from powergraph.analyses.synthesis.synthesize_search import graph_layouts, speed_functions


def candidates(graphs, teeth=(12, 120), planets=3) -> tuple[int, list]:
    """Number of candidates the synthesis evaluates, and the (graph, layout, choices)
    searched."""
    total, searched = 0, []
    for graph in graphs:
        choices = [(f, a, b) for f, others, _ in speed_functions(graph)
                   for a in others for b in others if a != b]
        for layout in graph_layouts(graph, teeth, planets):
            if layout.size <= MAX_GRID:
                total += layout.size * len(choices)
                searched.append((graph, layout, choices))
    return total, searched


def naive(searched, count: int, seed: int = 1) -> tuple[float, float]:
    """Seconds per candidate: build the model and solve it; and solve alone."""
    from powergraph.model import model_from_dict
    from powergraph.statics import solve
    from powergraph.errors import PowerGraphError

    rng = np.random.default_rng(seed)
    sizes = np.array([layout.size * len(choices) for _, layout, choices in searched], float)
    picks = rng.choice(len(searched), size=count, p=sizes / sizes.sum())
    docs = []
    start = time.perf_counter()
    models = []
    for index in picks:
        graph, layout, choices = searched[index]
        flat = np.array([rng.integers(layout.size)])
        teeth = {key: int(v[0]) for key, v in layout.teeth(flat).items()}
        fixed, a, b = choices[rng.integers(len(choices))]
        doc = graph.to_model_dict(frame=fixed, inputs=(a,), outputs=(b,), teeth=teeth,
                                  internal=layout.internal, mesh_efficiency=0.98)
        docs.append(doc)
        models.append(model_from_dict(doc))
    built = time.perf_counter() - start
    start = time.perf_counter()
    for model in models:
        try:
            solve(model)
        except PowerGraphError:
            pass            # a candidate whose output stands still, say: still one solve
    solved = time.perf_counter() - start
    return (built + solved) / count, solved / count


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", action="store_true")
    parser.add_argument("--ratio", type=float, default=121.0)
    parser.add_argument("--loop", type=int, default=300)
    parser.add_argument("--cold", action="store_true", help="no warm-up run")
    parser.add_argument("--no-dask", action="store_true")
    args = parser.parse_args(argv)
    graphs = classic_graphs(6)
    cold_s = None
    if not args.cold:
        start = time.perf_counter()
        synthesize(args.ratio, graphs=graphs, top=None)
        cold_s = round(time.perf_counter() - start, 2)
    start = time.perf_counter()
    alone = synthesize(args.ratio, graphs=graphs, top=None)
    synthesis_s = time.perf_counter() - start
    total, searched = candidates(graphs)
    per_candidate, per_solve = naive(searched, args.loop)
    out = {"ratio": args.ratio, "graphs": len(graphs), "grid_points": alone.evaluated,
           "candidates": total, "feasible_tooth_sets": alone.feasible,
           "arrangements": alone.arrangements, "synthesis_s": round(synthesis_s, 2),
           "synthesis_cold_s": cold_s,
           "synthesis_per_s": round(total / synthesis_s),
           "naive_per_s": round(1 / per_candidate, 1),
           "solve_only_per_s": round(1 / per_solve, 1),
           "speedup": round(total / synthesis_s * per_candidate, 1),
           "speedup_solve_only": round(total / synthesis_s * per_solve, 1),
           "naive_extrapolated_s": round(total * per_candidate)}
    if not args.no_dask:
        start = time.perf_counter()
        spread = synthesize(args.ratio, graphs=graphs, top=None, workers=2)
        out["dask_s"] = round(time.perf_counter() - start, 2)
        out["dask_matches"] = spread.to_dict() == alone.to_dict()
    if args.json:
        print(json.dumps(out))
    else:
        for key, value in out.items():
            print(f"{key:24s} {value}")
    return 0 if out.get("dask_matches", True) else 1


if __name__ == "__main__":
    sys.exit(main())
