"""Modes as operating states (docs/modes.md), derived by hand: inactive ports, idle
members, two ports on one shaft, 2-DOF modes beside 1-DOF ones in one table.

The train is ``models/volt_gen1.yaml`` (a simplified Chevrolet Volt Gen 1) with its meshes
made ideal, so that every number follows from the lever and the bus balance alone:

- planetary: sun S (MG-B) 37, ring R 83, carrier C (output); k = z_r/z_s = 83/37;
  Willis: w_S = (1 + k) w_C - k w_R; ideal external torques holding the carrier's
  torque tau_c (what the carrier passes on to the output) are T_S = tau_c/(1 + k) on the
  sun and T_R = k tau_c/(1 + k) on the ring;
- transfer: carrier gear 25 -> idler 40 -> final drive 54, two external meshes, so
  w_D = w_C · 25/54 = w_C / 2.16 (the wheels turn the carrier's way);
- machines at eta = 0.9: drawing P/eta motoring, returning P·eta generating;
- wheels at 800 rpm; engine 2000 rpm, 30 kW; MG-A 1500 rpm in two-motor EV; the EV modes
  take 20 kW out at the wheels from a free battery, the engine modes keep the battery at
  0 W.
"""
from __future__ import annotations

import math
from pathlib import Path

import pytest

from powergraph.errors import KinematicsError, ModelError, StaticsError
from powergraph.model import load_model, model_from_dict
from powergraph.statics import solve
from powergraph.statics.case import TrainCase
from powergraph.testing import assert_conservation

ROOT = Path(__file__).resolve().parents[2]
VOLT = ROOT / "models" / "volt_gen1.yaml"
RPM = math.pi / 30
K = 83 / 37
FD = 54 / 25
ETA = 0.9
W_D, W_E, W_A = 800 * RPM, 2000 * RPM, 1500 * RPM
W_C = W_D * FD


@pytest.fixture(scope="module")
def volt():
    return load_model(VOLT).with_mesh_efficiency(1.0)


def point(model, mode):
    p = TrainCase.of(model, mode).point()
    assert_conservation(p.result)
    return p


def machines(result):
    return {m.name: m for m in result.machines}


def test_one_motor_ev_engine_and_mg_a_inactive_and_idle(volt) -> None:
    """C1 holds the ring: MG-B alone drives, sun to wheels (1 + k)·2.16 = 7.0054. The
    engine and MG-A are inactive; their shafts, declutched (C2, C3 open), are idle."""
    p = point(volt, "one-motor EV")
    result, mg = p.result, machines(p.result)
    w_s = (1 + K) * W_C
    assert p.verdict == "ok" and result.kinematics.dof == 1
    assert mg["MG-B"].speed == pytest.approx(w_s, rel=1e-12)
    assert mg["MG-B"].power == pytest.approx(20e3, rel=1e-12)        # ideal meshes
    assert mg["MG-B"].torque == pytest.approx(20e3 / w_s, rel=1e-12)
    assert result.buses["dc"].battery_power == pytest.approx(20e3 / ETA, rel=1e-12)
    assert result.efficiency == pytest.approx(ETA, rel=1e-12)
    assert mg["MG-A"].state == "inactive" and mg["MG-A"].torque == 0.0
    assert result.model.idle == {"A", "E"}
    # the brake holds the ring against k times the sun's torque
    assert p.moded.element("C1").torque == pytest.approx(K * 20e3 / w_s, rel=1e-12)
    assert p.moded.element("C2").slip_speed is None       # beside the idle MG-A rotor
    assert p.moded.element("C3").slip_speed is None
    dump = p.report.to_dict()
    assert dump["speeds"]["A"] is None and dump["speeds"]["E"] is None
    assert dump["speeds"]["S"] == pytest.approx(w_s, rel=1e-12)
    assert dump["inactive"] == ["engine", "MG-A"] and dump["idle"] == ["A", "E"]
    engine = next(port for port in dump["ports"] if port["name"] == "engine")
    assert engine["active"] is False and engine["speed"] is None and engine["power"] == 0
    assert dump["ratio"] is None and dump["verdict"] == "ok"
    text = p.report.text_report()
    assert "inactive ports: engine, MG-A" in text and "idle" in text


