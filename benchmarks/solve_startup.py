"""Whole-process time of `powergraph solve models/rv40e_wang2021.yaml --json`, against a baseline
`python -c pass` measured in the same run (goal: < 0.5 s).

Usage: python benchmarks/solve_startup.py [--repeat N] [--json]
"""
from __future__ import annotations

import argparse
import json
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def wall_times(command: list[str], repeat: int) -> list[float]:
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        subprocess.run(command, cwd=ROOT, check=True, stdout=subprocess.DEVNULL)
        times.append(time.perf_counter() - start)
    return times


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--repeat", type=int, default=10)
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()
    exe = shutil.which("powergraph")
    solve = [exe] if exe else [sys.executable, "-m", "powergraph.cli.main"]
    solve += ["solve", "models/rv40e_wang2021.yaml", "--json"]
    wall_times(solve, 1)  # warm the file cache
    baseline = statistics.median(wall_times([sys.executable, "-c", "pass"], args.repeat))
    measured = statistics.median(wall_times(solve, args.repeat))
    row = {"solve_s": round(measured, 4), "python_pass_s": round(baseline, 4),
           "ratio_to_python": round(measured / baseline, 2),
           "overhead_s": round(measured - baseline, 4), "goal_s": 0.5,
           "meets_goal": measured < 0.5}
    print(json.dumps(row) if args.json else
          "\n".join(f"{key:>16}: {value}" for key, value in row.items()))


if __name__ == "__main__":
    main()
