"""A machine's efficiency over speed and torque, read from a CSV file (docs/hybrid.md).

``efficiency: {map: mg2.csv}`` on a machine port names a table, relative to the model
file's folder: a header ``speed [UNIT]``, ``torque [UNIT]``, ``efficiency`` (the units read
as a model's are, :func:`~powergraph.model.units.unit_factor`: ``speed [rpm]``,
``speed [rad/s]``, ``torque [N·m]``, ``torque [Nm]``...), then one row per grid point,
every combination of the speeds and torques given exactly once, efficiencies in
[1e-6, 1] (:data:`~powergraph.model.schema_parts.MIN_MACHINE_EFFICIENCY`, as
``--mesh-efficiency``'s range). The file is read as every table is
(:mod:`powergraph.model.input_files`: bounded, UTF-8 with or without a byte-order mark);
its problems are :class:`ModelError` at the port's ``efficiency.map``, naming the file and
its line. The machine's efficiency at a point is the bilinear interpolation at ``|speed|``
and ``|torque|`` (the same efficiency motoring and generating, in either sense of rotation,
as catalogue maps are drawn); outside the grid the nearest edge value is taken and the
result warns (``outside-map``).

Examples
--------
>>> table = EfficiencyTable("mg.csv", speeds=(0.0, 100.0), torques=(0.0, 10.0),
...                         values=((0.75, 0.875), (0.8125, 0.9375)))
>>> table.at(50.0, -5.0)        # halfway in both: the mean of the four corners
(0.84375, True)
>>> table.at(200.0, 5.0)        # beyond the fastest row: its edge, flagged
(0.875, False)
"""
from __future__ import annotations

import csv
import functools
import math
import os
import re
import warnings
from pathlib import Path

import numpy as np

from powergraph.errors import ModelError, UsageError
from powergraph.model.input_files import decode_text, read_bytes
from powergraph.model.schema_parts import MAX_SPEED, MAX_TORQUE, MIN_MACHINE_EFFICIENCY
from powergraph.model.units import unit_factor
from powergraph.model.yaml_loader import brief
from powergraph.records import record

#: A column header: its name, then its unit in brackets (``speed [rpm]``).
_COLUMN = re.compile(r"\s*(?P<kind>speed|torque|efficiency)\s*(?:\[(?P<unit>[^\]]*)\])?\s*",
                     re.IGNORECASE)
_LINE = re.compile(r".*?(?:\r\n|\r|\n)|.+", re.DOTALL)
#: A line holding nothing but spaces and commas (skipped by the row-by-row reading).
_BLANK = re.compile(r"(?:\A|\r\n|\r|\n)[\s,]*(?:\r\n|\r|\n)")
#: Most rows of one table (a map of 500 × 500 points is far finer than any catalogue's).
MAX_ROWS = 250_000


@record
class EfficiencyTable:
    """Efficiency ``values[i][j]`` at speed ``speeds[i]`` (rad/s) and torque
    ``torques[j]`` (N·m), both ascending and >= 0; ``source`` is the file as written."""

    source: str
    speeds: tuple[float, ...]
    torques: tuple[float, ...]
    values: tuple[tuple[float, ...], ...]

    def at(self, speed, torque):
        """The efficiency at ``|speed|`` (rad/s) and ``|torque|`` (N·m), and whether the
        point lies on the grid (else the nearest edge's value is returned): floats, or
        arrays over many points (the same rule, one point or many).

        >>> table = EfficiencyTable("mg.csv", (0.0, 100.0), (0.0, 10.0), ((0.5, 1.0), (0.5, 1.0)))
        >>> eta, on_map = table.at(np.array([10.0, -10.0]), np.array([2.5, 20.0]))
        >>> eta.tolist(), on_map.tolist()
        ([0.625, 1.0], [True, False])
        """
        s, t = np.abs(np.asarray(speed, dtype=float)), np.abs(np.asarray(torque, dtype=float))
        speeds, torques, values = _arrays(self)
        inside = ((speeds[0] <= s) & (s <= speeds[-1])
                  & (torques[0] <= t) & (t <= torques[-1]))
        i, a = _cell(speeds, s)
        j, b = _cell(torques, t)
        low = _between(values[i, j], values[i, j + 1], b)
        high = _between(values[i + 1, j], values[i + 1, j + 1], b)
        eta = _between(low, high, a)
        if eta.ndim == 0:
            return float(eta), bool(inside)
        return eta, inside


