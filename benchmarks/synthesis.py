"""Synthesis for a ratio: one process against Dask workers, and against a naive loop.

The problem is ``synthesize(RATIO)`` over the enumeration's graphs of at most
``--max-links`` links (``--classics``: the classic trains only), layouts up to
``--max-grid`` grid points, teeth ``--teeth``. The run:

(a) the search in this process, from cold (sympy derivations and layouts included, as a
    fresh worker pays them): ``one_process_s``;
(b) for each N of ``--workers`` (default 2): a ``LocalCluster`` of N single-threaded
    worker processes, its start-up timed apart (``workers_N_startup_s``), the same search
    on it (``workers_N_s``), the ratio (a)/(search on N workers) (``workers_N_speedup``)
    and whether the result equals (a)'s exactly (``to_dict()``: ``workers_N_matches``);
(c) with ``--naive``: one model and one ``powergraph.solve`` per candidate on ``--loop``
    candidates drawn from the classic graphs' grids (seeded), extrapolated, against the
    search over those grids.

Times are single runs (``time.perf_counter``) on a shared machine, so noisy: compare
numbers of one run only.

Usage: python benchmarks/synthesis.py [--json] [--ratio R] [--max-links N] [--max-grid G]
       [--teeth LOW:HIGH] [--classics] [--workers 2,4] [--naive] [--loop N]
"""
from __future__ import annotations

import argparse
import json
import os
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
            if layout.size <= 4_000_000:
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


def scaling(args, graphs) -> dict:
    """One process against local clusters of ``args.workers`` worker processes on one
    problem; cluster start-up timed apart from the search."""
    from dask.distributed import Client, LocalCluster

    from powergraph.analyses.parallel import numpy_friendly_workers

    problem = dict(graphs=graphs, top=None, teeth=args.teeth, max_grid=args.max_grid,
                   max_links=args.max_links)
    start = time.perf_counter()
    alone = synthesize(args.ratio, **problem)
    out = {"one_process_s": round(time.perf_counter() - start, 2),
           "grid_points": alone.evaluated, "feasible_tooth_sets": alone.feasible,
           "skipped_layouts": len(alone.skipped)}
    for n in args.workers:
        start = time.perf_counter()
        with numpy_friendly_workers(), LocalCluster(
                n_workers=n, threads_per_worker=1, processes=True,
                dashboard_address=None) as local, Client(local):
            started = time.perf_counter()
            spread = synthesize(args.ratio, scheduler=local.scheduler_address, **problem)
            done = time.perf_counter()
        out[f"workers_{n}_startup_s"] = round(started - start, 2)
        out[f"workers_{n}_s"] = round(done - started, 2)
        out[f"workers_{n}_speedup"] = round(out["one_process_s"] / (done - started), 2)
        out[f"workers_{n}_matches"] = spread.to_dict() == alone.to_dict()
    return out


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", action="store_true")
    parser.add_argument("--ratio", type=float, default=121.0)
    parser.add_argument("--max-links", type=int, default=6,
                        help="problem size: graphs of the enumeration up to N links")
    parser.add_argument("--max-grid", type=float, default=MAX_GRID,
                        help="problem size: largest layout grid searched")
    parser.add_argument("--teeth", type=lambda t: tuple(int(x) for x in t.split(":")),
                        default=(12, 120), help="problem size: LOW:HIGH")
    parser.add_argument("--classics", action="store_true",
                        help="the classic graphs only (not the enumeration)")
    parser.add_argument("--workers", type=lambda t: [int(x) for x in t.split(",")],
                        default=[2], help="worker counts to compare, e.g. 2,4")
    parser.add_argument("--naive", action="store_true",
                        help="also the naive loop (one solve per candidate) on --loop "
                             "candidates of the classic graphs")
    parser.add_argument("--loop", type=int, default=300)
    args = parser.parse_args(argv)
    args.max_grid = int(args.max_grid)
    graphs = classic_graphs(args.max_links) if args.classics else None
    out = {"ratio": args.ratio, "max_links": args.max_links, "max_grid": args.max_grid,
           "teeth": list(args.teeth), "cores": os.cpu_count()}
    out.update(scaling(args, graphs))
    if args.naive:
        graphs = classic_graphs(6)
        start = time.perf_counter()
        synthesize(args.ratio, graphs=graphs, top=None, max_grid=4_000_000)
        synthesis_s = time.perf_counter() - start
        total, searched = candidates(graphs)
        per_candidate, per_solve = naive(searched, args.loop)
        out.update({"naive_candidates": total, "naive_synthesis_s": round(synthesis_s, 2),
                    "naive_per_s": round(1 / per_candidate, 1),
                    "speedup_over_naive": round(total / synthesis_s * per_candidate, 1)})
    if args.json:
        print(json.dumps(out))
    else:
        for key, value in out.items():
            print(f"{key:24s} {value}")
    return 0 if all(v for k, v in out.items() if k.endswith("_matches")) else 1


if __name__ == "__main__":
    sys.exit(main())
