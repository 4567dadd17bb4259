"""The power at each port of a solved train, the efficiency from those actual flows, and
the caveats a designer should see beside them (docs/format.md, docs/theory.md).

The declared roles (``input``/``output``) say where the user *expects* power to enter and
leave; the solve says where it *does*. The efficiency reported first is read from the
actual flows — the power leaving the train at its ports over the power entering at its
ports — so it is never above 1, whatever the roles; the role-based ratio stays available
as ``formal_efficiency`` (the quantity papers use, negative when a train self-locks).

Examples
--------
>>> flow_efficiency([1000.0, -950.0])          # 1 kW in, 950 W out
0.95
>>> flow_efficiency([-970.0, 1000.0])          # back-driven: in at the "output"
0.97
>>> flow_efficiency([500.0, 20.0])             # every port takes power in
0.0
>>> flow_efficiency([0.0, 0.0]) is None        # no power passes
True
"""
from __future__ import annotations

from typing import Any, Iterable, Sequence

import numpy as np

from powergraph.errors import Caveat
from powergraph.records import record

#: When every port's power is at or below this (W), no power passes.
ABSOLUTE_ZERO = 1e-12
#: A port's power must exceed this fraction of the power entering to be warned about.
WARN_FRACTION = 1e-9


@record
class PortFlow:
    """What happens at one port: its speed, the torque on the train there and the power.

    ``power`` is positive INTO the train (``torque * speed``, the torque being the one the
    outside applies to the train, positive in the sense of positive speed); ``direction``
    is ``"in"``, ``"out"`` or ``"none"`` (no power within the solve's precision).
    """

    index: int
    component: str
    name: str | None
    role: str
    speed: float
    torque: float
    power: float
    direction: str
    #: True when the port's component is idle in its mode (docs/modes.md): no speed.
    idle: bool = False

    @property
    def path(self) -> str:
        """``ports[i]``, the place in the model file."""
        return f"ports[{self.index}]"

    @property
    def label(self) -> str:
        """``ports[2] (MG1, component S)`` or ``ports[0] (component 1)``."""
        named = f"{self.name}, " if self.name else ""
        return f"{self.path} ({named}component {self.component})"

    @property
    def reversed(self) -> bool:
        """True when the power runs against the declared role."""
        return (self.role, self.direction) in (("input", "out"), ("output", "in"))

    def to_dict(self, raw=str) -> dict[str, Any]:
        return {"component": raw(self.component), "name": self.name, "role": self.role,
                "speed": None if self.idle else self.speed, "torque": self.torque,
                "power": self.power, "direction": self.direction}


def port_flows(result: "PowerFlowResult") -> tuple[PortFlow, ...]:
    """Every port of ``result``'s model with its actual speed, torque and power."""
    model, kin = result.model, result.kinematics
    raw = []
    for port in model.ports:
        body = model.body_of[port.component]
        speed = float(kin.body_speeds[body]) + 0.0
        torque = float(result.port_torque(port.index)) + 0.0
        raw.append((port, speed, torque, torque * speed))
    quiet = _no_power(result, [p for _, _, _, p in raw])
    return tuple(PortFlow(index=port.index, component=port.component, name=port.name,
                          role=port.role, speed=speed, torque=torque,
                          power=0.0 if quiet else power + 0.0,
                          direction="none" if quiet or power == 0 else
                          ("in" if power > 0 else "out"),
                          idle=port.component in model.idle)
                 for port, speed, torque, power in raw)


def _no_power(result: "PowerFlowResult", powers: Sequence[float]) -> bool:
    """True when every port's power is below a picowatt (a train with no load and no drag
    solves to exact zeros)."""
    return max((abs(p) for p in powers), default=0.0) <= ABSOLUTE_ZERO


def flow_efficiency(powers: Iterable[float]) -> float | None:
    """Power leaving at the ports over power entering at the ports (``None``: none enters
    and none leaves). Powers are positive into the train; the result lies in [0, 1] when
    the losses are >= 0, whatever roles the ports were declared with.

    >>> flow_efficiency([100.0, -30.0, -60.0])
    0.9
    """
    powers = [float(p) for p in powers]
    entering = sum(p for p in powers if p > 0)
    leaving = -sum(p for p in powers if p < 0)
    if entering == 0.0:
        return None if leaving == 0.0 else float("inf")
    return capped(leaving / entering)


#: An efficiency above 1 by no more than this is round-off (a lossless gear's torques
#: rounded differently), reported as 1; beyond it, it is left for the checks to catch.
ROUND_OFF = 1e-9


def capped(efficiency):
    """``efficiency`` (a float or an array) with round-off above 1 taken back to 1.

    >>> capped(1.0000000000000002), capped(0.97)
    (1.0, 0.97)
    """
    if isinstance(efficiency, np.ndarray):
        return np.where((efficiency > 1.0) & (efficiency <= 1.0 + ROUND_OFF), 1.0, efficiency)
    return 1.0 if 1.0 < efficiency <= 1.0 + ROUND_OFF else efficiency


