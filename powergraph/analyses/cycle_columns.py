"""The rows of a duty cycle held in columns (:mod:`powergraph.analyses.cycle`): one numpy
array per quantity over the rows, tens of bytes per row, filled at once from the
compiled sweep's arrays or row by row by the single solves; and :class:`CycleRow`, one row
as a record, built on demand from the columns.

A train with machines also has, per row, each machine's speed, torque, mechanical and
electrical power (:data:`MACHINE_KEYS`; its state is the sign of its power), each bus's
battery power and each other port's power (the model's sign: fed in at an input, taken
out at an output): NaN in a row not solved.

Verdicts are codes into texts: :data:`VERDICTS` first (``ok``, ``locked``,
``self-locking``, ``no power``), then each distinct ``error: ...`` text once. A row's
losses are one column per element, NaN where the row has no such element (a coupling
without loss in a single solve, a row that cannot be solved).

Examples
--------
>>> columns = Columns(2)
>>> columns.fill(slice(0, 2), np.array([True, False]), np.array([10.0, 0.0]),
...              np.array([9.0, 0.0]), np.array([1.0, 0.0]), np.array([0.9, np.nan]),
...              np.array([OK, OK]), {"links[0] mesh S-P": np.array([1.0, 0.0])})
>>> columns.fail(1, "error: no speed")
>>> columns.verdict_codes.tolist(), columns.verdict_texts, columns.losses["links[0] mesh S-P"]
([0, 4], ['ok', 'locked', 'self-locking', 'no power', 'error: no speed'], array([ 1., nan]))
>>> total(np.array([0.1, 0.2, 0.3])) == sum([0.1, 0.2, 0.3])
True
"""
from __future__ import annotations

import math
from dataclasses import field
from typing import Any, Iterable, Mapping, NamedTuple, Sequence

import numpy as np

from powergraph.model.spec import Model
from powergraph.records import record
from powergraph.statics.verdicts import VERDICTS

#: Codes into :data:`VERDICTS` (``powergraph.statics.verdicts``) of a row that was solved;
#: codes from ``len(VERDICTS)`` on are the ``error: ...`` texts of rows that could not be.
OK, LOCKED, SELF_LOCKING, NO_POWER = range(4)
FAILED = len(VERDICTS)
#: A machine's quantities per row: rad/s, N·m, W into the train, W drawn from its bus.
MACHINE_KEYS = ("speed", "torque", "power", "electrical_power")


class FlowNames(NamedTuple):
    """The names of a cycle's per-row flows: the ports other than machines, the machines
    (each as the points file names it: its ``name``, else its component id) and the
    buses. Empty for a train without machines."""

    ports: tuple[str, ...] = ()
    machines: tuple[str, ...] = ()
    buses: tuple[str, ...] = ()


#: The flows of a train without machines: none.
NO_FLOWS = FlowNames()


def flow_names(model: Model) -> FlowNames:
    """The flows a cycle of ``model`` carries per row (none without machines)."""
    if not model.machines:
        return NO_FLOWS
    return FlowNames(tuple(port_label(p) for p in model.ports if not p.is_machine),
                     tuple(port_label(p) for p in model.machines), tuple(model.buses))


def port_label(port: Any) -> str:
    """A port as the points file names it: its ``name``, else its component id."""
    return port.name or str(port.component)


def machine_state(power: float, speed: float = 0.0) -> str:
    """``motoring``, ``generating`` or ``idle``, by the sign of the mechanical power
    (:attr:`powergraph.statics.machines.MachineFlow.state`); ``inactive`` without a speed
    (NaN: a machine its row's mode switches off, docs/modes.md)."""
    return machine_states(np.array([power]), np.array([speed]))[0]


def machine_states(power: np.ndarray, speed: np.ndarray) -> list[str]:
    """:func:`machine_state` of each power and speed, an empty text for a NaN power (a
    row not solved).

    >>> machine_states(np.array([5.0, -1.0, 0.0, np.nan, 0.0]),
    ...                np.array([1.0, 1.0, 0.0, np.nan, np.nan]))
    ['motoring', 'generating', 'idle', '', 'inactive']
    """
    codes = np.where(power > 0, 1, np.where(power < 0, 2, np.where(power == 0, 3, 0)))
    codes[(codes == 3) & np.isnan(speed)] = 4
    return _STATES[codes].tolist()


_STATES = np.array(["", "motoring", "generating", "idle", "inactive"], dtype=object)


