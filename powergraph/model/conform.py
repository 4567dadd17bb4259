"""Check plain data against :data:`powergraph.model.schema.MODEL_SCHEMA`, one message per error.

A small interpreter of the part of JSON Schema the model format uses (``type``,
``properties``, ``required``, ``additionalProperties``, ``enum``, ``const``, ranges,
``minItems``/``maxItems``, ``minLength``, ``pattern``, ``anyOf``, ``oneOf`` and ``$ref``),
plus the ``x-quantity`` and ``x-expect`` annotations. It stops at the first error and
raises a :class:`~powergraph.errors.ModelError` naming the place (``links[2].efficiency``)
in the project's wording. It is a fast path with no import cost (``powergraph solve``
starts quickly); the test-suite checks that it agrees with the ``jsonschema`` package.

``oneOf`` is used only with a discriminator: a property that is ``const`` in every branch
(``type`` of a link, ``shape`` of a geometry); a branch that does not require it is the
default when it is absent.

Examples
--------
>>> conform({"module": 1, "profile_error": -1}, definition("cycloid"), "links[0].cycloid")
Traceback (most recent call last):
...
powergraph.errors.ModelError: links[0].cycloid.profile_error: must be >= 0 mm, got -1
"""
from __future__ import annotations

import math
import re
from typing import Any, Callable

from powergraph.errors import ModelError
from powergraph.model.schema import definition, document_schema
from powergraph.model.schema_parts import _EFFICIENCY
from powergraph.model.units import SI_UNITS, parse_quantity
from powergraph.model.yaml_loader import brief, join_path

__all__ = ["check_efficiency", "conform", "definition"]

_JSON_TYPES = {"object": dict, "array": list, "string": str, "boolean": bool}


def conform(value: Any, schema: dict, path: str = "") -> None:
    """Raise :class:`ModelError` at the first place where ``value`` breaks ``schema``.

    Parameters
    ----------
    value : Any
        Plain data as read from YAML.
    schema : dict
        :data:`MODEL_SCHEMA` or one of its definitions.
    path : str
        Place of ``value`` in the model file.
    """
    _checker(schema)(value, path)


def _checker(schema: dict) -> Callable[[Any, str], None]:
    """The check of ``schema``, compiled once into a closure (cached by identity); a
    ``$ref`` is compiled when a document first reaches it."""
    hit = _CHECKERS.get(id(schema))
    if hit is not None and hit[0] is schema:
        return hit[1]
    check = _later(schema) if "$ref" in schema else _compile(schema)
    _CHECKERS[id(schema)] = (schema, check)
    return check


_CHECKERS: dict[int, tuple[dict, Callable[[Any, str], None]]] = {}


def _later(schema: dict) -> Callable[[Any, str], None]:
    """The check of a ``$ref``, compiled on its first use."""
    compiled: list = []

    def check(value: Any, path: str) -> None:
        if not compiled:
            compiled.append(_compile(_resolve(schema)))
        compiled[0](value, path)

    return check


def _compile(schema: dict) -> Callable[[Any, str], None]:
    if "x-quantity" in schema:
        return lambda value, path: _quantity(value, schema, path)
    if "oneOf" in schema:
        return _one_of_checker(schema)
    if "anyOf" in schema and not _ranges_only(schema):
        return lambda value, path: _any_of(value, schema, path)
    types = schema.get("type")
    obj = _object_checker(schema) if "properties" in schema or \
        "additionalProperties" in schema else None
    arr = _array_checker(schema) if types == "array" else None
    text = "minLength" in schema or "pattern" in schema
    ranged = "anyOf" in schema or bool(_RANGE_KEYS & set(schema))
    integer, enum = types == "integer", schema.get("enum")

    def check(value: Any, path: str) -> None:
        if types is not None and not _is_type(value, types):
            raise _expected(value, schema, path)
        if isinstance(value, dict):
            if obj is not None:
                obj(value, path)
        elif isinstance(value, list):
            if arr is not None:
                arr(value, path)
        elif isinstance(value, str):
            if text and (len(value) < schema.get("minLength", 0) or (
                    "pattern" in schema and not re.search(schema["pattern"], value))):
                raise _expected(value, schema, path)
        elif isinstance(value, (int, float)) and not isinstance(value, bool):
            if integer and ranged and not _in_range(value, schema):
                raise _expected(value, schema, path)
            if (ranged or isinstance(value, float)):
                _number(value, schema, path)
        if enum is not None and value not in enum:
            raise _expected(value, schema, path)

    return check


def _resolve(schema: dict) -> dict:
    """The schema a ``$ref`` points to (with the referring node's own annotations)."""
    while "$ref" in schema:
        target = definition(schema["$ref"].rsplit("/", 1)[1])
        extra = {k: v for k, v in schema.items() if k != "$ref"}
        schema = {**target, **extra} if extra else target
    return schema


