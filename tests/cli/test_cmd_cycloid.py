"""``powergraph cycloid --module M --teeth Z1 --error D [--shift X] [--rc RC] [--json] [--plot F]``
and ``powergraph cycloid --fit --module M [--json] [--plot F]``: Csobán (2021), "Impacts of a
Profile Failure of the Cycloidal Drive of a Planetary Gear on Transmission Gear" (fitted
surfaces in tests/data/published_values.yaml, section ``csoban2021``)."""
from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from powergraph.cli.main import main

DATA = Path(__file__).resolve().parents[1] / "data" / "published_values.yaml"
FITS = yaml.safe_load(DATA.read_text())["csoban2021"]["fits"]


def run(capsys, *argv: str) -> tuple[int, str, str]:
    status = main(["cycloid", *argv])
    out, err = capsys.readouterr()
    return status, out, err


def test_json_keys_and_zero_error(capsys) -> None:
    status, out, err = run(capsys, "--module", "1", "--teeth", "9", "--error", "0", "--json")
    assert status == 0, err
    data = json.loads(out)
    for key in ("ratio_nominal", "max_deviation_percent", "max_deviation_percent_2deg",
                "crank_angle_deg", "ratio"):
        assert key in data
    assert data["ratio_nominal"] == 9
    assert len(data["crank_angle_deg"]) == len(data["ratio"]) > 100
    assert max(abs(i - 9) for i in data["ratio"]) < 1e-9
    assert data["max_deviation_percent"] < 1e-9


def test_json_case_of_table2(capsys) -> None:
    # Paper Table 2: m = 1, z1 = 9, z2 = 10, x = 0.3, rc* = 1, d = 0.1 mm.
    status, out, err = run(capsys, "--module", "1", "--teeth", "9", "--error", "0.1",
                           "--json")
    assert status == 0, err
    data = json.loads(out)
    assert (data["pins"], data["shift"], data["rc"]) == (10, 0.3, 1.0)
    assert data["eccentricity"] == pytest.approx(0.35)           # (1 - x)·m/2
    assert data["pin_circle_radius"] == pytest.approx(5.0)       # m·z2/2
    assert data["segments"] == 10                                # z2 per revolution
    assert data["max_deviation_percent"] > data["max_deviation_percent_2deg"] > 0
    assert data["crank_angle_deg"][0] == 0 and data["crank_angle_deg"][-1] < 360


def test_human_report(capsys) -> None:
    status, out, _ = run(capsys, "--module", "2", "--teeth", "25", "--error", "0.0065")
    assert status == 0
    for text in ("z1 = 25", "z2 = 26", "max |Δi| exact", "paper (2° differences)"):
        assert text in out


def test_fit_json_matches_the_paper(capsys) -> None:
    status, out, err = run(capsys, "--fit", "--module", "2", "--json")
    assert status == 0, err
    data = json.loads(out)
    # The paper's fitted surface for m = 2: 3.464·d + 1720.82·d·z1^-1.5
    a, b = FITS[2]["a"], FITS[2]["b"]
    assert (data["paper_a"], data["paper_b"]) == (a, b)
    assert data["a"] == pytest.approx(a, rel=0.03)
    assert data["b"] == pytest.approx(b, rel=0.03)
    assert len(data["points"]) == 25


@pytest.mark.slow  # a study of its own
def test_fit_text_for_a_module_the_paper_does_not_give(capsys) -> None:
    status, out, _ = run(capsys, "--fit", "--module", "7")
    assert status == 0
    assert "paper gives none" in out
    assert "left out (m·z1 > 500 mm): z1 = 117" in out


@pytest.mark.parametrize("argv", [
    ("--module", "-1", "--teeth", "9", "--error", "0.01"),
    ("--module", "1", "--teeth", "2", "--error", "0.01"),
    ("--module", "1", "--teeth", "9", "--error", "-0.01"),
    ("--module", "1", "--teeth", "9", "--error", "0.01", "--shift", "1.5"),
    ("--module", "1", "--teeth", "9", "--error", "0.01", "--rc", "-1"),
    ("--module", "1", "--teeth", "9", "--error", "0.9"),         # undercut
    ("--module", "1", "--teeth", "9"),                           # no --error
    ("--fit", "--module", "1", "--teeth", "9"),
    ("--fit", "--module", "0"),
    ("--module", "1", "--teeth", "9", "--error", "0.01", "--plot", "out.jpg"),
    ("--module", "1", "--teeth", "9", "--error", "0.01", "--plot", "/no/such/dir/a.png"),
])
def test_bad_arguments_exit_2_without_traceback(capsys, argv) -> None:
    status, out, err = run(capsys, *argv)
    assert status == 2
    assert out == ""
    assert err.startswith("powergraph: error: ") and err.count("\n") == 1
    assert "Traceback" not in err


def test_plot_writes_a_figure(capsys, tmp_path) -> None:
    target = tmp_path / "fig10.png"
    status, _, err = run(capsys, "--module", "1", "--teeth", "9", "--error", "0.1",
                         "--plot", str(target))
    assert status == 0, err
    assert target.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_fit_plot_writes_a_figure(capsys, tmp_path) -> None:
    target = tmp_path / "fig15.svg"
    status, _, err = run(capsys, "--fit", "--module", "2", "--plot", str(target))
    assert status == 0, err
    assert b"<svg" in target.read_bytes()[:500]


def test_importing_the_command_does_not_import_matplotlib() -> None:
    code = ("import sys, powergraph.cli.cmd_cycloid; "
            "print('matplotlib' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout
    assert out.strip() == "False"
