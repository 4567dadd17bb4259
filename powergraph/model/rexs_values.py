"""Attributes of a REXS document read in the model's units, every use noted
(:mod:`powergraph.model.rexs_reader` lists what was not used as not mapped).

>>> from powergraph.model.rexs_document import parse_rexs
>>> doc = parse_rexs(b'<model version="1.4"><relations/><components>'
...                  b'<component id="1" name="" type="shaft">'
...                  b'<attribute id="rotational_speed" unit="rad / s">10</attribute>'
...                  b'</component></components></model>', "x.rexs")
>>> reader = AttributeReader(doc)
>>> round(reader.value(1, "rotational_speed", "speed"), 4), reader.used
(95.493, {(1, 'rotational_speed')})
"""
from __future__ import annotations

import math
from collections import defaultdict
from typing import Any

from powergraph.errors import ModelError
from powergraph.model.rexs_document import RexsDocument
from powergraph.model.yaml_loader import brief

#: Units of the attributes read, without spaces: unit -> factor to the model's unit
#: (mm, degrees, rpm, N·m, fraction, cSt, kg/m³).
UNITS = {
    "length": {"mm": 1.0, "m": 1000.0, "mum": 1e-3, "um": 1e-3},
    "angle": {"deg": 1.0, "rad": 180.0 / math.pi},
    "speed": {"1/min": 1.0, "rpm": 1.0, "rad/s": 30.0 / math.pi},
    "torque": {"Nm": 1.0, "N*m": 1.0, "Nmm": 1e-3, "kNm": 1e3},
    "fraction": {"%": 0.01, "": 1.0, "none": 1.0, "-": 1.0},
    "number": {"": 1.0, "none": 1.0, "-": 1.0},
    "viscosity": {"mm^2/s": 1.0, "cSt": 1.0, "m^2/s": 1e6},
    "density": {"kg/dm^3": 1000.0, "kg/m^3": 1.0, "g/cm^3": 1000.0},
    "temperature": {"C": 1.0, "degC": 1.0},
}


class AttributeReader:
    """Reads the attributes and relations of a document, noting each one it uses (what
    is not used is what was not mapped)."""

    def __init__(self, document: RexsDocument) -> None:
        self.doc, self.used, self.used_relations = document, set(), set()
        self.case_used: set[tuple[int, int, str]] = set()
        by_type = defaultdict(list)
        for relation in document.relations:
            by_type[relation.type].append(relation)
        self.by_type = by_type

    def error(self, message: str) -> ModelError:
        return ModelError(message, self.doc.source)

    def of_type(self, *types: str) -> list[int]:
        return [c.id for c in self.doc.components.values() if c.type in types]

    def value(self, ident: int, attribute: str, kind: str, case: int | None = None) -> Any:
        """An attribute as a float in the model's unit (None when absent)."""
        source = (self.doc.components[ident].attributes if case is None
                  else self.doc.load_cases[case].get(ident, {}))
        if attribute not in source:
            return None
        (self.used.add((ident, attribute)) if case is None
         else self.case_used.add((case, ident, attribute)))
        raw, unit = source[attribute]
        factors = UNITS[kind]
        key = unit.replace(" ", "")
        where = f"component {ident} {attribute}" + ("" if case is None else
                                                    f" (load case {case + 1})")
        if key not in factors:
            raise self.error(f"{where}: unit {unit!r} is not one of "
                             f"{', '.join(repr(u) for u in factors)}")
        try:
            number = float(raw)
        except (TypeError, ValueError):
            raise self.error(f"{where}: {brief(raw)} is not a number") from None
        if not math.isfinite(number):
            raise self.error(f"{where}: {brief(raw)} is not a finite number")
        return number * factors[key]

    def flag(self, ident: int, attribute: str, default: bool) -> bool:
        attributes = self.doc.components[ident].attributes
        if attribute not in attributes:
            return default
        self.used.add((ident, attribute))
        raw = attributes[attribute][0]
        if isinstance(raw, bool) or str(raw).lower() in ("true", "false"):
            return raw if isinstance(raw, bool) else str(raw).lower() == "true"
        raise self.error(f"component {ident} {attribute}: {raw!r} is not true or false")

    def relations(self, kind: str) -> list:
        found = self.by_type.get(kind, [])
        self.used_relations.update(r.id for r in found)
        return found

    def flank_values(self, gear: int, attribute: str, kind: str) -> list[float]:
        """A gear's attribute, else its flanks' (``flank`` relation: left, right)."""
        own = self.value(gear, attribute, kind)
        if own is not None:
            return [own]
        flanks = [ref for r in self.relations("flank") if r.role("gear") == gear
                  for role, ref, _ in r.refs if role in ("left", "right")]
        return [v for v in (self.value(f, attribute, kind) for f in flanks) if v is not None]

    def shift(self, gear: int) -> float | None:
        """A gear's profile shift coefficient (its flanks' must agree), or None."""
        for attribute in ("profile_shift_coefficient", "addendum_modification_coefficient"):
            values = self.flank_values(gear, attribute, "number")
            if values:
                if max(values) - min(values) > 1e-12:
                    raise self.error(f"cylindrical gear {gear}: its flanks have different "
                                     f"{attribute} ({', '.join(f'{v:g}' for v in values)})")
                return values[0]
        return None

    def vector(self, ident: int, attribute: str) -> list[float] | None:
        """A vector of three numbers (an axis, a position), or None when absent."""
        raw = self.doc.components[ident].attributes.get(attribute)
        if raw is None:
            return None
        self.used.add((ident, attribute))
        try:
            axis = [float(x) for x in raw[0]]
        except (TypeError, ValueError):
            axis = []
        if len(axis) != 3 or not any(axis) or not all(map(math.isfinite, axis)):
            raise self.error(f"component {ident} {attribute}: {raw[0]!r} is not a vector "
                             "of three numbers")
        return axis
