"""Hostile model files and arguments: exit status, tracebacks, hangs and answers of every
command.

From the library models in models/, generates (seeded) hostile files, one mutation class
each (benchmarks/hostile_mutations.py: control characters, invalid UTF-8, byte flips,
deleted/duplicated lines, junk values, deep nesting, huge integers, explicit YAML tags,
unit bombs, equivalent and frequency units, component ids renamed to the flow graph's
reserved words or odd text, YAML merge keys), plus a few files over 1 MB. Every model
command runs on every file in-process (``powergraph.cli.main.main(argv)``, stderr
captured), on all cores; each file also gets one numeric option at a float limit and one
bad output path of a writing command, and a sample runs through real subprocesses.

Reports: the statuses, the tracebacks (promise: none), other exit statuses than 0 and 2
(none), the commands over 5 s (none), and for the mutations that do not change the train
(``same``: ids renamed, merges of equal values, equivalent units, a comment) the answers
that differ from the plain model's (efficiency, circulating power, the speeds and torques,
`draw` succeeding),
per class; then the time taken.

Usage: python benchmarks/hostile_inputs.py [--count 3000] [--jobs N] [--subprocess 30]
                                           [--seed 1] [--classes a,b,...]
"""
from __future__ import annotations

import argparse
import collections
import io
import json
import multiprocessing
import os
import random
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import traceback
import warnings
from contextlib import redirect_stderr, redirect_stdout
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT), str(ROOT / "benchmarks"), str(ROOT / "tests" / "cli")]

from hostile_mutations import CLASSES, mutate  # noqa: E402
from test_common import NOT_NUMBERS, NUMERIC_OPTIONS, WRITERS  # noqa: E402

from powergraph.cli.main import main  # noqa: E402

#: Every command that reads a model: argv with {m} for the model and {out} for a folder.
MODEL_COMMANDS = {
    "check": ["check", "{m}"], "solve": ["solve", "{m}", "--json"],
    "wang2021": ["solve", "{m}", "--method", "wang2021", "--json"],
    "draw": ["draw", "{m}", "-o", "{out}/flow.svg"], "compare": ["compare", "{m}", "--json"],
    "backlash": ["backlash", "{m}", "--json"], "volume": ["volume", "{m}", "--json"],
    "formula": ["formula", "{m}", "--json"],
    "sweep": ["sweep", "{m}", "--quiet", "--set", "links.*.efficiency=0.9:1:3"],
    "tolerance": ["tolerance", "{m}", "--samples", "64", "--sobol-samples", "0", "--seed", "1",
                  "--json"],
    "map": ["map", "{m}", "--torque", "100:200:2", "--speed", "1000:2000:2", "--json",
            "--loss-map", "{out}/loss.vtlm"],
    "modes": ["modes", "{m}", "--json"], "lever": ["lever", "{m}", "--json"],
    "shifts": ["shifts", "{m}", "--ratios", "2.5,1,-2", "--tolerance", "50%", "--json",
               "-o", "{out}/placed.yaml"],
    "cycle": ["cycle", "{m}", "--points", "{out}/points.csv", "--json"],
}
#: The operating points given to ``cycle``: component 1's speed (most models have one).
POINTS = "1.speed [rpm],duration [s]\n1000,1\n1500,2\n"
LIMIT_VALUES = NOT_NUMBERS + ["0", "-0", "1e308", "-1e308", "1e-300", "10" + "0" * 30, "-5"]
SLOW = 5.0       # seconds: a command over this counts as a hang
ABORT = 120      # seconds: a command still running is stopped (a real hang)


class Hang(BaseException):
    """Raised in a worker by the alarm of a command running over ABORT seconds."""


def _alarm(signum, frame):
    raise Hang()


def run(argv: list[str]) -> tuple[object, str, float, str]:
    """(status, first stderr line, seconds, stdout) of ``main(argv)``; status
    'traceback' or 'hang' when so."""
    out, err = io.StringIO(), io.StringIO()
    start = time.perf_counter()
    signal.alarm(ABORT)
    with redirect_stdout(out), redirect_stderr(err), warnings.catch_warnings():
        warnings.simplefilter("error")
        try:
            status = main(argv)
        except SystemExit as exc:
            status = exc.code
        except Hang:
            status = "hang"
        except BaseException:  # noqa: BLE001 - a crash is what we are counting
            status = "traceback"
            err.write(traceback.format_exc())
        finally:
            signal.alarm(0)
    seconds = time.perf_counter() - start
    text = err.getvalue()
    lines = text.strip().splitlines()
    if "Traceback" in text:
        status, lines = "traceback", lines[-1:]      # the exception, not the header
    elif len(lines) > 1 and status not in ("hang",):
        status = f"{status} (several lines)"
    return status, (lines or [""])[0][:160], seconds, out.getvalue()


