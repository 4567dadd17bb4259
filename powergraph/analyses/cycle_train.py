"""The plain train of a hybrid duty cycle over its rows (:mod:`powergraph.analyses.
cycle_hybrid`): the train with the buses taken off and the unknown machine torques as
load columns, evaluated for many rows at once — directions and losses by the compiled
sweep, ports' torques and elements' forces from the statics of each direction pattern,
the machines' efficiencies and the bus residuals by the single solve's functions on
arrays.

The statics of a plain train are linear in its loads for a given direction pattern (the
elements' factors): its forces and reactions are the loads times the answers of
:func:`~powergraph.statics.equilibrium.solve_equilibrium` to a unit load at each loaded
port, computed once per pattern met. The speeds are linear in the given speeds: the
bodies' speeds of a row are the given speeds times :func:`~powergraph.kinematics.
solve_speeds` of each given speed alone.
"""
from __future__ import annotations

import dataclasses
from types import MappingProxyType

import numpy as np

from powergraph.analyses.cycle_points import Points
from powergraph.analyses.sweep import STATUS, CompiledSweep
from powergraph.analyses.sweep.paths import value_allowed
from powergraph.errors import StaticsError
from powergraph.kinematics import elements_of, solve_speeds
from powergraph.model.spec import Model
from powergraph.statics.directions import factors_of
from powergraph.statics.equilibrium import Loads, loads_of, port_torque, solve_equilibrium
from powergraph.statics.machines import bus_residuals, electrical_power, machine_efficiency
from powergraph.statics.ports import ABSOLUTE_ZERO


class RowValues:
    """The port values of a cycle's rows (a column's, or the model's own) and the bodies'
    speeds; ``model`` is the model with buses, its loaded ports cleared."""

    def __init__(self, model: Model, points: Points) -> None:
        self.model = model
        self.columns = {(index, kind): values
                        for (_, index, kind), values in zip(points.columns, points.values)}
        self.paths = {(index, kind): path for path, index, kind in points.columns}
        self.bodies = {body.id: j for j, body in enumerate(model.bodies)}
        self.batteries = dict(points.batteries)
        self.speed_ports = [p.index for p in model.ports if self.given(p.index, "speed")]
        basis = []
        for j in self.speed_ports or [None]:
            unit = model
            for i in self.speed_ports:
                unit = unit.with_port(i, speed=1.0 if i == j else 0.0)
            self.kinematics = solve_speeds(unit)
            basis.append([self.kinematics.body_speeds[body.id] for body in model.bodies])
        self.basis = np.array(basis)

    def given(self, index: int, kind: str) -> bool:
        return (index, kind) in self.columns or getattr(self.model.ports[index], kind) is not None

    def value(self, index: int, kind: str, rows: np.ndarray) -> np.ndarray:
        """Port ``index``'s ``kind`` over ``rows`` (it must be given)."""
        if (index, kind) in self.columns:
            return self.columns[(index, kind)][rows]
        return np.full(len(rows), float(getattr(self.model.ports[index], kind)))

    def battery(self, bus: str, rows: np.ndarray) -> np.ndarray:
        """Bus ``bus``'s battery power over ``rows`` (a column's, or the model's)."""
        if bus in self.batteries:
            return self.batteries[bus][rows]
        return np.full(len(rows), float(self.model.buses[bus].battery))

    def body(self, index: int) -> int:
        """The column of port ``index``'s body in :meth:`speeds`."""
        return self.bodies[self.model.body_of[self.model.ports[index].component]]

    def speeds(self, rows: np.ndarray) -> np.ndarray:
        """``(rows, bodies)``: every body's speed, rad/s."""
        given = [self.value(i, "speed", rows) for i in self.speed_ports] or [np.ones(len(rows))]
        return np.stack(given, axis=1) @ self.basis


@dataclasses.dataclass
class Batch:
    """Rows of the cycle (indices ``rows``) prepared for a :class:`PlainTrain`: the
    bodies' speeds, the loads' torques (the unknowns' columns to be filled), the sweep's
    values of the points' columns, the balanced buses' battery powers; ``ok`` False
    where the single solve refuses them."""

    rows: np.ndarray
    speeds: np.ndarray
    torques: np.ndarray
    values: dict
    ok: np.ndarray
    batteries: np.ndarray

    def take(self, keep: np.ndarray) -> "Batch":
        return Batch(self.rows[keep], self.speeds[keep], self.torques[keep],
                     {path: v[keep] for path, v in self.values.items()}, self.ok[keep],
                     self.batteries[keep])


