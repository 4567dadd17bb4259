"""Operating points of a duty cycle read from CSV (docs/hybrid.md, ``powergraph cycle``).

One row per operating point: ``PORT.speed``, ``PORT.power`` or ``PORT.torque`` columns
(PORT a port's ``name`` or component id; the unit in brackets, SI without one), optional
``BUS.battery`` columns (a bus's battery power in the row), ``duration [s]`` or
``time [s]`` (each row lasts until the next, the last as long as the one before) and
``mode`` (docs/hybrid.md lists what is refused).

The header is checked whole before a row is read, each unit once
(:mod:`~powergraph.analyses.cycle_header`). The rows are streamed into one float array
per column, :data:`CHUNK` rows at a time; the first problem is an error naming the row
(the file's line) and the column. A file is read by
:func:`~powergraph.model.input_files.read_table_text` (size limit, UTF-8).

Examples
--------
>>> import io
>>> from powergraph.model import load_model
>>> m = load_model("models/planetary_2kh_carrier_to_ring.yaml")
>>> pts = read_points(io.StringIO("carrier.speed [rpm],carrier.power [kW],duration [s]\\n"
...                               "1000,1,2\\n2000,2,3\\n"), m)
>>> pts.columns[0], pts.values[0].tolist(), pts.durations.tolist(), pts.lines.tolist()
(('ports.0.speed', 0, 'speed'), [104.71975511965977, 209.43951023931953], [2.0, 3.0], [2, 3])
>>> read_points(io.StringIO("carrier.speed [rpm],carrier.speed [rad/s]\\n1,2\\n"), m)
Traceback (most recent call last):
...
powergraph.errors.UsageError: points: column 'carrier.speed [rad/s]': the same quantity \
as column 'carrier.speed [rpm]' (ports[0] speed); one column per quantity
"""
from __future__ import annotations

import csv
import io
import itertools
import os
from typing import IO, Iterator

import numpy as np

from powergraph.analyses.cycle_header import TIME_UNITS, Column, Layout, layout  # noqa: F401
from powergraph.errors import UsageError
from powergraph.model.input_files import read_table_text
from powergraph.model.spec import Model
from powergraph.model.schema_parts import MAX_POWER, MAX_SPEED, MAX_TORQUE
from powergraph.model.units import SI_UNITS
from powergraph.model.yaml_loader import brief
from powergraph.records import record

#: Largest port values (SI) a row may give, as in model files.
PORT_LIMITS = {"speed": MAX_SPEED, "power": MAX_POWER, "torque": MAX_TORQUE,
               "battery": MAX_POWER}
#: Rows converted at a time: the most rows held as text at once.
CHUNK = 8192


@record
class Points:
    """The operating points: ``columns`` ``(PATH, port index, kind)`` with their SI
    ``values`` (one float array per column), each row's duration (s) and file line, and
    the modes as ``mode_codes`` (one per row, or None without a ``mode`` column) into
    ``mode_names``; ``batteries`` ``(bus, SI values)`` of the ``BUS.battery`` columns."""

    columns: tuple[tuple[str, int, str], ...]
    values: tuple[np.ndarray, ...]
    durations: np.ndarray
    lines: np.ndarray
    source: str = "points"
    mode_names: tuple[str, ...] = ()
    mode_codes: np.ndarray | None = None
    #: The header of the ``duration`` or ``time`` column, if any.
    duration_column: str | None = None
    #: ``(bus name, battery power per row, W)`` of each ``BUS.battery`` column.
    batteries: tuple[tuple[str, np.ndarray], ...] = ()

    def __len__(self) -> int:
        return len(self.durations)

    def mode(self, row: int) -> str | None:
        """The mode of one row (None without a mode)."""
        return None if self.mode_codes is None else self.mode_names[self.mode_codes[row]]

    @property
    def modes(self) -> tuple[str | None, ...]:
        """Every row's mode (a tuple as long as the points: prefer :meth:`mode`)."""
        if self.mode_codes is None:
            return (None,) * len(self)
        return tuple(self.mode_names[c] for c in self.mode_codes.tolist())