def answer(status: object, stdout: str) -> tuple | None:
    """(efficiency, circulating power, speeds, torques) of a successful ``solve --json``;
    speeds and torques sorted, so that renamed ids compare equal."""
    if status != 0:
        return None
    data = json.loads(stdout)
    return (data.get("efficiency"), data.get("circulating_power"),
            *sorted(data.get("speeds", {}).values()), *sorted(data.get("torques", {}).values()))


def same(a: tuple | None, b: tuple | None) -> bool:
    if a is None or b is None:
        return a is b
    return len(a) == len(b) and all(
        (x is None and y is None) or (x is not None and y is not None and
                                      abs(x - y) <= 1e-9 * max(1.0, abs(x), abs(y)))
        for x, y in zip(a, b))


def check_file(task: tuple) -> list[tuple]:
    """Every model command on one file, one numeric limit and one bad output path."""
    path, kind, expect, base, big, seed = task
    rng = random.Random(seed)
    records = []
    with tempfile.TemporaryDirectory() as out:
        Path(out, "points.csv").write_text(POINTS)
        commands = ("check", "solve") if big else MODEL_COMMANDS
        found = {}
        for name in commands:
            argv = [a.format(m=path, out=out) for a in MODEL_COMMANDS[name]]
            status, line, seconds, stdout = run(argv)
            found[name] = (status, stdout)
            records.append((kind, expect, base, name, status, line, seconds, path))
        if not big:
            argv, option = rng.choice(NUMERIC_OPTIONS)
            value = rng.choice(LIMIT_VALUES)
            full = [a.replace("{v}", value).replace("{tmp}", out) for a in argv]
            status, line, seconds, _ = run(full)
            records.append((kind, "any", base, f"{argv[0]} {option}", status, line, seconds,
                            " ".join(full)[:200]))
            argv, option, what = rng.choice(WRITERS)
            bad = rng.choice([f"{out}/missing/dir/x", out])
            bad += {"figure": ".png", "file": ".csv", "model": ".yaml",
                    "folder": ""}[what] if bad != out else ""
            if what == "folder" and bad == out:
                Path(out, "afile").write_text("x")
                bad = f"{out}/afile"
            full = [a.format(missing=path) for a in argv] + [option, bad]
            status, line, seconds, _ = run(full)
            records.append((kind, "exit 2", base, f"{argv[0]} {option}", status, line,
                            seconds, " ".join(full)[:200]))
    if expect == "same":
        got = (answer(*found["solve"]), found["draw"][0] == 0)
        records.append((kind, "same", base, "answer", got, "", 0.0, path))
    return records


def build_files(args, folder: Path, models: dict[str, str]) -> list[tuple]:
    rng = random.Random(args.seed)
    classes = args.classes.split(",") if args.classes else list(CLASSES)
    tasks = []
    for i in range(args.count):
        base = rng.choice(sorted(models))
        kind = classes[i % len(classes)]
        data, expect = mutate(kind, models[base], rng)
        path = folder / f"{i:05d}-{kind}-{base}"
        path.write_bytes(data)
        tasks.append((str(path), kind, expect, base, False, rng.randrange(2**32)))
    for label, data in big_files():
        path = folder / f"{label}.yaml"
        path.write_bytes(data)
        tasks.append((str(path), "large", "any", "", True, 0))
    return tasks


def big_files() -> list[tuple[str, bytes]]:
    """A few large files: 20 MB single lines (over the limit) and 5 MB (under it)."""
    return [("20MB-comment", b"name: t\n# " + b"x" * 20_000_000 + b"\n"),
            ("20MB-name", b"name: " + b"y" * 20_000_000 + b"\n"),
            ("5MB-name", b"name: " + b"z" * 5_000_000 + b"\ncomponents: {}\nlinks: []\n"
                                                          b"ports: []\n"),
            ("5MB-list", b"name: t\nitems: [" + b"1, " * 1_600_000 + b"1]\n")]


def plain_answers(models: dict[str, str]) -> dict[str, tuple]:
    """(solve answer, draw succeeds) of each unmodified model."""
    out = {}
    with tempfile.TemporaryDirectory() as folder:
        for name in models:
            path = str(ROOT / "models" / name)
            status, _, _, stdout = run(["solve", path, "--json"])
            drawn = run(["draw", path, "-o", f"{folder}/x.svg"])[0] == 0
            out[name] = (answer(status, stdout), drawn)
    return out


