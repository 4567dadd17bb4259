"""Time the enumeration of planetary gear train graphs, N = 3 ... 8 links (1 DOF).

Prints, for each N, the counts of rotation and displacement graphs beside the published
ones (Yang & Ding 2019, "The complete set of one-degree-of-freedom planetary gear trains
with up to nine links", J. Mech. Des. 141(4): 6 links 27/81, 7 links 152/647, 8 links
1070/6360), the time, and the time over the 6-link time measured in the same run.
``--max-links`` stops earlier or goes on to 9; ``--dof 2`` times the 2-DOF graphs.

Usage: python benchmarks/enumerate.py [--max-links 8] [--dof 1] [--json]
"""
from __future__ import annotations

import argparse
import json
import time

from powergraph.analyses.synthesis import enumerate_trains
from powergraph.analyses.synthesis.enumerate import PUBLISHED


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--max-links", type=int, default=8)
    parser.add_argument("--dof", type=int, default=1)
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()
    sizes = list(range(max(3, args.dof + 2), args.max_links + 1))
    times, rows = {}, []
    for links in [6] + [n for n in sizes if n != 6]:   # the baseline first, always
        start = time.perf_counter()
        result = enumerate_trains(links, args.dof)
        times[links] = time.perf_counter() - start
        published = PUBLISHED.get(args.dof, {}).get(links)
        rows.append({"links": links, "rotation_graphs": result.rotation_graphs,
                     "displacement_graphs": result.displacement_graphs,
                     "published": list(published) if published else None,
                     "agrees": None if not published else
                     published == (result.rotation_graphs, result.displacement_graphs),
                     "seconds": times[links]})
    rows.sort(key=lambda r: r["links"])
    for row in rows:
        row["ratio_to_6_links"] = row["seconds"] / times[6]
    if args.json:
        print(json.dumps({"dof": args.dof, "rows": rows}, indent=2))
        return
    print(f"{args.dof}-DOF planetary gear train graphs"
          + ("; published: Yang & Ding (2019)" if args.dof in PUBLISHED else
             "; no published counts with these definitions"))
    print(f"{'links':>5}  {'r-graphs':>8}  {'d-graphs':>8}  {'published r/d':>13}  "
          f"{'seconds':>9}  {'/ 6 links':>9}")
    for row in rows:
        published = "/".join(map(str, row["published"])) if row["published"] else "-"
        mark = "" if row["agrees"] is None else ("  ok" if row["agrees"] else "  DIFFERS")
        print(f"{row['links']:>5}  {row['rotation_graphs']:>8}  {row['displacement_graphs']:>8}"
              f"  {published:>13}  {row['seconds']:>9.3f}  {row['ratio_to_6_links']:>9.2f}{mark}")


if __name__ == "__main__":
    main()
