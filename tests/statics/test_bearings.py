"""Bearing friction and no-load drag as losses (powergraph.statics.bearings).

Expected values are hand derivations written in each test: a bearing's torque
``M = mu * F * d / 2 + M0`` opposes the relative rotation of its two members, its loss is
``M * |Δω|``, and its radial load F is the sum of the tangential tooth forces on the
carried member (docs/losses.md). Every solve is followed by assert_conservation.
"""
from __future__ import annotations

import copy
import json
import math
from pathlib import Path

import pytest

import powergraph as pg
from powergraph.errors import SolveError
from powergraph.model import model_from_dict
from powergraph.statics.flow import Node
from powergraph.testing import assert_conservation

MODELS = Path(__file__).resolve().parents[2] / "models"
RPM = 2 * math.pi / 60


def solve(model, **kwargs):
    result = pg.solve(model, **kwargs)
    assert_conservation(result)
    return result


def pair(bearing: dict | None = None, drag2: dict | None = None, ports: list | None = None,
         efficiency: float = 0.98) -> dict:
    """Gears 1 (z 20) and 2 (z 40) on fixed axes; gear 1's geometry gives r1 = m·z/2 = 20 mm;
    gear 1's shaft runs in a bearing on the housing 0."""
    components = {0: {"role": "frame"},
                  1: {"teeth": 20, "geometry": {"module": 2, "face_width": 10,
                                                "bore_radius": 0}},
                  2: {"teeth": 40}}
    if drag2 is not None:
        components[2]["drag"] = drag2
    links = [{"type": "mesh", "between": [1, 2], "efficiency": efficiency}]
    if bearing is not None:
        links.append({"type": "bearing", "between": [1, 0], **bearing})
    return {"name": "pair", "components": components, "links": links,
            "ports": ports or [{"component": 1, "role": "input", "speed": 100.0,
                                "power": 1000.0}, {"component": 2, "role": "output"}]}


def test_shaft_bearing_of_a_fixed_axis_pair_by_hand() -> None:
    # Input: T = 1000 W / 100 rad/s = 10 N·m on gear 1. The bearing takes M off it, the mesh
    # the rest: tooth force F = (T - M)/r1 with r1 = 0.020 m, so with c = mu·d/(2·r1)
    #   M = c·(T - M) + T0   ->   M = (c·T + T0)/(1 + c).
    mu, d, t0, r1, torque, w = 0.0015, 0.020, 0.3, 0.020, 10.0, 100.0
    c = mu * d / (2 * r1)
    m = (c * torque + t0) / (1 + c)
    model = model_from_dict(pair({"friction": {"mu": mu, "bore": "20 mm"},
                                  "drag": {"no_load_torque": "0.3 N*m"}}))
    result = solve(model)
    (state,) = result.bearings
    assert state.node == "bearing 1-0" and state.relative_speed == w
    assert state.radial_load == pytest.approx((torque - m) / r1, rel=1e-12)
    assert state.torque == pytest.approx(m, rel=1e-12)
    assert state.loss == pytest.approx(mu * state.radial_load * d / 2 * w + t0 * w, rel=1e-12)
    mesh_loss = 0.02 * (torque - m) * w
    assert result.total_loss == pytest.approx(m * w + mesh_loss, rel=1e-12)
    assert result.output_power == pytest.approx(0.98 * (torque - m) * w, rel=1e-12)
    assert result.friction_passes >= 3          # the load-dependent part needs passes


def test_drag_of_a_body_against_the_frame_and_speed_law() -> None:
    # Gear 2 turns at -50 rad/s (-477.46 rpm); its drag a + b·|n| opposes that: the output
    # gets the mesh's 0.98 · 1000 W less M0·50 W. The input shaft's bearing: drag only
    # (no friction block), M0 = 0.3 N·m -> 30 W.
    a, b = 0.1, 0.002
    m0 = a + b * 50 / RPM
    model = model_from_dict(pair({"drag": {"no_load_torque": 0.3}}, {"a": a, "b": "0.002 N*m"}))
    result = solve(model)
    shaft, gear2 = result.bearings
    assert (gear2.kind, gear2.node, gear2.relative_speed) == ("drag", "drag 2", -50.0)
    assert gear2.torque == pytest.approx(m0, rel=1e-12)
    assert gear2.torques == {"2": pytest.approx(m0), "0": pytest.approx(-m0)}
    assert shaft.radial_load == 0.0 and shaft.loss == pytest.approx(30.0, rel=1e-12)
    expected = 0.98 * (10.0 - 0.3) * 100.0 - m0 * 50.0
    assert result.output_power == pytest.approx(expected, rel=1e-12)
    assert result.friction_passes == 2          # drags depend on the speeds only


