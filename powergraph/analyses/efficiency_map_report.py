"""The text and JSON of an efficiency map (:class:`~powergraph.analyses.efficiency_map.
EfficiencyMap`): works on the map it is given, computes nothing.

Columns are output torques (coasting ones, < 0, first when the span runs upwards), each
labelled with its side; rows input speeds; cells the efficiency in %.
"""
from __future__ import annotations

import math
from typing import Any

import numpy as np

from powergraph.format import aligned_table, format_fixed, format_number
from powergraph.statics.verdicts import MEANINGS

#: The names of the map's sides by the sign of the output torque.
SIDE_NAMES = {-1: "coasting", 0: "no load", 1: "driving"}
COASTING_NOTE = ("torque < 0: coasting, the output drives the train; efficiency = power "
                 "leaving at the input / power entering at the output")
NO_LOAD_NOTE = ("torque 0: no load, the efficiency is undefined (nan); the loss map "
                "carries the drag there")
SELF_LOCKING = ("efficiency 0, no power comes out; coasting, the output cannot drive the "
                "train and the input must drive too")


def map_notes(result: "EfficiencyMap") -> list[str]:
    """What the reader needs to read the map's sides: the coasting side's efficiency and
    the no-load column's (each only when the map has it)."""
    sides = set(result.sides.tolist())
    return [note for side, note in ((-1, COASTING_NOTE), (0, NO_LOAD_NOTE)) if side in sides]


def map_dict(result: "EfficiencyMap") -> dict[str, Any]:
    """``{name, torques, speeds_rpm, efficiency (rows by speed; null where undefined),
    sides (per torque: coasting, no load, driving), rated_torque, load_dependent,
    self_locking, locked, unconverged, no_freewheel_state, notes}``; ``self_locking`` and
    ``locked`` list the ``[speed rpm, torque]`` points under load with that verdict."""
    values = [[None if math.isnan(e) else e for e in row] for row in result.efficiency.tolist()]
    return {"name": result.name, "torques": result.torques.tolist(),
            "speeds_rpm": result.speeds_rpm.tolist(), "efficiency": values,
            "sides": [SIDE_NAMES[s] for s in result.sides.tolist()],
            "rated_torque": result.rated_torque, "load_dependent": result.load_dependent,
            "self_locking": [list(p) for p in result.points_with("self-locking")],
            "locked": [list(p) for p in result.points_with("locked")],
            "unconverged": [list(p) for p in result.unconverged],
            "no_freewheel_state": [list(p) for p in result.no_freewheel_state],
            "notes": map_notes(result)}


def map_text(result: "EfficiencyMap") -> str:
    """The map as a table, efficiencies in %, its sides labelled, with the notes and the
    points that have no efficiency or no power out."""
    flat = "" if result.load_dependent else (
        ": constant mesh efficiencies and no drag, so it does not vary with load or speed"
        + (" on either side" if np.any(result.sides < 0) else ""))
    lines = [f"{result.name} — efficiency map (%){flat}"]
    cells = []
    if np.any(result.sides <= 0):
        cells.append(["side", *(SIDE_NAMES[s] for s in result.sides.tolist())])
    cells.append(["speed rpm \\ torque N·m", *(format_number(t, 4) for t in result.torques)])
    cells += [[format_number(speed, 5), *(format_fixed(100 * e, 3) for e in row)]
              for speed, row in zip(result.speeds_rpm, result.efficiency)]
    lines += aligned_table(cells, set(range(len(cells[0]))), rules_after=())
    lines += map_notes(result)
    for verdict, meaning in (("self-locking", SELF_LOCKING), ("locked", MEANINGS["locked"])):
        points = result.points_with(verdict)
        if points:
            lines.append(f"{len(points)} point(s) {verdict} ({meaning}): "
                         f"{_by_torque(points, len(result.speeds_rpm))}")
    for points, what in ((result.unconverged, "did not converge"),
                         (result.no_freewheel_state, "have no consistent freewheel state")):
        if points:
            lines.append(f"{len(points)} point(s) {what} (nan): {_points(points)}")
    return "\n".join(lines)


def _points(points) -> str:
    return ", ".join(f"{n:g} rpm {t:g} N·m" for n, t in points)


def _by_torque(points, speeds: int, most: int = 12) -> str:
    """``points`` by torque column: ``-400 N·m (every speed), -100 N·m (300, 1200 rpm)``,
    at most ``most`` columns named.

    >>> _by_torque([(300.0, -400.0), (900.0, -400.0), (300.0, -100.0)], 2)
    '-400 N·m (every speed), -100 N·m (300 rpm)'
    """
    columns: dict[float, list[float]] = {}
    for speed, torque in points:
        columns.setdefault(torque, []).append(speed)
    named = [f"{t:g} N·m (" + ("every speed" if len(s) == speeds else
                                ", ".join(f"{n:g}" for n in s) + " rpm") + ")"
             for t, s in list(columns.items())[:most]]
    more = len(columns) - most
    return ", ".join(named) + (f" and {more} more torque(s)" if more > 0 else "")


#: The loss map's columns, as VECTO's transmission loss maps (.vtlm) name them.
LOSS_MAP_HEADER = "Input Speed [rpm],Input Torque [Nm],Torque Loss [Nm]"


def loss_map_text(result: "EfficiencyMap") -> str:
    """The map's points (:meth:`EfficiencyMap.loss_map`) as the text of a VECTO
    transmission loss map (``.vtlm``): the header, then one line per point."""
    rows = result.loss_map()
    lines = [LOSS_MAP_HEADER] + [f"{n:.10g},{t:.10g},{loss:.10g}" for n, t, loss in
                                 zip(rows["speed_rpm"], rows["input_torque"],
                                     rows["torque_loss"])]
    return "\n".join(lines) + "\n"
