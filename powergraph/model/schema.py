"""The model file format, described once as a JSON Schema (draft 2020-12).

This is the single description of what a model file may contain: every field, its type,
range, default and meaning. :func:`powergraph.model.conform.conform` checks documents
against it (with the project's one-line messages) and ``powergraph schema`` prints it for
editors. What a schema cannot say (references between components, exactly one frame,
rigid bodies, the block-specific geometry rules) is checked in code by
:mod:`powergraph.model.validate` and the ``block_*`` modules. The format is explained in
docs/format.md.

Two annotations beyond JSON Schema, which editors ignore:

- ``x-quantity``: a physical quantity (``speed``, ``power``, ``torque``, ``length``): a
  number in SI units (mm for lengths) or a string with units; the range of the number
  branch applies after conversion.
- ``x-expect``: how a message words the expectation (``ratio must be a non-zero number...``).

Examples
--------
>>> MODEL_SCHEMA["$schema"]
'https://json-schema.org/draft/2020-12/schema'
>>> sorted(MODEL_SCHEMA["required"])
['components', 'links', 'name', 'ports']
"""
from __future__ import annotations

from dataclasses import fields
from typing import Any

from powergraph.model.block_geometry import NON_NEGATIVE, SHAPES

#: Largest magnitudes accepted, so that products of model numbers stay finite.
MAX_SPEED = 1e6        # rad/s (about 10^7 rpm)
MAX_POWER = 1e12       # W
MAX_TORQUE = 1e12      # N·m
MAX_LENGTH = 1e6       # mm
MAX_TEETH = 100_000
MAX_COUNT = 10_000
MIN_RATIO, MAX_RATIO = 1e-6, 1e6
LINK_TYPES = ("mesh", "fixed", "coupling", "bearing")
_UNIT_TEXT = r"^\s*[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?\s*\S.*$"
_SI = {"speed": "rad/s", "power": "W", "torque": "N·m", "length": "mm"}


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
             "torque": ["120 N*m", 12.5], "length": ["12 mm", 1.5]}


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

_MESH = {
    "carrier": _ref("componentId", title="carrier",
                    description="The member on which both gear axes are fixed (the arm of a "
                                "planetary). Default: the frame (a fixed-axis pair)."),
    "efficiency": {**_EFFICIENCY, "title": "efficiency",
                   "description": "Basic efficiency of the mesh with its carrier held, in "
                                  "(0, 1]. Default: defaults.mesh_efficiency, else 1 (ideal)."},
    "ratio": {"type": "number", "title": "ratio",
              "description": "Willis ratio (w_a - w_c)/(w_b - w_c) of the pair, for meshes "
                             "whose gears have no teeth (bevel gears...). Default: "
                             "-z_b/z_a for two external gears, +z_b/z_a with an internal one.",
              "anyOf": [{"minimum": MIN_RATIO, "maximum": MAX_RATIO},
                        {"minimum": -MAX_RATIO, "maximum": -MIN_RATIO}],
              "x-expect": f"a non-zero number of magnitude between {MIN_RATIO:g} and "
                          f"{MAX_RATIO:g}"},
    "backlash_arcmin": _number("backlash_arcmin",
                               "Angular play of the first gear with the second held, in the "
                               "carrier's frame, in arc-minutes (docs/backlash.md).",
                               minimum=0, maximum=21600),
    "backlash": _ref("backlash"),
    "cycloid": _ref("cycloid"),
    "friction": _ref("friction"),
    "geometry": _ref("meshGeometry"),
    "pins": _ref("pins"),
    "output_pins": _ref("outputPins"),
    "crank_bearing": _ref("crankBearing"),
}

