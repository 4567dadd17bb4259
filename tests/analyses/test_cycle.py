"""Duty cycles: the totals are the single solves' powers times the rows' durations,
through the compiled sweep (a plain train), the sweep with the bus balance (machines on
buses: tests/analyses/test_cycle_hybrid_batch.py) and each mode's case (modes:
tests/analyses/test_cycle_modes.py);
issue 34: a row that cannot be solved is an error naming it, or with ``keep_going`` is
left out of the totals, which count it."""
from __future__ import annotations

import csv as csv_module
import dataclasses
import gc
import io
import json
import math
import tracemalloc
from pathlib import Path

import numpy as np
import pytest

import powergraph as pg
from powergraph.analyses import cycle_report, cycle_rows
from powergraph.analyses.cycle import CycleResult, CycleRow, cycle, solve_losses
from powergraph.analyses.cycle_points import Points, read_points
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


def test_a_hybrid_cycle_sums_the_single_solves():
    csv = ("engine.speed [rpm],engine.power [kW],wheels.speed [rpm],time [s]\n"
           "2000,30,400,0\n1500,15,1400,10\n2500,40,200,15\n")
    model = pg.load_model(THS)
    result = cycle(model, io.StringIO(csv))
    assert result.method == "sweep with bus balance"
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
    assert result.method == "modes (sweep per gear)"
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
    # 1e12 W (the most a port takes, as in model files) for 1e297 s: 1e309 J, beyond the
    # largest float (1.8e308)
    csv = "carrier.speed [rpm],carrier.power [W],duration [s]\n1000,1e12,1e297\n"
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


# --- issue 34: the result in columns ----------------------------------------------------

ETA0 = 0.98 * 0.99                          # the model file's two meshes
ETA = 4 * ETA0 / (3 * ETA0 + 1)             # (k + 1)·η0/(k·η0 + 1), k = 72/24 = 3


def _plain_points(n: int, seed: int = 34) -> Points:
    """``n`` rows driving the planetary's carrier forwards: 500-3000 rpm, 0.5-20 kW, each
    for 0.1-10 s."""
    rng = np.random.default_rng(seed)
    return Points(columns=(("ports.0.speed", 0, "speed"), ("ports.0.power", 0, "power")),
                  values=(rng.uniform(500, 3000, n) * RPM, rng.uniform(500.0, 20e3, n)),
                  durations=rng.uniform(0.1, 10.0, n), lines=np.arange(2, n + 2))


def test_issue34_energies_are_the_hand_sums_of_power_times_duration():
    points = _plain_points(1000)
    result = cycle(pg.load_model(PLANETARY), points)
    assert result.method == "sweep"
    power, seconds = points.values[1].tolist(), points.durations.tolist()
    e_in = math.fsum(p * t for p, t in zip(power, seconds))
    # every row has the closed-form efficiency, so energy out is ETA times energy in
    assert result.efficiencies == pytest.approx(np.full(1000, ETA), rel=1e-12)
    assert result.power_out == pytest.approx(ETA * points.values[1], rel=1e-12)
    assert result.energy_in == pytest.approx(e_in, rel=1e-13)
    assert result.energy_out == pytest.approx(ETA * e_in, rel=1e-12)
    assert sum(result.energy_lost.values()) == pytest.approx((1 - ETA) * e_in, rel=1e-9)
    assert result.efficiency == pytest.approx(ETA, rel=1e-12)
    assert result.time == pytest.approx(math.fsum(seconds), rel=1e-13)


@pytest.mark.slow
def test_issue34_a_cycle_holds_tens_of_bytes_per_row_not_a_record_per_row():
    """10^5 rows through the sweep (with its numba kernels, as for 10^6): the result keeps
    at most 8 bytes per value of a row (its JSON row: 12 values and one per element), the
    points' arrays shared, not copied; while the sweep runs, its work arrays over the rows
    take a few times that. A CycleRow record per row, with its losses dict, would alone
    take some 750 bytes per row."""
    model, n = pg.load_model(PLANETARY), 100_000
    cycle(model, _plain_points(n))          # the one-off compile and imports, not counted
    points = _plain_points(n)
    gc.collect()
    tracemalloc.start()
    try:
        result = cycle(model, points)
        kept, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    values = 12 + len(result.losses)        # row, line, duration, mode, powers... warnings
    assert len(result.rows) == n and result.failed.sum() == 0
    assert kept < 8 * values * n + 65536
    assert peak < 4 * 8 * values * n
    assert np.shares_memory(result.durations, points.durations)


def test_issue34_the_rows_are_records_built_from_the_columns():
    model = pg.load_model(PLANETARY)
    result = cycle(model, io.StringIO(ZERO_SPEED_ROWS), keep_going=True)
    rows = result.rows
    assert len(rows) == 4 and rows[-1] == rows[3] == result.row(3)
    assert [r.index for r in rows[1:3]] == [1, 2]
    with pytest.raises(IndexError, match="row 4 of a cycle of 4 rows"):
        result.row(4)
    # the JSON rows and the records agree, key for key
    assert [r.to_dict() for r in rows] == result.to_dict()["rows"]
    # a failed row: no power, no efficiency (NaN in the column, None in its record)
    assert result.failed.tolist() == [False, True, False, True]
    assert np.isnan(result.efficiencies[[1, 3]]).all() and rows[1].efficiency is None
    assert all(np.isnan(v[[1, 3]]).all() for v in result.losses.values())
    assert rows[1].losses == {} and set(rows[0].losses) == set(result.losses)
    # the two rows fail for the same reason: its text is stored once
    reason = "error: " + _zero_speed_reason()
    assert result.verdict_texts.count(reason) == 1
    assert result.verdict_codes[1] == result.verdict_codes[3] != result.verdict_codes[0]
    # the columns are read-only, as a frozen record's values
    with pytest.raises(ValueError):
        result.power_in[0] = 1.0


