"""Hostile tables, modes and machines: the file sets of benchmarks/hostile_inputs.py and
tests/cli/test_hostile.py beside the model-text classes of hostile_mutations.py.

A class makes a :class:`Bundle` from a library model: the model file and the tables it
names. ``points-*`` mutate a duty cycle's points CSV made valid for the model from its
ports (its speeds and loads as columns, durations or times, a mode column with modes);
``map-*`` an efficiency map made valid for each machine; ``modes-*`` and ``machines`` the
model's modes table, shift elements or machine ports (hostile_mutations.py). Expected:
``"any"`` (exit 0 or 2, one line, no traceback, no hang) or ``"same"`` (the cycle's
answer equals the plain points file's). ``TABLE_CLASSES`` lists them with their family
(which commands read them: hostile_inputs.bundle_commands); ``make_bundle(name, text,
rng)`` makes one.
"""
from __future__ import annotations

import csv
import io
import math
import random
import re
from dataclasses import dataclass, field
from typing import Any, Callable

import yaml

from hostile_mutations import (HOSTILE_UNITS, _fast, _fast_dump, machine_ports, mode_names,
                               mode_tables, shift_elements, typed_name)

#: A file that is not a regular file of the bundle: a directory, a missing name, a device.
DIRECTORY, MISSING = "@dir", "@missing"
UNITS = ["rmp", "kW", "KW", "N*m", "", " ", "rpm rpm", "1e400 rpm", "rpm/0", "1/0", "°/s",
         "%", "rpm]", "r\u200bpm", "RPM", "Hz", "1/min", "rad/s", "0 rpm", "-1 rpm", "nan rpm",
         "2 rpm", "kw", "hp", "MW", "N·m", "kN*m", "W/rpm", "m"]
UNITS += [u.split(" ", 1)[1] for u in HOSTILE_UNITS if " " in u and len(u) < 9000]
TIME_UNITS = ["ms", "", "min", "h", "d", "s s", "S", "sec", "1e400 s", "-1 s", "years", "s]"]
CELLS = ["abc", "1,5", "1.2.3", "--1", "0x10", "1e", "true", "None", "١٠٠٠", "1_000", "½", "∞",
         "1e400", "-1e400", "nan", "NaN", "inf", "-inf", "Infinity", "1e308", "-1e308",
         "1e-320", "9" * 400, "0", "-0", "1000 rpm", "$x$", "=1+1", "1e-300", "", "   ", "+5"]
COLUMNS = ["foo", "engine.rpm", "nobody.speed [rpm]", ".speed", "speed", "1.speed [rpm]",
           "Duration [s]", "duration[s]x", "Mode", "", " ", "x" * 100_000, "mode2", "time",
           "PORT.speed [rpm]", "0.speed", "frame.speed [rpm]", "$x$.speed"]


@dataclass
class Bundle:
    """One hostile case of a ``family``: files (name -> bytes, DIRECTORY or MISSING), the
    points file (a name here or an absolute path), the modes as typed, whether figures
    must be drawn (odd names), and for ``"same"`` the plain points file."""

    family: str
    files: dict[str, Any]
    modes: list[str] = field(default_factory=list)
    figures: bool = False
    expect: str = "any"
    note: str = ""
    points: str = "points.csv"
    plain: bytes | None = None


# --- a valid points file from the model's ports ---------------------------------------------
def _number(value: Any) -> tuple[float, str] | None:
    m = re.fullmatch(r"\s*([-+0-9.eE]+)\s*(.*?)\s*", str(value))
    try:
        number = float(m[1]) if m else math.nan
    except ValueError:
        return None
    return (number, m[2]) if math.isfinite(number) and number != 0 else None


def port_columns(data: Any, rng: random.Random) -> list[tuple[str, float]]:
    """``(header, value)`` of every load and speed the model's ports give, each port named
    by its name or its component id."""
    out = []
    ports = data.get("ports") if isinstance(data, dict) else None
    for port in ports if isinstance(ports, list) else []:
        if not isinstance(port, dict) or "component" not in port:
            continue
        label = port.get("name") if port.get("name") and rng.random() < 0.7 \
            else port["component"]
        for kind in ("speed", "power", "torque"):
            given = _number(port.get(kind, ""))
            if given:
                out.append((f"{label}.{kind}" + (f" [{given[1]}]" if given[1] else ""),
                            given[0]))
    return out