_FRICTION = {
    "title": "mesh friction",
    "description": "The friction law that sets the mesh's basic efficiency 1 - mu*H_V, with "
                   "H_V from the mesh's geometry (docs/losses.md). Replaces efficiency.",
    "oneOf": [
        {"type": "object", "title": "constant coefficient",
         "description": "A constant mean coefficient of friction.",
         "properties": {"model": {"const": "constant", "default": "constant",
                                  "title": "model",
                                  "description": "constant (the default): a given mu."},
                        "mu": {"type": "number", "minimum": 0, "exclusiveMaximum": 1,
                               "title": "mu", "description": "Mean coefficient of friction "
                                                             "in the mesh, in [0, 1)."}},
         "additionalProperties": False, "required": ["mu"]},
        {"type": "object", "title": "ISO/TR 14179-2",
         "description": "Mean coefficient from the tooth load and speed (Schlenk's fit); "
                        "needs geometry.face_width.",
         "properties": {
             "model": {"const": "iso14179", "title": "model",
                       "description": "iso14179: the coefficient of ISO/TR 14179-2."},
             "viscosity": {"title": "viscosity",
                           "description": "Dynamic viscosity of the oil at its working "
                                          "temperature: mPa*s, or a string with units.",
                           "anyOf": [{"type": "number", "exclusiveMinimum": 0,
                                      "maximum": 1e6},
                                     {"type": "string", "pattern": _UNIT_TEXT}]},
             "roughness": {"title": "roughness",
                           "description": "Mean arithmetic roughness Ra of the flanks: "
                                          "micrometres, or a string with units.",
                           "anyOf": [{"type": "number", "exclusiveMinimum": 0,
                                      "maximum": 1000},
                                     {"type": "string", "pattern": _UNIT_TEXT}]},
             "lubricant_factor": {"type": "number", "exclusiveMinimum": 0, "maximum": 10,
                                  "default": 1, "title": "lubricant_factor",
                                  "description": "X_L: 1 for mineral oil."}},
         "additionalProperties": False, "required": ["model", "viscosity", "roughness"]},
    ],
}

_MU = {"type": "number", "minimum": 0, "exclusiveMaximum": 1, "title": "mu"}
_ROLLING = {"type": "boolean", "default": False, "title": "rolling"}

_PINS = {
    "type": "object", "title": "cycloid pins",
    "description": "Friction at the pin ring of a cycloid mesh (disc of z_c lobes, internal "
                   "ring of z_c + 1 pins): sets the mesh's basic efficiency from the "
                   "equal-load pin forces (docs/losses.md). Replaces efficiency. radius, "
                   "circle_radius and eccentricity may come from the mesh's cycloid block or "
                   "the disc's cycloid_disc geometry instead.",
    "properties": {
        "mu": {**_MU, "description": "Friction coefficient: at the contact with the disc "
                                     "(fixed pins) or at the pin's seat (rolling pins)."},
        "rolling": {**_ROLLING, "description": "true: the pins roll on the disc and turn in "
                                               "their seats (or on needle bearings)."},
        "radius": _length("radius", "Pin radius r_p."),
        "circle_radius": _length("circle_radius", "Radius R_p of the pin-centre circle."),
        "eccentricity": _length("eccentricity", "Crank eccentricity e."),
        "seat_radius": _length("seat_radius", "Rolling pins: radius on which the friction "
                                              "acts (default: the pin radius)."),
    },
    "additionalProperties": False,
    "required": ["mu"],
}

_OUTPUT_PINS = {
    "type": "object", "title": "output pins",
    "description": "A W output mechanism of a cycloid mesh with a pins block: pins in holes "
                   "(pin radius + e) of the disc; its friction is folded into the mesh's "
                   "efficiency (docs/losses.md).",
    "properties": {
        "count": _integer("count", "Number of output pins.", 2, 1000),
        "circle_radius": _length("circle_radius", "Radius R_w of the output pins' circle."),
        "mu": {**_MU, "description": "Friction coefficient of a pin in its hole (or of a "
                                     "rolling sleeve on its pin)."},
        "rolling": {**_ROLLING, "description": "true: rolling sleeves (needs radius and "
                                               "seat_radius)."},
        "radius": _length("radius", "Outer radius of a rolling sleeve."),
        "seat_radius": _length("seat_radius", "Radius on which a rolling sleeve turns."),
    },
    "additionalProperties": False,
    "required": ["count", "circle_radius", "mu"],
}

