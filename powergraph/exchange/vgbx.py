"""A train as a VECTO gearbox file (``.vgbx``) with one transmission loss map (``.vtlm``)
per gear (docs/exchange.md).

VECTO's gearbox file (JSON, ``FileVersion`` 6, the version VECTO 3 writes) lists the axle
gear first, then one entry per gear with its ``Ratio`` (input over output speed) and its
``LossMap``. Here:

- a train with modes gives one gear per forward mode (ratio > 0 in the gear table,
  :func:`powergraph.analyses.gear_table.gear_table`), in the order of its modes table;
  a train without modes one gear, the size of its ratio (an external pair's −2 is 2);
- the **axle gear** is the mesh link named ``axle`` or ``final drive`` (its ``name``,
  any case), a fixed-axis pair with one gear on the output's rigid body: its ratio is
  its tooth ratio, its loss map that pair's alone, and the gears' maps are those of the
  train with the output moved to the axle's pinion. A train without such a link gets an
  axle of ratio 1 and no loss (all its losses are in the gears' maps);
- every loss map is :meth:`~powergraph.analyses.efficiency_map.EfficiencyMap.loss_map`
  over both quadrants (driving and coasting), by default at 8 input speeds from a
  quarter to twice the model's input speed and 9 input torques from −2 to +2 times its
  input torque at its own operating point.

Examples
--------
>>> from powergraph.model import load_model
>>> gearbox = vgbx_export(load_model("models/planetary_2kh_two_stages.yaml"), "p")
>>> [(round(g["Ratio"], 6), g["LossMap"]) for g in gearbox.document["Body"]["Gears"]]
[(1.0, 'p_axle.vtlm'), (20.0, 'p_gear.vtlm')]
"""
from __future__ import annotations

from datetime import datetime, timezone
from typing import Any

import numpy as np

from powergraph import __version__
from powergraph.analyses.efficiency_map import efficiency_map
from powergraph.analyses.efficiency_map_report import LOSS_MAP_HEADER, loss_map_text
from powergraph.analyses.gear_table import gear_table
from powergraph.errors import UsageError
from powergraph.model import model_from_dict
from powergraph.model.spec import Model
from powergraph.records import record
from powergraph.statics.case import TrainCase
from powergraph.units_si import RAD_S_PER_RPM

#: The gearbox file version VECTO 3 writes (its JSONFileWriter's GearboxFormatVersion).
FILE_VERSION = 6
#: Link names that mark the axle gear.
AXLE_NAMES = ("axle", "final drive")


@record
class VgbxExport:
    """The ``.vgbx`` JSON ``document`` and its loss maps ``{file name: .vtlm text}``
    (the axle's first), the file names relative to the ``.vgbx``."""

    document: dict[str, Any]
    maps: dict[str, str]


def vgbx_export(model: Model, stem: str, speeds_rpm: np.ndarray | None = None,
                input_torques: np.ndarray | None = None) -> VgbxExport:
    """The gearbox file of ``model``, its loss maps named ``STEM_axle.vtlm``,
    ``STEM_gear_MODE.vtlm``; ``speeds_rpm`` (input) and ``input_torques`` (N·m) set the
    maps' grid (defaults above)."""
    axle = _axle(model)
    gearbox = model if axle is None else model.with_port(model.outputs[0].index,
                                                         component=axle[1])
    modes = _forward_modes(gearbox)
    point = TrainCase.of(gearbox, modes[0][0]).point().required().result
    speed, torque = _input_point(point)
    speeds = speeds_rpm if speeds_rpm is not None else np.linspace(0.25, 2.0, 8) * speed
    torques = (input_torques if input_torques is not None
               else np.linspace(-2.0, 2.0, 9) * abs(torque))
    if not np.any(torques):
        raise UsageError("the model's input carries no torque: give the maps' input "
                         "torques (--torque)")
    gears = [{"Ratio": 1.0 if axle is None else axle[3], "LossMap": _name(stem, "axle")}]
    maps = {gears[0]["LossMap"]: lossless(speeds, torques) if axle is None else
            loss_map_text(efficiency_map(axle[2], torques * axle[3], speeds))}
    for mode, ratio in modes:
        name = _name(stem, "gear" if mode is None else f"gear_{mode}")
        maps[name] = loss_map_text(efficiency_map(gearbox, torques * ratio, speeds, mode=mode))
        gears.append({"Ratio": ratio, "LossMap": name, "ShiftPolygon": "<NOFILE>",
                      "FullLoadCurve": "<NOFILE>"})
    document = {
        "Header": {"CreatedBy": f"powergraph {__version__}",
                   "Date": datetime.now(timezone.utc).isoformat(timespec="seconds"),
                   "AppVersion": "3", "FileVersion": FILE_VERSION},
        "Body": {"SavedInDeclMode": False, "ModelName": model.name, "Inertia": 0.0,
                 "TracInt": 1.0, "GearboxType": "AMT", "Gears": gears}}
    return VgbxExport(document, maps)


