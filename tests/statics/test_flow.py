"""The flow graph keeps component ids apart from its own nodes (powergraph.statics.flow).

The train of every test here is the plain 2K-H of models/planetary_2kh_sun_to_carrier.yaml:
sun in (1 kW at 1000 rpm), carrier out, ring fixed, z_s = 24, z_r = 72 (k = 3), basic
efficiencies 0.98 (sun-planet) and 0.99 (planet-ring). By hand, in the carrier's frame:
the sun turns at w_s - w_c = w_s·k/(1 + k), so mesh 1 passes P·k/(1 + k) = 750 W and loses
2 % of it (15 W); mesh 2 passes the 735 W left and loses 1 % (7.35 W). Efficiency
1 - 22.35/1000 = 0.97765 = (1 + η0·k)/(1 + k) with η0 = 0.98·0.99. Power enters at the
sun and leaves at the carrier or as loss, never returning: no directed cycle, so the
circulating power is 0. These numbers must not depend on what the components are called.
"""
from __future__ import annotations

import copy
from pathlib import Path

import pytest
import yaml

from powergraph.model import model_from_dict
from powergraph.statics.flow import (Flow, Node, body_node, circulating_power, element_nodes,
                                     split_powers)
from powergraph.testing import assert_conservation
from powergraph.testing_trains import with_ids

ROOT = Path(__file__).resolve().parents[2]
PLAIN = yaml.safe_load((ROOT / "models" / "planetary_2kh_sun_to_carrier.yaml").read_text())
K, ETA1, ETA2, P = 3.0, 0.98, 0.99, 1000.0
VIRTUAL = (P * K / (1 + K), P * K / (1 + K) * ETA1)          # 750 W, 735 W
LOSSES = (VIRTUAL[0] * (1 - ETA1), VIRTUAL[1] * (1 - ETA2))   # 15 W, 7.35 W
EFFICIENCY = (1 + ETA1 * ETA2 * K) / (1 + K)                  # 0.97765

#: Renamings of the audit: a reserved word for the sun, for the carrier, all of them at
#: once, and ids with "/" that spell a body's joined name ("F" + "R" -> "F/R").
RENAMINGS = {
    "sun motor": {"sun": "motor"},
    "carrier generator": {"carrier": "generator"},
    "all reserved": {"sun": "loss", "carrier": "motor", "ring": "generator",
                     "planet": "mesh loss-motor"},
    "slash": {"frame": "F", "ring": "R", "carrier": "F/R"},
    "ground and drag": {"frame": "ground", "sun": "drag sun", "planet": "bearing planet-carrier"},
    "scripts": {"sun": "太阳轮", "planet": "遊星歯車", "ring": "１２", "carrier": "🚀 carrier"},
}


def rename(data: dict, new: dict[str, str]) -> dict:
    """The model data with components renamed (file order kept, so link indices too)."""
    return with_ids(copy.deepcopy(data), new)


def solve(data: dict):
    from powergraph import solve as pg_solve

    result = pg_solve(model_from_dict(data))
    assert_conservation(result)
    return result


@pytest.mark.parametrize("new", RENAMINGS.values(), ids=RENAMINGS.keys())
def test_plain_2kh_has_its_closed_form_whatever_the_ids(new) -> None:
    result = solve(rename(PLAIN, new))
    assert result.efficiency == pytest.approx(EFFICIENCY, rel=1e-12)
    assert [m.carrier_frame_power for m in result.meshes] == pytest.approx(VIRTUAL, rel=1e-12)
    assert [m.loss for m in result.meshes] == pytest.approx(LOSSES, rel=1e-12)
    assert result.circulating_power == 0.0                  # no directed cycle
    data = result.to_dict()
    assert data["circulating_power"] == 0.0
    into_loss = [f for f in data["flows"] if f["to_kind"] == "loss"]
    assert sorted(f["power"] for f in into_loss) == pytest.approx(sorted(LOSSES), rel=1e-12)


def test_a_body_called_motor_is_not_the_motor() -> None:
    result = solve(rename(PLAIN, {"sun": "motor", "carrier": "generator"}))
    flows = {(f.source_node, f.target_node): f.power for f in result.flows()}
    assert flows[(Node("motor", "motor"), Node("body", "motor"))] == pytest.approx(P)
    assert flows[(Node("body", "generator"), Node("generator", "generator"))] == \
        pytest.approx(P * EFFICIENCY)
    motor = next(f for f in result.to_dict()["flows"] if f["from_kind"] == "motor")
    assert motor == {"from": "motor", "to": "motor", "power": pytest.approx(P),
                     "from_kind": "motor", "to_kind": "body"}
    graph = result.flow_graph()
    assert graph.nodes[Node("body", "motor")]["kind"] == "body"
    assert graph.nodes[Node("motor", "motor")]["kind"] == "motor"
    assert not any(u == v for u, v in graph.edges)          # no self-loop


