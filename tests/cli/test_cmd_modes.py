"""`powergraph modes` and `solve --mode`: output, JSON keys, refusals with exit 2."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from powergraph.cli.main import main

MODELS = Path(__file__).resolve().parents[2] / "models"
RAV = str(MODELS / "ravigneaux_4speed.yaml")
SIMPSON = str(MODELS / "simpson_3speed.yaml")


@pytest.mark.slow
def test_modes_prints_the_gear_table(capsys) -> None:
    assert main(["modes", RAV]) == 0
    out = capsys.readouterr().out
    assert "spread (forward) 3.6000" in out and "C1 B2" in out


def test_modes_json(capsys) -> None:
    assert main(["modes", SIMPSON, "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert [m["mode"] for m in data["modes"]] == ["1", "2", "3", "R"]
    assert data["spread"] == pytest.approx(7 / 3, rel=1e-12)
    assert data["modes"][0]["coast_efficiency"] is None


@pytest.mark.slow
def test_modes_writes_a_chart(tmp_path: Path, capsys) -> None:
    target = tmp_path / "gears.png"
    assert main(["modes", RAV, "-o", str(target)]) == 0
    assert target.stat().st_size > 1000


def test_solve_mode_json_has_the_solve_keys_and_the_elements(capsys) -> None:
    assert main(["solve", SIMPSON, "--mode", "2", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert {"ratio", "efficiency", "meshes", "flows", "mode", "shift_elements"} <= set(data)
    assert data["mode"] == "2" and data["ratio"] == pytest.approx(4 / 3, rel=1e-12)
    b1 = next(e for e in data["shift_elements"] if e["name"] == "B1")
    assert b1["engaged"] and b1["slip_speed"] == 0.0


@pytest.mark.parametrize("args, message", [
    (["solve", SIMPSON], "the model has modes 1, 2, 3, R: choose one with --mode NAME"),
    (["solve", SIMPSON, "--mode", "9"], "--mode 9: unknown mode"),
    (["solve", str(MODELS / "rv40e.yaml"), "--mode", "1"], "the model has no modes table"),
    (["modes", str(MODELS / "rv40e.yaml")], "modes: the model has no modes table"),
])
def test_refusals_exit_2_with_one_line(args, message, capsys) -> None:
    assert main(args) == 2
    err = capsys.readouterr().err
    assert message in err and "Traceback" not in err and err.count("\n") == 1


def test_check_solves_every_mode(capsys) -> None:
    assert main(["check", RAV]) == 0
    assert "modes 1, 2, 3, 4, R: each solves with 1 DOF" in capsys.readouterr().out


@pytest.mark.slow
def test_lever_and_draw_take_a_mode(tmp_path: Path, capsys) -> None:
    lever, flow = tmp_path / "lever.png", tmp_path / "flow.png"
    assert main(["lever", RAV, "--mode", "2", "-o", str(lever)]) == 0
    assert "s2     at -0.8333  w = 0 rad/s  (held)" in capsys.readouterr().out
    assert main(["draw", RAV, "--mode", "R", "-o", str(flow)]) == 0
    assert lever.stat().st_size > 1000 and flow.stat().st_size > 1000
    assert main(["draw", RAV, "-o", str(flow)]) == 2


def test_compare_takes_model_colon_mode(capsys) -> None:
    """Ravigneaux 1st as a mode and as its own file: the same row (ratio 2.4, eta^3)."""
    assert main(["compare", f"{RAV}:1", str(MODELS / "ravigneaux_first.yaml"), "--json"]) == 0
    rows = json.loads(capsys.readouterr().out)
    assert rows[0]["name"] == "Ravigneaux 4-speed [1]"
    assert rows[0]["ratio"] == pytest.approx(2.4, rel=1e-12)
    assert rows[0]["efficiency"] == pytest.approx(0.98 ** 3, rel=1e-9)
    assert rows[0]["efficiency"] == pytest.approx(rows[1]["efficiency"], rel=1e-9)
    assert main(["compare", f"{SIMPSON}:1", "--json"]) == 0
    simpson = json.loads(capsys.readouterr().out)[0]
    assert simpson["backdrive_efficiency"] is None
    assert "no consistent freewheel state" in simpson["backdrive_note"]


@pytest.mark.slow  # three commands, each solving a mode first
def test_sweep_map_and_tolerance_take_a_mode(capsys) -> None:
    """``--mode`` evaluates one gear: the sweep's ratio is the gear's published ratio, and
    a model with modes asked without one is refused naming the modes (exit 2)."""
    model = str(MODELS / "zf8hp_8speed.yaml")
    assert main(["sweep", model, "--mode", "3", "--set", "links.0.efficiency=0.98"]) == 0
    out = capsys.readouterr().out.splitlines()
    assert float(out[1].split(",")[1]) == pytest.approx(2.104, abs=1e-3)  # 8HP70, 3rd gear
    assert main(["map", model, "--mode", "1", "--torque", "100", "--speed", "1000"]) == 0
    assert "[1]" in capsys.readouterr().out
    assert main(["sweep", model, "--set", "links.0.efficiency=0.98"]) == 2
    assert "--mode" in capsys.readouterr().err


VOLT = MODELS / "volt_gen1.yaml"


@pytest.mark.parametrize("change, command, message", [
    (("inactive: [engine, MG-A]", "inactive: [engin, MG-A]"), "check",
     "modes.one-motor EV.inactive[0]: unknown port 'engin'"),
    (("inactive: [engine]  ", "off: [engine]  "), "modes",
     "modes.two-motor EV.False: unknown field: a key read as the boolean false (YAML 1.1 "
     "reads off, on, yes, no, true and false unquoted as booleans; ports that carry "
     "nothing in a mode are listed under inactive)"),
    (("ports: {wheels: {power: 20 kW}}", "ports: {engine: {power: 20 kW}}"), "modes",
     "modes.one-motor EV.ports.engine: ports[0] (engine) is inactive in this mode"),
    (("engage: [C1, C3]  ", "engage: [C1, C3]\n    ports: {MG-A: {speed: 1900 rpm}}\n  "),
     "solve", "ports[0] (engine) gives 209.44 rad/s and ports[1] (MG-A) 198.968 rad/s, "
              "but they are on one rigid body 'A/E'"),
    (("engage: [C1, C3]  ", "engage: [C3]  "), "solve",
     "modes.series: engages C3: leaves 3 DOF, the train needs 1 more engaged element (or a "
     "given speed on 1 more port)"),
])
def test_hybrid_mode_mistakes_exit_2_with_one_line(change, command, message, tmp_path,
                                                   capsys) -> None:
    text = VOLT.read_text()
    assert change[0] in text
    path = tmp_path / "volt.yaml"
    path.write_text(text.replace(change[0], change[1], 1))
    args = [command, str(path)] + (["--mode", "series"] if command == "solve" else [])
    assert main(args) == 2
    err = capsys.readouterr().err
    assert message in err and "Traceback" not in err and err.count("\n") == 1


def test_check_names_each_mode_s_dof(capsys) -> None:
    assert main(["check", str(VOLT)]) == 0
    out = capsys.readouterr().out
    assert "DOF power split 2, series 2, one-motor EV 1, two-motor EV 2" in out
