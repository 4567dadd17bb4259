"""A single-planetary power-split device (THS type) with its two machines on one bus,
derived by hand.

Engine on the carrier C, MG1 on the sun S, MG2 on the ring R; the ring drives the wheels
W through an ideal 40:40 external pair (w_W = -w_r, the ring's power reaches the wheels).
Meshes ideal, machines eta = 0.9, a charge-sustaining bus (battery 0 W).

Hand derivation (k = z_r / z_s = 78 / 30):
- Willis: w_s = (1 + k) w_c - k w_r.
- Ideal planetary balance: the external torques on sun and ring that hold the carrier's
  torque T_c are T_s = -T_c / (1 + k) and T_r = -k T_c / (1 + k).
- MG1 holds the sun: P_MG1 = T_s w_s (into the train); it draws P_e1 = P/eta motoring,
  P*eta generating.
- The bus: P_e1 + P_e2 = battery = 0, so P_e2 = -P_e1 and P_MG2 = P_e2*eta when MG2
  motors (P_e2 > 0), P_e2/eta when it generates.
- Ideal meshes: the wheels take P_engine + P_MG1 + P_MG2.
"""
import math

import pytest

from powergraph.errors import StaticsError
from powergraph.model import model_from_dict
from powergraph.statics import solve
from powergraph.testing import assert_conservation

K = 78 / 30
ETA = 0.9
RPM = math.pi / 30


def _device(wheel_rpm: float, battery="0 W", engine_power="30 kW") -> dict:
    return {
        "name": "power split",
        "components": {"frame": {"role": "frame"}, "S": {"teeth": 30},
                       "P": {"teeth": 24, "count": 4}, "R": {"teeth": 78, "internal": True},
                       "C": {}, "R2": {"teeth": 40}, "W": {"teeth": 40}},
        "links": [{"type": "mesh", "between": ["S", "P"], "carrier": "C", "efficiency": 1},
                  {"type": "mesh", "between": ["P", "R"], "carrier": "C", "efficiency": 1},
                  {"type": "bearing", "between": ["P", "C"]},
                  {"type": "fixed", "between": ["R", "R2"]},
                  {"type": "mesh", "between": ["R2", "W"], "efficiency": 1}],
        "ports": [{"component": "C", "role": "input", "name": "engine", "speed": "2000 rpm",
                   "power": engine_power},
                  {"component": "S", "role": "machine", "name": "MG1", "efficiency": ETA,
                   "bus": "dc"},
                  {"component": "R", "role": "machine", "name": "MG2", "efficiency": ETA,
                   "bus": "dc"},
                  {"component": "W", "role": "output", "name": "wheels",
                   "speed": f"{-wheel_rpm} rpm"}],
        "buses": {"dc": {"battery": battery}},
    }


def _by_hand(wheel_rpm: float, engine_power: float = 30e3) -> dict:
    w_c, w_r = 2000 * RPM, wheel_rpm * RPM
    w_s = (1 + K) * w_c - K * w_r
    t_c = engine_power / w_c
    p_mg1 = -t_c / (1 + K) * w_s
    p_e1 = p_mg1 / ETA if p_mg1 > 0 else p_mg1 * ETA
    p_e2 = -p_e1
    p_mg2 = p_e2 * ETA if p_e2 > 0 else p_e2 / ETA
    return {"w_s": w_s, "p_mg1": p_mg1, "p_e1": p_e1, "p_mg2": p_mg2, "p_e2": p_e2,
            "wheels": engine_power + p_mg1 + p_mg2}


def _machines(result):
    return {m.name: m for m in result.machines}


