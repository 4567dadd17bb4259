"""The gear table of a multi-mode hybrid (docs/modes.md): per mode its DOF, engaged
elements, inactive ports, speed relation, machines, battery power, electrical share and
verdict — the same numbers as ``solve --mode`` on every mode.

The relations by hand (``models/volt_gen1.yaml``: k = 83/37, wheels = carrier/2.16):
w_C = (w_S + k w_R)/(1 + k), so with the ring held (one-motor EV, series) the wheels turn
at w_S/((1 + k)·2.16) — ratio (1 + k)·2.16 = 7.0054 — and with the ring on MG-A (two-motor
EV) or on the engine (power split) at k/((1 + k)·2.16)·w_R + 1/((1 + k)·2.16)·w_S.
"""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from powergraph.analyses.gear_table import gear_table
from powergraph.cli.main import main
from powergraph.model import load_model
from powergraph.statics.case import TrainCase
from powergraph.testing import assert_conservation

VOLT = Path(__file__).resolve().parents[2] / "models" / "volt_gen1.yaml"
K = 83 / 37
FD = 2.16


@pytest.fixture(scope="module")
def table():
    return gear_table(load_model(VOLT))


def test_each_mode_s_dof_elements_and_relation(table) -> None:
    rows = {r.mode: r for r in table.rows}
    assert {m: (r.dof, r.engaged, r.inactive) for m, r in rows.items()} == {
        "power split": (2, ("C2", "C3"), ()), "series": (2, ("C1", "C3"), ()),
        "one-motor EV": (1, ("C1",), ("engine", "MG-A")),
        "two-motor EV": (2, ("C2",), ("engine",))}
    ev1 = rows["one-motor EV"]
    assert ev1.ratio == pytest.approx((1 + K) * FD, rel=1e-12)
    assert ev1.relation.terms[0][0] == "MG-B"
    for mode, ring in (("two-motor EV", "MG-A"), ("power split", "engine")):
        terms = dict(rows[mode].relation.terms)
        assert terms == pytest.approx({ring: K / (1 + K) / FD, "MG-B": 1 / (1 + K) / FD},
                                      rel=1e-12)
        assert rows[mode].ratio is None
    # series: the engine's shaft turns apart from the wheels
    assert dict(rows["series"].relation.terms) == pytest.approx(
        {"engine": 0.0, "MG-B": 1 / (1 + K) / FD}, abs=1e-15)
    assert rows["series"].relation.text() == "wheels = 0.1427·MG-B"
    assert table.spread == pytest.approx(1.0)            # one 1-DOF mode


def test_the_table_equals_solve_mode_on_every_mode(table, capsys) -> None:
    for row in table.rows:
        point = TrainCase.of(table.model, row.mode).point()
        assert_conservation(point.result)
        assert row.machines == point.result.machines, row.mode
        assert main(["solve", str(VOLT), "--mode", row.mode, "--json"]) == 0
        solved = json.loads(capsys.readouterr().out)
        dumped = row.to_dict()
        assert dumped["machines"] == solved["machines"], row.mode
        assert dumped["buses"] == solved["buses"], row.mode
        assert dumped["electrical_share"] == solved["electrical_share"], row.mode
        assert dumped["efficiency"] == solved["efficiency"], row.mode
        assert dumped["verdict"] == solved["verdict"] == "ok", row.mode
        assert dumped["inactive"] == solved["inactive"], row.mode
        assert dumped["dof"] == solved["dof"], row.mode
        engaged = {e["name"]: e["torque"] for e in solved["shift_elements"] if e["engaged"]}
        assert dumped["shift_torques"] == engaged, row.mode
        slips = {e["name"]: e["slip_speed"] for e in solved["shift_elements"]
                 if not e["engaged"]}
        assert dumped["shift_slips"] == slips, row.mode


def test_modes_prints_the_hybrid_table(capsys) -> None:
    assert main(["modes", str(VOLT)]) == 0
    out = capsys.readouterr().out
    assert "speed relation" in out and "ratio 7.0054 (MG-B : wheels)" in out
    assert "wheels = 0.3202·engine + 0.1427·MG-B" in out
    assert "inactive" in out and "idle" in out and "dc battery kW" in out
    assert main(["modes", str(VOLT), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert [m["dof"] for m in data["modes"]] == [2, 2, 1, 2]
    ev1 = data["modes"][2]
    assert {m["name"]: m["state"] for m in ev1["machines"]} == {
        "MG-A": "inactive", "MG-B": "motoring"}
    assert ev1["machines"][0]["speed"] is None            # MG-A's rotor is idle
    assert ev1["coast_efficiency"] is None


def test_the_chart_of_ratios_refuses_a_2_dof_mode(tmp_path, capsys) -> None:
    assert main(["modes", str(VOLT), "-o", str(tmp_path / "t.png")]) == 2
    err = capsys.readouterr().err
    assert "mode 'power split' has 2 DOF (no single ratio)" in err
    assert err.count("\n") == 1 and "Traceback" not in err
