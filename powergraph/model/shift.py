"""Reading the shift elements (clutch, brake, freewheel links) and the ``modes`` table
into a model (docs/modes.md).

A shift element stays in ``Model.links`` at its own index, resolved to a classic link:
``fixed`` when engaged (one rigid body, the same as a file written with ``fixed``), and
``bearing`` when open (no kinematic constraint; its ``drag`` acts in its slip speed, as a
bearing's does). The element itself is kept in ``Model.shift_elements``, so that
:func:`powergraph.model.modes.resolve` can resolve it again for any mode.

Examples
--------
>>> from powergraph.model import model_from_dict
>>> m = model_from_dict({"name": "pair", "components": {0: {"role": "frame"},
...     1: {"teeth": 20}, 2: {"teeth": 40}, 3: {}},
...     "links": [{"type": "mesh", "between": [1, 2]},
...               {"type": "clutch", "name": "C1", "between": [2, 3], "engaged": True}],
...     "ports": [{"component": 1, "role": "input", "speed": 10},
...               {"component": 3, "role": "output"}]})
>>> m.shift_elements[0].name, m.links[1].type, [b.id for b in m.bodies]
('C1', 'fixed', ['0', '1', '2/3'])
"""
from __future__ import annotations

from types import MappingProxyType
from typing import Any, Mapping

from powergraph.errors import ModelError
from powergraph.model.names import name_text
from powergraph.model.spec_parts import Component, Link, ShiftElement


def shift_element(raw: Mapping, index: int, between: tuple[str, str],
                  components: Mapping[str, Component], frame: str) -> ShiftElement:
    """Read ``links[index]`` (a clutch, brake or freewheel, checked by the schema)."""
    path, kind = f"links[{index}]", raw["type"]
    if kind == "brake" and between[1] != frame:
        raise ModelError(f"a brake holds a member against the frame: write between: "
                         f"[member, {components[frame].raw_id!r}]", f"{path}.between[1]")
    if kind == "clutch" and frame in between:
        raise ModelError("a clutch to the frame is a brake (type: brake)", f"{path}.type")
    drag = None
    if "drag" in raw:
        from powergraph.model.block_bearing import parse_drag

        drag = parse_drag(raw["drag"], f"{path}.drag")
    name = name_text(raw["name"], f"{path}.name", "shift element name")
    return ShiftElement(index=index, kind=kind, name=name, between=between,
                        raw_between=tuple(raw["between"]),
                        engaged=bool(raw.get("engaged", False)), holds=raw.get("holds"),
                        drag=drag)


def as_link(element: ShiftElement, engaged: bool) -> Link:
    """The classic link that stands for ``element`` in that state: ``fixed`` when engaged,
    a ``bearing`` carrying only its drag when open."""
    blocks = {} if engaged or element.drag is None else {"drag": element.drag}
    return Link(index=element.index, type="fixed" if engaged else "bearing",
                between=element.between, raw_between=element.raw_between,
                name=element.name, blocks=MappingProxyType(blocks))


def check_names(elements: tuple[ShiftElement, ...]) -> None:
    """Shift-element names are unique."""
    seen: dict[str, int] = {}
    for element in elements:
        if element.name in seen:
            raise ModelError(f"shift element name {element.name!r} is used twice "
                             f"(links[{seen[element.name]}])", f"{element.path}.name")
        seen[element.name] = element.index


def read_modes(raw: Any, elements: tuple[ShiftElement, ...]) -> Mapping[str, tuple[str, ...]]:
    """``modes`` as ``{name: engaged element names}``, every name known and not a freewheel
    (freewheels decide for themselves), none twice. A mode is a list of names or a
    mapping whose ``engage`` lists them (its other keys: :mod:`powergraph.model.mode_specs`)."""
    by_name = {e.name: e for e in elements}
    modes: dict[str, tuple[str, ...]] = {}
    for mode, entry in raw.items():
        path = f"modes.{mode}"
        names, where = (entry.get("engage") or [], f"{path}.engage") \
            if isinstance(entry, Mapping) else (entry, path)
        engaged: list[str] = []
        for i, name in enumerate(names):
            name = str(name)
            if name not in by_name:
                known = ", ".join(by_name) or "none"
                raise ModelError(f"unknown shift element {name!r} (the model's: {known})",
                                 f"{where}[{i}]")
            if by_name[name].kind == "freewheel":
                raise ModelError(f"{name} is a freewheel: it engages by itself, do not "
                                 "list it", f"{where}[{i}]")
            if name in engaged:
                raise ModelError(f"{name} is listed twice", f"{where}[{i}]")
            engaged.append(name)
        modes[name_text(mode, path, "mode name")] = tuple(engaged)
    return MappingProxyType(modes)