def test_load_given_at_the_output_and_reversed_motion() -> None:
    # Output torque 40 N·m resisted at gear 2 (ratio 2): the mesh needs 40/(2·0.98) N·m from
    # gear 1's teeth; the shaft's drag adds M0 whichever way the input turns.
    for speed in (100.0, -100.0):
        ports = [{"component": 1, "role": "input", "speed": speed},
                 {"component": 2, "role": "output",
                  "torque": 40.0 if speed > 0 else -40.0}]
        result = solve(model_from_dict(pair({"drag": {"no_load_torque": 0.3}}, ports=ports)))
        tooth = 40.0 / (2 * 0.98)
        assert abs(result.torques["1"]) == pytest.approx(tooth + 0.3, rel=1e-12)
        assert result.bearings[0].loss == pytest.approx(0.3 * 100.0, rel=1e-12)
        assert result.efficiency == pytest.approx(40.0 * 50.0 / ((tooth + 0.3) * 100.0),
                                                  rel=1e-12)


def planetary(bearing: dict, efficiency: float = 1.0) -> dict:
    """2K-H: sun 1 (z 20) input, 3 planets 2 (z 30, module 2: r_p = 30 mm), ring 3 (z 80)
    fixed, carrier 4 output; each planet runs in a bearing on the carrier."""
    return {"name": "2K-H with planet bearings",
            "components": {0: {"role": "frame"}, 1: {"teeth": 20},
                           2: {"teeth": 30, "count": 3,
                               "geometry": {"module": 2, "face_width": 10,
                                            "bore_radius": 5}},
                           3: {"teeth": 80, "internal": True}, 4: {}},
            "links": [{"type": "mesh", "between": [1, 2], "carrier": 4,
                       "efficiency": efficiency},
                      {"type": "mesh", "between": [2, 3], "carrier": 4,
                       "efficiency": efficiency},
                      {"type": "fixed", "between": [3, 0]},
                      {"type": "bearing", "between": [2, 4], **bearing}],
            "ports": [{"component": 1, "role": "input", "speed": 100.0, "power": 2000.0},
                      {"component": 4, "role": "output"}]}


def test_planet_bearing_of_a_2kh_set_by_hand() -> None:
    # Speeds: w_c = w_s·z_s/(z_s + z_r) = 20 rad/s; planet relative to the carrier
    # w_p - w_c = -(z_s/z_p)(w_s - w_c) = -53.33 rad/s.
    # Forces per planet (ideal meshes): the sun pushes with F_s = T_s/(3·r_s), T_s = 20 N·m,
    # r_s = 20 mm; the planet's balance about its axis in the carrier's frame (the sun drives
    # it, the ring and the bearing resist): F_r·r_p = F_s·r_p - M_1. Both tooth forces push
    # the planet the same way, so F = F_s + F_r = 2·F_s - M_1/r_p, and with
    # M_1 = mu·F·d/2 + T0:   M_1 = (mu·d·F_s + T0)/(1 + mu·d/(2·r_p)).
    mu, d, t0, r_p = 0.002, 0.025, 0.05, 0.030
    w_s, w_c = 100.0, 100.0 * 20 / 100
    rel = -(20 / 30) * (w_s - w_c)
    f_s = 20.0 / (3 * 0.020)
    m_1 = (mu * d * f_s + t0) / (1 + mu * d / (2 * r_p))
    result = solve(model_from_dict(planetary({"friction": {"mu": mu, "bore": "25 mm"},
                                              "drag": {"no_load_torque": t0}})))
    (state,) = result.bearings
    assert state.instances == 3 and state.node == "bearing 2-4"
    assert state.relative_speed == pytest.approx(rel, rel=1e-12)
    assert state.radial_load == pytest.approx(2 * f_s - m_1 / r_p, rel=1e-10)
    assert state.torque == pytest.approx(3 * m_1, rel=1e-10)
    loss = 3 * (mu * state.radial_load * d / 2 + t0) * abs(rel)
    assert state.loss == pytest.approx(loss, rel=1e-10)
    assert result.total_loss == pytest.approx(loss, rel=1e-10)        # ideal meshes
    assert result.efficiency == pytest.approx(1 - loss / 2000.0, rel=1e-10)


