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
RV = str(ROOT / "models" / "rv40e_wang2021.yaml")
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
    assert out["method"] == "virtual-power" and out["dof"] == 1 and out["name"] == "RV-40E (Wang 2021)"
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
    assert "28.74 %" in text and "1,500.00" in text  # efficiency and input speed in rpm
    # one unit for the mesh table (kW), the losses of published_values.yaml
    assert "loss kW" in text and "0.13507" in text and "1.48258" in text


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


@pytest.mark.parametrize("name", ["rv40e_wang2021.yaml", "rv40e.yaml"])
def test_solve_loads_no_other_command_nor_numpy_ma_nor_scipy(name) -> None:
    """Start-up: `powergraph solve` registers its own command only, and takes no path that
    imports numpy.ma (np.unique does, 10 ms) or scipy (the friction model's operating
    pressure angle once took scipy.optimize's root finder: 0.35 s)."""
    check = ("import sys\n"
             "from powergraph.cli.main import main\n"
             "assert main(['solve', %r, '--json']) == 0\n"
             "others = sorted(m for m in sys.modules if m.startswith('powergraph.cli.cmd_')"
             " and m != 'powergraph.cli.cmd_solve')\n"
             "print(others, 'numpy.ma' in sys.modules, 'scipy' in sys.modules, file=sys.stderr)"
             ) % str(ROOT / "models" / name)
    proc = subprocess.run([sys.executable, "-c", check], capture_output=True, text=True,
                          cwd=ROOT)
    assert proc.returncode == 0, proc.stderr
    assert proc.stderr.strip().splitlines()[-1] == "[] False False"


