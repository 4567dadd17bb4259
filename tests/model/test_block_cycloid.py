"""A mesh's ``cycloid: {module, profile_error, shift, rc}`` block (Csobán 2021)."""
from __future__ import annotations

import dataclasses

import pytest

from powergraph.errors import ModelError
from powergraph.model import model_from_dict


def stage(block, disc_teeth=39, ring_teeth=40, ring_internal=True, between=("d", "pins")):
    return {
        "name": "cycloid stage",
        "components": {0: {"role": "frame"}, "H": {}, "d": {"teeth": disc_teeth},
                       "pins": {"teeth": ring_teeth, "internal": ring_internal},
                       "out": {}},
        "links": [{"type": "mesh", "between": list(between), "carrier": "H",
                   "cycloid": block},
                  {"type": "fixed", "between": ["pins", 0]},
                  {"type": "coupling", "between": ["d", "out"]}],
        "ports": [{"component": "H", "role": "input"}, {"component": "out", "role": "output"}],
    }


def test_valid_block_with_defaults_and_units() -> None:
    model = model_from_dict(stage({"module": 3, "profile_error": "4.5 um"}))
    block = model.links[0].blocks["cycloid"]
    assert (block.module, block.shift, block.rc) == (3.0, 0.3, 1.0)
    assert block.profile_error == pytest.approx(0.0045, rel=1e-12)
    assert (block.disc, block.ring, block.teeth) == ("d", "pins", 39)
    with pytest.raises(dataclasses.FrozenInstanceError):
        block.module = 1.0


def test_disc_found_whatever_the_order() -> None:
    model = model_from_dict(stage({"module": 1, "profile_error": 0.01, "shift": 0.25,
                                   "rc": 0.8}, between=("pins", "d")))
    block = model.links[0].blocks["cycloid"]
    assert (block.disc, block.ring, block.shift, block.rc) == ("d", "pins", 0.25, 0.8)


@pytest.mark.parametrize("block, where", [
    ({"module": 1, "profile_error": 0.01, "teeth": 9}, "links[0].cycloid.teeth"),
    ({"profile_error": 0.01}, "links[0].cycloid.module"),
    ({"module": 1}, "links[0].cycloid.profile_error"),
    ({"module": "one", "profile_error": 0.01}, "links[0].cycloid.module"),
    ({"module": True, "profile_error": 0.01}, "links[0].cycloid.module"),
    ({"module": -1, "profile_error": 0.01}, "links[0].cycloid.module"),
    ({"module": 1, "profile_error": -0.01}, "links[0].cycloid.profile_error"),
    ({"module": 1, "profile_error": 0.01, "shift": 1.2}, "links[0].cycloid.shift"),
    ({"module": 1, "profile_error": 0.01, "shift": "0.3"}, "links[0].cycloid.shift"),
    ({"module": 1, "profile_error": 0.01, "rc": 0}, "links[0].cycloid.rc"),
    ({"module": 1, "profile_error": float("inf")}, "links[0].cycloid.profile_error"),
    ({"module": "1 kg", "profile_error": 0.01}, "links[0].cycloid.module"),
    ([1, 0.01], "links[0].cycloid"),
])
def test_bad_blocks_name_their_place(block, where) -> None:
    with pytest.raises(ModelError) as info:
        model_from_dict(stage(block))
    assert info.value.path == where


@pytest.mark.parametrize("teeth, internal", [((39, 41), True), ((2, 3), True),
                                              ((39, 40), False)])
def test_mesh_must_be_a_cycloid_pair(teeth, internal) -> None:
    with pytest.raises(ModelError) as info:
        model_from_dict(stage({"module": 1, "profile_error": 0.01}, *teeth,
                              ring_internal=internal))
    assert info.value.path == "links[0].cycloid"
