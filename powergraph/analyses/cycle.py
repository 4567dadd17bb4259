"""A train over a duty cycle: one operating point per row, energies over the cycle
(docs/hybrid.md, ``powergraph cycle``).

Rows of a plain train (no machines, no modes, no load-dependent losses) are evaluated at
once by the compiled sweep (:mod:`powergraph.analyses.sweep`), its arrays becoming the
result's columns (``method`` ``sweep``). Rows of a train with machines on buses (and no
``mode`` column, no load-dependent losses) are solved together too
(:mod:`powergraph.analyses.cycle_hybrid`, ``sweep with bus balance``): the single solve's
Newton iteration on the bus balances, over every row at once, each step one call of the
sweep — the THS-II's 10^5 rows in 2-3 s against 18-40 min for a loop of single solves,
660-860 times faster in one run of ``python benchmarks/cycle.py --points 100000 --sample
500`` (docs/performance.md), every row the same as its single solve to about 1e-12.
Rows with a ``mode`` column are each their mode's case
(:mod:`powergraph.analyses.cycle_modes`, ``modes (sweep per gear)``): a gear that does not
depend on the load through its compiled sweep, a mode whose freewheels are decided at each
load row by row. Friction laws and bearing losses take one single solve per row, into
preallocated columns (``single solves``). A row the batched evaluators do not solve is
solved alone, for its reason.

The result holds columns (one numpy array per quantity over the rows: tens of bytes per
row), not a record per row; ``result.rows[i]`` builds row ``i`` as a
:class:`CycleRow` when asked for. The totals are sums over the arrays, in row order.

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
>>> r.method, round(r.energy_in), round(r.efficiency, 6), r.power_in.tolist()
('sweep', 8000, 0.99238, [1000.0, 2000.0])
>>> r.rows[1].verdict, r.rows[1].file_line
('ok', 3)
"""
from __future__ import annotations

import dataclasses
import math
import os
from typing import IO, Any, Iterable, Mapping

import numpy as np

from powergraph.analyses.cycle_columns import (FAILED, LOCKED, SELF_LOCKING, Columns,
                                               CycleRow, CycleRows, FlowNames, frozen,
                                               machine_states, total)
from powergraph.analyses.cycle_points import Points, check_modes, read_points
from powergraph.analyses.cycle_rows import (NUMERICAL, RowError, element_label, single_rows,
                                            solve_losses, sweep_rows, sweepable)
from powergraph.errors import ModelError, UsageError
from powergraph.model.spec import Model
from powergraph.records import record

__all__ = ["CycleResult", "CycleRow", "cycle", "element_label", "solve_losses"]


