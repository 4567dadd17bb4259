"""``powergraph map MODEL --torque A:B:N --speed C:D:N [--rated T] [-o FILE] [--json]
[--loss-map FILE]``, both sides: driving (torque > 0) and coasting (torque < 0).

Expected values: the pair z 20 → 40 with η = 0.98 (i = 2), derived in
tests/analyses/test_efficiency_map.py: coasting at −T the input torque is −η·T/i and the
torque loss (1 − η)·T/i; driving at T, T/(i·η) and T·(1/η − 1)/i.
"""
from __future__ import annotations

import io
import json
from contextlib import redirect_stderr, redirect_stdout
from pathlib import Path

import numpy as np
import pytest

from powergraph.cli.main import main

ROOT = Path(__file__).resolve().parents[2]
RV = str(ROOT / "models" / "rv40e.yaml")
PAIR = {"name": "pair", "components": {0: {"role": "frame"}, 1: {"teeth": 20}, 2: {"teeth": 40}},
        "links": [{"type": "mesh", "between": [1, 2], "efficiency": 0.98}],
        "ports": [{"component": 1, "role": "input", "speed": 100.0},
                  {"component": 2, "role": "output"}]}
ISO_PAIR = {"name": "iso pair", "components": {0: {"role": "frame"}, 1: {"teeth": 20},
                                               2: {"teeth": 40}},
            "links": [{"type": "mesh", "between": [1, 2],
                       "friction": {"model": "iso14179", "viscosity": 30, "roughness": 0.5},
                       "geometry": {"module": 2, "face_width": 20}}],
            "ports": [{"component": 1, "role": "input", "speed": 100.0, "power": 1000.0},
                      {"component": 2, "role": "output"}]}


def run(*argv: str) -> tuple[int, str, str]:
    """``powergraph map ...`` in-process: (status, stdout, stderr); argparse exits too."""
    out, err = io.StringIO(), io.StringIO()
    with redirect_stdout(out), redirect_stderr(err):
        try:
            status = main(["map", *argv])
        except SystemExit as exc:
            status = int(exc.code)
    return status, out.getvalue(), err.getvalue()


def _model(tmp_path, data: dict) -> str:
    path = tmp_path / f"{data['name'].replace(' ', '_')}.yaml"
    path.write_text(json.dumps(data))
    return str(path)


def test_json_and_picture(tmp_path) -> None:
    picture = tmp_path / "map.png"
    status, out, err = run(_model(tmp_path, ISO_PAIR), "--torque", "20:200:4", "--speed",
                           "500:3000:3", "--rated", "150", "--json", "-o", str(picture))
    assert status == 0, err
    data = json.loads(out)
    assert len(data["efficiency"]) == 3 and len(data["efficiency"][0]) == 4
    assert data["rated_torque"] == 150 and data["load_dependent"] is True
    assert data["sides"] == ["driving"] * 4 and data["notes"] == []
    assert picture.stat().st_size > 1000


def test_a_negative_torque_span_maps_both_sides_and_writes_both_quadrants(tmp_path) -> None:
    target = tmp_path / "pair.vtlm"
    status, out, err = run(_model(tmp_path, PAIR), "--torque=-20:20:5", "--speed",
                           "1000:2000:2", "--loss-map", str(target))
    assert status == 0, err
    lines = out.splitlines()
    assert lines[1].split() == ["side", "coasting", "coasting", "no", "load", "driving",
                                "driving"]
    assert lines[3].split()[1:] == ["98.000", "98.000", "-", "98.000", "98.000"]
    assert any(line.startswith("torque < 0: coasting, the output drives") for line in lines)
    assert "(10 points: 4 driving, 4 coasting, 2 no load)" in out
    rows = target.read_text().splitlines()
    assert rows[0] == "Input Speed [rpm],Input Torque [Nm],Torque Loss [Nm]"
    table = np.array([[float(x) for x in row.split(",")] for row in rows[1:]])
    output = np.tile([-20.0, -10.0, 0.0, 10.0, 20.0], 2)
    assert np.allclose(table[:, 1], np.where(output < 0, 0.98 * output / 2,
                                             output / (2 * 0.98)), rtol=1e-9)
    assert np.all(table[:, 2] >= 0)                                    # never negative
    assert np.any(table[:, 1] < 0) and np.any(table[:, 1] > 0)         # both quadrants
    assert np.allclose((table[:, 1] - table[:, 2]) * 2, output, rtol=1e-9, atol=1e-12)


def test_the_figure_names_both_sides_and_marks_self_locking_points(tmp_path) -> None:
    # Wang's RV-40E self-locks coasting: both sides flat (constant efficiencies), each
    # written in its half, the coasting side's points crossed, the no-load line between.
    import matplotlib

    matplotlib.use("Agg")
    from powergraph.analyses.efficiency_map import efficiency_map
    from powergraph.model import load_model

    emap = efficiency_map(load_model(ROOT / "models" / "rv40e_wang2021.yaml"),
                          [-400.0, -200.0, 0.0, 200.0, 400.0], [500.0, 1500.0])
    ax = emap.plot()
    texts = [t.get_text() for t in ax.texts]
    assert "coasting (output drives)" in texts and "driving (input drives)" in texts
    assert any(t.startswith("self-locking: efficiency 0 %") for t in texts)
    assert any(t.startswith("efficiency 28.738 %") for t in texts)
    labels = ax.get_legend_handles_labels()[1]
    assert "self-locking (no power comes out)" in labels
    assert "no load (efficiency undefined)" in labels
    assert ax.get_xlim() == (-400.0, 400.0)
    picture = tmp_path / "coasting.png"
    status, _, err = run(_model(tmp_path, PAIR), "--torque=-20:20:5", "--speed",
                         "1000:2000:2", "-o", str(picture))
    assert status == 0 and picture.stat().st_size > 1000, err


def test_json_of_a_coasting_map_names_its_sides_and_undefined_points(tmp_path) -> None:
    status, out, err = run(RV, "--torque=-400:400:3", "--speed", "1000", "--json")
    assert status == 0, err
    data = json.loads(out)
    assert data["sides"] == ["coasting", "no load", "driving"]
    assert data["efficiency"][0][1] is None and 0.8 < data["efficiency"][0][0] < 0.9
    assert data["self_locking"] == [] and len(data["notes"]) == 2


@pytest.mark.parametrize("args, fragment", [
    (["--torque", "-20:20:5", "--speed", "100"],
     "argument --torque: expected one argument; a value that starts with - is written "
     "--torque=VALUE"),
    (["--torque=-20:20:x", "--speed", "100"], "START:STOP:N"),
    (["--torque=-20:20", "--speed", "100"], "expected START:STOP:N or one value"),
    (["--torque=-1e13:0:3", "--speed", "100"], "must be at least -1e+12"),
    (["--torque=nan:-1:3", "--speed", "100"], "must be finite"),
    (["--torque=-20:20:0", "--speed", "100"], "whole number from 1 to 500"),
    (["--torque=-10", "--speed", "0"], "non-zero"),
])
def test_bad_spans_exit_2_with_one_line(tmp_path, args, fragment) -> None:
    status, out, err = run(_model(tmp_path, ISO_PAIR), *args)
    assert status == 2 and out == "", err
    assert err.count("\n") == 1 and "Traceback" not in err
    assert err.startswith("powergraph: error: ") and fragment in err


def test_a_negative_single_torque_needs_no_equals_sign(tmp_path) -> None:
    status, out, err = run(_model(tmp_path, PAIR), "--torque", "-10", "--speed", "1000")
    assert status == 0, err
    assert "coasting" in out and "98.000" in out
