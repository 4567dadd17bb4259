"""The rows of a duty cycle (:mod:`powergraph.analyses.cycle`): each row's powers, losses
and verdict, by the compiled sweep for a plain train (a row it does not solve is solved
alone, for its reason) or by one single solve per row (in the row's mode, the freewheels
decided)."""
from __future__ import annotations

import math
from dataclasses import field
from typing import Any, Mapping

import numpy as np

from powergraph.analyses.cycle_points import Points, as_dict
from powergraph.errors import ModelError, PowerGraphError, UsageError
from powergraph.model.spec import Model
from powergraph.records import record

#: Errors of a numerical procedure (numpy's warnings are errors under the command line).
NUMERICAL = (FloatingPointError, OverflowError, RuntimeWarning)


class RowError(UsageError):
    """A row of the points that cannot be solved (without ``keep_going``)."""


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
                "negative_split": self.negative_split, "warnings": list(self.warnings)}


def refused(points: Points, row: CycleRow) -> RowError:
    """The error for a row that cannot be solved."""
    return RowError(f"{points.source}: row {row.file_line}: cannot be solved: "
                    f"{row.verdict[7:]} (--keep-going, keep_going=True, leaves such rows "
                    "out of the totals)")


def sweepable(model: Model, points: Points) -> bool:
    """A plain train: no machines, no shift elements, no modes (the compiled sweep's)."""
    return not (model.buses or model.shift_elements or points.mode_codes is not None)


def sweep_rows(model: Model, points: Points, keep_going: bool) -> tuple[CycleRow, ...]:
    """The rows through the compiled sweep; a row it does not solve (status other than
    ``ok`` or ``locked``, powers not finite) is solved alone, for its reason."""
    from powergraph.analyses.sweep import STATUS, sweep

    base = _cleared(model, points)
    result = sweep(base, {path: v for (path, _, _), v in zip(points.columns, points.values)},
                   quiet=True)
    labels = {link: element_label(model, link) for link in result.losses}
    p_in, p_out = np.asarray(result.input_power, float), -np.asarray(result.output_power, float)
    status = np.asarray(result.status)
    solved = (((status == STATUS.index("ok")) | (status == STATUS.index("locked")))
              & np.isfinite(p_in) & np.isfinite(p_out)
              & np.isfinite(np.asarray(result.total_loss, float)))
    p_in, p_out = _finite(p_in), _finite(p_out)
    entering = (np.maximum(p_in, 0.0) + np.maximum(p_out, 0.0)).tolist()
    leaving = (np.maximum(-p_in, 0.0) + np.maximum(-p_out, 0.0)).tolist()
    losses = {labels[k]: _finite(v).tolist() for k, v in result.losses.items()}
    total = _finite(result.total_loss).tolist()
    efficiency = np.asarray(result.efficiency, dtype=float).tolist()
    locked = (status == STATUS.index("locked")).tolist()
    locking = np.asarray(result.self_locking).tolist()
    durations, lines = points.durations.tolist(), points.lines.tolist()
    reversed_ = _reversed_roles(p_in, p_out).tolist()
    rows = []
    for i, ok in enumerate(solved.tolist()):
        if not ok:
            rows.append(_single_row(base, points, i, keep_going))
            continue
        verdict = ("locked" if locked[i] else "self-locking" if locking[i] else
                   "ok" if entering[i] > 0 else "no power")
        eff = efficiency[i]
        rows.append(CycleRow(
            index=i, duration=durations[i], mode=None, power_in=entering[i],
            power_out=leaving[i], loss=total[i],
            efficiency=eff if math.isfinite(eff) else None, verdict=verdict,
            losses={label: values[i] for label, values in losses.items()},
            warnings=("role-reversed",) if reversed_[i] and verdict == "ok" else (),
            line=lines[i]))
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


def _cleared(model: Model, points: Points) -> Model:
    """The model with the loads of the ports the points load cleared (a port takes
    power or torque, not both)."""
    for _, index, kind in points.columns:
        if kind in ("power", "torque"):
            model = model.with_port(index, power=None, torque=None)
    return model


def single_rows(model: Model, points: Points,
                keep_going: bool = True) -> tuple[CycleRow, ...]:
    """One single solve per row; without ``keep_going`` the first row that cannot be
    solved is an error."""
    base = _cleared(model, points)
    return tuple(_single_row(base, points, i, keep_going) for i in range(len(points)))


def _single_row(base: Model, points: Points, i: int, keep_going: bool) -> CycleRow:
    """Row ``i`` by the single solve (``base``: the model with the loaded ports cleared)."""
    from powergraph.statics.machine_report import (boundary_powers, electrical_share,
                                                   negative_split)

    mode, duration, line = points.mode(i), float(points.durations[i]), int(points.lines[i])
    try:
        variant = base
        for path, value in as_dict(points, i).items():
            _, index, kind = path.split(".")
            variant = variant.with_port(int(index), **{kind: value})
        result = _solve(variant, mode)
        crossing = boundary_powers(result)
        power_in = sum(p for p in crossing if p > 0) + 0.0
        power_out = -sum(p for p in crossing if p < 0) + 0.0
        if not all(map(math.isfinite, (power_in, power_out, result.total_loss))):
            raise FloatingPointError("the powers are not finite")
    except (PowerGraphError, *NUMERICAL) as error:
        reason = " ".join(str(error).split())
        row = CycleRow(i, duration, mode, 0.0, 0.0, 0.0, None, "error: " + (
            reason if isinstance(error, PowerGraphError) else f"numerical problem ({reason})"),
            line=line)
        if not keep_going:
            raise refused(points, row)
        return row
    verdict = ("locked" if result.lock is not None else
               "self-locking" if result.self_locking else
               "no power" if result.efficiency is None else "ok")
    return CycleRow(
        index=i, duration=duration, mode=mode, power_in=power_in, power_out=power_out,
        loss=result.total_loss, efficiency=result.efficiency, verdict=verdict,
        losses=solve_losses(result),
        electrical_share=electrical_share(result) if result.machines else None,
        negative_split=negative_split(result) if result.machines else None,
        warnings=_own_warnings(result), line=line)


def _solve(model: Model, mode: str | None):
    """The single solve of one row: in its mode, the freewheels decided
    (:func:`~powergraph.statics.modes.solve_mode`), when the model has shift elements."""
    from powergraph.statics import solve
    from powergraph.statics.modes import solve_mode

    if mode is None and not model.shift_elements:
        return solve(model)
    moded = solve_mode(model, mode)
    if moded.result is None:
        raise ModelError(f"mode {mode}: {moded.verdict}" if mode else moded.verdict)
    return moded.result


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
