"""A train over a duty cycle: one operating point per row, energies over the cycle
(docs/hybrid.md, ``powergraph cycle``).

Rows of a plain train (no machines, no modes, no load-dependent losses) are evaluated at
once by the compiled sweep (:mod:`powergraph.analyses.sweep`); the others — machines on
buses, a ``mode`` column, friction laws and bearing losses — by one single solve per row.
``CycleResult.method`` says which.

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

from dataclasses import field
from typing import IO, Any, Mapping

import numpy as np

from powergraph.errors import ModelError, UsageError
from powergraph.model.spec import Model
from powergraph.analyses.cycle_points import Points, as_dict, read_points
from powergraph.records import record


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

    def to_dict(self) -> dict[str, Any]:
        return {"row": self.index, "duration": self.duration, "mode": self.mode,
                "power_in": self.power_in, "power_out": self.power_out, "loss": self.loss,
                "efficiency": self.efficiency, "verdict": self.verdict,
                "losses": dict(self.losses), "electrical_share": self.electrical_share,
                "negative_split": self.negative_split, "warnings": list(self.warnings)}


@record
class CycleResult:
    """The cycle's rows and totals: energies in, out and lost per element (J), the cycle
    efficiency (energy out / energy in), time per mode (s) and the rows that lock."""

    name: str
    rows: tuple[CycleRow, ...]
    method: str

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


def cycle(model: Model, points: IO[str] | str | Points) -> CycleResult:
    """Evaluate ``model`` at every row of ``points`` (a CSV path or handle, or
    :class:`Points`); see the module docstring for the columns."""
    if not isinstance(points, Points):
        points = read_points(points, model)
    if not points.columns:
        raise UsageError(f"{points.source}: no PORT.speed, PORT.power or PORT.torque column")
    if _sweepable(model, points):
        try:
            return CycleResult(model.name, _sweep_rows(model, points), "sweep")
        except (UsageError, ModelError):
            pass    # a combination the compiled sweep does not take: solve row by row
    return CycleResult(model.name, _single_rows(model, points), "single solves")


def _sweepable(model: Model, points: Points) -> bool:
    return not model.buses and not model.modes and all(m is None for m in points.modes)


def _sweep_rows(model: Model, points: Points) -> tuple[CycleRow, ...]:
    from powergraph.analyses.sweep import STATUS, sweep

    base = _cleared(model, points)
    result = sweep(base, {path: v for (path, _, _), v in zip(points.columns, points.values)},
                   quiet=True)
    labels = {link: element_label(model, link) for link in result.losses}
    p_in = _finite(result.input_power)
    p_out = -_finite(result.output_power)
    entering = (np.maximum(p_in, 0.0) + np.maximum(p_out, 0.0)).tolist()
    leaving = (np.maximum(-p_in, 0.0) + np.maximum(-p_out, 0.0)).tolist()
    losses = {labels[k]: _finite(v).tolist() for k, v in result.losses.items()}
    total = _finite(result.total_loss).tolist()
    efficiency = np.asarray(result.efficiency, dtype=float).tolist()
    status = [STATUS[s] for s in np.asarray(result.status).tolist()]
    locking = np.asarray(result.self_locking).tolist()
    durations = np.asarray(points.durations, dtype=float).tolist()
    reversed_ = _reversed_roles(p_in, p_out).tolist()
    rows = []
    for i in range(len(points)):
        verdict = ("locked" if status[i] == "locked" else
                   "self-locking" if locking[i] else
                   f"error: {status[i]}" if status[i] != "ok" else
                   ("ok" if entering[i] > 0 else "no power"))
        eff = efficiency[i]
        rows.append(CycleRow(
            index=i, duration=durations[i], mode=None, power_in=entering[i],
            power_out=leaving[i], loss=total[i],
            efficiency=eff if math.isfinite(eff) else None, verdict=verdict,
            losses={label: values[i] for label, values in losses.items()},
            warnings=("role-reversed",) if reversed_[i] and verdict == "ok" else ()))
    return tuple(rows)


def _reversed_roles(p_in: np.ndarray, p_out: np.ndarray) -> np.ndarray:
    """Rows whose inputs give power out or whose outputs take power in (powers into the
    train), beyond round-off: the single solve's ``role-reversed`` warning, read from the
    sums over the input and the output ports (the ports themselves for a train with one
    of each)."""
    from powergraph.statics.ports import WARN_FRACTION

    entering = np.maximum(p_in, 0.0) + np.maximum(p_out, 0.0)
    return (p_in < -WARN_FRACTION * entering) | (p_out > WARN_FRACTION * entering)


def _finite(values) -> np.ndarray:
    """``values`` as floats with NaN (a variant not solved) as 0 and no -0."""
    array = np.asarray(values, dtype=float)
    return np.where(np.isfinite(array), array, 0.0) + 0.0


def _zero_nan(value: float) -> float:
    return value + 0.0 if np.isfinite(value) else 0.0


def _cleared(model: Model, points: Points) -> Model:
    """The model with the loads of the ports the points load cleared (a port takes
    power or torque, not both)."""
    for _, index, kind in points.columns:
        if kind in ("power", "torque"):
            model = model.with_port(index, power=None, torque=None)
    return model


def _single_rows(model: Model, points: Points) -> tuple[CycleRow, ...]:
    from powergraph.statics import solve
    from powergraph.statics.machine_report import (boundary_powers, electrical_share,
                                                   negative_split)

    base = _cleared(model, points)
    rows = []
    for i in range(len(points)):
        variant = base.in_mode(points.modes[i]) if points.modes[i] else base
        for path, value in as_dict(points, i).items():
            _, index, kind = path.split(".")
            variant = variant.with_port(int(index), **{kind: value})
        try:
            result = solve(variant)
        except ModelError as error:
            rows.append(CycleRow(i, float(points.durations[i]), points.modes[i], 0.0, 0.0,
                                 0.0, None, f"error: {error}"))
            continue
        crossing = boundary_powers(result)
        verdict = ("locked" if result.lock is not None else
                   "self-locking" if result.self_locking else
                   "no power" if result.efficiency is None else "ok")
        rows.append(CycleRow(
            index=i, duration=float(points.durations[i]), mode=points.modes[i],
            power_in=sum(p for p in crossing if p > 0) + 0.0,
            power_out=-sum(p for p in crossing if p < 0) + 0.0,
            loss=result.total_loss, efficiency=result.efficiency, verdict=verdict,
            losses=solve_losses(result),
            electrical_share=electrical_share(result) if result.machines else None,
            negative_split=negative_split(result) if result.machines else None,
            warnings=_own_warnings(result)))
    return tuple(rows)


def _own_warnings(result) -> tuple[str, ...]:
    """The codes of a row's warnings that the model file does not have by itself."""
    own = result.warnings[len(result.model.warnings):]   # the model's come first
    return tuple(dict.fromkeys(w.code for w in own))


def element_label(model: Model, link: int) -> str:
    """``links[2] mesh S-P``: an element of the loss totals."""
    lk = model.links[link]
    a, b = (model.raw_id(c) for c in lk.between)
    return f"links[{link}] {lk.type} {a}-{b}"


def solve_losses(result) -> dict[str, float]:
    """``{element: W}`` of one solve: its elements, bearings and drags, machines."""
    out = {element_label(result.model, e.link): e.loss for e in result.elements
           if e.kind == "mesh" or e.loss}
    for b in result.bearings:
        out[b.node] = out.get(b.node, 0.0) + b.loss
    for m in result.machines:
        out[f"machine {m.name}"] = m.loss
    return out