_CRANK_BEARING = {
    "type": "object", "title": "crank bearing",
    "description": "The disc's bearing on its eccentric, for a cycloid mesh with a pins "
                   "block; its friction is folded into the mesh's efficiency "
                   "(docs/losses.md).",
    "properties": {
        "mu": {**_MU, "description": "Bearing friction coefficient referred to the bore "
                                     "(e.g. about 0.002 for needle roller bearings)."},
        "bore_radius": _length("bore_radius", "Bore radius of the bearing (friction "
                                              "radius)."),
        "crank_circle_radius": {**_length("crank_circle_radius",
                                          "0 for one central crank; else the radius of the "
                                          "circle of the cranks that carry the disc (an RV "
                                          "reducer).", non_negative=True), "default": 0},
    },
    "additionalProperties": False,
    "required": ["mu", "bore_radius"],
}

_MESH_GEOMETRY = {
    "type": "object", "title": "mesh geometry",
    "description": "Involute geometry of the pair, used by its friction block "
                   "(docs/losses.md). The pinion is the external gear of an internal pair, "
                   "the link's first gear otherwise.",
    "properties": {
        "module": _length("module", "Normal module."),
        "face_width": _length("face_width", "Face width (needed by friction model "
                                            "iso14179)."),
        "pressure_angle": {"type": "number", "exclusiveMinimum": 0, "maximum": 45,
                           "default": 20, "title": "pressure_angle",
                           "description": "Normal pressure angle, degrees."},
        "helix_angle": {"type": "number", "minimum": -60, "maximum": 60, "default": 0,
                        "title": "helix_angle", "description": "Helix angle, degrees."},
        "shifts": {"type": "array", "items": {"type": "number", "minimum": -2, "maximum": 2},
                   "minItems": 2, "maxItems": 2, "default": [0, 0], "title": "shifts",
                   "description": "Profile shift coefficients (pinion, wheel).",
                   "x-expect": "a list of two numbers (pinion, wheel)"},
        "addendum": {"type": "number", "exclusiveMinimum": 0, "maximum": 2, "default": 1,
                     "title": "addendum", "description": "Addendum coefficient h_a*."},
    },
    "additionalProperties": False,
    "required": ["module"],
}

_TOLERANCES = {
    "type": "object", "title": "tolerances",
    "description": "PATH -> distribution of a toleranced value, for `powergraph tolerance` "
                   "(docs/tolerance.md): {distribution: uniform, min, max}, {distribution: "
                   "normal, mean, sd[, low, high]}, {nominal, tolerance} or an ISO grade.",
    "additionalProperties": {"type": "object", "title": "distribution",
                             "description": "One toleranced value's distribution "
                                            "(docs/tolerance.md)."},
}

_PER_GEAR_LENGTH = {"type": "object", "x-expect": "a mapping {gear id: value} over the "
                                                  "mesh's two gears"}

_BACKLASH = {
    "type": "object", "title": "backlash measurements",
    "description": "Over-pin measurements of an internal involute pair (Li et al. 2012), "
                   "from which the backlash analysis computes profile shifts and lost motion "
                   "(docs/backlash.md). Keys of the per-gear mappings are the mesh's two "
                   "gear ids.",
    "properties": {
        "module": _length("module", "Module of the pair."),
        "pressure_angle": {"type": "number", "exclusiveMinimum": 0, "exclusiveMaximum": 45,
                           "default": 20, "title": "pressure_angle",
                           "description": "Pressure angle in degrees."},
        "pin_diameter": _length("pin_diameter", "Diameter of the measuring pins."),
        "standard_M": {**_PER_GEAR_LENGTH, "title": "standard_M",
                       "description": "Nominal over-pin distance M of each gear.",
                       "additionalProperties": _length("M", "Over-pin distance.")},
        "measured_M": {**_PER_GEAR_LENGTH, "title": "measured_M",
                       "description": "Measured over-pin distances of each gear (one value "
                                      "or a non-empty list).",
                       "additionalProperties": {
                           "anyOf": [_length("M", "Over-pin distance."),
                                     {"type": "array", "minItems": 1,
                                      "items": _length("M", "Over-pin distance.")}],
                           "x-expect": "an over-pin distance or a non-empty list of them"}},
        "runout": {**_PER_GEAR_LENGTH, "title": "runout",
                   "description": "Radial runout F_r of each gear. Default 0.",
                   "additionalProperties": _length("F_r", "Radial runout.", True)},
        "bearing_clearance": {"title": "bearing_clearance",
                              "description": "Radial clearance u_r of each bearing (one "
                                             "value or a non-empty list). Default: none.",
                              "anyOf": [_length("u_r", "Clearance.", True),
                                        {"type": "array", "minItems": 1,
                                         "items": _length("u_r", "Clearance.", True)}],
                              "x-expect": "a clearance or a non-empty list of them"},
        "assembly": {"enum": ["standard", "compensated"], "default": "standard",
                     "title": "assembly",
                     "description": "standard centre distance, or compensated (eccentric "
                                    "at a'')."},
    },
    "additionalProperties": False,
    "required": ["module", "pin_diameter", "standard_M", "measured_M"],
}

