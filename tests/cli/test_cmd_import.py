"""``powergraph import FILE.rexs -o MODEL.yaml [--points POINTS.csv]``: the written model
solves to the hand-derived ratio (58/17)(67/19) of the two-stage unit
(tests/model/test_rexs_reader.py), the points run through ``powergraph cycle``, the
summary names what was not mapped, and every bad file is one line and exit status 2."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

import powergraph as pg
from powergraph.testing import assert_conservation

DATA = Path(__file__).resolve().parents[1] / "exchange" / "data"
HELICAL = DATA / "two_stage_helical.rexs"


def test_import_writes_a_model_and_points(cli, tmp_path: Path) -> None:
    model, points = tmp_path / "unit.yaml", tmp_path / "unit.csv"
    status, out, err = cli("import", str(HELICAL), "-o", str(model), "--points", str(points),
                           "--mesh-efficiency", "0.97")
    assert status == 0, err
    assert f"wrote {model}" in out and f"wrote {points}" in out
    assert "not mapped from" in out and "cylindrical_gear: tip_diameter" in out
    result = pg.solve(pg.load_model(model))
    assert_conservation(result)
    assert result.ratio == pytest.approx((58 / 17) * (67 / 19), rel=1e-12)
    assert result.efficiency == pytest.approx(0.97 ** 2, rel=1e-12)
    status, out, err = cli("cycle", str(model), "--points", str(points), "--json")
    assert status == 0, err
    cycle = json.loads(out)
    assert [row["duration"] for row in cycle["rows"]] == [2700.0, 900.0]
    assert cycle["efficiency"] == pytest.approx(0.97 ** 2, rel=1e-9)


def _bad(tmp_path: Path, text: str, suffix: str = ".rexs") -> Path:
    path = tmp_path / f"bad{suffix}"
    path.write_text(text, encoding="utf-8")
    return path


@pytest.mark.parametrize("text, words", [
    ("<gearbox><part/></gearbox>", "not a REXS file"),
    ("<model version='1.4'><relations><relation id='4' type='weld'/></relations>"
     "<components/></model>", "unknown relation type 'weld'"),
    ("<model version='1.4'><relations><relation id='4' type='assembly'>"
     "<ref hint='shaft' id='77' role='assembly'/></relation></relations><components/>"
     "</model>", "component 77, which is not in the file"),
    ("<model version='1.4'><components><component id='1'", "not well-formed XML"),
])
def test_bad_files_are_one_line_and_status_2(cli, tmp_path: Path, text: str, words: str) -> None:
    path = _bad(tmp_path, text)
    status, out, err = cli("import", str(path), "-o", str(tmp_path / "m.yaml"))
    lines = err.strip().splitlines()
    assert status == 2 and len(lines) == 1 and "Traceback" not in err, err
    assert str(path) in lines[0] and words in lines[0]
    assert not (tmp_path / "m.yaml").exists()


def test_a_too_large_file_is_refused(cli, tmp_path: Path) -> None:
    status, out, err = cli("--max-model-size", "1k", "import", str(HELICAL),
                           "-o", str(tmp_path / "m.yaml"))
    assert status == 2 and len(err.strip().splitlines()) == 1, err
    assert "1000" in err or "limit" in err or "larger" in err


def test_a_file_that_is_not_named_rexs_is_refused(cli, tmp_path: Path) -> None:
    status, out, err = cli("import", str(_bad(tmp_path, "x", ".xml")), "-o",
                           str(tmp_path / "m.yaml"))
    assert status == 2 and "not a REXS file name" in err
