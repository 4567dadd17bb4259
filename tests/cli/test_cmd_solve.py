"""`powergraph solve` / `check`: the JSON keys of docs/format.md, exit codes, messages
without tracebacks. RV-40E values: tests/data/published_values.yaml (virtual-power method
worked by hand on Wang (2021)'s Table 1)."""
from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from powergraph.cli.main import main

ROOT = Path(__file__).resolve().parents[2]
RV = str(ROOT / "models" / "rv40e.yaml")
FORMAT_KEYS = {"name", "method", "dof", "ratio", "efficiency", "input_power", "output_power",
             "total_loss", "speeds", "torques", "meshes", "flows", "circulating_power",
             "self_locking"}
PUBLISHED = yaml.safe_load((ROOT / "tests" / "data" / "published_values.yaml").read_text())
MALFORMED = yaml.safe_load((ROOT / "tests" / "data" / "malformed.yaml").read_text())


def run_cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "powergraph.cli.main", *args],
                          capture_output=True, text=True, cwd=ROOT, timeout=60)


def test_solve_json_has_the_spec_keys_and_reference_numbers(capsys) -> None:
    assert main(["solve", RV, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert FORMAT_KEYS <= set(out)
    assert out["method"] == "virtual-power" and out["dof"] == 1 and out["name"] == "RV-40E"
    assert out["ratio"] == pytest.approx(121, rel=1e-12)
    expected = PUBLISHED["rv40e_virtual_power"]["both_094"]
    assert out["efficiency"] == pytest.approx(expected["efficiency"], abs=5e-7)
    assert [m["loss"] for m in out["meshes"]] == pytest.approx(
        [expected["loss_1"], expected["loss_2"]], abs=5e-4)
    assert [m["between"] for m in out["meshes"]] == [[1, 2], [4, 5]]
    assert [m["carrier"] for m in out["meshes"]] == [7, 3]
    assert [m["driver"] for m in out["meshes"]] == [1, 5]
    assert all(m["virtual_power"] >= 0 for m in out["meshes"])
    assert set(out["speeds"]) == {str(i) for i in range(8)}
    assert set(out["torques"]) == {"1", "6", "0"}
    assert out["input_power"] == pytest.approx(out["output_power"] + out["total_loss"])
    assert all({"from", "to", "power", "from_kind", "to_kind"} == set(f) and f["power"] >= 0
               for f in out["flows"])
    assert out["circulating_power"] == 0 and out["self_locking"] is False


def test_mesh_efficiency_override(capsys) -> None:
    assert main(["solve", RV, "--json", "--mesh-efficiency", "1"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["efficiency"] == pytest.approx(1.0, rel=1e-12) and out["total_loss"] == pytest.approx(0, abs=1e-9)


def test_readable_report_mentions_every_mesh_and_efficiency(capsys) -> None:
    assert main(["solve", RV]) == 0
    text = capsys.readouterr().out
    assert "28.7376 %" in text and "1500" in text  # efficiency and input speed in rpm
    assert "135.0744 W" in text and "1.4826 kW" in text


def test_check_reports_dof(capsys) -> None:
    assert main(["check", RV]) == 0
    assert "1 DOF" in capsys.readouterr().out


@pytest.mark.parametrize("case", MALFORMED[:6] + MALFORMED[-8:],
                         ids=[c["id"] for c in MALFORMED[:6] + MALFORMED[-8:]])
def test_malformed_model_exits_2_with_one_line_and_no_traceback(case, tmp_path) -> None:
    path = tmp_path / "bad.yaml"
    path.write_text(case["text"])
    proc = run_cli("solve", str(path))
    assert proc.returncode == 2
    assert "Traceback" not in proc.stderr and proc.stdout == ""
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("powergraph: error: ")
    if case["path"]:
        assert f"{case['path']}: " in lines[0]


@pytest.mark.parametrize("args", [["solve"], ["solve", RV, "--method", "nope"],
                                  ["solve", RV, "--mesh-efficiency", "1.5"],
                                  ["solve", "missing.yaml"], ["frobnicate"]])
def test_bad_arguments_exit_2_without_traceback(args) -> None:
    proc = run_cli(*args)
    assert proc.returncode == 2 and "Traceback" not in proc.stderr


def test_unsolvable_train_exits_2(tmp_path) -> None:
    path = tmp_path / "dof.yaml"
    path.write_text(yaml.safe_load((ROOT / "tests" / "data" / "unsolvable.yaml").read_text())[0]["text"])
    proc = run_cli("solve", str(path), "--json")
    assert proc.returncode == 2
    assert "train has 2 degrees of freedom but 1 speed was given" in proc.stderr


def test_solve_does_not_import_matplotlib_or_sympy() -> None:
    code = ("import sys; from powergraph.cli.main import main; main(['solve', %r, '--json']);"
            "print('MPL' if 'matplotlib' in sys.modules else '', 'SYMPY' if 'sympy' in sys.modules else '', file=sys.stderr)") % RV
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT)
    assert proc.returncode == 0
    assert "MPL" not in proc.stderr and "SYMPY" not in proc.stderr


def test_solve_reports_the_cycloid_fluctuation_at_the_output(capsys) -> None:
    """RV: i_train = 1 + (z2/z1)(1 + i_stage) = 4 + 3 i_stage, so a relative stage deviation
    δ shows at the output as 3 i_stage/i_train δ = (117/121) δ (input speed held)."""
    path = str(ROOT / "models" / "rv40e_profile_error.yaml")
    assert main(["solve", path, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    stage, = out["cycloid_fluctuation"]["stages"]
    assert stage["max_deviation_percent"] == pytest.approx(
        stage["stage_max_deviation_percent"] * 117 / 121, rel=1e-9)
    assert stage["stage_max_deviation_percent"] > 0
    assert out["efficiency"] == pytest.approx(  # the block changes no power
        PUBLISHED["rv40e_virtual_power"]["both_094"]["efficiency"], abs=5e-7)
    assert main(["solve", RV, "--json"]) == 0
    assert "cycloid_fluctuation" not in json.loads(capsys.readouterr().out)
