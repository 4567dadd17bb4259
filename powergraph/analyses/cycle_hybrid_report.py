"""The columns of hybrid rows solved together (:mod:`powergraph.analyses.cycle_hybrid`):
what :func:`~powergraph.analyses.cycle_rows.single_row` reads from each row's single solve
— the powers at the system's boundary (the ports, the batteries instead of the machines),
the loss of every element and machine, the efficiency, the verdict, the electrical share,
the negative split, the row's own warnings and its flows (each port's power, each
machine's speed, torque and powers, each bus's battery power) — by the same rules, on
arrays over the rows (the rules of :mod:`powergraph.statics.result`,
:mod:`~powergraph.statics.ports`, :mod:`~powergraph.statics.machine_report` and
:mod:`~powergraph.statics.flow`).
"""
from __future__ import annotations

import numpy as np

from powergraph.analyses.cycle_columns import Columns, port_label
from powergraph.statics.ports import capped
from powergraph.statics.verdicts import verdict_codes
from powergraph.statics.loss_sources import element_label, loss_sources
from powergraph.analyses.cycle_train import PlainTrain, State, distinct_rows
from powergraph.kinematics import element_stencil
from powergraph.statics.directions import factors_for
from powergraph.statics.flow import _reaches
from powergraph.statics.machines import machine_name, over_max_speed
from powergraph.statics.ports import WARN_FRACTION

#: The flow graph's tolerance of :func:`~powergraph.statics.machine_report.negative_split`.
TOLERANCE = 1e-9


def report(train: PlainTrain, state: State, rows: np.ndarray, columns: Columns) -> np.ndarray:
    """Rows ``rows`` (their settled ``state``) into ``columns``; returns the rows whose
    numbers are not finite (the single solve's numerical error), not written."""
    model = train.values.model
    ports, machines = model.ports, train.machines
    powers, mechanical = state.powers, state.powers[:, [p.index for p in machines]]
    machine_loss = state.electrical - mechanical + 0.0
    drawn: dict = {}
    for j, port in enumerate(machines):
        drawn[port.bus] = drawn.get(port.bus, 0.0) + state.electrical[:, j]
    balanced = [bus.name for bus in train.balanced]
    batteries = [np.broadcast_to(state.batteries[:, balanced.index(name)] if name in balanced
                                 else drawn.get(name, 0.0), len(rows)) + 0.0
                 for name in model.buses]
    crossing = [powers[:, p.index] for p in ports if not p.is_machine] + batteries
    entering, leaving = _sums(crossing)
    machine_sum = sum(machine_loss[:, j] for j in range(len(machines)))
    loss = state.total_loss + machine_sum
    with np.errstate(all="ignore"):
        efficiency = np.where(entering > 0, capped(leaving / entering),
                              np.where(leaving == 0, np.nan, np.inf))
        fed_in = sum(state.raw[:, p.index] for p in model.inputs)
        fed_out = -sum(state.raw[:, p.index] for p in model.outputs) + 0.0
        formal = np.where(fed_in != 0, fed_out / fed_in, np.nan)
    silent = np.all(powers == 0, axis=1)          # every port's direction "none"
    verdicts = verdict_codes(False, ~silent & ~(formal > 0), silent)
    losses = {}
    for k, element in enumerate(train.elements):
        values = state.losses[:, k]
        losses[element_label(model, element.link)] = (
            values if element.kind == "mesh" else np.where(values != 0, values, np.nan))
    by_machine = [s for s in loss_sources(model) if s.applied == "machine"]
    for j, source in enumerate(by_machine):
        losses[source.label] = machine_loss[:, j]
    split = negative_split(train, state, machine_loss, batteries)
    out = -sum(np.minimum(powers[:, p.index], 0.0) for p in model.outputs)
    motoring = sum(np.maximum(mechanical[:, j], 0.0) for j in range(len(machines)))
    with np.errstate(all="ignore"):
        share = np.where(out > 0, np.where(split, -motoring, motoring) / out, np.nan)
    good = np.isfinite(entering) & np.isfinite(leaving) & np.isfinite(loss)
    keep = lambda a: a[good]  # noqa: E731
    columns.put(rows[good], *(keep(a + 0.0) for a in (entering, leaving, loss)),
                keep(efficiency), keep(verdicts), {k: keep(v) for k, v in losses.items()},
                keep(share), keep(split))
    columns.put_flows(rows[good], *_flows(train, state, batteries, good))
    places = _warnings(train, state, silent)
    first = {code: (int(np.argmax(np.isfinite(p))), float(p[np.isfinite(p)][0]))
             for code, p in places.items()}
    for code in sorted(places, key=first.__getitem__):  # as the first row lists them
        columns.warn(code, rows[np.isfinite(places[code]) & good])
    return rows[~good]


def _flows(train: PlainTrain, state: State, batteries: list,
           good: np.ndarray) -> tuple[dict, dict, dict]:
    """The flows of the rows ``good``, as :func:`~powergraph.analyses.cycle_rows.flows`
    reads them from a single solve."""
    model = train.values.model
    label = port_label
    ports = {label(p): (-state.powers[good, p.index] if p.role == "output"
                        else state.powers[good, p.index]) + 0.0
             for p in model.ports if not p.is_machine}
    machines = {label(p): {"speed": state.speeds[good, p.index],
                           "torque": state.torques[good, p.index],
                           "power": state.powers[good, p.index],
                           "electrical_power": state.electrical[good, j]}
                for j, p in enumerate(train.machines)}
    return ports, machines, {name: b[good] for name, b in zip(model.buses, batteries)}


