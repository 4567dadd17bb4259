"""Shift elements and the modes table in the model (powergraph.model.shift,
docs/modes.md, docs/format.md): what is accepted, what is refused and where."""
from __future__ import annotations

import copy

import pytest

from powergraph.errors import ModelError
from powergraph.model import model_from_dict

BASE = {
    "name": "two-speed",
    "components": {0: {"role": "frame"}, "s": {"teeth": 24}, "p": {"teeth": 24},
                   "r": {"teeth": 72, "internal": True}, "c": {}},
    "links": [{"type": "mesh", "between": ["s", "p"], "carrier": "c"},
              {"type": "mesh", "between": ["p", "r"], "carrier": "c"},
              {"type": "clutch", "name": "C", "between": ["s", "r"]},
              {"type": "brake", "name": "B", "between": ["r", 0]},
              {"type": "freewheel", "name": "F", "between": ["r", 0], "holds": "positive"}],
    "ports": [{"component": "s", "role": "input", "speed": 100.0},
              {"component": "c", "role": "output"}],
}


def build(**changes):
    data = copy.deepcopy(BASE)
    for key, value in changes.items():
        data[key] = value
    return model_from_dict(data)


def with_link(index: int, **fields):
    data = copy.deepcopy(BASE)
    data["links"][index] = {**data["links"][index], **fields}
    return data


def refused(data, path: str, words: str) -> None:
    with pytest.raises(ModelError) as info:
        model_from_dict(data)
    assert info.value.path == path and words in info.value.message, str(info.value)


def test_elements_are_read_and_open_by_default() -> None:
    model = build()
    assert [(e.name, e.kind, e.engaged) for e in model.shift_elements] == [
        ("C", "clutch", False), ("B", "brake", False), ("F", "freewheel", False)]
    assert [link.type for link in model.links[2:]] == ["bearing"] * 3
    assert model.mode is None and not model.modes


def test_engaged_makes_a_rigid_joint_like_fixed() -> None:
    model = model_from_dict(with_link(3, engaged=True))
    assert model.links[3].type == "fixed"
    assert model.body_of["r"] == model.body_of["0"]


def test_with_modes_the_model_is_in_its_first_mode_with_freewheels_holding() -> None:
    model = build(modes={"low": [], "high": ["C"]})
    assert model.mode == "low" and dict(model.modes) == {"low": (), "high": ("C",)}
    assert model.body_of["r"] == model.body_of["0"]         # F holding
    assert model.links[2].type == "bearing"                # C open


def test_names_are_required_and_unique() -> None:
    data = with_link(3)
    del data["links"][3]["name"]
    refused(data, "links[3].name", "missing")
    refused(with_link(3, name="C"), "links[3].name", "'C' is used twice")


def test_a_brake_must_hold_against_the_frame_and_a_clutch_must_not() -> None:
    refused(with_link(3, between=["r", "c"]), "links[3].between[1]", "against the frame")
    refused(with_link(2, between=["s", 0]), "links[2].type", "a brake")


def test_a_freewheel_needs_its_sign() -> None:
    data = with_link(4)
    del data["links"][4]["holds"]
    refused(data, "links[4].holds", "missing")
    refused(with_link(4, holds="forward"), "links[4].holds", "")


def test_modes_name_known_clutches_and_brakes_once() -> None:
    data = copy.deepcopy(BASE)
    data["modes"] = {"1": ["C", "X"]}
    refused(data, "modes.1[1]", "unknown shift element 'X'")
    data["modes"] = {"1": ["F"]}
    refused(data, "modes.1[0]", "freewheel")
    data["modes"] = {"1": ["C", "C"]}
    refused(data, "modes.1[1]", "twice")


def test_modes_need_shift_elements() -> None:
    data = copy.deepcopy(BASE)
    data["links"] = data["links"][:2] + [{"type": "fixed", "between": ["r", 0]}]
    data["modes"] = {"1": []}
    refused(data, "modes", "needs shift elements")


def test_a_first_mode_holding_the_input_is_refused_at_load_naming_the_mode() -> None:
    data = copy.deepcopy(BASE)
    data["links"].append({"type": "brake", "name": "BS", "between": ["s", 0]})
    data["modes"] = {"bad": ["BS"]}
    refused(data, "modes.bad", "engages BS: component 's' is fixed to the frame")


def test_drag_on_an_open_element_is_a_bearing_drag() -> None:
    model = model_from_dict(with_link(2, drag={"no_load_torque": "0.5 N*m"}))
    assert model.links[2].type == "bearing"
    assert model.links[2].blocks["drag"].a == 0.5
    assert model.has_bearing_losses