_CYCLOID = {
    "type": "object", "title": "cycloid stage",
    "description": "Ratio-fluctuation data of a cycloid-disc / pin-ring mesh (Csobán 2021; "
                   "docs/cycloid.md). The mesh pairs a disc (z1 >= 3 teeth) with an internal "
                   "pin ring of z1 + 1 pins.",
    "properties": {
        "module": _length("module", "Pin circle radius m*z2/2, pin radius rc*m."),
        "profile_error": _length("profile_error", "Disc profile moved inward along its "
                                 "normal (d).", True),
        "shift": {"type": "number", "exclusiveMinimum": 0, "exclusiveMaximum": 1,
                  "default": 0.3, "title": "shift",
                  "description": "x: eccentricity (1 - x)*m/2."},
        "rc": {"type": "number", "exclusiveMinimum": 0, "maximum": 100, "default": 1,
               "title": "rc", "description": "Pin-radius factor."},
    },
    "additionalProperties": False,
    "required": ["module", "profile_error"],
}

_COMPONENT = {
    "type": ["object", "null"], "title": "component",
    "description": "A numbered part: a gear, a shaft, a carrier, the housing.",
    "properties": {
        "role": {"enum": ["frame"], "title": "role",
                 "description": "frame for the housing (exactly one component); absent "
                                "otherwise."},
        "name": _text("name", "A label for reports."),
        "kind": _text("kind", "What the part is (sun, planet, carrier...), for reports."),
        "teeth": _integer("teeth", "Number of teeth (pins of a pin ring).", 1, MAX_TEETH),
        "internal": {"type": "boolean", "default": False, "title": "internal",
                     "description": "true for an internal (ring) gear."},
        "count": _integer("count", "Identical parts in parallel (planets): losses and "
                          "volumes count each.", 1, MAX_COUNT, default=1),
        "geometry": _ref("geometry"),
        "drag": _ref("drag", description="The body's no-load drag against the frame (seals, "
                                         "churning; docs/losses.md)."),
        "note": _text("note", "Free text, ignored by the analyses."),
    },
    "additionalProperties": False,
}

_TORQUE_0 = {"minimum": 0, "maximum": MAX_TORQUE}
_DRAG = {
    "type": "object", "title": "no-load drag",
    "description": "Load-independent drag torque per instance, opposing the relative "
                   "rotation: no_load_torque, or a + b*|n| with n the relative speed in rpm "
                   "(docs/losses.md).",
    "properties": {
        "no_load_torque": _quantity("torque", "no_load_torque", "Constant drag torque.",
                                    **_TORQUE_0),
        "a": _quantity("torque", "a", "Constant part of the drag. Default 0.", **_TORQUE_0),
        "b": _quantity("torque", "b", "Drag per rpm of relative speed. Default 0.",
                       **_TORQUE_0)},
    "additionalProperties": False, "minProperties": 1,
}
_BEARING_FRICTION = {
    "type": "object", "title": "bearing friction",
    "description": "Load-dependent friction torque M = mu*F*bore/2 per bearing, F the "
                   "radial load from the carried member's tooth forces (docs/losses.md).",
    "properties": {
        "mu": {"type": "number", "minimum": 0, "maximum": 1, "title": "mu",
               "description": "Constant friction coefficient of the bearing, in [0, 1]."},
        "bore": _length("bore", "Bore diameter of the bearing.", True)},
    "additionalProperties": False, "required": ["mu", "bore"],
}

