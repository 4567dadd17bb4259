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

The table classes (benchmarks/hostile_tables.py) make a folder per case instead: the model,
a duty cycle's points CSV and the machines' efficiency maps, one of them hostile
(``points-*``: units, columns, cells, bytes, odd files, and ``points-same``, edits that
keep the cycle; ``map-*``: values, grid, bytes and files of an efficiency map;
``modes-*``: mode names, tables and shift elements; ``machines``: machine ports and
buses), and run every command that reads that input (:func:`bundle_commands`); a few
large tables (2·10^5 rows, over the size limits) run once.

Reports: the statuses, the tracebacks (promise: none), other exit statuses than 0 and 2
(none), the commands over 5 s (none), and for the mutations that do not change the train
(``same``: ids renamed, merges of equal values, equivalent units, a comment) the answers
that differ from the plain model's (efficiency, circulating power, the speeds and torques,
`draw` succeeding) and for ``points-same`` (BOM, CRLF, quotes, column order, equivalent
units...) the cycles that differ from the plain points file's (energies, efficiency, time,
each row's verdict), per class; then the time taken (``--json``: all of it as one object,
every finding listed, and the commonest error lines of each class).

Usage: python benchmarks/hostile_inputs.py [--count 3000] [--jobs N] [--subprocess 30]
                                           [--seed 1] [--classes a,b,...] [--no-large]
                                           [--json] [--keep DIR] [--abort 120]
       python benchmarks/hostile_inputs.py --make CLASS MODEL SEED [--keep DIR]
