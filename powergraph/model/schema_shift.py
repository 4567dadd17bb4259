"""Schema pieces of the shift elements and the modes table (docs/modes.md): clutch, brake
and freewheel links and the top-level ``modes`` mapping, assembled into
:data:`powergraph.model.schema.MODEL_SCHEMA`.

Examples
--------
>>> sorted(SHIFT_LINKS[2]["properties"]["holds"]["enum"])
['negative', 'positive']
"""
from __future__ import annotations

from powergraph.model.schema_parts import _link, _ref, _text

_NAME = {**_text("name", "The element's name (unique), used by the modes table."),
         "type": ["string", "number"], "pattern": r"\S", "x-expect": "non-empty text"}
_ENGAGED = {"type": "boolean", "default": False, "title": "engaged",
            "description": "Its state when the model is solved without a mode. Default "
                           "false (open)."}
_DRAG = _ref("drag", title="drag",
             description="Drag torque while open, in the slip speed (docs/losses.md).")


def _shift(kind: str, description: str, extra: dict) -> dict:
    schema = _link(kind, description, {"name": _NAME, "drag": _DRAG, **extra})
    schema["required"] = ["type", "between", "name"]
    return schema


SHIFT_LINKS = [
    _shift("clutch", "A shift element joining two turning members: rigid when engaged, "
           "free (only its drag) when open (docs/modes.md).", {"engaged": _ENGAGED}),
    _shift("brake", "A clutch to the frame (between: [member, frame id]): holds the member "
           "when engaged (docs/modes.md).", {"engaged": _ENGAGED}),
    _shift("freewheel", "A one-way clutch: holds when w_a - w_b would take the sign it "
           "does not allow, overruns otherwise (docs/modes.md).",
           {"holds": {"enum": ["positive", "negative"], "title": "holds",
                      "description": "The sign of w_a - w_b the freewheel allows (it "
                                     "overruns with that sign and holds against the other): "
                                     "positive lets a turn forward relative to b only."}}),
]
for _schema in SHIFT_LINKS[-1:]:
    _schema["required"] = ["type", "between", "name", "holds"]

_ELEMENTS = {"type": "array", "title": "engaged elements",
             "items": {"type": ["string", "number"]},
             "x-expect": "a list of shift-element names"}
_NAMES = {"type": "array", "items": {"type": ["string", "number"]},
          "x-expect": "a list of port names"}


def _override(kind: str) -> dict:
    return {"title": kind, "anyOf": [{"type": "number"}, {"type": "string"}],
            "x-expect": f"a {kind} or free",
            "description": f"The port's {kind} in this mode, as in a port (a number in SI "
                           "units or a string with units), or free: the mode drops the "
                           f"model's {kind}."}


_MODE = {
    "type": "object", "title": "mode",
    "description": "A mode as an operating state: the elements it engages, the ports it "
                   "leaves inactive, and its operating point (docs/modes.md).",
    "x-expect": "a list of shift-element names, or a mapping (engage, inactive, ports, "
                "buses)",
    "properties": {
        "engage": {**_ELEMENTS, "title": "engage",
                   "description": "The clutches and brakes engaged in this mode (default "
                                  "none)."},
        "inactive": {**_NAMES, "title": "inactive",
                     "description": "Ports (by name or component id) that carry nothing in "
                                    "this mode: an engine off, an unpowered machine."},
        "ports": {"type": "object", "title": "ports",
                  "description": "{port name or component id: {speed, power, torque}}: the "
                                 "port's values in this mode, replacing the model's.",
                  "additionalProperties": {
                      "type": "object", "title": "port values",
                      "description": "speed, power or torque (at most one of power and "
                                     "torque), each a quantity or free.",
                      "properties": {k: _override(k) for k in ("speed", "power", "torque")},
                      "additionalProperties": False}},
        "buses": {"type": "object", "title": "buses",
                  "description": "{bus name: {battery}}: the bus's battery power in this "
                                 "mode (a power, or free), replacing the model's.",
                  "additionalProperties": {
                      "type": "object", "title": "bus", "required": ["battery"],
                      "properties": {"battery": {
                          "title": "battery", "anyOf": [{"type": "number"},
                                                        {"type": "string"}],
                          "description": "The battery's power into the bus in this mode "
                                         "(W or a string with units), or free."}},
                      "additionalProperties": False}},
    },
    "additionalProperties": False,
}

MODES = {
    "type": "object", "title": "modes",
    "description": "{mode name: [engaged clutch and brake names]} or {mode name: {engage, "
                   "inactive, ports, buses}}; freewheels decide for themselves "
                   "(docs/modes.md). Solve one with `powergraph solve --mode`.",
    "minProperties": 1,
    "additionalProperties": {"anyOf": [_ELEMENTS, _MODE],
                             "x-expect": "a list of shift-element names, or a mapping "
                                         "(engage, inactive, ports, buses)"},
}