@dataclasses.dataclass
class State:
    """The plain train at one torque of each unknown machine, per row (first axis):
    solved (``ok``), the elements' driver codes, losses and forces, the ports' torques,
    speeds and powers (``powers``: as the single solve reports them, a train passing no
    power all zeros), the machines' efficiencies, points on their maps and electrical
    powers, the plain train's loss, each balanced bus's residual and battery power."""

    ok: np.ndarray
    codes: np.ndarray
    losses: np.ndarray
    forces: np.ndarray
    torques: np.ndarray
    speeds: np.ndarray
    raw: np.ndarray
    powers: np.ndarray
    bodies: np.ndarray
    efficiency: np.ndarray
    on_map: np.ndarray
    electrical: np.ndarray
    total_loss: np.ndarray
    residual: np.ndarray
    batteries: np.ndarray

    def take(self, keep: np.ndarray) -> "State":
        return State(**{f.name: getattr(self, f.name)[keep] for f in dataclasses.fields(self)})


class PlainTrain:
    """The train of ``values.model`` without its buses, the torques of the machine ports
    ``unknowns`` (one per balanced bus) given: compiled into a sweep over the points'
    columns and the unknowns' torques.

    Raises
    ------
    UsageError, ModelError
        The train does not compile (loads not determined with these unknowns, a
        load-dependent loss the sweep does not take).
    """

    def __init__(self, values: RowValues, unknowns: tuple[int, ...]) -> None:
        model, self.values, self.unknowns = values.model, values, unknowns
        self.balanced = [bus for bus in model.buses.values() if bus.battery is not None]
        plain = dataclasses.replace(model, buses=MappingProxyType({}))
        #: (port, kind) of each load, as the statics take it: a machine's power as torque
        self.loads = [(p.index, "power" if values.given(p.index, "power") and not p.is_machine
                       else "torque") for p in model.ports
                      if p.index in unknowns or values.given(p.index, "power")
                      or values.given(p.index, "torque")]
        self.swept = [(i, kind) for i, kind in self.loads
                      if i in unknowns or (i, kind) in values.columns
                      or (kind == "torque" and values.given(i, "power"))]
        probe = plain
        for i, _ in self.loads:
            probe = probe.with_port(i, power=None, torque=1.0)
        for i, _ in self.swept:
            plain = plain.with_port(i, power=None, torque=None)
        paths = [values.paths[(i, "speed")] for i in values.speed_ports
                 if (i, "speed") in values.paths]
        self.paths = paths + [f"ports.{i}.{kind}" for i, kind in self.swept]
        self.sweep = CompiledSweep(plain, self.paths)
        self.elements = elements_of(plain)
        self.model = plain
        structure = loads_of(probe, values.kinematics)
        self.given_bodies = list(structure.given)
        self.unit = [Loads({body: 1.0}, structure.unknown, structure.needed)
                     for body in self.given_bodies]
        self.reaction = {body: len(self.elements) + j
                         for j, body in enumerate(structure.unknown)}
        self.machines = list(model.machines)
        self._statics: dict[tuple[int, ...], np.ndarray | None] = {}

    def prepare(self, rows: np.ndarray, speeds: np.ndarray) -> Batch:
        """Rows ``rows`` (their bodies' ``speeds``) ready to evaluate."""
        values, torques = self.values, np.zeros((len(rows), len(self.loads)))
        ok = np.ones(len(rows), dtype=bool)
        sweep_values = {self.values.paths[(i, "speed")]: values.value(i, "speed", rows)
                        for i in values.speed_ports if (i, "speed") in values.paths}
        with np.errstate(all="ignore"):
            for slot, (i, kind) in enumerate(self.loads):
                if i in self.unknowns:
                    continue
                port, w = values.model.ports[i], speeds[:, values.body(i)]
                if kind == "torque" and values.given(i, "power"):     # a machine's power
                    torques[:, slot] = values.value(i, "power", rows) / w
                    ok &= np.abs(w) >= 1e-12
                elif kind == "power":
                    torques[:, slot] = port_torque(values.value(i, "power", rows), "power",
                                                   port.role, w)
                else:
                    torques[:, slot] = values.value(i, "torque", rows)
                if (i, kind) in self.swept:
                    given = torques[:, slot] if kind == "torque" else values.value(i, kind, rows)
                    sweep_values[f"ports.{i}.{kind}"] = given
                    ok &= value_allowed(kind, given)
        batteries = np.stack([values.battery(bus.name, rows) for bus in self.balanced]
                             + [np.zeros(len(rows))], axis=1)[:, :-1]
        return Batch(rows, speeds, torques, sweep_values, ok, batteries)

    def evaluate(self, batch: Batch, x: np.ndarray) -> State:
        """The plain train at the unknowns' torques ``x`` (``(rows, unknowns)``, every
        value one a model takes) over ``batch``."""
        torques, values = batch.torques.copy(), dict(batch.values)
        for j, i in enumerate(self.unknowns):
            torques[:, self.loads.index((i, "torque"))] = x[:, j]
            values[f"ports.{i}.torque"] = x[:, j]
        result = self.sweep(values, quiet=True)
        codes = np.stack([result.drivers[e.link] for e in self.elements], axis=1)
        ok = batch.ok & (result.status == STATUS.index("ok"))
        forces = np.full((len(ok), len(self.elements) + len(self.reaction)), np.nan)
        with np.errstate(all="ignore"):
            if ok.any():
                patterns, group = distinct_rows(codes[ok])
                members = np.flatnonzero(ok)
                for g, pattern in enumerate(patterns):
                    statics = self.statics(tuple(pattern.tolist()))
                    chosen = members[group == g]
                    if statics is None:
                        ok[chosen] = False
                    else:
                        forces[chosen] = torques[chosen] @ statics
            return self._state(batch, ok, codes, result, forces, torques)

    def statics(self, pattern: tuple[int, ...]) -> np.ndarray | None:
        """``(loads, forces + reactions)``: the answer to a unit load at each loaded port
        with the factors of ``pattern`` (None where the balance is not determined)."""
        if pattern not in self._statics:
            factors = factors_of(pattern, self.elements)
            try:
                answers = [solve_equilibrium(self.model, self.elements, unit, factors)
                           for unit in self.unit]
            except StaticsError:
                self._statics[pattern] = None
            else:
                self._statics[pattern] = np.array(
                    [np.concatenate([eq.forces, [eq.external[b] for b in self.reaction]])
                     for eq in answers])
        return self._statics[pattern]

    def _state(self, batch: Batch, ok, codes, result, forces, torques) -> State:
        values, model = self.values, self.values.model
        external = np.empty((len(ok), len(model.ports)))
        for port in model.ports:
            body = model.body_of[port.component]
            external[:, port.index] = (torques[:, self.given_bodies.index(body)]
                                       if body in self.given_bodies
                                       else forces[:, self.reaction[body]])
        speeds = batch.speeds[:, [values.body(p.index) for p in model.ports]]
        raw = external * speeds
        quiet = np.max(np.abs(raw), axis=1, initial=0.0) <= ABSOLUTE_ZERO
        powers = np.where(quiet[:, None], 0.0, raw + 0.0)
        m = [p.index for p in self.machines]
        efficiency, on_map = np.ones((len(ok), len(m))), np.ones((len(ok), len(m)), bool)
        for j, port in enumerate(self.machines):
            efficiency[:, j], on_map[:, j] = machine_efficiency(port, speeds[:, port.index],
                                                                external[:, port.index])
        electrical = electrical_power(powers[:, m], efficiency) + 0.0
        residual = np.zeros((len(ok), len(self.balanced)))
        for j, r in enumerate(bus_residuals([(p.bus, electrical[:, k])
                                             for k, p in enumerate(self.machines)],
                                            self.balanced, batch.batteries.T)):
            residual[:, j] = r
        losses = np.stack([result.losses[e.link] for e in self.elements], axis=1)
        total = np.asarray(result.total_loss, dtype=float)
        ok &= np.isfinite(raw).all(axis=1) & np.isfinite(residual).all(axis=1) \
            & np.isfinite(losses).all(axis=1) & np.isfinite(total)
        return State(ok, codes, losses, forces, external, speeds, raw, powers,
                     batch.speeds, efficiency, on_map, electrical, total, residual,
                     batch.batteries)


def distinct_rows(codes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The distinct rows of ``codes`` (values -1, 0 and 1) and the index of each row's
    among them (as ``np.unique(codes, axis=0, return_inverse=True)``, by one integer key
    per row where it fits: sorting rows is much slower)."""
    if codes.shape[1] > 39:                     # 3**40 overflows int64
        found, which = np.unique(codes, axis=0, return_inverse=True)
        return found, which.ravel()
    keys = np.zeros(len(codes), dtype=np.int64)
    for column in codes.T:
        keys = keys * 3 + (column.astype(np.int64) + 1)
    _, first, which = np.unique(keys, return_index=True, return_inverse=True)
    return codes[first], which.ravel()
