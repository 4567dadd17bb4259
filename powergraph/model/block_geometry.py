"""``components.ID.geometry``: the dimensions of the volume formulas (Pan & Wang 2019).

Pan & Wang (2019) give one volume formula per kind of RV-reducer part (Eqs. 1–7). A geometry
block says which formula applies with ``shape:`` and gives that formula's dimensions in plain
words (a block without ``shape`` on a component with teeth is a gear). Lengths are in mm: a number (mm) or a string with units (``"12 mm"``, ``"1.2 cm"``).
Counts are integers. Tooth numbers are never repeated here: the analysis reads the
component's own ``teeth`` (and ``count`` for identical parts in parallel).

=================  =======  ==============================================================
shape              paper    parameters (paper symbol)
=================  =======  ==============================================================
gear               (1)–(2)  module (m), face_width (B), bore_radius (r)
cycloid_disc       (3)      width (B2), pin_circle_radius (r_p), pin_radius (r_rp),
                            eccentricity (a), crank_hole_radius (r3), crank_holes (2),
                            pillar_radius (r8), pillar_holes (6), center_bore_radius (r4)
needle_gear        (4)      width (2·B2), pin_circle_radius (r_p), pin_radius (r_rp),
                            shell_thickness (t)
crankshaft         (5)      shaft_radius (r2), gear_seat_length (B1), bearing_width (B3),
                            journal_radius (r5), journal_length (B2), journals (2)
planet_frame_1     (6)      bearing_seat_radius (r6), bearing_width (B4),
                            crank_bearing_radius (r7), crank_bearing_width (B3),
                            crank_bearings (2)
planet_frame_2     (7)      seal_radius (r9), bearing_seat_radius (r6), bearing_width (B4),
                            crank_bearing_radius (r7), crank_bearing_width (B3),
                            crank_bearings (2), pillar_radius (r8), pillars (6),
                            pillar_length (2·B2), sun (component id), planet (component id)
=================  =======  ==============================================================

Every radius is a radius (the paper says "diameter" in places, but its formulas square the
value next to a pitch *radius* m·z/2). Counts in brackets are the paper's fixed numbers.

A block is read by :func:`powergraph.model.blocks.validate_geometry` (the schema's
format, then the checks of its shape's class here); the schema writes its ``geometry``
definition from :data:`SHAPES`, so this module imports neither the schema nor its checker.

Examples
--------
>>> from powergraph.model.blocks import validate_geometry
>>> g = validate_geometry({"shape": "gear", "module": 1.5, "face_width": "12 mm",
...                        "bore_radius": 0}, "components.1.geometry")
>>> g.shape, g.module, g.face_width
('gear', 1.5, 12.0)
>>> validate_geometry({"shape": "gear", "module": -1, "face_width": 12, "bore_radius": 0},
...                   "components.1.geometry")
Traceback (most recent call last):
...
powergraph.errors.ModelError: components.1.geometry.module: must be > 0 mm, got -1
"""
from __future__ import annotations

import math
from dataclasses import field, fields
from typing import Any, ClassVar

from powergraph.errors import ModelError
from powergraph.model.schema_parts import NON_NEGATIVE, POSITIVE
from powergraph.records import record


def _length(doc: str, symbol: str, minimum: str = POSITIVE) -> Any:
    return field(metadata={"kind": "length", "min": minimum, "doc": doc, "symbol": symbol})


def _count(doc: str, symbol: str, minimum: int = 1) -> Any:
    return field(metadata={"kind": "count", "min": minimum, "doc": doc, "symbol": symbol})


def _component(doc: str) -> Any:
    return field(metadata={"kind": "component", "doc": doc, "symbol": ""})


class _Shape:
    """Behaviour shared by every geometry dataclass."""

    shape: ClassVar[str]
    equation: ClassVar[str]

    def to_dict(self) -> dict[str, Any]:
        """Plain data: ``{"shape": ..., parameter: value, ...}`` (lengths in mm)."""
        data: dict[str, Any] = {"shape": self.shape}
        data.update({f.name: getattr(self, f.name) for f in fields(self)})  # type: ignore
        return data

    def check(self, path: str) -> None:
        """Raise :class:`ModelError` on dimensions that cannot be built (shape-specific)."""

    def check_teeth(self, teeth: int | None, path: str) -> None:
        """Checks that need the component's tooth number (nothing by default)."""


