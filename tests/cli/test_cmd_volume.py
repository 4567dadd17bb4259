"""``powergraph volume MODEL [--json] [--plot FILE]``: Pan & Wang (2019), "Volume calculation
of RV reducer" (docs/volume.md). The paper prints no inputs for its volumes, so the
expected values are hand computations of the geometry in models/rv40e_wang2021.yaml."""
from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from powergraph.cli.main import main

ROOT = Path(__file__).resolve().parents[2]
RV40E = str(ROOT / "models" / "rv40e_wang2021.yaml")
# Total of models/rv40e_wang2021.yaml by hand, / π (see tests/analyses/test_volume.py for the parts):
# 972 + 2·7548 + 2·6980 + 2·27058.2 + 31200 + 38882 + 47682
RV40E_TOTAL = math.pi * (972 + 2 * 7548 + 2 * 6980 + 2 * 27058.2 + 31200 + 38882 + 47682)

NO_GEOMETRY = """name: bare
components:
  0: {role: frame}
  1: {teeth: 12}
  2: {teeth: 36}
links: [{type: mesh, between: [1, 2], carrier: 0}]
ports: [{component: 1, role: input}, {component: 2, role: output}]
"""


def run(capsys, *argv: str) -> tuple[int, str, str]:
    status = main(["volume", *argv])
    out, err = capsys.readouterr()
    return status, out, err


def test_json_keys_and_total(capsys) -> None:
    status, out, err = run(capsys, RV40E, "--json")
    assert status == 0, err
    data = json.loads(out)
    assert {"components", "total_mm3"} <= set(data)
    assert set(data["components"]) == {"1", "2", "3", "4", "5", "6", "7"}
    assert data["total_mm3"] == pytest.approx(RV40E_TOTAL, rel=1e-12)
    assert sum(data["components"].values()) == pytest.approx(data["total_mm3"], rel=1e-12)
    # sun: π·B·(m²z²/4 − r²) = π·12·(1.5²·12²/4 − 0)
    assert data["components"]["1"] == pytest.approx(math.pi * 12 * 81, rel=1e-14)
    assert data["parts"]["2"]["count"] == 2
    assert data["parts"]["2"]["shape"] == "gear"
    assert data["parts"]["3"]["exact_profile_mm3"] is None
    assert data["parts"]["1"]["profile_error"] > 0


def test_table(capsys) -> None:
    status, out, err = run(capsys, RV40E)
    assert status == 0, err
    lines = out.splitlines()
    assert lines[0].startswith("RV-40E")
    header = lines[1].split()
    assert header[:4] == ["id", "name", "shape", "eq."]
    for word in ("center gear", "cycloid_disc", "planet_frame_2", "total (Eq. 8)"):
        assert word in out
    assert f"{RV40E_TOTAL:,.1f}" in out
    # aligned: the volume column is right-aligned under its header in every row
    end = lines[1].index("volume mm³") + len("volume mm³")
    rows = [line for line in lines[3:] if line[:1].isdigit()]
    assert len(rows) == 7
    assert all(row[end - 1].isdigit() and row[end:end + 1] in ("", " ") for row in rows)


def test_no_geometry_exits_2_with_a_message(capsys, tmp_path) -> None:
    path = tmp_path / "bare.yaml"
    path.write_text(NO_GEOMETRY)
    status, out, err = run(capsys, str(path))
    assert status == 2
    assert out == ""
    assert "no component has a geometry block" in err
    assert "Traceback" not in err


def test_bad_geometry_exits_2_with_the_path(capsys, tmp_path) -> None:
    path = tmp_path / "bad.yaml"
    path.write_text(NO_GEOMETRY.replace(
        "1: {teeth: 12}", "1: {teeth: 12, geometry: {shape: gear, module: 1.5, "
                          "face_width: 12, bore_radius: 8}}"))
    status, _, err = run(capsys, str(path))
    assert status == 2
    assert "components.1.geometry.bore_radius" in err       # root radius 7.125 mm


def test_plot_writes_the_error_figure(capsys, tmp_path) -> None:
    target = tmp_path / "error.png"
    status, out, err = run(capsys, RV40E, "--json", "--plot", str(target))
    assert status == 0, err
    json.loads(out)                                   # stdout stays pure JSON
    assert target.exists() and target.stat().st_size > 1000
    assert str(target) in err


@pytest.mark.parametrize("name", ["error.txt", "missing_dir/error.png"])
def test_bad_plot_path_exits_2(capsys, tmp_path, name) -> None:
    status, out, err = run(capsys, RV40E, "--plot", str(tmp_path / name))
    assert status == 2
    assert "--plot" in err and out == ""


def test_plot_function_draws_given_numbers() -> None:
    import matplotlib.pyplot as plt

    from powergraph.plot.volume import pitch_circle_error_plot

    ax = pitch_circle_error_plot([12, 13, 14], [0.03, 0.02, 0.01], marks={"sun": (12, 0.03)})
    line = ax.get_lines()[0]
    assert list(line.get_xdata()) == [12, 13, 14]
    assert list(line.get_ydata()) == pytest.approx([3.0, 2.0, 1.0])
    fig, other = plt.subplots()
    assert pitch_circle_error_plot([20], [0.01], ax=other) is other
    plt.close("all")
