"""A REXS file read into plain records: its components with their typed attributes, its
relations, and the load cases of its load spectrum (docs/exchange.md).

REXS (the Reusable Engineering EXchange Standard of the FVA) comes as XML (``.rexs``: a
``<model version=...>`` root holding ``<relations>``, ``<components>`` and an optional
``<load_spectrum>``) or as JSON (``.rexsj``: ``{"model": {...}}`` with the same parts, each
attribute's value under the key of its type, e.g. ``floating_point``). Both are read into
the one :class:`RexsDocument`; what the values mean is :mod:`powergraph.model.rexs_reader`'s.

The file is read in bounded memory like a YAML model (its size limit, ``--max-model-size``).
XML is parsed by the standard library; a document type declaration (the door to entity
expansion) is refused before parsing.

Examples
--------
>>> doc = parse_rexs(b'<model version="1.4"><relations/><components>'
...                  b'<component id="1" name="Shaft" type="shaft">'
...                  b'<attribute id="defines_speed" unit="none">true</attribute>'
...                  b'</component></components></model>', "unit.rexs")
>>> doc.version, doc.components[1].type, doc.components[1].attributes["defines_speed"]
('1.4', 'shaft', ('true', 'none'))
"""
from __future__ import annotations

import json
import xml.etree.ElementTree as ET
from dataclasses import field
from typing import Any

from powergraph.errors import ModelError
from powergraph.records import record

#: Every relation type of the REXS standard (versions 1.3 to 1.6); another is an error.
RELATION_TYPES = frozenset({
    "assembly", "ordered_assembly", "stage", "stage_gear_data", "side", "coupling", "flank",
    "reference", "ordered_reference", "planet_shaft", "central_shaft", "planet_carrier_shaft",
    "planet_pin", "connection", "manufacturing_step"})
#: The keys a JSON attribute may give its value under.
_JSON_VALUE_KEYS = ("floating_point", "integer", "boolean", "string", "enum",
                    "reference_component", "file_reference", "floating_point_array",
                    "integer_array", "boolean_array", "string_array", "enum_array",
                    "floating_point_matrix", "integer_matrix", "boolean_matrix",
                    "string_matrix", "array_of_integer_arrays", "value")


@record
class RexsComponent:
    """One component: its integer ``id``, ``type`` (``shaft``, ``cylindrical_gear``…),
    ``name`` and ``attributes`` ``{attribute id: (value, unit)}`` (an XML value is its
    text, an array a list of texts; a JSON value keeps its JSON type)."""

    id: int
    type: str
    name: str
    attributes: dict[str, tuple[Any, str]] = field(default_factory=dict)


@record
class RexsRelation:
    """One relation: ``id``, ``type`` and its ``refs`` as ``(role, component id, hint)``."""

    id: int
    type: str
    refs: tuple[tuple[str, int, str], ...]

    def role(self, role: str) -> int | None:
        """The component id under ``role`` (the first), or None."""
        return next((ref for name, ref, _ in self.refs if name == role), None)


@record
class RexsDocument:
    """A REXS file: ``version``, ``components`` by id, ``relations`` in file order,
    ``load_cases`` (each ``{component id: {attribute id: (value, unit)}}``), ``source``."""

    version: str
    components: dict[int, RexsComponent]
    relations: tuple[RexsRelation, ...]
    load_cases: tuple[dict[int, dict[str, tuple[Any, str]]], ...]
    source: str


def parse_rexs(data: bytes, source: str) -> RexsDocument:
    """Read the bytes of a ``.rexs`` (XML) or ``.rexsj`` (JSON) file: JSON when the text
    starts with ``{``, XML otherwise. A file that is neither, or not REXS, is a
    :class:`~powergraph.errors.ModelError` naming it."""
    text = data.lstrip(b"\xef\xbb\xbf \t\r\n")
    document = _from_json(text, source) if text[:1] == b"{" else _from_xml(text, source)
    _check_relations(document)
    return document


def _integer(text: Any, what: str, source: str) -> int:
    try:
        value = int(text)
    except (TypeError, ValueError):
        raise ModelError(f"{what}: id {text!r} is not an integer", source) from None
    if isinstance(text, float) or isinstance(text, bool):
        raise ModelError(f"{what}: id {text!r} is not an integer", source)
    return value


def _from_xml(data: bytes, source: str) -> RexsDocument:
    head = data[:4096].upper()
    if b"<!DOCTYPE" in head or b"<!ENTITY" in data.upper():
        raise ModelError("a REXS file has no document type or entity declarations; refused",
                         source)
    try:
        root = ET.fromstring(data)
    except ET.ParseError as exc:
        line, column = exc.position
        raise ModelError(f"not well-formed XML (line {line}, column {column + 1})",
                         source) from None
    if root.tag != "model" or "version" not in root.attrib:
        raise ModelError(f"not a REXS file: the root element is <{root.tag}>, expected "
                         "<model version=...>", source)
    components = {}
    for element in root.findall("./components/component"):
        component = _xml_component(element, "component", source)
        if component.id in components:
            raise ModelError(f"component {component.id} is defined twice", source)
        components[component.id] = component
    relations = []
    for element in root.findall("./relations/relation"):
        what = f"relation {element.get('id')}"
        refs = tuple((ref.get("role", ""), _integer(ref.get("id"), what, source),
                      ref.get("hint", "")) for ref in element.findall("ref"))
        relations.append(RexsRelation(_integer(element.get("id"), what, source),
                                      element.get("type", ""), refs))
    cases = []
    for case in root.findall("./load_spectrum/load_case"):
        entries = [_xml_component(c, f"load case {case.get('id')}", source)
                   for c in case.findall("component")]
        cases.append({c.id: c.attributes for c in entries})
    return RexsDocument(root.get("version", ""), components, tuple(relations), tuple(cases),
                        source)


