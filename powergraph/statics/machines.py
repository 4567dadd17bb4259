"""Electric machines on electrical buses: the bus balance as one more equation of the
train (docs/hybrid.md).

A machine port applies a torque ``T`` to its body; its mechanical power into the train is
``P = T·ω`` and it draws ``P_e = P/η`` from its bus when it motors (``P > 0``), ``P·η``
when it generates. A bus whose battery power ``P_b`` is given balances:
``Σ P_e = P_b`` over its machines. The train then takes one port load fewer per such bus.

Formulation: one machine torque per balanced bus is the unknown ``τ``; for given ``τ``
the train is a plain one (every load given), solved by the ordinary solve with all its
direction logic (meshes, friction, locking). The bus residual ``r(τ) = Σ P_e − P_b`` is
linear for a fixed pattern of mesh directions and machine states (motoring/generating)
and continuous across them (both branches of ``P_e`` vanish at ``P = 0``), so Newton's
method with the slope of the current piece lands on the consistent pattern in a few steps.
"""
from __future__ import annotations

import dataclasses
import itertools
from types import MappingProxyType
from typing import Any, Callable, Mapping

import numpy as np

from powergraph.errors import Caveat, StaticsError
from powergraph.kinematics import solve_speeds
from powergraph.model.efficiency_table import EfficiencyTable
from powergraph.model.spec import Model, Port
from powergraph.records import record
from powergraph.units_si import RPM_PER_RAD_S, rpm

#: Newton iterations on the bus balances before giving up.
MAX_STEPS = 40
#: A bus balances when its residual is within this fraction of the train's power.
RTOL = 1e-11
#: A machine runs beyond its max_speed when faster by more than this fraction of it.
SPEED_RTOL = 1e-9


def electrical_power(power, efficiency):
    """Electrical power a machine draws from its bus for mechanical power ``power`` into
    the train: ``P/η`` motoring, ``P·η`` generating. Floats, or arrays over many points.

    >>> electrical_power(900.0, 0.9), electrical_power(-1000.0, 0.9)
    (1000.0, -900.0)
    >>> electrical_power(np.array([900.0, -1000.0]), 0.9).tolist()
    [1000.0, -900.0]
    """
    with np.errstate(divide="ignore", invalid="ignore"):
        drawn = np.where(np.greater(power, 0), np.divide(power, efficiency),
                         np.multiply(power, efficiency))
    return float(drawn) if drawn.ndim == 0 else drawn


def machine_efficiency(port: Port, speed, torque):
    """A machine port's efficiency at ``speed`` (rad/s) and ``torque`` (N·m): its number,
    or its map's value there; and whether the point lies on the map (always True for a
    number). Floats, or arrays over many points (then arrays of that shape).

    >>> machine_efficiency(Port(0, "S", "machine", efficiency=0.9, bus="dc"), 10.0, 2.0)
    (0.9, True)
    """
    if isinstance(port.efficiency, EfficiencyTable):
        return port.efficiency.at(speed, torque)
    shape = np.broadcast_shapes(np.shape(speed), np.shape(torque))
    if not shape:
        return port.efficiency, True
    return np.full(shape, float(port.efficiency)), np.ones(shape, dtype=bool)


def over_max_speed(port: Port, speed):
    """Whether a machine at ``speed`` (rad/s; a float or an array) runs beyond its
    ``max_speed``, by more than round-off (:data:`SPEED_RTOL`); False without one."""
    if port.max_speed is None:
        return np.zeros(np.shape(speed), dtype=bool) if np.ndim(speed) else False
    return np.abs(speed) > port.max_speed * (1 + SPEED_RTOL)


