"""A machine's efficiency over speed and torque, read from a CSV file (docs/hybrid.md).

``efficiency: {map: mg2.csv}`` on a machine port names a table, relative to the model
file's folder: a header ``speed [rpm]`` (or ``speed [rad/s]``), ``torque [N·m]`` (or
``torque [Nm]``), ``efficiency``, then one row per grid point, every combination of the
speeds and torques given exactly once, efficiencies in (0, 1]. The machine's efficiency at
a point is the bilinear interpolation at ``|speed|`` and ``|torque|`` (the same efficiency
motoring and generating, in either sense of rotation, as catalogue maps are drawn); outside
the grid the nearest edge value is taken and the result warns (``outside-map``).

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
import math
from pathlib import Path

import numpy as np

from powergraph.errors import ModelError
from powergraph.records import record
from powergraph.units_si import RAD_S_PER_RPM

#: Header names accepted for each column, with the factor to SI (rad/s, N·m).
SPEED_COLUMNS = {"speed [rpm]": RAD_S_PER_RPM, "speed [rad/s]": 1.0}
TORQUE_COLUMNS = {"torque [n·m]": 1.0, "torque [nm]": 1.0, "torque [n*m]": 1.0}
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

    def at(self, speed: float, torque: float) -> tuple[float, bool]:
        """The efficiency at ``|speed|`` (rad/s) and ``|torque|`` (N·m), and whether the
        point lies on the grid (else the nearest edge's value is returned)."""
        s, t = abs(float(speed)), abs(float(torque))
        inside = (self.speeds[0] <= s <= self.speeds[-1]
                  and self.torques[0] <= t <= self.torques[-1])
        along_torque = [np.interp(t, self.torques, row) for row in self.values]
        return float(np.interp(s, self.speeds, along_torque)), inside


def read_efficiency_table(name: str, folder: Path | None, path: str) -> EfficiencyTable:
    """Read and check the table ``name`` (relative to ``folder``, the model file's
    folder, or the working folder); a :class:`ModelError` at ``path`` otherwise."""
    file = Path(name) if folder is None else folder / name
    try:
        with open(file, newline="", encoding="utf-8") as handle:
            rows = list(_rows(csv.reader(handle), name, path))
    except (OSError, UnicodeDecodeError, csv.Error) as exc:
        raise ModelError(f"cannot read the efficiency map {name!r}: "
                         f"{getattr(exc, 'strerror', None) or exc}", path) from None
    return _grid(rows, name, path)


def _rows(reader, name: str, path: str):
    """``(line, speed rad/s, torque N·m, efficiency)`` per data row, header checked."""
    header = next(reader, None)
    if header is None:
        raise ModelError(f"{name}: the file is empty", path)
    keys = [h.strip().lower() for h in header]
    if len(keys) != 3 or keys[0] not in SPEED_COLUMNS or keys[1] not in TORQUE_COLUMNS \
            or keys[2] != "efficiency":
        raise ModelError(f"{name} line 1: expected the columns 'speed [rpm]' (or 'speed "
                         f"[rad/s]'), 'torque [N·m]', 'efficiency'; got {header!r}", path)
    to_si = SPEED_COLUMNS[keys[0]]
    for line, row in enumerate(reader, start=2):
        if not row or all(not cell.strip() for cell in row):
            continue
        if line > MAX_ROWS + 1:
            raise ModelError(f"{name}: more than {MAX_ROWS} rows", path)
        if len(row) != 3:
            raise ModelError(f"{name} line {line}: expected 3 values, got {len(row)}", path)
        speed, torque, eta = (_number(cell, name, line, path) for cell in row)
        if speed < 0 or torque < 0:
            raise ModelError(f"{name} line {line}: speeds and torques are magnitudes (>= 0); "
                             "the map applies to both senses", path)
        if not 0 < eta <= 1:
            raise ModelError(f"{name} line {line}: efficiency must be in (0, 1], got "
                             f"{eta:g}", path)
        yield line, speed * to_si, torque, eta


def _number(cell: str, name: str, line: int, path: str) -> float:
    try:
        value = float(cell.strip())
    except ValueError:
        value = math.nan
    if not math.isfinite(value) or len(cell) > 64:
        raise ModelError(f"{name} line {line}: {cell.strip()[:40]!r} is not a finite number",
                         path)
    return value


def _grid(rows: list, name: str, path: str) -> EfficiencyTable:
    """The rows as a full rectilinear grid (every speed with every torque, once)."""
    where = {}
    for line, speed, torque, eta in rows:
        if (speed, torque) in where:
            raise ModelError(f"{name} line {line}: the point {speed:g} rad/s, {torque:g} N·m "
                             f"is given twice (line {where[speed, torque][0]})", path)
        where[speed, torque] = (line, eta)
    speeds = sorted({speed for speed, _ in where})
    torques = sorted({torque for _, torque in where})
    if len(speeds) < 2 or len(torques) < 2:
        raise ModelError(f"{name}: a map needs at least two speeds and two torques", path)
    missing = len(speeds) * len(torques) - len(where)
    if missing:
        raise ModelError(f"{name}: {missing} point(s) of the grid of {len(speeds)} speeds × "
                         f"{len(torques)} torques are missing (every speed needs every "
                         "torque)", path)
    values = tuple(tuple(where[s, t][1] for t in torques) for s in speeds)
    return EfficiencyTable(name, tuple(speeds), tuple(torques), values)
