"""A bearing's ``friction: {mu, bore}`` and ``drag:`` blocks, and a component's ``drag:``
(docs/losses.md): values, units, and errors naming their place."""
from __future__ import annotations

import copy
import math

import pytest

from powergraph.cli.main import main
from powergraph.errors import ModelError
from powergraph.model import loads_model, model_from_dict
from powergraph.model.block_bearing import BearingFriction, Drag


def train() -> dict:
    return {"name": "pair",
            "components": {0: {"role": "frame"},
                           1: {"teeth": 20, "geometry": {"module": 2, "face_width": 10,
                                                         "bore_radius": 0}},
                           2: {"teeth": 40, "drag": {"no_load_torque": "0.5 N*m"}}},
            "links": [{"type": "mesh", "between": [1, 2], "efficiency": 0.98},
                      {"type": "bearing", "between": [1, 0],
                       "friction": {"mu": 0.0015, "bore": "2 cm"},
                       "drag": {"a": "100 N*mm", "b": 0.002}}],
            "ports": [{"component": 1, "role": "input", "speed": 100, "power": 1000},
                      {"component": 2, "role": "output"}]}


def test_blocks_are_read_with_units() -> None:
    model = model_from_dict(train())
    assert model.links[1].blocks["friction"] == BearingFriction(mu=0.0015, bore=20.0)
    drag = model.links[1].blocks["drag"]
    assert drag.a == pytest.approx(0.1, rel=1e-12) and drag.b == 0.002
    assert model.components["2"].drag == Drag(0.5)
    assert model.has_bearing_losses


def test_drag_laws_by_hand() -> None:
    # 0.1 N·m + 0.002 N·m/rpm · 1000 rpm = 2.1 N·m, whichever the sense of rotation.
    drag = Drag(0.1, 0.002)
    assert drag.torque(1000 * 2 * math.pi / 60) == pytest.approx(2.1, rel=1e-12)
    assert drag.torque(-1000 * 2 * math.pi / 60) == pytest.approx(2.1, rel=1e-12)
    # 0.0015 · 2000 N · 20 mm / 2 = 0.03 N·m
    assert BearingFriction(0.0015, 20.0).torque(2000.0) == pytest.approx(0.03, rel=1e-12)


def test_plain_bearings_keep_their_meaning() -> None:
    data = train()
    del data["links"][1]["friction"], data["links"][1]["drag"], data["components"][2]["drag"]
    model = model_from_dict(data)
    assert not model.links[1].blocks and not model.has_bearing_losses


@pytest.mark.parametrize("change, path, fragment", [
    (lambda d: d["links"][1]["friction"].update(mu=-0.1), "links[1].friction.mu", "mu must"),
    (lambda d: d["links"][1]["friction"].update(mu=float("nan")), "links[1].friction.mu",
     "finite"),
    (lambda d: d["links"][1]["friction"].pop("bore"), "links[1].friction.bore", "bore"),
    (lambda d: d["links"][1]["friction"].update(bore="-3 mm"), "links[1].friction.bore", ">= 0"),
    (lambda d: d["links"][1]["friction"].update(colour=1), "links[1].friction.colour",
     "unknown field"),
    (lambda d: d["links"][1]["drag"].update(no_load_torque=1), "links[1].drag.a", "not both"),
    (lambda d: d["links"][1]["drag"].update(a="1 rpm"), "links[1].drag.a", "torque"),
    (lambda d: d["links"][1]["drag"].update(b=-1), "links[1].drag.b", ">= 0"),
    (lambda d: d["links"][1]["drag"].update(b=float("inf")), "links[1].drag.b", "finite"),
    (lambda d: d["links"][1].update(drag={}), "links[1].drag", "at least"),
    (lambda d: d["links"][1].update(drag=3), "links[1].drag", "mapping"),
    (lambda d: d["components"][2]["drag"].update(speed=2), "components.2.drag.speed",
     "unknown field"),
    (lambda d: d["components"][0].update(drag={"a": 1}), "components.0.drag", "frame"),
    (lambda d: d["links"][0].update(drag={"a": 1}), "links[0].drag", "unknown field"),
    (lambda d: d["links"].append({"type": "fixed", "between": [2, 0], "friction": {}}),
     "links[2].friction", "unknown field"),
    (lambda d: d["components"][1].pop("geometry"), "links[1].friction", "pitch radius"),
])
def test_bad_blocks_name_the_place(change, path, fragment) -> None:
    data = copy.deepcopy(train())
    change(data)
    with pytest.raises(ModelError, match=fragment) as info:
        model_from_dict(data)
    assert str(info.value).startswith(path), str(info.value)


def test_check_command_exits_2_with_one_line(tmp_path, capsys) -> None:
    path = tmp_path / "bad.yaml"
    path.write_text("name: x\ncomponents: {0: {role: frame}, 1: {teeth: 20}, 2: {teeth: 40}}\n"
                    "links:\n  - {type: mesh, between: [1, 2]}\n"
                    "  - {type: bearing, between: [1, 0], drag: {no_load_torque: -1}}\n"
                    "ports: [{component: 1, role: input}, {component: 2, role: output}]\n")
    assert main(["check", str(path)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "links[1].drag.no_load_torque" in err[0]


def test_a_body_without_meshes_needs_no_radius() -> None:
    # The carried member (a carrier) has no gears in mesh: F = 0, its friction is allowed.
    model = loads_model("""
name: carrier bearing
components: {0: {role: frame}, 1: {teeth: 20}, 2: {teeth: 30}, 3: {teeth: 80, internal: true}, 4: {}}
links:
  - {type: mesh, between: [1, 2], carrier: 4}
  - {type: mesh, between: [2, 3], carrier: 4}
  - {type: fixed, between: [3, 0]}
  - {type: bearing, between: [4, 0], friction: {mu: 0.001, bore: 40 mm}}
ports: [{component: 1, role: input}, {component: 4, role: output}]
""")
    assert model.links[3].blocks["friction"].bore == 40.0