@record
class MachineFlow:
    """One machine at the solved point: speed (rad/s), torque on the train (N·m),
    mechanical ``power`` into the train and ``electrical_power`` drawn from its bus (W,
    both negative when it generates); ``loss = electrical_power - power >= 0``.
    ``efficiency`` is the one at this point (from the map, for a machine with one);
    ``on_map`` is False when the point lies outside the map (its edge value taken)."""

    name: str
    component: str
    bus: str
    efficiency: float
    speed: float
    torque: float
    power: float
    electrical_power: float
    on_map: bool = True
    #: False for a machine its mode leaves inactive (docs/modes.md): it carries nothing.
    active: bool = True
    #: True when its rotor is idle (joined to no active port nor the frame): no speed.
    idle: bool = False

    @property
    def state(self) -> str:
        """``motoring``, ``generating``, ``idle`` (no power) or ``inactive`` (its mode
        switches it off)."""
        if not self.active:
            return "inactive"
        return "motoring" if self.power > 0 else ("generating" if self.power < 0 else "idle")

    @property
    def loss(self) -> float:
        return self.electrical_power - self.power + 0.0

    def to_dict(self, raw: Callable = str) -> dict[str, Any]:
        return {"name": self.name, "component": raw(self.component), "bus": self.bus,
                "speed": None if self.idle else self.speed, "torque": self.torque,
                "power": self.power,
                "electrical_power": self.electrical_power, "state": self.state,
                "loss": self.loss, "efficiency": self.efficiency}


@record
class BusFlow:
    """A bus at the solved point: the battery's power into it (W; given or, for a free
    battery, what the machines draw)."""

    name: str
    battery_power: float
    given: bool

    def to_dict(self) -> dict[str, Any]:
        return {"battery_power": self.battery_power}


def machine_name(port: Port, model: Model) -> str:
    """The port's name, else ``machine COMPONENT``."""
    return port.name or f"machine {model.raw_id(port.component)}"


def solve_machines(model: Model, speeds: Mapping[str, float] | None,
                   plain_solve: Callable[[Model], Any]):
    """Solve a train with machines on buses; ``plain_solve(model)`` solves a train
    without buses. Returns the plain result with ``machines`` and ``buses`` set and the
    machines' losses in ``total_loss``."""
    kin = solve_speeds(model, speeds)
    base = dataclasses.replace(model, buses=MappingProxyType({}),
                               ports=_machine_torques(model, kin))
    balanced = [bus for bus in model.buses.values() if bus.battery is not None]
    _check_count(model, kin, balanced)
    unknowns, first = _choose_unknowns(base, balanced, kin, plain_solve)
    result = _newton(base, balanced, unknowns, kin, plain_solve, first)
    return _with_machines(model, result)


def _machine_torques(model: Model, kin) -> tuple[Port, ...]:
    """Machine ports with a given power carry it as a torque (power into the train)."""
    ports = []
    for port in model.ports:
        if port.is_machine and port.power is not None:
            speed = kin.speed(port.component)
            if abs(speed) < 1e-12:
                raise StaticsError("a machine's power is given but it does not turn; give "
                                   "a torque instead", f"{port.path}.power")
            port = dataclasses.replace(port, power=None, torque=port.power / speed)
        ports.append(port)
    return tuple(ports)


def _given(port: Port) -> bool:
    return port.power is not None or port.torque is not None


def _check_count(model: Model, kin, balanced: list) -> None:
    active = [p for p in model.ports if p.index not in model.inactive]
    needed = len(active) - kin.dof
    given = sum(_given(p) for p in active)
    if given + len(balanced) == needed:
        return
    buses = ", ".join(b.path for b in balanced) or "none"
    counted = (f"this train takes the power or torque of {needed} port(s); "
               f"{given} given and {len(balanced)} bus balance(s) (battery given: {buses})")
    if given + len(balanced) < needed:
        raise StaticsError(f"the loads are not determined: {counted}; give "
                           f"{needed - given - len(balanced)} more (a port's power or "
                           f"torque, or a bus's battery power)", "ports", missing="load")
    raise StaticsError(f"the given loads contradict each other: {counted}; drop "
                       f"{given + len(balanced) - needed} (or set a battery to free)", "ports")


def _choose_unknowns(base: Model, balanced: list, kin, plain_solve) -> tuple[list[int], Any]:
    """For each balanced bus, the index of a machine port whose torque is the unknown:
    one without a given load, turning, with which the train is determined; and the solve
    with those torques 0."""
    if not balanced:        # no bus balance: the plain train, its own errors
        return [], plain_solve(base)
    options = []
    for bus in balanced:
        free = [p.index for p in base.ports if p.bus == bus.name and not _given(p)
                and abs(kin.speed(p.component)) > 1e-12]
        if not free:
            raise StaticsError("every machine on this bus has a given load or stands still, "
                               "so its battery power cannot be met; set battery: free or "
                               "drop a machine's load", f"{bus.path}.battery")
        free.sort(key=lambda i: -abs(kin.speed(base.ports[i].component)))
        options.append(free)
    last: StaticsError | None = None
    for choice in itertools.product(*options):
        try:
            return list(choice), plain_solve(_with_torques(base, choice, np.zeros(len(choice))))
        except StaticsError as error:
            last = error
    raise StaticsError(f"no choice of the machines' torques on the balanced buses "
                       f"determines the train ({last.message if last else ''})", "buses")