(``--make``: write one table case, as the report names it, and print its commands.)
"""
from __future__ import annotations

import argparse
import collections
import io
import json
import multiprocessing
import os
import random
import re
import shutil
import shlex
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

from hostile_mutations import CLASSES, _fast, mutate  # noqa: E402
from hostile_tables import (DIRECTORY, MISSING, TABLE_CLASSES, Bundle,  # noqa: E402
                            eligible, make_bundle, plain_points, to_csv)
from test_common import NAMES, NOT_NUMBERS, NUMERIC_OPTIONS, WRITERS  # noqa: E402

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
            bad += Path(NAMES[what]).suffix if bad != out else ""
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


# --- the table classes: a folder per case, the commands that read its input -----------------
def bundle_commands(bundle: Bundle, rng: random.Random) -> list[tuple[str, list[str]]]:
    """``(label, argv)`` of every command reading the bundle's hostile input (``{m}`` the
    model, ``{p}`` the points, ``{out}`` an output folder); the figures, slow, on a quarter
    of the cases and on every case with odd names."""
    plots = 1.0 if bundle.figures else 0.25
    cycle = ["cycle", "{m}", "--points", "{p}"]
    if bundle.family == "points":
        out = [("cycle", cycle), ("cycle --json", cycle + ["--json"]),
               ("cycle -o", cycle + ["-o", "{out}/rows.csv"])]
        return out + ([("cycle --plot", cycle + ["--plot", "{out}/cycle.png"])]
                      if rng.random() < plots else [])
    fig = rng.choice([".png", ".svg"]) if rng.random() < plots else ".svg"
    out = [("check", ["check", "{m}"]), ("solve", ["solve", "{m}", "--json"]),
           ("map", ["map", "{m}", "--torque", "100:200:2", "--speed", "1000:2000:2", "--json"]),
           ("cycle --json", cycle + ["--json"])]
    if bundle.family != "modes":
        out += [("draw", ["draw", "{m}", "-o", "{out}/flow" + fig])] + (
            [("cycle --plot", cycle + ["--plot", "{out}/cycle.png"])] if fig == ".png" else [])
        out += [("compare", ["compare", "{m}", "--json"]), ("lever", ["lever", "{m}", "--json"])]
        return out + ([("solve text", ["solve", "{m}"]),
                       ("cycle -o", cycle + ["-o", "{out}/rows.csv"])]
                      if bundle.family == "machines" else [])
    first = bundle.modes[0] if bundle.modes else "1"
    out += [(f"solve --mode #{i}", ["solve", "{m}", "--mode", m, "--json"])
            for i, m in enumerate(bundle.modes[:12])]
    out += [("modes", ["modes", "{m}", "--json"]), ("modes text", ["modes", "{m}"]),
            ("lever --mode", ["lever", "{m}", "--mode", first, "--json"]),
            ("lever", ["lever", "{m}", "--json"]),
            ("shifts", ["shifts", "{m}", "--ratios", "2.5,1,-2", "--json"]),
            ("map --mode", ["map", "{m}", "--mode", first, "--torque", "100:200:2",
                            "--speed", "1000:2000:2", "--json"]),
            ("compare", ["compare", f"{{m}}:{first}", "--json"])]
    if rng.random() < plots:
        out += [("modes -o", ["modes", "{m}", "-o", "{out}/gears.png"]),
                ("cycle --plot", cycle + ["--plot", "{out}/cycle.png"]),
                ("lever -o", ["lever", "{m}", "--mode", first, "-o", "{out}/lever.png"]),
                ("draw --mode", ["draw", "{m}", "--mode", first, "-o", "{out}/flow.png"])]
    return out


def write_bundle(bundle: Bundle, folder: Path) -> None:
    for name, data in bundle.files.items():
        if data == DIRECTORY:
            (folder / name).mkdir()
        elif isinstance(data, int):                 # a sparse file of this size
            with open(folder / name, "wb") as handle:
                handle.truncate(data)
        elif data != MISSING:
            (folder / name).write_bytes(data)
    if bundle.plain is not None:
        (folder / "plain.csv").write_bytes(bundle.plain)


def expand(argv: list[str], folder: Path, out: Path, points: str) -> list[str]:
    where = {"{m}": str(folder / "model.yaml"), "{out}": str(out), "{d}": str(folder),
             "{p}": points if points.startswith("/") else f"{folder}/{points}"}
    for key, value in where.items():
        argv = [a.replace(key, value) for a in argv]
    return argv


def cycle_answer(status: object, stdout: str) -> tuple | None:
    """(efficiency, energies in, out and lost, time, each row's verdict) of ``cycle
    --json``."""
    if status != 0:
        return None
    data = json.loads(stdout)
    return (data.get("efficiency"), data.get("energy_in"), data.get("energy_out"),
            data.get("total_energy_lost"), data.get("time"),
            *(row.get("verdict") for row in data.get("rows", [])))


def same_cycle(a: tuple | None, b: tuple | None) -> bool:
    if a is None or b is None or len(a) != len(b):
        return a == b
    return all(x == y if not all(isinstance(v, float) for v in (x, y)) else
               abs(x - y) <= 1e-9 * max(1.0, abs(x), abs(y)) for x, y in zip(a, b))


def check_bundle(task: tuple) -> list[tuple]:
    """Every command reading one table case's hostile input; for ``"same"``, its cycle
    against the plain points file's."""
    _, kind, base, seed, text, keep = task
    rng = random.Random(seed)
    bundle = LARGE[kind][1](text) if kind in LARGE else make_bundle(kind, text, rng)
    argvs = getattr(bundle, "argvs", None) or bundle_commands(bundle, rng)
    records, tag = [], f"{kind} {base} {seed}"
    with tempfile.TemporaryDirectory() as tmp:
        folder, out = Path(tmp, "case"), Path(tmp, "out")
        folder.mkdir(), out.mkdir()
        write_bundle(bundle, folder)
        found, bad = {}, False
        for label, argv in argvs:
            full = expand(argv, folder, out, bundle.points)
            status, line, seconds, stdout = run(full)
            found[label] = (status, stdout)
            shown = " ".join(full).replace(str(folder) + "/", "").replace(str(out) + "/", "")
            records.append((kind, bundle.expect, base, label, status, line, seconds,
                            f"{tag} ({bundle.note}): {shown[:160]}"))
            bad |= status not in (0, 2) or seconds > SLOW
        if bundle.expect == "same":
            plain = run(expand(["cycle", "{m}", "--points", "{p}", "--json"], folder,
                               out, str(folder / "plain.csv")))
            got = cycle_answer(*found["cycle --json"]), cycle_answer(plain[0], plain[3])
            records.append((kind, "same", base, "answer-table", got, "", 0.0,
                            f"{tag} ({bundle.note})"))
            bad |= not same_cycle(*got)
        if bad and keep:
            shutil.copytree(folder, Path(keep, tag.replace(" ", "-")), dirs_exist_ok=True)
    return records


class Large(Bundle):
    """A large case, run once, with its own commands."""

    argvs: list = []


def _large(family: str, files: dict, argvs: list, note: str, points="points.csv") -> Large:
    case = Large(family, files, note=note, points=points)
    case.argvs = argvs
    return case


def _rows(text: str, rows: int, cell: tuple[int, str] | None = None, modes=()) -> bytes:
    """A valid points file of ``rows`` rows, one cell of the last row replaced."""
    table = plain_points(_fast(text), random.Random(0), list(modes), rows)
    if cell:
        table[-1][cell[0]] = cell[1]
    return to_csv(table).encode()


def _map_rows(speeds: int, torques: int, extra: str = "") -> bytes:
    lines = ["speed [rpm],torque [N*m],efficiency"] + [
        f"{s * 20000 / speeds},{t * 500 / torques},0.9" for s in range(speeds)
        for t in range(torques)]
    return ("\n".join(lines) + "\n" + extra).encode()


def _with_map(text: str, name: str) -> bytes:
    data = _fast(text)
    for port in data["ports"]:
        if port.get("role") == "machine":
            port["efficiency"] = {"map": name}
    return json.dumps(data).encode()


CYCLE = ["cycle", "{m}", "--points", "{p}"]
JSON = [("cycle --json", CYCLE + ["--json"])]
#: The large cases, run once each (model, then the case from the model's text): 2·10^5
#: rows (valid, or a bad last cell or mode; 5·10^4 valid ones with --json), 10^5 columns, a 5 MB cell, files over the
#: size limit (a sparse 150 MB file; --max-table-size 1k), maps at and over MAX_ROWS.
LARGE = {
    "points-200k-rows": ("planetary_2kh_sun_to_ring.yaml", lambda t: _large(
        "points", {"model.yaml": t.encode(), "points.csv": _rows(t, 200_000)},
        [("cycle", CYCLE), ("cycle -o", CYCLE + ["-o", "{out}/rows.csv"])],
        "2e5 valid rows (sweep)")),
    # --json prints some 500 bytes a row at about 25 µs a row (the standard library's
    # encoder): 2e5 rows are 100 MB of text and 6-9 s on the development machine, linear
    # in the rows, so the JSON of a large valid cycle is timed on 5e4 rows.
    "points-50k-rows-json": ("planetary_2kh_sun_to_ring.yaml", lambda t: _large(
        "points", {"model.yaml": t.encode(), "points.csv": _rows(t, 50_000)},
        JSON, "5e4 valid rows (sweep), --json")),
    "points-200k-bad-last-cell": ("ths2_power_split.yaml", lambda t: _large(
        "points", {"model.yaml": t.encode(), "points.csv": _rows(t, 200_000, (0, "x"))},
        JSON, "2e5 rows, the last cell 'x'")),
    "points-3k-unknown-mode-last": ("zf8hp_8speed.yaml", lambda t: _large(
        "points", {"model.yaml": t.encode(), "points.csv": _rows(t, 3000, (-1, "9"), "1")},
        JSON, "3000 rows in mode 1, the last in mode 9")),
    "points-100k-columns": ("planetary_2kh_sun_to_ring.yaml", lambda t: _large(
        "points", {"model.yaml": t.encode(),
                   "points.csv": _rows(t, 3).replace(b"\n", b",x" * 100_000 + b"\n", 1)},
        JSON, "1e5 unknown columns")),
    "points-5MB-cell": ("planetary_2kh_sun_to_ring.yaml", lambda t: _large(
        "points", {"model.yaml": t.encode(), "points.csv": _rows(t, 3) + b"1" * 5_000_000},
        JSON, "a 5 MB cell")),
    "tables-over-size-limit": ("ths2_power_split.yaml", lambda t: _large(
        "map", {"model.yaml": _with_map(t, "big.csv"), "points.csv": _rows(t, 3),
                "big.csv": 150_000_000}, JSON + [
            ("check", ["check", "{m}"]),
            ("--max-table-size 1k cycle", ["--max-table-size", "1k", "cycle", "{m}",
                                           "--points", "{d}/points.csv"])],
        "150 MB sparse file as points and map", points="big.csv")),
    "map-250k-rows": ("ths2_power_split.yaml", lambda t: _large(
        "map", {"model.yaml": _with_map(t, "mg.csv"), "mg.csv": _map_rows(500, 500),
                "points.csv": _rows(t, 3)},
        [("check", ["check", "{m}"]), ("solve", ["solve", "{m}", "--json"])] + JSON,
        "500 x 500 map (MAX_ROWS)")),
    "map-over-max-rows": ("ths2_power_split.yaml", lambda t: _large(
        "map", {"model.yaml": _with_map(t, "mg.csv"),
                "mg.csv": _map_rows(500, 500, "20000,600,0.9\n")},
        [("check", ["check", "{m}"])], "250,001 rows")),
}


def build_files(args, folder: Path, models: dict[str, str]) -> list[tuple]:
    """The tasks: a file per model-text class case (written here), a case per table class
    case (made by the worker from its seed, on a model the class applies to) and, with a
    table class, the large cases."""
    rng = random.Random(args.seed)
    classes = args.classes.split(",") if args.classes else list(CLASSES) + list(TABLE_CLASSES)
    unknown = set(classes) - set(CLASSES) - set(TABLE_CLASSES)
    if unknown:
        raise SystemExit(f"unknown classes: {', '.join(sorted(unknown))}")
    parsed = {name: _fast(text) for name, text in models.items()}
    tasks = []
    for i in range(args.count):
        kind = classes[i % len(classes)]
        if kind in TABLE_CLASSES:
            base = rng.choice(sorted(m for m in models if eligible(kind, parsed[m])))
            tasks.append(("bundle", kind, base, rng.randrange(2**32), models[base],
                          args.keep))
            continue
        base = rng.choice(sorted(models))
        data, expect = mutate(kind, models[base], rng)
        path = folder / f"{i:05d}-{kind}-{base}"
        path.write_bytes(data)
        tasks.append((str(path), kind, expect, base, False, rng.randrange(2**32)))
    for label, data in big_files():
        path = folder / f"{label}.yaml"
        path.write_bytes(data)
        tasks.append((str(path), "large", "any", "", True, 0))
    if not args.no_large and any(kind in TABLE_CLASSES for kind in classes):
        tasks += [("bundle", label, base, 0, models[base], args.keep)
                  for label, (base, _) in LARGE.items()]
    return tasks


def check_task(task: tuple) -> list[tuple]:
    return check_bundle(task) if task[0] == "bundle" else check_file(task)


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


def _shown(where: str, expect: str) -> str:
    """A file as the report names it: a model file by its name, a table case as tagged."""
    return Path(where).name if where.startswith("/") and expect != "exit 2" else where


def summarise(records: list[tuple], plain: dict, total_files: int) -> dict:
    """Statuses per command and per class, the bad statuses, the slow commands and the
    answers that differ, as one dict (``--json`` prints it)."""
    histogram, per_class = collections.Counter(), collections.defaultdict(collections.Counter)
    bad, slow, differ = [], [], collections.defaultdict(list)
    errors = collections.defaultdict(collections.Counter)
    checked = collections.Counter()
    for kind, expect, base, command, status, line, seconds, where in records:
        if command in ("answer", "answer-table"):
            checked[kind] += 1
            if command == "answer-table" and not same_cycle(*status):
                differ[kind].append(f"{where}: cycle {status[0]} vs plain points {status[1]}")
            elif command == "answer" and (not same(status[0], plain[base][0])
                                          or status[1] != plain[base][1]):
                differ[kind].append(f"{Path(where).name}: {status} vs plain {plain[base]}")
            continue
        histogram[(command, status)] += 1
        per_class[kind][str(status)] += 1
        errors[kind][re.sub(r"/tmp/\S*/", "", line)[19:79]] += status == 2
        shown = _shown(where, expect)
        if status not in (0, 2) or (expect == "exit 2" and status != 2):
            bad.append({"class": kind, "command": command, "status": str(status),
                        "line": line, "where": shown})
        if seconds > SLOW:
            slow.append({"seconds": round(seconds, 2), "class": kind, "command": command,
                         "status": str(status), "line": line[:120], "where": shown})
    return {"files": total_files, "commands": sum(histogram.values()),
            "statuses": {f"{c} | exit {s}": n for (c, s), n in sorted(histogram.items(),
                                                                         key=str)},
            "per_class": {k: dict(v) for k, v in sorted(per_class.items())},
            "tracebacks": sum(n for (_, s), n in histogram.items() if s == "traceback"),
            "bad": bad, "slow": sorted(slow, key=lambda x: -x["seconds"]),
            "answers_checked": dict(checked), "answers_differ": dict(differ),
            "errors_per_class": {k: dict(v.most_common(12)) for k, v in errors.items()}}


def report(summary: dict) -> None:
    print(f"files: {summary['files']}; commands run in-process: {summary['commands']}")
    for what, n in summary["statuses"].items():
        command, status = what.split(" | ")
        print(f"  {command:<28} {status}: {n}")
    print("per class (exit statuses of its commands):")
    for kind, statuses in summary["per_class"].items():
        print(f"  {kind:<22} " + ", ".join(f"{s}: {n}" for s, n in sorted(statuses.items())))
    bad = summary["bad"]
    print(f"tracebacks: {summary['tracebacks']}; other statuses than 0/2 (or not 2 for a bad "
          f"output path): {len(bad)}")
    for kind, n in sorted(collections.Counter(b["class"] for b in bad).items()):
        b = next(b for b in bad if b["class"] == kind)
        print(f"  {kind}: {n}, e.g. {b['command']} {b['where'][:150]}: {b['status']} "
              f"{b['line'][:160]}")
    print(f"commands over {SLOW:g} s: {len(summary['slow'])}")
    for x in summary["slow"][:10]:
        print(f"  {x['seconds']:6.1f} s [{x['class']}] {x['command']} {x['where'][:110]}: "
              f"{x['line'][:80]}")
    differ, checked = summary["answers_differ"], summary["answers_checked"]
    print("answers of mutations that keep the train (efficiency, circulating power, speeds, "
          "torques, draw; a cycle's energies and verdicts): "
          f"{sum(checked.values())} checked, {sum(map(len, differ.values()))} differ")
    for kind in sorted(checked):
        example = f"; e.g. {differ[kind][0][:200]}" if differ.get(kind) else ""
        print(f"  {kind}: {len(differ.get(kind, []))} of {checked[kind]} differ{example}")
    if bad or summary["slow"] or differ:
        print("a table case again: python benchmarks/hostile_inputs.py --make CLASS MODEL "
              "SEED (the three words the report gives before the note in brackets)")


def subprocess_sample(tasks: list[tuple], rng: random.Random, count: int) -> None:
    """``check`` on a sample of the model files and the first command of a sample of the
    table cases, through real processes."""
    exe = shutil.which("powergraph")
    base = [exe] if exe else [sys.executable, "-m", "powergraph.cli.main"]
    files = [t for t in tasks if t[0] != "bundle" and not t[4]]
    cases = [t for t in tasks if t[0] == "bundle" and t[1] in TABLE_CLASSES]
    sample = rng.sample(files, min(count - count // 2 if cases else count, len(files)))
    sample += rng.sample(cases, min(count // 2, len(cases)))
    statuses, tracebacks = collections.Counter(), 0
    with tempfile.TemporaryDirectory() as tmp:
        for n, task in enumerate(sample):
            argv = ["check", task[0]]
            if task[0] == "bundle":
                case_rng = random.Random(task[3])
                bundle = make_bundle(task[1], task[4], case_rng)
                folder = Path(tmp, str(n))
                folder.mkdir()
                write_bundle(bundle, folder)
                argv = expand(bundle_commands(bundle, case_rng)[0][1], folder, folder,
                              bundle.points)
            proc = subprocess.run(base + argv, capture_output=True, text=True,
                                  errors="replace", cwd=ROOT, timeout=60)
            statuses[proc.returncode] += 1
            lines = proc.stderr.strip().splitlines()
            tracebacks += "Traceback" in proc.stderr or len(lines) > 1
    print(f"subprocess sample: {len(sample)} runs (`check` of model files, the first command "
          f"of table cases), exit statuses {dict(statuses)}, tracebacks or several lines: "
          f"{tracebacks}")


def make_one(args) -> None:
    """``--make CLASS MODEL SEED``: write one table case and print its commands."""
    kind, model, seed = args.make
    folder = Path(args.keep or f"hostile-{kind}-{seed}")
    folder.mkdir(parents=True, exist_ok=True)
    if kind in LARGE:
        bundle = LARGE[kind][1]((ROOT / "models" / LARGE[kind][0]).read_text())
        argvs = bundle.argvs
    else:
        rng = random.Random(int(seed))
        bundle = make_bundle(kind, (ROOT / "models" / model).read_text(), rng)
        argvs = bundle_commands(bundle, rng)
    write_bundle(bundle, folder)
    lines = [f"# {kind} {model} {seed}: {bundle.note}; expect {bundle.expect}; in {folder}"]
    lines += ["powergraph " + " ".join(shlex.quote(a) for a in expand(argv, folder, folder,
                                                                     bundle.points))
              for _, argv in argvs]
    try:
        print("\n".join(lines))
    except BrokenPipeError:      # | head
        pass


def main_benchmark() -> None:
    global ABORT
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--count", type=int, default=3000, help="mutated files")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    parser.add_argument("--subprocess", type=int, default=30)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--classes", help="comma-separated mutation classes (default all: "
                        + ", ".join(list(CLASSES) + list(TABLE_CLASSES)) + ")")
    parser.add_argument("--no-large", action="store_true",
                        help="leave out the large tables (run once with a table class)")
    parser.add_argument("--json", action="store_true", help="print the summary as JSON")
    parser.add_argument("--keep", metavar="DIR",
                        help="copy each table case with a finding here (with --make: the "
                             "folder to write)")
    parser.add_argument("--abort", type=int, default=ABORT,
                        help=f"seconds after which a command is stopped (default {ABORT})")
    parser.add_argument("--make", nargs=3, metavar=("CLASS", "MODEL", "SEED"),
                        help="write one table case (as the report names it) and print its "
                             "commands")
    args = parser.parse_args()
    ABORT = args.abort
    os.environ.setdefault("MPLBACKEND", "Agg")
    if args.make:
        return make_one(args)
    files = sorted((ROOT / "models").glob("*.yaml")) + sorted((ROOT / "models").glob("*/*.yaml"))
    models = {m.name: m.read_text() for m in files}
    start = time.perf_counter()
    plain = plain_answers(models)   # also the one-time imports, before the workers fork
    with tempfile.TemporaryDirectory() as tmp:
        tasks = build_files(args, Path(tmp), models)
        records: list[tuple] = []
        with multiprocessing.get_context("fork").Pool(args.jobs) as pool:
            for done, part in enumerate(pool.imap_unordered(check_task, tasks, chunksize=2)):
                records.extend(part)
                if done and done % 500 == 0:
                    print(f"  ... {done} files, {time.perf_counter() - start:.0f} s",
                          file=sys.stderr, flush=True)
        seconds = time.perf_counter() - start
        summary = summarise(records, plain, len(tasks))
        summary["seconds"] = round(seconds, 1)
        if args.json:
            print(json.dumps(summary, indent=1, default=str))
        else:
            report(summary)
            subprocess_sample(tasks, random.Random(args.seed), args.subprocess)
    if not args.json:
        print(f"time: {seconds:.0f} s for {len(tasks)} files on {args.jobs} processes "
              f"({len(tasks) / seconds:.1f} files/s, {len(records) / seconds:.0f} "
              "commands/s)")


if __name__ == "__main__":
    main_benchmark()