@record(eq=False, repr=False)
class CycleResult:
    """The cycle's rows, as columns over the rows, and its totals: energies in, out and
    lost per element (J), the cycle efficiency (energy out / energy in), time (s) in all
    and per mode and the rows that lock, over the rows solved; the rows left out (that
    could not be solved) and their time.

    Attributes
    ----------
    name, method : str
        The model's name; ``sweep``, ``sweep with bus balance`` or ``single solves``.
    durations : ndarray
        Each row's duration, s.
    lines : ndarray of int
        Each row's line in the points file.
    mode_codes : ndarray of int or None
        Each row's mode, an index into ``mode_names`` (None without a mode column).
    power_in, power_out, loss : ndarray
        Power entering and leaving the system, and lost, W (0 in a row not solved).
    efficiencies : ndarray
        Each row's efficiency, NaN where undefined (no power passes, or not solved).
    verdict_codes : ndarray of int32
        Each row's verdict, an index into ``verdict_texts``: ``ok``, ``locked``,
        ``self-locking``, ``no power``, then each distinct ``error: ...`` text once
        (codes from :data:`~powergraph.analyses.cycle_columns.FAILED` on).
    losses : Mapping[str, ndarray]
        Loss of each element (mesh, coupling, bearing, drag, machine), W, NaN in the rows
        without that element.
    electrical_share : ndarray
        With machines, the electrical path's share (docs/hybrid.md); NaN where none.
    negative_split, with_machines : ndarray of bool
        Power circulates through a bus; the row was solved with machines (elsewhere a
        row's ``negative_split`` is None).
    warnings : Mapping[str, ndarray of int]
        ``{warning code: sorted row indices}`` of the rows whose solve warned.
    port_power : Mapping[str, ndarray]
        With machines, each other port's power, W, by its name (or component id): fed
        in at an input, taken out at an output (the model's sign); NaN in a row not
        solved. Empty without machines.
    machines : Mapping[str, Mapping[str, ndarray]]
        With machines, each machine's ``speed`` (rad/s), ``torque`` (N·m), ``power``
        (mechanical, into the train) and ``electrical_power`` (drawn from its bus), W;
        its state is the sign of ``power`` (:meth:`machine_states`); NaN speed in a row
        whose mode leaves it inactive.
    battery_power : Mapping[str, ndarray]
        With machines, each bus's battery power into the bus, W (given, or what the
        machines draw for a free battery).
    """

    name: str
    method: str
    durations: np.ndarray
    lines: np.ndarray
    mode_names: tuple[str, ...]
    mode_codes: np.ndarray | None
    power_in: np.ndarray
    power_out: np.ndarray
    loss: np.ndarray
    efficiencies: np.ndarray
    verdict_codes: np.ndarray
    verdict_texts: tuple[str, ...]
    losses: Mapping[str, np.ndarray]
    electrical_share: np.ndarray
    negative_split: np.ndarray
    with_machines: np.ndarray
    warnings: Mapping[str, np.ndarray]
    port_power: Mapping[str, np.ndarray] = dataclasses.field(default_factory=dict)
    machines: Mapping[str, Mapping[str, np.ndarray]] = dataclasses.field(default_factory=dict)
    battery_power: Mapping[str, np.ndarray] = dataclasses.field(default_factory=dict)

    @classmethod
    def of(cls, name: str, method: str, points: Points, columns: Columns) -> "CycleResult":
        """The result of the filled ``columns`` of ``points`` (whose durations, lines and
        mode codes it shares)."""
        if (columns.verdict_codes < 0).any():
            raise AssertionError("a row of the cycle was neither solved nor failed")
        arrays = {key: frozen(getattr(columns, key)) for key in (
            "power_in", "power_out", "loss", "efficiencies", "verdict_codes",
            "electrical_share", "negative_split", "with_machines")}
        return cls(name=name, method=method, durations=frozen(points.durations),
                   lines=frozen(points.lines), mode_names=tuple(points.mode_names),
                   mode_codes=(None if points.mode_codes is None else
                               frozen(points.mode_codes)),
                   verdict_texts=tuple(columns.verdict_texts),
                   losses={k: frozen(v) for k, v in columns.losses.items()},
                   warnings={k: frozen(v) for k, v in columns.warnings().items()},
                   port_power={k: frozen(v) for k, v in columns.port_power.items()},
                   machines={name: {k: frozen(v) for k, v in m.items()}
                             for name, m in columns.machines.items()},
                   battery_power={k: frozen(v) for k, v in columns.battery_power.items()},
                   **arrays)

    @classmethod
    def from_rows(cls, name: str, rows: Iterable[CycleRow], method: str) -> "CycleResult":
        """The result holding ``rows`` (records, in order; ``index`` is their place)."""
        rows = tuple(rows)
        names = [dict.fromkeys(n for r in rows for n in getattr(r, key))
                 for key in ("port_power", "machines", "battery_power")]
        columns = Columns(len(rows), FlowNames(*map(tuple, names)))
        for i, r in enumerate(rows):
            if r.failed:
                columns.fail(i, r.verdict)
            else:
                columns.set(i, r.power_in, r.power_out, r.loss, r.efficiency, r.verdict,
                            r.losses, r.electrical_share, r.negative_split, r.warnings)
                columns.put_flows(i, r.port_power, r.machines, r.battery_power)
        names = tuple(dict.fromkeys(r.mode for r in rows if r.mode is not None))
        if names and any(r.mode is None for r in rows):
            raise ValueError("rows with a mode and rows without one")
        points = Points(columns=(), values=(), durations=np.array([r.duration for r in rows]),
                        lines=np.array([r.file_line for r in rows], dtype=np.int64),
                        mode_names=names, mode_codes=(np.array(
                            [names.index(r.mode) for r in rows], dtype=np.uint32)
                            if names else None))
        return cls.of(name, method, points, columns)

    def __repr__(self) -> str:
        return (f"CycleResult(name={self.name!r}, method={self.method!r}, "
                f"rows={len(self.durations)})")

    @property
    def rows(self) -> CycleRows:
        """The rows as :class:`CycleRow` records, each built when read."""
        return CycleRows(self)

    def row(self, i: int) -> CycleRow:
        """Row ``i`` as a record (negative ``i`` from the end)."""
        n, asked = len(self.durations), int(i)
        i = asked + n if asked < 0 else asked
        if not 0 <= i < n:
            raise IndexError(f"row {asked} of a cycle of {n} rows")
        optional = lambda value: None if math.isnan(value) else value  # noqa: E731
        return CycleRow(
            index=i, duration=float(self.durations[i]),
            mode=None if self.mode_codes is None else self.mode_names[self.mode_codes[i]],
            power_in=float(self.power_in[i]), power_out=float(self.power_out[i]),
            loss=float(self.loss[i]), efficiency=optional(float(self.efficiencies[i])),
            verdict=self.verdict_texts[self.verdict_codes[i]],
            losses={label: float(v[i]) for label, v in self.losses.items()
                    if not math.isnan(v[i])},
            electrical_share=optional(float(self.electrical_share[i])),
            negative_split=bool(self.negative_split[i]) if self.with_machines[i] else None,
            warnings=tuple(code for code, rows in self.warnings.items()
                           if _holds(rows, i)),
            line=int(self.lines[i]),
            port_power=_present({k: float(v[i]) for k, v in self.port_power.items()}),
            machines={name: {k: float(v[i]) for k, v in m.items()}
                      for name, m in self.machines.items() if not math.isnan(m["power"][i])},
            battery_power=_present({k: float(v[i]) for k, v in self.battery_power.items()}))

    def machine_states(self, name: str) -> list[str]:
        """Machine ``name``'s state per row: ``motoring``, ``generating``, ``idle``, or
        ``inactive`` (its row's mode switches it off: no speed), or an empty text in a
        row not solved (the sign of its mechanical power)."""
        return machine_states(self.machines[name]["power"], self.machines[name]["speed"])

    @property
    def failed(self) -> np.ndarray:
        """The rows that could not be solved (bool per row), left out of the totals."""
        return self.verdict_codes >= FAILED

    @property
    def time(self) -> float:
        """Time (s) of the rows solved."""
        return total(self.durations[~self.failed])

    @property
    def left_out(self) -> list[int]:
        """Indices of the rows that could not be solved, left out of the totals."""
        return np.flatnonzero(self.failed).tolist()

    @property
    def left_out_time(self) -> float:
        return total(self.durations[self.failed])

    @property
    def energy_in(self) -> float:
        return self._energy(self.power_in)

    @property
    def energy_out(self) -> float:
        return self._energy(self.power_out)

    @property
    def energy_lost(self) -> dict[str, float]:
        """``{element: J}``: each mesh, coupling, bearing, drag and machine."""
        return {label: self._energy(np.where(np.isnan(w), 0.0, w))
                for label, w in self.losses.items()}

    def _energy(self, power: np.ndarray) -> float:
        """Σ power × duration over the rows, in row order (J)."""
        with np.errstate(over="ignore", invalid="ignore"):
            return total(power * self.durations)

    @property
    def battery_energy(self) -> dict[str, float]:
        """``{bus: J}``: the energy each battery gives its bus over the rows solved
        (< 0: it is charged)."""
        return {bus: self._energy(np.where(np.isnan(w), 0.0, w))
                for bus, w in self.battery_power.items()}

    @property
    def efficiency(self) -> float | None:
        return self.energy_out / self.energy_in if self.energy_in > 0 else None

    @property
    def time_per_mode(self) -> dict[str, float]:
        """``{mode: s}`` of the rows solved, the modes in the order of their first row
        (``-`` without a mode column)."""
        solved = ~self.failed
        durations = self.durations[solved]
        if self.mode_codes is None:
            return {"-": total(durations)} if len(durations) else {}
        codes = self.mode_codes[solved]
        found, first = np.unique(codes, return_index=True)
        return {self.mode_names[c]: total(durations[codes == c])
                for c in found[np.argsort(first)].tolist()}

    @property
    def negative_split_time(self) -> float:
        """Time (s) the machines spend in a negative split (power circulating through a
        bus)."""
        return total(self.durations[self.negative_split])

    @property
    def warned_rows(self) -> dict[str, list[int]]:
        """``{warning code: row indices}`` of the rows whose solve warned."""
        return {code: rows.tolist() for code, rows in self.warnings.items()}

    @property
    def locked_rows(self) -> list[int]:
        codes = self.verdict_codes
        return np.flatnonzero((codes == LOCKED) | (codes == SELF_LOCKING)).tolist()

    def to_dict(self) -> dict[str, Any]:
        from powergraph.analyses.cycle_report import row_dicts

        lost = self.energy_lost
        return {"name": self.name, "method": self.method, "rows": row_dicts(self),
                "time": self.time,
                "left_out": {"rows": int(self.failed.sum()), "time": self.left_out_time},
                "energy_in": self.energy_in, "energy_out": self.energy_out,
                "energy_lost": lost, "total_energy_lost": float(sum(lost.values())),
                "efficiency": self.efficiency, "time_per_mode": self.time_per_mode,
                "locked_rows": self.locked_rows, "warned_rows": self.warned_rows,
                "negative_split_time": self.negative_split_time,
                "battery_energy": self.battery_energy}

    def text_report(self) -> str:
        from powergraph.analyses.cycle_report import text_report

        return text_report(self)

    def to_csv(self, path: Any = None) -> str | None:
        from powergraph.analyses.cycle_report import to_csv

        return to_csv(self, path)

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        from powergraph.plot.cycle import plot_cycle

        return plot_cycle(self, ax=ax, **kwargs)