def _is_type(value: Any, types: str | list) -> bool:
    for name in ([types] if isinstance(types, str) else types):
        if name == "null":
            if value is None:
                return True
        elif name in ("number", "integer"):
            if isinstance(value, bool):
                continue
            if isinstance(value, int) or (name == "number" and isinstance(value, float)):
                return True
        elif isinstance(value, _JSON_TYPES[name]):
            return True
    return False


def _name(path: str) -> str:
    """The last key of ``path`` (``links[0].efficiency`` -> ``efficiency``)."""
    return re.sub(r"\[\d+\]$", "", path).rsplit(".", 1)[-1]


def _expected(value: Any, schema: dict, path: str) -> ModelError:
    if schema.get("type") == "object" or schema.get("type") == ["object", "null"]:
        if not isinstance(value, dict):
            expect = schema.get("x-expect", "a mapping")
            return ModelError(f"must be {expect}, got {type(value).__name__}", path)
    return ModelError(f"{_name(path)} must be {_phrase(schema)}, got {brief(value)}", path)


def _phrase(schema: dict) -> str:
    """What a value of ``schema`` must be, in words."""
    if "x-expect" in schema:
        return schema["x-expect"]
    if "enum" in schema:
        return " or ".join(repr(v) for v in schema["enum"])
    kind = schema.get("type")
    if kind == "integer":
        low, high = schema.get("minimum"), schema.get("maximum")
        text = f"{'a positive' if low == 1 else 'an'} integer >= {low}"
        return text + (f" and <= {high}" if high is not None else "")
    if kind == "number":
        return f"a number {_range(schema)}".rstrip()
    if kind == ["integer", "string"]:
        return "a component id (an integer or a non-empty string)"
    if kind == "array":
        return f"a list of at least {schema.get('minItems', 0)} item(s)"
    if kind == "boolean":
        return "true or false"
    return "text" if "string" in (kind or ()) else "valid"


def _range(schema: dict, unit: str = "", value: float | None = None) -> str:
    """``in (0, 1]`` for a short interval, else the bound ``value`` breaks (``> 0 mm``)."""
    low = schema.get("exclusiveMinimum", schema.get("minimum"))
    high = schema.get("exclusiveMaximum", schema.get("maximum"))
    open_low, open_high = "exclusiveMinimum" in schema, "exclusiveMaximum" in schema
    if low is not None and high is not None and high - low <= 1000:
        return (f"in {'(' if open_low else '['}{low:g}, {high:g}{')' if open_high else ']'}"
                + unit)
    parts = []
    if low is not None and (value is None or value <= low):
        parts.append(f"{'>' if open_low else '>='} {low:g}{unit}")
    if high is not None and (value is None or value >= high):
        parts.append(f"{'<' if open_high else '<='} {high:g}{unit}")
    return " and ".join(parts)


def _number(value: float, schema: dict, path: str, unit: str | None = None,
            shown: Any = None) -> None:
    shown = value if shown is None else shown
    if isinstance(value, float) and not math.isfinite(value):
        raise ModelError(f"must be finite, got {brief(shown)}", path)
    if not _in_range(value, schema):
        if "x-expect" in schema:
            raise ModelError(f"{_name(path)} must be {schema['x-expect']}, got {brief(shown)}",
                             path)
        prefix = "" if unit is not None else f"{_name(path)} "
        unit = unit or ""
        raise ModelError(f"{prefix}must be {_range(schema, unit, value)}, got {brief(shown)}",
                         path)


def _in_range(value: float, schema: dict) -> bool:
    if "anyOf" in schema and not any(_in_range(value, s) for s in schema["anyOf"]):
        return False
    return (value >= schema.get("minimum", -math.inf)
            and value > schema.get("exclusiveMinimum", -math.inf)
            and value <= schema.get("maximum", math.inf)
            and value < schema.get("exclusiveMaximum", math.inf))


def _quantity(value: Any, schema: dict, path: str) -> None:
    kind = schema["x-quantity"]
    number = parse_quantity(value, kind, path)  # type errors, units, finiteness
    _number(number, schema["anyOf"][0], path, " " + SI_UNITS[kind], shown=value)


def _ranges_only(schema: dict) -> bool:
    """An ``anyOf`` of numeric ranges (checked by :func:`_number`), not of alternatives."""
    return all(set(branch) <= _RANGE_KEYS for branch in schema["anyOf"])


_RANGE_KEYS = {"minimum", "maximum", "exclusiveMinimum", "exclusiveMaximum"}


def _any_of(value: Any, schema: dict, path: str) -> None:
    """Conform to the first alternative of the value's kind (list, or a single value)."""
    for branch in schema["anyOf"]:
        branch = _resolve(branch)
        if ("x-quantity" in branch and not isinstance(value, (list, dict))) \
                or _is_type(value, branch.get("type", [])):
            conform(value, branch, path)
            return
    raise _expected(value, schema, path)