def test_two_motor_ev_a_2_dof_mode_with_an_inactive_port(volt) -> None:
    """C2 joins the ring to MG-A, given 1500 rpm: 2 DOF (MG-A's and the wheels' speeds),
    the engine inactive and idle. The lever shares the carrier's torque: MG-B on the sun
    tau_c/(1 + k), MG-A on the ring k tau_c/(1 + k), both motoring."""
    p = point(volt, "two-motor EV")
    result, mg = p.result, machines(p.result)
    tau_c = 20e3 / W_C
    w_s = (1 + K) * W_C - K * W_A
    assert result.kinematics.dof == 2 and result.model.idle == {"E"}
    assert mg["MG-A"].speed == pytest.approx(W_A, rel=1e-12)
    assert mg["MG-B"].speed == pytest.approx(w_s, rel=1e-12)
    assert mg["MG-B"].torque == pytest.approx(tau_c / (1 + K), rel=1e-12)
    assert mg["MG-A"].torque == pytest.approx(K * tau_c / (1 + K), rel=1e-12)
    assert mg["MG-A"].state == mg["MG-B"].state == "motoring"
    assert mg["MG-A"].power + mg["MG-B"].power == pytest.approx(20e3, rel=1e-12)
    assert result.buses["dc"].battery_power == pytest.approx(20e3 / ETA, rel=1e-12)
    assert p.moded.element("C1").slip_speed == pytest.approx(W_A, rel=1e-12)
    assert p.moded.element("C3").slip_speed is None
    assert [port.name for port in result.model.inputs] == []


def test_series_engine_and_mg_a_on_one_shaft(volt) -> None:
    """C1 + C3: the engine and MG-A share one shaft, its only load: MG-A takes the
    engine's 30 kW back (-30 kW, 27 kW to the bus); the bus at 0 W gives MG-B 27 kW
    drawn, 24.3 kW on its shaft, all of it at the wheels (ideal meshes)."""
    p = point(volt, "series")
    result, mg = p.result, machines(p.result)
    assert result.kinematics.dof == 2 and not result.model.idle
    assert mg["MG-A"].speed == pytest.approx(W_E, rel=1e-12)
    assert mg["MG-A"].torque == pytest.approx(-30e3 / W_E, rel=1e-12)
    assert mg["MG-A"].power == pytest.approx(-30e3, rel=1e-12)
    assert mg["MG-A"].electrical_power == pytest.approx(-27e3, rel=1e-12)
    assert mg["MG-B"].power == pytest.approx(24.3e3, rel=1e-12)
    assert mg["MG-B"].speed == pytest.approx((1 + K) * W_C, rel=1e-12)
    wheels = next(port for port in result.ports if port.name == "wheels")
    assert -wheels.power == pytest.approx(24.3e3, rel=1e-12)
    engine = next(port for port in result.ports if port.name == "engine")
    assert engine.torque == pytest.approx(30e3 / W_E, rel=1e-12)   # its own, not the body's
    assert result.efficiency == pytest.approx(0.81, rel=1e-12)
    # C3 joins MG-A (its first member) to the engine: it carries the engine's torque
    assert p.moded.element("C3").torque == pytest.approx(30e3 / W_E, rel=1e-12)


def test_power_split_output_split_through_the_bus(volt) -> None:
    """C2 + C3: engine and MG-A on the ring, MG-B on the sun. With the carrier's torque
    tau_c: T_MG-A = k tau_c/(1 + k) - T_engine, P_MG-B = tau_c w_S/(1 + k); the bus at
    0 W: 0.9 P_MG-A + P_MG-B/0.9 = 0 (MG-A generates, MG-B motors), so
    tau_c = (1 + k) P_engine / (k w_R + w_S/0.81)."""
    p = point(volt, "power split")
    result, mg = p.result, machines(p.result)
    w_s = (1 + K) * W_C - K * W_E
    tau_c = (1 + K) * 30e3 / (K * W_E + w_s / ETA**2)
    p_b = tau_c * w_s / (1 + K)
    assert mg["MG-B"].speed == pytest.approx(w_s, rel=1e-12)
    assert mg["MG-B"].power == pytest.approx(p_b, rel=1e-9)
    assert mg["MG-A"].power == pytest.approx(-p_b / ETA**2, rel=1e-9)
    assert mg["MG-A"].state == "generating" and mg["MG-B"].state == "motoring"
    wheels = next(port for port in result.ports if port.name == "wheels")
    assert -wheels.power == pytest.approx(tau_c * W_C, rel=1e-9)
    assert p.report.to_dict()["electrical_share"] == pytest.approx(p_b / (tau_c * W_C),
                                                                   rel=1e-9)


