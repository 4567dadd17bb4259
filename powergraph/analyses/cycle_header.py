"""The header of a duty cycle's points (:mod:`powergraph.analyses.cycle_points`): which
column is which quantity, each unit read once (:func:`~powergraph.model.units.unit_factor`).

``PORT.speed``, ``PORT.power`` and ``PORT.torque`` (PORT a port's ``name`` or component
id), ``BUS.battery`` (a key of the model's ``buses:``: the battery's power into the bus),
``duration`` or ``time`` and ``mode``; a unit in brackets, SI without one. Every problem is
one error naming the file and the column (docs/hybrid.md lists them).

Examples
--------
>>> from powergraph.model import load_model
>>> m = load_model("models/ths2_power_split.yaml")
>>> found = layout(["engine.speed [rpm]", "engine.power [kW]", "dc.battery [kW]"], m, "p")
>>> [(c.path, c.kind, c.scale) for c in found.batteries]
[('buses.dc.battery', 'battery', 1000.0)]
>>> layout(["engine.speed [rpm]", "hv.battery [kW]"], m, "p")
Traceback (most recent call last):
...
powergraph.errors.UsageError: p: column 'hv.battery [kW]': unknown bus 'hv' (the model's \
buses: dc)
"""
from __future__ import annotations

import re
from typing import NamedTuple

from powergraph.errors import ModelError, UsageError
from powergraph.model.spec import Model
from powergraph.model.units import unit_factor
from powergraph.model.yaml_loader import brief

_HEADER = re.compile(r"^\s*(?P<port>.+?)\.(?P<what>speed|power|torque)\s*"
                     r"(\[(?P<unit>[^\]]*)\])?\s*$")
_BATTERY = re.compile(r"^\s*(?P<bus>.+?)\.battery\s*(\[(?P<unit>[^\]]*)\])?\s*$")
_TIME = re.compile(r"^\s*(?P<what>duration|time)\s*(\[(?P<unit>[^\]]*)\])?\s*$")
#: Units of a ``duration`` or ``time`` column, in seconds.
TIME_UNITS = {"s": 1.0, "min": 60.0, "h": 3600.0}


class Column(NamedTuple):
    """A column of numbers: its place in the row, its header, its path
    (``ports.<i>.<kind>``, ``buses.<name>.battery``, ``duration`` or ``time``), its port
    (-1 for the others), its kind (``speed``, ``power``, ``torque``, ``battery`` or
    ``time``), its factor to SI and, for a battery, its bus."""

    position: int
    name: str
    path: str
    port: int
    kind: str
    scale: float
    bus: str | None = None


class Layout(NamedTuple):
    """What the header says: the port columns, the bus columns, the duration or time
    column, the mode column's place and the number of cells of a row."""

    ports: tuple[Column, ...]
    time: Column | None
    mode: int | None
    width: int
    batteries: tuple[Column, ...] = ()


def layout(header: list[str], model: Model, source: str) -> Layout:
    """Check a header against ``model``: every column known, each quantity once, each
    unit of its column's kind, a mode column when (and only when) the model has modes."""
    ports, found, batteries, seen = _port_index(model), [], [], {}
    time = mode = None
    for j, name in enumerate(cell.strip() for cell in header):
        where = f"{source}: column {brief(name)}"
        timed, match, bus = _TIME.match(name), _HEADER.match(name), _BATTERY.match(name)
        if name == "mode":
            if mode is not None or not model.modes:
                raise UsageError(f"{where}: " + ("a second mode column; a row has one mode"
                                 if mode is not None else f"the model {model.name!r} has "
                                 "no modes (no modes: table, docs/modes.md)"))
            mode = j
        elif timed:
            if time is not None:
                raise UsageError(f"{where}: " + _clash(time.name, time.path == timed["what"],
                                                       "a row's duration or its time"))
            time = Column(j, name, timed["what"], -1, "time", _time_scale(timed["unit"], where))
        elif match and match["port"].strip() in ports:
            found.append(_port_column(j, name, match, ports, seen, where))
        elif bus:
            batteries.append(_battery_column(j, name, bus, model, seen, where))
        else:
            buses = (f", BUS.battery with BUS one of {', '.join(model.buses)}"
                     if model.buses else "")
            raise UsageError(f"{where}: expected PORT.speed, PORT.power or PORT.torque "
                             f"with PORT one of {', '.join(sorted(ports))}{buses}, "
                             "duration [s], time [s] or mode")
    if not found:
        raise UsageError(f"{source}: no PORT.speed, PORT.power or PORT.torque column")
    if model.modes and mode is None:
        raise UsageError(f"{source}: no mode column, but the model has modes "
                         f"{', '.join(model.modes)}: a 'mode' column names each row's")
    return Layout(tuple(found), time, mode, len(header), tuple(batteries))


def _port_column(j: int, name: str, match: re.Match, ports: dict[str, int],
                 seen: dict[tuple, Column], where: str) -> Column:
    """The column of a port's speed, power or torque; ``seen`` by (port, speed or load)."""
    index, kind = ports[match["port"].strip()], match["what"]
    key = (index, "speed" if kind == "speed" else "load")
    if key in seen:
        raise UsageError(f"{where}: " + _clash(seen[key].name, seen[key].kind == kind,
                                               "a port's load is its power or its torque",
                                               f" (ports[{index}] {kind})"))
    seen[key] = Column(j, name, f"ports.{index}.{kind}", index, kind,
                       _scale(match["unit"], kind, where))
    return seen[key]


def _battery_column(j: int, name: str, match: re.Match, model: Model,
                    seen: dict[tuple, Column], where: str) -> Column:
    """The column of a bus's battery power (a power, W without a unit)."""
    bus = match["bus"].strip()
    if bus not in model.buses:
        raise UsageError(f"{where}: " + (
            f"unknown bus {brief(bus)} (the model's buses: {', '.join(model.buses)})"
            if model.buses else f"the model {model.name!r} has no buses (a BUS.battery "
            "column sets a bus's battery power, docs/hybrid.md)"))
    key = ("bus", bus)
    if key in seen:
        raise UsageError(f"{where}: " + _clash(seen[key].name, True, "",
                                               f" (buses.{bus}.battery)"))
    seen[key] = Column(j, name, f"buses.{bus}.battery", -1, "battery",
                       _scale(match["unit"], "power", where), bus)
    return seen[key]


def _clash(first: str, same: bool, either: str, what: str = "") -> str:
    if same:
        return f"the same quantity as column {brief(first)}{what}; one column per quantity"
    return f"conflicts with column {brief(first)}: {either}, not both"


def _port_index(model: Model) -> dict[str, int]:
    out = {str(p.component): p.index for p in model.ports}
    out.update({p.name: p.index for p in model.ports if p.name})
    return out


def _scale(unit: str | None, kind: str, where: str) -> float:
    """The SI value of one ``unit`` of ``kind`` (1 without a unit)."""
    if unit is None or not unit.strip():
        return 1.0
    try:
        return unit_factor(unit, kind, where)
    except ModelError as error:
        raise UsageError(error.message, error.path) from None


def _time_scale(unit: str | None, where: str) -> float:
    if unit is None or not unit.strip():
        return 1.0
    if unit.strip() not in TIME_UNITS:
        raise UsageError(f"{where}: {brief(unit.strip())} is not a unit of time: a duration or "
                         f"a time is written in {', '.join(TIME_UNITS)}")
    return TIME_UNITS[unit.strip()]
