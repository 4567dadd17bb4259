"""A REXS gear unit read as a powergraph model (docs/exchange.md).

Shafts become components (the casing the frame), each cylindrical gear a component with
its teeth ``fixed`` to the shaft it is assembled on, each ``stage`` relation a mesh with
its geometry (module, face width, helix and pressure angles, profile shifts, else the
stage's centre distance), the meshes of a planetary stage get its planet carrier shaft as
carrier, every ``side`` relation (concept and rolling bearings) a ``bearing`` link, every
``coupling`` relation a ``coupling``; the lubricant the model's ``lubricant``; the
external loads that transmit torque become ports, the shaft that ``defines_speed`` the
input, its speed and the defined torques from the first load case. Every load case is
also a duty-cycle point (speed and torque columns, a duration of its fraction of one
hour). Whatever is not read is named in :attr:`RexsImport.unmapped`.

Attributes the standard has no name for are read from custom attributes
(``custom_powergraph_mesh_efficiency`` on a stage, ``custom_powergraph_efficiency`` on a
coupling), which :mod:`powergraph.exchange.rexs_writer` writes.

Examples
--------
>>> result = read_rexs("tests/exchange/data/two_stage_helical.rexs")     # doctest: +SKIP
>>> result.data["links"][0]["type"]                                      # doctest: +SKIP
'fixed'
"""
from __future__ import annotations

import math
from collections import defaultdict
from pathlib import Path
from typing import Any

from powergraph.errors import Caveat
from powergraph.model.rexs_document import RexsDocument, parse_rexs
from powergraph.model.rexs_values import AttributeReader
from powergraph.model.input_files import REXS_SUFFIXES, is_rexs_path  # noqa: F401
from powergraph.model.yaml_loader import read_model_bytes
from powergraph.records import record

#: File suffixes read as REXS wherever a model path is taken.
#: How long the load spectrum lasts in the duty-cycle points: fractions of one hour.
SPECTRUM_SECONDS = 3600.0
_BEARING_ROLES = ("inner_part", "outer_part")
_FRACTIONS = ("load_duration_fraction", "custom_load_duration_fraction")


@record
class RexsImport:
    """What a REXS file gives: ``data`` (the model as plain data, as YAML would give it),
    ``points`` (one row per load case: ``{column: value}`` in the duty-cycle points format,
    ``duration [s]`` first) and ``unmapped`` (one line per kind of thing not read)."""

    data: dict[str, Any]
    points: tuple[dict[str, float], ...]
    unmapped: tuple[str, ...]


def rexs_caveats(imported: RexsImport) -> tuple[Caveat, ...]:
    """What a model read straight from a REXS file should warn of: meshes without an
    efficiency (REXS carries none: they are ideal) and the attributes not read.

    >>> data = {"links": [{"type": "mesh", "between": [1, 2]}]}
    >>> [c.code for c in rexs_caveats(RexsImport(data, (), ("shaft: mass",)))]
    ['rexs-ideal-meshes', 'rexs-not-mapped']
    """
    out = []
    ideal = [i for i, link in enumerate(imported.data["links"])
             if link["type"] == "mesh" and "efficiency" not in link]
    if ideal and "mesh_efficiency" not in imported.data.get("defaults", {}):
        out.append(Caveat(f"{len(ideal)} mesh(es) without an efficiency (REXS carries "
                          "none): ideal, η = 1, so no mesh loss; import the file with "
                          "--mesh-efficiency E, or give the meshes efficiencies or friction "
                          "blocks in the model file", f"links[{ideal[0]}]",
                          "rexs-ideal-meshes"))
    if imported.unmapped:
        out.append(Caveat(f"not read from the REXS file: {'; '.join(imported.unmapped)}",
                          None, "rexs-not-mapped"))
    return tuple(out)


def read_rexs(path: str | Path, mesh_efficiency: float | None = None) -> RexsImport:
    """Read a REXS file (size-limited as a model file) into a :class:`RexsImport`."""
    document = parse_rexs(read_model_bytes(path), str(path))
    return rexs_import(document, mesh_efficiency, Path(path).stem)


