"""The gear table (powergraph.analyses.gear_table): steps and spread from the closed-form
ratios, coasting, element torques over the input torque."""
from __future__ import annotations

import math
from pathlib import Path

import pytest

from powergraph.analyses.gear_table import gear_table
from powergraph.model import load_model

MODELS = Path(__file__).resolve().parents[2] / "models"
# Ravigneaux 4-speed closed forms (models/ravigneaux_4speed.yaml): z_s1 30, z_s2 36, z_r 72.
RATIOS = {"1": 72 / 30, "2": 72 * 66 / (30 * 108), "3": 1.0, "4": 72 / 108, "R": -2.0}


def test_ravigneaux_steps_and_spread_follow_the_closed_forms() -> None:
    table = gear_table(load_model(MODELS / "ravigneaux_4speed.yaml"))
    assert [r.mode for r in table.rows] == list(RATIOS)
    assert [r.ratio for r in table.rows] == pytest.approx(list(RATIOS.values()), rel=1e-12)
    forward = ["1", "2", "3", "4"]
    steps = {m: RATIOS[m] / RATIOS[n] for m, n in zip(forward, forward[1:])}
    got = {r.mode: r.step for r in table.rows}
    assert got["4"] is None and got["R"] is None      # no next forward gear
    assert {m: got[m] for m in steps} == pytest.approx(steps, rel=1e-12)
    assert table.spread == pytest.approx(RATIOS["1"] / RATIOS["4"], rel=1e-12)
    # C1 passes the whole input torque in 1st and 2nd (it is the input's only path)
    assert table.rows[0].torques["C1"] == pytest.approx(-1.0, rel=1e-12)
    # direct drive: efficiency 1 both ways (a locked set has no loss)
    assert table.rows[2].efficiency == pytest.approx(1.0, rel=1e-12)
    assert table.rows[2].coast_efficiency == pytest.approx(1.0, rel=1e-12)


def test_simpson_first_gear_cannot_coast_through_its_freewheel() -> None:
    table = gear_table(load_model(MODELS / "simpson_3speed.yaml"))
    first = table.rows[0]
    assert first.freewheels == {"F1": "holding"}
    assert first.coast_efficiency is None
    assert "no consistent freewheel state" in first.coast_verdict
    second = table.rows[1]
    assert second.freewheels == {"F1": "overrunning"}
    # 2nd: the rear carrier turns at w_out k/(1 + k) = w_in (3/4)/(4/3) = 0.5625 w_in
    assert second.slips["F1"] == pytest.approx(0.75 / (4 / 3), rel=1e-12)
    assert 0 < second.coast_efficiency < 1


def test_to_dict_has_the_documented_keys() -> None:
    data = gear_table(load_model(MODELS / "ravigneaux_4speed.yaml")).to_dict()
    assert set(data) == {"name", "modes", "spread", "warnings"}
    assert {"mode", "engaged", "ratio", "step", "efficiency", "coast_efficiency",
            "element_torques", "slip_speeds", "drag_loss", "verdict"} <= set(data["modes"][0])


def test_drag_column_is_the_open_elements_drag() -> None:
    """Two-speed 2K-H (k = 3), sun in at 100 rad/s, 1 kW; clutch C sun-ring with a drag of
    0.5 N·m, brake B on the ring. Low (B): C slips at w_s - w_r = 100 rad/s: 50 W of drag.
    High (C): B slips at the ring's speed (100 rad/s) but has no drag: 0 W."""
    from powergraph.model import model_from_dict

    model = model_from_dict({
        "name": "two-speed", "description": "hand-derived",
        "components": {0: {"role": "frame"}, "s": {"teeth": 24}, "p": {"teeth": 24},
                       "r": {"teeth": 72, "internal": True}, "c": {}},
        "links": [{"type": "mesh", "between": ["s", "p"], "carrier": "c"},
                  {"type": "mesh", "between": ["p", "r"], "carrier": "c"},
                  {"type": "clutch", "name": "C", "between": ["s", "r"],
                   "drag": {"no_load_torque": 0.5}},
                  {"type": "brake", "name": "B", "between": ["r", 0]}],
        "modes": {"low": ["B"], "high": ["C"]},
        "ports": [{"component": "s", "role": "input", "speed": 100.0, "power": 1000.0},
                  {"component": "c", "role": "output"}]})
    low, high = gear_table(model).rows
    assert low.drag_loss == pytest.approx(50.0, rel=1e-12)
    assert low.efficiency == pytest.approx(0.95, rel=1e-12)      # ideal meshes: 1 - 50/1000
    assert low.slips["C"] == pytest.approx(1.0, rel=1e-12)
    assert high.drag_loss == 0.0 and high.slips["B"] == pytest.approx(1.0, rel=1e-12)


