"""A cycloid mesh's ``pins:``, ``output_pins:`` and ``crank_bearing:`` blocks (docs/losses.md).

They give the mesh its basic efficiency from Coulomb friction
(:mod:`powergraph.gears.cycloid_loss`)::

    links:
      - type: mesh
        between: [4, 5]          # cycloid disc (z_c lobes), pin ring (internal, z_c + 1)
        carrier: 3               # the crank
        pins: {mu: 0.05, rolling: true, radius: 3 mm, circle_radius: 64 mm,
               eccentricity: 1.3 mm}
        crank_bearing: {mu: 0.002, bore_radius: 13 mm, crank_circle_radius: 36 mm}

The stage's ``radius`` (pin radius), ``circle_radius`` and ``eccentricity`` may be left out
of ``pins`` when the mesh has a ``cycloid:`` block (``rc·m``, ``m·z_p/2``, ``(1 − x)·m/2``)
or the disc has a ``cycloid_disc`` geometry (``pin_radius``, ``pin_circle_radius``,
``eccentricity``); a value given in several places must agree. The result is stored as the
mesh's friction law (``blocks["friction"]``, a :class:`CycloidFriction`), so the solver
treats it like any friction mesh: its efficiency is constant and set when the model is
loaded.

Examples
--------
>>> from powergraph.model import model_from_dict
>>> m = model_from_dict({"name": "K-H-V",
...     "components": {0: {"role": "frame"}, "H": {}, "d": {"teeth": 39},
...                    "p": {"teeth": 40, "internal": True}},
...     "links": [{"type": "mesh", "between": ["d", "p"], "carrier": "H",
...                "pins": {"mu": 0.05, "radius": 3, "circle_radius": 64,
...                         "eccentricity": 1.3}},
...               {"type": "fixed", "between": ["p", 0]}],
...     "ports": [{"component": "H", "role": "input"}, {"component": "d", "role": "output"}]})
>>> round(m.links[0].efficiency, 6)
0.998085
"""
from __future__ import annotations

import math
from typing import Any, Mapping

from powergraph.errors import ModelError
from powergraph.gears.cycloid_loss import (CrankBearing, CycloidLoss, OutputPins, PinContact,
                                           PinRing, cycloid_mesh_loss)
from powergraph.model.units import parse_quantity
from powergraph.records import record

PIN_BLOCKS = ("pins", "output_pins", "crank_bearing")
_STAGE = (("radius", "pin_radius"), ("circle_radius", "pin_circle_radius"),
          ("eccentricity", "eccentricity"))


@record
class CycloidFriction:
    """A cycloid mesh's friction law: constant, from its pin ring (and output mechanism
    and crank bearing). ``gear_1`` is the disc; ``pitch_radius`` (mm) is the disc's pitch
    circle ``z_c·e``, at which the solver reports the mesh's force and speed."""

    link: int
    gear_1: str
    loss: CycloidLoss
    model: str = "cycloid"
    load_dependent: bool = False

    @property
    def pitch_radius(self) -> float:
        return self.loss.stage.lobes * self.loss.stage.eccentricity

    @property
    def loss_factor(self) -> float:
        """The pins' loss factor (the output mechanism and bearing are in ``loss``)."""
        return self.loss.pin_loss_factor

    def efficiency(self, tangential_force: float = 0.0,
                   pitch_speed: float = 0.0) -> tuple[float, float]:
        """``(μ of the pins, basic efficiency)``; independent of the load."""
        return self.loss.pins.mu, self.loss.efficiency


