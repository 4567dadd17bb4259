"""``powergraph formula MODEL [--latex] [--json] [--let NAME=EXPR]`` (docs/formula.md)."""
from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
import sympy as sp

import powergraph as pg
from powergraph.cli.main import main
from powergraph.model import load_model

ROOT = Path(__file__).resolve().parents[2]
RV40E = str(ROOT / "models" / "rv40e_wang2021.yaml")
KHV = str(ROOT / "models" / "khv_involute.yaml")


def run(capsys, *argv: str) -> tuple[int, str, str]:
    status = main(["formula", *argv])
    out, err = capsys.readouterr()
    return status, out, err


def _evaluate(text: str, symbols: dict) -> float:
    expr = sp.sympify(text)
    return float(expr.subs({sp.Symbol(n): v["value"] for n, v in symbols.items()}))


def test_json_parses_and_matches_the_solver(capsys) -> None:
    status, out, err = run(capsys, RV40E, "--json")
    assert status == 0, err
    data = json.loads(out)
    assert {"ratio", "efficiency", "latex", "directions", "conditions", "symbols"} <= set(data)
    assert set(data["latex"]) == {"ratio", "efficiency"}
    assert set(data["symbols"]) == {"z_1", "z_2", "z_4", "z_5", "eta_0", "eta_1"}
    assert data["symbols"]["z_5"] == {"kind": "teeth", "value": 40.0, "component": 5,
                                      "path": "components.5.teeth"}
    assert data["symbols"]["eta_1"]["path"] == "links.1.efficiency"
    numeric = pg.solve(load_model(RV40E))
    assert _evaluate(data["ratio"], data["symbols"]) == pytest.approx(numeric.ratio, rel=1e-12)
    assert _evaluate(data["efficiency"], data["symbols"]) == pytest.approx(
        numeric.efficiency, rel=1e-12)
    # the hand closed form of benchmarks/sweep_rv.py: 0.287376 with both meshes at 0.94
    assert _evaluate(data["efficiency"], data["symbols"]) == pytest.approx(0.287376, abs=5e-7)
    assert [(d["link"], d["between"], d["driver"]) for d in data["directions"]] == [
        (0, [1, 2], 1), (1, [4, 5], 5)]
    assert all({"condition", "expression", "relation"} <= set(c) for c in data["conditions"])


def test_let_gives_the_textbook_rv_ratio(capsys) -> None:
    status, out, err = run(capsys, RV40E, "--json", "--let", "z_4=z_5-1")
    assert status == 0, err
    data = json.loads(out)
    z1, z2, z5 = sp.symbols("z_1 z_2 z_5")
    assert sp.simplify(sp.sympify(data["ratio"]) - (1 + z2 * z5 / z1)) == 0
    assert data["relations"] == {"z_4": "z_5 - 1"}


def test_text_report(capsys) -> None:
    status, out, err = run(capsys, KHV)
    assert status == 0, err
    assert "ratio" in out and "efficiency" in out and "valid while" in out
    assert "r drives, f = 1/eta_0" in out
    assert "eta_0*(z_r - z_p)/(z_r - eta_0*z_p)" in out


def test_latex(capsys) -> None:
    status, out, err = run(capsys, KHV, "--latex")
    assert status == 0, err
    assert r"\eta = \frac{\eta_{0}" in out and out.startswith("%")


@pytest.mark.parametrize("argv,message", [
    (["--let", "z_4=z_5-2"], "does not hold"),
    (["--let", "z_4"], "NAME=EXPR"),
    (["--let", "z_9=3"], "unknown symbol"),
])
def test_bad_relations_exit_2(capsys, argv, message) -> None:
    status, out, err = run(capsys, RV40E, *argv)
    assert status == 2 and message in err and "Traceback" not in err


def test_not_applicable_and_invalid_models_exit_2(capsys, tmp_path) -> None:
    two_outputs = tmp_path / "two_outputs.yaml"
    two_outputs.write_text(Path(KHV).read_text().replace(
        "  - {component: out, role: output}",
        "  - {component: out, role: output}\n  - {component: p, role: output}"))
    status, _, err = run(capsys, str(two_outputs))
    assert status == 2 and "one input and one output" in err
    status, _, err = run(capsys, str(ROOT / "tests" / "data" / "malformed.yaml"))
    assert status == 2 and "Traceback" not in err


def test_cli_module_does_not_import_sympy() -> None:
    """sympy is slow to import: the command module loads it only when the command runs
    (main.py imports every command module to build the parser)."""
    code = "import sys, powergraph.cli.cmd_formula; print('sympy' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, cwd=ROOT).stdout
    assert out.strip() == "False"
