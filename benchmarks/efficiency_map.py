"""Efficiency map of an RV-40E with mesh friction, bearing friction and drag: 50 × 50 points.

The model is ``models/rv40e.yaml`` with, written here: the first-stage mesh given
``friction: {mu: 0.05}`` and ``geometry: {module: 1.5, shifts: [0.3, -0.3]}``; the two crank
bearings in the planet frame (``bearing [3, 7]``, mu 0.0015, bore 20 mm, drag 0.05 N·m
each); the input shaft's bearing and seal (``bearing [1, 0]``, drag 0.1 N·m + 0.0005 N·m
per rpm); and the output seal (``components.6.drag``, 0.5 N·m).

Measured in the same run:

- ``single_solve_s``: one ``powergraph.solve`` of the model (best of ``--repeat``
  averages over 20 solves);
- ``map_s``: :func:`powergraph.analyses.efficiency_map.efficiency_map` over ``--torques``
  output torques (50–800 N·m) × ``--speeds`` input speeds (100–3000 rpm). The mesh
  efficiencies are constant, so each row (one speed) is affine in the load: two solves per
  speed, at the smallest and the largest torque, give the row;
- ``loop_s_extrapolated``: a plain loop of one solve per point over ``--loop-rows`` rows,
  extrapolated to the whole map, and ``max_abs_diff_vs_loop`` between the two on those
  rows;
- ``iso_map_s_extrapolated``: the same model with the first stage's friction by
  ISO/TR 14179-2 (viscosity 30 mPa·s, Ra 0.5 µm, face width 12 mm), whose efficiency depends
  on the load, so every point is solved: an ``--iso-grid`` square map, extrapolated.

Ratios: ``map_over_single`` = map_s / single_solve_s, ``loop_over_map``. Wall-clock, best
of ``--repeat``, after a warm-up.

Usage: python benchmarks/efficiency_map.py [--json] [--torques N] [--speeds N]
[--loop-rows N] [--repeat N]
"""
from __future__ import annotations

import argparse
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


def friction_model(iso: bool = False):
    """``models/rv40e_friction.yaml`` if it exists, else the RV-40E with the blocks above
    (with ``iso``, the first stage's friction by ISO/TR 14179-2)."""
    path = ROOT / "models" / "rv40e_friction.yaml"
    if path.exists() and not iso:
        return pg.load_model(path)
    data = yaml.safe_load((ROOT / "models" / "rv40e.yaml").read_text())
    first = data["links"][0]
    first.pop("efficiency", None)
    first.update(friction={"mu": 0.05}, geometry={"module": 1.5, "shifts": [0.3, -0.3]})
    if iso:
        first.update(friction={"model": "iso14179", "viscosity": "30 mPa*s",
                               "roughness": "0.5 um"},
                     geometry={"module": 1.5, "shifts": [0.3, -0.3], "face_width": 12})
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


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--torques", type=int, default=50)
    parser.add_argument("--speeds", type=int, default=50)
    parser.add_argument("--loop-rows", type=int, default=2)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--iso-grid", type=int, default=8)
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()

    model = friction_model()
    torques = np.linspace(50.0, 800.0, args.torques)
    speeds = np.linspace(100.0, 3000.0, args.speeds)
    pg.solve(model)                                                    # warm-up
    single, _ = best_of(args.repeat, lambda: [pg.solve(model) for _ in range(20)])
    single /= 20
    efficiency_map(model, torques[:2], speeds[:1])                     # warm-up
    map_s, emap = best_of(args.repeat, lambda: efficiency_map(model, torques, speeds))

    rows = np.linspace(0, args.speeds - 1, args.loop_rows).astype(int)
    sense = np.sign(solve_speeds(model).ratio)

    def loop():
        return np.array([[pg.solve(_at(model, speeds[i] * math.pi / 30, t, sense)).efficiency
                          for t in torques] for i in rows])

    loop_s, looped = best_of(1, loop)
    loop_full = loop_s / len(rows) * args.speeds
    iso = friction_model(iso=True)
    n = args.iso_grid
    iso_s, _ = best_of(1, lambda: efficiency_map(iso, np.linspace(50.0, 800.0, n),
                                                 np.linspace(100.0, 3000.0, n)))
    report = {
        "model": model.name, "points": int(torques.size * speeds.size),
        "single_solve_s": single, "map_s": map_s, "map_over_single": map_s / single,
        "loop_s_extrapolated": loop_full, "loop_over_map": loop_full / map_s,
        "max_abs_diff_vs_loop": float(np.max(np.abs(looped - emap.efficiency[rows]))),
        "efficiency_range": [float(emap.efficiency.min()), float(emap.efficiency.max())],
        "rises_with_torque": bool(np.all(np.diff(emap.efficiency, axis=1) > 0)),
        "iso_map_s_extrapolated": iso_s / n ** 2 * torques.size * speeds.size,
        "goal_s": 2.0,
    }
    if args.json:
        print(json.dumps(report, indent=1))
    else:
        for key, value in report.items():
            print(f"{key:<24}{value}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
