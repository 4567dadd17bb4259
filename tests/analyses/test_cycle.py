"""Duty cycles: the totals are the single solves' powers times the rows' durations,
through the compiled sweep (a plain train) and through single solves (machines, modes)."""
from __future__ import annotations

import io
import json
from pathlib import Path

import pytest

import powergraph as pg
from powergraph.analyses.cycle import cycle, solve_losses
from powergraph.cli.main import main
from powergraph.errors import UsageError
from powergraph.statics.machine_report import boundary_powers
from powergraph.testing import assert_conservation

MODELS = Path(__file__).resolve().parents[2] / "models"
PLANETARY = MODELS / "planetary_2kh_carrier_to_ring.yaml"
THS = MODELS / "ths2_power_split.yaml"
RPM = 3.141592653589793 / 30


def _expected(model, rows):
    """Energies from one single solve per row: ``rows`` = [(port changes, duration)]."""
    e_in = e_out = 0.0
    lost: dict[str, float] = {}
    for changes, duration in rows:
        variant = model
        for index, values in changes.items():
            variant = variant.with_port(index, power=None, torque=None).with_port(index,
                                                                                 **values)
        result = pg.solve(variant)
        assert_conservation(result)
        crossing = boundary_powers(result)
        e_in += sum(p for p in crossing if p > 0) * duration
        e_out -= sum(p for p in crossing if p < 0) * duration
        for label, loss in solve_losses(result).items():
            lost[label] = lost.get(label, 0.0) + loss * duration
    return e_in, e_out, lost


def _check(result, e_in, e_out, lost):
    assert result.energy_in == pytest.approx(e_in, rel=1e-9)
    assert result.energy_out == pytest.approx(e_out, rel=1e-9)
    assert set(result.energy_lost) == set(lost)
    for label, joules in lost.items():
        assert result.energy_lost[label] == pytest.approx(joules, rel=1e-9, abs=1e-9)
    # energy is conserved over the cycle too
    assert result.energy_in == pytest.approx(
        result.energy_out + sum(result.energy_lost.values()), rel=1e-9)
    assert result.efficiency == pytest.approx(e_out / e_in, rel=1e-9)


def test_a_plain_train_cycle_goes_through_the_sweep_and_sums_the_single_solves():
    csv = ("carrier.speed [rpm],carrier.power [kW],duration [s]\n"
           "1000,1,2\n2000,2.5,3\n1500,-1,0.5\n")
    result = cycle(pg.load_model(PLANETARY), io.StringIO(csv))
    assert result.method == "sweep"
    rows = [({0: {"speed": 1000 * RPM, "power": 1e3}}, 2.0),
            ({0: {"speed": 2000 * RPM, "power": 2.5e3}}, 3.0),
            ({0: {"speed": 1500 * RPM, "power": -1e3}}, 0.5)]
    _check(result, *_expected(pg.load_model(PLANETARY), rows))
    assert [r.verdict for r in result.rows] == ["ok", "ok", "ok"]
    # The last row drives the train from its output: the single solve warns that both
    # ports run against their roles, and so does the batched row.
    single = pg.solve(pg.load_model(PLANETARY).with_port(0, power=None, torque=None)
                      .with_port(0, speed=1500 * RPM, power=-1e3))
    assert {w.code for w in single.warnings} == {"role-reversed"}
    assert [r.warnings for r in result.rows] == [(), (), ("role-reversed",)]
    assert result.warned_rows == {"role-reversed": [2]}


def test_a_hybrid_cycle_solves_row_by_row_and_sums_the_single_solves():
    csv = ("engine.speed [rpm],engine.power [kW],wheels.speed [rpm],time [s]\n"
           "2000,30,400,0\n1500,15,1400,10\n2500,40,200,15\n")
    model = pg.load_model(THS)
    result = cycle(model, io.StringIO(csv))
    assert result.method == "single solves"
    # time [s]: each row lasts until the next, the last as long as the one before
    assert [r.duration for r in result.rows] == [10.0, 5.0, 5.0]
    rows = [({0: {"speed": 2000 * RPM, "power": 30e3}, 3: {"speed": 400 * RPM}}, 10.0),
            ({0: {"speed": 1500 * RPM, "power": 15e3}, 3: {"speed": 1400 * RPM}}, 5.0),
            ({0: {"speed": 2500 * RPM, "power": 40e3}, 3: {"speed": 200 * RPM}}, 5.0)]
    _check(result, *_expected(model, rows))
    assert "machine MG1" in result.energy_lost
    # Row 2: the ring turns at 1400 * 78/19 = 5747 rpm, the sun at
    # 3.6 * 1500 - 2.6 * 5747 < 0 against its torque -T_c/3.6 < 0: MG1 motors, a negative
    # split, for that row's 5 s; rows 1 and 3 have the sun forwards (positive split).
    assert [r.negative_split for r in result.rows] == [False, True, False]
    assert result.negative_split_time == 5.0


def test_time_per_mode_of_a_gearbox_cycle():
    csv = "in.speed [rpm],in.power [kW],duration [s],mode\n2500,20,4,1\n2500,20,6,2\n" \
          "2000,10,1,1\n"
    result = cycle(pg.load_model(MODELS / "simpson_3speed.yaml"), io.StringIO(csv))
    assert result.method == "single solves"
    assert result.time_per_mode == {"1": 5.0, "2": 6.0}
    assert result.locked_rows == []


def test_an_unknown_column_is_a_usage_error():
    with pytest.raises(UsageError, match="column 'gearbox.speed"):
        cycle(pg.load_model(PLANETARY), io.StringIO("gearbox.speed [rpm]\n1000\n"))


def test_cli_cycle_json_and_csv(tmp_path, capsys):
    points = tmp_path / "points.csv"
    points.write_text("carrier.speed [rpm],carrier.power [W],duration [s]\n1000,500,2\n")
    out = tmp_path / "rows.csv"
    assert main(["cycle", str(PLANETARY), "--points", str(points), "--json",
                 "-o", str(out)]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["energy_in"] == pytest.approx(1000.0)
    assert out.read_text().splitlines()[0].startswith("row,duration [s],mode,power_in [W]")


def test_cli_cycle_bad_cell_is_one_error_line(tmp_path, capsys):
    points = tmp_path / "points.csv"
    points.write_text("carrier.speed [rpm],carrier.power [W]\n1000,lots\n")
    assert main(["cycle", str(PLANETARY), "--points", str(points)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("powergraph: error:") and "row 2" in err and len(err.splitlines()) == 1