_PORT = {
    "type": "object", "title": "port",
    "description": "Where power enters (input) or leaves (output) the train. A train with "
                   "P ports and D degrees of freedom takes D speeds and the power or torque "
                   "of P - D ports.",
    "properties": {
        "component": _ref("componentId", title="component",
                          description="The component the port is on (not the frame)."),
        "role": {"enum": ["input", "output"], "title": "role",
                 "description": "input: power fed in; output: power taken out."},
        "speed": _quantity("speed", "speed", "Speed of the component.",
                           minimum=-MAX_SPEED, maximum=MAX_SPEED),
        "power": _quantity("power", "power", "Power fed in (input) or taken out (output).",
                           minimum=-MAX_POWER, maximum=MAX_POWER),
        "torque": _quantity("torque", "torque", "External torque on the component.",
                            minimum=-MAX_TORQUE, maximum=MAX_TORQUE),
        "name": _text("name", "A label for reports."),
    },
    "additionalProperties": False,
    "required": ["component", "role"],
}

MODEL_SCHEMA: dict[str, Any] = {
    "$schema": "https://json-schema.org/draft/2020-12/schema",
    "title": "powergraph model",
    "description": "A gear train as a graph: components (nodes), links (edges) and ports. "
                   "See docs/format.md.",
    "type": "object",
    "properties": {
        "name": {"type": ["string", "number"], "pattern": r"\S", "title": "name",
                 "description": "Name of the train.", "x-expect": "non-empty text"},
        "description": _text("description", "Source, closed form, remarks."),
        "defaults": {"type": ["object", "null"], "title": "defaults",
                     "description": "Values used where a link gives none.",
                     "properties": {"mesh_efficiency": {
                         **_EFFICIENCY, "default": 1, "title": "mesh_efficiency",
                         "description": "Basic efficiency of every mesh without its own "
                                        "efficiency, in (0, 1]."}},
                     "additionalProperties": False},
        "components": {"type": "object", "title": "components", "minProperties": 1,
                       "description": "{id: component}; ids are integers or strings and "
                                      "compare as strings.",
                       "additionalProperties": _ref("component")},
        "links": {"type": "array", "title": "links", "items": _ref("link"),
                  "description": "The edges: meshes, fixed joints, couplings, bearings."},
        "ports": {"type": "array", "title": "ports", "items": _ref("port"),
                  "description": "At least one input and one output."},
        "tolerances": _TOLERANCES,
    },
    "additionalProperties": False,
    "required": ["name", "components", "links", "ports"],
    "$defs": {
        "componentId": {"type": ["integer", "string"], "minLength": 1,
                        "title": "component id",
                        "description": "A key of components (an integer or a string)."},
        "component": _COMPONENT,
        "geometry": {"title": "geometry",
                     "description": "Dimensions for the volume formulas of Pan & Wang "
                                    "(2019), by shape (docs/volume.md). Lengths in mm.",
                     "oneOf": [_geometry_shape(cls) for cls in SHAPES.values()]},
        "link": {"title": "link", "description": "An edge of the graph, by its type.",
                 "oneOf": [
                     _link("mesh", "Two gears in mesh, their axes fixed on the carrier.",
                           _MESH),
                     _link("fixed", "Two components joined rigidly (one body).", {}),
                     _link("coupling", "A shaft coupling: equal speeds, may have an "
                           "efficiency (the loss reacts on the frame).",
                           {"efficiency": {**_EFFICIENCY, "default": 1,
                                           "title": "efficiency",
                                           "description": "Efficiency in (0, 1]. Default "
                                                          "1."}}),
                     _link("bearing", "Records which member carries which (between: [planet, "
                           "carrier]); sets no speed; passes no power unless it has "
                           "friction or drag (docs/losses.md).",
                           {"friction": _ref("bearingFriction"), "drag": _ref("drag")}),
                 ]},
        "backlash": _BACKLASH,
        "cycloid": _CYCLOID,
        "friction": _FRICTION,
        "bearingFriction": _BEARING_FRICTION,
        "drag": _DRAG,
        "meshGeometry": _MESH_GEOMETRY,
        "pins": _PINS,
        "outputPins": _OUTPUT_PINS,
        "crankBearing": _CRANK_BEARING,
        "port": _PORT,
    },
}


def definition(name: str) -> dict:
    """The schema of ``$defs/name`` (``"geometry"``, ``"link"``...).

    >>> definition("cycloid")["required"]
    ['module', 'profile_error']
    """
    return MODEL_SCHEMA["$defs"][name]