@record
class CycleRow:
    """One operating point: its duration (s), mode, powers entering and leaving the
    system (W), loss (W), efficiency (None when no power passes) and verdict
    (``ok``, ``locked``, ``self-locking``, ``no power`` or ``error: ...``)."""

    index: int
    duration: float
    mode: str | None
    power_in: float
    power_out: float
    loss: float
    efficiency: float | None
    verdict: str
    losses: Mapping[str, float] = field(repr=False, default_factory=dict)
    #: With machines: the electrical path's share and whether power circulates through
    #: a bus (docs/hybrid.md); None otherwise.
    electrical_share: float | None = None
    negative_split: bool | None = None
    #: Codes of the row's own warnings (``outside-map``, ``role-reversed``...: the
    #: solve's, not the model file's), each a reason to doubt that row's numbers.
    warnings: tuple[str, ...] = ()
    #: The row's line in the points file (None: the row after the header, ``index + 2``).
    line: int | None = None
    #: With machines: each other port's power (W, fed in at an input, taken out at an
    #: output), each machine's :data:`MACHINE_KEYS` and each bus's battery power (W into
    #: the bus); empty otherwise and in a row not solved.
    port_power: Mapping[str, float] = field(repr=False, default_factory=dict)
    machines: Mapping[str, Mapping[str, float]] = field(repr=False, default_factory=dict)
    battery_power: Mapping[str, float] = field(repr=False, default_factory=dict)

    @property
    def failed(self) -> bool:
        """The row could not be solved (``error: ...``): it is left out of the totals."""
        return self.verdict.startswith("error")

    @property
    def file_line(self) -> int:
        """The row's line in the points file."""
        return self.index + 2 if self.line is None else self.line

    def to_dict(self) -> dict[str, Any]:
        return {"row": self.index, "line": self.file_line, "duration": self.duration,
                "mode": self.mode, "power_in": self.power_in, "power_out": self.power_out,
                "loss": self.loss, "efficiency": self.efficiency, "verdict": self.verdict,
                "losses": dict(self.losses), "electrical_share": self.electrical_share,
                "negative_split": self.negative_split, "warnings": list(self.warnings),
                "port_power": dict(self.port_power),
                "machines": {name: {**{k: _number(m[k]) for k in MACHINE_KEYS},
                                    "state": machine_state(m["power"], m["speed"])}
                             for name, m in self.machines.items()},
                "buses": {bus: {"battery_power": w} for bus, w in self.battery_power.items()}}


def _number(value: float) -> float | None:
    """``value``, None for NaN (an inactive machine's speed)."""
    return None if math.isnan(value) else value