def _xml_component(element: ET.Element, what: str, source: str) -> RexsComponent:
    ident = _integer(element.get("id"), what, source)
    attributes = {}
    for attribute in element.findall("attribute"):
        name = attribute.get("id", "")
        if name in attributes:
            raise ModelError(f"{what} {ident}: attribute {name!r} given twice", source)
        array = attribute.find("array")
        matrix = attribute.find("matrix")
        if array is not None:
            value: Any = [(c.text or "").strip() for c in array.findall("c")]
        elif matrix is not None:
            value = [[(c.text or "").strip() for c in row.findall("c")]
                     for row in matrix.findall("r")]
        else:
            value = (attribute.text or "").strip()
        attributes[name] = (value, attribute.get("unit", ""))
    return RexsComponent(ident, element.get("type", ""), element.get("name", ""), attributes)


def _from_json(data: bytes, source: str) -> RexsDocument:
    def unique(pairs):
        out = dict(pairs)
        if len(out) < len(pairs):
            seen: set = set()
            repeated = next(k for k, _ in pairs if k in seen or seen.add(k))
            raise ModelError(f"JSON key {repeated!r} given twice in one object", source)
        return out

    try:
        top = json.loads(data.decode("utf-8"), object_pairs_hook=unique)
    except (UnicodeDecodeError, json.JSONDecodeError, RecursionError) as exc:
        where = (f" (line {exc.lineno}, column {exc.colno})"
                 if isinstance(exc, json.JSONDecodeError) else "")
        raise ModelError(f"not valid JSON{where}", source) from None
    except ModelError:
        raise
    except ValueError:         # an integer of more digits than Python converts
        raise ModelError("not valid JSON: a number of thousands of digits", source) from None
    model = top.get("model") if isinstance(top, dict) else None
    if not isinstance(model, dict) or "version" not in model:
        raise ModelError("not a REXS file: expected a JSON object {\"model\": {\"version\": "
                         "..., \"components\": [...], \"relations\": [...]}}", source)
    components = {}
    for raw in _list(model, "components", source):
        component = _json_component(raw, "component", source)
        if component.id in components:
            raise ModelError(f"component {component.id} is defined twice", source)
        components[component.id] = component
    relations = []
    for raw in _list(model, "relations", source):
        what = f"relation {raw.get('id') if isinstance(raw, dict) else raw!r}"
        if not isinstance(raw, dict):
            raise ModelError(f"{what}: expected an object", source)
        refs = tuple((str(ref.get("role", "")), _integer(ref.get("id"), what, source),
                      str(ref.get("hint", ""))) for ref in _list(raw, "refs", source))
        relations.append(RexsRelation(_integer(raw.get("id"), what, source),
                                      str(raw.get("type", "")), refs))
    spectrum = model.get("load_spectrum") or {}
    cases = []
    for case in _list(spectrum, "load_cases", source) if isinstance(spectrum, dict) else ():
        entries = [_json_component(c, f"load case {case.get('id')}", source)
                   for c in _list(case, "components", source)]
        cases.append({c.id: c.attributes for c in entries})
    return RexsDocument(str(model["version"]), components, tuple(relations), tuple(cases),
                        source)


def _list(raw: Any, key: str, source: str) -> list:
    value = raw.get(key, []) if isinstance(raw, dict) else None
    if not isinstance(value, list):
        raise ModelError(f"{key}: expected a list", source)
    return value


def _json_component(raw: Any, what: str, source: str) -> RexsComponent:
    if not isinstance(raw, dict):
        raise ModelError(f"{what}: expected an object, got {type(raw).__name__}", source)
    ident = _integer(raw.get("id"), what, source)
    attributes = {}
    for attribute in _list(raw, "attributes", source):
        name = str(attribute.get("id", "")) if isinstance(attribute, dict) else ""
        if name in attributes or not name:
            raise ModelError(f"{what} {ident}: attribute {name!r} missing or given twice",
                             source)
        value = next((attribute[k] for k in _JSON_VALUE_KEYS if k in attribute), "")
        attributes[name] = (value, str(attribute.get("unit", "")))
    return RexsComponent(ident, str(raw.get("type", "")), str(raw.get("name", "")),
                         attributes)


def _check_relations(document: RexsDocument) -> None:
    for relation in document.relations:
        if relation.type not in RELATION_TYPES:
            raise ModelError(f"relation {relation.id}: unknown relation type "
                             f"{relation.type!r}", document.source)
        for role, ref, _ in relation.refs:
            if ref not in document.components:
                raise ModelError(f"relation {relation.id} ({relation.type}): {role} refers to "
                                 f"component {ref}, which is not in the file", document.source)
    for index, case in enumerate(document.load_cases):
        missing = next((ident for ident in case if ident not in document.components), None)
        if missing is not None:
            raise ModelError(f"load case {index + 1}: component {missing} is not in the file",
                             document.source)
