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

from powergraph.analyses.gear_relation import SpeedRelation, speed_relation
from powergraph.model.spec import Model
from powergraph.records import record
from powergraph.statics.case import CasePoint, TrainCase


@record
class GearRow:
    """One mode of the table. Ratios are input over output speed (for a train with
    machines, the 1-DOF mode's driving port's over the output's; None for a mode of more
    than one DOF, whose ``relation`` says how the output's speed follows the driving
    ports'); ``step`` is this
    forward gear's ratio over the next forward gear's (None for the last and reverse);
    ``torques`` engaged element torque / input torque (None when indeterminate, or for
    every element when the input torque is zero), ``slips`` open element slip / input
    speed (None for every element when the input stands still); ``efficiency`` None when
    no power passes (``verdict`` says so); ``coast_efficiency`` None when coasting has no
    consistent state or no power passes (``coast_verdict`` says why). ``input_torque``
    (N·m) and ``input_speed`` (rad/s) are what the torques and slips are divided by, None
    when zero (nothing to divide by). ``dof``, ``inactive`` (the ports the mode leaves
    inactive), ``machines`` (each machine at the mode's point, a
    :class:`~powergraph.statics.machines.MachineFlow`: speed, torque, power, state),
    ``buses`` (battery power into each bus, W), ``electrical_share`` and
    ``element_torques`` (N·m, the engaged elements') / ``slip_speeds`` (rad/s, the open
    ones', None beside an idle member) are those of ``solve --mode`` at the same point."""

    mode: str
    engaged: tuple[str, ...]
    ratio: float | None
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
    dof: int = 1
    inactive: tuple[str, ...] = ()
    relation: SpeedRelation | None = None
    machines: tuple = ()
    buses: Mapping[str, float] = field(default_factory=lambda: MappingProxyType({}))
    electrical_share: float | None = None
    element_torques: Mapping[str, float | None] = field(
        default_factory=lambda: MappingProxyType({}))
    slip_speeds: Mapping[str, float | None] = field(
        default_factory=lambda: MappingProxyType({}))
    raw: Any = field(default=str, repr=False, compare=False)

    def to_dict(self) -> dict[str, Any]:
        return {"mode": self.mode, "dof": self.dof, "engaged": list(self.engaged),
                "inactive": list(self.inactive),
                "relation": None if self.relation is None else self.relation.to_dict(),
                "machines": [m.to_dict(self.raw) for m in self.machines],
                "buses": {name: {"battery_power": p} for name, p in self.buses.items()},
                "electrical_share": self.electrical_share,
                "shift_torques": dict(self.element_torques),
                "shift_slips": dict(self.slip_speeds), "ratio": self.ratio,
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
        forward = [r.ratio for r in self.rows if r.ratio is not None and r.ratio > 0]
        return max(forward) / min(forward) if forward else None

    @property
    def hybrid(self) -> bool:
        """The train has machines, or a mode of other than 1 DOF or with inactive ports:
        the report shows each mode's DOF, relation and machines."""
        return bool(self.model.machines) or any(r.dof != 1 or r.inactive
                                                 for r in self.rows)

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
        A model with a ``modes`` table.

    Raises
    ------
    ModelError
        ``modes.NAME: ...`` for the first mode that cannot be solved (docs/modes.md).

    Examples
    --------
    >>> from powergraph.model import load_model
    >>> table = gear_table(load_model("models/volt_gen1.yaml"))
    >>> [(r.mode, r.dof) for r in table.rows]
    [('power split', 2), ('series', 2), ('one-motor EV', 1), ('two-motor EV', 2)]
    >>> round(table.rows[2].ratio, 4), table.rows[2].relation.text()
    (7.0054, 'ratio 7.0054 (MG-B : wheels)')
    >>> table.rows[1].relation.text()
    'wheels = 0.1427·MG-B'
    """
    if not model.modes:
        from powergraph.errors import ModelError

        raise ModelError("the model has no modes table (docs/modes.md)", "modes")
    rows = [_row(model, mode) for mode in model.modes]
    forward = [i for i, r in enumerate(rows) if r.ratio is not None and r.ratio > 0]
    for i, j in zip(forward, forward[1:]):
        rows[i] = dataclasses.replace(rows[i], step=rows[i].ratio / rows[j].ratio)
    return GearTable(model=model, rows=tuple(rows))


def _row(model: Model, mode: str) -> GearRow:
    from powergraph.statics.machine_report import electrical_share

    forward = TrainCase.of(model, mode).point()
    forward.required()
    result, moded = forward.result, forward.moded
    solved = result.model                     # the train in the mode, at its point
    relation = speed_relation(solved)
    ratio = _ratio(result, relation)
    first = solved.inputs[0] if solved.inputs else None
    w_in = t_in = None
    if first is not None:
        w_in = _unless_zero(result.kinematics.speed(first.component),
                            result.kinematics.body_speeds.values())
        t_in = _unless_zero(result.port_torque(first.index),
                            result.external_torques.values())
    coast_efficiency, coast_verdict = _coast(model, forward)
    torques = {e.name: (None if e.torque is None or t_in is None else e.torque / t_in)
               for e in moded.elements if e.engaged}
    slips = {e.name: None if w_in is None or e.slip_speed is None else e.slip_speed / w_in
             for e in moded.elements if not e.engaged}
    return GearRow(mode=mode, engaged=moded.engaged, ratio=ratio, step=None,
                   efficiency=result.efficiency, coast_efficiency=coast_efficiency,
                   coast_verdict=coast_verdict, torques=MappingProxyType(torques),
                   slips=MappingProxyType(slips),
                   drag_loss=sum(e.drag_loss for e in moded.elements),
                   freewheels=moded.freewheels, verdict=forward.verdict,
                   warnings=moded.warnings, input_torque=t_in, input_speed=w_in,
                   dof=result.kinematics.dof, inactive=moded.inactive, relation=relation,
                   machines=tuple(result.machines),
                   buses=MappingProxyType({n: b.battery_power
                                           for n, b in result.buses.items()}),
                   electrical_share=electrical_share(result) if result.machines else None,
                   element_torques=MappingProxyType({e.name: e.torque for e in moded.elements
                                                     if e.engaged}),
                   slip_speeds=MappingProxyType({e.name: e.slip_speed
                                                 for e in moded.elements if not e.engaged}),
                   raw=solved.raw_id)


def _ratio(result, relation: SpeedRelation | None) -> float | None:
    """Input over output speed for a 1-DOF mode with one input and one output (the
    solve's ratio); else the driving port's over the output's of a 1-DOF relation, from
    the point's speeds; None for a mode of more DOF."""
    if result.kinematics.dof != 1:
        return None
    if result.ratio is not None:
        return result.ratio
    if relation is None or relation.ratio is None:
        return None
    names = {p.name or f"ports[{p.index}]": p for p in result.model.ports}
    reference, output = names[relation.terms[0][0]], names[relation.output]
    w_out = result.kinematics.speed(output.component)
    return result.kinematics.speed(reference.component) / w_out if w_out else None


#: The coasting verdict of a train with machines (it regenerates through them: a mode
#: with a negative output power says how).
NOT_COASTED = "not solved (a train with machines: give a mode a negative output power)"


def _coast(model: Model, forward: CasePoint) -> tuple[float | None, str]:
    """Coasting's efficiency and verdict (the case back-driven); not solved when no power
    passes forward (the input's power, zero, is what coasting feeds in at the output),
    nor for a train with machines."""
    if model.machines:
        return None, NOT_COASTED
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