def plain_points(data: Any, rng: random.Random, modes: list[str],
                 rows: int | None = None) -> list[list[str]]:
    """Header and rows of a valid duty cycle: each value 0.6 to 1.2 times the model's,
    durations or time instants, and the modes in turn (with modes)."""
    columns = port_columns(data, rng)
    timed = rng.choice(["duration [s]", "time [s]", None])
    header = [h for h, _ in columns] + ([timed] if timed else []) + (["mode"] if modes else [])
    body = []
    for i in range(rows or rng.randint(2, 8)):
        row = [repr(round(v * rng.uniform(0.6, 1.2), 6)) for _, v in columns]
        row += [repr(rng.choice([0.5, 1.0, 2.0]) if timed == "duration [s]" else 1.5 * i)
                ] if timed else []
        body.append(row + ([modes[i % len(modes)]] if modes else []))
    return [header] + body


def to_csv(table: list[list[str]], **options: Any) -> str:
    handle = io.StringIO()
    csv.writer(handle, lineterminator="\n", **options).writerows(table)
    return handle.getvalue()


# --- points classes: (table, rng) -> (file bytes / DIRECTORY / path, note) ------------------
def _column(table: list, rng: random.Random, kinds: tuple = ("speed", "power", "torque")):
    found = [j for j, h in enumerate(table[0]) if any(f".{k}" in h for k in kinds)]
    return rng.choice(found) if found else 0


def _retitle(table: list, j: int, unit: str) -> None:
    table[0][j] = re.sub(r"\s*\[.*\]$", "", table[0][j]) + f" [{unit}]"


def points_units(table: list, rng: random.Random, data: Any = None):
    timed = [j for j, h in enumerate(table[0]) if h in ("time [s]", "duration [s]")]
    if timed and rng.random() < 0.3:
        j, unit = timed[0], rng.choice(TIME_UNITS)
    else:
        j, unit = _column(table, rng), rng.choice(UNITS)
    _retitle(table, j, unit)
    return to_csv(table).encode(), f"[{unit[:20]}]"


def points_columns(table: list, rng: random.Random, data: Any = None):
    how = rng.choice(["unknown", "twice", "twice-other", "power+torque", "two-durations",
                      "time+duration", "two-modes", "header-only", "by-id-and-name",
                      "no-ports", "mode-column", "many", "every-port", "every-port"])
    j = _column(table, rng)
    if how == "every-port":      # a speed, torque or power on every port (of the only ones)
        keep = [k for k, h in enumerate(table[0]) if "." not in h]
        table = [[row[k] for k in keep if k < len(row)] for row in table]
        for port in (data or {}).get("ports") or []:
            kind, unit, value = rng.choice([("speed", "rpm", 1500), ("torque", "N*m", -80),
                                            ("power", "kW", 5), ("speed", "rpm", -700)])
            table[0].append(f"{port.get('name') or port.get('component')}.{kind} [{unit}]")
            for row in table[1:]:
                row.append(f"{value * rng.uniform(0.5, 1.5):.4f}")
    extra: list[tuple[str, Any]] = {
        "unknown": [(rng.choice(COLUMNS), "1")],
        "twice": [(table[0][j], None)], "twice-other": [(table[0][j], "7")],
        "power+torque": [(table[0][j].split(".")[0] + ".torque [N*m]", "100"),
                         (table[0][j].split(".")[0] + ".power [kW]", "10")],
        "two-durations": [("duration [s]", "1"), ("duration [min]", "2")],
        "time+duration": [("time [s]", None), ("duration [s]", "1")],
        "two-modes": [("mode", "1"), ("mode", "R")],
        "by-id-and-name": [(re.sub(r"^[^.]*", lambda _: rng.choice(["0", "1", "S", "C", "in",
                                                                     "frame"]), table[0][j]),
                            None)],
        "mode-column": [("mode", "1")],
        "many": [(table[0][j], None)] * rng.choice([100, 2000])}.get(how, [])
    for name, value in extra:
        table[0].append(name)
        for i, row in enumerate(table[1:]):
            row.append(str(i * 2.0) if name[:4] == "time" else row[j] if value is None
                       else str(value))
    if how == "header-only":
        table[1:] = []
    elif how == "no-ports":
        table = [[c for c, h in zip(row, table[0]) if "." not in h] for row in table]
    return to_csv(table).encode(), how