class Columns:
    """The per-row columns of a cycle of ``n`` rows, preallocated, as they are filled:
    a row's verdict code is -1 until :meth:`fill` or :meth:`set` solves it or :meth:`fail`
    gives its reason."""

    def __init__(self, n: int, flows: FlowNames = NO_FLOWS) -> None:
        self.n = n
        self.port_power = {name: np.full(n, np.nan) for name in flows.ports}
        self.machines = {name: {key: np.full(n, np.nan) for key in MACHINE_KEYS}
                         for name in flows.machines}
        self.battery_power = {bus: np.full(n, np.nan) for bus in flows.buses}
        self.power_in, self.power_out, self.loss = np.zeros(n), np.zeros(n), np.zeros(n)
        self.efficiencies, self.electrical_share = np.full(n, np.nan), np.full(n, np.nan)
        self.verdict_texts = list(VERDICTS)
        self.verdict_codes = np.full(n, -1, dtype=np.int32)
        self.negative_split = np.zeros(n, dtype=bool)
        self.with_machines = np.zeros(n, dtype=bool)
        self.losses: dict[str, np.ndarray] = {}
        self._texts = {text: code for code, text in enumerate(self.verdict_texts)}
        self._warned: dict[str, tuple[list[np.ndarray], list[int]]] = {}

    def verdict_code(self, text: str) -> int:
        """The code of a verdict text (a new error text gets the next code)."""
        code = self._texts.get(text)
        if code is None:
            code = self._texts[text] = len(self.verdict_texts)
            self.verdict_texts.append(text)
        return code

    def _loss_column(self, label: str) -> np.ndarray:
        if label not in self.losses:
            self.losses[label] = np.full(self.n, np.nan)
        return self.losses[label]

    def fill(self, part: slice | np.ndarray, solved: np.ndarray, power_in: np.ndarray,
             power_out: np.ndarray, loss: np.ndarray, efficiencies: np.ndarray,
             verdicts: np.ndarray, losses: Mapping[str, np.ndarray]) -> None:
        """The rows ``solved`` (a mask over the rows ``part``: a slice or row indices),
        solved at once: their values from the arrays over ``part``."""
        for target, values in ((self.power_in, power_in), (self.power_out, power_out),
                               (self.loss, loss), (self.efficiencies, efficiencies),
                               (self.verdict_codes, verdicts)):
            target[part] = np.where(solved, values, target[part])
        if solved.any():
            for label, values in losses.items():
                column = self._loss_column(label)
                column[part] = np.where(solved, values, column[part])

    def put(self, rows: np.ndarray, power_in: np.ndarray, power_out: np.ndarray,
            loss: np.ndarray, efficiencies: np.ndarray, verdicts: np.ndarray,
            losses: Mapping[str, np.ndarray], electrical_share: np.ndarray,
            negative_split: np.ndarray) -> None:
        """The rows ``rows`` (indices), solved at once with machines: their values from
        the arrays over them (a loss NaN in a row without that element)."""
        for target, values in ((self.power_in, power_in), (self.power_out, power_out),
                               (self.loss, loss), (self.efficiencies, efficiencies),
                               (self.verdict_codes, verdicts),
                               (self.electrical_share, electrical_share),
                               (self.negative_split, negative_split)):
            target[rows] = values
        self.with_machines[rows] = True
        for label, values in losses.items():
            if label in self.losses or not np.isnan(values).all():
                self._loss_column(label)[rows] = values

    def flow_arrays(self) -> list[np.ndarray]:
        """Every flow column (ports, machines, buses)."""
        return [*self.port_power.values(), *self.battery_power.values(),
                *(a for m in self.machines.values() for a in m.values())]

    def put_flows(self, rows: np.ndarray | int, port_power: Mapping[str, Any],
                  machines: Mapping[str, Mapping[str, Any]],
                  battery_power: Mapping[str, Any]) -> None:
        """The flows of the rows ``rows`` (indices, or one row): values or arrays over
        them, by name (a name the columns lack is an error)."""
        for name, values in port_power.items():
            self.port_power[name][rows] = values
        for name, quantities in machines.items():
            for key in MACHINE_KEYS:
                self.machines[name][key][rows] = quantities[key]
        for bus, values in battery_power.items():
            self.battery_power[bus][rows] = values

    def set(self, i: int, power_in: float, power_out: float, loss: float,
            efficiency: float | None, verdict: str, losses: Mapping[str, float],
            electrical_share: float | None = None, negative_split: bool | None = None,
            warnings: Iterable[str] = ()) -> None:
        """Row ``i``, solved by one single solve (its flows by :meth:`put_flows`)."""
        self.power_in[i], self.power_out[i], self.loss[i] = power_in, power_out, loss
        self.efficiencies[i] = math.nan if efficiency is None else efficiency
        self.verdict_codes[i] = self.verdict_code(verdict)
        for label, value in losses.items():
            self._loss_column(label)[i] = value
        self.electrical_share[i] = math.nan if electrical_share is None else electrical_share
        self.with_machines[i] = negative_split is not None
        self.negative_split[i] = bool(negative_split)
        for code in warnings:
            self._warned.setdefault(code, ([], []))[1].append(i)

    def fail(self, i: int, verdict: str) -> None:
        """Row ``i`` cannot be solved: ``verdict`` is ``error: <reason>``."""
        self.power_in[i] = self.power_out[i] = self.loss[i] = 0.0
        self.efficiencies[i] = self.electrical_share[i] = math.nan
        self.verdict_codes[i] = self.verdict_code(verdict)
        self.with_machines[i] = self.negative_split[i] = False
        for column in [*self.losses.values(), *self.flow_arrays()]:
            column[i] = math.nan

    def warn(self, code: str, rows: np.ndarray) -> None:
        """The rows (indices) whose solve warned ``code``."""
        if len(rows):
            self._warned.setdefault(code, ([], []))[0].append(np.asarray(rows, dtype=np.int64))

    def warnings(self) -> dict[str, np.ndarray]:
        """``{code: sorted row indices}``, the codes in the order of their first row."""
        out = {code: np.unique(np.concatenate([*arrays, np.array(rows, dtype=np.int64)]))
               for code, (arrays, rows) in self._warned.items()}
        return {code: out[code] for code in sorted(out, key=lambda c: int(out[c][0]))}


def frozen(array: np.ndarray) -> np.ndarray:
    """A read-only view of ``array`` (the array itself stays as it is)."""
    view = array.view()
    view.flags.writeable = False
    return view


def total(values: np.ndarray) -> float:
    """The sum of ``values`` one after the other from 0, in row order, as Python's
    ``sum`` over the rows adds them (numpy's ``sum`` adds pairwise, which differs in the
    last bits): the totals of a cycle are those of a loop over its rows."""
    if not len(values):
        return 0.0
    with np.errstate(over="ignore", invalid="ignore"):
        return 0.0 + float(np.cumsum(values)[-1])


class CycleRows(Sequence):
    """The rows of a cycle as :class:`CycleRow` records, each built when asked for
    (``result.rows[i]``, iteration): the result holds columns, not records."""

    def __init__(self, result: Any) -> None:
        self._result = result

    def __len__(self) -> int:
        return len(self._result.durations)

    def __getitem__(self, index):   # type: ignore[override]
        if isinstance(index, slice):
            return tuple(self._result.row(i) for i in range(*index.indices(len(self))))
        return self._result.row(index)

    def __repr__(self) -> str:
        return f"<{len(self)} rows of the cycle {self._result.name!r}>"
