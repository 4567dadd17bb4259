"""``powergraph solve MODEL --method wang2021``: the keys of docs/format.md plus the method's
own, and Wang (2021)'s RV-40E ("A calculation method of transmission efficiency for RV
reducer", Table 1, Eqs. 16–20; values in tests/data/published_values.yaml)."""
from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from powergraph.cli.main import main

ROOT = Path(__file__).resolve().parents[2]
RV40E = str(ROOT / "models" / "rv40e_wang2021.yaml")
RENAMED = str(ROOT / "tests" / "data" / "rv_renamed_shuffled.yaml")
SMALL = ROOT / "tests" / "data" / "rv_small.yaml"
PUBLISHED = yaml.safe_load((ROOT / "tests" / "data" / "published_values.yaml").read_text())

FORMAT_KEYS = {"name", "method", "dof", "ratio", "efficiency", "input_power", "output_power",
             "total_loss", "speeds", "torques", "meshes", "flows", "circulating_power",
             "self_locking", "split_power", "virtual_power", "losses", "beta", "alpha"}


def run(capsys, *argv: str) -> tuple[int, str, str]:
    status = main(["solve", *argv])
    out, err = capsys.readouterr()
    return status, out, err


def test_json_reproduces_the_paper(capsys) -> None:
    status, out, err = run(capsys, RV40E, "--method", "wang2021", "--json")
    assert status == 0, err
    data = json.loads(out)
    assert FORMAT_KEYS <= set(data)
    assert data["method"] == "wang2021"
    # The paper's equations exactly (V = 38/39 P, U = P/39, Eqs. 16-20).
    P = 2270.0
    assert data["split_power"] == pytest.approx(38 / 39 * P, abs=1e-6)
    assert data["virtual_power"] == pytest.approx(P / 39, abs=1e-6)
    l1 = P * 0.06
    l2 = (P + P / 39 - l1) * 0.06
    assert data["losses"] == pytest.approx([l1, l2], abs=1e-6)
    assert data["efficiency"] == pytest.approx((P - l1 - l2) / P, abs=1e-9)
    exact, printed = PUBLISHED["wang2021"]["exact"], PUBLISHED["wang2021"]["printed"]
    assert data["split_power"] == pytest.approx(exact["split_power"], abs=5e-5)
    assert data["virtual_power"] == pytest.approx(exact["virtual_power"], abs=5e-6)
    assert data["losses"] == pytest.approx([exact["loss_1"], exact["loss_2"]], abs=5e-6)
    assert data["efficiency"] == pytest.approx(exact["efficiency"], abs=5e-8)
    assert 100 * data["efficiency"] == pytest.approx(printed["efficiency_percent"], abs=0.05)
    assert data["beta"] == pytest.approx(39) and data["alpha"] == pytest.approx(40)
    assert data["ratio"] == pytest.approx(121)
    assert [m["between"] for m in data["meshes"]] == [[1, 2], [4, 5]]
    assert data["virtual_power_efficiency"] == pytest.approx(
        PUBLISHED["rv40e_virtual_power"]["both_094"]["efficiency"], abs=5e-7)


def test_readable_report_shows_both_efficiencies(capsys) -> None:
    status, out, err = run(capsys, RV40E, "--method", "wang2021")
    assert status == 0, err
    assert "88.2062 %" in out and "28.7376 %" in out
    assert "2,211.7949 W" in out and "131.5203 W" in out
    assert "38.7 x P" in out          # (i - 1)·|w3/w1| = 120·39/121 = 38.68


def test_renamed_file_same_numbers(capsys) -> None:
    _, out, _ = run(capsys, RV40E, "--method", "wang2021", "--json")
    reference = json.loads(out)
    status, out, err = run(capsys, RENAMED, "--method", "wang2021", "--json")
    assert status == 0, err
    data = json.loads(out)
    for key in ("split_power", "virtual_power", "efficiency", "beta", "alpha", "ratio"):
        assert data[key] == pytest.approx(reference[key], rel=1e-12), key
    assert data["losses"] == pytest.approx(reference["losses"], rel=1e-12)
    assert data["meshes"][0]["between"] == ["needles", "disc"]


def test_mesh_efficiency_override(capsys) -> None:
    status, out, _ = run(capsys, RV40E, "--method", "wang2021", "--json",
                         "--mesh-efficiency", "0.98")
    assert status == 0
    # The paper's Eqs. (8)-(15): eta = eta1 - (eta1 + 1/beta)(1 - eta2), beta = 39.
    assert json.loads(out)["efficiency"] == pytest.approx(0.98 - (0.98 + 1 / 39) * 0.02,
                                                          rel=1e-12)


@pytest.mark.parametrize("name", ["planetary_2kh_sun_to_carrier.yaml", "khv_involute.yaml"])
def test_non_rv_train_exits_2_with_a_message(capsys, name: str) -> None:
    status, out, err = run(capsys, str(ROOT / "models" / name), "--method", "wang2021")
    assert status == 2
    assert out == ""
    assert "wang2021 method needs an RV-type train" in err
    assert "found" in err and "Traceback" not in err


def test_two_dof_train_exits_2(capsys, tmp_path) -> None:
    data = yaml.safe_load(SMALL.read_text())
    data["links"] = [link for link in data["links"] if link["between"] != [5, 0]]
    data["ports"].append({"component": 5, "role": "input", "speed": 5.0})
    path = tmp_path / "differential.yaml"
    path.write_text(yaml.safe_dump(data))
    status, _, err = run(capsys, str(path), "--method", "wang2021", "--json")
    assert status == 2
    assert "2 input ports" in err


def test_solve_path_does_not_import_matplotlib() -> None:
    code = ("import sys, io, contextlib\n"
            "from powergraph.methods.wang2021 import solve_wang2021\n"
            "from powergraph.model import load_model\n"
            f"solve_wang2021(load_model({RV40E!r})).to_dict()\n"
            "assert 'matplotlib' not in sys.modules, 'matplotlib imported'\n")
    completed = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert completed.returncode == 0, completed.stderr