def test_a_slash_in_an_id_never_makes_two_bodies_one() -> None:
    # "F" (the frame) and "R" (the ring) are one body; the carrier is called "F/R": the
    # body takes the next free name, and the model is not refused.
    model = model_from_dict(rename(PLAIN, RENAMINGS["slash"]))
    assert model.body_of["F/R"] == "F/R"
    assert model.body_of["F"] == model.body_of["R"] == "F/R #2"
    assert len({b.id for b in model.bodies}) == len(model.bodies)
    result = solve(rename(PLAIN, RENAMINGS["slash"]))
    assert result.kinematics.speed("F/R") == pytest.approx(result.kinematics.speed("sun") / 4)


def test_elements_with_the_same_name_stay_two_nodes() -> None:
    # ids with "-": mesh 1 / 2-3 and mesh 1-2 / 3 are both written "mesh 1-2-3". A
    # two-stage reducer (20:40 twice, ratio 4), losses 2 % then 1 %, by hand.
    data = {"name": "dashes", "components": {
        "0": {"role": "frame"}, "1": {"teeth": 20}, "2-3": {"teeth": 40},
        "1-2": {"teeth": 20}, "3": {"teeth": 40}},
        "links": [{"type": "mesh", "between": ["1", "2-3"], "carrier": "0", "efficiency": 0.98},
                  {"type": "mesh", "between": ["1-2", "3"], "carrier": "0", "efficiency": 0.99},
                  {"type": "fixed", "between": ["2-3", "1-2"]}],
        "ports": [{"component": "1", "role": "input", "speed": "1000 rpm", "power": "1 kW"},
                  {"component": "3", "role": "output"}]}
    result = solve(data)                  # the flow balance of each mesh node holds
    assert result.ratio == pytest.approx(4.0)
    assert result.efficiency == pytest.approx(0.98 * 0.99, rel=1e-12)
    assert [n.name for n in element_nodes(result).values()] == ["mesh 1-2-3", "mesh 1-2-3 #2"]
    losses = {f.source: f.power for f in result.flows() if f.target_kind == "loss"}
    assert losses == pytest.approx({"mesh 1-2-3": 20.0, "mesh 1-2-3 #2": 9.8})


def test_split_powers_are_keyed_by_node() -> None:
    # Ground frame (docs/theory.md, section 7): the sun-planet mesh splits the 1000 W fed
    # by the sun into 490 W to the planets and 495 W to the carrier (15 W lost). By hand,
    # with w_c = w_s/4 and z_p = z_s: w_p - w_c = -(w_s - w_c) = -0.75 w_s, w_p = -0.5 w_s.
    # The mesh hands the planet 735 W in the carrier's frame, so its torque on the planet
    # is T_p = 735/(w_p - w_c), and in the ground frame the planet gets T_p·w_p = 735·(0.5
    # /0.75) = 490 W; the element balances (1000 in = 490 + carrier + 15), carrier 495 W.
    result = solve(rename(PLAIN, {"planet": "mesh sun-planet"}))
    split = result.split_powers()
    mesh = Node("mesh", "mesh sun-mesh sun-planet")
    assert split[mesh] == pytest.approx({Node("body", "mesh sun-planet"): 490.0,
                                         Node("body", "carrier"): 495.0}, rel=1e-12)
    assert body_node(result, "frame/ring") == Node("frame", "frame/ring")


def test_cycles_and_splits_on_nodes_not_names() -> None:
    # a body "m" and a mesh node "m": a path m(body) -> m(mesh) is no cycle
    flows = [Flow("motor", "m", 5.0, "motor", "body"), Flow("m", "m", 5.0, "body", "mesh"),
             Flow("m", "g", 4.0, "mesh", "body"), Flow("m", "loss", 1.0, "mesh", "loss"),
             Flow("g", "generator", 4.0, "body", "generator")]
    assert circulating_power(flows) == 0.0
    assert split_powers(flows) == {}             # the loss arrow is not a split
    assert circulating_power([Flow("a", "b", 5.0), Flow("b", "a", 2.0)]) == 2.0