def _sums(powers: list) -> tuple[np.ndarray, np.ndarray]:
    """Power entering (the sum of the positive ``powers``) and leaving (minus that of the
    negative ones), added in their order as :func:`~powergraph.statics.ports.
    flow_efficiency` adds them."""
    entering = leaving = 0.0
    for p in powers:
        entering = entering + np.where(p > 0, p, 0.0)
        leaving = leaving + np.where(p < 0, p, 0.0)
    return np.asarray(entering, dtype=float), -np.asarray(leaving, dtype=float)


def negative_split(train: PlainTrain, state: State, machine_loss: np.ndarray,
                   batteries: list) -> np.ndarray:
    """Per row, whether a directed loop of the flow graph passes through a bus
    (:func:`~powergraph.statics.machine_report.negative_split`): the flow graph's arrows
    (:func:`~powergraph.statics.flow.flow_edges`, seen from the ground) whose power
    exceeds its tolerance, then the loop sought once per pattern of arrows met."""
    model, columns = train.values.model, train.values.bodies
    count = len(train.elements)
    forces = state.forces[:, :count]
    factors = factors_for(state.codes, np.array([e.efficiency for e in train.elements]))
    arrows, sizes = [], [np.abs(state.raw[:, p.index]) for p in model.ports
                         if not p.is_machine]
    for k, element in enumerate(train.elements):
        stencil = element_stencil(element.ratio, factors[:, k])
        places = [element.body_a, element.body_b]
        if element.kind == "mesh" or element.efficiency != 1.0:
            places.append(element.body_c)        # an ideal coupling does not touch the frame
        torques: dict = {}
        for body, coefficient in zip(places, stencil):
            torques[body] = torques.get(body, 0.0) + coefficient * forces[:, k]
        for body, torque in torques.items():
            arrows.append((("body", body), ("element", element.link),
                           -torque * state.bodies[:, columns[body]]))
        sizes.append(np.maximum(state.losses[:, k], 0.0) if element.efficiency == 1.0
                     else state.losses[:, k])
    for j, port in enumerate(train.machines):
        name = ("machine", machine_name(port, model))
        arrows.append((name, ("body", model.body_of[port.component]),
                       state.torques[:, port.index] * state.speeds[:, port.index]))
        arrows.append((("bus", port.bus), name, state.electrical[:, j]))
        sizes.append(machine_loss[:, j])
    sizes += [np.abs(b) for b in batteries]
    largest = np.max(np.stack([np.abs(p) for *_, p in arrows] + sizes), axis=0)
    threshold = TOLERANCE * np.maximum(1.0, largest)
    signs = np.stack([np.sign(p) * (np.abs(p) > threshold) for *_, p in arrows],
                     axis=1).astype(np.int8)
    patterns, which = distinct_rows(signs)
    loops = np.array([_loop(arrows, pattern) for pattern in patterns], dtype=bool)
    return loops[which]


def _loop(arrows: list, pattern: np.ndarray) -> bool:
    """Whether the arrows of ``pattern`` (+1 as written, -1 reversed, 0 absent) close a
    directed loop through a bus."""
    successors: dict = {}
    for (source, target, _), sign in zip(arrows, pattern.tolist()):
        if sign:
            a, b = (source, target) if sign > 0 else (target, source)
            successors.setdefault(a, set()).add(b)
    return any(_reaches(successors, target, bus)
               for bus in successors if bus[0] == "bus" for target in successors[bus])


def _warnings(train: PlainTrain, state: State, silent: np.ndarray) -> dict[str, np.ndarray]:
    """``{code: place}`` of each row's own warnings (:func:`~powergraph.statics.ports.
    result_caveats`, then :func:`~powergraph.statics.machines.machine_caveats`): the
    place of the code's first caveat among the row's, ``inf`` in a row without it."""
    model, values = train.values.model, train.values
    powers, rows = state.powers, len(silent)
    entering = sum(np.maximum(powers[:, p.index], 0.0) for p in model.ports)
    found: dict[str, np.ndarray] = {}

    def add(code: str, where: np.ndarray, place: float) -> None:
        found[code] = np.minimum(found.get(code, np.full(rows, np.inf)),
                                 np.where(where, place, np.inf))

    add("no-power", silent, -1)
    for port in model.ports:
        if port.role not in ("input", "output"):
            continue
        p = powers[:, port.index]
        shown = ~silent & (np.abs(p) > WARN_FRACTION * entering)
        drives = shown & (p > 0) & (port.role == "output"
                                    and values.given(port.index, "torque"))
        add("output-drives", drives, port.index)
        add("role-reversed", shown & ~drives & ((p < 0) if port.role == "input" else (p > 0)),
            port.index)
    for j, port in enumerate(train.machines):
        place = len(model.ports) + 2 * j
        add("outside-map", ~state.on_map[:, j], place)
        add("over-max-speed", over_max_speed(port, state.speeds[:, port.index]), place + 1)
    return {code: place for code, place in found.items() if np.isfinite(place).any()}