def _object_checker(schema: dict) -> Callable[[dict, str], None]:
    properties = {key: _checker(sub) for key, sub in schema.get("properties", {}).items()}
    extra = schema.get("additionalProperties", True)
    extra_check = _checker(extra) if isinstance(extra, dict) else None
    allowed = ", ".join(sorted(properties))
    required, least = tuple(schema.get("required", ())), schema.get("minProperties", 0)

    def check(value: dict, path: str) -> None:
        for key, item in value.items():
            sub = properties.get(key) if isinstance(key, str) else None
            if sub is not None:
                sub(item, f"{path}.{key}" if path else key)
            elif extra_check is not None:
                extra_check(item, f"{path}.{key}" if path else str(key))
            elif extra is False:
                raise ModelError(_unknown(key, allowed), join_path(path, key))
        for key in required:
            if key not in value:
                raise ModelError(_missing(schema, key), join_path(path, key))
        if len(value) < least:
            raise ModelError(f"must have at least {least} entry", path)

    return check


def _unknown(key: Any, allowed: str) -> str:
    """``unknown field (allowed: ...)``; for a key YAML 1.1 read as a boolean (``off:``,
    ``on:``, ``yes:``, ``no:``), why.

    >>> _unknown(False, "buses, engage, inactive, ports")
    'unknown field: a key read as the boolean false (YAML 1.1 reads off, on, yes, no, true \
and false unquoted as booleans; ports that carry nothing in a mode are listed under \
inactive) (allowed: buses, engage, inactive, ports)'
    """
    if not isinstance(key, bool):
        return f"unknown field (allowed: {allowed})"
    hint = ("; ports that carry nothing in a mode are listed under inactive"
            if "inactive" in allowed.split(", ") else "")
    return (f"unknown field: a key read as the boolean {str(key).lower()} (YAML 1.1 reads "
            f"off, on, yes, no, true and false unquoted as booleans{hint}) (allowed: "
            f"{allowed})")


def _missing(schema: dict, key: str) -> str:
    described = _resolve(schema["properties"][key]).get("description", "")
    needs = ", ".join(schema["required"])
    return f"missing (needed here: {needs})" + (f"; {key}: {described}" if described else "")


def _array_checker(schema: dict) -> Callable[[list, str], None]:
    low, high = schema.get("minItems", 0), schema.get("maxItems", math.inf)
    items = _checker(schema["items"]) if "items" in schema else None

    def check(value: list, path: str) -> None:
        if not low <= len(value) <= high:
            raise _expected(value, schema, path)
        if items is not None:
            for index, item in enumerate(value):
                items(item, f"{path}[{index}]")

    return check


def _one_of_checker(schema: dict) -> Callable[[Any, str], None]:
    """A ``oneOf`` dispatched on its discriminator: the property that is ``const`` in every
    branch; a branch that does not require it is the default when it is absent."""
    branches = [_resolve(b) for b in schema["oneOf"]]
    name = next(k for k, v in branches[0]["properties"].items() if "const" in v)
    table = {b["properties"][name]["const"]: _checker(b) for b in branches}
    default = next((_checker(b) for b in branches if name not in b.get("required", ())),
                   None)
    allowed = ", ".join(str(k) for k in table)
    title = branches[0]["properties"][name].get("title", name)

    def check(value: Any, path: str) -> None:
        if not isinstance(value, dict):
            raise ModelError(f"must be a mapping, got {type(value).__name__}", path)
        if name not in value:
            if default is None:
                raise ModelError(f"missing (one of {allowed})", join_path(path, name))
            default(value, path)
            return
        branch = table.get(value[name]) if _hashable(value[name]) else None
        if branch is None:
            raise ModelError(f"unknown {title} {brief(value[name])} (allowed: {allowed})",
                             join_path(path, name))
        branch(value, path)

    return check


def _hashable(value: Any) -> bool:
    try:
        hash(value)
    except TypeError:
        return False
    return True


def check_efficiency(value: Any, path: str) -> float:
    """A basic efficiency must be a number in (0, 1] (the schema's efficiency).

    Parameters
    ----------
    value : Any
        The value as given (``--mesh-efficiency``, ``Model.with_mesh_efficiency``).
    path : str
        Where it was given, for the message.

    Returns
    -------
    float

    Examples
    --------
    >>> check_efficiency(0.94, "x")
    0.94
    """
    conform(value, _EFFICIENCY, path)
    return float(value)


def check_document(data: Any, source: str | None = None) -> None:
    """Check a whole model document (a mapping) against :data:`MODEL_SCHEMA`."""
    if not isinstance(data, dict):
        raise ModelError("a model must be a mapping with name, components, links and ports; "
                         f"got {type(data).__name__}", source)
    conform(data, document_schema(), "")
