"""Building blocks of the model's JSON Schema: the limits of model numbers and the helpers
that write a field's schema (:mod:`powergraph.model.schema` assembles them)."""
from __future__ import annotations

from dataclasses import fields
from typing import Any

#: The lower bound of a geometry length (block_geometry's fields say which).
POSITIVE, NON_NEGATIVE = "positive", "non-negative"

#: Largest magnitudes accepted, so that products of model numbers stay finite.
MAX_SPEED = 1e6        # rad/s (about 10^7 rpm)
MAX_POWER = 1e12       # W
MAX_TORQUE = 1e12      # N·m
#: The largest port values (SI) and their units, as the schema bounds them in files.
PORT_RANGES = {"speed": (MAX_SPEED, "rad/s"), "power": (MAX_POWER, "W"),
               "torque": (MAX_TORQUE, "N*m")}
MAX_LENGTH = 1e6       # mm
MAX_TEETH = 100_000
MAX_COUNT = 10_000
MIN_RATIO, MAX_RATIO = 1e-6, 1e6
#: Smallest efficiency of a machine (a number or a map's value), as ``--mesh-efficiency``'s:
#: below it the power a machine draws, P/η, leaves the range the solve can balance.
MIN_MACHINE_EFFICIENCY = 1e-6
LINK_TYPES = ("mesh", "fixed", "coupling", "bearing", "seal", "clutch", "brake", "freewheel")
_UNIT_TEXT = r"^\s*[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?\s*\S.*$"
_SI = {"speed": "rad/s", "power": "W", "torque": "N·m", "length": "mm",
       "kinematic viscosity": "m²/s", "density": "kg/m³", "area": "m²",
       "heat transfer coefficient": "W/(m²·K)", "temperature": "K", "volume": "m³"}


def _ref(name: str, **annotations: Any) -> dict:
    return {"$ref": f"#/$defs/{name}", **annotations}


def _number(title: str, description: str, **bounds: Any) -> dict:
    return {"type": "number", "title": title, "description": description, **bounds}


def _integer(title: str, description: str, minimum: int, maximum: int, **extra: Any) -> dict:
    return {"type": "integer", "title": title, "description": description,
            "minimum": minimum, "maximum": maximum, **extra}


def _quantity(kind: str, title: str, description: str, **bounds: Any) -> dict:
    """A number in SI units (mm for a length) or a string with units (``"1500 rpm"``)."""
    unit = _SI[kind]
    return {"title": title,
            "description": f"{description} A number in {unit}, or a string with units.",
            "x-quantity": kind,
            "anyOf": [{"type": "number", **bounds},
                      {"type": "string", "pattern": _UNIT_TEXT,
                       "description": f"a number and a {kind} unit"}],
            **({"examples": _EXAMPLES[kind]} if kind in _EXAMPLES else {})}


_EXAMPLES = {"speed": ["1500 rpm", 157.08], "power": ["2.27 kW", 1000],
             "torque": ["120 N*m", 12.5], "length": ["12 mm", 1.5],
             "kinematic viscosity": ["32 cSt"], "density": ["870 kg/m^3"],
             "area": ["0.3 m^2"], "heat transfer coefficient": ["18 W/(m^2*K)"],
             "temperature": ["80 degC", 353.15], "volume": ["1.5 L"]}


def _text(title: str, description: str) -> dict:
    return {"type": ["string", "number", "null"], "title": title,
            "description": description}


def _length(title: str, description: str, non_negative: bool = False) -> dict:
    low = {"minimum": 0} if non_negative else {"exclusiveMinimum": 0}
    return _quantity("length", title, description, maximum=MAX_LENGTH, **low)


def _geometry_shape(cls: type) -> dict:
    """Schema of one geometry shape, from its dataclass fields' metadata."""
    properties: dict[str, Any] = {"shape": {"const": cls.shape, "title": "shape",
                                            "description": cls.__doc__.splitlines()[0]}}
    for spec in fields(cls):
        meta = spec.metadata
        symbol = f" (paper symbol {meta['symbol']})" if meta["symbol"] else ""
        text = f"{meta['doc'][0].upper()}{meta['doc'][1:]}{symbol}."
        if meta["kind"] == "length":
            properties[spec.name] = _length(spec.name, text, meta["min"] == NON_NEGATIVE)
        elif meta["kind"] == "count":
            properties[spec.name] = _integer(spec.name, text, meta["min"], 1000)
        else:
            properties[spec.name] = _ref("componentId", title=spec.name, description=text)
    names = [f.name for f in fields(cls)]
    gear = cls.shape == "gear"
    return {"type": "object", "title": f"geometry of shape {cls.shape}",
            "description": (cls.__doc__.splitlines()[0]
                            + (" `shape` may be left out on a component with teeth."
                               if gear else "")),
            "properties": properties, "additionalProperties": False,
            "required": names if gear else ["shape", *names]}


def _link(kind: str, description: str, extra: dict) -> dict:
    properties = {
        "type": {"const": kind, "title": "link type", "description": description},
        "between": {"type": "array", "title": "between",
                    "description": "The two components the link joins.",
                    "items": _ref("componentId"), "minItems": 2, "maxItems": 2,
                    "x-expect": "a list of two component ids"},
        **extra,
        "name": _text("name", "A label for reports."),
        "note": _text("note", "Free text, ignored by the analyses."),
    }
    return {"type": "object", "title": f"{kind} link", "description": description,
            "properties": properties, "additionalProperties": False,
            "required": ["type", "between"]}


_EFFICIENCY = {"type": "number", "exclusiveMinimum": 0, "maximum": 1}
_MACHINE_EFFICIENCY = {"type": "number", "minimum": MIN_MACHINE_EFFICIENCY, "maximum": 1}
