"""Hostile model files: exit status, tracebacks and time of `check` and `solve`.

From the library models in models/, generates (seeded) mutated and hostile files: control
characters, NUL, byte-order marks mid-file, invalid UTF-8, 1e308, NaN, inf, deep nesting,
huge integers, 20 MB single lines, random byte flips, deleted/duplicated lines and random
field values. Runs `check` and `solve` on each in-process (through
``powergraph.cli.main.main(argv)``, stderr captured) and a sample through real
subprocesses, and reports the count, the exit-status histogram, the tracebacks (the
promise: none), and the slowest file against a baseline measured in the same run (`check`
of the unmodified RV-40E). Promise: every file under 1 s, except files over 1 MB, which are
refused by size or handled under 10 s.

Usage: python benchmarks/hostile_inputs.py [--count 3000] [--subprocess 30] [--seed 1]
"""
from __future__ import annotations

import argparse
import collections
import io
import random
import shutil
import subprocess
import sys
import tempfile
import time
import traceback
import warnings
from contextlib import redirect_stderr, redirect_stdout
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from powergraph.cli.main import main  # noqa: E402

JUNK_VALUES = ["1e308", "-1e308", ".nan", ".inf", "-.inf", "1e-308", "0", "-1", "9" * 400,
               "[]", "{}", "~", "true", "'x'", "*a", "&a [1, 2]", "[[[[[[[[", "!!binary aGk=",
               "!!python/object:os.system x", "1e400 rpm", "0.0", "2.5", "-0.0", "1 kg",
               "\"\\u0000\"", "[1, 2, 3]", "{a: 1}", "null", "0x7fffffffffffffffffff"]


def mutate(text: str, rng: random.Random, index: int) -> bytes:
    """One hostile variant of ``text`` (the kind cycles with ``index``)."""
    lines = text.splitlines(keepends=True)
    where = rng.randrange(len(lines))
    kind = index % 12
    if kind == 0:    # a control character, NUL or BOM inside the text
        pos = rng.randrange(len(text))
        return (text[:pos] + rng.choice(["\x00", "\x01", "\x1b", "\x7f", "\ufeff", "\x85",
                                         "\ud800"]) + text[pos:]).encode("utf-8",
                                                                         "surrogatepass")
    if kind == 1:    # invalid UTF-8 bytes
        raw = bytearray(text.encode())
        raw[rng.randrange(len(raw))] = rng.choice([0xff, 0xc3, 0x80, 0xfe])
        return bytes(raw)
    if kind in (2, 3):  # random byte flips
        raw = bytearray(text.encode())
        for _ in range(rng.randint(1, 6)):
            raw[rng.randrange(len(raw))] = rng.randrange(256)
        return bytes(raw)
    if kind == 4:    # delete a line
        return "".join(lines[:where] + lines[where + 1:]).encode()
    if kind == 5:    # duplicate a line
        return "".join(lines[:where + 1] + lines[where:]).encode()
    if kind in (6, 7, 8):  # a random value for a field
        candidates = [i for i, line in enumerate(lines) if ": " in line
                      and not line.lstrip().startswith("#")]
        i = rng.choice(candidates)
        head = lines[i].split(": ", 1)[0] if rng.random() < 0.5 else lines[i].rsplit(": ", 1)[0]
        lines[i] = f"{head}: {rng.choice(JUNK_VALUES)}\n"
        if "{" in head and "}" not in head:
            lines[i] = lines[i].rstrip("\n") + "}" * head.count("{") + "\n"
        return "".join(lines).encode("utf-8", "surrogatepass")
    if kind == 9:    # deep nesting
        depth = rng.choice([50, 99, 101, 1000, 100_000])
        return (text + f"\nx: {'[' * depth}{']' * depth}\n").encode()
    if kind == 10:   # huge integers in place of numbers
        return "".join(line.replace(": 1", ": 1" + "0" * rng.randint(20, 5000), 1)
                       for line in lines).encode()
    return (text + f"\n# {'x' * rng.randint(1, 200)}\n").encode()  # a harmless comment


def big_files() -> list[tuple[str, bytes]]:
    """A few large files: 20 MB single lines (over the limit) and 5 MB (under it)."""
    return [("20MB-comment", b"name: t\n# " + b"x" * 20_000_000 + b"\n"),
            ("20MB-name", b"name: " + b"y" * 20_000_000 + b"\n"),
            ("5MB-name", b"name: " + b"z" * 5_000_000 + b"\ncomponents: {}\nlinks: []\n"
                                                          b"ports: []\n"),
            ("5MB-list", b"name: t\nitems: [" + b"1, " * 1_600_000 + b"1]\n")]


