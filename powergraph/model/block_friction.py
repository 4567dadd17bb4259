"""The ``friction:`` and ``geometry:`` blocks of a mesh (docs/losses.md), read into
:class:`MeshFriction`: the pair's involute geometry and its friction law. A ``geometry``
alone (no friction) is read by :func:`parse_mesh_geometry`: the feasibility checks use it
(working centre distance, undercut; docs/feasibility.md)."""
from __future__ import annotations

import dataclasses
import math
from typing import Any, Mapping

from powergraph.gears.mesh_loss import MeshGeometry, iso14179_mu, mesh_loss
from powergraph.errors import ModelError
from powergraph.model.units import parse_in_unit, parse_quantity
from powergraph.records import record

FRICTION_MODELS = ("constant", "iso14179")


@record
class MeshFriction:
    """How one mesh loses power: its involute geometry and its friction law.

    ``gear_1`` is the link's gear that plays the pinion (the external one of an internal
    pair; gear a otherwise). ``mu`` is set for a constant coefficient; ``viscosity``
    (mPa·s) and ``roughness`` (µm) for ISO/TR 14179-2.
    """

    link: int
    gear_1: str
    geometry: MeshGeometry
    face_width: float | None
    model: str
    mu: float | None = None
    viscosity: float | None = None
    roughness: float | None = None
    lubricant_factor: float = 1.0
    #: True when the viscosity is the model's lubricant's at its temperature (bound by
    #: :meth:`at_oil`), not given in the block.
    takes_oil: bool = False

    def at_oil(self, oil: Any) -> "MeshFriction":
        """This law with the dynamic viscosity (mPa·s) of ``oil`` at its temperature."""
        return dataclasses.replace(self, viscosity=oil.dynamic_viscosity() * 1000.0)

    @property
    def load_dependent(self) -> bool:
        return self.model == "iso14179"

    def efficiency(self, tangential_force: float = 0.0,
                   pitch_speed: float = 0.0) -> tuple[float, float]:
        """``(μ, η)`` at a tangential force (N, per mesh) and pitch-line speed (m/s).

        >>> f = MeshFriction(0, "1", MeshGeometry(20, 40), None, "constant", mu=0.05)
        >>> round(f.efficiency()[1], 5)
        0.9917
        """
        if self.model == "constant":
            mu = self.mu
        else:
            mu = iso14179_mu(tangential_force, self.face_width, pitch_speed, self.geometry,
                             self.viscosity, self.roughness, self.lubricant_factor)
        return mu, mesh_loss(self.geometry, mu=mu).efficiency


def parse_mesh_friction(link: int, friction: Mapping, geometry: Mapping | None,
                        pair: tuple[Any, Any], path: str) -> MeshFriction:
    """Read a mesh's ``friction`` block with its ``geometry`` block (both already checked
    against the schema: fields, types and ranges).

    ``pair`` holds the two gears as ``(id, teeth, internal)``; ``path`` is the link's place
    in the file (``links[0]``) for error messages.

    >>> f = parse_mesh_friction(0, {"mu": 0.05}, {"module": 2}, (("1", 20, False),
    ...                         ("2", 40, False)), "links[0]")
    >>> f.model, f.geometry.module
    ('constant', 2.0)
    """
    if geometry is None:
        raise ModelError("a mesh with friction needs its geometry (at least module)",
                         f"{path}.geometry")
    gears = sorted(pair, key=lambda gear: bool(gear[2]))     # the internal gear second
    g = parse_mesh_geometry(geometry, pair, path, "a mesh with friction")
    face = geometry.get("face_width")
    face_width = None if face is None else parse_quantity(face, "length",
                                                          f"{path}.geometry.face_width")
    if "mu" in friction:
        return MeshFriction(link, gears[0][0], g, face_width, "constant",
                            mu=float(friction["mu"]))
    if face_width is None:
        raise ModelError("the iso14179 model needs geometry.face_width", f"{path}.geometry")
    return MeshFriction(link, gears[0][0], g, face_width, "iso14179",
                        viscosity=(_viscosity(friction["viscosity"], f"{path}.friction.viscosity")
                                   if "viscosity" in friction else None),
                        takes_oil="viscosity" not in friction,
                        roughness=_roughness(friction["roughness"], f"{path}.friction.roughness"),
                        lubricant_factor=float(friction.get("lubricant_factor", 1.0)))


def parse_mesh_geometry(geometry: Mapping, pair: tuple[Any, Any], path: str,
                        what: str = "a mesh with geometry") -> MeshGeometry:
    """Read a mesh's ``geometry`` block (schema-checked) into a :class:`MeshGeometry`,
    the external gear first; the pair must mesh (no interference, contact ratio >= 1).

    ``pair`` holds the two gears as ``(id, teeth, internal)``; ``path`` is the link's place.

    >>> g = parse_mesh_geometry({"module": 1, "shifts": [0.2, 0.5]},
    ...                         (("r", 48, True), ("p", 15, False)), "links[1]")
    >>> g.teeth_1, g.teeth_2, g.internal, g.shift_2
    (15, 48, True, 0.5)
    """
    gears = sorted(pair, key=lambda gear: bool(gear[2]))     # the internal gear second
    if any(teeth is None for _, teeth, _ in gears):
        raise ModelError(f"{what} needs the teeth of both gears", f"{path}.between")
    g = _geometry(geometry, gears, f"{path}.geometry")
    try:
        mesh_loss(g)
    except ModelError as exc:
        raise ModelError(str(exc), f"{path}.geometry") from None
    return g


def _geometry(raw: Mapping, gears, path: str) -> MeshGeometry:
    x1, x2 = (float(x) for x in raw.get("shifts", (0.0, 0.0)))
    return MeshGeometry(
        teeth_1=gears[0][1], teeth_2=gears[1][1], internal=bool(gears[1][2]),
        module=parse_quantity(raw["module"], "length", f"{path}.module"),
        pressure_angle_deg=float(raw.get("pressure_angle", 20.0)),
        helix_angle_deg=float(raw.get("helix_angle", 0.0)), shift_1=x1, shift_2=x2,
        addendum=float(raw.get("addendum", 1.0)))


def _roughness(value: Any, path: str) -> float:
    """Ra in µm: a number (µm) or a string with units."""
    if isinstance(value, str):
        return parse_quantity(value, "length", path) * 1e3      # mm -> µm
    return float(value)


def _viscosity(value: Any, path: str) -> float:
    """Dynamic viscosity in mPa·s: a number (mPa·s) or a string with units."""
    if not isinstance(value, str):
        return float(value)
    number = parse_in_unit(value, "mPa*s", "dynamic viscosity", path)
    if not (math.isfinite(number) and 0 < number <= 1e6):
        raise ModelError(f"must be in (0, 1e6] mPa*s, got {value!r}", path)
    return number