def _with_torques(base: Model, indices, torques) -> Model:
    ports = list(base.ports)
    for i, t in zip(indices, torques):
        ports[i] = dataclasses.replace(ports[i], torque=float(t))
    return dataclasses.replace(base, ports=tuple(ports))


def _residuals(result, balanced: list) -> np.ndarray:
    drawn = []
    for flow in result.ports:
        port = result.model.ports[flow.index]
        if port.is_machine:
            efficiency = machine_efficiency(port, flow.speed, flow.torque)[0]
            drawn.append((port.bus, electrical_power(flow.power, efficiency)))
    return np.array(bus_residuals(drawn, balanced))


def bus_residuals(drawn, balanced: list, batteries=None) -> list:
    """``Σ P_e − P_b`` of each balanced bus, from ``(bus, P_e)`` of each machine in the
    ports' order (floats, or arrays over many points); ``batteries``, one per balanced
    bus (floats or arrays), instead of the buses' own."""
    out: dict[str, Any] = {}
    for bus, power in drawn:
        out[bus] = out.get(bus, 0.0) + power
    if batteries is None:
        batteries = [bus.battery for bus in balanced]
    return [out.get(bus.name, 0.0) - battery for bus, battery in zip(balanced, batteries)]


def balance_scale(powers, balanced: list, batteries=None):
    """The power the bus residuals are judged against: the largest port power (the last
    axis of ``powers``), battery power or 1 W; ``batteries`` (an array, the balanced
    buses on its last axis) instead of the buses' own."""
    if batteries is None:
        batteries = max([abs(bus.battery) for bus in balanced], default=0.0)
    else:
        batteries = np.max(np.abs(batteries), axis=-1, initial=0.0)
    return np.maximum(np.max(np.abs(powers), axis=-1, initial=1.0), batteries)


def settled(r, scale):
    """The bus residuals ``r`` (last axis: the buses) are within :data:`RTOL` of
    ``scale``."""
    return np.max(np.abs(r), axis=-1, initial=0.0) <= RTOL * scale


def difference_steps(x, scale, speeds):
    """The torque steps of the slopes by forward differences."""
    return np.maximum(1e-7 * np.abs(x), 1e-7 * np.asarray(scale)[..., None] / np.abs(speeds))


def newton_step(jac, r):
    """``-J⁻¹ r`` (stacks of them: ``jac`` ``(..., B, B)``, ``r`` ``(..., B)``);
    ``LinAlgError`` where ``jac`` is singular."""
    return -np.linalg.solve(jac, r[..., None])[..., 0]


def broyden_update(jac, dx, dr):
    """Broyden's update of the slopes ``jac`` after the step ``dx`` changed the
    residuals by ``dr`` (stacks of them, as :func:`newton_step`)."""
    predicted = np.matmul(jac, dx[..., None])[..., 0]
    return jac + (dr - predicted)[..., :, None] * dx[..., None, :] \
        / np.sum(dx * dx, axis=-1)[..., None, None]


def _newton(base: Model, balanced: list, unknowns: list[int], kin, plain_solve, result):
    """Newton's method on the bus residuals from ``result`` (the torques 0): the slopes
    by differences once, then Broyden's updates (on a piecewise-linear residual, a step
    within one piece lands on the root; across a kink the secant corrects it)."""
    x = np.zeros(len(unknowns))
    speeds = np.array([kin.speed(base.ports[i].component) for i in unknowns])
    scale = float(balance_scale(np.array([p.power for p in result.ports]), balanced))
    r = _residuals(result, balanced)
    jac = None
    for _ in range(MAX_STEPS):
        if settled(r, scale) or result.lock is not None:
            return result
        if jac is None:
            jac = _slopes(base, balanced, unknowns, plain_solve, x, r,
                          difference_steps(x, scale, speeds))
        try:
            dx = newton_step(jac, r)
        except np.linalg.LinAlgError:
            break
        x = x + dx
        result = plain_solve(_with_torques(base, unknowns, x))
        new = _residuals(result, balanced)
        jac = broyden_update(jac, dx, new - r)
        r = new
    raise StaticsError("the bus balance did not settle (no machine torques meet the "
                       "battery powers)", "buses")