def test_cycloid_model_reports_the_fluctuation_at_the_output(capsys) -> None:
    """RV: i_train = 1 + (z2/z1)(1 + i_stage) = 4 + 3 i_stage, so a relative stage deviation
    δ shows at the output as 3 i_stage/i_train δ = (117/121) δ (input speed held).
    ``cycloid --model`` reports it; ``solve --json`` is the result's ``to_dict()`` alone
    and its text points to that command."""
    path = str(ROOT / "models" / "rv40e_profile_error.yaml")
    assert main(["cycloid", "--model", path, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    stage, = out["stages"]
    assert stage["max_deviation_percent"] == pytest.approx(
        stage["stage_max_deviation_percent"] * 117 / 121, rel=1e-9)
    assert stage["stage_max_deviation_percent"] > 0
    assert main(["solve", path, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert "cycloid_fluctuation" not in out
    assert out["efficiency"] == pytest.approx(  # the block changes no power
        PUBLISHED["rv40e_virtual_power"]["both_094"]["efficiency"], abs=5e-7)
    assert main(["solve", path]) == 0
    assert f"powergraph cycloid --model {path}" in capsys.readouterr().out
    assert main(["cycloid", "--model", RV]) == 2       # no cycloid block: one line
    assert "no mesh has a cycloid block" in capsys.readouterr().err


@pytest.mark.parametrize("name, mode, backdrive", [
    ("rv40e.yaml", None, False), ("wolfrom_3k.yaml", None, True),
    ("simpson_3speed.yaml", "2", False), ("ravigneaux_4speed.yaml", "3", True),
    ("ths2_power_split.yaml", None, False)])
def test_solve_json_is_the_case_answers_to_dict(capsys, name, mode, backdrive) -> None:
    """``solve --json`` prints ``to_dict()`` of the case's answer and nothing else."""
    from powergraph.model import load_model
    from powergraph.statics.case import TrainCase

    path = str(ROOT / "models" / name)
    argv = ["solve", path, "--json"] + (["--mode", mode] if mode else []) \
        + (["--backdrive"] if backdrive else [])
    assert main(argv) == 0
    printed = json.loads(capsys.readouterr().out)
    answer = TrainCase.of(load_model(path), mode, backdrive).point().report.to_dict()
    assert printed == json.loads(json.dumps(answer, default=str))


FIRST_RUN = str(ROOT / "models" / "rv40e.yaml")


def test_first_run_is_a_believable_rv40e(capsys) -> None:
    """models/rv40e.yaml has its losses from friction and geometry: a catalogue RV-40E is
    80–90 % efficient at its rating; the report says where the power goes."""
    assert main(["solve", FIRST_RUN, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert 0.75 < out["efficiency"] < 0.95 and out["warnings"] == []
    assert [p["name"] for p in out["ports"]] == ["motor", "arm"]
    assert [p["direction"] for p in out["ports"]] == ["in", "out"]
    # conservation: the ports' powers (positive into the train) add up to the losses,
    # and the losses table to the total loss
    assert sum(p["power"] for p in out["ports"]) == pytest.approx(out["total_loss"], rel=1e-9)
    assert sum(x["power"] for x in out["loss_breakdown"]) == pytest.approx(out["total_loss"],
                                                                        rel=1e-12)
    assert main(["solve", FIRST_RUN]) == 0
    text = capsys.readouterr().out
    assert "where the power goes" in text and "pins" in text and "crank bearings" in text
    assert "121 : 1" in text and "motor" in text and "warning" not in text


def test_json_keeps_every_key_and_adds_ports_and_warnings(capsys) -> None:
    assert main(["solve", RV, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert FORMAT_KEYS | {"ports", "warnings", "formal_efficiency", "efficiency_note",
                          "loss_breakdown", "passes", "load_sharing_assumed"} <= set(out)
    for port in out["ports"]:
        assert set(port) == {"component", "name", "role", "speed", "torque", "power",
                             "direction"}
        assert port["power"] == pytest.approx(port["torque"] * port["speed"], rel=1e-12)
    assert [p["component"] for p in out["ports"]] == [1, 6]    # ids as in the file
    assert out["formal_efficiency"] == pytest.approx(out["efficiency"], rel=1e-12)


def _with_pin_mesh(tmp_path, efficiency: float) -> str:
    text = Path(RV).read_text().replace(
        "{type: mesh, between: [4, 5], carrier: 3, efficiency: 0.94}",
        f"{{type: mesh, between: [4, 5], carrier: 3, efficiency: {efficiency}}}")
    assert str(efficiency) in text
    path = tmp_path / "rv.yaml"
    path.write_text(text)
    return str(path)


def test_backdrive_reports_the_backdriven_train(capsys, tmp_path) -> None:
    """Published (tests/data/published_values.yaml): first stage 0.94, pin mesh 0.998,
    back-driven 0.867490."""
    path = _with_pin_mesh(tmp_path, 0.998)
    assert main(["solve", path, "--backdrive", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    expected = PUBLISHED["rv40e_virtual_power"]["backdriven_needle_0998"]["efficiency"]
    assert out["efficiency"] == pytest.approx(expected, abs=5e-7)
    assert out["name"].endswith("(back-driven)")
    assert [p["role"] for p in out["ports"]] == ["output", "input"]
    assert [p["direction"] for p in out["ports"]] == ["out", "in"]
    assert main(["solve", path, "--backdrive"]) == 0
    assert "1 : 121" in capsys.readouterr().out


def test_backdrive_of_a_self_locking_train_says_so(capsys) -> None:
    """The Table 1 RV (both meshes 0.94) back-driven: formal efficiency < 0; from the
    flows nothing leaves at a port, so 0."""
    assert main(["solve", RV, "--backdrive", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["self_locking"] is True and out["efficiency"] == 0.0
    assert out["formal_efficiency"] < 0
    assert all(p["direction"] == "in" for p in out["ports"])


def test_backdrive_needs_one_input_and_one_output() -> None:
    proc = run_cli("solve", str(ROOT / "models" / "bevel_differential.yaml"), "--backdrive")
    assert proc.returncode == 2 and "Traceback" not in proc.stderr
    assert proc.stderr.startswith("powergraph: error: --backdrive needs")