def points_cells(table: list, rng: random.Random, data: Any = None):
    how = rng.choice(["extra", "missing", "junk", "junk", "junk-time", "negative",
                      "zero-durations", "1e308-durations", "decreasing", "equal-times",
                      "one-row-time", "mode"])
    head, body = table[0], table[1:]
    r = rng.randrange(len(body))
    times = [j for j, h in enumerate(head) if h.startswith(("time", "duration"))]
    timed = times[0] if times else None
    if how == "extra":
        body[r] += ["1"] * rng.choice([1, 2, 50])
    elif how == "missing":
        del body[r][rng.randrange(len(body[r])):]
    elif how == "junk" or (timed is None and how != "mode"):
        how, body[r][_column(table, rng)] = "junk", rng.choice(CELLS)
    elif how == "junk-time":
        body[r][timed] = rng.choice(CELLS)
    elif how in ("negative", "zero-durations", "1e308-durations"):
        head[timed] = "duration [s]"
        for i, row in enumerate(body):
            row[timed] = {"negative": "-1" if i == r else "1", "zero-durations": "0",
                          "1e308-durations": "1e308"}[how]
    elif how in ("decreasing", "equal-times", "one-row-time"):
        head[timed] = "time [s]"
        for i, row in enumerate(body):
            row[timed] = str({"decreasing": -i, "equal-times": 0}.get(how, i))
        body[1:] = body[1:] if how != "one-row-time" else []
    else:
        if "mode" not in head:
            head.append("mode")
            for row in body:
                row.append("1")
        body[r][head.index("mode")] = rng.choice(["9", "", "R ", "$x$", "1.0", "r", "none",
                                                  "x" * 1000, "on", "True", "\t"])
    return to_csv(table).encode(), how


def points_bytes(table: list, rng: random.Random, data: Any = None):
    text = to_csv(table)
    at = rng.randrange(len(text))
    how = rng.choice(["latin-1", "bom-twice", "bom-inside", "utf-16", "nul", "control",
                      "cr", "long-cell", "long-line", "quoted", "unterminated", "bad-utf8"])
    if how == "latin-1":
        return (text[:at] + rng.choice("éµ°·ß") + text[at:]).encode("latin-1"), how
    if how == "utf-16":
        return text.encode(rng.choice(["utf-16", "utf-16-le"])), how
    if how == "bad-utf8":
        return text[:at].encode() + rng.choice([b"\xff", b"\xc3", b"\xed\xa0\x80"]) + \
            text[at:].encode(), how
    text = {
        "bom-twice": "\ufeff\ufeff" + text, "bom-inside": text[:at] + "\ufeff" + text[at:],
        "nul": text[:at] + "\x00" + text[at:],
        "control": text[:at] + rng.choice("\x1a\x0c\x1b\x85\u2028\x7f\r") + text[at:],
        "cr": text.replace("\n", "\r"),
        "long-cell": text.rstrip("\n") + "x" * rng.choice([10_000, 200_000]) + "\n",
        "long-line": text + "," * rng.choice([100_000, 1_000_000]) + "\n",
        "unterminated": text[:at] + '"' + text[at:] + "1" * rng.choice([10, 200_000]),
    }.get(how, text)
    if how == "quoted":
        cell = rng.choice(['"1,000"', '"10\n00"', '"1\n"', '""', '"a""b"', '"1" 2', ' "1"'])
        body = text.split("\n")
        i = rng.randrange(1, max(2, len(body) - 1))
        cells = body[i].split(",")
        cells[rng.randrange(len(cells))] = cell
        body[i] = ",".join(cells)
        text = "\n".join(body)
    return text.encode("utf-8", "surrogatepass"), how


def points_files(table: list, rng: random.Random, data: Any = None):
    how = rng.choice(["/dev/zero", "/dev/null", DIRECTORY, MISSING, "empty", "newlines",
                      "blank-cells", "header-only-bom", "dir/", "long-name"])
    return {"empty": b"", "newlines": b"\n\r\n\n", "blank-cells": b" , ,\n,,\n",
            "header-only-bom": b"\xef\xbb\xbf" + to_csv(table[:1]).encode()}.get(how, how), how


def points_same(table: list, rng: random.Random, data: Any = None):
    """Edits that keep the cycle: BOM, CRLF, blank lines, spaces, quotes, column order,
    equivalent units, no final newline."""
    how = rng.choice(["bom", "crlf", "blank-lines", "spaces", "quoted", "order", "units",
                      "no-newline", "exponent"])
    if how == "order":
        order = rng.sample(range(len(table[0])), len(table[0]))
        table = [[row[j] for j in order] for row in table]
    elif how == "units":
        for j, name in enumerate(table[0]):
            unit = {"rpm": ("rad/s", math.pi / 30), "kW": ("W", 1e3), "W": ("kW", 1e-3),
                    "N*m": ("N·m", 1.0), "s": ("min", 1 / 60)}.get(
                (re.search(r"\[(.*)\]$", name) or [None, None])[1])
            if unit:
                _retitle(table, j, unit[0])
                for row in table[1:]:
                    row[j] = repr(float(row[j]) * unit[1])
    elif how in ("spaces", "exponent"):
        modes = [name.strip() == "mode" for name in table[0]]   # a mode is a name, not a number
        table = [table[0]] + [[f" {c} " if how == "spaces" else c if mode else _exponent(c)
                               for c, mode in zip(row, modes)] for row in table[1:]]
    text = to_csv(table, quoting=csv.QUOTE_ALL) if how == "quoted" else to_csv(table)
    text = {"bom": "\ufeff" + text, "crlf": text.replace("\n", "\r\n"),
            "blank-lines": text.replace("\n", "\n\n", 2) + "\n, ,\n",
            "no-newline": text.rstrip("\n")}.get(how, text)
    return text.encode(), how


