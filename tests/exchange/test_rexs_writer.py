"""A train written as REXS (powergraph.exchange.rexs_writer) and read back: the same
ratio, efficiency and every mesh loss (the conservation law closes both solves), through
XML and JSON. What a model holds beyond REXS is named, not dropped."""
from __future__ import annotations

from pathlib import Path

import pytest

import powergraph as pg
from powergraph.errors import ModelError
from powergraph.exchange.rexs_text import to_json, to_xml
from powergraph.exchange.rexs_writer import rexs_export
from powergraph.statics.case import TrainCase
from powergraph.testing import assert_conservation

MODELS = Path(__file__).resolve().parents[2] / "models"
ROUND_TRIP = [("planetary_2kh_two_stages.yaml", None), ("rv40e_wang2021.yaml", None),
              ("planetary_double_planet.yaml", None), ("planetary_stepped.yaml", None),
              ("wolfrom_3k.yaml", None), ("simpson_3speed.yaml", "1"),
              ("simpson_3speed.yaml", "R")]


def _read_back(model, mode, tmp_path: Path, suffix: str):
    export = rexs_export(model, mode)
    path = tmp_path / f"unit{suffix}"
    path.write_text((to_xml if suffix == ".rexs" else to_json)(export.document),
                    encoding="utf-8")
    return pg.load_model(path), export


@pytest.mark.parametrize("suffix", [".rexs", ".rexsj"])
@pytest.mark.parametrize("name, mode", ROUND_TRIP)
def test_round_trip_keeps_ratio_efficiency_and_mesh_losses(name, mode, suffix, tmp_path):
    model = pg.load_model(MODELS / name)
    before = pg.solve(TrainCase.of(model, mode).plain_model() if mode else model)
    back, _ = _read_back(model, mode, tmp_path, suffix)
    after = pg.solve(back)
    assert_conservation(before)
    assert_conservation(after)
    scale = abs(before.input_power)
    assert after.ratio == pytest.approx(before.ratio, rel=1e-9)
    assert after.efficiency == pytest.approx(before.efficiency, rel=1e-9)
    assert [m.loss for m in after.meshes] == pytest.approx(
        [m.loss for m in before.meshes], rel=1e-9, abs=1e-9 * scale)
    assert after.total_loss == pytest.approx(before.total_loss, rel=1e-9, abs=1e-9 * scale)


def test_planetary_relations_are_written() -> None:
    document = rexs_export(pg.load_model(MODELS / "planetary_2kh_two_stages.yaml")).document
    kinds = [r.type for r in document.relations]
    # two carriers: two planetary stages, each with its carrier shaft, planet and sun
    assert kinds.count("planet_carrier_shaft") == 2
    assert kinds.count("planet_shaft") == 2
    stages = [c for c in document.components.values() if c.type == "planetary_stage"]
    assert [s.attributes["number_of_planets"][0] for s in stages] == [3, 3]
    rings = [c for c in document.components.values() if c.type == "cylindrical_gear"
             and c.attributes["number_of_teeth"][0] < 0]
    assert len(rings) == 2                        # internal gears: negative teeth


def test_what_rexs_cannot_hold_is_listed() -> None:
    unmapped = rexs_export(pg.load_model(MODELS / "rv40e.yaml")).unmapped
    assert "links[6].friction" in unmapped        # crank bearing friction
    assert "links[7].drag" in unmapped
    assert "thermal" in unmapped
    assert any(line.startswith("links[0].friction: written as the basic efficiency")
               for line in unmapped)


def test_shift_elements_need_a_mode() -> None:
    with pytest.raises(ModelError, match="name the mode"):
        rexs_export(pg.load_model(MODELS / "simpson_3speed.yaml"))


def test_an_imported_unit_keeps_its_geometry_through_export(tmp_path: Path) -> None:
    # the hand-written two-stage unit: stage 1 with shifts, stage 2 with a centre distance
    from powergraph.model.rexs_reader import read_rexs

    data = Path(__file__).resolve().parent / "data" / "two_stage_helical.rexs"
    model = pg.model_from_dict(read_rexs(data, mesh_efficiency=0.98).data)
    back, _ = _read_back(model, None, tmp_path, ".rexs")
    assert [link.blocks["geometry"] for link in back.meshes] == [
        link.blocks["geometry"] for link in model.meshes]
    before, after = pg.solve(model), pg.solve(back)
    assert_conservation(after)
    assert [m.loss for m in after.meshes] == pytest.approx([m.loss for m in before.meshes],
                                                           rel=1e-9)
