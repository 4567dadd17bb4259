"""A duty cycle of 10^5 operating points through ``powergraph.analyses.cycle``, a plain
train's and a hybrid's, each against a loop of single solves over the same rows timed in
the same run (on a sample, extrapolated, unless ``--full``): the plain train's rows go
through the compiled sweep, the hybrid's (the THS-II, machines on a bus) through the
sweep with the bus balance (``powergraph.analyses.cycle_hybrid``). The result's columns
are weighed too (bytes per row: issue 34; docs/performance.md has the figures of the
command line, wall time and peak memory).

    python benchmarks/cycle.py [--points 100000] [--sample 2000] [--full]
"""
from __future__ import annotations

import argparse
import io
import time
from pathlib import Path

import numpy as np

import powergraph as pg
from powergraph.analyses.cycle import _single_rows, cycle
from powergraph.analyses.cycle_hybrid import METHOD
from powergraph.analyses.cycle_points import read_points

ROOT = Path(__file__).resolve().parents[1]


def _points(n: int, rng: np.random.Generator) -> str:
    rpm = rng.uniform(500, 3000, n)
    kw = rng.uniform(0.1, 2.0, n)
    lines = ["carrier.speed [rpm],carrier.power [kW],duration [s]"]
    lines += [f"{a!r},{b!r},1" for a, b in zip(rpm.tolist(), kw.tolist())]
    return "\n".join(lines) + "\n"


def _hybrid_points(n: int, rng: np.random.Generator) -> str:
    lines = ["engine.speed [rpm],engine.power [kW],wheels.speed [rpm],duration [s]"]
    for e, p, w in zip(rng.uniform(1000, 4000, n).tolist(), rng.uniform(5, 50, n).tolist(),
                       rng.uniform(50, 900, n).tolist()):
        lines.append(f"{e!r},{p!r},{w!r},1")
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--points", type=int, default=100_000)
    parser.add_argument("--sample", type=int, default=2000,
                        help="single solves timed (extrapolated to --points)")
    parser.add_argument("--full", action="store_true", help="time every single solve")
    args = parser.parse_args(argv)
    rng = np.random.default_rng(1)
    model = pg.load_model(ROOT / "models" / "planetary_2kh_carrier_to_ring.yaml")
    text = _points(args.points, rng)

    start = time.perf_counter()
    result = cycle(model, io.StringIO(text))
    cold = time.perf_counter() - start       # with the one-off imports (sympy)
    start = time.perf_counter()
    result = cycle(model, io.StringIO(text))
    batched = time.perf_counter() - start    # the same call again, imports done
    assert result.method == "sweep"

    n_single = args.points if args.full else min(args.sample, args.points)
    head = "\n".join(text.splitlines()[: n_single + 1]) + "\n"
    points = read_points(io.StringIO(head), model)
    start = time.perf_counter()
    rows = _single_rows(model, points)
    single = (time.perf_counter() - start) * args.points / n_single
    worst = float(np.max(np.abs(result.loss[:n_single] - rows.loss)
                         / np.maximum(rows.loss, 1e-300)))
    print(f"{args.points} points, plain train: cycle (sweep) {batched:.2f} s, first call "
          f"{cold:.2f} s (with the one-off imports); loop of single solves {single:.1f} s"
          f"{'' if args.full else ' (extrapolated from '}"
          f"{'' if args.full else str(n_single) + ')'}; speed-up {single / batched:.0f}x "
          f"({single / cold:.0f}x on the first call); largest relative difference of a "
          f"row's loss {worst:.1e}")
    held = sum(a.nbytes for a in (result.power_in, result.power_out, result.loss,
                                  result.efficiencies, result.verdict_codes,
                                  result.electrical_share, result.negative_split,
                                  result.with_machines, *result.losses.values()))
    print(f"the result's own columns: {held / args.points:.0f} bytes per row (the "
          "durations and file lines shared with the points)")

    ths = pg.load_model(ROOT / "models" / "ths2_power_split.yaml")
    text = _hybrid_points(args.points, rng)
    start = time.perf_counter()
    hybrid = cycle(ths, io.StringIO(text))
    cold = time.perf_counter() - start        # the first call of the process
    start = time.perf_counter()
    hybrid = cycle(ths, io.StringIO(text))
    batched = time.perf_counter() - start
    assert hybrid.method == METHOD and not hybrid.failed.any()
    head = "\n".join(text.splitlines()[: n_single + 1]) + "\n"
    points = read_points(io.StringIO(head), ths)
    start = time.perf_counter()
    rows = _single_rows(ths, points)
    per_row = (time.perf_counter() - start) / n_single
    single = per_row * args.points
    worst = max(float(np.max(np.abs(a[:n_single] - b) / np.maximum(np.abs(b), 1e-300)))
                for a, b in
                [(hybrid.power_out, rows.power_out), (hybrid.loss, rows.loss),
                 *((hybrid.losses[k], v) for k, v in rows.losses.items())])
    same = (np.array_equal(hybrid.verdict_codes[:n_single], rows.verdict_codes)
            and np.array_equal(hybrid.negative_split[:n_single], rows.negative_split))
    print(f"{args.points} points, THS-II hybrid: cycle (sweep with bus balance) "
          f"{batched:.2f} s, first call {cold:.2f} s (each call reads the points and "
          f"compiles the train's sweep); loop of single solves {single:.0f} s "
          f"({per_row * 1e3:.2f} ms per row"
          f"{'' if args.full else ', extrapolated from ' + str(n_single)}); speed-up "
          f"{single / batched:.0f}x ({single / cold:.0f}x on the first call); largest "
          f"relative difference of a row's power out, loss or element loss {worst:.1e}; "
          f"verdicts and negative splits {'the same' if same else 'DIFFERENT'}; "
          f"{int(hybrid.negative_split.sum())} rows in a negative split, cycle efficiency "
          f"{hybrid.efficiency:.4f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
