"""The ``friction:`` and ``geometry:`` blocks of a mesh (docs/losses.md), read into
:class:`MeshFriction`: the pair's involute geometry and its friction law."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Mapping

from powergraph.gears.mesh_loss import MeshGeometry, iso14179_mu, mesh_loss
from powergraph.errors import ModelError
from powergraph.model.units import parse_number

FRICTION_MODELS = ("constant", "iso14179")
_FRICTION_FIELDS = {"mu", "model", "viscosity", "roughness", "lubricant_factor"}
_GEOMETRY_FIELDS = {"module", "pressure_angle", "helix_angle", "shifts", "addendum",
                    "face_width"}


@dataclass(frozen=True)
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

    @property
    def load_dependent(self) -> bool:
        return self.model == "iso14179"

    def efficiency(self, tangential_force: float = 0.0, pitch_speed: float = 0.0) -> tuple[float, float]:
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


def parse_mesh_friction(link: int, friction: Any, geometry: Any, pair: tuple[Any, Any],
                        path: str) -> MeshFriction:
    """Read a mesh's ``friction`` block with its ``geometry`` block.

    ``pair`` holds the two gears as ``(id, teeth, internal)``; ``path`` is the link's place
    in the file (``links[0]``) for error messages.

    >>> f = parse_mesh_friction(0, {"mu": 0.05}, {"module": 2}, (("1", 20, False),
    ...                         ("2", 40, False)), "links[0]")
    >>> f.model, f.geometry.module
    ('constant', 2.0)
    """
    friction = _mapping(friction, f"{path}.friction", _FRICTION_FIELDS)
    geometry = _mapping(geometry, f"{path}.geometry", _GEOMETRY_FIELDS)
    gears = sorted(pair, key=lambda gear: bool(gear[2]))     # the internal gear second
    if gears[0][2]:
        raise ModelError("two internal gears cannot mesh", f"{path}.between")
    if any(teeth is None for _, teeth, _ in gears):
        raise ModelError("a mesh with friction needs the teeth of both gears", f"{path}.between")
    model = friction.get("model", "constant")
    if model not in FRICTION_MODELS:
        raise ModelError(f"unknown friction model {model!r}; expected one of "
                         f"{', '.join(FRICTION_MODELS)}", f"{path}.friction.model")
    g = _geometry(geometry, gears, f"{path}.geometry")
    face = geometry.get("face_width")
    face_width = None if face is None else parse_number(face, f"{path}.geometry.face_width",
                                                         positive=True, length=True)
    _check_pair(g, f"{path}.geometry")
    if model == "constant":
        _only(friction, {"mu"}, f"{path}.friction", "a constant coefficient takes only mu")
        if "mu" not in friction:
            raise ModelError("missing mu (or give model: iso14179)", f"{path}.friction")
        mu = parse_number(friction["mu"], f"{path}.friction.mu", minimum=0.0)
        if mu >= 1:
            raise ModelError(f"must be < 1, got {friction['mu']!r}", f"{path}.friction.mu")
        return MeshFriction(link, gears[0][0], g, face_width, model, mu=mu)
    return _iso(link, friction, gears, g, face_width, path)


def _iso(link: int, friction: Mapping, gears, g: MeshGeometry, face_width, path: str):
    if "mu" in friction:
        raise ModelError("mu is computed by the iso14179 model; remove it", f"{path}.friction.mu")
    for name in ("viscosity", "roughness"):
        if name not in friction:
            raise ModelError(f"the iso14179 model needs {name}", f"{path}.friction")
    if face_width is None:
        raise ModelError("the iso14179 model needs geometry.face_width", f"{path}.geometry")
    viscosity = _viscosity(friction["viscosity"], f"{path}.friction.viscosity")
    roughness = parse_number(friction["roughness"], f"{path}.friction.roughness",
                             positive=True, length=True)
    if isinstance(friction["roughness"], str):
        roughness *= 1e3                      # mm -> µm
    factor = parse_number(friction.get("lubricant_factor", 1.0),
                          f"{path}.friction.lubricant_factor", positive=True)
    return MeshFriction(link, gears[0][0], g, face_width, "iso14179", viscosity=viscosity,
                        roughness=roughness, lubricant_factor=factor)


def _geometry(raw: Mapping, gears, path: str) -> MeshGeometry:
    if "module" not in raw:
        raise ModelError("missing module", path)
    shifts = raw.get("shifts", [0.0, 0.0])
    if not isinstance(shifts, (list, tuple)) or len(shifts) != 2:
        raise ModelError(f"shifts must be a list of two numbers (pinion, wheel), got {shifts!r}",
                         f"{path}.shifts")
    x = [parse_number(s, f"{path}.shifts[{i}]") for i, s in enumerate(shifts)]
    return MeshGeometry(
        teeth_1=gears[0][1], teeth_2=gears[1][1], internal=bool(gears[1][2]),
        module=parse_number(raw["module"], f"{path}.module", positive=True, length=True),
        pressure_angle_deg=parse_number(raw.get("pressure_angle", 20.0), f"{path}.pressure_angle",
                                        positive=True),
        helix_angle_deg=parse_number(raw.get("helix_angle", 0.0), f"{path}.helix_angle"),
        shift_1=x[0], shift_2=x[1],
        addendum=parse_number(raw.get("addendum", 1.0), f"{path}.addendum", positive=True))


def _check_pair(g: MeshGeometry, path: str) -> None:
    try:
        mesh_loss(g)
    except ModelError as exc:
        raise ModelError(str(exc), path) from None


def _viscosity(value: Any, path: str) -> float:
    """Dynamic viscosity in mPa·s: a number (mPa·s) or a string with units (pint)."""
    if isinstance(value, str):
        try:
            import pint

            quantity = pint.UnitRegistry().Quantity(value)
            number = float(quantity.to("mPa*s").magnitude)
        except Exception:
            raise ModelError(f"cannot read {value!r} as a dynamic viscosity (e.g. '30 mPa*s')",
                             path) from None
    else:
        number = parse_number(value, path, positive=True)
    if not (math.isfinite(number) and number > 0):
        raise ModelError(f"must be > 0, got {value!r}", path)
    return number


def _mapping(raw: Any, path: str, allowed: set[str]) -> Mapping:
    if raw is None:
        return {}
    if not isinstance(raw, Mapping):
        raise ModelError(f"must be a mapping, got {raw!r}", path)
    _only(raw, allowed, path, "unknown field")
    return raw


def _only(raw: Mapping, allowed: set[str], path: str, what: str) -> None:
    for key in raw:
        if key not in allowed:
            raise ModelError(f"{what} {key!r}; allowed: {', '.join(sorted(allowed))}",
                             f"{path}.{key}")
