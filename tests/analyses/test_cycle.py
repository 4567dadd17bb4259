"""Duty cycles: the totals are the single solves' powers times the rows' durations,
through the compiled sweep (a plain train) and through single solves (machines, modes);
issue 34: a row that cannot be solved is an error naming it, or with ``keep_going`` is
left out of the totals, which count it."""
from __future__ import annotations

import dataclasses
import io
import json
from pathlib import Path

import pytest

import powergraph as pg
from powergraph.analyses.cycle import cycle, solve_losses
from powergraph.analyses.cycle_points import read_points
from powergraph.cli.main import main
from powergraph.errors import ModelError, UsageError
from powergraph.statics.machine_report import boundary_powers
from powergraph.statics.modes import solve_mode
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
    model = pg.load_model(MODELS / "simpson_3speed.yaml")
    result = cycle(model, io.StringIO(csv))
    assert result.method == "single solves"
    assert result.time_per_mode == {"1": 5.0, "2": 6.0}
    assert result.locked_rows == []
    # Each row as `powergraph solve --mode` solves it: first gear through the freewheel F1
    # holding (in.power 20 kW enters; what leaves is the mode's efficiency times it).
    e_out = 0.0
    for rpm, kw, seconds, mode in ((2500, 20, 4, "1"), (2500, 20, 6, "2"), (2000, 10, 1, "1")):
        moded = solve_mode(model.with_port(0, speed=rpm * RPM, power=kw * 1e3), mode)
        assert moded.verdict == "ok" and (mode != "1" or moded.freewheels == {"F1": "holding"})
        e_out += moded.result.efficiency * kw * 1e3 * seconds
    assert result.energy_in == pytest.approx(20e3 * 10 + 10e3 * 1, rel=1e-12)
    assert result.energy_out == pytest.approx(e_out, rel=1e-9)


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


ZERO_SPEED_ROWS = ("carrier.speed [rpm],carrier.power [kW],duration [s]\n"
                   "1000,1,2\n0,1,3\n\n1500,2,0.5\n0,-1,4\n")  # rows on lines 2, 3, 5, 6


def _zero_speed_reason() -> str:
    """The single solve's reason for a power given at a port that does not turn."""
    variant = pg.load_model(PLANETARY).with_port(0, power=None, torque=None).with_port(
        0, speed=0.0, power=1e3)
    with pytest.raises(ModelError) as info:
        pg.solve(variant)
    return str(info.value)


def test_issue34_a_row_that_cannot_be_solved_stops_the_cycle_naming_it():
    reason = _zero_speed_reason()
    assert "does not turn" in reason
    with pytest.raises(UsageError) as info:
        cycle(pg.load_model(PLANETARY), io.StringIO(ZERO_SPEED_ROWS))
    assert str(info.value) == (f"points: row 3: cannot be solved: {reason} (--keep-going, "
                               "keep_going=True, leaves such rows out of the totals)")


def test_issue34_a_sweep_row_that_fails_gives_the_single_solves_reason_not_loads():
    result = cycle(pg.load_model(PLANETARY), io.StringIO(ZERO_SPEED_ROWS), keep_going=True)
    assert result.method == "sweep"
    reason = _zero_speed_reason()
    assert [r.verdict for r in result.rows] == ["ok", f"error: {reason}", "ok",
                                                f"error: {reason}"]


def test_issue34_keep_going_leaves_the_failed_rows_out_of_the_totals_and_counts_them():
    model = pg.load_model(PLANETARY)
    result = cycle(model, io.StringIO(ZERO_SPEED_ROWS), keep_going=True)
    solved = [({0: {"speed": 1000 * RPM, "power": 1e3}}, 2.0),
              ({0: {"speed": 1500 * RPM, "power": 2e3}}, 0.5)]
    _check(result, *_expected(model, solved))
    # left out: the rows on lines 3 and 6, 3 s + 4 s; the time is the rest, 2 s + 0.5 s
    assert result.left_out == [1, 3] and result.left_out_time == 7.0
    assert result.time == 2.5 and result.time_per_mode == {"-": 2.5}
    data = result.to_dict()
    assert data["left_out"] == {"rows": 2, "time": 7.0} and data["time"] == 2.5
    assert [r["line"] for r in data["rows"]] == [2, 3, 5, 6]
    report = result.text_report()
    assert "left out            2 row(s), 7 s (cannot be solved; file lines 3, 6)" in report
    assert f"warning: row 6: {_zero_speed_reason()}" in report


def test_issue34_a_cycle_with_no_row_solved_is_an_error_even_keeping_going():
    # A third speed on the 2-DOF power split: no row is determined.
    csv = "MG2.speed [rpm],engine.power [kW],wheels.speed [rpm]\n1000,10,400\n2000,10,400\n"
    reason = "train has 2 degrees of freedom but 3 speeds were given"
    with pytest.raises(UsageError, match=f"^points: row 2: cannot be solved: {reason}"):
        cycle(pg.load_model(THS), io.StringIO(csv))
    with pytest.raises(UsageError, match=f"^points: no row could be solved \\(2 row\\(s\\)\\); "
                                         f"the first, row 2: {reason}"):
        cycle(pg.load_model(THS), io.StringIO(csv), keep_going=True)


def test_issue34_energies_that_overflow_name_the_duration_column():
    # 1e300 W for 1e10 s: 1e310 J, beyond the largest float (1.8e308)
    csv = "carrier.speed [rpm],carrier.power [W],duration [s]\n1000,1e300,1e10\n"
    with pytest.raises(UsageError, match="^points: column 'duration \\[s\\]': the energies over "
                                         "the cycle overflow"):
        cycle(pg.load_model(PLANETARY), io.StringIO(csv))


def test_issue34_points_with_a_mode_the_model_lacks_are_refused_before_a_solve():
    simpson = pg.load_model(MODELS / "simpson_3speed.yaml")
    points = read_points(io.StringIO("in.speed [rpm],in.power [kW],mode\n2500,20,2\n"),
                         simpson)
    fewer = dataclasses.replace(simpson, modes={"1": ("C1",)})
    with pytest.raises(UsageError, match="^points: row 2, column 'mode': unknown mode '2' "
                                         "\\(the model's modes: 1\\)"):
        cycle(fewer, points)
