"""The ``friction:`` and ``geometry:`` blocks of a mesh (docs/losses.md), read into
:class:`MeshFriction`: the pair's involute geometry and its friction law. A ``geometry``
alone (no friction) is read by :func:`parse_mesh_geometry`: the feasibility checks use it
(working centre distance, undercut; docs/feasibility.md). A geometry may give the pair's
operating ``centre_distance``: beside ``shifts`` (or with friction) it must be theirs;
alone it fixes the shift sum and is read into an :class:`OperatingGeometry`."""
from __future__ import annotations

import dataclasses
import math
from typing import Any, Mapping

from powergraph.gears import planetary
from powergraph.gears.mesh_loss import MeshGeometry, iso14179_mu, mesh_loss
from powergraph.errors import ModelError
from powergraph.model.units import parse_in_unit, parse_quantity
from powergraph.records import record

FRICTION_MODELS = ("constant", "iso14179")


@record
class OperatingGeometry:
    """A mesh's ``geometry`` that gives the pair's operating ``centre_distance`` (mm) and
    no ``shifts`` (docs/feasibility.md): the shift sum ``x_2 ± x_1`` follows from it, the
    split between the gears does not. ``split`` is the pair (a :class:`MeshGeometry`) with
    one split that meshes — the first on a 0.01 grid of ``x_1`` without undercut, else the
    first that meshes; the checks read from it only whether some split avoids undercut.

    >>> g = parse_mesh_geometry({"module": 1, "centre_distance": 17.1},
    ...                         (("r", 48, True), ("p", 15, False)), "links[1]")
    >>> round(g.shift_sum, 4), g.split.shift_1, round(g.split.shift_2, 4)     # x2 − x1
    (0.6736, 0.13, 0.8036)
    """

    teeth_1: int
    teeth_2: int
    internal: bool
    module: float
    pressure_angle_deg: float
    helix_angle_deg: float
    addendum: float
    centre_distance: float
    shift_sum: float
    split: MeshGeometry


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
    g = parse_mesh_geometry(geometry, pair, path, "a mesh with friction", friction=True)
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
                        what: str = "a mesh with geometry", friction: bool = False
                        ) -> MeshGeometry | OperatingGeometry:
    """Read a mesh's ``geometry`` block (schema-checked) into a :class:`MeshGeometry`,
    the external gear first; the pair must mesh (no interference, contact ratio >= 1).

    ``pair`` holds the two gears as ``(id, teeth, internal)``; ``path`` is the link's place.
    A ``centre_distance`` must be the working centre distance of the shifts (given, or
    ``[0, 0]`` under ``friction``) within :func:`planetary.centre_tolerance`; without
    ``shifts`` and ``friction`` it gives an :class:`OperatingGeometry`, refused when no
    split of its shift sum (each shift in [−2, 2]) lets the pair mesh.

    >>> g = parse_mesh_geometry({"module": 1, "shifts": [0.2, 0.5]},
    ...                         (("r", 48, True), ("p", 15, False)), "links[1]")
    >>> g.teeth_1, g.teeth_2, g.internal, g.shift_2
    (15, 48, True, 0.5)
    >>> parse_mesh_geometry({"module": 1, "shifts": [0.2, 0.5], "centre_distance": 17},
    ...                     (("r", 48, True), ("p", 15, False)), "links[1]")
    ... # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    powergraph.errors.ModelError: links[1].geometry.centre_distance: the shifts [0.2, 0.5] put the pair at a working centre distance of 16.7827 mm, not 17.0000 mm (217.3 µm apart; ...)
    """
    gears = sorted(pair, key=lambda gear: bool(gear[2]))     # the internal gear second
    if any(teeth is None for _, teeth, _ in gears):
        raise ModelError(f"{what} needs the teeth of both gears", f"{path}.between")
    g = _geometry(geometry, gears, f"{path}.geometry")
    if "centre_distance" in geometry:
        where = f"{path}.geometry.centre_distance"
        stated = parse_quantity(geometry["centre_distance"], "length", where)
        if "shifts" not in geometry and not friction:
            return _operating(g, stated, where)
        _agree(g, stated, "shifts" in geometry, where)
    try:
        mesh_loss(g)
    except ModelError as exc:
        raise ModelError(str(exc), f"{path}.geometry") from None
    return g


def _agree(g: MeshGeometry, stated: float, given: bool, where: str) -> None:
    """The shifts' working centre distance is the stated one."""
    working = planetary.working_centre_distance(
        g.teeth_1, g.teeth_2, g.internal, g.module, g.pressure_angle_deg,
        g.helix_angle_deg, g.shift_1, g.shift_2)
    tolerance = planetary.centre_tolerance(g.module)
    if abs(working - stated) <= tolerance:
        return
    apart = (f"{abs(working - stated) * 1e3:.1f} µm apart; they must agree within "
             f"{planetary.CENTRE_TOLERANCE:g} module = {tolerance * 1e3:.3g} µm")
    if given:
        raise ModelError(f"the shifts [{g.shift_1:g}, {g.shift_2:g}] put the pair at a "
                         f"working centre distance of {working:.4f} mm, not {stated:.4f} mm "
                         f"({apart})", where)
    total = _shift_sum(g, stated, where)
    raise ModelError(f"a mesh with friction needs its shifts when it is not at its standard "
                     f"centre distance: unshifted the pair sits at {working:.4f} mm, not "
                     f"{stated:.4f} mm ({apart}); the centre distance gives only the sum "
                     f"{_sum_words(g)} = {total:.4f}: give shifts", where)


def _sum_words(g: Any) -> str:
    return "x2 − x1" if g.internal else "x1 + x2"


def _shift_sum(g: MeshGeometry, stated: float, where: str) -> float:
    try:
        return planetary.shift_sum(g.teeth_1, g.teeth_2, g.internal, g.module, stated,
                                   g.pressure_angle_deg, g.helix_angle_deg)
    except ModelError as exc:
        raise ModelError(str(exc), where) from None


def _operating(g: MeshGeometry, stated: float, where: str) -> OperatingGeometry:
    """The pair at its stated centre distance, shifts unknown (:class:`OperatingGeometry`)."""
    total = _shift_sum(g, stated, where)
    split = _split(g, total)
    if split is None:
        raise ModelError(f"no profile shifts put the pair at {stated:.4f} mm and let it mesh: "
                         f"it needs {_sum_words(g)} = {total:.4f}, and no split of it (each "
                         "shift in [−2, 2], in steps of 0.01) avoids interference with a "
                         "contact ratio of at least 1", where)
    return OperatingGeometry(g.teeth_1, g.teeth_2, g.internal, g.module,
                             g.pressure_angle_deg, g.helix_angle_deg, g.addendum, stated,
                             total, split)


def _split(g: MeshGeometry, total: float) -> MeshGeometry | None:
    """The pair with the first ``x_1`` on a 0.01 grid whose split of ``total`` meshes and
    leaves no external gear undercut; else the first that meshes; None if none does."""
    first = None
    for step in range(-200, 201):
        x1 = step / 100
        x2 = total + x1 if g.internal else total - x1
        if abs(x2) > 2.0:
            continue
        candidate = dataclasses.replace(g, shift_1=x1, shift_2=x2)
        try:
            mesh_loss(candidate)
        except ModelError:
            continue
        if not planetary.undercut_gears(candidate):
            return candidate
        first = first or candidate
    return first


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