def _present(values: dict[str, float]) -> dict[str, float]:
    """``values`` without the NaN ones (a row not solved)."""
    return {k: v for k, v in values.items() if not math.isnan(v)}


def _holds(rows: np.ndarray, i: int) -> bool:
    """Whether the sorted indices ``rows`` hold ``i``."""
    k = int(np.searchsorted(rows, i))
    return k < len(rows) and int(rows[k]) == i


def _single_rows(model: Model, points: Points, keep_going: bool = True) -> CycleResult:
    """Every row by its single solve (``benchmarks/cycle.py`` times them)."""
    return CycleResult.of(model.name, "single solves", points,
                          single_rows(model, points, keep_going))


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
    from powergraph.analyses.cycle_hybrid import METHOD, batchable, hybrid_rows

    result = None
    from powergraph.analyses.cycle_modes import METHOD as IN_MODES, mode_rows

    batched = (("sweep", sweep_rows) if sweepable(model, points) else
               (METHOD, hybrid_rows) if batchable(model, points) else
               (IN_MODES, mode_rows) if points.mode_codes is not None else None)
    if batched is not None:
        method, rows = batched
        try:
            result = CycleResult.of(model.name, method, points,
                                    rows(model, points, keep_going))
        except RowError:
            raise
        except (UsageError, ModelError, *NUMERICAL):
            pass    # a combination the compiled sweep does not take: solve row by row
    if result is None:
        result = _single_rows(model, points, keep_going)
    _check_totals(result, points)
    return result


def _check_totals(result: CycleResult, points: Points) -> None:
    """Refuse a cycle without a row solved, or whose totals are not finite."""
    if result.failed.all():
        raise UsageError(f"no row could be solved ({len(result.durations)} row(s)); the "
                         f"first, row {result.lines[0]}: "
                         f"{result.verdict_texts[result.verdict_codes[0]][7:]}",
                         points.source)
    totals = [result.time, result.energy_in, result.energy_out,
              *result.energy_lost.values()]
    if not all(math.isfinite(t) for t in totals):
        column = points.duration_column
        where = f"{points.source}: column {column!r}" if column else points.source
        raise UsageError(f"{where}: the energies over the cycle overflow (powers times "
                         "durations beyond the largest float, 1.8e308 J)")