def report(records: list[tuple], plain: dict, total_files: int) -> None:
    histogram = collections.Counter()
    bad, slow, differ = [], [], collections.defaultdict(list)
    per_class = collections.Counter()
    for kind, expect, base, command, status, line, seconds, where in records:
        if command == "answer":
            per_class[kind] += 1
            if not same(status[0], plain[base][0]) or status[1] != plain[base][1]:
                differ[kind].append(f"{Path(where).name}: {status} vs plain {plain[base]}")
            continue
        histogram[(command, status)] += 1
        if status not in (0, 2) or (expect == "exit 2" and status != 2):
            bad.append(f"[{kind}] {command} {Path(where).name if expect != 'exit 2' else where}"
                       f": {status} {line}")
        if seconds > SLOW:
            slow.append((seconds, f"[{kind}] {command} {Path(where).name}: {line[:80]}"))
    print(f"files: {total_files}; commands run in-process: {sum(histogram.values())}")
    for (command, status), n in sorted(histogram.items(), key=str):
        print(f"  {command:<28} exit {status}: {n}")
    tracebacks = sum(n for (_, s), n in histogram.items() if s == "traceback")
    print(f"tracebacks: {tracebacks}; other statuses than 0/2 (or not 2 for a bad output "
          f"path): {len(bad)}")
    by_kind = collections.Counter(line.split("]")[0][1:] for line in bad)
    for kind, n in sorted(by_kind.items()):
        print(f"  {kind}: {n}, e.g. {next(b for b in bad if b.startswith(f'[{kind}]'))[:230]}")
    print(f"commands over {SLOW:g} s: {len(slow)}")
    for seconds, what in sorted(slow, reverse=True)[:10]:
        print(f"  {seconds:6.1f} s {what}")
    print("answers of mutations that keep the train (efficiency, circulating power, speeds, "
          "torques, draw): "
          f"{sum(per_class.values())} checked, {sum(map(len, differ.values()))} differ")
    for kind in sorted(per_class):
        example = f"; e.g. {differ[kind][0][:200]}" if differ[kind] else ""
        print(f"  {kind}: {len(differ[kind])} of {per_class[kind]} differ{example}")


def subprocess_sample(tasks: list[tuple], rng: random.Random, count: int) -> None:
    exe = shutil.which("powergraph")
    base = [exe] if exe else [sys.executable, "-m", "powergraph.cli.main"]
    sample = rng.sample([t for t in tasks if not t[4]], min(count, len(tasks)))
    statuses, tracebacks = collections.Counter(), 0
    for task in sample:
        proc = subprocess.run(base + ["check", task[0]], capture_output=True, text=True,
                              errors="replace", cwd=ROOT, timeout=60)
        statuses[proc.returncode] += 1
        lines = proc.stderr.strip().splitlines()
        tracebacks += "Traceback" in proc.stderr or len(lines) > 1
    print(f"subprocess sample: {len(sample)} `check` runs, exit statuses {dict(statuses)}, "
          f"tracebacks or several lines: {tracebacks}")


def main_benchmark() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--count", type=int, default=3000, help="mutated files")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    parser.add_argument("--subprocess", type=int, default=30)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--classes", help="comma-separated mutation classes (default all)")
    args = parser.parse_args()
    os.environ.setdefault("MPLBACKEND", "Agg")
    files = sorted((ROOT / "models").glob("*.yaml")) + sorted((ROOT / "models").glob("*/*.yaml"))
    models = {m.name: m.read_text() for m in files}
    start = time.perf_counter()
    plain = plain_answers(models)   # also the one-time imports, before the workers fork
    with tempfile.TemporaryDirectory() as tmp:
        tasks = build_files(args, Path(tmp), models)
        records: list[tuple] = []
        with multiprocessing.get_context("fork").Pool(args.jobs) as pool:
            for done, part in enumerate(pool.imap_unordered(check_file, tasks, chunksize=2)):
                records.extend(part)
                if done and done % 500 == 0:
                    print(f"  ... {done} files, {time.perf_counter() - start:.0f} s",
                          file=sys.stderr, flush=True)
        seconds = time.perf_counter() - start
        report(records, plain, len(tasks))
        subprocess_sample(tasks, random.Random(args.seed), args.subprocess)
    print(f"time: {seconds:.0f} s for {len(tasks)} files on {args.jobs} processes "
          f"({len(tasks) / seconds:.1f} files/s, {len(records) / seconds:.0f} commands/s)")


if __name__ == "__main__":
    main_benchmark()