def rexs_import(document: RexsDocument, mesh_efficiency: float | None = None,
                name: str = "REXS model") -> RexsImport:
    """The model, points and unmapped summary of a parsed REXS document."""
    return _Reader(document).build(mesh_efficiency, name)


class _Reader(AttributeReader):
    """Reads a document once, noting every attribute and relation it uses."""

    def build(self, mesh_efficiency: float | None, name: str) -> RexsImport:
        doc = self.doc
        casings = self.of_type("gear_casing")
        if len(casings) > 1:
            raise self.error(f"{len(casings)} gear casings (components "
                             f"{', '.join(map(str, casings))}); expected at most one")
        units = self.of_type("gear_unit")
        title = doc.components[units[0]].name if units and doc.components[units[0]].name \
            else name
        self.frame = casings[0] if casings else "housing"
        components: dict[Any, dict] = {self.frame: {"role": "frame", "name": (
            doc.components[casings[0]].name or "casing") if casings else "housing"}}
        for shaft in self.of_type("shaft"):
            components[shaft] = _named(doc.components[shaft].name)
        links: list[dict] = []
        stages = self._planetary_stages()
        self._gears(components, links, stages)
        links += [self._mesh(r, stages) for r in self.relations("stage")
                  if self._cylindrical(r)]
        links += self._bearings(components) + self._couplings(components)
        for stage in stages.values():
            links += [{"type": "fixed", "between": [pin, stage["carrier"]]}
                      for pin in stage["pins"]]
        data = {"name": title,
                "description": f"Imported from the REXS {doc.version} file "
                               f"{Path(doc.source).name} by powergraph import.",
                "components": components, "links": links}
        if mesh_efficiency is not None:
            data["defaults"] = {"mesh_efficiency": mesh_efficiency}
        lubricant = self._lubricant()
        if lubricant:
            data["lubricant"] = lubricant
        data["ports"], points = self._ports(components)
        return RexsImport(data, points, self._unmapped())

    def _planetary_stages(self) -> dict[int, dict]:
        stages = {s: {"carrier": None, "planets": set(), "pins": [], "count": None,
                      "parts": set()} for s in self.of_type("planetary_stage")}
        for kind in ("planet_carrier_shaft", "planet_shaft", "planet_pin", "central_shaft"):
            for relation in self.relations(kind):
                stage, shaft = relation.role("planetary_stage"), relation.role("shaft")
                if stage not in stages or shaft is None:
                    raise self.error(f"relation {relation.id} ({kind}): needs a "
                                     "planetary_stage and a shaft")
                entry = stages[stage]
                if kind == "planet_carrier_shaft":
                    entry["carrier"] = entry["carrier"] or shaft
                    if entry["carrier"] != shaft:
                        entry["pins"].append(shaft)     # a second carrier shaft: one body
                elif kind == "planet_shaft":
                    entry["planets"].add(shaft)
                elif kind == "planet_pin":
                    entry["pins"].append(shaft)
        for ident, entry in stages.items():
            if entry["carrier"] is None:
                raise self.error(f"planetary stage {ident}: no planet_carrier_shaft relation "
                                 "names its carrier")
            count = self.value(ident, "number_of_planets", "number")
            entry["count"] = None if count is None else int(count)
        for relation in self.by_type.get("assembly", []):
            if relation.role("assembly") in stages:
                stages[relation.role("assembly")]["parts"].add(relation.role("part"))
        return stages

    def _gears(self, components: dict, links: list, stages: dict) -> None:
        self.shaft_of: dict[int, Any] = {}
        holders = set(self.of_type("shaft", "gear_casing"))
        for relation in self.relations("assembly") + self.relations("ordered_assembly"):
            part, holder = relation.role("part"), relation.role("assembly")
            if self.doc.components[part].type == "cylindrical_gear" and holder in holders:
                self.shaft_of[part] = self.frame if self.doc.components[holder].type == \
                    "gear_casing" else holder
        planet_count = {p: s["count"] for s in stages.values() for p in s["planets"]}
        for gear in self.of_type("cylindrical_gear"):
            if gear not in self.shaft_of:
                raise self.error(f"cylindrical gear {gear}: no assembly relation puts it on a "
                                 "shaft or the casing")
            teeth = self.value(gear, "number_of_teeth", "number")
            if teeth is None or teeth != int(teeth) or teeth == 0:
                raise self.error(f"cylindrical gear {gear}: number_of_teeth must be a whole "
                                 f"number other than 0, got {teeth}")
            entry = _named(self.doc.components[gear].name) | {"teeth": abs(int(teeth))}
            if teeth < 0:
                entry["internal"] = True           # REXS: an internal gear's teeth are < 0
            shaft = self.shaft_of[gear]
            if planet_count.get(shaft):
                entry["count"] = components[shaft]["count"] = planet_count[shaft]
            components[gear] = entry
            links.append({"type": "fixed", "between": [gear, shaft]})

    def _cylindrical(self, relation) -> bool:
        """A stage between two cylindrical gears; another (bevel, worm) is not mapped."""
        gears = [relation.role(r) for r in ("gear_1", "gear_2")]
        if all(g is not None and self.doc.components[g].type == "cylindrical_gear"
               for g in gears):
            return True
        self.used_relations.discard(relation.id)
        return False

    def _mesh(self, relation, stages: dict) -> dict:
        stage, g1, g2 = (relation.role(r) for r in ("stage", "gear_1", "gear_2"))
        if None in (stage, g1, g2) or g1 not in self.shaft_of or g2 not in self.shaft_of:
            raise self.error(f"relation {relation.id} (stage): needs a stage and two "
                             "cylindrical gears (gear_1, gear_2)")
        link: dict[str, Any] = {"type": "mesh", "between": [g1, g2]}
        name = self.doc.components[stage].name
        if name:
            link["name"] = name
        efficiency = self.value(stage, "custom_powergraph_mesh_efficiency", "number")
        if efficiency is not None:
            link["efficiency"] = efficiency
        for ident, entry in stages.items():
            if (stage in entry["parts"] or self.shaft_of[g1] in entry["planets"]
                    or self.shaft_of[g2] in entry["planets"]):
                link["carrier"] = entry["carrier"]
        geometry = self._geometry(stage, g1, g2)
        if geometry:
            link["geometry"] = geometry
        return link

    def _geometry(self, stage: int, g1: int, g2: int) -> dict:
        modules = [self.value(g, "normal_module", "length") for g in (g1, g2)]
        known = [m for m in modules if m is not None]
        if not known:
            return {}
        if len(known) == 2 and not math.isclose(*known, rel_tol=1e-9):
            raise self.error(f"stage {stage}: gears {g1} and {g2} have different normal "
                             f"modules ({known[0]:g} and {known[1]:g} mm)")
        geometry: dict[str, Any] = {"module": known[0]}
        widths = [w for w in (self.value(g, "face_width", "length") for g in (g1, g2))
                  if w is not None]
        if widths:
            geometry["face_width"] = min(widths)
        helix = [self.value(g, "helix_angle_reference_diameter", "angle") for g in (g1, g2)]
        if helix[0] is not None:
            geometry["helix_angle"] = helix[0]
        angle = [a for g in (g1, g2) for a in self.flank_values(g, "normal_pressure_angle",
                                                                 "angle")]
        if angle:
            geometry["pressure_angle"] = angle[0]
        shifts = [self.shift(g) for g in (g1, g2)]
        internal_first = (self.value(g1, "number_of_teeth", "number") or 0) < 0
        distance = self.value(stage, "center_distance", "length")
        if any(s is not None for s in shifts):
            pair = [s or 0.0 for s in shifts]
            geometry["shifts"] = pair[::-1] if internal_first else pair
            if distance is not None:
                self.used.discard((stage, "center_distance"))   # the shifts fix it
        elif distance is not None:
            geometry["centre_distance"] = distance
        return geometry

    def _member(self, ident: int, components: dict) -> Any:
        kind = self.doc.components[ident].type
        if kind == "gear_casing":
            return self.frame
        if ident not in components:
            raise self.error(f"component {ident} ({kind}) is joined by a bearing or coupling "
                             "but is not a shaft, gear or the casing")
        return ident

    def _bearings(self, components: dict) -> list[dict]:
        links = []
        for relation in self.relations("side"):
            inner, outer = (relation.role(r) for r in _BEARING_ROLES)
            if inner is None or outer is None:
                raise self.error(f"relation {relation.id} (side): needs an inner_part and an "
                                 "outer_part")
            link = {"type": "bearing",
                    "between": [self._member(inner, components), self._member(outer, components)]}
            name = self.doc.components[relation.role("assembly")].name \
                if relation.role("assembly") is not None else ""
            links.append(link | ({"name": name} if name else {}))
        return links

    def _couplings(self, components: dict) -> list[dict]:
        links = []
        for relation in self.relations("coupling"):
            sides = [ref for role, ref, _ in relation.refs if role != "assembly"]
            if len(sides) != 2:
                raise self.error(f"relation {relation.id} (coupling): needs two sides")
            link = {"type": "coupling", "between": [self._member(s, components) for s in sides]}
            holder = relation.role("assembly")
            efficiency = None if holder is None else self.value(
                holder, "custom_powergraph_efficiency", "number")
            links.append(link | ({} if efficiency is None else {"efficiency": efficiency}))
        return links

    def _lubricant(self) -> dict:
        oils = self.of_type("lubricant")
        if not oils:
            return {}
        oil = oils[0]
        values = [self.value(oil, f"viscosity_at_{t}_degree_celsius", "viscosity")
                  for t in (40, 100)]
        density = self.value(oil, "density_at_15_degree_celsius", "density")
        if None in values or density is None:
            for attribute in ("viscosity_at_40_degree_celsius", "density_at_15_degree_celsius",
                              "viscosity_at_100_degree_celsius"):
                self.used.discard((oil, attribute))     # cannot be a model lubricant
            return {}
        block = {"viscosity_40": f"{values[0]!r} cSt", "viscosity_100": f"{values[1]!r} cSt",
                 "density": f"{density!r} kg/m^3"}
        temperature = (None if not self.doc.load_cases else next(
            (t for c in self.of_type("gear_casing")
             if (t := self.value(c, "temperature_lubricant", "temperature", 0)) is not None),
            None))
        return block | ({} if temperature is None else {"temperature": f"{temperature!r} degC"})

    def _ports(self, components: dict) -> tuple[list[dict], tuple]:
        shafts = set(self.of_type("shaft"))
        loads = {}
        for relation in self.by_type.get("assembly", []):
            part, holder = relation.role("part"), relation.role("assembly")
            if self.doc.components[part].type == "external_load" and holder in shafts:
                if self.flag(part, "transmits_torque", True):
                    if holder in loads.values():
                        raise self.error(f"shaft {holder} carries two loads that transmit "
                                         "torque; powergraph takes one port per shaft")
                    loads[part] = holder
        driven = [s for s in sorted(shafts) if self.flag(s, "defines_speed", False)]
        defined = {load: shaft for load, shaft in loads.items()
                   if self.flag(load, "defines_torque", False)}
        order = driven + [s for s in loads.values() if s not in driven]
        first_input = order[0] if driven else next(iter(defined.values()), None)
        ports, rows = [], []
        for case in range(len(self.doc.load_cases)):
            rows.append(self._row(case, order, driven, defined))
        roles = {shaft: self._role(load) for load, shaft in loads.items()}
        for shaft in order:
            port = {"component": shaft, "role": roles.get(shaft) or (
                "input" if shaft in driven or shaft == first_input else "output")}
            if rows and f"{shaft}.speed [rpm]" in rows[0]:
                port["speed"] = f"{rows[0][f'{shaft}.speed [rpm]']!r} rpm"
            if rows and f"{shaft}.torque [N*m]" in rows[0]:
                port["torque"] = f"{rows[0][f'{shaft}.torque [N*m]']!r} N*m"
            ports.append(port)
        return ports, tuple(rows)

    def _role(self, load: int) -> str | None:
        """The role powergraph wrote on a load (``custom_powergraph_role``), or None."""
        raw = self.doc.components[load].attributes.get("custom_powergraph_role")
        if raw is None:
            return None
        self.used.add((load, "custom_powergraph_role"))
        if raw[0] not in ("input", "output"):
            raise self.error(f"component {load} custom_powergraph_role: {raw[0]!r} is not "
                             "input or output")
        return raw[0]

    def _row(self, case: int, order: list, driven: list, defined: dict) -> dict:
        fractions = [f for c in self.doc.load_cases[case] for attribute in _FRACTIONS
                     if (f := self.value(c, attribute, "fraction", case)) is not None]
        share = fractions[0] if fractions else 1.0 / len(self.doc.load_cases)
        row = {"duration [s]": share * SPECTRUM_SECONDS}
        for shaft in order:
            sense = self._sense(shaft)
            speed = self.value(shaft, "rotational_speed", "speed", case) \
                if shaft in driven else None
            if speed is not None:
                row[f"{shaft}.speed [rpm]"] = sense * speed
            torque = next((t for load, s in defined.items() if s == shaft and
                           (t := self.value(load, "torque_around_u_axis", "torque", case))
                           is not None), None)
            if torque is not None:
                row[f"{shaft}.torque [N*m]"] = sense * torque
        return row

    def _sense(self, shaft: int) -> float:
        """+1 when the shaft's ``u_axis_vector`` points as the gear unit's (else as the
        first shaft's that gives one), −1 when it points the other way: REXS gives speeds
        and torques about each shaft's own axis, the model about one common axis. An axis
        at an angle (a bevel stage) is an error."""
        axes = {c: self.vector(c, "u_axis_vector") for c in self.of_type("gear_unit", "shaft")}
        reference = next((axes[c] for c in self.of_type("gear_unit") if axes[c] is not None),
                         next((a for a in axes.values() if a is not None), None))
        own = axes.get(shaft)
        if own is None or reference is None:
            return 1.0
        cosine = sum(a * b for a, b in zip(own, reference)) / math.hypot(*own) / \
            math.hypot(*reference)
        if abs(abs(cosine) - 1.0) > 1e-6:
            raise self.error(f"shaft {shaft}: its u_axis_vector is not parallel to the gear "
                             "unit's; powergraph takes speeds about one common axis")
        return 1.0 if cosine > 0 else -1.0

    def _unmapped(self) -> tuple[str, ...]:
        found = defaultdict(set)
        for component in self.doc.components.values():
            for attribute in component.attributes:
                if (component.id, attribute) not in self.used:
                    found[component.type].add(attribute)
        lines = [f"{kind}: {', '.join(sorted(names))}" for kind, names in sorted(found.items())]
        cases = defaultdict(set)
        for index, case in enumerate(self.doc.load_cases):
            for ident, attributes in case.items():
                kind = self.doc.components.get(ident)
                cases[kind.type if kind else f"component {ident}"].update(
                    a for a in attributes if (index, ident, a) not in self.case_used)
        lines += [f"load cases, {kind}: {', '.join(sorted(names))}"
                  for kind, names in sorted(cases.items()) if names]
        relations = defaultdict(int)
        for relation in self.doc.relations:
            if relation.id not in self.used_relations and relation.type not in (
                    "assembly", "stage_gear_data", "reference"):
                relations[relation.type] += 1
        lines += [f"relations: {', '.join(f'{k} ({n})' for k, n in sorted(relations.items()))}"
                  ] if relations else []
        return tuple(lines)


def _named(name: str) -> dict:
    return {"name": name} if name else {}
