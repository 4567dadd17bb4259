"""How many feasible tooth sets lie in the layouts a synthesis does not search?

For every layout of the default graphs (``--max-links``) whose grid exceeds ``--max-grid``,
``--samples`` grid points drawn at random (seeded) pass the synthesis's own exact test
(:func:`powergraph.analyses.synthesis.synthesize_search.exact_hits`: the ratio within the
tolerance, the train drivable at its input, the conditions joining planets, every idle
gear fixed, driven or loaded). Graphs with an idle gear in every arrangement are left out,
as the synthesis leaves them out (``workable``). The hits per
sampled point, times the grid, estimate the layout's feasible tooth sets (counted per
arrangement, as ``synthesize`` counts them). A layout with no sampled hit is estimated at
zero; its true count is below about ``grid / samples``.

The estimate bounds what a complete search must do: every feasible tooth set is
evaluated (forward and back-driven) to find each arrangement's best one. The baseline of
the same run is the search itself at the same limit (``synthesize``): its feasible sets
and seconds, and the ratio of the estimate to what it found (``estimate_vs_search``).

Usage: python benchmarks/synthesis_census.py [--json] [--ratio R] [--max-links N]
       [--max-grid G] [--samples S] [--top K]
"""
from __future__ import annotations

import argparse
import json
import time

import numpy as np

from powergraph.analyses.synthesis.synthesize import MAX_GRID, default_graphs, synthesize
from powergraph.analyses.synthesis.synthesize_search import (exact_hits, graph_layouts,
                                                             workable)


def census(ratio: float, max_links: int, max_grid: int, samples: int, tolerance: float = 0.005,
           teeth: tuple[int, int] = (12, 120), planets: int = 3, seed: int = 0) -> dict:
    rng = np.random.default_rng(seed)
    rows, start = [], time.perf_counter()
    for graph in filter(workable, default_graphs(max_links)):
        for layout in graph_layouts(graph, teeth, planets):
            if layout.size <= max_grid:
                continue
            flat = np.unique(rng.integers(0, layout.size, samples))
            found = exact_hits(graph, layout, flat, ratio, tolerance)
            hits = sum(h.size for h in found.values())
            rows.append({"graph": graph.name, "layout": layout.name, "grid": layout.size,
                         "sampled": int(flat.size), "hits": int(hits),
                         "estimate": hits / flat.size * layout.size})
    total = sum(r["estimate"] for r in rows)
    census_s = time.perf_counter() - start
    start = time.perf_counter()
    searched = synthesize(ratio, tolerance, max_links, teeth, planets, max_grid=max_grid)
    search_s = time.perf_counter() - start
    return {"ratio": ratio, "max_links": max_links, "max_grid": max_grid,
            "samples": samples, "layouts": len(rows),
            "layouts_with_hits": sum(1 for r in rows if r["hits"]),
            "estimated_feasible": total, "seconds": round(census_s, 1),
            "search_feasible": searched.feasible, "search_s": round(search_s, 1),
            "estimate_vs_search": total / max(searched.feasible, 1),
            "largest": sorted(rows, key=lambda r: -r["estimate"])}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", action="store_true")
    parser.add_argument("--ratio", type=float, default=121.0)
    parser.add_argument("--max-links", type=int, default=6)
    parser.add_argument("--max-grid", type=float, default=MAX_GRID)
    parser.add_argument("--samples", type=int, default=100_000)
    parser.add_argument("--top", type=int, default=10)
    args = parser.parse_args()
    out = census(args.ratio, args.max_links, int(args.max_grid), args.samples)
    out["largest"] = out["largest"][:args.top]
    if args.json:
        print(json.dumps(out))
        return
    print(f"{out['layouts']} layouts over {out['max_grid']:.3g} points, {out['layouts_with_hits']}"
          f" with sampled hits: about {out['estimated_feasible']:.3g} feasible tooth sets "
          f"({out['samples']} samples a layout, {out['seconds']} s)")
    print(f"the search at that limit: {out['search_feasible']} feasible tooth sets in "
          f"{out['search_s']} s; the layouts over it hold "
          f"{out['estimate_vs_search']:.3g} x as many")
    for r in out["largest"]:
        print(f"  {r['estimate']:9.3g}  {r['grid']:9.3g} points  {r['hits']:>5} hits  "
              f"{r['graph'][:40]}, {r['layout']}")


if __name__ == "__main__":
    main()
