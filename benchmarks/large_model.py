"""Loading and validating a large model is linear in its size.

Generates fixed-axis chains of N gears (each meshes the next, carrier = the frame) for
N = 10,000 and 100,000 (about 0.6 and 6 MB), and times reading the YAML, checking it
against the schema and building the model, with `check` of the RV-40E (in-process) as the
baseline of the same run. Linear work shows as a time ratio near the size ratio (10).

Usage: python benchmarks/large_model.py [--sizes 10000 100000]
"""
from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from powergraph.model import load_model  # noqa: E402
from powergraph.model.conform import check_document  # noqa: E402
from powergraph.model.yaml_loader import gc_paused, load_yaml_file  # noqa: E402


def chain_text(n: int) -> str:
    """A fixed-axis chain of ``n`` gears: gear i meshes gear i + 1 on the frame."""
    lines = ["name: chain", f"description: fixed-axis chain of {n} gears", "components:",
             "  0: {role: frame}"]
    lines += [f"  {i}: {{teeth: {20 + i % 7}}}" for i in range(1, n + 1)]
    lines.append("links:")
    lines += [f"  - {{type: mesh, between: [{i}, {i + 1}], efficiency: 0.99}}"
              for i in range(1, n)]
    lines += ["ports:", "  - {component: 1, role: input, speed: 1500 rpm, power: 1 kW}",
              f"  - {{component: {n}, role: output}}"]
    return "\n".join(lines) + "\n"


def timed(function, *args):
    start = time.perf_counter()
    value = function(*args)
    return time.perf_counter() - start, value


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--sizes", type=int, nargs="+", default=[10_000, 100_000])
    args = parser.parse_args()
    rv = ROOT / "models" / "rv40e_wang2021.yaml"
    load_model(rv)
    baseline = min(timed(load_model, rv)[0] for _ in range(5))
    print(f"baseline: load_model(rv40e_wang2021.yaml) {baseline * 1e3:.2f} ms")
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for n in args.sizes:
            path = Path(tmp) / f"chain{n}.yaml"
            path.write_text(chain_text(n))
            read, data = timed(load_yaml_file, path)
            with gc_paused():
                schema, _ = timed(check_document, data)
            whole, model = timed(load_model, path)
            assert len(model.bodies) == n + 1 and len(model.meshes) == n - 1
            rows.append((n, path.stat().st_size, read, schema, whole))
            print(f"N = {n:>7}: {path.stat().st_size / 1e6:5.2f} MB  read {read:6.2f} s  "
                  f"schema {schema:6.2f} s  load_model (all) {whole:6.2f} s  "
                  f"({whole / baseline:.0f}x baseline)")
    if len(rows) > 1:
        (n0, _, _, _, t0), (n1, _, _, _, t1) = rows[0], rows[-1]
        print(f"size ratio {n1 / n0:.0f}, time ratio {t1 / t0:.1f} (linear: about equal)")


if __name__ == "__main__":
    main()
