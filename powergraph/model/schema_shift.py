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

MODES = {
    "type": "object", "title": "modes",
    "description": "{mode name: [engaged clutch and brake names]}; freewheels decide for "
                   "themselves (docs/modes.md). Solve one with `powergraph solve --mode`.",
    "minProperties": 1,
    "additionalProperties": {"type": "array", "title": "engaged elements",
                             "items": {"type": ["string", "number"]},
                             "x-expect": "a list of shift-element names"},
}
