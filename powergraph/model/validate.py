"""Raw YAML data -> validated :class:`~powergraph.model.spec.Model`.

The format is checked against the schema (:mod:`powergraph.model.schema`, through
:func:`~powergraph.model.conform.check_document`); this module adds what a schema cannot
say -- component references, exactly one frame, teeth for a mesh, the carrier -- and builds
the immutable model. Every problem is a :class:`~powergraph.errors.ModelError` naming its
place in the file (``links[2].carrier: unknown component 'c9'``); nothing is dropped.
Everything here is linear in the size of the model. The format: docs/format.md.
"""
from __future__ import annotations

import dataclasses
from pathlib import Path
from types import MappingProxyType
from typing import Any, Mapping

from powergraph.errors import Caveat, ModelError
from powergraph.model.buses import buses_of, machine_fields
from powergraph.model.conform import check_document
from powergraph.model.names import name_text, optional_name
from powergraph.model.schema_parts import PORT_RANGES  # noqa: F401 (re-exported)
from powergraph.model.spec import SHIFT_TYPES, Component, Link, Model, Port
from powergraph.model.units import bare_speed_caveat, parse_quantity
from powergraph.model.yaml_loader import brief, gc_paused



def check_port_ranges(model: Model, speeds: Mapping[str, float] | None = None) -> None:
    """Refuse port values a model file could not hold (a speed beyond ``MAX_SPEED``, a
    power or torque beyond ``MAX_POWER``/``MAX_TORQUE``, SI, or not finite): a model
    changed in Python (``Model.with_port``) or a duty cycle's row is held to the same
    ranges as the file, so no solve runs on numbers that overflow on the way.

    >>> from powergraph.model import load_model
    >>> m = load_model("models/planetary_2kh_carrier_to_ring.yaml")
    >>> check_port_ranges(m.with_port(0, power=1e308))
    Traceback (most recent call last):
    ...
    powergraph.errors.ModelError: ports[0].power: 1e+308 is out of range: at most 1e+12 W \
either way
    """
    for port in model.ports:
        for kind, value in (("speed", port.speed), ("power", port.power),
                            ("torque", port.torque)):
            _in_range(value, kind, f"{port.path}.{kind}")
    for component, value in (speeds or {}).items():
        _in_range(value, "speed", f"speed of {component}")


def _in_range(value: float | None, kind: str, path: str) -> None:
    limit, unit = PORT_RANGES[kind]
    if value is not None and not abs(value) <= limit:
        raise ModelError(f"{value:g} is out of range: at most {limit:g} {unit} either way",
                         path)


def model_from_dict(data: Any, source: str | None = None) -> Model:
    """Validate plain data (as read from YAML) into a :class:`Model`.

    Parameters
    ----------
    data : dict
        The document: ``name``, ``components``, ``links``, ``ports`` (``defaults`` and
        ``description`` optional).
    source : str, optional
        File name, kept on the model for messages.

    Examples
    --------
    >>> m = model_from_dict({
    ...     "name": "pair",
    ...     "components": {0: {"role": "frame"}, 1: {"teeth": 20}, 2: {"teeth": 40}},
    ...     "links": [{"type": "mesh", "between": [1, 2], "carrier": 0}],
    ...     "ports": [{"component": 1, "role": "input"}, {"component": 2, "role": "output"}]})
    >>> m.meshes[0].between, [b.id for b in m.bodies]
    (('1', '2'), ['0', '1', '2'])
    """
    with gc_paused():
        return _model(data, source)


def _model(data: Any, source: str | None) -> Model:
    check_document(data, source)
    default_eta = float((data.get("defaults") or {}).get("mesh_efficiency", 1.0))
    components = _components(data["components"])
    frame = next(c.id for c in components.values() if c.is_frame)
    links = tuple(_link(raw, i, components, frame, default_eta)
                  for i, raw in enumerate(data["links"]))
    links, shift_elements, modes = _shift_elements(data, links, components, frame)
    caveats: list[Caveat] = []  # other checks append theirs
    ports = _ports(data["ports"], components, caveats, _folder(source))
    from powergraph.model.graph import bodies_of, check_topology

    bodies, body_of = bodies_of(components, links)
    buses = buses_of(data.get("buses"), ports)
    specs = MappingProxyType({})
    if modes:
        from powergraph.model.mode_specs import read_mode_specs

        specs = read_mode_specs(data["modes"], modes, ports, buses)
    model = Model(name=name_text(data["name"], "name", "model name"),
                  description=_text(data.get("description")),
                  components=MappingProxyType(components), links=links, ports=ports,
                  bodies=bodies, body_of=MappingProxyType(body_of), source=source,
                  shift_elements=shift_elements, modes=modes,
                  mode=next(iter(modes), None), warnings=tuple(caveats),
                  buses=buses, mode_specs=specs, **_oil(data))
    model = _bind_oil(model)
    if modes:
        model = _default_state(model)
    check_topology(model)
    _check_churning(model)
    if model.has_bearing_losses:
        from powergraph.model.block_bearing import check_bearing_loads

        check_bearing_loads(model)
    from powergraph.model.feasibility import feasibility_caveats

    model = dataclasses.replace(model, warnings=model.warnings + feasibility_caveats(model))
    if "tolerances" in data:
        from powergraph.model.blocks import validate_tolerances

        model = dataclasses.replace(model, tolerances=validate_tolerances(data["tolerances"],
                                                                         model))
    return model


