"""Raw YAML data -> validated :class:`~powergraph.model.spec.Model` (SPEC §1).

Every problem is a :class:`~powergraph.errors.ModelError` naming its place in the file
(``links[2].carrier: unknown component 'c9'``). Nothing is dropped: unknown fields are
errors too.
"""
from __future__ import annotations

import dataclasses
import math
from types import MappingProxyType
from typing import Any, Callable, Mapping

from powergraph.errors import ModelError
from powergraph.model.spec import LINK_TYPES, Component, Link, Model, Port
from powergraph.model.units import parse_quantity

TOP_FIELDS = {"name", "description", "defaults", "components", "links", "ports", "tolerances"}
DEFAULT_FIELDS = {"mesh_efficiency"}
COMPONENT_FIELDS = {"role", "name", "kind", "teeth", "internal", "count", "geometry", "note"}
LINK_FIELDS = {
    "mesh": {"type", "between", "carrier", "efficiency", "ratio", "name", "note",
             "backlash", "backlash_arcmin", "cycloid", "friction", "geometry"},
    "fixed": {"type", "between", "name", "note"},
    "coupling": {"type", "between", "efficiency", "name", "note"},
    "bearing": {"type", "between", "name", "note"},
}
PORT_FIELDS = {"component", "role", "speed", "power", "torque", "name"}

#: Validators of the optional analysis blocks on mesh links: name -> f(raw, path, ctx).
#: Each returns the validated (immutable) block. Filled lazily by :func:`_block_validators`.
BlockValidator = Callable[[Any, str, Mapping[str, Component], tuple], Any]


def check_efficiency(value: Any, path: str) -> float:
    """A basic efficiency must be a number in (0, 1].

    >>> check_efficiency(0.94, "x")
    0.94
    """
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ModelError(f"efficiency must be a number in (0, 1], got {value!r}", path)
    if not (0.0 < float(value) <= 1.0) or math.isnan(value):
        raise ModelError(f"efficiency must be in (0, 1], got {value!r}", path)
    return float(value)


def require_mapping(value: Any, path: str, what: str) -> Mapping:
    if not isinstance(value, dict):
        raise ModelError(f"{what} must be a mapping, got {type(value).__name__}", path)
    return value


def reject_unknown(data: Mapping, allowed: set, path: str) -> None:
    """Raise on the first key of ``data`` not in ``allowed`` (sorted list in the message)."""
    for key in data:
        if key not in allowed:
            where = f"{path}.{key}" if path else str(key)
            raise ModelError(f"unknown field (allowed: {', '.join(sorted(allowed))})", where)


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
    if not isinstance(data, dict):
        raise ModelError(f"a model must be a mapping with name, components, links and ports; "
                         f"got {type(data).__name__}", source)
    reject_unknown(data, TOP_FIELDS, "")
    for key in ("name", "components", "links", "ports"):
        if key not in data:
            raise ModelError("missing (a model needs name, components, links and ports)", key)
    name = _text(data["name"], "name", required=True)
    description = _text(data.get("description"), "description")
    default_eta = _defaults(data.get("defaults"))
    components = _components(data["components"])
    links = tuple(_link(raw, i, components, default_eta)
                  for i, raw in enumerate(_list(data["links"], "links")))
    ports = _ports(data["ports"], components)
    from powergraph.model.graph import bodies_of, check_topology

    bodies, body_of = bodies_of(components, links)
    model = Model(name=name, description=description, components=MappingProxyType(components),
                  links=links, ports=ports, bodies=bodies,
                  body_of=MappingProxyType(body_of), source=source)
    check_topology(model)
    if "tolerances" in data:
        from powergraph.model.blocks import validate_tolerances

        model = dataclasses.replace(model, tolerances=validate_tolerances(data["tolerances"],
                                                                         model))
    return model


def _text(value: Any, path: str, required: bool = False) -> str | None:
    if value is None and not required:
        return None
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return str(value)
    if not isinstance(value, str) or (required and not value.strip()):
        raise ModelError(f"must be {'non-empty ' if required else ''}text, got {value!r}", path)
    return value


