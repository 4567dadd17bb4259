"""The schema of the loss blocks: a mesh's ``friction:``, ``geometry:``, ``pins:``,
``output_pins:`` and ``crank_bearing:``, a bearing's ``friction:`` and the ``drag:`` of a
bearing or a component (docs/losses.md, docs/format.md)."""
from __future__ import annotations

from powergraph.model.schema_parts import (MAX_TORQUE, _UNIT_TEXT, _integer, _length,
                                           _quantity)

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
                                          "temperature: mPa*s, or a string with units. "
                                          "Default: the model's lubricant at its "
                                          "temperature.",
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
         "additionalProperties": False, "required": ["model", "roughness"]},
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
                   "(docs/losses.md) and by the feasibility checks (working centre "
                   "distance, undercut; docs/feasibility.md); it may stand without "
                   "friction. The pinion is the external gear of an internal pair, the "
                   "link's first gear otherwise.",
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
        "centre_distance": _length("centre_distance",
                                   "Operating (working) centre distance of the pair as "
                                   "built. With shifts (or friction) it must be theirs; "
                                   "without, it fixes the pair's shift sum "
                                   "(docs/feasibility.md)."),
    },
    "additionalProperties": False,
    "required": ["module"],
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
                       **_TORQUE_0),
        "wet": {"type": "object", "title": "wet clutch drag",
                "description": "Laminar shear of the oil in each gap of an open wet clutch "
                               "or brake, T = faces·π·μ·|Δω|·(r_o⁴ − r_i⁴)/(2h), μ from "
                               "the model's lubricant at its temperature (docs/losses.md).",
                "properties": {
                    "faces": {"type": "integer", "minimum": 1, "maximum": 100,
                              "title": "faces", "description": "Number of oil gaps "
                                                               "(friction faces)."},
                    "inner_radius": _length("inner_radius", "Inner radius r_i of the "
                                                            "friction faces."),
                    "outer_radius": _length("outer_radius", "Outer radius r_o of the "
                                                            "friction faces."),
                    "clearance": _length("clearance", "Oil gap h per face.")},
                "additionalProperties": False,
                "required": ["faces", "inner_radius", "outer_radius", "clearance"]}},
    "additionalProperties": False, "minProperties": 1,
}
_TEMPERATURE = {"title": "temperature",
                "description": "A temperature: a number in K, or a string in K, degC or degF.",
                "anyOf": [{"type": "number", "exclusiveMinimum": 0},
                          {"type": "string", "maxLength": 64}],
                "examples": ["80 degC", 353.15]}
_SKF = {
    "type": "object", "title": "SKF bearing",
    "description": "A rolling bearing by SKF's four-component model: its frictional moment "
                   "at the radial load of the carried member's tooth forces, the relative "
                   "speed and the lubricant's viscosity (docs/losses.md).",
    "properties": {
        "series": {"type": ["string", "integer"], "title": "series",
                   "description": "Bearing series: 60, 62, 63, 64 (deep groove ball), "
                                  "NU 2, NU 3, NU 4 (cylindrical roller)."},
        "bore": _length("bore", "Bore diameter d."),
        "outside": _length("outside", "Outside diameter D."),
        "lubrication": {"enum": ["oil_bath", "oil_jet", "grease", "oil_air"],
                        "title": "lubrication", "description": "How it is lubricated "
                        "(the replenishment constant K_rs). Default oil_bath."}},
    "additionalProperties": False, "required": ["series", "bore", "outside"],
}
_CHURNING = {
    "type": "object", "title": "churning",
    "description": "The gear dips into the sump: its churning torque against the housing by "
                   "Changenet & Velex (2007), with the lubricant's viscosity and density "
                   "(docs/losses.md). Not for planets.",
    "properties": {
        "immersion": _length("immersion", "Depth of the pitch circle's lowest point below "
                                          "the oil level."),
        "oil_volume": _quantity("volume", "oil_volume", "Oil volume of the sump.",
                                exclusiveMinimum=0),
        "pitch_radius": _length("pitch_radius", "Pitch radius. Default: module x teeth / 2 "
                                                "of the gear's geometry."),
        "face_width": _length("face_width", "Face width. Default: the gear's "
                                            "geometry.face_width.")},
    "additionalProperties": False, "required": ["immersion", "oil_volume"],
}
_LUBRICANT = {
    "type": "object", "title": "lubricant",
    "description": "The oil: its viscosity at 40 and 100 degC (or an ISO VG grade), density "
                   "and temperature; every viscous law takes its viscosity from it "
                   "(docs/losses.md).",
    "properties": {
        "grade": {"type": ["string", "integer"], "title": "grade",
                  "description": "ISO VG grade (ISO VG 32 ... 680): viscosities and density "
                                 "of a typical mineral gear oil (docs/losses.md)."},
        "viscosity_40": _quantity("kinematic viscosity", "viscosity_40",
                                  "Kinematic viscosity at 40 degC.", exclusiveMinimum=0),
        "viscosity_100": _quantity("kinematic viscosity", "viscosity_100",
                                   "Kinematic viscosity at 100 degC.", exclusiveMinimum=0),
        "density": _quantity("density", "density", "Density (taken as constant).",
                             exclusiveMinimum=0),
        "temperature": {**_TEMPERATURE, "description": "The oil temperature the model runs "
                        "at, unless a thermal: block sets it. Default 40 degC."},
        "max_temperature": {**_TEMPERATURE, "description": "The oil's limit. Default "
                            "150 degC."}},
    "additionalProperties": False,
}
_THERMAL = {
    "type": "object", "title": "thermal",
    "description": "Heat balance: the oil temperature at which every loss equals "
                   "h·A·(T − T_ambient) plus a cooler's power (docs/losses.md).",
    "properties": {
        "ambient": {**_TEMPERATURE, "description": "Ambient temperature."},
        "heat_transfer": _quantity("heat transfer coefficient", "heat_transfer",
                                   "Heat transfer coefficient h of the housing.",
                                   exclusiveMinimum=0),
        "area": _quantity("area", "area", "The housing's heat-giving area A.",
                          exclusiveMinimum=0),
        "cooler": _quantity("power", "cooler", "Power a cooler takes away. Default 0.",
                            minimum=0)},
    "additionalProperties": False, "required": ["ambient", "heat_transfer", "area"],
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