def _check_churning(model: Model) -> None:
    """Churning is a gear's against the housing: a planet's (its mesh on a moving
    carrier) is not modelled."""
    for link in model.meshes:
        if model.body_of[link.carrier] == model.frame_body:
            continue
        for gear in link.between:
            component = model.components[gear]
            if component.churning is not None:
                raise ModelError("churning of a planet (a gear on a moving carrier) is not "
                                 "modelled", f"components.{component.raw_id}.churning")


def _oil(data: Mapping) -> dict[str, Any]:
    """The ``lubricant`` and ``thermal`` blocks, read (a heat balance needs an oil)."""
    if "lubricant" not in data and "thermal" not in data:
        return {}
    from powergraph.model.lubricant import parse_lubricant, parse_thermal

    if "thermal" in data and "lubricant" not in data:
        raise ModelError("a heat balance sets the oil's temperature: give the model a "
                         "lubricant: block too", "thermal")
    out = {"lubricant": parse_lubricant(data["lubricant"], "lubricant")}
    if "thermal" in data:
        out["thermal"] = parse_thermal(data["thermal"], "thermal")
    return out


def _bind_oil(model: Model) -> Model:
    """Every viscous law bound to the oil at its temperature (or refused without one)."""
    from powergraph.model.lubricant import bind_oil

    return bind_oil(model)


def _default_state(model: Model) -> Model:
    """The model in its default state: the first mode with its freewheels holding, or
    overrunning where holding them all would join what cannot be joined (a freewheel
    between the input and the output, or holding a port); errors name the mode."""
    from powergraph.model.graph import bodies_of
    from powergraph.model.modes import resolve

    try:
        resolve(model, model.mode, {e.name: True for e in model.shift_elements
                                    if e.kind == "freewheel"})
        return model
    except ModelError:
        overrunning = resolve(model, model.mode)      # the mode's own error, if any
    # the links of the mode, the ports as loaded (the mode's point is the case's)
    bodies, body_of = bodies_of(model.components, overrunning.links)
    return dataclasses.replace(model, links=overrunning.links, bodies=bodies,
                               body_of=MappingProxyType(body_of))


def _shift_elements(data: Mapping, links: tuple, components: Mapping[str, Component],
                    frame: str) -> tuple[tuple, tuple, Any]:
    """Clutches, brakes and freewheels, each resolved in ``links`` to its default state,
    and the modes table (docs/modes.md)."""
    if not any(link is None for link in links):
        if "modes" in data:
            raise ModelError("a modes table needs shift elements (clutch, brake or freewheel "
                             "links)", "modes")
        return links, (), MappingProxyType({})
    from powergraph.model.shift import as_link, check_names, read_modes, shift_element

    elements = tuple(shift_element(raw, i, _pair(raw, i, components), components, frame)
                     for i, (raw, link) in enumerate(zip(data["links"], links))
                     if link is None)
    check_names(elements)
    modes = read_modes(data["modes"], elements) if "modes" in data else MappingProxyType({})
    # The state without a mode: each element's `engaged`; with modes, the first mode with
    # its freewheels holding (docs/modes.md).
    first = set(next(iter(modes.values()))) if modes else None
    resolved = list(links)
    for element in elements:
        on = element.engaged if first is None else (
            element.name in first or element.kind == "freewheel")
        resolved[element.index] = as_link(element, on)
    return tuple(resolved), elements, modes


def _pair(raw: Mapping, index: int, components: Mapping[str, Component]) -> tuple[str, str]:
    return tuple(_ref(x, components, f"links[{index}].between[{i}]")  # type: ignore[return-value]
                 for i, x in enumerate(raw["between"]))