def in_process(argv: list[str]) -> tuple[int, str, float]:
    """(status or 'traceback', first stderr line, seconds) of ``main(argv)``."""
    out, err = io.StringIO(), io.StringIO()
    start = time.perf_counter()
    with redirect_stdout(out), redirect_stderr(err), warnings.catch_warnings():
        warnings.simplefilter("error")
        try:
            status = main(argv)
        except SystemExit as exc:
            status = exc.code
        except BaseException:  # noqa: BLE001 - a crash is what we are counting
            status = "traceback"
            err.write(traceback.format_exc())
    seconds = time.perf_counter() - start
    text = err.getvalue()
    if "Traceback" in text or len(text.strip().splitlines()) > 1:
        status = "traceback" if "Traceback" in text else f"{status} (several lines)"
    return status, (text.strip().splitlines() or [""])[0][:160], seconds


def main_benchmark() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--count", type=int, default=3000)
    parser.add_argument("--subprocess", type=int, default=30)
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    rng = random.Random(args.seed)
    models = sorted((ROOT / "models").glob("*.yaml"))
    texts = {m.name: m.read_text() for m in models}
    rv = str(ROOT / "models" / "rv40e_wang2021.yaml")
    for model in models:  # one-time imports (scipy, pint...) are not a per-file cost
        in_process(["check", str(model)])
        in_process(["solve", str(model)])
    baseline = min(in_process(["check", rv])[2] for _ in range(5))
    histogram: collections.Counter = collections.Counter()
    bad: list[str] = []
    slowest = (0.0, "", "")
    slowest_big = (0.0, "", "")
    with tempfile.TemporaryDirectory() as tmp:
        files = []
        for i in range(args.count):
            name = rng.choice(list(texts))
            path = Path(tmp) / f"{i:05d}-{name}"
            path.write_bytes(mutate(texts[name], rng, i))
            files.append(path)
        for label, data in big_files():
            path = Path(tmp) / f"{label}.yaml"
            path.write_bytes(data)
            files.append(path)
        for path in files:
            big = path.stat().st_size > 1_000_000
            for command in ("check", "solve"):
                status, line, seconds = in_process([command, str(path)])
                histogram[(command, status)] += 1
                if status not in (0, 2):
                    bad.append(f"{command} {path.name}: {status} {line}")
                if big and seconds > slowest_big[0]:
                    slowest_big = (seconds, f"{command} {path.name}", line)
                elif not big and seconds > slowest[0]:
                    slowest = (seconds, f"{command} {path.name}", line)
        exe = shutil.which("powergraph")
        base = [exe] if exe else [sys.executable, "-m", "powergraph.cli.main"]
        sample = rng.sample(files[:args.count], min(args.subprocess, args.count))
        sub_tracebacks, sub_statuses = 0, collections.Counter()
        for path in sample:
            proc = subprocess.run(base + ["check", str(path)], capture_output=True, text=True,
                                  errors="replace", cwd=ROOT, timeout=60)
            sub_statuses[proc.returncode] += 1
            lines = proc.stderr.strip().splitlines()
            if "Traceback" in proc.stderr or len(lines) > 1:
                sub_tracebacks += 1
    total = len(files)
    print(f"files: {total} ({args.count} mutated, {total - args.count} large); "
          f"commands run in-process: {2 * total}")
    for (command, status), n in sorted(histogram.items(), key=str):
        print(f"  {command:<6} exit {status}: {n}")
    tracebacks = sum(n for (_, s), n in histogram.items() if s == "traceback")
    print(f"tracebacks: {tracebacks}; other statuses than 0/2: {len(bad)}")
    for line in bad[:10]:
        print("   ", line)
    print(f"baseline (check of the unmodified RV-40E, in-process): {baseline * 1e3:.1f} ms")
    print(f"slowest file under 1 MB: {slowest[0] * 1e3:.1f} ms "
          f"({slowest[0] / baseline:.1f}x baseline) {slowest[1]} -> {slowest[2][:80]}")
    print(f"slowest file over 1 MB: {slowest_big[0]:.2f} s {slowest_big[1]} -> "
          f"{slowest_big[2][:80]}")
    print(f"subprocess sample: {len(sample)} `check` runs, exit statuses "
          f"{dict(sub_statuses)}, tracebacks or several lines: {sub_tracebacks}")


if __name__ == "__main__":
    main_benchmark()