@functools.lru_cache(maxsize=32)
def _arrays(table: EfficiencyTable) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The table's speeds, torques and values as arrays (kept for its next points)."""
    return (np.array(table.speeds), np.array(table.torques), np.array(table.values))


def _cell(grid: np.ndarray, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The interval of ``grid`` holding ``x`` (the first or last beyond the grid) and the
    fraction of the way along it, clipped to [0, 1] (beyond the grid: its edge value)."""
    k = np.clip(np.searchsorted(grid, x, side="right") - 1, 0, len(grid) - 2)
    with np.errstate(invalid="ignore"):
        fraction = np.clip((x - grid[k]) / (grid[k + 1] - grid[k]), 0.0, 1.0)
    return k, fraction


def _between(low, high, fraction):
    """Linear interpolation, exact at both ends: ``low`` at 0, ``high`` at 1."""
    return (1.0 - fraction) * low + fraction * high


def read_efficiency_table(name: str, folder: Path | None, path: str) -> EfficiencyTable:
    """Read and check the table ``name`` (relative to ``folder``, the model file's
    folder, or the working folder); a :class:`ModelError` at ``path`` otherwise, naming
    the file and its line.

    The file is read as every table is (:mod:`powergraph.model.input_files`: its size
    limit, UTF-8 with or without a byte-order mark); the rows are checked as they are
    read, so a file of more than :data:`MAX_ROWS` stops there.
    """
    file = name if folder is None else os.path.join(folder, name)   # a trailing / kept
    try:
        data = read_bytes(file, "table", "an efficiency map")
    except UsageError as error:
        raise ModelError(f"cannot read the efficiency map {name!r}: {error.message}",
                         path) from None
    try:
        text = decode_text(data, name)
    except UsageError as error:
        raise ModelError(error.message, path) from None
    del data
    try:
        lines, speed, torque, eta = _read_rows(text, name, path)
    except csv.Error as error:      # a cell over the csv module's field limit, say
        raise ModelError(f"cannot read the efficiency map {name!r}: {error}", path) from None
    _check(lines, speed, torque, eta, name, path)
    return _grid(lines, speed, torque, eta, name, path)


def _lines(text: str):
    """The lines of ``text`` one at a time, their ends kept (``\\n``, ``\\r\\n`` or ``\\r``):
    no copy of the whole (``io.StringIO`` would hold it as four bytes a character)."""
    return (match.group() for match in _LINE.finditer(text))


def _columns(header: list[str], name: str, path: str) -> tuple[float, float]:
    """The factors to rad/s and N·m of the header's speed and torque columns."""
    found = [_COLUMN.fullmatch(cell) for cell in header]
    kinds = [m["kind"].lower() if m else None for m in found]
    if kinds != ["speed", "torque", "efficiency"] or found[2]["unit"] is not None \
            or found[0]["unit"] is None or found[1]["unit"] is None:
        raise ModelError(f"{name} line 1: expected the columns 'speed [rpm]' (or another "
                         "speed unit), 'torque [N·m]' (or another torque unit), "
                         f"'efficiency'; got {brief(header)}", path)
    try:
        return tuple(unit_factor(m["unit"], kind, path)  # type: ignore[return-value]
                     for m, kind in zip(found[:2], kinds))
    except ModelError as error:
        raise ModelError(f"{name} line 1: {error.message}", path) from None


def _read_rows(text: str, name: str, path: str) -> tuple[np.ndarray, ...]:
    """The file's lines, speeds (rad/s), torques (N·m) and efficiencies of its rows, at
    most :data:`MAX_ROWS`: numpy's parser reads a plain file at once; a file it cannot
    read (a cell that is no number, a row of another width, blank lines) is read row by
    row, so that its first problem names its line."""
    lines = _lines(text)
    header = next(csv.reader([next(lines, "")]))
    if not header:
        raise ModelError(f"{name}: the file is empty", path)
    scales = _columns(header, name, path)
    table = None if _BLANK.search(text) else _plain_table(lines)
    if table is None:
        numbers = list(_rows(csv.reader(_lines(text)), name, path))
        table = np.array([row[1:] for row in numbers], dtype=float).reshape(-1, 3)
        line_numbers = np.array([row[0] for row in numbers], dtype=np.int64)
    else:
        line_numbers = np.arange(2, len(table) + 2)
    if len(table) > MAX_ROWS:
        raise ModelError(f"{name} line {line_numbers[MAX_ROWS]}: more than {MAX_ROWS} rows",
                         path)
    return (line_numbers, table[:, 0] * scales[0], table[:, 1] * scales[1], table[:, 2])


def _plain_table(lines) -> np.ndarray | None:
    """The rows as a table of finite numbers three wide, read by numpy, or None where
    numpy cannot read them so (the rows are then read one by one)."""
    try:
        with warnings.catch_warnings():        # "input contained no data": said later
            warnings.simplefilter("ignore")
            table = np.loadtxt(lines, delimiter=",", quotechar='"', dtype=float, ndmin=2,
                               max_rows=MAX_ROWS + 1)
    except ValueError:
        return None
    return table if table.shape[1] == 3 and np.isfinite(table).all() else None


def _rows(reader, name: str, path: str):
    """``(line, speed, torque, efficiency)`` per data row (in the file's units), the
    header skipped, at most one more than :data:`MAX_ROWS`: every cell a finite number."""
    next(reader, None)
    count = 0
    for row in reader:
        if not any(cell.strip() for cell in row):
            continue                               # a blank line
        line = reader.line_num
        if len(row) != 3:
            raise ModelError(f"{name} line {line}: expected 3 values, got {len(row)}", path)
        count += 1
        yield (line, *(_number(cell, name, line, path) for cell in row))
        if count > MAX_ROWS:
            return


def _check(lines: np.ndarray, speed: np.ndarray, torque: np.ndarray, eta: np.ndarray,
           name: str, path: str) -> None:
    """Every row's values possible, else a :class:`ModelError` naming the first row that
    is not: finite, speeds and torques magnitudes (>= 0) within a model's ranges,
    efficiencies in [``MIN_MACHINE_EFFICIENCY``, 1]."""
    rules = (
        (~np.isfinite(speed + torque + eta), "not finite numbers"),
        ((speed < 0) | (torque < 0), "speeds and torques are magnitudes (>= 0); the map "
                                     "applies to both senses"),
        ((speed > MAX_SPEED) | (torque > MAX_TORQUE),
         f"beyond the largest speed ({MAX_SPEED:g} rad/s) or torque ({MAX_TORQUE:g} N·m) "
         "a model takes"),
        (~((eta >= MIN_MACHINE_EFFICIENCY) & (eta <= 1)),
         f"efficiency must be in [{MIN_MACHINE_EFFICIENCY:g}, 1], got {{eta:g}}"),
    )
    for bad, message in rules:
        if bad.any():
            k = int(np.argmax(bad))
            raise ModelError(f"{name} line {lines[k]}: " + message.format(eta=eta[k]), path)


def _number(cell: str, name: str, line: int, path: str) -> float:
    try:
        value = float(cell)
    except ValueError:
        value = math.nan
    if not math.isfinite(value):
        raise ModelError(f"{name} line {line}: {brief(cell.strip()[:40])} is not a finite "
                         "number", path)
    return value


def _grid(lines: np.ndarray, speed: np.ndarray, torque: np.ndarray, eta: np.ndarray,
          name: str, path: str) -> EfficiencyTable:
    """The rows as a full rectilinear grid (every speed with every torque, once)."""
    speeds, i = np.unique(speed, return_inverse=True)
    torques, j = np.unique(torque, return_inverse=True)
    cell = i.ravel() * len(torques) + j.ravel()
    order = np.argsort(cell, kind="stable")
    twice = np.flatnonzero(np.diff(cell[order]) == 0)
    if len(twice):
        first, again = order[twice[0]], order[twice[0] + 1]
        raise ModelError(f"{name} line {lines[again]}: the point {speed[again]:g} rad/s, "
                         f"{torque[again]:g} N·m is given twice (line {lines[first]})", path)
    if len(speeds) < 2 or len(torques) < 2:
        raise ModelError(f"{name}: a map needs at least two speeds and two torques", path)
    missing = len(speeds) * len(torques) - len(cell)
    if missing:
        raise ModelError(f"{name}: {missing} point(s) of the grid of {len(speeds)} speeds × "
                         f"{len(torques)} torques are missing (every speed needs every "
                         "torque)", path)
    values = np.empty(len(cell))
    values[cell] = eta
    grid = values.reshape(len(speeds), len(torques))
    return EfficiencyTable(name, tuple(speeds.tolist()), tuple(torques.tolist()),
                           tuple(map(tuple, grid.tolist())))