def _list(value: Any, path: str) -> list:
    if not isinstance(value, list):
        raise ModelError(f"must be a list, got {type(value).__name__}", path)
    return value


def _defaults(raw: Any) -> float:
    if raw is None:
        return 1.0
    require_mapping(raw, "defaults", "defaults")
    reject_unknown(raw, DEFAULT_FIELDS, "defaults")
    if "mesh_efficiency" not in raw:
        return 1.0
    return check_efficiency(raw["mesh_efficiency"], "defaults.mesh_efficiency")


def _component_id(raw: Any, path: str) -> str:
    if isinstance(raw, bool) or not isinstance(raw, (int, str)) or raw == "":
        raise ModelError(f"a component id must be an integer or a non-empty string, "
                         f"got {raw!r}", path)
    return str(raw)


def _components(raw: Any) -> dict[str, Component]:
    require_mapping(raw, "components", "components")
    if not raw:
        raise ModelError("no components", "components")
    components: dict[str, Component] = {}
    for raw_id, attrs in raw.items():
        path = f"components.{raw_id}"
        cid = _component_id(raw_id, "components")
        if cid in components:
            raise ModelError(f"component id {raw_id!r} is given twice (ids compare as strings)",
                             path)
        attrs = {} if attrs is None else require_mapping(attrs, path, "a component")
        components[cid] = _component(cid, raw_id, attrs, path)
    frames = [c.id for c in components.values() if c.is_frame]
    if len(frames) != 1:
        raise ModelError("exactly one component must have role: frame; "
                         f"found {len(frames)}" + (f" ({', '.join(frames)})" if frames else ""),
                         "components")
    return components


def _component(cid: str, raw_id: Any, attrs: Mapping, path: str) -> Component:
    reject_unknown(attrs, COMPONENT_FIELDS, path)
    role = attrs.get("role")
    if role is not None and role != "frame":
        raise ModelError(f"role must be 'frame' (or absent), got {role!r}", f"{path}.role")
    teeth = attrs.get("teeth")
    if teeth is not None and (isinstance(teeth, bool) or not isinstance(teeth, int) or teeth < 1):
        raise ModelError(f"teeth must be a positive integer, got {teeth!r}", f"{path}.teeth")
    count = attrs.get("count", 1)
    if isinstance(count, bool) or not isinstance(count, int) or count < 1:
        raise ModelError(f"count must be a positive integer, got {count!r}", f"{path}.count")
    internal = attrs.get("internal", False)
    if not isinstance(internal, bool):
        raise ModelError(f"internal must be true or false, got {internal!r}", f"{path}.internal")
    geometry = attrs.get("geometry")
    if geometry is not None:
        from powergraph.model.blocks import validate_geometry

        geometry = validate_geometry(geometry, f"{path}.geometry", teeth=teeth)
    return Component(id=cid, raw_id=raw_id, name=_text(attrs.get("name"), f"{path}.name"),
                     role=role, kind=_text(attrs.get("kind"), f"{path}.kind"), teeth=teeth,
                     internal=internal, count=count, geometry=geometry,
                     note=_text(attrs.get("note"), f"{path}.note"))


def _ref(raw: Any, components: Mapping[str, Component], path: str) -> str:
    if isinstance(raw, bool) or not isinstance(raw, (int, str)):
        raise ModelError(f"expected a component id, got {raw!r}", path)
    if str(raw) not in components:
        raise ModelError(f"unknown component {str(raw)!r}", path)
    return str(raw)