def read_points(handle: IO[str] | str | os.PathLike, model: Model,
                source: str = "points") -> Points:
    """Read the operating points of ``model`` from a CSV file (path) or a text handle.

    Raises
    ------
    UsageError
        One line naming the file, the column and, for a cell, the row (the file's line):
        ``points.csv: row 7, column 'engine.speed [rpm]': not a number: 'fast'``.
    """
    if isinstance(handle, (str, os.PathLike)):
        source = str(handle)
        handle = _lines(read_table_text(handle, "the points"))
    reader = csv.reader(handle, strict=True)
    try:
        header = next((row for row in reader if "".join(row).strip()), None)
    except csv.Error as error:
        raise UsageError(f"{source}: row {reader.line_num}: not CSV ({error})") from None
    if header is None:
        raise UsageError(f"{source}: needs a header and at least one row")
    header[0] = header[0].removeprefix("\ufeff")
    table = _Table(layout(header, model, source), model, source)
    table.read(reader)
    return table.points()


def _lines(text: str, size: int = 1 << 16) -> Iterator[str]:
    """The lines of ``text``, each ending in ``\\n`` (LF, CR LF and a lone CR, as old Mac
    spreadsheets write, are line ends), read from pieces of about ``size`` characters
    (each a :class:`io.StringIO`: no copy of the whole)."""
    pieces = (text[start:end] for start, end in _bounds(text, size))
    return itertools.chain.from_iterable(io.StringIO(p, newline=None) for p in pieces)


def _bounds(text: str, size: int) -> Iterator[tuple[int, int]]:
    """Pieces of ``text`` ending after a line end (not between the CR and LF of one)."""
    start, length = 0, len(text)
    while start < length:
        end = text.find("\n", start + size)
        end = (end if end >= 0 else text.find("\r", start + size)) + 1 or length
        yield start, end
        start = end


