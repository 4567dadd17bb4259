"""Every random valid train gets an answer: a solution or a locking verdict.

Generates ``--count`` trains from the stage templates of ``powergraph.testing_trains``
(seeded), solves each, and checks it: ``assert_conservation`` always; the ratio (1 DOF)
or the ports' speeds (2 DOF) against the stages' closed forms; and, for trains with at
most ``--brute-limit`` moving lossy meshes, an independent brute-force pattern search
(``powergraph.testing.consistent_patterns``) must agree — none found for a locked train,
the reported drivers among those found otherwise. Prints counts by verdict and the time
per train against the RV-40E solve measured in the same run.

Usage: python benchmarks/random_trains.py [--count 2000] [--seed 0] [--brute-limit 10] [--json]
"""
from __future__ import annotations

import argparse
import collections
import json
import statistics
import time
from pathlib import Path

import powergraph as pg
from powergraph.testing import assert_conservation, consistent_patterns
from powergraph.testing_trains import random_train

ROOT = Path(__file__).resolve().parents[1]


def verdict(result) -> str:
    if result.lock is not None:
        return "locked"
    if result.search is not None:
        return "several solutions (least loss)" if result.search.solutions > 1 \
            else "unique (found by the search)"
    return "self-locking, formal efficiency <= 0" if result.self_locking else "solved"


def check(train, result, brute_limit: int) -> bool:
    """Conservation, closed-form kinematics and (small trains) the brute force. Returns
    whether the brute force ran."""
    assert_conservation(result)
    kin = result.lock.asked if result.lock is not None else result.kinematics
    if train.ratio is not None:
        assert abs(kin.ratio / train.ratio - 1) < 1e-9, (train.seed, kin.ratio, train.ratio)
    for component, w in train.speeds.items():
        assert abs(kin.speed(component) - w) <= 1e-9 * max(abs(w), 1.0), (train.seed, component)
    lossy = [e for e in result.elements if e.efficiency < 1]
    if len(lossy) > brute_limit:
        return False
    found = consistent_patterns(train.model)
    if result.lock is not None:
        assert not found, (train.seed, "locked but the brute force finds", found)
    else:
        drivers = {e.link: (1 if e.driver == e.a else -1) for e in result.elements
                   if e.driver is not None and e.efficiency < 1}
        assert any(all(p.get(k, c) == c for k, c in drivers.items()) for p in found), \
            (train.seed, "solution not among the brute force's", drivers, found)
    return True


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--count", type=int, default=2000)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--brute-limit", type=int, default=10)
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()
    rv = pg.load_model(ROOT / "models" / "rv40e_wang2021.yaml")
    pg.solve(rv)
    start = time.perf_counter()
    for _ in range(50):
        pg.solve(rv)
    baseline = (time.perf_counter() - start) / 50
    counts: collections.Counter = collections.Counter()
    times: dict[str, list[float]] = collections.defaultdict(list)
    brute = unsettled = 0
    for n in range(args.count):
        train = random_train(f"{args.seed}-{n}")
        start = time.perf_counter()
        try:
            result = pg.solve(train.model)
        except pg.SolveError as exc:  # must never happen
            unsettled += 1
            print(f"seed {train.seed}: {exc}")
            continue
        elapsed = time.perf_counter() - start
        kind = verdict(result)
        counts[kind] += 1
        times[kind].append(elapsed)
        brute += check(train, result, args.brute_limit)
    every = [t for ts in times.values() for t in ts]
    report = {
        "trains": args.count, "seed": args.seed, "did_not_settle": unsettled,
        "verdicts": dict(counts), "brute_force_checked": brute,
        "rv40e_solve_ms": round(baseline * 1e3, 3),
        "median_per_train_vs_rv40e": round(statistics.median(every) / baseline, 2),
        "mean_per_train_vs_rv40e": round(statistics.mean(every) / baseline, 2),
        "mean_by_verdict_vs_rv40e": {k: round(statistics.mean(v) / baseline, 2)
                                     for k, v in times.items()},
    }
    if args.json:
        print(json.dumps(report, indent=1))
        return
    print(f"{args.count} random trains (seed {args.seed}): {unsettled} did not settle; "
          f"{brute} also checked by brute force")
    for kind, n in counts.most_common():
        print(f"  {kind:<40}{n:>6}   mean time {statistics.mean(times[kind]) / baseline:8.2f}"
              f" x RV-40E solve")
    print(f"RV-40E solve: {baseline * 1e3:.2f} ms; per train median "
          f"{report['median_per_train_vs_rv40e']} x, mean {report['mean_per_train_vs_rv40e']} x")


if __name__ == "__main__":
    main()