def test_planet_bearing_with_lossy_meshes_conserves_power() -> None:
    result = solve(model_from_dict(planetary({"friction": {"mu": 0.002, "bore": 25},
                                              "drag": {"a": 0.02, "b": 1e-4}}, 0.985)))
    assert result.bearing_loss > 0
    assert result.total_loss == pytest.approx(sum(e.loss for e in result.meshes)
                                              + result.bearing_loss, rel=1e-12)


def test_radius_from_the_mesh_friction_geometry() -> None:
    # A standard pair (no shifts) has working pitch radius m·z/2 = 20 mm for gear 1;
    # mu = 0 in the mesh keeps it ideal. Only the friction part: M = c·T/(1 + c).
    data = pair({"friction": {"mu": 0.01, "bore": 20}}, efficiency=1.0)
    del data["components"][1]["geometry"]
    data["links"][0] = {"type": "mesh", "between": [1, 2], "friction": {"mu": 0.0},
                        "geometry": {"module": 2}}
    result = solve(model_from_dict(data))
    c = 0.01 * 0.020 / (2 * 0.020)
    assert result.bearings[0].torque == pytest.approx(c * 10.0 / (1 + c), rel=1e-12)


def test_flows_json_and_report() -> None:
    model = model_from_dict(pair({"friction": {"mu": 0.0015, "bore": 20},
                                  "drag": {"no_load_torque": 0.3}}, {"no_load_torque": 0.5}))
    result = solve(model)
    edges = {(f.source, f.target): f.power for f in result.flows()}
    assert edges[("1", "bearing 1-0")] == pytest.approx(result.bearings[0].loss, rel=1e-12)
    assert edges[("bearing 1-0", "loss")] == result.bearings[0].loss
    assert edges[("2", "drag 2")] == pytest.approx(0.5 * 50.0, rel=1e-12)
    seen_from_2 = {(f.source, f.target): f.power for f in result.flows(frame="2")}
    assert ("drag 2", "loss") in seen_from_2             # losses are frame-invariant
    data = json.loads(json.dumps(result.to_dict()))
    assert [b["node"] for b in data["bearings"]] == ["bearing 1-0", "drag 2"]
    assert data["bearings"][0]["between"] == [1, 0] and data["bearings"][1]["link"] is None
    assert data["bearing_loss"] == pytest.approx(result.bearing_loss)
    text = result.text_report()
    assert "bearings and drag" in text and "drag 2" in text
    graph = result.flow_graph()
    assert graph.nodes[Node("bearing", "bearing 1-0")]["kind"] == "bearing"
    assert graph.nodes[Node("drag", "drag 2")]["kind"] == "drag"


def test_rv40e_crank_bearings_and_output_drag() -> None:
    # Every element of the RV solved with bearings on its two cranks (count 2), the first
    # stage's friction from geometry, and a seal drag on the output: losses add up.
    data = json.loads(json.dumps(_rv_with_bearings()))
    result = solve(model_from_dict(data))
    crank, seal = result.bearings
    assert crank.instances == 2 and crank.radial_load > 0
    # The crank 2/3 turns in the planet frame at the planet's relative speed.
    speeds = result.speeds
    assert crank.relative_speed == pytest.approx(speeds["2"] - speeds["7"], rel=1e-12)
    assert seal.loss == pytest.approx(0.5 * abs(speeds["6"]), rel=1e-12)