def test_issue34_a_hybrid_cycle_fills_its_machine_columns_row_by_row():
    csv = ("engine.speed [rpm],engine.power [kW],wheels.speed [rpm],time [s]\n"
           "2000,30,400,0\n1500,15,1400,10\n2500,40,200,15\n")
    result = cycle(pg.load_model(THS), io.StringIO(csv))
    # the negative split of row 2 (see the hybrid test above), as columns
    assert result.negative_split.tolist() == [False, True, False]
    assert result.with_machines.all() and not np.isnan(result.electrical_share).any()
    assert result.electrical_share[1] < 0 < result.electrical_share[0]
    assert result.negative_split_time == 5.0


def test_issue34_the_csv_is_written_in_chunks_with_every_row_in_order(monkeypatch, tmp_path):
    monkeypatch.setattr(cycle_report, "CHUNK", 3)       # 6 rows: two chunks
    text = ZERO_SPEED_ROWS + "1500,-1,1\n1000,0,1\n"     # lines 7, 8: reversed, no power
    result = cycle(pg.load_model(PLANETARY), io.StringIO(text), keep_going=True)
    path = tmp_path / "rows.csv"
    assert result.to_csv(path) is None
    rows = list(csv_module.DictReader(path.open(encoding="utf-8")))
    assert rows == list(csv_module.DictReader(io.StringIO(result.to_csv())))
    assert [r["row"] for r in rows] == ["0", "1", "2", "3", "4", "5"]
    assert [r["verdict"][:6] for r in rows] == ["ok", "error:", "ok", "error:", "ok",
                                                "no pow"]
    assert [r["warnings"] for r in rows] == ["", "", "", "", "role-reversed", ""]
    assert [r["efficiency [-]"] == "" for r in rows] == [False, True, False, True, False,
                                                         True]
    assert float(rows[0]["power_out [W]"]) == pytest.approx(1000 * ETA, rel=1e-12)


@pytest.mark.slow       # matplotlib's first import
def test_issue34_the_plot_leaves_a_gap_at_a_row_that_cannot_be_solved():
    import matplotlib.pyplot as plt

    result = cycle(pg.load_model(PLANETARY), io.StringIO(ZERO_SPEED_ROWS), keep_going=True)
    ax = result.plot()
    power_in = ax.patches[0].get_data()
    # rows of 2, 3, 0.5 and 4 s: edges at 0, 2, 5, 5.5, 9.5 s; 1 kW, a gap, 2 kW, a gap
    assert power_in.edges.tolist() == [0.0, 2.0, 5.0, 5.5, 9.5]
    assert power_in.values[[0, 2]].tolist() == [1.0, 2.0]
    assert np.isnan(power_in.values[[1, 3]]).all()
    plt.close(ax.figure)


def test_issue34_a_result_from_records_totals_them_by_hand():
    rows = [CycleRow(0, 2.0, None, 1000.0, 900.0, 100.0, 0.9, "ok", {"mesh": 100.0}),
            CycleRow(1, 3.0, None, 0.0, 0.0, 0.0, None, "error: no speed"),
            CycleRow(2, 0.5, None, 400.0, 300.0, 100.0, 0.75, "ok", {"mesh": 100.0})]
    result = CycleResult.from_rows("demo", rows, "single solves")
    # 1 kW · 2 s + 0.4 kW · 0.5 s in; 0.9 kW · 2 s + 0.3 kW · 0.5 s out
    assert (result.energy_in, result.energy_out) == (2200.0, 1950.0)
    assert result.energy_lost == {"mesh": 250.0}
    assert (result.time, result.left_out, result.left_out_time) == (2.5, [1], 3.0)
    assert [r.to_dict() for r in result.rows] == [r.to_dict() for r in rows]


def test_issue34_rows_swept_in_slices_keep_their_places(monkeypatch):
    # 9 rows in slices of 4, 4 and 1: row 5 (line 7) does not turn under a power, row 6
    # (line 8) is driven from its output; each keeps its place across the slices.
    monkeypatch.setattr(cycle_rows, "slices",
                        lambda n: [slice(0, 4), slice(4, 8), slice(8, n)])
    kw = [1, 2, 3, 4, 5, 6, -1, 8, 9]
    rpm = [1000, 1100, 1200, 1300, 1400, 0, 1600, 1700, 1800]
    text = "carrier.speed [rpm],carrier.power [kW]\n" + "".join(
        f"{n},{p}\n" for n, p in zip(rpm, kw))
    result = cycle(pg.load_model(PLANETARY), io.StringIO(text), keep_going=True)
    assert result.method == "sweep" and result.left_out == [5]
    assert result.warned_rows == {"role-reversed": [6]}
    assert result.row(5).file_line == 7 and result.row(5).verdict.startswith("error: ")
    forwards = [k for k in range(9) if k not in (5, 6)]
    assert result.power_out[forwards] == pytest.approx(ETA * 1e3 * np.array(kw)[forwards],
                                                       rel=1e-12)
    # Row 6: the ring drives and the carrier gives 1 kW; the meshes pass 1/(k + 1) of the
    # power in the carrier's frame, so η' = 1 - (1 - η0)/(k + 1) = (k + η0)/(k + 1).
    back = (3 + ETA0) / 4
    assert result.power_in[6] == pytest.approx(1e3 / back, rel=1e-12)
    # 1 s per row: energy in is the sum of the powers entering
    assert result.energy_in == pytest.approx(1e3 * sum(kw[k] for k in forwards)
                                             + 1e3 / back, rel=1e-12)