def _text(value: Any) -> str | None:
    """Text fields may be written as numbers (``name: 2024``); they are kept as text."""
    return None if value is None else str(value)


def _components(raw: Mapping) -> dict[str, Component]:
    components: dict[str, Component] = {}
    for raw_id, attrs in raw.items():
        path = f"components.{raw_id}"
        if isinstance(raw_id, (bool, str)) or raw_id is None:
            name_text(raw_id, path, "component id")    # a boolean, nothing, two lines
        if not isinstance(raw_id, (int, str)) or raw_id == "":
            raise ModelError("a component id must be an integer or a non-empty string, "
                             f"got {brief(raw_id)}", "components")
        cid = str(raw_id)
        if cid in components:
            raise ModelError(f"component id {brief(raw_id)} is given twice (ids compare as strings)",
                             path)
        components[cid] = _component(cid, raw_id, attrs or {}, path)
    frames = [c.id for c in components.values() if c.is_frame]
    if len(frames) != 1:
        raise ModelError("exactly one component must have role: frame; "
                         f"found {len(frames)}" + (f" ({', '.join(frames)})" if frames else ""),
                         "components")
    return components


def _component(cid: str, raw_id: Any, attrs: Mapping, path: str) -> Component:
    teeth = attrs.get("teeth")
    geometry = attrs.get("geometry")
    if geometry is not None:
        from powergraph.model.blocks import validate_geometry

        geometry = validate_geometry(geometry, f"{path}.geometry", teeth=teeth)
    drag = attrs.get("drag")
    if drag is not None:
        from powergraph.model.block_bearing import parse_drag

        if attrs.get("role") == "frame":
            raise ModelError("the frame does not turn, so it has no drag", f"{path}.drag")
        drag = parse_drag(drag, f"{path}.drag")
    component = Component(id=cid, raw_id=raw_id,
                          name=optional_name(attrs.get("name"), f"{path}.name",
                                             "component name"),
                          role=attrs.get("role"), kind=_text(attrs.get("kind")), teeth=teeth,
                          internal=attrs.get("internal", False), count=attrs.get("count", 1),
                          geometry=geometry, note=_text(attrs.get("note")), drag=drag)
    if "churning" in attrs:
        from powergraph.model.block_spin import parse_churning

        if attrs.get("role") == "frame":
            raise ModelError("the frame does not turn, so it churns no oil",
                             f"{path}.churning")
        component = dataclasses.replace(component, churning=parse_churning(
            attrs["churning"], component, f"{path}.churning"))
    return component


def _ref(raw: Any, components: Mapping[str, Component], path: str) -> str:
    if str(raw) not in components:
        raise ModelError(f"unknown component {brief(str(raw))}", path)
    return str(raw)


def _link(raw: Mapping, index: int, components: Mapping[str, Component], frame: str,
          default_eta: float) -> Link | None:
    """The link at ``links[index]``; None for a shift element (read by _shift_elements)."""
    path, kind, between = f"links[{index}]", raw["type"], raw["between"]
    a, b = (_ref(x, components, f"{path}.between[{i}]") for i, x in enumerate(between))
    if a == b:
        what = "a gear cannot mesh with itself" if kind == "mesh" else "a link needs two components"
        raise ModelError(f"{what} ({a!r} twice)", f"{path}.between")
    if kind in SHIFT_TYPES:
        return None
    fields: dict[str, Any] = {}
    if kind == "mesh":
        fields = _mesh_fields(raw, path, (a, b), components, frame, default_eta)
    elif kind == "coupling" and "efficiency" in raw:
        fields["efficiency"] = float(raw["efficiency"])
    elif kind == "bearing" and ("friction" in raw or "drag" in raw or "skf" in raw):
        from powergraph.model.block_bearing import parse_bearing_blocks

        fields["blocks"] = MappingProxyType(parse_bearing_blocks(raw, path))
    elif kind == "seal":
        from powergraph.model.block_bearing import parse_seal

        fields["blocks"] = MappingProxyType(parse_seal(raw, path))
    return Link(index=index, type=kind, between=(a, b), raw_between=tuple(between),
                name=optional_name(raw.get("name"), f"links[{index}].name", "link name"),
                **fields)


