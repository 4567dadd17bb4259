"""Modes as operating states (docs/modes.md): the ports a mode leaves inactive and the
operating point it sets, read from the ``modes`` table and applied to a model.

A mode is a list of engaged clutches and brakes, or a mapping::

    EV1: {engage: [C1], inactive: [engine, MG-A],
          ports: {wheels: {power: -20 kW}}, buses: {dc: {battery: free}}}

``inactive`` ports (by name or component id) carry nothing in the mode; ``ports`` gives a
port's ``speed``, ``power`` or ``torque`` in the mode (``free`` drops the model's value),
``buses`` a bus's ``battery``. :func:`read_mode_specs` reads them (every problem a
:class:`~powergraph.errors.ModelError` naming its place, ``modes.EV1.inactive[0]: unknown
port 'engin'``); :func:`at_mode_point` puts a model at a mode's point.

Examples
--------
>>> from powergraph.model import model_from_dict
>>> m = model_from_dict({"name": "p1", "components": {0: {"role": "frame"},
...     "e": {}, "w": {"teeth": 20}, "g": {"teeth": 40}},
...     "links": [{"type": "mesh", "between": ["w", "g"]},
...               {"type": "clutch", "name": "C", "between": ["e", "w"]}],
...     "ports": [{"component": "e", "role": "input", "name": "engine", "speed": 100,
...                "power": 1000},
...               {"component": "w", "role": "machine", "name": "MG", "bus": "dc"},
...               {"component": "g", "role": "output", "name": "wheels"}],
...     "buses": {"dc": {"battery": 0}},
...     "modes": {"EV": {"inactive": ["engine"], "ports": {"MG": {"speed": 100}},
...                      "buses": {"dc": {"battery": "free"}}},
...               "P1": {"engage": ["C"]}}})
>>> spec = m.mode_specs["EV"]
>>> spec.engaged, spec.inactive, dict(spec.ports[1]), dict(spec.buses)
((), (0,), {'speed': 100.0}, {'dc': None})
>>> ev = at_mode_point(m, "EV")
>>> ev.ports[0].speed, ev.ports[0].torque, ev.ports[1].speed, ev.buses["dc"].battery
(None, 0.0, 100.0, None)
>>> sorted(ev.inactive), [p.name for p in ev.inputs]
([0], [])
"""
from __future__ import annotations

import dataclasses
from types import MappingProxyType
from typing import Any, Mapping

from powergraph.errors import ModelError
from powergraph.model.input_files import brief
from powergraph.model.names import name_text
from powergraph.model.schema_parts import PORT_RANGES
from powergraph.model.spec_parts import Bus, ModeSpec, Port

#: The fields of a port a mode may give.
PORT_FIELDS = ("speed", "power", "torque")
#: The word that drops a value in a mode (as a bus's ``battery: free``).
FREE = "free"



def read_mode_specs(raw: Mapping, engaged: Mapping[str, tuple[str, ...]],
                    ports: tuple[Port, ...], buses: Mapping[str, Bus]
                    ) -> Mapping[str, ModeSpec]:
    """Every mode of the ``modes`` table (``raw``, checked by the schema) as a
    :class:`ModeSpec`; ``engaged`` its engaged elements as read by
    :func:`powergraph.model.shift.read_modes`."""
    names = _port_names(ports)
    specs = {}
    for (key, entry), mode in zip(raw.items(), engaged):
        if not isinstance(entry, Mapping):
            specs[mode] = ModeSpec(engaged=engaged[mode])
            continue
        path = f"modes.{mode}"
        inactive = _inactive(entry.get("inactive") or [], names, ports, f"{path}.inactive")
        values = _port_values(entry.get("ports") or {}, names, ports, inactive, path)
        battery = _batteries(entry.get("buses") or {}, buses, f"{path}.buses")
        specs[mode] = ModeSpec(engaged=engaged[mode], inactive=tuple(inactive),
                               ports=MappingProxyType(values),
                               buses=MappingProxyType(battery))
    return MappingProxyType(specs)


def _port_names(ports: tuple[Port, ...]) -> dict[str, int]:
    """A port by its component id or its name (as a duty cycle's columns address it)."""
    out = {str(p.component): p.index for p in ports}
    out.update({p.name.strip(): p.index for p in ports if p.name})
    return out


def _port(name: Any, names: Mapping[str, int], ports: tuple[Port, ...], path: str) -> int:
    text = name_text(name, path, "port name").strip()
    if text not in names:
        known = ", ".join(p.name or str(p.component) for p in ports)
        raise ModelError(f"unknown port {brief(text)} (the model's ports: {known})", path)
    return names[text]


def _label(port: Port) -> str:
    return f"{port.path} ({port.name})" if port.name else f"{port.path}"


def _inactive(raw: list, names, ports, path: str) -> list[int]:
    out: list[int] = []
    for i, name in enumerate(raw):
        index = _port(name, names, ports, f"{path}[{i}]")
        if index in out:
            raise ModelError(f"{_label(ports[index])} is listed twice", f"{path}[{i}]")
        out.append(index)
    return out


