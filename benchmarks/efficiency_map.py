"""Efficiency maps of two RV-40Es, 50 × 50 points, against single solves in the same run.

**Friction RV** (the goal: its 50 × 50 map in under 2 s): ``models/rv40e.yaml`` at its
lubricant's own temperature (its heat balance removed: with it, ``map`` solves each point
with its own heat balance, a whole solve per step) —
ISO/TR 14179-2 on the first stage (load-dependent: every point is its own fixed point),
pins and crank bearings on the cycloid mesh, crank-support bearing friction and drags. Its
map runs the load-dependent passes on the whole grid at once
(:mod:`powergraph.analyses.efficiency_grid`).

- ``friction_single_solve_s``: one ``powergraph.solve`` of it (best of ``--repeat``
  averages over 20 solves);
- ``friction_map_s``: :func:`powergraph.analyses.efficiency_map.efficiency_map` over
  ``--torques`` output torques (50–800 N·m) × ``--speeds`` input speeds (100–3000 rpm);
  ``friction_single_solves`` the points it solved one by one, ``friction_unconverged``
  the points that did not converge;
- ``friction_loop_s_extrapolated``: a plain loop of one solve per point over
  ``--loop-rows`` rows, extrapolated to the whole map, and
  ``friction_max_rel_diff_vs_loop`` between the two on those rows.

**Affine RV**: ``models/rv40e_wang2021.yaml`` with, written here: the first-stage mesh given
``friction: {mu: 0.05}`` and ``geometry: {module: 1.5, shifts: [0.3, -0.3]}``; the two crank
bearings in the planet frame (``bearing [3, 7]``, mu 0.0015, bore 20 mm, drag 0.05 N·m
each); the input shaft's bearing and seal (``bearing [1, 0]``, drag 0.1 N·m + 0.0005 N·m
per rpm); and the output seal (``components.6.drag``, 0.5 N·m). Its mesh efficiencies are
constant, so each row (one speed) is affine in the load: two solves per speed give the row
(``affine_map_s``, against ``affine_single_solve_s``).

Ratios: ``*_map_over_single`` = map / one single solve, ``friction_loop_over_map``.
Wall-clock, best of ``--repeat``, after a warm-up.

Usage: python benchmarks/efficiency_map.py [--json] [--torques N] [--speeds N]
[--loop-rows N] [--repeat N]
"""
from __future__ import annotations

import argparse
import dataclasses
import json
import math
import sys
import time
from pathlib import Path

import numpy as np
import yaml

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import powergraph as pg  # noqa: E402
from powergraph.analyses.efficiency_map import _at, efficiency_map  # noqa: E402
from powergraph.kinematics import solve_speeds  # noqa: E402
from powergraph.model import model_from_dict  # noqa: E402


def affine_model():
    """The RV-40E with constant mesh friction, bearings and drags (written above)."""
    data = yaml.safe_load((ROOT / "models" / "rv40e_wang2021.yaml").read_text())
    first = data["links"][0]
    first.pop("efficiency", None)
    first.update(friction={"mu": 0.05}, geometry={"module": 1.5, "shifts": [0.3, -0.3]})
    data["links"] += [
        {"type": "bearing", "between": [3, 7], "friction": {"mu": 0.0015, "bore": "20 mm"},
         "drag": {"no_load_torque": "0.05 N*m"}},
        {"type": "bearing", "between": [1, 0], "drag": {"a": "0.1 N*m", "b": "0.0005 N*m"}},
    ]
    data["components"][6]["drag"] = {"no_load_torque": "0.5 N*m"}
    return model_from_dict(data)


def best_of(repeat: int, run) -> tuple[float, object]:
    times, result = [], None
    for _ in range(repeat):
        start = time.perf_counter()
        result = run()
        times.append(time.perf_counter() - start)
    return min(times), result


def single_solve(model, repeat: int) -> float:
    pg.solve(model)                                                    # warm-up
    seconds, _ = best_of(repeat, lambda: [pg.solve(model) for _ in range(20)])
    return seconds / 20


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--torques", type=int, default=50)
    parser.add_argument("--speeds", type=int, default=50)
    parser.add_argument("--loop-rows", type=int, default=2)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()

    torques = np.linspace(50.0, 800.0, args.torques)
    speeds = np.linspace(100.0, 3000.0, args.speeds)
    # at its lubricant's own temperature: the heat balance (a whole solve per step at every
    # point) is what `map` adds on top, not what the batched grid is timed for
    friction = dataclasses.replace(pg.load_model(ROOT / "models" / "rv40e.yaml"), thermal=None)
    single = single_solve(friction, args.repeat)
    efficiency_map(friction, torques[:2], speeds[:2])                  # warm-up
    map_s, emap = best_of(args.repeat, lambda: efficiency_map(friction, torques, speeds))

    rows = np.linspace(0, args.speeds - 1, args.loop_rows).astype(int)
    sense = np.sign(solve_speeds(friction).ratio)

    def loop():
        return np.array([[pg.solve(_at(friction, speeds[i] * math.pi / 30, t, sense)).efficiency
                          for t in torques] for i in rows])

    loop_s, looped = best_of(1, loop)
    loop_full = loop_s / len(rows) * args.speeds
    affine = affine_model()
    affine_single = single_solve(affine, args.repeat)
    efficiency_map(affine, torques[:2], speeds[:1])                    # warm-up
    affine_s, _ = best_of(args.repeat, lambda: efficiency_map(affine, torques, speeds))
    report = {
        "model": friction.name, "points": int(torques.size * speeds.size),
        "friction_single_solve_s": single, "friction_map_s": map_s,
        "friction_map_over_single": map_s / single,
        "friction_single_solves": emap.single_solves,
        "friction_unconverged": len(emap.unconverged),
        "friction_loop_s_extrapolated": loop_full, "friction_loop_over_map": loop_full / map_s,
        "friction_max_rel_diff_vs_loop":
            float(np.max(np.abs(looped / emap.efficiency[rows] - 1.0))),
        "friction_efficiency_range": [float(emap.efficiency.min()),
                                      float(emap.efficiency.max())],
        "goal_s": 2.0, "goal_met": bool(map_s < 2.0),
        "affine_model": affine.name, "affine_single_solve_s": affine_single,
        "affine_map_s": affine_s, "affine_map_over_single": affine_s / affine_single,
    }
    if args.json:
        print(json.dumps(report, indent=1))
    else:
        for key, value in report.items():
            print(f"{key:<32}{value}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