def _name(stem: str, part: str) -> str:
    safe = "".join(ch if ch.isalnum() or ch in "-_." else "_" for ch in part)
    return f"{stem}_{safe}.vtlm"


def _forward_modes(model: Model) -> list[tuple[str | None, float]]:
    if not model.modes:
        result = TrainCase.of(model).point().required().result
        if not result.ratio:
            raise UsageError("the train has no ratio (its output stands still or is free)")
        return [(None, abs(float(result.ratio)))]   # VECTO's ratio: a speed ratio, unsigned
    rows = [(row.mode, row.ratio) for row in gear_table(model).rows
            if row.ratio is not None and row.ratio > 0]
    if not rows:
        raise UsageError("the train has no forward mode (a mode of ratio > 0)")
    return rows


def _input_point(result) -> tuple[float, float]:
    port = next(p for p in result.ports if p.role == "input")
    return abs(port.speed) / RAD_S_PER_RPM, port.torque


def _axle(model: Model) -> tuple[Any, str, Model, float] | None:
    """The axle link, its pinion (the gear off the output's body), the pair as a model of
    its own and its ratio; None when no mesh is named as the axle."""
    links = [l for l in model.links if l.type == "mesh"
             and (l.name or "").strip().lower() in AXLE_NAMES]
    if not links:
        return None
    link = links[0]
    output = model.body_of[model.outputs[0].component]
    on_output = [c for c in link.between if model.body_of[c] == output]
    if len(links) > 1 or len(on_output) != 1 or link.carrier != model.frame or \
            any(model.components[c].teeth is None for c in link.between):
        raise UsageError(f"links[{link.index}]: the axle gear must be the one fixed-axis pair "
                         "named 'axle' with teeth on both gears and one on the output's body")
    wheel = on_output[0]
    pinion = next(c for c in link.between if c != wheel)
    z = {c: model.components[c].teeth for c in link.between}
    internal = any(model.components[c].internal for c in link.between)
    pair = model_from_dict({
        "name": f"{model.name}: axle", "components": {
            "frame": {"role": "frame"}, "pinion": {"teeth": z[pinion]},
            "wheel": {"teeth": z[wheel], "internal": internal}},
        "links": [{"type": "mesh", "between": ["pinion", "wheel"],
                   "efficiency": link.efficiency}],
        "ports": [{"component": "pinion", "role": "input"},
                  {"component": "wheel", "role": "output"}]})
    return link, pinion, pair, z[wheel] / z[pinion]


def lossless(speeds_rpm: np.ndarray, input_torques: np.ndarray) -> str:
    """A loss map of no loss at every point (the axle of a train without one).

    >>> print(lossless(np.array([1000.0]), np.array([-10.0, 10.0])), end="")
    Input Speed [rpm],Input Torque [Nm],Torque Loss [Nm]
    1000,-10,0
    1000,10,0
    """
    rows = [f"{n:.10g},{t:.10g},0" for n in speeds_rpm for t in input_torques]
    return "\n".join([LOSS_MAP_HEADER] + rows) + "\n"