def _slopes(base, balanced, unknowns, plain_solve, x, r, steps) -> np.ndarray:
    """The residuals' slopes by forward differences."""
    jac = np.empty((len(r), len(x)))
    for j, h in enumerate(steps):
        shifted = x.copy()
        shifted[j] += h
        jac[:, j] = (_residuals(plain_solve(_with_torques(base, unknowns, shifted)),
                                balanced) - r) / h
    return jac


def _with_machines(model: Model, result):
    """The plain result re-attached to the model with buses, its machines and buses."""
    result = dataclasses.replace(result, model=model)
    machines = tuple(_machine_flow(model, port, result.ports[port.index])
                     for port in model.machines)
    drawn = {}
    for m in machines:
        drawn[m.bus] = drawn.get(m.bus, 0.0) + m.electrical_power
    buses = MappingProxyType({
        name: BusFlow(name=name, given=bus.battery is not None,
                      battery_power=float(bus.battery if bus.battery is not None
                                          else drawn.get(name, 0.0)) + 0.0)
        for name, bus in model.buses.items()})
    return dataclasses.replace(result, machines=machines, buses=buses,
                               total_loss=result.total_loss + sum(m.loss for m in machines))


def _machine_flow(model: Model, port: Port, flow) -> MachineFlow:
    efficiency, on_map = machine_efficiency(port, flow.speed, flow.torque)
    active = port.index not in model.inactive
    return MachineFlow(name=machine_name(port, model), component=port.component,
                       bus=port.bus, efficiency=efficiency, speed=flow.speed,
                       torque=flow.torque, power=flow.power,
                       electrical_power=electrical_power(flow.power, efficiency) + 0.0,
                       on_map=on_map or not active, active=active,
                       idle=port.component in model.idle)


def machine_caveats(result) -> tuple[Caveat, ...]:
    """What a machine's data do not vouch for: a point outside its efficiency map
    (``outside-map``, naming the axis and by how much; the map's edge value was taken),
    a speed beyond its ``max_speed`` (``over-max-speed``, by more than round-off:
    :data:`SPEED_RTOL`)."""
    caveats = []
    for machine, port in zip(result.machines, result.model.machines):
        if not machine.active:
            continue
        label = (f"{port.path} ({port.name})" if port.name else
                 f"{port.path} (component {result.model.raw_id(port.component)})")
        if not machine.on_map:
            caveats.append(_outside_map(machine, port.efficiency, label, port.path))
        if over_max_speed(port, machine.speed):
            speed, top = abs(rpm(machine.speed)), rpm(port.max_speed)
            caveats.append(Caveat(
                f"{label} runs at {speed:.6g} rpm, {speed - top:.4g} rpm above its "
                f"max_speed of {top:.6g} rpm", f"{port.path}.max_speed", "over-max-speed"))
    return tuple(caveats)


def _outside_map(machine: MachineFlow, table: EfficiencyTable, label: str,
                 path: str) -> Caveat:
    speed, torque = abs(machine.speed), abs(machine.torque)
    beyond = [_beyond("speed", speed, table.speeds, RPM_PER_RAD_S, "rpm"),
              _beyond("torque", torque, table.torques, 1.0, "N·m")]
    return Caveat(f"{label} runs at {rpm(speed):.6g} rpm and {torque:.6g} N·m, outside its "
                  f"efficiency map {table.source!r}: "
                  f"{' and '.join(b for b in beyond if b)}; the map's edge value "
                  f"{machine.efficiency:.4g} was taken", f"{path}.efficiency", "outside-map")


def _beyond(axis: str, value: float, grid: tuple[float, ...], scale: float,
            unit: str) -> str:
    """``the speed is 1900 rpm above the map's highest, 4000 rpm``, or '' within the
    ``grid`` (SI, as EfficiencyTable.at compares; ``scale`` converts for the text)."""
    if grid[0] <= value <= grid[-1]:
        return ""
    side, edge, limit = (("above", "highest", grid[-1]) if value > grid[-1]
                         else ("below", "lowest", grid[0]))
    return (f"the {axis} is {abs(value - limit) * scale:.4g} {unit} {side} the map's "
            f"{edge}, {limit * scale:.6g} {unit}")