class _Table:
    """The columns as read: float arrays per column (one per chunk), lines, mode codes."""

    def __init__(self, layout: Layout, model: Model, source: str) -> None:
        self.layout, self.modes, self.source = layout, model.modes, source
        self.numbers = layout.ports + layout.batteries + ((layout.time,) if layout.time
                                                          else ())
        self.parts: list[list[np.ndarray]] = [[] for _ in self.numbers]
        self.lines: list[np.ndarray] = []
        self.mode_names: list[str] = []
        self.mode_index: dict[str, int] = {}
        self.codes: list[np.ndarray] = []

    def read(self, reader) -> None:
        """Read every row, :data:`CHUNK` at a time."""
        while True:
            before = reader.line_num
            try:
                rows = list(itertools.islice(reader, CHUNK))
            except csv.Error as error:
                raise UsageError(f"{self.source}: row {reader.line_num}: not CSV ({error})") \
                    from None
            if not rows:
                return
            starts = _starts(rows, before, reader.line_num)
            if set(map(len, rows)) != {self.layout.width}:
                rows, starts = self._full(rows, starts)
            if rows:
                self.add(rows, starts)

    def _full(self, rows: list[list[str]], starts) -> tuple[list[list[str]], list[int]]:
        """The rows without the blank lines; a row of another width is an error."""
        kept = [k for k, row in enumerate(rows) if "".join(row).strip()]
        for k in kept:
            if len(rows[k]) != self.layout.width:
                raise UsageError(f"{self.source}: row {starts[k]}: {len(rows[k])} cells, but "
                                 f"the header has {self.layout.width} columns")
        return [rows[k] for k in kept], [int(starts[k]) for k in kept]

    def add(self, rows: list[list[str]], starts: list[int]) -> None:
        """Convert a chunk of rows; the first problem (by row, then column) is an error."""
        if self.layout.mode is not None and not all(map("".join, rows)):
            rows, starts = self._full(rows, starts)      # blank rows (",,,"): skipped
            if not rows:
                return None
        flat, width = list(itertools.chain.from_iterable(rows)), self.layout.width
        cells = [flat[j::width] for j in range(width)]
        converted = [_numbers(cells[c.position], c, self._may_be_empty(c))
                     for c in self.numbers]
        problems = [p for _, p in converted if p is not None]
        if any(p[2].startswith("empty cell") for p in problems):
            full, full_starts = self._full(rows, starts)
            if len(full) < len(rows):   # blank rows (",,,"): skipped
                return self.add(full, full_starts) if full else None
        if self.layout.mode is not None:
            problems.append(self._codes(cells[self.layout.mode]))
        problems = [p for p in problems if p is not None]
        if problems:
            k, name, message = min(problems, key=lambda p: p[0])
            raise UsageError(f"{self.source}: row {starts[k]}, column {brief(name)}: {message}")
        for part, (values, _) in zip(self.parts, converted):
            part.append(values)
        self.lines.append(np.array(starts, dtype=np.int64))

    def _may_be_empty(self, column: Column) -> bool:
        """In a cycle in modes, a port's or a bus's cell may be empty: not given in
        this row (the row's mode, then the model, give the value)."""
        return self.layout.mode is not None and column.kind != "time"

    def _codes(self, cells: list[str]) -> tuple[int, str, str] | None:
        """Append the chunk's mode codes; an unknown mode is a problem."""
        for text in sorted(set(cells) - self.mode_index.keys(), key=cells.index):
            name = text.strip()
            if name not in self.modes:
                return (cells.index(text), "mode", (f"unknown mode {brief(name)}" if name else
                        "empty cell") + f" (the model's modes: {', '.join(self.modes)})")
            if name not in self.mode_names:
                self.mode_names.append(name)
            self.mode_index[text] = self.mode_names.index(name)
        self.codes.append(np.fromiter(map(self.mode_index.__getitem__, cells),
                                      dtype=np.uint32, count=len(cells)))
        return None

    def points(self) -> Points:
        if not self.lines:
            raise UsageError(f"{self.source}: needs a header and at least one row")
        lines = np.concatenate(self.lines)
        values = [np.concatenate(part) for part in self.parts]
        time = self.layout.time
        durations = (_durations(values.pop(), time, lines, self.source) if time
                     else np.ones(len(lines)))
        ports = len(self.layout.ports)
        batteries = tuple((c.bus, v) for c, v in zip(self.layout.batteries, values[ports:]))
        return Points(columns=tuple((c.path, c.port, c.kind) for c in self.layout.ports),
                      values=tuple(values[:ports]), durations=durations, lines=lines,
                      batteries=batteries,
                      source=self.source, mode_names=tuple(self.mode_names),
                      mode_codes=(None if self.layout.mode is None else
                                  np.concatenate(self.codes)),
                      duration_column=time.name if time else None)


#: What an empty cell is told in a cycle without a ``mode`` column (in one with, an
#: empty port or bus cell is "not given in this row").
_EMPTY = {"battery": ": a BUS.battery column gives the bus's battery power in every row "
                     "(a number, in the header's unit)", "time": ""}
_EMPTY_PORT = (": without a mode column every row gives each column's value (in a cycle in "
               "modes an empty cell is 'not given in this row')")