@record
class GearGeometry(_Shape):
    """External spur gear, Eqs. (1)–(2): V = π·B·((m·z)²/4 − r²)."""

    shape: ClassVar[str] = "gear"
    equation: ClassVar[str] = "(1)/(2)"
    module: float = _length("module", "m")
    face_width: float = _length("face width (tooth width)", "B")
    bore_radius: float = _length("radius of the bore (0 for a pinion cut on its shaft)", "r",
                                 NON_NEGATIVE)

    def root_radius(self, teeth: int) -> float:
        """Root radius of a standard gear, m·z/2 − 1.25·m (dedendum 1.25·m)."""
        return self.module * teeth / 2 - 1.25 * self.module

    def check_teeth(self, teeth: int | None, path: str) -> None:
        if teeth is None:
            raise ModelError("a gear geometry needs the component's teeth", path)
        root = self.root_radius(teeth)
        if self.bore_radius >= root:
            raise ModelError(f"bore radius {self.bore_radius:g} mm is not smaller than the "
                             f"root radius m·z/2 − 1.25·m = {root:g} mm", f"{path}.bore_radius")


@record
class CycloidDiscGeometry(_Shape):
    """Cycloid disc, Eq. (3): V = π·B2·[(r_p − r_rp)² − n8·(r8 + a)² − n3·r3² − r4²]."""

    shape: ClassVar[str] = "cycloid_disc"
    equation: ClassVar[str] = "(3)"
    width: float = _length("disc thickness", "B2")
    pin_circle_radius: float = _length("radius of the needle (pin) centre circle", "r_p")
    pin_radius: float = _length("needle (pin) radius", "r_rp")
    eccentricity: float = _length("crank eccentricity", "a")
    crank_hole_radius: float = _length("crank hole radius = roller bearing outer radius", "r3")
    crank_holes: int = _count("number of crank holes (paper: 2)", "2")
    pillar_radius: float = _length("radius of the planet-frame-II pillars through the disc",
                                   "r8")
    pillar_holes: int = _count("number of pillar holes (paper: 6)", "6", minimum=0)
    center_bore_radius: float = _length("radius of the central hole", "r4", NON_NEGATIVE)

    @property
    def root_radius(self) -> float:
        """Root radius of the disc profile, r_p − a − r_rp."""
        return self.pin_circle_radius - self.eccentricity - self.pin_radius

    def check(self, path: str) -> None:
        root = self.root_radius
        if root <= 0:
            raise ModelError(f"pin_circle_radius − eccentricity − pin_radius = {root:g} mm: "
                             "the disc has no root circle", f"{path}.pin_circle_radius")
        for key, radius in (("center_bore_radius", self.center_bore_radius),
                            ("crank_hole_radius", self.crank_hole_radius),
                            ("pillar_radius", self.pillar_radius + self.eccentricity)):
            if radius >= root:
                raise ModelError(f"hole radius {radius:g} mm is not smaller than the disc's "
                                 f"root radius r_p − a − r_rp = {root:g} mm", f"{path}.{key}")

    def check_teeth(self, teeth: int | None, path: str) -> None:
        if teeth is None:
            return
        k1 = self.eccentricity * (teeth + 1) / self.pin_circle_radius
        if k1 >= 1:
            raise ModelError(f"short-width coefficient a·z_p/r_p = {k1:.3f} must be < 1 "
                             f"(z_p = teeth + 1 = {teeth + 1})", f"{path}.eccentricity")


@record
class NeedleGearGeometry(_Shape):
    """Needle gear (pin ring), Eq. (4): V = W·[π((r_p + t)² − r_p²) + z·π·r_rp²/2]."""

    shape: ClassVar[str] = "needle_gear"
    equation: ClassVar[str] = "(4)"
    width: float = _length("axial length of shell and pins (paper: 2·B2, both discs)", "2·B2")
    pin_circle_radius: float = _length("radius of the needle (pin) centre circle", "r_p")
    pin_radius: float = _length("needle (pin) radius", "r_rp")
    shell_thickness: float = _length("radial thickness of the shell outside the pin circle",
                                     "t")

    def check(self, path: str) -> None:
        if self.pin_radius >= self.pin_circle_radius:
            raise ModelError(f"pin radius {self.pin_radius:g} mm is not smaller than the pin "
                             f"circle radius {self.pin_circle_radius:g} mm", f"{path}.pin_radius")

    def check_teeth(self, teeth: int | None, path: str) -> None:
        if teeth is None:
            raise ModelError("a needle gear geometry needs the component's teeth (pins)", path)
        half_pitch = self.pin_circle_radius * math.sin(math.pi / teeth)
        if self.pin_radius >= half_pitch:
            raise ModelError(f"{teeth} pins of radius {self.pin_radius:g} mm overlap on a "
                             f"circle of radius {self.pin_circle_radius:g} mm",
                             f"{path}.pin_radius")


