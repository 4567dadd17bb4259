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

    def torque(self, radial_load: float, relative_speed: float = 0.0) -> float:
        """Friction torque (N·m) of one bearing under ``radial_load`` (N), at any speed.

        >>> BearingFriction(0.0015, 20.0).torque(1000.0)     # 0.0015 * 1000 N * 0.010 m
        0.015
        """
        return self.mu * abs(radial_load) * self.bore / 2000.0

    @property
    def load_dependent(self) -> bool:
        return self.mu > 0.0


@record
class WetDrag:
    """Laminar shear drag of an open wet clutch or brake (per instance):

        T = faces · π · μ · |Δω| · (r_o⁴ − r_i⁴) / (2 h)

    (Newtonian oil filling each gap of height ``h`` between annular faces ``r_i … r_o``,
    Couette flow; lengths in m, ``mu`` the dynamic viscosity in Pa·s, bound from the
    model's lubricant at its temperature: :meth:`at_oil`).

    >>> wet = WetDrag(6, 0.06, 0.08, 0.2e-3, mu=0.0074)   # 8.5 cSt x 870 kg/m3
    >>> round(wet.torque(100.0), 4)     # 6 pi 0.0074 100 (0.08^4 - 0.06^4) / (2 0.2e-3)
    0.9764
    """

    faces: int
    inner_radius: float
    outer_radius: float
    clearance: float
    mu: float | None = None

    takes_oil = True

    def at_oil(self, oil: Any) -> "WetDrag":
        """This drag with the dynamic viscosity of ``oil`` (a Lubricant) at its
        temperature."""
        return WetDrag(self.faces, self.inner_radius, self.outer_radius, self.clearance,
                       oil.dynamic_viscosity())

    def torque(self, relative_speed: Any) -> Any:
        """Drag torque (N·m) at ``relative_speed`` (rad/s)."""
        return (self.faces * math.pi * self.mu * abs(relative_speed)
                * (self.outer_radius ** 4 - self.inner_radius ** 4) / (2.0 * self.clearance))


@record
class SealDrag:
    """A lip seal on a shaft of ``diameter`` d (mm): it loses ``P = 7.69e-6 · d² · n`` W at
    ``n`` rpm (ISO/TR 14179-2), a constant torque ``P/ω = 7.69e-6 · d² · 30/π`` N·m.

    >>> round(SealDrag(30.0).torque(1000 * math.pi / 30) * 1000 * math.pi / 30, 6)  # W
    6.921
    """

    diameter: float

    #: ISO/TR 14179-2's seal coefficient: W per (mm² · rpm).
    COEFFICIENT = 7.69e-6

    def torque(self, relative_speed: Any) -> Any:
        """The seal's torque (N·m), the same at any relative speed (0 at rest is the
        bearing law's)."""
        return self.COEFFICIENT * self.diameter ** 2 * RPM_PER_RAD_S + 0.0 * abs(relative_speed)


@record
class Drag:
    """No-load drag ``M0 = a + b * |n|`` (N·m; ``n`` the relative speed in rpm), plus an
    open wet clutch's laminar drag (``wet``, :class:`WetDrag`) when given."""

    a: float
    b: float = 0.0
    wet: WetDrag | None = None

    @property
    def takes_oil(self) -> bool:
        return self.wet is not None

    def at_oil(self, oil: Any) -> "Drag":
        """This drag with its wet part at ``oil``'s viscosity."""
        return Drag(self.a, self.b, None if self.wet is None else self.wet.at_oil(oil))

    def torque(self, relative_speed: Any) -> Any:
        """Drag torque (N·m) of one instance at ``relative_speed`` (rad/s)."""
        torque = self.a + self.b * abs(relative_speed) * RPM_PER_RAD_S
        return torque if self.wet is None else torque + self.wet.torque(relative_speed)


def parse_drag(raw: Mapping, path: str) -> Drag:
    """Read a ``drag:`` block (already checked against the schema)."""
    wet = _wet(raw["wet"], f"{path}.wet") if "wet" in raw else None
    if "no_load_torque" in raw:
        both = [k for k in ("a", "b") if k in raw]
        if both:
            raise ModelError("give no_load_torque or a/b, not both", f"{path}.{both[0]}")
        return Drag(_torque(raw["no_load_torque"], f"{path}.no_load_torque"), wet=wet)
    if not raw:
        raise ModelError("give no_load_torque, or a and/or b, or wet", path)
    return Drag(_torque(raw.get("a", 0.0), f"{path}.a"), _torque(raw.get("b", 0.0), f"{path}.b"),
                wet)


def _wet(raw: Mapping, path: str) -> WetDrag:
    """A ``wet:`` drag (lengths to m); the viscosity is bound later, from the lubricant."""
    inner, outer, gap = (parse_quantity(raw[k], "length", f"{path}.{k}") / 1000.0
                         for k in ("inner_radius", "outer_radius", "clearance"))
    if not outer > inner:
        raise ModelError(f"outer_radius ({outer * 1000:g} mm) must be larger than "
                         f"inner_radius ({inner * 1000:g} mm)", f"{path}.outer_radius")
    return WetDrag(int(raw["faces"]), inner, outer, gap)


def parse_seal(raw: Mapping, path: str) -> dict[str, Any]:
    """The blocks of a ``seal`` link: its drag (:class:`SealDrag`)."""
    diameter = parse_quantity(raw["diameter"], "length", f"{path}.diameter")
    if not diameter > 0.0:
        raise ModelError(f"must be > 0 mm, got {diameter:g}", f"{path}.diameter")
    return {"drag": SealDrag(diameter)}


def parse_bearing_blocks(raw: Mapping, path: str) -> dict[str, Any]:
    """The ``friction`` and ``drag`` blocks of a bearing link, by name."""
    blocks: dict[str, Any] = {}
    if "friction" in raw:
        friction = raw["friction"]
        bore = parse_quantity(friction["bore"], "length", f"{path}.friction.bore")
        _non_negative(bore, f"{path}.friction.bore", "mm")
        blocks["friction"] = BearingFriction(mu=float(friction["mu"]), bore=bore)
    if "skf" in raw:
        if "friction" in raw:
            raise ModelError("give friction (mu, bore) or skf, not both", f"{path}.skf")
        from powergraph.model.block_spin import parse_skf

        blocks["friction"] = parse_skf(raw["skf"], f"{path}.skf")
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