def test_the_model_file_as_written_solves_every_mode() -> None:
    """With its meshes at 0.98 every mode solves, conserves power and is ``ok``."""
    model = load_model(VOLT)
    for mode in model.modes:
        p = point(model, mode)
        assert p.verdict == "ok"


# --- a plain P1 hybrid: an engine and a machine on one shaft, no modes ------------------

def p1() -> dict:
    """Engine e and machine m on one shaft (e, m and the pinion p joined by fixed links),
    pinion 20 -> wheel 60 at 0.98; the bus charges its battery at 5 kW."""
    return {"name": "P1", "components": {0: {"role": "frame"}, "e": {}, "m": {},
                                         "p": {"teeth": 20}, "w": {"teeth": 60}},
            "links": [{"type": "fixed", "between": ["e", "m"]},
                      {"type": "fixed", "between": ["m", "p"]},
                      {"type": "mesh", "between": ["p", "w"], "efficiency": 0.98}],
            "ports": [{"component": "e", "role": "input", "name": "engine",
                       "speed": "3000 rpm", "power": "20 kW"},
                      {"component": "m", "role": "machine", "name": "MG", "bus": "dc",
                       "efficiency": ETA},
                      {"component": "w", "role": "output", "name": "wheels"}],
            "buses": {"dc": {"battery": "-5 kW"}}}


def test_two_ports_on_one_shaft_without_modes() -> None:
    """The machine returns 5 kW to the bus: it takes 5/0.9 kW off the shaft; the mesh
    passes the rest at 0.98."""
    result = solve(model_from_dict(p1()))
    assert_conservation(result)
    w_e = 3000 * RPM
    mg = machines(result)["MG"]
    assert mg.speed == pytest.approx(w_e, rel=1e-12)
    assert mg.power == pytest.approx(-5e3 / ETA, rel=1e-12)
    assert mg.torque == pytest.approx(-5e3 / ETA / w_e, rel=1e-12)
    ports = {p.name: p for p in result.ports}
    assert ports["engine"].power == pytest.approx(20e3, rel=1e-12)
    assert -ports["wheels"].power == pytest.approx((20e3 - 5e3 / ETA) * 0.98, rel=1e-12)
    assert ports["wheels"].speed == pytest.approx(-w_e / 3, rel=1e-12)
    dump = result.to_dict()
    assert dump["torques"]["e"] == pytest.approx(20e3 / w_e, rel=1e-12)
    assert dump["torques"]["m"] == pytest.approx(mg.torque, rel=1e-12)


def test_two_ports_on_one_shaft_must_agree_and_be_determined() -> None:
    data = p1()
    data["ports"][1]["speed"] = "2900 rpm"
    with pytest.raises(KinematicsError, match=r"ports\[1\]\.speed: ports\[0\] \(engine\) "
                                              r"gives 314\.159 rad/s and ports\[1\] \(MG\) "
                                              r"303\.687 rad/s, but they are on one rigid"):
        solve(model_from_dict(data))
    data["ports"][1]["speed"] = "3000 rpm"          # the same speed twice is one DOF
    assert_conservation(solve(model_from_dict(data)))


def test_two_unloaded_ports_on_one_shaft_are_refused() -> None:
    """Series mode with the engine's power dropped (``free``), the battery free, and the
    wheels' and MG-B's loads given: the count of loads is right (4 ports, 2 DOF, 2 given),
    but the engine and MG-A share a shaft and neither has a load."""
    import yaml

    data = yaml.safe_load(VOLT.read_text())
    data["modes"]["series"] = {"engage": ["C1", "C3"],
                               "ports": {"engine": {"power": "free"},
                                         "wheels": {"power": "20 kW"},
                                         "MG-B": {"torque": "10 N*m"}},
                               "buses": {"dc": {"battery": "free"}}}
    model = model_from_dict(data)
    with pytest.raises(StaticsError, match=r"ports\[0\] \(engine\) and ports\[1\] "
                                           r"\(MG-A\) are on one rigid body 'A/E' and "
                                           r"neither has a load"):
        TrainCase.of(model, "series").point()


