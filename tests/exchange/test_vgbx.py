"""VECTO gearbox files (powergraph.exchange.vgbx): the gears' ratios are the gear
table's, every loss map is a VECTO loss map, and a mesh named ``axle`` is the axle gear.

Hand derivation for the axle case: a pair 20 → 40 (η 0.98) then the axle pair 15 → 45
(η 0.97). The gearbox is the first pair alone (ratio 40/20 = 2), the axle 45/15 = 3. A
single pair of ratio i and efficiency η driving: T_out = T_in·η·i, so the torque loss
referred to the input is T_in − T_out/i = (1 − η)·T_in.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import powergraph as pg
from powergraph.analyses.gear_table import gear_table
from powergraph.exchange.vgbx import FILE_VERSION, vgbx_export

MODELS = Path(__file__).resolve().parents[2] / "models"
AXLE = {"name": "with axle", "components": {0: {"role": "frame"}, 1: {"teeth": 20},
                                            2: {"teeth": 40}, 3: {"teeth": 15},
                                            4: {"teeth": 45}},
        "links": [{"type": "mesh", "between": [1, 2], "efficiency": 0.98},
                  {"type": "fixed", "between": [2, 3]},
                  {"type": "mesh", "name": "axle", "between": [3, 4], "efficiency": 0.97}],
        "ports": [{"component": 1, "role": "input", "speed": "2000 rpm", "torque": 100},
                  {"component": 4, "role": "output"}]}


def _table(text: str) -> np.ndarray:
    lines = text.splitlines()
    assert lines[0] == "Input Speed [rpm],Input Torque [Nm],Torque Loss [Nm]"
    assert len(lines) >= 5                       # VECTO: at least four data lines
    return np.array([[float(x) for x in line.split(",")] for line in lines[1:]])


def test_gear_ratios_are_the_gear_tables() -> None:
    model = pg.load_model(MODELS / "simpson_3speed.yaml")
    export = vgbx_export(model, "simpson", np.array([1000.0, 2000.0]),
                         np.array([-50.0, 0.0, 50.0, 100.0]))
    gears = export.document["Body"]["Gears"]
    forward = [row.ratio for row in gear_table(model).rows if row.ratio and row.ratio > 0]
    assert [g["Ratio"] for g in gears[1:]] == pytest.approx(forward, rel=1e-12)
    assert gears[0]["Ratio"] == 1.0             # no mesh named axle: a 1 : 1 axle
    assert export.document["Header"]["FileVersion"] == FILE_VERSION
    for gear in gears:
        table = _table(export.maps[gear["LossMap"]])
        assert np.all(table[:, 2] >= 0.0)        # losses are positive


@pytest.mark.slow
def test_the_default_grid_covers_every_forward_gear() -> None:
    # 8 speeds × 9 input torques per gear, coasting points left out where a freewheel
    # overruns (first gear): every map keeps its driving side
    export = vgbx_export(pg.load_model(MODELS / "simpson_3speed.yaml"), "simpson")
    for gear in export.document["Body"]["Gears"][1:]:
        table = _table(export.maps[gear["LossMap"]])
        assert np.count_nonzero(table[:, 1] > 0) == 8 * 4


def test_a_train_without_modes_is_one_gear_with_both_quadrants() -> None:
    export = vgbx_export(pg.load_model(MODELS / "planetary_2kh_two_stages.yaml"), "p")
    gears = export.document["Body"]["Gears"]
    assert len(gears) == 2 and gears[1]["Ratio"] == pytest.approx(20.0, rel=1e-12)
    table = _table(export.maps[gears[1]["LossMap"]])
    assert (table[:, 1] < 0).any() and (table[:, 1] > 0).any()


def test_a_mesh_named_axle_is_the_axle_gear() -> None:
    export = vgbx_export(pg.model_from_dict(AXLE), "a")
    axle, gear = export.document["Body"]["Gears"]
    assert axle["Ratio"] == pytest.approx(3.0) and gear["Ratio"] == pytest.approx(2.0)
    for entry, eta in ((axle, 0.97), (gear, 0.98)):
        table = _table(export.maps[entry["LossMap"]])
        driving = table[table[:, 1] > 0]
        assert driving[:, 2] == pytest.approx((1 - eta) * driving[:, 1], rel=1e-9)
