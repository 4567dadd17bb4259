"""``powergraph tolerance MODEL --samples N [--seed S] [--spec ...] [--json] [-o FILE]``."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from powergraph.cli.main import main

ROOT = Path(__file__).resolve().parents[2]
RV = str(ROOT / "models" / "rv40e_tolerances.yaml")
# One pair, gear 1 (20) drives gear 2 (60): a play of gear 1 reaches gear 2 as a third.
PAIR = """
name: pair
components: {0: {role: frame}, 1: {teeth: 20}, 2: {teeth: 60}}
links: [{type: mesh, between: [1, 2], backlash_arcmin: 3.0}]
ports: [{component: 1, role: input}, {component: 2, role: output}]
tolerances:
  links.0.backlash_arcmin: {distribution: uniform, min: 0, max: 6}
"""


def run(capsys, *argv: str) -> tuple[int, str, str]:
    status = main(["tolerance", *argv])
    out, err = capsys.readouterr()
    return status, out, err


@pytest.fixture
def pair(tmp_path) -> str:
    path = tmp_path / "pair.yaml"
    path.write_text(PAIR)
    return str(path)


def test_json_keys_and_closed_form(capsys, pair) -> None:
    status, out, err = run(capsys, pair, "--samples", "200000", "--seed", "4", "--json",
                           "--spec", "lost_motion<=1arcmin", "--sobol-samples", "256")
    assert status == 0, err
    assert err == ""                                   # no progress bar with --json
    data = json.loads(out)
    assert {"samples", "seed", "outputs", "yield", "sensitivity"} <= set(data)
    assert (data["samples"], data["seed"]) == (200000, 4)
    lost = data["outputs"]["lost_motion_arcmin"]
    assert set(lost) >= {"mean", "sd", "p50", "p95", "p99_73", "max"}
    # play ~ U(0, 6') on gear 1 -> U(0, 2') at the output: p95 = 1.9, P(<= 1') = 1/2
    assert lost["p95"] == pytest.approx(1.9, abs=0.01)
    y = data["yield"]["lost_motion<=1arcmin"]
    assert y["low"] <= 0.5 <= y["high"]
    assert data["sensitivity"]["links.0.backlash_arcmin"]["total"] == pytest.approx(1.0,
                                                                                    abs=0.05)


@pytest.mark.slow
def test_text_report_and_figure(capsys, tmp_path) -> None:
    figure = tmp_path / "tol.png"
    status, out, err = run(capsys, RV, "--samples", "20000", "--seed", "1",
                           "--spec", "lost_motion<=1arcmin", "--spec", "fluctuation<=0.05%",
                           "--spec", "efficiency>=90%", "-o", str(figure))
    assert status == 0, err
    assert "Wilson" in out and "Sobol" in out and "lost motion" in out
    assert figure.stat().st_size > 10_000
    assert out.splitlines()[-1] == f"wrote {figure}"
    # each toleranced PATH with the mesh it belongs to, in the model's names (links[1]
    # of rv40e_tolerances.yaml is the cycloid gear - needle gear mesh)
    line = next(x for x in out.splitlines() if x.startswith("links.1.backlash_arcmin"))
    assert "mesh cycloid gear-needle gear" in line


def test_same_seed_same_output(capsys, pair) -> None:
    first = run(capsys, pair, "--samples", "5000", "--seed", "9", "--json")[1]
    second = run(capsys, pair, "--samples", "5000", "--seed", "9", "--json")[1]
    assert first == second


@pytest.mark.parametrize("argv, message", [
    (["--spec", "lost_motion<=1kg"], "unit 'kg'"),
    (["--spec", "fluctuation<=1%"], "no fluctuation_percent"),
    (["-o", "x.txt"], "suffix"),
])
def test_bad_arguments_exit_2(capsys, pair, argv, message) -> None:
    status, out, err = run(capsys, pair, "--samples", "100", *argv)
    assert status == 2
    assert message in err and "Traceback" not in err
    assert len(err.strip().splitlines()) == 1


@pytest.mark.parametrize("argv", [["--samples", "1"], ["--samples", "x"], ["--seed", "-1"],
                                  ["--sobol-samples", "100"], ["--samples", "1e308"],
                                  ["--seed", "1.5"], ["--sobol-samples", "-0.5"]])
def test_bad_numbers_exit_2(capsys, pair, argv) -> None:
    # --samples 1e308 once ended in numpy's "Maximum allowed dimension exceeded" traceback
    status, out, err = run(capsys, pair, *argv)
    assert status == 2 and out == ""
    assert err.startswith(f"powergraph: error: {argv[0]} ") and err.count("\n") == 1


def test_bad_tolerance_names_its_place(capsys, tmp_path) -> None:
    path = tmp_path / "bad.yaml"
    path.write_text(PAIR.replace("links.0.backlash_arcmin: {", "links.9.backlash_arcmin: {"))
    status, out, err = run(capsys, str(path))
    assert status == 2
    assert "tolerances['links.9.backlash_arcmin']: no links[9]" in err
    assert main(["check", str(path)]) == 2                      # check catches it too


def test_model_without_tolerances_exits_2(capsys) -> None:
    status, out, err = run(capsys, str(ROOT / "models" / "rv40e_wang2021.yaml"))
    assert status == 2
    assert "no tolerances" in err
