"""A powergraph train written as a REXS gear unit (docs/exchange.md).

Each rigid body becomes a shaft (the frame's the gear casing), each gear on it a
cylindrical gear (an internal one with negative teeth) with its module, helix angle,
pressure angle and profile shift (on its two flanks), each mesh a cylindrical stage
with both gears' stage data, the meshes on a moving carrier grouped in a planetary stage
per carrier (``planet_carrier_shaft``, ``planet_shaft``, ``central_shaft`` relations, the
number of planets), each ``bearing`` link a concept bearing (``side``), each coupling a
``coupling`` relation, the lubricant, and the operating point as the one load case: the
speeds of the shafts that define them and the torques of the loads that define them
(a port given by its power is written with its torque at the solved point). The basic
efficiency each mesh has at that point and the ports' roles go in custom attributes
(``custom_powergraph_mesh_efficiency``, ``custom_powergraph_role``), which
:mod:`powergraph.model.rexs_reader` reads back. What the format cannot hold is named in
:attr:`RexsExport.unmapped`.

Examples
--------
>>> from powergraph.model import load_model
>>> export = rexs_export(load_model("models/planetary_2kh_two_stages.yaml"))
>>> kinds = [c.type for c in export.document.components.values()]
>>> kinds.count("planetary_stage"), kinds.count("cylindrical_stage")
(2, 4)
"""
from __future__ import annotations

import math
from itertools import count
from typing import Any

from powergraph.errors import ModelError
from powergraph.model.rexs_document import RexsComponent, RexsDocument, RexsRelation
from powergraph.model.spec import Model
from powergraph.records import record
from powergraph.statics import solve
from powergraph.statics.case import TrainCase

#: The REXS version written.
REXS_VERSION = "1.4"
_RPM = 30.0 / math.pi
#: Every shaft's axis, the gear unit's: speeds and torques are about one common axis.
_AXIS = [1.0, 0.0, 0.0]


@record
class RexsExport:
    """A train as a REXS ``document`` and the ``unmapped`` features (one line each)."""

    document: RexsDocument
    unmapped: tuple[str, ...]


def rexs_export(model: Model, mode: str | None = None, source: str = "<export>") -> RexsExport:
    """The train (in ``mode``, for a train with shift elements) as a REXS document."""
    if model.shift_elements and mode is None:
        raise ModelError("the train has shift elements: name the mode to write (--mode); "
                         "REXS holds one gear train", "modes")
    plain = TrainCase.of(model, mode).plain_model() if model.shift_elements else model
    return _Writer(plain, source).build(model)


