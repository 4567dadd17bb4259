"""The torque a rigid joint carries, found by cutting it (docs/modes.md).

An engaged clutch, brake or freewheel is a ``fixed`` link: its two members are one rigid
body, so the torque balance knows only the body's total. The joint's own torque follows
from the balance of one side: remove the joint from the body's tree of fixed links, take
the members still attached to its first member ``a``, and sum every torque acting on them
-- the elements' (mesh, coupling) on each member, the bearings' and drags', the port's
or the frame's reaction. The joint applies the opposite to ``a``. When ``a`` and ``b`` stay
connected without the joint (two joints in parallel), its torque is statically
indeterminate (None).

Examples
--------
>>> from powergraph.model import model_from_dict
>>> import powergraph as pg
>>> m = model_from_dict({"name": "pair", "components": {0: {"role": "frame"},
...     1: {"teeth": 20}, 2: {"teeth": 40}, 3: {}},
...     "links": [{"type": "mesh", "between": [1, 2]},
...               {"type": "clutch", "name": "C1", "between": [3, 2], "engaged": True}],
...     "ports": [{"component": 1, "role": "input", "speed": 10, "torque": 1.0},
...               {"component": 3, "role": "output"}]})
>>> joint_torque(pg.solve(m), 1)     # shaft 3 turns at -5 rad/s, its load pushes +2 N·m
-2.0
"""
from __future__ import annotations

from collections import defaultdict

from powergraph.kinematics import element_stencil
from powergraph.model.spec import Model


def component_torques(result) -> dict[str, float]:
    """Every torque on each component (N·m): elements, bearings and drags, ports, frame."""
    model: Model = result.model
    torques: dict[str, float] = defaultdict(float)
    for flow in result.elements:
        ones = element_stencil(flow.ratio, flow.factor)
        for component, unit in zip((flow.a, flow.b, flow.carrier), ones):
            torques[component] += float(unit) * flow.force
    for bearing in result.bearings:
        sign = (bearing.relative_speed > 0) - (bearing.relative_speed < 0)
        torques[bearing.between[0]] -= bearing.torque * sign
        torques[bearing.between[1]] += bearing.torque * sign
    for port in model.ports:
        torques[port.component] += result.port_torque(port.index)
    torques[model.frame] += result.external_torques.get(model.frame_body, 0.0)
    return dict(torques)


def joint_torque(result, link: int, torques: dict[str, float] | None = None) -> float | None:
    """The torque the ``fixed`` link ``links[link]`` applies to its first member (N·m), or
    None when it is statically indeterminate (another rigid path joins its members)."""
    model: Model = result.model
    a, b = model.links[link].between
    side = _side(model, link, a)
    if b in side:
        return None
    torques = component_torques(result) if torques is None else torques
    return -sum(torques.get(c, 0.0) for c in side)


def _side(model: Model, cut: int, start: str) -> set[str]:
    """Components joined to ``start`` by fixed links other than ``links[cut]``."""
    neighbours: dict[str, list[str]] = defaultdict(list)
    for link in model.links:
        if link.type == "fixed" and link.index != cut:
            x, y = link.between
            neighbours[x].append(y)
            neighbours[y].append(x)
    seen, todo = {start}, [start]
    while todo:
        for other in neighbours[todo.pop()]:
            if other not in seen:
                seen.add(other)
                todo.append(other)
    return seen
