"""A train over a duty cycle: one operating point per row, energies over the cycle
(docs/hybrid.md, ``powergraph cycle``).

Rows of a plain train (no machines, no modes, no load-dependent losses) are evaluated at
once by the compiled sweep (:mod:`powergraph.analyses.sweep`); the others — machines on
buses, a ``mode`` column, friction laws and bearing losses — by one single solve per row.
``CycleResult.method`` says which; a row the sweep does not solve is solved alone, for
its reason.

A row that cannot be solved (its loads or speeds do not determine the train...) is an
error naming it, unless ``keep_going``: then it is left out of the totals, which say how
many rows and how much time that is. Totals that would overflow are an error too.

Examples
--------
>>> import io
>>> from powergraph.model import load_model
>>> m = load_model("models/planetary_2kh_carrier_to_ring.yaml")
>>> r = cycle(m, io.StringIO("carrier.speed [rpm],carrier.power [kW],duration [s]\\n"
...                          "1000,1,2\\n2000,2,3\\n"))
>>> r.method, round(r.energy_in), round(r.efficiency, 6)
('sweep', 8000, 0.99238)
"""
from __future__ import annotations

import math
import os
from typing import IO, Any

from powergraph.analyses.cycle_points import Points, check_modes, read_points
from powergraph.analyses.cycle_rows import (NUMERICAL, CycleRow, RowError, element_label,
                                            single_rows, solve_losses, sweep_rows, sweepable)
from powergraph.errors import ModelError, UsageError
from powergraph.model.spec import Model
from powergraph.records import record

__all__ = ["CycleResult", "CycleRow", "cycle", "element_label", "solve_losses"]
#: The single solves of every row (``benchmarks/cycle.py`` times them).
_single_rows = single_rows


@record
class CycleResult:
    """The cycle's rows and totals: energies in, out and lost per element (J), the cycle
    efficiency (energy out / energy in), time (s) in all and per mode and the rows that
    lock, over the rows solved; the rows left out (that could not be solved) and their
    time."""

    name: str
    rows: tuple[CycleRow, ...]
    method: str

    @property
    def time(self) -> float:
        """Time (s) of the rows solved."""
        return float(sum(r.duration for r in self.rows if not r.failed))

    @property
    def left_out(self) -> list[int]:
        """Indices of the rows that could not be solved, left out of the totals."""
        return [r.index for r in self.rows if r.failed]

    @property
    def left_out_time(self) -> float:
        return float(sum(r.duration for r in self.rows if r.failed))

    @property
    def energy_in(self) -> float:
        return float(sum(r.power_in * r.duration for r in self.rows))

    @property
    def energy_out(self) -> float:
        return float(sum(r.power_out * r.duration for r in self.rows))

    @property
    def energy_lost(self) -> dict[str, float]:
        """``{element: J}``: each mesh, coupling, bearing, drag and machine."""
        out: dict[str, float] = {}
        for r in self.rows:
            for label, loss in r.losses.items():
                out[label] = out.get(label, 0.0) + loss * r.duration
        return out

    @property
    def efficiency(self) -> float | None:
        return self.energy_out / self.energy_in if self.energy_in > 0 else None

    @property
    def time_per_mode(self) -> dict[str, float]:
        out: dict[str, float] = {}
        for r in self.rows:
            if not r.failed:
                key = r.mode or "-"
                out[key] = out.get(key, 0.0) + r.duration
        return out

    @property
    def negative_split_time(self) -> float:
        """Time (s) the machines spend in a negative split (power circulating through a
        bus)."""
        return float(sum(r.duration for r in self.rows if r.negative_split))

    @property
    def warned_rows(self) -> dict[str, list[int]]:
        """``{warning code: row indices}`` of the rows whose solve warned."""
        out: dict[str, list[int]] = {}
        for r in self.rows:
            for code in r.warnings:
                out.setdefault(code, []).append(r.index)
        return out

    @property
    def locked_rows(self) -> list[int]:
        return [r.index for r in self.rows if r.verdict in ("locked", "self-locking")]

    def to_dict(self) -> dict[str, Any]:
        return {"name": self.name, "method": self.method, "rows": [r.to_dict() for r in self.rows],
                "time": self.time,
                "left_out": {"rows": len(self.left_out), "time": self.left_out_time},
                "energy_in": self.energy_in, "energy_out": self.energy_out,
                "energy_lost": self.energy_lost,
                "total_energy_lost": float(sum(self.energy_lost.values())),
                "efficiency": self.efficiency, "time_per_mode": self.time_per_mode,
                "locked_rows": self.locked_rows, "warned_rows": self.warned_rows,
                "negative_split_time": self.negative_split_time}

    def text_report(self) -> str:
        from powergraph.analyses.cycle_report import text_report

        return text_report(self)

    def to_csv(self, path: Any = None) -> str | None:
        from powergraph.analyses.cycle_report import to_csv

        return to_csv(self, path)

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        from powergraph.plot.cycle import plot_cycle

        return plot_cycle(self, ax=ax, **kwargs)


def cycle(model: Model, points: IO[str] | str | os.PathLike | Points,
          keep_going: bool = False) -> CycleResult:
    """Evaluate ``model`` at every row of ``points`` (a CSV path or handle, or
    :class:`Points`); see the module docstring for the columns.

    Parameters
    ----------
    keep_going : bool
        Leave the rows that cannot be solved out of the totals (each keeps its
        ``error: ...`` verdict) instead of refusing the cycle at the first.

    Raises
    ------
    UsageError
        A points file or a row that cannot be solved (without ``keep_going``), no row
        solved at all, or totals beyond the largest float; one line naming the file, and
        the row or column.
    """
    if isinstance(points, Points):
        check_modes(points, model)
    else:
        points = read_points(points, model)
    if not points.columns or not len(points):
        raise UsageError(f"{points.source}: needs a PORT.speed, PORT.power or PORT.torque "
                         "column and a row")
    result = None
    if sweepable(model, points):
        try:
            result = CycleResult(model.name, sweep_rows(model, points, keep_going), "sweep")
        except RowError:
            raise
        except (UsageError, ModelError, *NUMERICAL):
            pass    # a combination the compiled sweep does not take: solve row by row
    if result is None:
        result = CycleResult(model.name, single_rows(model, points, keep_going),
                             "single solves")
    _check_totals(result, points)
    return result


def _check_totals(result: CycleResult, points: Points) -> None:
    """Refuse a cycle without a row solved, or whose totals are not finite."""
    if len(result.left_out) == len(result.rows):
        first = result.rows[0]
        raise UsageError(f"no row could be solved ({len(result.rows)} row(s)); the first, "
                         f"row {first.file_line}: {first.verdict[7:]}", points.source)
    totals = [result.time, result.energy_in, result.energy_out,
              *result.energy_lost.values()]
    if not all(math.isfinite(t) for t in totals):
        column = points.duration_column
        where = f"{points.source}: column {column!r}" if column else points.source
        raise UsageError(f"{where}: the energies over the cycle overflow (powers times "
                         "durations beyond the largest float, 1.8e308 J)")
