"""Electric machines on electrical buses (docs/hybrid.md): the ``efficiency``, ``bus`` and
``max_speed`` of a ``role: machine`` port, and the top-level ``buses:`` block.

A machine turns electrical power into mechanical power at its port: it draws ``P/η`` from
its bus when it motors (``P`` > 0, mechanical power into the train) and returns ``P·η``
when it generates. Each bus balances: the battery's power into it equals what its
machines draw. A bus whose battery is ``free`` (or omitted) adds no equation.

Examples
--------
>>> from powergraph.model.spec import Port
>>> mg = Port(index=0, component="S", role="machine", efficiency=0.9, bus="dc")
>>> buses_of({"dc": {"battery": "0 W"}}, (mg,))["dc"].battery
0.0
"""
from __future__ import annotations

from pathlib import Path
from types import MappingProxyType
from typing import Any, Mapping

from powergraph.errors import ModelError
from powergraph.model.names import name_text
from powergraph.model.spec import Bus, Port
from powergraph.model.units import parse_quantity

_FREE = (None, "free")


def machine_fields(item: Mapping[str, Any], path: str,
                   folder: Path | None = None) -> dict[str, Any]:
    """``{efficiency, bus, max_speed}`` of a port: a machine needs a bus (efficiency
    default 1, or ``{map: FILE.csv}`` read relative to ``folder``, the model file's folder;
    ``max_speed`` optional, rad/s, > 0 by the schema); an input or output takes none.

    >>> machine_fields({"role": "machine", "bus": "dc", "max_speed": "3000 rpm"}, "x")
    {'efficiency': 1.0, 'bus': 'dc', 'max_speed': 314.1592653589793}
    """
    if item.get("role") != "machine":
        for key in ("efficiency", "bus", "max_speed"):
            if key in item:
                raise ModelError(f"only a machine port (role: machine) has {key}",
                                 f"{path}.{key}")
        return {}
    if item.get("bus") is None:
        raise ModelError("a machine needs the bus it is on (bus: NAME, a key of buses)",
                         f"{path}.bus")
    efficiency = item.get("efficiency", 1.0)
    if isinstance(efficiency, Mapping):
        from powergraph.model.efficiency_table import read_efficiency_table

        efficiency = read_efficiency_table(str(efficiency["map"]), folder,
                                           f"{path}.efficiency.map")
    else:
        efficiency = float(efficiency)
    max_speed = item.get("max_speed")
    if max_speed is not None:
        max_speed = parse_quantity(max_speed, "speed", f"{path}.max_speed")
    return {"efficiency": efficiency, "bus": name_text(item["bus"], f"{path}.bus", "bus name"), "max_speed": max_speed}


def buses_of(raw: Mapping | None, ports: tuple[Port, ...]) -> Mapping[str, Bus]:
    """The ``buses:`` block checked against the machine ports: every machine's bus is
    declared, every bus has a machine, a battery power is a power or ``free``."""
    raw = raw or {}
    buses = {}
    for name, attrs in raw.items():
        path = f"buses.{name}"
        battery = (attrs or {}).get("battery")
        value = None if battery in _FREE else parse_quantity(battery, "power",
                                                              f"{path}.battery")
        text = name_text(name, path, "bus name")
        buses[text] = Bus(name=text, battery=value)
    used = set()
    for port in ports:
        if port.bus is None:
            continue
        if port.bus not in buses:
            raise ModelError(f"unknown bus {port.bus!r} (declare it under buses:)",
                             f"{port.path}.bus")
        used.add(port.bus)
    for name in buses:
        if name not in used:
            raise ModelError("no machine is on this bus", f"buses.{name}")
    return MappingProxyType(buses)