def parse_pins(raw: Mapping, path: str, pair: tuple, components: Mapping) -> CycloidFriction:
    """Read a mesh's ``pins`` (and ``output_pins``, ``crank_bearing``) blocks.

    ``raw`` is the whole link, already checked against the schema; ``path`` its place
    (``links[1]``). Raises ModelError naming the place for anything impossible.
    """
    from powergraph.model.block_cycloid import validate_cycloid, _roles

    if "pins" not in raw:
        extra = next(key for key in PIN_BLOCKS if key in raw)
        raise ModelError("belongs to a cycloid mesh with a pins: block (add pins: {mu: ...})",
                         f"{path}.{extra}")
    for other in ("efficiency", "friction"):
        if other in raw:
            raise ModelError("give the mesh's pins or its " + other + ", not both (the pins "
                             "set the efficiency)", f"{path}.{other}")
    disc, _ = _roles(pair, components, f"{path}.pins")
    block = raw["pins"]
    cycloid = (validate_cycloid(raw["cycloid"], f"{path}.cycloid", pair, components)
               if "cycloid" in raw else None)
    radius, circle, eccentricity = (
        _stage_value(block, key, field, cycloid, components[disc], path) for key, field in _STAGE)
    stage = PinRing(components[disc].teeth, circle_radius=circle, pin_radius=radius,
                    eccentricity=eccentricity)
    pins = PinContact(mu=float(block["mu"]), rolling=bool(block.get("rolling", False)),
                      seat_radius=_length(block, "seat_radius", f"{path}.pins"))
    if pins.seat_radius is not None and not pins.rolling:
        raise ModelError("a seat radius needs rolling: true (a fixed pin slides on the disc)",
                         f"{path}.pins.seat_radius")
    output = _output(raw.get("output_pins"), f"{path}.output_pins")
    bearing = _bearing(raw.get("crank_bearing"), f"{path}.crank_bearing")
    if output is not None and bearing is not None and bearing.crank_circle_radius > 0:
        raise ModelError("cranks on a circle are the output mechanism: give output_pins or "
                         "crank_circle_radius, not both", f"{path}.output_pins")
    try:
        loss = cycloid_mesh_loss(stage, pins, output, bearing)
    except ModelError as exc:
        raise ModelError(str(exc), f"{path}.pins") from None
    return CycloidFriction(link=int(path[6:-1]), gear_1=disc, loss=loss)


def _stage_value(block: Mapping, key: str, field: str, cycloid: Any, disc: Any,
                 path: str) -> float:
    """One stage dimension from ``pins``, the ``cycloid`` block or the disc's geometry."""
    found: list[tuple[str, float]] = []
    if key in block:
        found.append((f"{path}.pins.{key}", parse_quantity(block[key], "length",
                                                          f"{path}.pins.{key}")))
    if cycloid is not None:
        m = cycloid.module
        value = {"radius": cycloid.rc * m, "circle_radius": m * (cycloid.teeth + 1) / 2.0,
                 "eccentricity": (1.0 - cycloid.shift) * m / 2.0}[key]
        found.append((f"{path}.cycloid", value))
    geometry = getattr(disc, "geometry", None)
    if geometry is not None and getattr(geometry, "shape", None) == "cycloid_disc":
        found.append((f"components.{disc.id}.geometry.{field}", float(getattr(geometry, field))))
    if not found:
        raise ModelError(f"needs the stage's {key} (give it here, or a cycloid: block on the "
                         "mesh, or a cycloid_disc geometry on the disc)", f"{path}.pins")
    first_place, first = found[0]
    for place, value in found[1:]:
        if not math.isclose(value, first, rel_tol=1e-9):
            raise ModelError(f"{key} {first:g} mm disagrees with {value:g} mm at {place}",
                             first_place)
    return first


def _length(block: Mapping, key: str, path: str) -> float | None:
    return None if key not in block else parse_quantity(block[key], "length", f"{path}.{key}")


def _output(raw: Mapping | None, path: str) -> OutputPins | None:
    if raw is None:
        return None
    output = OutputPins(count=int(raw["count"]),
                        circle_radius=parse_quantity(raw["circle_radius"], "length",
                                                     f"{path}.circle_radius"),
                        mu=float(raw["mu"]), rolling=bool(raw.get("rolling", False)),
                        radius=_length(raw, "radius", path),
                        seat_radius=_length(raw, "seat_radius", path))
    if output.rolling and (output.radius is None or output.seat_radius is None
                           or output.seat_radius > output.radius):
        raise ModelError("rolling output pins need radius and seat_radius <= radius",
                         f"{path}.rolling")
    if not output.rolling and (output.radius is not None or output.seat_radius is not None):
        raise ModelError("radius and seat_radius describe rolling sleeves: add rolling: true",
                         path)
    return output


def _bearing(raw: Mapping | None, path: str) -> CrankBearing | None:
    if raw is None:
        return None
    circle = raw.get("crank_circle_radius", 0.0)
    return CrankBearing(mu=float(raw["mu"]),
                        radius=parse_quantity(raw["bore_radius"], "length",
                                              f"{path}.bore_radius"),
                        crank_circle_radius=parse_quantity(circle, "length",
                                                           f"{path}.crank_circle_radius"))