def _numbers(cells: list[str], column: Column, may_be_empty: bool = False):
    """``(SI values, None)`` of a column's cells, or ``(None, (k, name, problem))`` for
    its first bad cell ``k``; an empty cell is NaN where ``may_be_empty``."""
    empty = None
    if may_be_empty and not all(map(str.strip, cells)):
        empty = np.array([not text.strip() for text in cells])
        cells = ["nan" if blank else text for text, blank in zip(cells, empty)]
    try:
        raw = np.array(cells, dtype=float)
    except ValueError:
        k = next((k for k, text in enumerate(cells) if not _is_number(text)), 0)
        text = cells[k].strip()
        return None, (k, column.name, f"not a number: {brief(text)}" if text else
                      "empty cell" + _EMPTY.get(column.kind, _EMPTY_PORT))
    with np.errstate(over="ignore", invalid="ignore"):
        values = raw * column.scale
    limit = PORT_LIMITS.get(column.kind, np.finfo(float).max)   # a time: finite
    what = "power" if column.kind == "battery" else column.kind
    bad = ~(np.abs(values) <= limit)          # NaN and inf included
    if empty is not None:
        bad &= ~empty
    if not bad.any():
        return values, None
    k = int(np.argmax(bad))
    text = cells[k].strip()
    if not np.isfinite(raw[k]):
        return None, (k, column.name, f"not a finite number: {brief(text)}")
    si = "s" if column.kind == "time" else SI_UNITS[what]
    if np.isfinite(values[k]):
        owner = "a battery's" if column.kind == "battery" else "a port's"
        return None, (k, column.name, f"{brief(text)} is out of range: {owner} "
                      f"{what} is at most {limit:g} {si} either way, as in model files")
    return None, (k, column.name, f"{brief(text)} overflows once in {si} (beyond the "
                  f"largest float, {np.finfo(float).max:.3g})")


def _starts(rows: list[list[str]], before: int, after: int) -> np.ndarray:
    """The first line of each row read from line ``before + 1`` to ``after``: a row takes
    one line and one more per line end in its quoted cells."""
    if after - before == len(rows):
        return np.arange(before + 1, after + 1)
    taken = [1 + sum(cell.count("\n") for cell in row) for row in rows]
    return before + 1 + np.concatenate([[0], np.cumsum(taken[:-1], dtype=np.int64)])


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def _durations(t: np.ndarray, column: Column, lines: np.ndarray, source: str) -> np.ndarray:
    """Each row's duration (s) from a ``duration`` or ``time`` column."""
    def refuse(k: int, message: str) -> UsageError:
        return UsageError(f"{source}: row {lines[k]}, column {brief(column.name)}: {message}")

    with np.errstate(over="ignore", invalid="ignore"):
        if column.path == "time":
            if len(t) < 2:
                raise UsageError(f"{source}: column {brief(column.name)}: sample times need two "
                                 "rows at least (each row lasts until the next)")
            step = np.diff(t)
            if not np.isfinite(step).all():
                k = int(np.argmin(np.isfinite(step))) + 1
                raise refuse(k, "the step from the row before overflows")
            if (step <= 0).any():
                k = int(np.argmax(step <= 0)) + 1
                raise refuse(k, f"the time does not increase ({t[k - 1]:g} s, then "
                             f"{t[k]:g} s)")
            t = np.append(step, step[-1])
        elif (t < 0).any():
            k = int(np.argmax(t < 0))
            raise refuse(k, f"a duration must be >= 0, got {t[k]:g} s")
        if not np.isfinite(t.sum()):
            raise UsageError(f"{source}: column {brief(column.name)}: the durations add up to "
                             "more than the largest float")
    return t


def check_modes(points: Points, model: Model) -> None:
    """Refuse points whose modes ``model`` does not have (a :class:`Points` made for
    another model), naming the first row with one."""
    for code, name in enumerate(points.mode_names):
        if name is not None and name not in model.modes:
            k = int(np.argmax(points.mode_codes == code))
            raise UsageError(f"{points.source}: row {points.lines[k]}, column 'mode': "
                             f"unknown mode {brief(name)} (the model's modes: "
                             f"{', '.join(model.modes) or 'none'})")


def as_dict(points: Points, row: int) -> dict[str, float]:
    """``{PATH: SI value}`` of one row's port columns."""
    return {path: float(v[row]) for (path, _, _), v in zip(points.columns, points.values)}