def _exponent(cell: str) -> str:
    try:
        return f"{float(cell):e}" if float(cell) == float(f"{float(cell):e}") else cell
    except ValueError:
        return cell


# --- efficiency maps ------------------------------------------------------------------------
MAP_HEADER = ["speed [rpm]", "torque [N·m]", "efficiency"]


def plain_map(rng: random.Random) -> list[list[str]]:
    """A full grid over 0..15,000 rpm and 0..400 N·m (the THS's points lie inside)."""
    speeds = [0, 1000, 3000, 6000, 10000, 15000][:rng.randint(2, 6)] + [15000]
    torques = sorted({0, 400, *rng.sample([25, 50, 100, 200, 300], rng.randint(0, 4))})
    rows = [[str(s), str(t), f"{0.8 + 0.15 * s / 15000 + 0.02 * t / 400:.4f}"]
            for s in sorted(set(speeds)) for t in torques]
    rng.shuffle(rows)
    header = list(MAP_HEADER)
    header[1] = rng.choice(["torque [N·m]", "torque [Nm]", "torque [N*m]"])
    return [header] + rows


def map_values(table: list, rng: random.Random):
    r, how = rng.randrange(1, len(table)), rng.choice(["efficiency", "efficiency", "speed",
                                                       "torque", "all-tiny", "all-1e-6",
                                                       "all-one"])
    if how.startswith("all"):
        for row in table[1:]:
            row[2] = {"all-tiny": "1e-300", "all-1e-6": "1e-6", "all-one": "1"}[how]
    else:
        table[r][["speed", "torque", "efficiency"].index(how)] = rng.choice(
            ["0", "1e-300", "1.5", "1.0000001", "nan", "inf", "-0.5", "", "abc", "90%",
             " 0.9 ", "1e-320", "-1", "-0", "1e308", "-1e308", "9" * 70])
    return to_csv(table).encode(), how


def map_grid(table: list, rng: random.Random):
    how = rng.choice(["missing", "twice", "twice-other", "one-speed", "one-row",
                      "header-only", "extra-column", "short-column", "header", "no-header",
                      "torque-first", "off-grid", "tiny-steps", "huge-span", "fine"])
    r = rng.randrange(1, len(table))
    if how in ("missing", "twice", "twice-other"):
        table[r:r + 1] = {"missing": [], "twice": [table[r]] * 2,
                          "twice-other": [table[r], table[r][:2] + ["0.5"]]}[how]
    elif how in ("one-speed", "one-row", "header-only"):
        keep = {"one-speed": [row for row in table[1:] if row[0] == table[r][0]],
                "one-row": [table[r]], "header-only": []}[how]
        table = table[:1] + keep
    elif how in ("extra-column", "short-column", "torque-first"):
        table = [(row + ["1"] if how == "extra-column" else row[:2] if how == "short-column"
                  else [row[1], row[0], row[2]]) for row in table]
    elif how == "header":
        table[0][rng.randrange(3)] = rng.choice(["speed [rmp]", "speed", "torque [kN*m]",
                                                 "eta", "Speed [RPM]", "speed [rad/s]", "",
                                                 "efficiency [%]", "speed [rpm]"])
    elif how == "no-header":
        table = table[1:]
    else:
        factor = {"off-grid": None, "tiny-steps": 1e-300, "huge-span": 1e300 / 15000}
        if how == "fine":
            table = [MAP_HEADER] + [[str(s * 50), str(t * 4), "0.9"] for s in range(60)
                                    for t in range(60)]
        elif how == "off-grid":
            table[r][0] = str(float(table[r][0]) + 0.001)
        else:
            for row in table[1:]:
                row[0] = repr(float(row[0]) * factor[how])
    return to_csv(table).encode(), how