def _rv_with_bearings() -> dict:
    import yaml

    data = yaml.safe_load((MODELS / "rv40e_wang2021.yaml").read_text())
    mesh = data["links"][0]
    mesh.pop("efficiency", None)
    mesh.update(friction={"mu": 0.05}, geometry={"module": 1.5, "shifts": [0.3, -0.3]})
    data["links"].append({"type": "bearing", "between": [3, 7],
                          "friction": {"mu": 0.0015, "bore": "20 mm"},
                          "drag": {"no_load_torque": "0.05 N*m"}})
    data["components"][6]["drag"] = {"no_load_torque": 0.5}
    return data


def test_divergent_bearing_law_is_a_solve_error() -> None:
    # c = mu·d/(2·r1) = 1·0.1/0.04 = 2.5 > 1: M = c·|T - M| has no stable fixed point.
    model = model_from_dict(pair({"friction": {"mu": 1.0, "bore": 100}}))
    with pytest.raises(SolveError, match="did not converge"):
        pg.solve(model)


@pytest.mark.parametrize("path", sorted(MODELS.glob("*.yaml")), ids=lambda p: p.stem)
def test_models_without_blocks_are_unchanged_and_zero_blocks_change_nothing(path) -> None:
    # A bearing whose friction and drag are zero applies no torque: the solve must be the
    # same, bit for bit, as the model without it (and without any bearing state). A library
    # model with bearing, drag, SKF or churning blocks or seals is taken without them.
    import yaml

    data = yaml.safe_load(path.read_text())
    data["links"] = [link for link in data["links"] if link["type"] != "seal"]
    for link in data["links"]:
        if link["type"] == "bearing":
            for block in ("friction", "drag", "skf"):
                link.pop(block, None)
    for component in data["components"].values():
        component.pop("drag", None)
        component.pop("churning", None)
    model = model_from_dict(data)
    plain = solve(model)
    assert plain.bearings == () and plain.total_loss == (
        sum(e.loss for e in plain.elements) + sum(m.loss for m in plain.machines))
    moving = next(str(c) for c in data["components"] if str(c) != model.frame)
    zero = copy.deepcopy(data)
    zero["links"].append({"type": "bearing", "between": [moving, model.frame],
                          "drag": {"no_load_torque": 0}})
    with_zero = solve(model_from_dict(zero))
    assert with_zero.bearings[0].loss == 0.0
    assert with_zero.external_torques == plain.external_torques
    assert (with_zero.input_power, with_zero.output_power, with_zero.total_loss) == \
        (plain.input_power, plain.output_power, plain.total_loss)
    assert [e.force for e in with_zero.elements] == [e.force for e in plain.elements]


def test_conservation_checks_catch_wrong_bearing_states() -> None:
    import dataclasses

    result = solve(model_from_dict(pair({"friction": {"mu": 0.0015, "bore": 20},
                                         "drag": {"no_load_torque": 0.3}})))
    state = result.bearings[0]
    wrong = {
        "loss not M·|Δω|": dataclasses.replace(state, loss=state.loss * 1.01),
        "torque driving": dataclasses.replace(state, torque=-state.torque,
                                              loss=-state.loss),
        "relative speed": dataclasses.replace(state, relative_speed=2 * state.relative_speed),
        "torque left out": dataclasses.replace(state, torque=0.0, loss=0.0),
    }
    for what, bad in wrong.items():
        with pytest.raises(AssertionError):
            assert_conservation(dataclasses.replace(result, bearings=(bad,)))
            pytest.fail(f"not caught: {what}")


def test_cli_solve_json_and_map(tmp_path, capsys) -> None:
    from powergraph.cli.main import main

    path = tmp_path / "pair.json"
    path.write_text(json.dumps(pair({"drag": {"no_load_torque": "0.3 N*m"}})))
    assert main(["solve", str(path), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["bearings"][0]["loss"] == pytest.approx(30.0, rel=1e-12)
    assert data["total_loss"] == pytest.approx(30.0 + 0.02 * 970.0, rel=1e-12)
    assert main(["map", str(path), "--torque", "5:50:3", "--speed", "500", "--json"]) == 0
    row = json.loads(capsys.readouterr().out)["efficiency"][0]
    assert row == sorted(row) and row[0] < row[-1]
