"""Resolving a model in a mode (powergraph.model.modes): engaged elements become `fixed`
links, open ones `bearing`s, so the bodies are those of the same gear written by hand."""
from __future__ import annotations

from pathlib import Path

import pytest

from powergraph.errors import ModelError
from powergraph.model import load_model
from powergraph.model.modes import resolve

MODELS = Path(__file__).resolve().parents[2] / "models"


def test_a_mode_has_the_bodies_of_its_gear_written_with_fixed_links() -> None:
    """Ravigneaux 2nd (C1, B1): the input shaft joins the small sun, the large sun the
    housing -- the bodies of models/ravigneaux_second.yaml plus the input shaft."""
    second = resolve(load_model(MODELS / "ravigneaux_4speed.yaml"), "2")
    by_hand = load_model(MODELS / "ravigneaux_second.yaml")
    assert second.mode == "2"
    assert {b.id for b in second.bodies} == {b.id.replace("s1", "in/s1")
                                             for b in by_hand.bodies}
    assert [second.links[e.index].type for e in second.shift_elements] == [
        "fixed", "bearing", "bearing", "fixed", "bearing"]


def test_resolving_never_changes_the_model() -> None:
    model = load_model(MODELS / "ravigneaux_4speed.yaml")
    links, bodies = model.links, model.bodies
    model.in_mode("R")
    assert model.links is links and model.bodies is bodies and model.mode == "1"


def test_an_unknown_mode_lists_the_modes() -> None:
    with pytest.raises(ModelError, match=r"unknown mode '9' \(the model's modes: 1, 2, 3, 4, R\)"):
        resolve(load_model(MODELS / "ravigneaux_4speed.yaml"), "9")


SIMPSON_TEXT = (MODELS / "simpson_3speed.yaml").read_text()


def _simpson_with(lines: list[str]):
    from powergraph.model import loads_model

    extra = "".join(f"  - {line}\n" for line in lines)
    return loads_model(SIMPSON_TEXT.replace("\nmodes:\n", "\n" + extra + "modes:\n"))


def test_issue34_freewheels_on_the_same_two_bodies_are_one_group() -> None:
    """Mode 1 engages C1 (in/r1 one body). F2 written [0, c2] holding negative allows
    w_0 - w_c2 <= 0, i.e. w_c2 - w_0 >= 0: F1's sense (+1) though written reversed
    (orient -1); F3 [c2, 0] negative the opposite sense. G1 [in, s] and G2 [s, r1] join
    the same two bodies once C1 joins in and r1: one group, G2 reversed. B2 engaged
    (mode R) joins c2 to the housing: F1, F2, F3 are idle, in no group."""
    from powergraph.model.modes import freewheel_groups

    model = _simpson_with([
        "{type: freewheel, name: F2, between: [0, c2], holds: negative}",
        "{type: freewheel, name: F3, between: [c2, 0], holds: negative}",
        "{type: freewheel, name: G1, between: [in, s], holds: positive}",
        "{type: freewheel, name: G2, between: [s, r1], holds: positive}"])
    first = freewheel_groups(resolve(model, "1"))
    assert [(g.names, g.orients, g.senses) for g in first] == [
        (("F1", "F2", "F3"), (1, -1, 1), (1, 1, -1)),
        (("G1", "G2"), (1, -1), (1, -1))]
    assert first[0].bodies == (resolve(model, "1").body_of["c2"], "0")
    reverse = freewheel_groups(resolve(model, "R"))     # C2 joins in and s: G1 idle
    assert [g.names for g in reverse] == [("G2",)]


def test_issue34_a_group_label_names_its_members_briefly() -> None:
    from powergraph.model.modes import freewheel_groups

    model = _simpson_with([f"{{type: freewheel, name: F{k}, between: [c2, 0], "
                           "holds: positive}" for k in range(2, 6)])
    (group,) = freewheel_groups(resolve(model, "1"))
    assert group.label == "F1+F2+…+F5 (5 in parallel)"
    assert group.links == tuple(e.index for e in model.shift_elements
                                if e.kind == "freewheel")
