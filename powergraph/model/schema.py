"""The model file format, described once as a JSON Schema (draft 2020-12).

This is the single description of what a model file may contain: every field, its type,
range, default and meaning. :func:`powergraph.model.conform.conform` checks documents
against it (with the project's one-line messages) and ``powergraph schema`` prints it for
editors. What a schema cannot say (references between components, exactly one frame,
rigid bodies, the block-specific geometry rules) is checked in code by
:mod:`powergraph.model.validate` and the ``block_*`` modules. The format is explained in
docs/format.md.

The whole schema is :data:`MODEL_SCHEMA` (or :func:`model_schema`); the checks read it
through :func:`document_schema` and :func:`definition`, which write the ``geometry``
definition (from the shapes' own fields) only when a model has a geometry block.

Two annotations beyond JSON Schema, which editors ignore:

- ``x-quantity``: a physical quantity (``speed``, ``power``, ``torque``, ``length``): a
  number in SI units (mm for lengths) or a string with units; the range of the number
  branch applies after conversion.
- ``x-expect``: how a message words the expectation (``ratio must be a non-zero number...``).

Examples
--------
>>> model_schema()["$schema"]
'https://json-schema.org/draft/2020-12/schema'
>>> sorted(model_schema()["required"])
['components', 'links', 'name', 'ports']
"""
from __future__ import annotations

from typing import Any

from powergraph.model.schema_losses import (_BEARING_FRICTION, _CRANK_BEARING, _DRAG,
                                            _CHURNING, _LUBRICANT, _SKF, _THERMAL,
                                            _FRICTION, _MESH_GEOMETRY, _OUTPUT_PINS, _PINS)
from powergraph.model.schema_parts import (MAX_COUNT, MAX_POWER, MAX_RATIO, MAX_SPEED,
                                           MAX_TEETH, MAX_TORQUE, MIN_RATIO, _EFFICIENCY,
                                           _MACHINE_EFFICIENCY, _geometry_shape, _integer,
                                           _length, _link, _number, _quantity, _ref, _text)
from powergraph.model.schema_shift import MODES, SHIFT_LINKS

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
        "churning": _CHURNING,
        "note": _text("note", "Free text, ignored by the analyses."),
    },
    "additionalProperties": False,
}

_PORT = {
    "type": "object", "title": "port",
    "description": "Where power enters (input) or leaves (output) the train. A train with "
                   "P ports and D degrees of freedom takes D speeds and the power or torque "
                   "of P - D ports.",
    "properties": {
        "component": _ref("componentId", title="component",
                          description="The component the port is on (not the frame)."),
        "role": {"enum": ["input", "output", "machine"], "title": "role",
                 "description": "input: power fed in; output: power taken out; machine: an "
                                "electric machine on an electrical bus (docs/hybrid.md)."},
        "speed": _quantity("speed", "speed", "Speed of the component.",
                           minimum=-MAX_SPEED, maximum=MAX_SPEED),
        "power": _quantity("power", "power", "Power fed in (input) or taken out (output).",
                           minimum=-MAX_POWER, maximum=MAX_POWER),
        "torque": _quantity("torque", "torque", "External torque on the component.",
                            minimum=-MAX_TORQUE, maximum=MAX_TORQUE),
        "name": _text("name", "A label for reports, and the port's name in a duty cycle's "
                              "columns: unique among the ports, not another component's id."),
        "efficiency": {"title": "efficiency", "default": 1,
                       "description": "A machine's efficiency in [1e-6, 1]: electrical power "
                                      "P/efficiency when motoring, P*efficiency when "
                                      "generating; or {map: FILE.csv}, a table over speed "
                                      "and torque (docs/hybrid.md).",
                       "anyOf": [_MACHINE_EFFICIENCY, {
                           "type": "object", "title": "efficiency map",
                           "properties": {"map": {
                               "type": "string", "minLength": 1, "title": "map",
                               "description": "CSV file (relative to the model file): "
                                              "speed [rpm], torque [N·m], efficiency."}},
                           "required": ["map"], "additionalProperties": False}]},
        "bus": {"type": ["string", "number"], "title": "bus",
                "description": "A machine's electrical bus (a key of buses)."},
        "max_speed": _quantity("speed", "max_speed",
                               "A machine's top speed: a solve that turns it faster (in "
                               "either sense) warns (over-max-speed, docs/hybrid.md).",
                               exclusiveMinimum=0, maximum=MAX_SPEED),
    },
    "additionalProperties": False,
    "required": ["component", "role"],
}