def _ravigneaux_text_with_input(load: str) -> str:
    text = (MODELS / "ravigneaux_4speed.yaml").read_text()
    assert "speed: 2000 rpm, power: 10 kW" in text
    return text.replace("speed: 2000 rpm, power: 10 kW", load)


def test_issue34_zero_input_load_gear_table_says_no_power_passes() -> None:
    """Input at 2000 rpm with no load (torque 0): nothing passes, so every efficiency is
    undefined (None, as the solver says) and the torques over the input torque are
    undefined (None); the ratios are the closed forms all the same, the slips over the
    input speed too: 1st (C1, B2: carrier held) the large sun turns at
    -z_s1/z_s2 w_in = -30/36 w_in, so B1 slips at -0.8333 w_in."""
    from powergraph.model import loads_model
    from powergraph.statics.modes import solve_mode
    from powergraph.testing import assert_conservation

    model = loads_model(_ravigneaux_text_with_input("speed: 2000 rpm, torque: 0 N*m"))
    table = gear_table(model)
    assert [r.ratio for r in table.rows] == pytest.approx(list(RATIOS.values()), rel=1e-12)
    for row in table.rows:
        assert row.efficiency is None and row.coast_efficiency is None
        assert row.verdict == "no power"
        assert row.coast_verdict == row.verdict
        assert row.input_torque is None and set(row.torques.values()) == {None}
        assert row.warnings == ()          # no "carries no torque": nothing loads them
    assert table.rows[0].slips["B1"] == pytest.approx(-30 / 36, rel=1e-12)
    assert table.rows[0].input_speed == pytest.approx(2000 * math.pi / 30, rel=1e-12)
    first = solve_mode(model, "1")         # what solve --mode says of the same gear
    assert_conservation(first.result)
    assert first.result.efficiency is None and first.result.efficiency_note is not None
    text = table.text_report()
    assert "no power passes" in text and "T -" in text and "indet." not in text
    assert table.to_dict()["modes"][0]["efficiency"] is None


def test_issue34_zero_input_load_modes_command_exits_0(tmp_path, capsys) -> None:
    import json

    from powergraph.cli.main import main

    path = tmp_path / "unloaded.yaml"
    path.write_text(_ravigneaux_text_with_input("speed: 2000 rpm, torque: 0 N*m"))
    assert main(["modes", str(path)]) == 0
    out = capsys.readouterr().out
    assert out.count(" no power\n") == 5       # the verdict of each of the five modes
    assert "  no power: no power passes through the train (the efficiency is undefined)" in out
    assert main(["modes", str(path), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["modes"][0]["element_torques"] == {"C1": None, "B2": None}
    figure = tmp_path / "unloaded.png"
    assert main(["modes", str(path), "-o", str(figure)]) == 0     # no efficiency to mark
    assert figure.stat().st_size > 0


def test_issue34_input_standing_still_gear_table_does_not_divide_by_zero() -> None:
    """Input held at 0 rpm under 10 N·m: no power passes; the torques over the input
    torque stay defined -- 1st gear (C1, B2): C1 passes the whole input torque (-1) --
    and the slips over the (zero) input speed are undefined (None)."""
    from powergraph.model import loads_model

    text = _ravigneaux_text_with_input("speed: 0 rpm, torque: 10 N*m")
    table = gear_table(loads_model(text))
    first = table.rows[0]
    assert first.efficiency is None and first.verdict == "no power"
    assert first.torques["C1"] == pytest.approx(-1.0, rel=1e-12)
    assert first.input_speed is None and set(first.slips.values()) == {None}
    assert "w -" in table.text_report()