def test_positive_split_mg1_generates_mg2_motors():
    hand = _by_hand(1500)
    result = solve(model_from_dict(_device(1500)))
    assert_conservation(result)
    mg = _machines(result)
    assert hand["p_mg1"] < 0 < hand["p_mg2"]
    assert mg["MG1"].state == "generating" and mg["MG2"].state == "motoring"
    assert mg["MG1"].speed == pytest.approx(hand["w_s"], rel=1e-12)
    assert mg["MG1"].power == pytest.approx(hand["p_mg1"], rel=1e-9)
    assert mg["MG1"].electrical_power == pytest.approx(hand["p_e1"], rel=1e-9)
    assert mg["MG2"].power == pytest.approx(hand["p_mg2"], rel=1e-9)
    assert mg["MG2"].electrical_power == pytest.approx(hand["p_e2"], rel=1e-9)
    wheels = next(p for p in result.ports if p.name == "wheels")
    assert -wheels.power == pytest.approx(hand["wheels"], rel=1e-9)
    # the machines lose (1 - eta) of what passes them; nothing else loses
    losses = -hand["p_mg1"] - (-hand["p_e1"]) + hand["p_e2"] - hand["p_mg2"]
    assert result.total_loss == pytest.approx(losses, rel=1e-9)
    assert result.efficiency == pytest.approx(hand["wheels"] / 30e3, rel=1e-9)
    assert result.circulating_power == pytest.approx(0.0, abs=1e-6)
    assert result.buses["dc"].battery_power == 0.0
    dump = result.to_dict()
    assert dump["negative_split"] is False
    assert dump["electrical_share"] == pytest.approx(hand["p_mg2"] / hand["wheels"], rel=1e-9)
    assert {m["name"]: m["state"] for m in dump["machines"]} == {
        "MG1": "generating", "MG2": "motoring"}


def test_negative_split_power_circulates_through_the_bus():
    hand = _by_hand(6000)          # high wheel speed: the sun turns backwards
    result = solve(model_from_dict(_device(6000)))
    assert_conservation(result)
    mg = _machines(result)
    assert hand["w_s"] < 0 and hand["p_mg1"] > 0 > hand["p_mg2"]
    assert mg["MG1"].state == "motoring" and mg["MG2"].state == "generating"
    assert mg["MG1"].power == pytest.approx(hand["p_mg1"], rel=1e-9)
    assert mg["MG1"].electrical_power == pytest.approx(hand["p_e1"], rel=1e-9)
    assert mg["MG2"].power == pytest.approx(hand["p_mg2"], rel=1e-9)
    assert mg["MG2"].electrical_power == pytest.approx(hand["p_e2"], rel=1e-9)
    wheels = next(p for p in result.ports if p.name == "wheels")
    assert -wheels.power == pytest.approx(hand["wheels"], rel=1e-9)
    # The loop ring -> MG2 -> bus -> MG1 -> sun -> planets -> ring: its smallest arrow is
    # MG1's shaft power (|P_MG2| > |P_e2| = P_e1 > P_MG1, and the planets pass the
    # engine's power besides), so that is the power circulating.
    assert result.circulating_power == pytest.approx(hand["p_mg1"], rel=1e-9)
    dump = result.to_dict()
    assert dump["negative_split"] is True
    assert dump["electrical_share"] == pytest.approx(-hand["p_mg1"] / hand["wheels"],
                                                     rel=1e-9)
    assert "negative split" in result.text_report()


def test_a_discharging_battery_feeds_the_wheels():
    # 5 kW from the battery: P_e1 + P_e2 = 5 kW, so MG2 draws 5 kW more than MG1 returns
    result = solve(model_from_dict(_device(1500, battery="5 kW")))
    assert_conservation(result)
    hand = _by_hand(1500)
    p_e2 = 5e3 - hand["p_e1"]
    mg = _machines(result)
    assert mg["MG2"].power == pytest.approx(p_e2 * ETA, rel=1e-9)
    assert result.efficiency == pytest.approx(
        (30e3 + hand["p_mg1"] + p_e2 * ETA) / 35e3, rel=1e-9)


def test_a_free_battery_needs_another_load():
    with pytest.raises(StaticsError, match="give 1 more"):
        solve(model_from_dict(_device(1500, battery="free")))


def test_too_many_loads_with_a_balanced_bus_contradict():
    data = _device(1500)
    data["ports"][3]["power"] = "20 kW"
    with pytest.raises(StaticsError, match="contradict"):
        solve(model_from_dict(data))


def test_a_machine_on_an_undeclared_bus_is_refused():
    from powergraph.errors import ModelError

    data = _device(1500)
    data["ports"][1]["bus"] = "ac"
    with pytest.raises(ModelError, match="unknown bus"):
        model_from_dict(data)