_SCHEMA: dict[str, Any] = {
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
                  "description": "The edges: meshes, fixed joints, couplings, bearings, "
                                 "seals, clutches, brakes, freewheels."},
        "ports": {"type": "array", "title": "ports", "items": _ref("port"),
                  "description": "At least one input and one output."},
        "tolerances": _TOLERANCES,
        "lubricant": _LUBRICANT,
        "thermal": _THERMAL,
        "modes": MODES,
        "buses": {"type": "object", "title": "buses",
                  "description": "{name: bus}: electrical buses joining machine ports "
                                 "(docs/hybrid.md).",
                  "additionalProperties": {
                      "type": ["object", "null"], "title": "bus",
                      "properties": {"battery": {
                          "title": "battery",
                          "description": "The battery's power into the bus (W or a string "
                                         "with units), or free (omitted: free).",
                          "anyOf": [{"type": "number"}, {"type": "string"},
                                    {"type": "null"}]}},
                      "additionalProperties": False}},
    },
    "additionalProperties": False,
    "required": ["name", "components", "links", "ports"],
    "$defs": {
        "componentId": {"type": ["integer", "string"], "minLength": 1,
                        "title": "component id",
                        "description": "A key of components (an integer or a string)."},
        "component": _COMPONENT,
        "geometry": None,          # written on first use (_LATER)
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
                           {"friction": _ref("bearingFriction"), "drag": _ref("drag"),
                            "skf": _SKF}),
                     {**_link("seal", "A lip seal between two members: it loses "
                              "7.69e-6·d²·n W at n rpm of relative speed, d in mm "
                              "(ISO/TR 14179-2; docs/losses.md).",
                              {"diameter": _length("diameter", "Shaft diameter at the "
                                                               "seal's lip.")}),
                      "required": ["type", "between", "diameter"]},
                     *SHIFT_LINKS,
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


def _geometry() -> dict:
    """The ``geometry`` definition, written from the shapes' fields (their module is
    imported only when a model has a geometry block, or the whole schema is asked for)."""
    from powergraph.model.block_geometry import SHAPES

    return {"title": "geometry",
            "description": "Dimensions for the volume formulas of Pan & Wang (2019), by "
                           "shape (docs/volume.md). Lengths in mm.",
            "oneOf": [_geometry_shape(cls) for cls in SHAPES.values()]}


#: Definitions written on first use, by name.
_LATER = {"geometry": _geometry}


def definition(name: str) -> dict:
    """The schema of ``$defs/name`` (``"geometry"``, ``"link"``...).

    >>> definition("cycloid")["required"]
    ['module', 'profile_error']
    """
    defs = _SCHEMA["$defs"]
    if defs[name] is None:
        defs[name] = _LATER[name]()
    return defs[name]


def document_schema() -> dict:
    """The schema of a model document as the checks read it: its definitions are looked
    up (:func:`definition`) when a document uses them."""
    return _SCHEMA


def model_schema() -> dict:
    """The whole schema, every definition written out (``powergraph schema``,
    :data:`MODEL_SCHEMA`)."""
    for name in _LATER:
        definition(name)
    return _SCHEMA


def __getattr__(name: str) -> Any:
    if name == "MODEL_SCHEMA":     # the whole schema, as a module attribute
        return model_schema()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