def flow_efficiency_of_roles(input_power: np.ndarray, output_power: np.ndarray
                             ) -> np.ndarray:
    """Vectorised :func:`flow_efficiency` of a train with one input and one output port,
    from the declared input power (fed in) and output power (taken out), as the batched
    evaluators report them; NaN where no power passes.

    >>> flow_efficiency_of_roles(np.array([1.0, -1.0, 1.0, 0.0]),
    ...                          np.array([0.9, -1.25, -0.5, 0.0])).tolist()
    [0.9, 0.8, 0.0, nan]
    """
    p_in = np.asarray(input_power, dtype=float)
    p_out = -np.asarray(output_power, dtype=float)   # into the train at the output port
    entering = np.maximum(p_in, 0.0) + np.maximum(p_out, 0.0)
    leaving = np.maximum(-p_in, 0.0) + np.maximum(-p_out, 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        eta = capped(leaving / entering)
    return np.where(entering > 0, eta, np.where(leaving > 0, np.inf, np.nan))


def flow_efficiency_point(input_power: float, output_power: float) -> float:
    """:func:`flow_efficiency_of_roles` of one variant, on floats: plain Python that a
    compiler of scalar loops (the sweep's numba kernels) takes as it is, with the same
    operations, so the same number.

    >>> [flow_efficiency_point(p, q) for p, q in [(1.0, 0.9), (-1.0, -1.25), (0.0, 0.0)]]
    [0.9, 0.8, nan]
    """
    p_in, p_out = input_power, -output_power
    entering = float(np.maximum(p_in, 0.0) + np.maximum(p_out, 0.0))
    leaving = float(np.maximum(-p_in, 0.0) + np.maximum(-p_out, 0.0))
    if entering > 0.0:
        eta = leaving / entering
        return 1.0 if 1.0 < eta <= 1.0 + ROUND_OFF else eta
    return np.inf if leaving > 0.0 else np.nan


def result_caveats(result: "PowerFlowResult") -> tuple[Caveat, ...]:
    """The result's own caveats: ports whose power runs against their role
    (``role-reversed``), a torque written on an output port that drives the train
    (``output-drives``), and no power passing (``no-power``)."""
    if result.lock is not None:
        return ()
    ports = result.ports
    if all(p.direction == "none" for p in ports):
        return (Caveat("no power passes through the train (every port's power is zero): "
                       "the efficiency is undefined; give a load (a torque or power) on a "
                       "port, or a speed that is not zero", None, "no-power"),)
    entering = sum(p.power for p in ports if p.power > 0)
    caveats = []
    for flow in ports:
        if abs(flow.power) <= WARN_FRACTION * entering:
            continue
        given = result.model.ports[flow.index].torque
        if flow.role == "output" and given is not None and flow.direction == "in":
            caveats.append(_output_drives(flow, given))
        elif flow.reversed:
            caveats.append(_role_reversed(flow))
    if result.model.shift_elements and not result.model.resolved:
        caveats.append(_default_state(result.model))
    return tuple(caveats)


def _default_state(model) -> Caveat:
    """A loaded model with shift elements solved as it was loaded: no operating state was
    decided for this load."""
    held = [e.name for e in model.shift_elements
            if e.kind == "freewheel" and model.links[e.index].type == "fixed"]
    mode = f"mode {model.mode}, " if model.mode is not None else ""
    state = f"freewheels as loaded: {', '.join(held)} holding" if held else \
        "its freewheels as loaded"
    return Caveat(f"solved in the model's default state ({mode}{state}), not an operating "
                  "state decided for this load: solve its case (powergraph solve --mode "
                  "NAME, or TrainCase.of(model, mode).point()), which decides the freewheels",
                  "modes" if model.modes else "links", "default-state")


def _output_drives(flow: PortFlow, given: float) -> Caveat:
    return Caveat(
        f"declared output, but its torque {format_torque(given)} acts on the train in the "
        f"sense of the port's motion, so it drives the train ({format_power(flow.power, True)}"
        f" enters here); a torque is the one applied TO the train: to write a load that "
        f"resists the motion, give torque: {_number(-given)} N*m",
        flow.label, "output-drives")


def _role_reversed(flow: PortFlow) -> Caveat:
    if flow.role == "output":
        what = (f"declared output, but power enters here ({format_power(flow.power, True)}): "
                f"the machine on it motors, driving the train")
    else:
        what = (f"declared input, but power leaves here ({format_power(flow.power, True)}): "
                f"the train drives the machine on it (it brakes or generates)")
    return Caveat(what, flow.label, "role-reversed")


def _number(value: float) -> str:
    return f"{value + 0.0:.6g}"


def format_torque(value: float) -> str:
    """``+412 N·m`` (signed, so the sense is plain)."""
    return f"{value + 0.0:+.6g} N·m"


def format_power(watts: float, signed: bool = False) -> str:
    """A power with a unit fitting its size (``+24.6 kW``, ``-1.9 kW``, ``12.5 W``)."""
    sign = "+" if signed else ""
    size = abs(watts)
    for unit, scale in (("MW", 1e6), ("kW", 1e3), ("W", 1.0)):
        if size >= scale or unit == "W":
            return f"{watts / scale + 0.0:{sign}.3g} {unit}"
    raise AssertionError("unreachable")   # pragma: no cover