def test_the_ths2_model_file_with_ideal_meshes_is_the_hand_derivation():
    # models/ths2_power_split.yaml: the same planetary (30/78), the ring to the wheels
    # through 31:31 then 19:78, so w_r = w_wheels * 78/19 (two external pairs: same
    # sense). With every mesh ideal the hand derivation above holds at that ring speed.
    from pathlib import Path

    import powergraph as pg

    path = Path(__file__).resolve().parents[2] / "models" / "ths2_power_split.yaml"
    model = pg.load_model(path).with_mesh_efficiency(1.0)
    result = solve(model)
    assert_conservation(result)
    hand = _by_hand(400 * 78 / 19)
    mg = _machines(result)
    assert mg["MG1"].power == pytest.approx(hand["p_mg1"], rel=1e-9)
    assert mg["MG2"].power == pytest.approx(hand["p_mg2"], rel=1e-9)
    wheels = next(p for p in result.ports if p.name == "wheels")
    assert -wheels.power == pytest.approx(hand["wheels"], rel=1e-9)


def test_check_counts_the_bus_balance_and_explains_a_missing_load(tmp_path, capsys):
    import yaml

    from powergraph.cli.main import main

    good, free = tmp_path / "good.yaml", tmp_path / "free.yaml"
    good.write_text(yaml.safe_dump(_device(1500)))
    free.write_text(yaml.safe_dump(_device(1500, battery="free")))
    assert main(["check", str(good)]) == 0
    assert "loads of 1 of 2 port(s) given and 1 bus balance(s)" in capsys.readouterr().out
    assert main(["check", str(free)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("powergraph: error: ports: the loads are not determined")
    assert "0 bus balance(s)" in err and len(err.splitlines()) == 1


# Issue 34, item 4: a machine's stated max_speed. By Willis, w_s = (1 + k) w_c - k w_r:
# wheels at 1500 rpm put MG1 (the sun) at 3.6·2000 − 2.6·1500 = 3300 rpm; at 6000 rpm at
# 7200 − 15600 = −8400 rpm (backwards: the comparison is with |speed|).
def _over(result):
    return [w for w in result.warnings if w.code == "over-max-speed"]


def _with_max_speed(wheel_rpm: float, max_speed, port: int = 1) -> dict:
    data = _device(wheel_rpm)
    data["ports"][port]["max_speed"] = max_speed
    return data


def test_issue34_a_machine_beyond_its_max_speed_warns_naming_both_speeds():
    result = solve(model_from_dict(_with_max_speed(1500, "3000 rpm")))
    (warning,) = _over(result)
    assert warning.path == "ports[1].max_speed"
    assert warning.message == ("ports[1] (MG1) runs at 3300 rpm, 300 rpm above its "
                               "max_speed of 3000 rpm")


def test_issue34_max_speed_compares_the_magnitude_of_a_backward_speed():
    result = solve(model_from_dict(_with_max_speed(6000, "8000 RPM")))
    (warning,) = _over(result)
    assert warning.message == ("ports[1] (MG1) runs at 8400 rpm, 400 rpm above its "
                               "max_speed of 8000 rpm")
    assert not _over(solve(model_from_dict(_with_max_speed(6000, "8500 rpm"))))


def test_issue34_a_machine_at_or_below_its_max_speed_does_not_warn():
    assert not _over(solve(model_from_dict(_with_max_speed(1500, "3300 rpm"))))
    assert not _over(solve(model_from_dict(_with_max_speed(1500, "13500 rpm"))))
    # without a name the port is named by its component
    data = _with_max_speed(1500, "3000 rpm")
    del data["ports"][1]["name"]
    (warning,) = _over(solve(model_from_dict(data)))
    assert warning.message.startswith("ports[1] (component S) runs at 3300 rpm")


@pytest.mark.parametrize("port, value, path, words", [
    (1, "-5 rpm", "ports[1].max_speed", "must be > 0 rad/s, got '-5 rpm'"),
    (1, 0, "ports[1].max_speed", "must be > 0 rad/s, got 0"),
    (1, "3000 rpm/s", "ports[1].max_speed", "is not a speed"),
    (1, "off", "ports[1].max_speed", "expected a speed"),
    (0, "3000 rpm", "ports[0].max_speed", "only a machine port (role: machine) has max_speed"),
])
def test_issue34_a_bad_max_speed_is_refused(port, value, path, words):
    from powergraph.errors import ModelError

    data = _with_max_speed(1500, True if value == "off" else value, port)  # YAML 1.1 `off`
    with pytest.raises(ModelError) as info:
        model_from_dict(data)
    assert info.value.path == path and words in info.value.message


def test_issue34_a_max_speed_without_a_unit_is_rad_s_with_a_caveat():
    model = model_from_dict(_with_max_speed(1500, 500))
    assert model.ports[1].max_speed == 500.0
    (caveat,) = [c for c in model.warnings if c.code == "bare-speed"]
    assert caveat.path == "ports[1].max_speed"


def test_issue34_a_cycle_names_the_rows_beyond_a_max_speed():
    import io

    from powergraph.analyses.cycle import cycle

    # wheels at 1500 rpm: MG1 at 3300 rpm; at 1000 rpm: 7200 − 2600 = 4600 rpm > 3500 rpm
    model = model_from_dict(_with_max_speed(1500, "3500 rpm"))
    points = "wheels.speed [rpm],duration [s]\n-1500,1\n-1000,1\n"
    result = cycle(model, io.StringIO(points))
    assert [r.warnings for r in result.rows] == [(), ("over-max-speed",)]


def test_issue34_the_hybrid_docs_model_is_the_model_file_and_its_speeds_hold():
    """docs/hybrid.md shows models/ths2_power_split.yaml whole (but its description), and
    says what a wheel speed of the wrong sign does: by hand, two external meshes between
    ring and wheels keep the sense (w_R = w_W · 78/19 · 31/31) and Willis' relation of the
    set gives w_S = 3.6 w_C - 2.6 w_R."""
    import re
    from pathlib import Path

    import powergraph as pg
    from powergraph.model import load_yaml_text

    root = Path(__file__).resolve().parents[2]
    docs = (root / "docs" / "hybrid.md").read_text(encoding="utf-8")
    shown = load_yaml_text(re.search(r"```yaml\n(name: THS.*?)```", docs, re.S).group(1))
    file = load_yaml_text((root / "models" / "ths2_power_split.yaml").read_bytes())
    file.pop("description")
    assert shown == file
    model = pg.load_model(root / "models" / "ths2_power_split.yaml")
    result = solve(model)
    assert_conservation(result)
    rpm = 30 / math.pi
    ring = 400 * 78 / 19 * 31 / 31
    assert result.kinematics.speed("R") * rpm == pytest.approx(ring, rel=1e-12)
    assert result.kinematics.speed("S") * rpm == pytest.approx(3.6 * 2000 - 2.6 * ring,
                                                               rel=1e-12)
    assert not [w for w in result.warnings if w.code == "over-max-speed"]
    backwards = solve(model.with_port(3, speed=-1500 / rpm))
    mg1 = 3.6 * 2000 + 2.6 * 1500 * 78 / 19               # 23,210.5 rpm
    warned = [w for w in backwards.warnings if w.code == "over-max-speed"]
    assert [w.path for w in warned] == ["ports[1].max_speed", "ports[2].max_speed"]
    assert f"runs at {mg1:.6g} rpm" in warned[0].message and f"{mg1:.6g}" in docs


def test_the_machine_rules_over_arrays_are_the_rules_at_each_point() -> None:
    # one rule, a point or many (the batched duty cycle applies them over its rows)
    import numpy as np

    from powergraph.model.spec import Port
    from powergraph.statics.machines import (electrical_power, machine_efficiency,
                                             over_max_speed)

    powers = np.array([900.0, -1000.0, 0.0, 1e-300])
    assert electrical_power(powers, 0.9).tolist() == \
        [electrical_power(p, 0.9) for p in powers.tolist()]
    assert electrical_power(powers, np.array([0.9, 0.5, 0.9, 0.5])).tolist() == \
        [1000.0, -500.0, 0.0, 2e-300]
    port = Port(0, "S", "machine", efficiency=0.9, bus="dc", max_speed=100.0)
    eta, on_map = machine_efficiency(port, np.array([1.0, 2.0]), np.array([3.0, 4.0]))
    assert eta.tolist() == [0.9, 0.9] and on_map.tolist() == [True, True]
    speeds = np.array([100.0, -100.0 * (1 + 2e-9), 50.0])
    assert over_max_speed(port, speeds).tolist() == \
        [bool(over_max_speed(port, s)) for s in speeds.tolist()] == [False, True, False]
