"""A REXS file as a model file and points (powergraph.exchange.rexs_import): the YAML
names what was not mapped and loads back to the same model; the points need every
column in every load case."""
from __future__ import annotations

from pathlib import Path

import pytest

import powergraph as pg
from powergraph.errors import ModelError
from powergraph.exchange.rexs_import import import_rexs, model_yaml, points_csv

DATA = Path(__file__).resolve().parent / "data"


def test_model_yaml_loads_back_to_the_same_model() -> None:
    result = import_rexs(DATA / "two_stage_helical.rexs", 0.99)
    text = model_yaml(result, "two_stage_helical.rexs")
    assert text.startswith("# Imported from two_stage_helical.rexs")
    assert "#   cylindrical_gear: tip_diameter" in text
    from powergraph.model import loads_model

    assert loads_model(text, "x") == pg.model_from_dict(result.data, source="x")


def test_points_need_every_column_in_every_case() -> None:
    with pytest.raises(ModelError, match="load case 2 gives no a.speed"):
        points_csv(({"duration [s]": 1.0, "a.speed [rpm]": 1.0}, {"duration [s]": 1.0}))
    with pytest.raises(ModelError, match="no load spectrum"):
        points_csv(())


def test_a_file_without_a_valid_train_fails_on_import(tmp_path: Path) -> None:
    path = tmp_path / "empty.rexs"
    path.write_text("<model version='1.4'><relations/><components>"
                    "<component id='1' type='gear_casing' name='c'/></components></model>")
    with pytest.raises(ModelError):
        import_rexs(path)