def _link(raw: Any, index: int, components: Mapping[str, Component], default_eta: float) -> Link:
    path = f"links[{index}]"
    require_mapping(raw, path, "a link")
    if "type" not in raw:
        raise ModelError(f"missing (one of {', '.join(LINK_TYPES)})", f"{path}.type")
    kind = raw["type"]
    if kind not in LINK_TYPES:
        raise ModelError(f"unknown link type {kind!r} (allowed: {', '.join(LINK_TYPES)})",
                         f"{path}.type")
    reject_unknown(raw, LINK_FIELDS[kind], path)
    between = raw.get("between")
    if not isinstance(between, list) or len(between) != 2:
        raise ModelError(f"must be a list of two component ids, got {between!r}",
                         f"{path}.between")
    a, b = (_ref(x, components, f"{path}.between[{i}]") for i, x in enumerate(between))
    if a == b:
        what = "a gear cannot mesh with itself" if kind == "mesh" else "a link needs two components"
        raise ModelError(f"{what} ({a!r} twice)", f"{path}.between")
    fields: dict[str, Any] = {}
    if kind == "mesh":
        fields = _mesh_fields(raw, path, (a, b), components, default_eta)
    elif kind == "coupling" and "efficiency" in raw:
        fields["efficiency"] = check_efficiency(raw["efficiency"], f"{path}.efficiency")
    return Link(index=index, type=kind, between=(a, b), raw_between=tuple(between),
                name=_text(raw.get("name"), f"{path}.name"), **fields)


def _mesh_fields(raw: Mapping, path: str, pair: tuple[str, str],
                 components: Mapping[str, Component], default_eta: float) -> dict:
    a, b = pair
    frame = next(c.id for c in components.values() if c.is_frame)
    carrier = _ref(raw["carrier"], components, f"{path}.carrier") if "carrier" in raw else frame
    if carrier in pair:
        raise ModelError(f"the carrier {carrier!r} cannot be one of the meshing gears",
                         f"{path}.carrier")
    ratio = raw.get("ratio")
    if ratio is not None:
        if isinstance(ratio, bool) or not isinstance(ratio, (int, float)) \
                or not math.isfinite(ratio) or ratio == 0:
            raise ModelError(f"ratio must be a non-zero number, got {ratio!r}", f"{path}.ratio")
        ratio = float(ratio)
    else:
        for i, gear in enumerate(pair):
            if components[gear].teeth is None:
                raise ModelError(f"component {gear!r} meshes but has no teeth "
                                 "(give teeth, or ratio on the mesh)", f"{path}.between[{i}]")
        if components[a].internal and components[b].internal:
            raise ModelError("two internal gears cannot mesh", f"{path}.between")
    eta = check_efficiency(raw["efficiency"], f"{path}.efficiency") \
        if "efficiency" in raw else default_eta
    blocks = {}
    if any(key in raw for key in ("backlash", "backlash_arcmin", "cycloid", "friction",
                                  "geometry")):
        from powergraph.model.blocks import validate_mesh_blocks

        blocks = validate_mesh_blocks(raw, path, pair, components)
    if "friction" in blocks and not blocks["friction"].load_dependent:
        eta = blocks["friction"].efficiency()[1]
    return {"carrier": carrier, "ratio": ratio, "efficiency": eta,
            "blocks": MappingProxyType(blocks)}


def _ports(raw: Any, components: Mapping[str, Component]) -> tuple[Port, ...]:
    ports = []
    seen: dict[str, int] = {}
    for index, item in enumerate(_list(raw, "ports")):
        path = f"ports[{index}]"
        require_mapping(item, path, "a port")
        reject_unknown(item, PORT_FIELDS, path)
        if "component" not in item:
            raise ModelError("missing", f"{path}.component")
        component = _ref(item["component"], components, f"{path}.component")
        if components[component].is_frame:
            raise ModelError("the frame cannot be a port (it does not turn)", f"{path}.component")
        if component in seen:
            raise ModelError(f"component {component!r} already has a port (ports[{seen[component]}])",
                             f"{path}.component")
        seen[component] = index
        role = item.get("role")
        if role not in ("input", "output"):
            raise ModelError(f"role must be 'input' or 'output', got {role!r}", f"{path}.role")
        if "power" in item and "torque" in item:
            raise ModelError("give at most one of power and torque", path)
        values = {key: parse_quantity(item[key], key, f"{path}.{key}")
                  for key in ("speed", "power", "torque") if item.get(key) is not None}
        ports.append(Port(index=index, component=component, role=role,
                          name=_text(item.get("name"), f"{path}.name"), **values))
    if not any(p.role == "input" for p in ports) or not any(p.role == "output" for p in ports):
        raise ModelError("a train needs at least one input and one output port", "ports")
    return tuple(ports)
