"""``powergraph export MODEL --to rexs|vgbx -o FILE``: the REXS file solves as the model
did (ratio 20 of models/planetary_2kh_two_stages.yaml: (1 + 3)(1 + 4), its description's
closed form), the ``.vgbx`` names loss maps that exist beside it, and what a format
cannot hold is listed."""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import powergraph as pg
from powergraph.testing import assert_conservation

MODELS = Path(__file__).resolve().parents[2] / "models"


@pytest.mark.parametrize("suffix", [".rexs", ".rexsj"])
def test_export_rexs_solves_as_the_model(cli, tmp_path: Path, suffix: str) -> None:
    target = tmp_path / f"p{suffix}"
    status, out, err = cli("export", str(MODELS / "planetary_2kh_two_stages.yaml"),
                           "--to", "rexs", "-o", str(target))
    assert status == 0, err
    result = pg.solve(pg.load_model(target))
    assert_conservation(result)
    assert result.ratio == pytest.approx(20.0, rel=1e-12)


def test_export_lists_what_rexs_cannot_hold(cli, tmp_path: Path) -> None:
    status, out, err = cli("export", str(MODELS / "rv40e.yaml"), "--to", "rexs",
                           "-o", str(tmp_path / "rv.rexs"))
    assert status == 0, err
    assert "not written to rv.rexs" in out and "links[7].drag" in out


def test_export_vgbx_writes_its_loss_maps(cli, tmp_path: Path) -> None:
    target = tmp_path / "simpson.vgbx"
    status, out, err = cli("export", str(MODELS / "simpson_3speed.yaml"), "--to", "vgbx",
                           "-o", str(target), "--speed", "1000:3000:2", "--torque=-50:100:4")
    assert status == 0, err
    gears = json.loads(target.read_text())["Body"]["Gears"]
    assert [round(g["Ratio"], 9) for g in gears] == [1.0, round(7 / 3, 9), round(4 / 3, 9),
                                                     1.0]
    for gear in gears:
        table = np.loadtxt(target.with_name(gear["LossMap"]), delimiter=",", skiprows=1,
                           ndmin=2)
        assert table.shape[1] == 3 and set(table[:, 0]) <= {1000.0, 3000.0}


def test_bad_export_arguments_are_one_line(cli, tmp_path: Path) -> None:
    model = str(MODELS / "simpson_3speed.yaml")
    for argv, words in (((model, "--to", "rexs", "-o", str(tmp_path / "x.vgbx")), "suffix"),
                        ((model, "--to", "rexs", "-o", str(tmp_path / "x.rexs")), "mode"),
                        ((model, "--to", "vgbx", "-o", str(tmp_path / "x.vgbx"),
                          "--mode", "1"), "--mode")):
        status, out, err = cli("export", *argv)
        assert status == 2 and len(err.strip().splitlines()) == 1 and words in err, err