def _mesh_fields(raw: Mapping, path: str, pair: tuple[str, str],
                 components: Mapping[str, Component], frame: str, default_eta: float) -> dict:
    carrier = _ref(raw["carrier"], components, f"{path}.carrier") if "carrier" in raw else frame
    if carrier in pair:
        raise ModelError(f"the carrier {carrier!r} cannot be one of the meshing gears",
                         f"{path}.carrier")
    ratio = raw.get("ratio")
    if ratio is None:
        for i, gear in enumerate(pair):
            if components[gear].teeth is None:
                raise ModelError(f"component {gear!r} meshes but has no teeth "
                                 "(give teeth, or ratio on the mesh)", f"{path}.between[{i}]")
        if components[pair[0]].internal and components[pair[1]].internal:
            raise ModelError("two internal gears cannot mesh", f"{path}.between")
    blocks = {}
    if any(key in raw for key in ("backlash", "backlash_arcmin", "cycloid", "friction",
                                  "geometry", "pins", "output_pins", "crank_bearing")):
        from powergraph.model.blocks import validate_mesh_blocks

        blocks = validate_mesh_blocks(raw, path, pair, components)
    eta = float(raw.get("efficiency", default_eta))
    if "friction" in blocks and not blocks["friction"].load_dependent:
        eta = blocks["friction"].efficiency()[1]     # constant coefficient: docs/losses.md
    return {"carrier": carrier, "ratio": None if ratio is None else float(ratio),
            "efficiency": eta, "blocks": MappingProxyType(blocks)}


def _folder(source: str | None) -> Path | None:
    """The folder of the model file, where files it names are read; None (the working
    folder) for a model that is no file."""
    if not source or source.startswith("<"):
        return None
    return Path(source).parent


def _ports(raw: list, components: Mapping[str, Component],
           caveats: list[Caveat], folder: Path | None = None) -> tuple[Port, ...]:
    ports = []
    seen: dict[str, int] = {}
    for index, item in enumerate(raw):
        path = f"ports[{index}]"
        component = _ref(item["component"], components, f"{path}.component")
        if components[component].is_frame:
            raise ModelError("the frame cannot be a port (it does not turn)", f"{path}.component")
        if component in seen:
            raise ModelError(f"component {component!r} already has a port "
                             f"(ports[{seen[component]}]); for two ports on one shaft, put "
                             "this one on a component of its own joined to it by a fixed "
                             "link", f"{path}.component")
        seen[component] = index
        if "power" in item and "torque" in item:
            raise ModelError("give at most one of power and torque", path)
        values = {key: parse_quantity(item[key], key, f"{path}.{key}")
                  for key in ("speed", "power", "torque") if item.get(key) is not None}
        for key in ("speed", "max_speed"):  # a speed without a unit is rad/s, but said so
            caveat = bare_speed_caveat(item.get(key), f"{path}.{key}")
            if caveat is not None:
                caveats.append(caveat)
        ports.append(Port(index=index, component=component, role=item["role"],
                          name=optional_name(item.get("name"), f"{path}.name", "port name"),
                          **values,
                          **machine_fields(item, path, folder)))
    if not any(p.role == "input" for p in ports) or not any(p.role == "output" for p in ports):
        raise ModelError("a train needs at least one input and one output port", "ports")
    _check_port_names(ports, components)
    return tuple(ports)


def _check_port_names(ports: list[Port], components: Mapping[str, Component]) -> None:
    """A port's name addresses it -- a duty cycle's ``NAME.speed`` column (where a
    component id addresses its port too), a machine's losses and flow-graph node -- so it
    is not blank, not another port's name, and not the id of another component. A port
    may bear its own component's id: both then address the same port. Names compare as
    written apart from the spaces around them (a CSV header's are dropped)."""
    named: dict[str, int] = {}
    ports_of = {p.component: p.index for p in ports}
    ids = {cid.strip(): cid for cid in components}
    # what reports call a machine without a name (statics.machines.machine_name)
    unnamed = {f"machine {components[p.component].raw_id}": p.index
               for p in ports if p.is_machine and p.name is None}
    for port in ports:
        if port.name is None:
            continue
        name, path = port.name.strip(), f"{port.path}.name"
        if not name:
            raise ModelError("a port name must not be blank (leave name out for none)", path)
        if name in named:
            raise ModelError(f"port name {name!r} is already the name of ports[{named[name]}] "
                             "(port names are unique)", path)
        cid = ids.get(name)
        if cid is not None and cid != port.component:
            owner = f", the component of ports[{ports_of[cid]}]" if cid in ports_of else ""
            raise ModelError(f"port name {name!r} is the id of component {cid!r}{owner}: a "
                             "duty cycle's columns would not know which port it means; "
                             "rename the port", path)
        if name in unnamed:
            raise ModelError(f"port name {name!r} is the name reports give the machine "
                             f"ports[{unnamed[name]}], which has none; name that port, or "
                             "rename this one", path)
        named[name] = port.index
