"""The ``friction:`` and ``drag:`` blocks of a bearing, and ``drag:`` on a component
(docs/losses.md): rolling-bearing friction and no-load drag, read into
:class:`BearingFriction` and :class:`Drag`.

A bearing ``between: [carried, carrying]`` with ``friction: {mu, bore}`` has the
load-dependent friction torque ``M = mu * F * bore / 2`` (SKF's constant-coefficient form),
``F`` being the radial load per bearing instance; ``drag`` adds a load-independent
``M0 = no_load_torque`` or ``M0 = a + b * |n|`` (``n`` the relative speed in rpm). The load
``F`` comes from the tooth forces on the carried member's gears, which need each gear's
pitch radius (:func:`gear_radius`); :func:`check_bearing_loads` refuses a model in which
one is unknown.

Examples
--------
>>> drag = parse_drag({"a": "0.1 N*m", "b": 0.002}, "links[3].drag")
>>> round(drag.torque(1000 * 3.141592653589793 / 30), 12)     # 0.1 + 0.002 * 1000 rpm
2.1
"""
from __future__ import annotations

import math
from functools import lru_cache
from typing import Any, Mapping

from powergraph.errors import ModelError
from powergraph.model.units import parse_quantity
from powergraph.records import record
from powergraph.units_si import RPM_PER_RAD_S


@record
class BearingFriction:
    """Load-dependent bearing friction ``M = mu * F * bore / 2`` (``bore`` in mm)."""

    mu: float
    bore: float

    def torque(self, radial_load: float) -> float:
        """Friction torque (N·m) of one bearing under ``radial_load`` (N).

        >>> BearingFriction(0.0015, 20.0).torque(1000.0)     # 0.0015 * 1000 N * 0.010 m
        0.015
        """
        return self.mu * abs(radial_load) * self.bore / 2000.0

    @property
    def load_dependent(self) -> bool:
        return self.mu > 0.0


@record
class Drag:
    """No-load drag ``M0 = a + b * |n|`` (N·m; ``n`` the relative speed in rpm)."""

    a: float
    b: float = 0.0

    def torque(self, relative_speed: float) -> float:
        """Drag torque (N·m) of one instance at ``relative_speed`` (rad/s)."""
        return self.a + self.b * abs(relative_speed) * RPM_PER_RAD_S


def parse_drag(raw: Mapping, path: str) -> Drag:
    """Read a ``drag:`` block (already checked against the schema)."""
    if "no_load_torque" in raw:
        both = [k for k in ("a", "b") if k in raw]
        if both:
            raise ModelError("give no_load_torque or a/b, not both", f"{path}.{both[0]}")
        return Drag(_torque(raw["no_load_torque"], f"{path}.no_load_torque"))
    if not raw:
        raise ModelError("give no_load_torque, or a and/or b", path)
    return Drag(_torque(raw.get("a", 0.0), f"{path}.a"), _torque(raw.get("b", 0.0), f"{path}.b"))


def parse_bearing_blocks(raw: Mapping, path: str) -> dict[str, Any]:
    """The ``friction`` and ``drag`` blocks of a bearing link, by name."""
    blocks: dict[str, Any] = {}
    if "friction" in raw:
        friction = raw["friction"]
        bore = parse_quantity(friction["bore"], "length", f"{path}.friction.bore")
        _non_negative(bore, f"{path}.friction.bore", "mm")
        blocks["friction"] = BearingFriction(mu=float(friction["mu"]), bore=bore)
    if "drag" in raw:
        blocks["drag"] = parse_drag(raw["drag"], f"{path}.drag")
    return blocks


def _torque(value: Any, path: str) -> float:
    torque = parse_quantity(value, "torque", path)
    _non_negative(torque, path, "N·m")
    return torque


def _non_negative(value: float, path: str, unit: str) -> None:
    if not (math.isfinite(value) and value >= 0.0):
        raise ModelError(f"must be a finite number >= 0 {unit}, got {value!r}", path)


def gear_radius(model, link: int, gear: str) -> float | None:
    """Working pitch radius (m) of ``gear`` in the mesh ``links[link]``: from the mesh's
    friction geometry, else ``module * teeth / 2`` of the gear's own ``geometry:``; None
    when neither is given."""
    friction = model.links[link].blocks.get("friction")
    if friction is not None and hasattr(friction, "geometry"):
        radius_1, radius_2 = _working_radii(friction.geometry)
        return (radius_1 if gear == friction.gear_1 else radius_2) / 1000.0
    component = model.components[gear]
    module = getattr(component.geometry, "module", None)
    if module is None or component.teeth is None or \
            getattr(component.geometry, "shape", None) != "gear":
        return None
    return module * component.teeth / 2000.0


@lru_cache(maxsize=1024)
def _working_radii(geometry) -> tuple[float, float]:
    """Working pitch radii (mm) of a pair's pinion and wheel (cached: read every pass)."""
    from powergraph.gears.mesh_loss import path_of_contact

    path = path_of_contact(geometry)
    return abs(path.working_radius_1), abs(path.working_radius_2)


def load_meshes(model, carried: str) -> tuple[tuple[int, str], ...]:
    """``(mesh link, gear)`` for every gear of the carried member's rigid body in mesh."""
    body = model.body_of[carried]
    return tuple((link.index, gear) for link in model.meshes for gear in link.between
                 if model.body_of[gear] == body)


def check_bearing_loads(model) -> None:
    """Every bearing with friction must know the pitch radius of the gears whose tooth
    forces load it (docs/losses.md)."""
    for link in model.links:
        if link.type != "bearing" or "friction" not in link.blocks:
            continue
        for mesh, gear in load_meshes(model, link.between[0]):
            if gear_radius(model, mesh, gear) is None:
                raise ModelError(
                    f"the bearing's load is the tooth force of links[{mesh}] on component "
                    f"{model.raw_id(gear)!r}, whose pitch radius is unknown: give links[{mesh}] "
                    f"friction: with geometry:, or component {model.raw_id(gear)!r} a gear "
                    f"geometry: (module)", f"{link.path}.friction")
