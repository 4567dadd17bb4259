"""Results of a power-flow solve: frozen dataclasses indexed by the model's ids.

The JSON object of ``powergraph solve --json`` is described in docs/format.md.
"""
from __future__ import annotations

from dataclasses import field
from functools import cached_property
from typing import Any, Mapping

from powergraph.errors import Caveat
from powergraph.kinematics import Kinematics
from powergraph.model.spec import Model
from powergraph.records import record
from powergraph.statics.ports import PortFlow, flow_efficiency, port_flows, result_caveats


@record
class ElementFlow:
    """Torques, direction and loss of one mesh or coupling.

    ``torques`` is the torque the element applies to each of its bodies (N·m);
    ``driver`` the gear that feeds power into it in its carrier's frame (None when no
    power passes); ``carrier_frame_power`` that power, the mesh's *virtual power* in
    its carrier's frame (W, >= 0; JSON key ``virtual_power``); ``loss`` what it dissipates.
    """

    link: int
    kind: str
    a: str
    b: str
    carrier: str
    ratio: float
    efficiency: float
    force: float
    factor: float
    torques: Mapping[str, float]
    driver: str | None
    carrier_frame_power: float
    loss: float


@record
class Lock:
    """Why a train cannot move as asked under its loads (docs/locking.md).

    ``meshes`` are the links whose friction alone locks it (with that one lossless the
    train moves), each explained in ``reasons``; ``asked`` is the impossible motion.
    """

    meshes: tuple[int, ...]
    reasons: tuple[str, ...]
    asked: Kinematics = field(repr=False)

    @property
    def reason(self) -> str:
        return "; ".join(self.reasons)

    def to_dict(self) -> dict[str, Any]:
        speeds = {c: self.asked.body_speeds[b] for c, b in self.asked.body_of.items()}
        return {"locked": True, "meshes": list(self.meshes), "reason": self.reason,
                "asked_speeds": speeds,
                "holding_torques": "lossless equilibrium (one of the static-friction set)"}


@record
class DirectionSearch:
    """How the power directions were found when the fixed-point iteration cycled.

    ``solutions`` consistent patterns were found (0: locked), by ``method``
    ("exhaustive" or "branch and bound"); ``complete`` is False when the search stopped
    early. With several, the least-loss one is reported (docs/locking.md).
    """

    method: str
    solutions: int
    complete: bool

    def to_dict(self) -> dict[str, Any]:
        return {"method": self.method, "solutions": self.solutions,
                "complete": self.complete,
                "chosen": "least total loss" if self.solutions > 1 else None}


