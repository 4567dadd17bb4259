"""Operating points of a duty cycle read from CSV (docs/hybrid.md, ``powergraph cycle``).

One row per operating point. Columns ``PORT.speed``, ``PORT.power`` or ``PORT.torque``
(PORT a port's ``name`` or its component id) with the unit in brackets
(``engine.speed [rpm]``; without one, SI), optional ``duration [s]`` or ``time [s]``
(sample instants: each row lasts until the next, the last as long as the one before) and
an optional ``mode``.

Examples
--------
>>> import io
>>> from powergraph.model import load_model
>>> m = load_model("models/planetary_2kh_carrier_to_ring.yaml")
>>> pts = read_points(io.StringIO("carrier.speed [rpm],carrier.power [kW],duration [s]\\n"
...                               "1000,1,2\\n2000,2,3\\n"), m)
>>> pts.columns[0], pts.values[0].tolist(), pts.durations.tolist()
(('ports.0.speed', 0, 'speed'), [104.71975511965977, 209.43951023931953], [2.0, 3.0])
"""
from __future__ import annotations

import csv
import io
import re
from typing import IO, Any

import numpy as np

from powergraph.errors import ModelError, UsageError
from powergraph.model.spec import Model
from powergraph.model.units import parse_quantity
from powergraph.records import record

_HEADER = re.compile(r"^\s*(?P<port>.+?)\.(?P<what>speed|power|torque)\s*"
                     r"(\[(?P<unit>[^\]]*)\])?\s*$")
_TIME = re.compile(r"^\s*(?P<what>duration|time)\s*(\[(?P<unit>[^\]]*)\])?\s*$")


@record
class Points:
    """The operating points: ``columns`` ``(PATH, port index, kind)`` with their SI
    ``values`` (one array per column), each row's duration (s) and mode (or None)."""

    columns: tuple[tuple[str, int, str], ...]
    values: tuple[np.ndarray, ...]
    durations: np.ndarray
    modes: tuple[str | None, ...]
    source: str

    def __len__(self) -> int:
        return len(self.durations)


def read_points(handle: IO[str] | str, model: Model, source: str = "points") -> Points:
    """Read the operating points of ``model`` from a CSV file or handle; every cell is
    checked (``FILE: row 3, engine.speed [rpm]: ...``)."""
    if isinstance(handle, str):
        source = handle
        try:
            with open(handle, newline="", encoding="utf-8") as f:
                text = f.read()
        except OSError as error:
            raise UsageError(f"{handle}: cannot read the points ({error.strerror})") from None
        handle = io.StringIO(text)
    rows = [row for row in csv.reader(handle) if any(cell.strip() for cell in row)]
    if len(rows) < 2:
        raise UsageError(f"{source}: needs a header and at least one row")
    header, body = rows[0], rows[1:]
    ports = _port_index(model)
    columns, values, time_col, mode_col = [], [], None, None
    for j, name in enumerate(header):
        if name.strip() == "mode":
            mode_col = j
            continue
        timed = _TIME.match(name)
        if timed:
            time_col = (j, timed["what"], timed["unit"])
            continue
        m = _HEADER.match(name)
        if not m or m["port"].strip() not in ports:
            raise UsageError(f"{source}: column {name!r}: expected PORT.speed, PORT.power "
                             f"or PORT.torque with PORT one of {', '.join(sorted(ports))}, "
                             "duration [s], time [s] or mode")
        index = ports[m["port"].strip()]
        columns.append((f"ports.{index}.{m['what']}", index, m["what"]))
        values.append(_column(body, j, name, m["what"], m["unit"], source))
    durations = _durations(body, time_col, header, source)
    modes = tuple(row[mode_col].strip() if mode_col is not None and mode_col < len(row)
                  else None for row in body)
    return Points(columns=tuple(columns), values=tuple(values), durations=durations,
                  modes=modes, source=source)


def _port_index(model: Model) -> dict[str, int]:
    out = {str(p.component): p.index for p in model.ports}
    out.update({p.name: p.index for p in model.ports if p.name})
    return out


def _column(body: list, j: int, name: str, kind: str, unit: str | None,
            source: str) -> np.ndarray:
    """Column ``j`` in SI: plain numbers read at once and scaled by the header's unit;
    anything else (an empty cell, a unit in a cell, a value out of range) read cell by cell,
    so that the message names its row."""
    try:
        numbers = np.array([row[j] for row in body], dtype=float)
    except (ValueError, IndexError):
        numbers = None
    if numbers is not None and np.isfinite(numbers).all():
        scale = _cell(["1"], 0, name, kind, unit, source, 2) if unit else 1.0
        if unit is None or scale != 0.0:
            return numbers * scale
    return np.array([_cell(row, j, name, kind, unit, source, r)
                     for r, row in enumerate(body, start=2)])


def _cell(row: list, j: int, name: str, kind: str, unit: str | None, source: str,
          number: int) -> float:
    text = row[j].strip() if j < len(row) else ""
    where = f"{source}: row {number}, {name.strip()}"
    if not text:
        raise UsageError(f"{where}: empty cell")
    try:
        return parse_quantity(f"{text} {unit}" if unit else float(text), kind, where)
    except ValueError:
        raise UsageError(f"{where}: not a number: {text!r}") from None
    except ModelError as error:
        raise UsageError(f"{where}: {error.message}") from None


def _durations(body: list, time_col, header: list, source: str) -> np.ndarray:
    if time_col is None:
        return np.ones(len(body))
    j, what, unit = time_col
    scale = {None: 1.0, "": 1.0, "s": 1.0, "min": 60.0, "h": 3600.0}.get(
        unit.strip() if unit else unit)
    if scale is None:
        raise UsageError(f"{source}: column {header[j]!r}: unit must be s, min or h")
    try:
        t = np.array([float(row[j]) for row in body]) * scale
    except (ValueError, IndexError):
        raise UsageError(f"{source}: column {header[j]!r}: every row needs a number") from None
    if what == "time":
        if len(t) < 2 or np.any(np.diff(t) <= 0):
            raise UsageError(f"{source}: time [s] must increase, over two rows at least")
        step = np.diff(t)
        t = np.append(step, step[-1])
    if np.any(t < 0) or not np.all(np.isfinite(t)):
        raise UsageError(f"{source}: a duration must be a finite number >= 0")
    return t


def as_dict(points: Points, row: int) -> dict[str, Any]:
    """``{PATH: SI value}`` of one row."""
    return {path: float(v[row]) for (path, _, _), v in zip(points.columns, points.values)}
