"""The gear table of a train with modes (docs/modes.md): per mode the engaged elements,
ratio, step to the next forward gear, efficiency forward and coasting (back-driven), the
torque of each engaged element over the input torque, the slip speed of each open one
over the input speed, the drag, and the verdict; the spread of the forward gears.

Examples
--------
>>> from powergraph.model import load_model
>>> table = gear_table(load_model("models/ravigneaux_4speed.yaml"))   # doctest: +SKIP
>>> [round(r.ratio, 4) for r in table.rows], round(table.spread, 4)   # doctest: +SKIP
([2.4, 1.4667, 1.0, 0.6667, -2.0], 3.6)
"""
from __future__ import annotations

import dataclasses
from dataclasses import field
from types import MappingProxyType
from typing import Any, Mapping

from powergraph.model.spec import Model
from powergraph.records import record
from powergraph.statics.case import CasePoint, TrainCase


@record
class GearRow:
    """One mode of the table. Ratios are input over output speed; ``step`` is this
    forward gear's ratio over the next forward gear's (None for the last and reverse);
    ``torques`` engaged element torque / input torque (None when indeterminate, or for
    every element when the input torque is zero), ``slips`` open element slip / input
    speed (None for every element when the input stands still); ``efficiency`` None when
    no power passes (``verdict`` says so); ``coast_efficiency`` None when coasting has no
    consistent state or no power passes (``coast_verdict`` says why). ``input_torque``
    (N·m) and ``input_speed`` (rad/s) are what the torques and slips are divided by, None
    when zero (nothing to divide by)."""

    mode: str
    engaged: tuple[str, ...]
    ratio: float
    step: float | None
    efficiency: float | None
    coast_efficiency: float | None
    coast_verdict: str
    torques: Mapping[str, float | None]
    slips: Mapping[str, float | None]
    drag_loss: float
    freewheels: Mapping[str, str]
    verdict: str
    warnings: tuple = ()
    input_torque: float | None = None
    input_speed: float | None = None

    def to_dict(self) -> dict[str, Any]:
        return {"mode": self.mode, "engaged": list(self.engaged), "ratio": self.ratio,
                "step": self.step, "efficiency": self.efficiency,
                "coast_efficiency": self.coast_efficiency,
                "coast_verdict": self.coast_verdict, "element_torques": dict(self.torques),
                "slip_speeds": dict(self.slips), "drag_loss": self.drag_loss,
                "freewheels": dict(self.freewheels), "verdict": self.verdict,
                "warnings": [str(w) for w in self.warnings],
                "input_torque": self.input_torque, "input_speed": self.input_speed}


@record
class GearTable:
    """Every mode of a train; follows the result protocol."""

    model: Model = field(repr=False, compare=False)
    rows: tuple[GearRow, ...]

    @property
    def name(self) -> str:
        return self.model.name

    @property
    def spread(self) -> float | None:
        """Largest over smallest forward ratio (None with fewer than one forward gear)."""
        forward = [r.ratio for r in self.rows if r.ratio > 0]
        return max(forward) / min(forward) if forward else None

    @property
    def warnings(self) -> tuple:
        return tuple(w for r in self.rows for w in r.warnings)

    def to_dict(self) -> dict[str, Any]:
        return {"name": self.name, "modes": [r.to_dict() for r in self.rows],
                "spread": self.spread, "warnings": [str(w) for w in self.warnings]}

    def text_report(self) -> str:
        from powergraph.analyses.gear_table_report import gear_table_report

        return gear_table_report(self)

    def plot(self, ax: Any = None, **kwargs: Any):
        from powergraph.plot.gear_table import plot_gear_table

        return plot_gear_table(self, ax=ax, **kwargs)


def gear_table(model: Model) -> GearTable:
    """Every mode's case (:class:`~powergraph.statics.case.TrainCase`) forward and coasting.

    Parameters
    ----------
    model : Model
        A model with a ``modes`` table (one input, one output).

    Raises
    ------
    ModelError
        ``modes.NAME: ...`` for the first mode that cannot be solved (docs/modes.md).
    """
    if not model.modes:
        from powergraph.errors import ModelError

        raise ModelError("the model has no modes table (docs/modes.md)", "modes")
    rows = [_row(model, mode) for mode in model.modes]
    forward = [i for i, r in enumerate(rows) if r.ratio > 0]
    for i, j in zip(forward, forward[1:]):
        rows[i] = dataclasses.replace(rows[i], step=rows[i].ratio / rows[j].ratio)
    return GearTable(model=model, rows=tuple(rows))


def _row(model: Model, mode: str) -> GearRow:
    forward = TrainCase.of(model, mode).point()
    forward.required()
    result, moded = forward.result, forward.moded
    w_in = result.kinematics.speed(model.inputs[0].component)
    t_in = result.external_torques[result.model.body_of[model.inputs[0].component]]
    w_in = _unless_zero(w_in, result.kinematics.body_speeds.values())
    t_in = _unless_zero(t_in, result.external_torques.values())
    coast_efficiency, coast_verdict = _coast(model, forward)
    torques = {e.name: (None if e.torque is None or t_in is None else e.torque / t_in)
               for e in moded.elements if e.engaged}
    slips = {e.name: None if w_in is None else e.slip_speed / w_in
             for e in moded.elements if not e.engaged}
    return GearRow(mode=mode, engaged=moded.engaged, ratio=result.ratio, step=None,
                   efficiency=result.efficiency, coast_efficiency=coast_efficiency,
                   coast_verdict=coast_verdict, torques=MappingProxyType(torques),
                   slips=MappingProxyType(slips),
                   drag_loss=sum(e.drag_loss for e in moded.elements),
                   freewheels=moded.freewheels, verdict=forward.verdict,
                   warnings=moded.warnings, input_torque=t_in, input_speed=w_in)


def _coast(model: Model, forward: CasePoint) -> tuple[float | None, str]:
    """Coasting's efficiency and verdict (the case back-driven); not solved when no power
    passes forward (the input's power, zero, is what coasting feeds in at the output)."""
    if forward.result.efficiency_note is not None:
        return None, forward.verdict
    coast = TrainCase.of(model, forward.case.mode, backdrive=True).point()
    if coast.result is None or coast.result.efficiency_note is not None:
        return None, coast.verdict
    return coast.result.efficiency, coast.verdict


def _unless_zero(value: float, among) -> float | None:
    """``value``, or None when it is zero on the scale of ``among`` (relative values over
    it are undefined)."""
    scale = max((abs(v) for v in among), default=0.0)
    return None if abs(value) <= 1e-9 * scale else float(value)
