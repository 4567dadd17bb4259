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
