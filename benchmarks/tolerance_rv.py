"""RV-40E tolerance analysis: 10^6 units, vectorised, against a loop of nominal evaluations.

``models/rv40e_tolerances.yaml`` (five toleranced values: both meshes' plays, the cycloid
profile error, both mesh efficiencies) is analysed by

(a) :func:`powergraph.analyses.tolerance.tolerance_analysis` on ``--units`` units (sampling,
    vectorised evaluation of lost motion, fluctuation and efficiency, statistics and one
    yield), without the Sobol indices (``mc_s``), and the Sobol indices alone
    (``sobol_s``: N = 4096, 4096·7 evaluations plus SALib's bootstrap);
(b) a Python loop over ``--loop`` units of what the nominal tools do for one unit: the
    unit's values put into the model (``dataclasses.replace``, no re-validation), then
    ``analyse_backlash`` (lost motion), ``train_fluctuation`` (the exact fluctuation) and
    ``powergraph.solve`` (efficiency); extrapolated to ``--units``.

``max_abs_diff_vs_loop`` compares (a) and (b) on the loop's units, per output. ``setup_s``
is the one-off preparation of (a) (the fluctuation table of 10 exact
fluctuations and the compiled sweep); ``total_s`` = setup + mc. Wall-clock, best of
``--repeat`` after a warm-up; (a) and (b) run in the same process, one after the other.

Usage: python benchmarks/tolerance_rv.py [--json] [--units N] [--loop N] [--repeat N]
"""
from __future__ import annotations

import argparse
import dataclasses
import json
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import powergraph as pg  # noqa: E402
from powergraph.analyses.backlash import analyse_backlash  # noqa: E402
from powergraph.analyses.cycloid import train_fluctuation  # noqa: E402
from powergraph.analyses.tolerance import ToleranceEvaluator, tolerance_analysis  # noqa: E402
from powergraph.model import load_model  # noqa: E402


def loop_unit(model, values: dict) -> tuple[float, float, float]:
    """One unit by the nominal tools: (lost motion, fluctuation, efficiency)."""
    link0, link1 = model.links[0], model.links[1]
    blocks0 = {**link0.blocks, "backlash_arcmin": values["links.0.backlash_arcmin"]}
    cycloid = dataclasses.replace(link1.blocks["cycloid"],
                                  profile_error=values["links.1.cycloid.profile_error"])
    blocks1 = {**link1.blocks, "backlash_arcmin": values["links.1.backlash_arcmin"],
               "cycloid": cycloid}
    unit = model.with_link(0, blocks=blocks0, efficiency=values["links.0.efficiency"]) \
        .with_link(1, blocks=blocks1, efficiency=values["links.1.efficiency"])
    lost = analyse_backlash(unit).worst_case
    fluctuation = train_fluctuation(unit).stages[0].max_deviation_percent
    return lost, fluctuation, pg.solve(unit).efficiency


def best_of(repeat: int, run) -> tuple[float, object]:
    times, result = [], None
    for _ in range(repeat):
        start = time.perf_counter()
        result = run()
        times.append(time.perf_counter() - start)
    return min(times), result


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--json", action="store_true", help="print one JSON line")
    parser.add_argument("--units", type=int, default=1_000_000)
    parser.add_argument("--loop", type=int, default=20)
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    model = load_model(ROOT / "models" / "rv40e_tolerances.yaml")

    start = time.perf_counter()
    evaluator = ToleranceEvaluator(model)
    setup = time.perf_counter() - start
    specs = ["lost_motion<=1arcmin"]
    run = lambda: tolerance_analysis(model, samples=args.units, seed=1, specs=specs,  # noqa
                                     sobol_samples=0, evaluator=evaluator, progress=False)
    run()                                                     # warm-up
    mc, result = best_of(args.repeat, run)
    sobol, _ = best_of(1, lambda: tolerance_analysis(model, samples=2, seed=1,
                                                     evaluator=evaluator, progress=False))

    rng = np.random.default_rng(2)
    entries = model.tolerances.entries
    units = [{t.path: float(t.distribution.ppf(rng.random(1))[0]) for t in entries}
             for _ in range(args.loop)]
    loop_unit(model, units[0])                                # warm-up
    start = time.perf_counter()
    loop_values = [loop_unit(model, u) for u in units]
    loop = (time.perf_counter() - start) / args.loop * args.units
    # The loop's units through the vectorised evaluator: the same numbers?
    columns = {p: np.array([u[p] for u in units]) for p in units[0]}
    vectorised = evaluator(columns)
    diff = {k: float(np.max(np.abs(vectorised[k] - np.array([v[i] for v in loop_values]))))
            for i, k in enumerate(("lost_motion_arcmin", "fluctuation_percent",
                                   "efficiency"))}
    row = {"units": args.units, "setup_s": round(setup, 3), "mc_s": round(mc, 3),
           "total_s": round(setup + mc, 3), "sobol_s": round(sobol, 3),
           "units_per_s": round(args.units / mc), "loop_units": args.loop,
           "loop_s_extrapolated": round(loop, 1), "speedup_vs_loop": round(loop / mc, 1),
           "speedup_vs_loop_with_setup": round(loop / (setup + mc), 1),
           "max_abs_diff_vs_loop": diff,
           "yield_lost_motion_1arcmin": result.yields[0].to_dict()}
    if args.json:
        print(json.dumps(row))
    else:
        for key, value in row.items():
            print(f"{key:28} {value}")


if __name__ == "__main__":
    main()