def _port_values(raw: Mapping, names, ports, inactive: list[int], path: str) -> dict:
    from powergraph.model.units import parse_quantity

    out: dict[int, Mapping[str, float | None]] = {}
    for name, given in raw.items():
        where = f"{path}.ports.{name}"
        index = _port(name, names, ports, where)
        if index in inactive:
            raise ModelError(f"{_label(ports[index])} is inactive in this mode "
                             f"({path}.inactive): it takes no speed, power or torque", where)
        if index in out:
            raise ModelError(f"{_label(ports[index])} is given twice (by its name and its "
                             "component)", where)
        if "power" in given and "torque" in given:
            raise ModelError("give at most one of power and torque", where)
        values: dict[str, float | None] = {}
        for kind in PORT_FIELDS:
            if kind not in given:
                continue
            value = given[kind]
            if isinstance(value, str) and value.strip() == FREE:
                values[kind] = None
                continue
            number = parse_quantity(value, kind, f"{where}.{kind}")
            limit, unit = PORT_RANGES[kind]
            if not abs(number) <= limit:
                raise ModelError(f"{kind} must be within ±{limit:g} {unit}, got "
                                 f"{brief(value)}", f"{where}.{kind}")
            values[kind] = number
        out[index] = MappingProxyType(values)
    return out


def _batteries(raw: Mapping, buses: Mapping[str, Bus], path: str) -> dict[str, float | None]:
    from powergraph.model.units import parse_quantity

    out: dict[str, float | None] = {}
    for name, given in raw.items():
        text = name_text(name, f"{path}.{name}", "bus name")
        if text not in buses:
            known = ", ".join(buses) or "none"
            raise ModelError(f"unknown bus {brief(text)} (the model's buses: {known})",
                             f"{path}.{name}")
        battery = given["battery"]
        out[text] = None if battery in (None, FREE) else parse_quantity(
            battery, "power", f"{path}.{name}.battery")
    return out


def spec_of(model: Any, mode: str | None) -> ModeSpec | None:
    """The :class:`ModeSpec` of ``mode`` (None for no mode, or a model without specs)."""
    if mode is None:
        return None
    return model.mode_specs.get(mode)


def at_mode_point(model: Any, mode: str | None, loaded: Any = None) -> Any:
    """``model`` at the operating point of ``mode``: its inactive ports carrying nothing
    (torque 0, no speed), the ports and buses the mode gives set to its values.

    Parameters
    ----------
    model : Model
        The model, or a variant of it (other values, the same train: a duty cycle's row).
    mode : str or None
        A key of its modes table; None returns ``model``.
    loaded : Model, optional
        The model ``model`` is a variant of. Given, a value the variant changed from
        ``loaded`` is kept (a port's speed, its load — power or torque —, a bus's
        battery), so the variant's values come first, then the mode's, then the
        model's; without it the mode's replace the model's.

    Returns
    -------
    Model
        A new model with ``inactive`` and ``point_of`` set (``model`` itself when it is at
        that point already).
    """
    spec = spec_of(model, mode)
    if mode is None or model.point_of == mode:
        return model
    if spec is None or not spec.changes_point:
        return dataclasses.replace(model, point_of=mode)
    ports = list(model.ports)
    for index, values in spec.ports.items():
        ports[index] = _set_port(ports[index], values,
                                 None if loaded is None else loaded.ports[index])
    for index in spec.inactive:
        if loaded is not None:
            _refuse_values(ports[index], loaded.ports[index], mode)
        ports[index] = dataclasses.replace(ports[index], speed=None, power=None, torque=0.0)
    buses = dict(model.buses)
    for name, battery in spec.buses.items():
        if loaded is None or loaded.buses[name] == buses[name]:
            buses[name] = dataclasses.replace(buses[name], battery=battery)
    return dataclasses.replace(model, ports=tuple(ports), buses=MappingProxyType(buses),
                               inactive=frozenset(spec.inactive), point_of=mode)


def _refuse_values(port: Port, loaded: Port, mode: str) -> None:
    """A variant that gives an inactive port a value of its own (a duty cycle's cell) is
    refused: the mode says the port carries nothing. A value the variant leaves out, or
    leaves as the model has it, is no conflict."""
    for kind in PORT_FIELDS:
        value = getattr(port, kind)
        if value is not None and value != getattr(loaded, kind):
            raise ModelError(f"{_label(port)} is inactive in mode {mode!r}: it takes no "
                             f"{kind} (given {value:.6g} in SI units)",
                             f"modes.{mode}.inactive")


def _set_port(port: Port, values: Mapping[str, float | None], loaded: Port | None) -> Port:
    changes: dict[str, float | None] = {}
    if "speed" in values and (loaded is None or loaded.speed == port.speed):
        changes["speed"] = values["speed"]
    load = [k for k in ("power", "torque") if k in values]
    if load and (loaded is None or (loaded.power, loaded.torque) == (port.power, port.torque)):
        changes.update(power=None, torque=None)
        changes[load[0]] = values[load[0]]
    return dataclasses.replace(port, **changes) if changes else port
