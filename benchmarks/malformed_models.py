"""Wall time and exit status of `powergraph solve` on every malformed model of
tests/data/malformed.yaml (promise: exit 2, one line, no traceback, under a second),
with `python -c pass` measured in the same run as the baseline.

Usage: python benchmarks/malformed_models.py
"""
from __future__ import annotations

import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[1]


def timed(command: list[str]) -> tuple[float, subprocess.CompletedProcess]:
    start = time.perf_counter()
    proc = subprocess.run(command, cwd=ROOT, capture_output=True, text=True)
    return time.perf_counter() - start, proc


def main() -> None:
    cases = yaml.safe_load((ROOT / "tests" / "data" / "malformed.yaml").read_text())
    exe = shutil.which("powergraph")
    base = [exe] if exe else [sys.executable, "-m", "powergraph.cli.main"]
    baseline, _ = timed([sys.executable, "-c", "pass"])
    worst = 0.0
    with tempfile.TemporaryDirectory() as tmp:
        for case in cases:
            path = Path(tmp) / f"{case['id']}.yaml"
            path.write_text(case["text"])
            seconds, proc = timed(base + ["solve", str(path)])
            lines = proc.stderr.strip().splitlines()
            ok = proc.returncode == 2 and len(lines) == 1 and "Traceback" not in proc.stderr
            worst = max(worst, seconds)
            print(f"{case['id']:<24} exit {proc.returncode}  {seconds:6.3f} s  "
                  f"{'ok ' if ok else 'BAD'}  {lines[0] if lines else ''}")
    print(f"\nbaseline python -c pass: {baseline:.3f} s; slowest malformed model: {worst:.3f} s "
          f"({worst / baseline:.1f}x baseline)")


if __name__ == "__main__":
    main()