def map_files(table: list, rng: random.Random):
    text = to_csv(table)
    how = rng.choice(["latin-1", "bom", "nul", "long-cell", "utf-16", "/dev/zero", DIRECTORY,
                      MISSING, "empty", "crlf", "key"])
    if how == "latin-1":
        return text.encode("latin-1", "replace"), how
    if how == "key":
        return rng.choice([5, None, "", "a\x00b.csv", ".", "../missing.csv", "/", [],
                           {"a": 1}, "mg.csv\n", "x" * 5000]), "map: junk"
    return {"bom": ("\ufeff" + text).encode(), "nul": text.replace("0", "\x00", 1).encode(),
            "long-cell": (text + "1," * 10 + "9" * 200_000).encode(),
            "utf-16": text.encode("utf-16"), "empty": b"",
            "crlf": text.replace("\n", "\r\n").encode()}.get(how, how), how


# --- bundles --------------------------------------------------------------------------------
def _modes_of(text: str) -> list[str]:
    """The mode names of a model written by hostile_mutations._with_modes (or a library
    model), as typed on the command line."""
    block = text.split("\nmodes:", 1)[1] if "\nmodes:" in text else ""
    keys = []
    for line in block.split("\n")[1:]:
        if line.strip() and not line.startswith((" ", "#")):
            break
        if line.startswith("  ") and not line.startswith("   ") and ": " in line:
            keys.append(line[2:].split(": ", 1)[0])
    return [str(_fast(k)) if k[:1] in ("'", '"') else typed_name(k) for k in keys]


def _safe(text: str, fallback: str) -> Any:
    try:
        return _fast(text)
    except yaml.YAMLError:
        return _fast(fallback)


TABLE_CLASSES: dict[str, tuple[str, Callable]] = {
    "points-units": ("points", points_units), "points-columns": ("points", points_columns),
    "points-cells": ("points", points_cells), "points-bytes": ("points", points_bytes),
    "points-files": ("points", points_files), "points-same": ("points", points_same),
    "map-values": ("map", map_values), "map-grid": ("map", map_grid),
    "map-files": ("map", map_files), "modes-names": ("modes", mode_names),
    "modes-tables": ("modes", mode_tables), "modes-elements": ("modes", shift_elements),
    "machines": ("machines", machine_ports),
}


def eligible(name: str, data: Any) -> bool:
    """Whether class ``name`` applies to a model (its parsed YAML)."""
    family = TABLE_CLASSES[name][0]
    ports = data.get("ports") or []
    if family in ("map", "machines"):
        return any(isinstance(p, dict) and p.get("role") == "machine" for p in ports)
    return bool(data.get("modes")) if family == "modes" else bool(ports)


def make_bundle(name: str, text: str, rng: random.Random) -> Bundle:
    """Class ``name`` applied to the library model ``text``."""
    family, mutation = TABLE_CLASSES[name]
    files: dict[str, Any] = {}
    note, expect, plain = "", "any", None
    if family in ("modes", "machines"):
        text, note = mutation(text, rng)
    data = _safe(text, text if family == "points" else "{}") or {}
    modes = _modes_of(text) if isinstance(data, dict) and data.get("modes") else []
    figures = any(c in "".join(map(str, modes)) for c in "$\\") or \
        (family == "machines" and note == "odd-name")
    if family == "map":
        machines = [p for p in data["ports"] if p.get("role") == "machine"]
        chosen = rng.sample(machines, rng.randint(1, len(machines)))
        target = rng.choice(chosen)
        for i, port in enumerate(chosen):
            port["efficiency"] = {"map": f"mg{i}.csv"}
            table = plain_map(rng)
            files[f"mg{i}.csv"] = to_csv(table).encode()
            if port is target:
                content, note = mutation(table, rng)
                if note == "map: junk" or content == "/dev/zero":
                    port["efficiency"] = {"map": content}
                else:
                    files[f"mg{i}.csv"] = content
        text = _fast_dump(data)
    points = "points.csv"
    table = plain_points(data, rng, modes)
    files["points.csv"] = to_csv(table).encode()
    if family == "points":
        content, note = mutation(table, rng, data)
        if name == "points-same":
            expect, plain = "same", files["points.csv"]
        if isinstance(content, bytes) or content in (DIRECTORY, MISSING):
            files["points.csv"] = content
        elif content.startswith("/"):
            points = content
        else:
            points = {"dir/": "points.csv/", "long-name": "p" * 300 + ".csv"}[content]
    files["model.yaml"] = text.encode("utf-8", "surrogatepass")
    return Bundle(family, files, modes, figures, expect, note, points, plain)