# --- an idle member with a dragging clutch, and a PTO on the input shaft ---------------

def pto_train() -> dict:
    """Input shaft 'in' (100 rad/s, 10 kW) -> pinion 20 -> output 40 at 0.97; a PTO shaft
    x reached through clutch K (1 N·m drag when open) carries an output port 'pto'."""
    return {"name": "PTO", "components": {0: {"role": "frame"}, "in": {},
                                          "g": {"teeth": 20}, "out": {"teeth": 40},
                                          "x": {}},
            "links": [{"type": "fixed", "between": ["in", "g"]},
                      {"type": "mesh", "between": ["g", "out"], "efficiency": 0.97},
                      {"type": "clutch", "name": "K", "between": ["x", "in"],
                       "drag": {"no_load_torque": "1 N*m"}}],
            "ports": [{"component": "in", "role": "input", "name": "engine",
                       "speed": 100, "power": "10 kW"},
                      {"component": "out", "role": "output", "name": "axle"},
                      {"component": "x", "role": "output", "name": "pto", "power": "1 kW"}],
            "modes": {"drive": {"engage": [], "inactive": ["pto"]},
                      "pto": {"engage": ["K"]}}}


def test_an_idle_member_carries_nothing_not_even_its_clutch_drag() -> None:
    """Mode drive: the PTO is inactive and K open, so x is idle; K's drag, which would
    act in a slip the train does not set, is left out: the axle gets 10 kW at 0.97."""
    model = model_from_dict(pto_train())
    p = point(model, "drive")
    assert p.result.model.idle == {"x"}
    assert p.moded.element("K").slip_speed is None
    assert p.moded.element("K").drag_loss == 0.0
    axle = next(port for port in p.result.ports if port.name == "axle")
    assert -axle.power == pytest.approx(10e3 * 0.97, rel=1e-12)
    assert p.report.to_dict()["speeds"]["x"] is None


def test_a_pto_on_the_input_shaft_through_an_engaged_clutch() -> None:
    """Mode pto: K joins x to the input shaft (two ports on one body): the PTO takes
    1 kW straight off the shaft, the mesh passes the other 9 kW at 0.97."""
    model = model_from_dict(pto_train())
    p = point(model, "pto")
    ports = {port.name: port for port in p.result.ports}
    assert ports["pto"].speed == 100.0 and ports["pto"].torque == pytest.approx(-10.0)
    assert -ports["axle"].power == pytest.approx(9e3 * 0.97, rel=1e-12)
    # K carries the PTO's torque to x: x's load is -10 N·m, so K applies +10 N·m to it
    assert p.moded.element("K").torque == pytest.approx(10.0, rel=1e-12)


def test_a_mode_that_leaves_an_active_port_loose_is_still_a_dof_error() -> None:
    data = pto_train()
    data["modes"]["drive"] = {"engage": []}           # the PTO active on a loose shaft
    with pytest.raises(ModelError, match=r"modes\.drive: engages nothing: leaves 2 DOF"):
        TrainCase.of(model_from_dict(data), "drive").point()


def test_the_loaded_model_solves_its_first_mode_even_one_with_idle_members() -> None:
    """The Volt with one-motor EV listed first: ``powergraph.solve`` of the file as
    loaded solves that mode (the engine and MG-A inactive, their shafts idle), as
    ``solve --mode 'one-motor EV'`` does, and warns ``default-state``."""
    import yaml

    import powergraph as pg

    data = yaml.safe_load(VOLT.read_text())
    modes = data["modes"]
    data["modes"] = {"one-motor EV": modes.pop("one-motor EV"), **modes}
    model = model_from_dict(data)
    result = pg.solve(model)
    assert_conservation(result)
    assert result.model.idle == {"A", "E"}
    assert "default-state" in [w.code for w in result.warnings]
    expected = TrainCase.of(model, "one-motor EV").point().result
    assert result.efficiency == pytest.approx(expected.efficiency, rel=1e-12)
    assert result.total_loss == pytest.approx(expected.total_loss, rel=1e-12)
