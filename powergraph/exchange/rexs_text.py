"""A REXS document as text: XML (``.rexs``) or JSON (``.rexsj``), the two forms
:func:`powergraph.model.rexs_document.parse_rexs` reads.

Values are written by their Python type: a bool as ``true``/``false`` (JSON
``boolean``), an int as an integer, a float in full (``repr``; JSON ``floating_point``),
a string as text (JSON ``string``).

Examples
--------
>>> from powergraph.model.rexs_document import RexsComponent, RexsDocument
>>> doc = RexsDocument("1.4", {1: RexsComponent(1, "shaft", "input",
...                                             {"defines_speed": (True, "none")})}, (), (), "x")
>>> print(to_xml(doc, "2026-01-01T00:00:00+00:00").splitlines()[4].strip())
<component id="1" name="input" type="shaft">
>>> to_json(doc, "2026-01-01T00:00:00+00:00").count('"boolean": true')
1
"""
from __future__ import annotations

import json
import xml.etree.ElementTree as ET
from datetime import datetime, timezone
from typing import Any

from powergraph import __version__
from powergraph.model.rexs_document import RexsComponent, RexsDocument

_APPLICATION = "powergraph"


def _date(date: str | None) -> str:
    return date or datetime.now(timezone.utc).strftime("%Y-%m-%dT%H:%M:%S+00:00")


def _text(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    return repr(value) if isinstance(value, float) else str(value)


def to_xml(document: RexsDocument, date: str | None = None) -> str:
    """The document as REXS XML text."""
    root = ET.Element("model", {"applicationId": _APPLICATION,
                                "applicationVersion": __version__, "date": _date(date),
                                "version": document.version})
    relations = ET.SubElement(root, "relations")
    for relation in document.relations:
        element = ET.SubElement(relations, "relation", {"id": str(relation.id),
                                                        "type": relation.type})
        for role, ref, hint in relation.refs:
            ET.SubElement(element, "ref", {"hint": hint, "id": str(ref), "role": role})
    components = ET.SubElement(root, "components")
    for component in document.components.values():
        _xml_component(components, component, component.attributes)
    spectrum = ET.SubElement(root, "load_spectrum", {"id": "1"})
    for number, case in enumerate(document.load_cases, 1):
        element = ET.SubElement(spectrum, "load_case", {"id": str(number)})
        for ident, attributes in case.items():
            _xml_component(element, document.components[ident], attributes)
    ET.indent(root)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(root, "unicode") + "\n"


def _xml_component(parent: ET.Element, component: RexsComponent, attributes: dict) -> None:
    element = ET.SubElement(parent, "component", {"id": str(component.id),
                                                  "name": component.name,
                                                  "type": component.type})
    for key, (value, unit) in attributes.items():
        attribute = ET.SubElement(element, "attribute", {"id": key, "unit": unit})
        if isinstance(value, (list, tuple)):
            array = ET.SubElement(attribute, "array")
            for item in value:
                ET.SubElement(array, "c").text = _text(item)
        else:
            attribute.text = _text(value)


def to_json(document: RexsDocument, date: str | None = None) -> str:
    """The document as REXS JSON text."""
    def attributes(items: dict) -> list[dict]:
        return [{"id": key, "unit": unit, _json_kind(value): value}
                for key, (value, unit) in items.items()]

    model = {
        "version": document.version, "applicationId": _APPLICATION,
        "applicationVersion": __version__, "date": _date(date),
        "relations": [{"id": r.id, "type": r.type,
                       "refs": [{"hint": hint, "id": ref, "role": role}
                                for role, ref, hint in r.refs]} for r in document.relations],
        "components": [{"id": c.id, "name": c.name, "type": c.type,
                        "attributes": attributes(c.attributes)}
                       for c in document.components.values()],
        "load_spectrum": {"id": 1, "load_cases": [
            {"id": number, "components": [
                {"id": ident, "name": document.components[ident].name,
                 "type": document.components[ident].type,
                 "attributes": attributes(values)} for ident, values in case.items()]}
            for number, case in enumerate(document.load_cases, 1)]}}
    return json.dumps({"model": model}, indent=2, allow_nan=False) + "\n"


def _json_kind(value: Any) -> str:
    if isinstance(value, bool):
        return "boolean"
    if isinstance(value, int):
        return "integer"
    if isinstance(value, float):
        return "floating_point"
    if isinstance(value, (list, tuple)):
        return "floating_point_array"
    return "string"
