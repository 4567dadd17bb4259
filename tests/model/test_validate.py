"""Every malformed model is refused with a ModelError naming its place (data file driven)."""
from __future__ import annotations

import re
from pathlib import Path

import pytest
import yaml

import powergraph as pg
from powergraph.errors import ModelError
from powergraph.model import loads_model

DATA = Path(__file__).resolve().parents[1] / "data"
MALFORMED = yaml.safe_load((DATA / "malformed.yaml").read_text())
UNSOLVABLE = yaml.safe_load((DATA / "unsolvable.yaml").read_text())


@pytest.mark.parametrize("case", MALFORMED, ids=[c["id"] for c in MALFORMED])
def test_malformed_model_names_its_place(case: dict) -> None:
    with pytest.raises(ModelError) as info:
        loads_model(case["text"], source="<model>")
    message = str(info.value)
    assert re.search(case["match"], message), message
    if case["path"]:
        assert info.value.path == case["path"], message
        assert message.startswith(case["path"] + ": ")


@pytest.mark.parametrize("case", UNSOLVABLE, ids=[c["id"] for c in UNSOLVABLE])
def test_unsolvable_train_is_a_model_error(case: dict) -> None:
    model = loads_model(case["text"])
    with pytest.raises(ModelError, match=case["match"]):
        pg.solve(model)


def test_valid_model_is_immutable_and_keeps_ids() -> None:
    model = pg.load_model(Path(__file__).resolve().parents[2] / "models" / "rv40e_wang2021.yaml")
    assert [b.id for b in model.bodies] == ["0/5", "1", "2/3", "4", "6/7"]
    assert model.components["5"].internal and model.components["2"].count == 2
    with pytest.raises(Exception):
        model.name = "x"  # frozen dataclass
    with pytest.raises(TypeError):
        model.components["9"] = None  # read-only mapping


def test_mesh_carrier_defaults_to_frame_and_efficiency_to_defaults() -> None:
    model = loads_model("""
name: pair
defaults: {mesh_efficiency: 0.97}
components: {0: {role: frame}, 1: {teeth: 20}, 2: {teeth: 40}}
links: [{type: mesh, between: [1, 2]}]
ports: [{component: 1, role: input}, {component: 2, role: output}]
""")
    assert model.links[0].carrier == "0" and model.links[0].efficiency == 0.97


def test_network_view_has_components_as_nodes_and_links_as_edges() -> None:
    from powergraph.model import to_networkx

    model = pg.load_model(Path(__file__).resolve().parents[2] / "models" / "rv40e_wang2021.yaml")
    graph = to_networkx(model)
    assert set(graph.nodes) == set(model.components)
    assert graph.number_of_edges() == len(model.links)
    assert graph.edges["4", "5", 1]["carrier"] == "3"