@record
class CrankshaftGeometry(_Shape):
    """Crankshaft, Eq. (5): V = π·r2²·(B1 + 2·B3) + n·π·r5²·B2."""

    shape: ClassVar[str] = "crankshaft"
    equation: ClassVar[str] = "(5)"
    shaft_radius: float = _length("shaft radius (= planet gear bore radius)", "r2")
    gear_seat_length: float = _length("length under the planet gear (its face width)", "B1")
    bearing_width: float = _length("width of each of the two end (thrust) bearings", "B3")
    journal_radius: float = _length("eccentric journal radius = roller bearing inner radius",
                                    "r5")
    journal_length: float = _length("length of each eccentric journal (disc thickness)", "B2")
    journals: int = _count("number of eccentric journals (paper: 2)", "2")


@record
class PlanetFrame1Geometry(_Shape):
    """Planet frame I (end plate), Eq. (6): V = π·r6²·B4 − n·π·r7²·B3."""

    shape: ClassVar[str] = "planet_frame_1"
    equation: ClassVar[str] = "(6)"
    bearing_seat_radius: float = _length("main (angular contact) bearing inner radius", "r6")
    bearing_width: float = _length("main bearing width = plate thickness", "B4")
    crank_bearing_radius: float = _length("crank (thrust) bearing outer radius", "r7")
    crank_bearing_width: float = _length("crank (thrust) bearing width = seat depth", "B3")
    crank_bearings: int = _count("number of crank bearing seats (paper: 2)", "2")

    def check(self, path: str) -> None:
        _check_crank_seats(self, path)
        if self.crank_bearing_width > self.bearing_width:
            raise ModelError(f"the crank bearing seat ({self.crank_bearing_width:g} mm deep) is "
                             f"deeper than the plate ({self.bearing_width:g} mm)",
                             f"{path}.crank_bearing_width")


@record
class PlanetFrame2Geometry(_Shape):
    """Planet frame II, Eq. (7) (see :mod:`powergraph.analyses.volume.formulas`)."""

    shape: ClassVar[str] = "planet_frame_2"
    equation: ClassVar[str] = "(7)"
    seal_radius: float = _length("oil seal inner radius", "r9")
    bearing_seat_radius: float = _length("main (angular contact) bearing inner radius", "r6")
    bearing_width: float = _length("main bearing width", "B4")
    crank_bearing_radius: float = _length("crank (thrust) bearing outer radius", "r7")
    crank_bearing_width: float = _length("crank (thrust) bearing width", "B3")
    crank_bearings: int = _count("number of crank bearing seats (paper: 2)", "2")
    pillar_radius: float = _length("pillar radius", "r8")
    pillars: int = _count("number of pillars (paper: 6)", "6", minimum=0)
    pillar_length: float = _length("pillar length (paper: 2·B2, through both discs)", "2·B2")
    sun: str = _component("component id of the sun gear (its module, face width B1, teeth)")
    planet: str = _component("component id of the planet gear (its teeth and count)")

    def check(self, path: str) -> None:
        _check_crank_seats(self, path)


def _check_crank_seats(geometry: Any, path: str) -> None:
    if geometry.crank_bearing_radius >= geometry.bearing_seat_radius:
        raise ModelError(f"crank bearing radius {geometry.crank_bearing_radius:g} mm is not "
                         f"smaller than the frame radius {geometry.bearing_seat_radius:g} mm",
                         f"{path}.crank_bearing_radius")


#: shape name -> dataclass, in the paper's order.
SHAPES: dict[str, type] = {cls.shape: cls for cls in (
    GearGeometry, CycloidDiscGeometry, NeedleGearGeometry, CrankshaftGeometry,
    PlanetFrame1Geometry, PlanetFrame2Geometry)}

Geometry = (GearGeometry | CycloidDiscGeometry | NeedleGearGeometry | CrankshaftGeometry
            | PlanetFrame1Geometry | PlanetFrame2Geometry)