@record
class PowerFlowResult:
    """Everything a virtual-power solve finds (docs/theory.md, docs/locking.md).

    Indexed by the model's component ids (strings); bodies are named like "2/3".
    Follows the result protocol :class:`powergraph.result.Result`.

    Examples
    --------
    >>> import powergraph as pg
    >>> result = pg.solve(pg.load_model("models/rv40e_wang2021.yaml"))   # doctest: +SKIP
    >>> round(result.efficiency, 6)                              # doctest: +SKIP
    0.287376
    """

    model: Model = field(repr=False, compare=False)
    kinematics: Kinematics = field(repr=False)
    elements: tuple[ElementFlow, ...]
    external_torques: Mapping[str, float]   # by body
    input_power: float
    output_power: float
    total_loss: float
    passes: int
    load_sharing_assumed: bool = False
    method: str = "virtual-power"
    #: Meshes whose efficiency comes from a friction law (MeshFrictionState), and the
    #: passes of the load-dependent iteration (0 when no efficiency depends on the load).
    friction: tuple = ()
    friction_passes: int = 0
    #: Bearing friction and body drag (BearingState, powergraph.statics.bearings): their
    #: losses are in ``total_loss``, their torques act on the bodies beside the elements'.
    bearings: tuple = ()
    lock: Lock | None = None                 # set when the train cannot move as asked
    search: DirectionSearch | None = None    # set when the fixed-point iteration cycled
    #: Electric machines (MachineFlow) and buses ({name: BusFlow}) of a model with
    #: ``buses:`` (powergraph.statics.machines); their losses are in ``total_loss``.
    machines: tuple = ()
    buses: Mapping[str, Any] = field(default_factory=dict)
    #: The heat balance's state (ThermalState, powergraph.statics.thermal) of a model
    #: with ``thermal:``: the oil temperature the result was solved at.
    thermal: Any = None
    #: The external torque of each port, by its place in ``model.ports`` (N·m; several
    #: ports may share a body, docs/modes.md); empty: each port's body's torque.
    port_torques: tuple = ()

    @property
    def name(self) -> str:
        return self.model.name

    @property
    def dof(self) -> int:
        return self.kinematics.dof

    @property
    def ratio(self) -> float | None:
        """Input speed / output speed (one input and one output), else None; for a locked
        train, that of the motion asked."""
        return (self.lock.asked if self.lock is not None else self.kinematics).ratio

    @property
    def efficiency(self) -> float | None:
        """Power leaving the train at its ports over power entering at its ports, from the
        actual flows whatever the declared roles (:attr:`ports`): never above 1; 0 when
        every port takes power in (self-locking) or the train locks (it stays at rest);
        None when no power passes (:attr:`efficiency_note` says why)."""
        if self.lock is not None:
            return 0.0
        if self.machines:   # the machines are inside: count the batteries instead
            from powergraph.statics.machine_report import boundary_powers

            return flow_efficiency(boundary_powers(self))
        return flow_efficiency(p.power for p in self.ports)

    @property
    def formal_efficiency(self) -> float:
        """Declared output power / declared input power, the papers' efficiency: negative
        when the train self-locks, above 1 when it runs back-driven; 0 for a locked train,
        NaN when no power enters at the declared input."""
        if self.lock is not None:
            return 0.0
        return self.output_power / self.input_power if self.input_power else float("nan")

    @property
    def efficiency_note(self) -> str | None:
        """Why :attr:`efficiency` is None (no power passes), else None."""
        if self.lock is None and all(p.direction == "none" for p in self.ports):
            return "no power passes through the train: the efficiency is undefined"
        return None

    @property
    def self_locking(self) -> bool:
        """True when the declared input cannot drive the declared output in the asked
        direction: the train locks, or power passes and its formal efficiency is <= 0
        (the output must be driven too). False when no power passes at all, and for a
        mode whose declared inputs are all inactive (docs/modes.md: its machines drive)."""
        if self.lock is not None:
            return True
        if not self.model.inputs:
            return False
        return self.efficiency_note is None and not self.formal_efficiency > 0.0

    @cached_property
    def ports(self) -> tuple[PortFlow, ...]:
        """Every port with its speed, the torque on the train and the power (positive
        into the train), in the model's order."""
        return port_flows(self)

    @cached_property
    def warnings(self) -> tuple[Caveat, ...]:
        """The model's caveats, then the result's own (ports whose power runs against
        their declared role, an output torque that drives the train, no power passing, a
        machine outside its efficiency map)."""
        own = result_caveats(self)
        if self.bearings:
            from powergraph.statics.loss_sources import law_caveats

            own += law_caveats(self)
        if self.thermal is not None:
            own += self.thermal.caveats()
        if self.machines:
            from powergraph.statics.machines import machine_caveats

            return tuple(self.model.warnings) + own + machine_caveats(self)
        return tuple(self.model.warnings) + own

    @property
    def speeds(self) -> dict[str, float]:
        """Absolute speed of every component (rad/s)."""
        return {c: self.kinematics.speed(c) for c in self.model.components}

    @property
    def torques(self) -> dict[str, float]:
        """External torque on every port's component and on the frame (N·m)."""
        out = {p.component: self.port_torque(p.index) for p in self.model.ports}
        out[self.model.frame] = self.external_torques[self.model.frame_body]
        return out

    def port_torque(self, index: int) -> float:
        """The external torque of ``model.ports[index]`` (N·m): its own, when several
        ports share its body."""
        if self.port_torques:
            return self.port_torques[index]
        port = self.model.ports[index]
        return self.external_torques.get(self.model.body_of[port.component], 0.0)

    @property
    def meshes(self) -> tuple[ElementFlow, ...]:
        return tuple(e for e in self.elements if e.kind == "mesh")

    @property
    def bearing_loss(self) -> float:
        """Total loss of the bearings and body drags (W)."""
        return float(sum(b.loss for b in self.bearings))

    def element(self, link: int) -> ElementFlow:
        """The element of ``links[link]``."""
        return next(e for e in self.elements if e.link == link)

    def port_power(self, component: str, frame: str | None = None) -> float:
        """Power fed in at a port's component (negative when it takes power out)."""
        body = self.model.body_of[str(component)]
        w = self.kinematics.body_speeds[body]
        if frame is not None:
            w -= self.kinematics.speed(frame)
        ports = [p.index for p in self.model.ports if p.component == str(component)]
        torque = self.port_torque(ports[0]) if ports else self.external_torques.get(body, 0.0)
        return torque * w

    # --- flow-graph views (computed by powergraph.statics.flow) ---------------------------
    def flows(self, frame: str | None = None):
        """Power-flow edges ``[Flow(source, target, power)]``, seen from ``frame``."""
        from powergraph.statics.flow import flow_edges

        return flow_edges(self, frame)

    def flow_graph(self, frame: str | None = None):
        """The power-flow graph as a networkx DiGraph (edge attribute ``power``)."""
        from powergraph.statics.flow import flow_graph

        return flow_graph(self, frame)

    @property
    def circulating_power(self) -> float:
        """Largest, over directed cycles of the flow graph, of the smallest flow on it."""
        from powergraph.statics.flow import circulating_power

        return circulating_power(self.flows())

    def split_powers(self, frame: str | None = None) -> dict[str, dict[str, float]]:
        """Bodies that feed several elements, with the power into each."""
        from powergraph.statics.flow import split_powers

        return split_powers(self.flows(frame))

    def plot(self, ax: Any = None, *, frame: str | None = None, **kwargs: Any):
        """Draw the power-flow diagram, seen from ``frame`` (default the housing).

        Delegates, lazily, to :func:`powergraph.plot.power_flow.plot_power_flow`.
        """
        from powergraph.plot.power_flow import plot_power_flow

        return plot_power_flow(self, frame=frame, ax=ax, **kwargs)

    def __repr__(self) -> str:
        """One line: name, DOF, ratio and efficiency (``text_report()`` has the rest)."""
        from powergraph.statics.report import summary_line

        return f"<PowerFlowResult {summary_line(self)}>"

    def _repr_html_(self) -> str:
        """A small table for notebooks: the summary and the ports."""
        from powergraph.statics.report import html_summary

        return html_summary(self)

    def to_dataframe(self, what: str = "meshes", frame: str | None = None):
        """A pandas DataFrame of the ``meshes``, ``ports``, ``flows`` (seen from ``frame``)
        or ``speeds``, names beside ids, SI units in the column names (pandas optional).

        Delegates to :func:`powergraph.statics.tables.to_dataframe`.
        """
        from powergraph.statics.tables import to_dataframe

        return to_dataframe(self, what, frame)

    def text_report(self) -> str:
        """The readable report ``powergraph solve`` prints."""
        from powergraph.statics.report import text_report

        return text_report(self)

    def to_dict(self) -> dict[str, Any]:
        """The JSON object of ``powergraph solve --json`` (see docs/format.md).

        Per mesh, the key ``virtual_power`` is the mesh's power in its carrier's frame
        (:attr:`ElementFlow.carrier_frame_power`), the power its basic efficiency
        applies to.
        """
        from powergraph.statics.report import result_to_dict

        return result_to_dict(self)