class _Writer:
    def __init__(self, model: Model, source: str) -> None:
        self.model, self.source = model, source
        self.result = solve(model)
        self.ids = count(1)
        self.components: dict[int, RexsComponent] = {}
        self.relations: list[RexsRelation] = []
        self.unmapped: list[str] = []
        self.flanked: set[str] = set()

    def add(self, kind: str, name: str, **attributes: Any) -> int:
        ident = next(self.ids)
        self.components[ident] = RexsComponent(ident, kind, name, {
            key: value for key, value in attributes.items() if value[0] is not None})
        return ident

    def relate(self, kind: str, *refs: tuple[str, int]) -> None:
        self.relations.append(RexsRelation(next(self.ids), kind, tuple(
            (role, ref, self.components[ref].type) for role, ref in refs)))

    def build(self, original: Model) -> RexsExport:
        model = self.model
        self.unit = self.add("gear_unit", model.name, u_axis_vector=(_AXIS, "mm"))
        self.shaft = {}
        for body in model.bodies:
            names = [model.components[c].name or str(model.components[c].raw_id)
                     for c in body.members]
            kind = "gear_casing" if body.is_frame else "shaft"
            self.shaft[body.id] = self.add(kind, " / ".join(names), **(
                {} if body.is_frame else {"defines_speed": (False, "none"),
                                          "u_axis_vector": (_AXIS, "mm")}))
            self.relate("assembly", ("assembly", self.unit), ("part", self.shaft[body.id]))
        self.gear = {}
        for ident, component in model.components.items():
            if component.teeth is not None:
                self._gear(ident, component)
        stages = [self._stage(link) for link in model.links if link.type == "mesh"]
        self._planetary(stages)
        self._bearings_and_couplings()
        self._lubricant()
        cases = self._load_case()
        self._unmapped_features(original)
        document = RexsDocument(REXS_VERSION, self.components, tuple(self.relations),
                                cases, self.source)
        return RexsExport(document, tuple(self.unmapped))

    def _body_shaft(self, component: str) -> int:
        return self.shaft[self.model.body_of[component]]

    def _gear(self, ident: str, component) -> None:
        teeth = -component.teeth if component.internal else component.teeth
        width = getattr(component.geometry, "face_width", None)
        self.gear[ident] = self.add("cylindrical_gear", component.name or str(component.raw_id),
                                    number_of_teeth=(teeth, "none"),
                                    face_width=(width, "mm"))
        self.relate("assembly", ("assembly", self._body_shaft(ident)),
                    ("part", self.gear[ident]))

    def _stage(self, link) -> tuple[int, Any]:
        if link.ratio is not None or any(self.model.components[c].teeth is None
                                         for c in link.between):
            raise ModelError("a mesh given by its ratio, without the gears' teeth, has no "
                             "REXS cylindrical stage", f"links[{link.index}]")
        flow = next(e for e in self.result.elements if e.link == link.index)
        name = link.name or f"stage {'-'.join(map(str, link.raw_between))}"
        stage = self.add("cylindrical_stage", name,
                         custom_powergraph_mesh_efficiency=(flow.efficiency, "none"))
        g1, g2 = (self.gear[c] for c in link.between)
        self.relate("stage", ("stage", stage), ("gear_1", g1), ("gear_2", g2))
        for gear in (g1, g2):
            data = self.add("cylindrical_stage_gear_data", f"{name}: {gear}")
            self.relate("stage_gear_data", ("stage", stage), ("gear", gear),
                        ("stage_gear_data", data))
        geometry = link.blocks.get("geometry")
        if geometry is not None:
            self._geometry(link, geometry, stage)
        return stage, link

    def _geometry(self, link, geometry, stage: int) -> None:
        a, b = link.between
        pinion_first = not self.model.components[a].internal
        if hasattr(geometry, "centre_distance"):   # the operating centre distance, no shifts
            self.components[stage].attributes["center_distance"] = (
                geometry.centre_distance, "mm")
            shifts = (None, None)
        else:
            shifts = ((geometry.shift_1, geometry.shift_2) if pinion_first
                      else (geometry.shift_2, geometry.shift_1))
        internal = self.model.components[a].internal or self.model.components[b].internal
        helix = (geometry.helix_angle_deg,
                 geometry.helix_angle_deg if internal else -geometry.helix_angle_deg)
        for component, shift, beta in zip((a, b), shifts, helix):
            if component in self.flanked:
                continue                     # a gear in two meshes: its first mesh's data
            self.flanked.add(component)
            gear = self.gear[component]
            attributes = self.components[gear].attributes
            attributes["normal_module"] = (geometry.module, "mm")
            attributes["helix_angle_reference_diameter"] = (beta, "deg")
            flanks = [self.add("cylindrical_gear_flank", f"{side} flank",
                               normal_pressure_angle=(geometry.pressure_angle_deg, "deg"),
                               addendum_modification_coefficient=(shift, "none"))
                      for side in ("left", "right")]
            self.relate("flank", ("gear", gear), ("left", flanks[0]), ("right", flanks[1]))

    def _planetary(self, stages: list) -> None:
        by_carrier: dict[str, list] = {}
        frame = self.model.frame_body
        for stage, link in stages:
            carrier = self.model.body_of[link.carrier]
            if carrier != frame:
                by_carrier.setdefault(carrier, []).append((stage, link))
        for carrier, members in by_carrier.items():
            planets = {self.model.body_of[c] for _, link in members for c in link.between
                       if self._is_planet(c, carrier, members)}
            central = {self.model.body_of[c] for _, link in members
                       for c in link.between} - planets - {frame}
            number = max(self.model.components[c].count for body in planets
                         for c in self._members(body)) if planets else 1
            planetary = self.add("planetary_stage", f"planetary stage on {carrier}",
                                 number_of_planets=(number, "none"))
            self.relate("assembly", ("assembly", self.unit), ("part", planetary))
            self.relate("planet_carrier_shaft", ("planetary_stage", planetary),
                        ("shaft", self.shaft[carrier]))
            for kind, bodies in (("planet_shaft", planets), ("central_shaft", central)):
                for body in sorted(bodies):
                    self.relate(kind, ("planetary_stage", planetary), ("shaft", self.shaft[body]))
            for stage, _ in members:
                self.relate("assembly", ("assembly", planetary), ("part", stage))

    def _members(self, body: str) -> tuple[str, ...]:
        return next(b.members for b in self.model.bodies if b.id == body)

    def _is_planet(self, component: str, carrier: str, members: list) -> bool:
        """A gear turning on the carrier: counted several times, in more meshes on the
        carrier than its partner, or borne by it."""
        body = self.model.body_of[component]
        if any(self.model.components[c].count > 1 for c in self._members(body)):
            return True
        borne = any(link.type == "bearing" and {self.model.body_of[c] for c in link.between}
                    == {body, carrier} for link in self.model.links)
        meshes = sum(component in link.between for _, link in members)
        return borne or meshes > 1

    def _bearings_and_couplings(self) -> None:
        for link in self.model.links:
            if link.type not in ("bearing", "coupling"):
                continue
            bodies = [self.model.body_of[c] for c in link.between]
            if bodies[0] == bodies[1]:
                self.unmapped.append(f"links[{link.index}]: a {link.type} inside one rigid "
                                     "body (nothing turns in it)")
                continue
            shafts = [self.shaft[b] for b in bodies]
            if link.type == "coupling":
                self.relate("coupling", ("side_1", shafts[0]), ("side_2", shafts[1]))
                continue
            bearing = self.add("concept_bearing", link.name or
                               f"bearing {'-'.join(map(str, link.raw_between))}")
            self.relate("side", ("assembly", bearing), ("inner_part", shafts[0]),
                        ("outer_part", shafts[1]))

    def _lubricant(self) -> None:
        oil = self.model.lubricant
        if oil is None:
            return
        lubricant = self.add(
            "lubricant", oil.grade or "lubricant",
            viscosity_at_40_degree_celsius=(oil.viscosity_40 * 1e6, "mm^2 / s"),
            viscosity_at_100_degree_celsius=(oil.viscosity_100 * 1e6, "mm^2 / s"),
            density_at_15_degree_celsius=(oil.density / 1000.0, "kg / dm^3"))
        self.relate("reference", ("origin", self.shaft[self.model.frame_body]),
                    ("referenced", lubricant))

    def _load_case(self) -> tuple[dict, ...]:
        case: dict[int, dict] = {self.unit: {"load_duration_fraction": (100.0, "%")}}
        oil = self.model.lubricant
        if oil is not None:
            case[self.shaft[self.model.frame_body]] = {
                "temperature_lubricant": (oil.temperature - 273.15, "C")}
        for port, flow in zip(self.model.ports, self.result.ports):
            shaft = self._body_shaft(port.component)
            given_load = port.power is not None or port.torque is not None
            load = self.add("external_load", port.name or f"port {port.index}",
                            transmits_torque=(True, "none"), defines_torque=(given_load, "none"),
                            custom_powergraph_role=(
                                port.role if port.role in ("input", "output") else None,
                                "none"))
            self.relate("assembly", ("assembly", shaft), ("part", load))
            if port.speed is not None:
                self.components[shaft].attributes["defines_speed"] = (True, "none")
                case.setdefault(shaft, {})["rotational_speed"] = (port.speed * _RPM, "1 / min")
            if given_load:
                case[load] = {"torque_around_u_axis": (flow.torque, "N m")}
        return (case,)

    def _unmapped_features(self, original: Model) -> None:
        model, notes = self.model, self.unmapped
        for link in model.links:
            for key in link.blocks:
                if key == "friction" and link.type == "mesh":
                    notes.append(f"links[{link.index}].friction: written as the basic "
                                 "efficiency at the operating point")
                elif key != "geometry":
                    notes.append(f"links[{link.index}].{key}")
            if link.type == "seal":
                notes.append(f"links[{link.index}]: seal")
            if link.type == "coupling" and link.efficiency != 1.0:
                notes.append(f"links[{link.index}]: coupling efficiency {link.efficiency:g} "
                             "(written as an ideal coupling)")
        for ident, component in model.components.items():
            notes += [f"components.{component.raw_id}.{key}" for key in ("drag", "churning")
                      if getattr(component, key) is not None]
        if original.shift_elements:
            notes.append(f"shift elements and modes: the train in mode {model.mode!r} only")
        notes += [f"{key}" for key in ("thermal", "tolerances", "buses")
                  if getattr(original, key, None)]
        if any(p.role == "machine" for p in model.ports):
            notes.append("ports: electric machines (written as plain loads)")
