"""Issue 37, item 5: cycles that report machines. Every row of a hybrid's cycle carries
each machine's speed, torque, mechanical and electrical power and state, each bus's
battery power and each other port's power — in the result's columns, the ``--json`` rows
and the ``-o`` CSV — and a ``BUS.battery [UNIT]`` column sets the bus per row.

Expected numbers: the single solve of each row's model, built here by hand
(``pg.solve`` of the THS-II with the row's values), and the speeds by hand: the ring
(MG2) turns at 78/19 of the wheels (two external meshes, 31/31 between them) and the sun
(MG1) at w_S = (1 + k)·w_C − k·w_R, k = 78/30 (docs/hybrid.md).
"""
from __future__ import annotations

import csv
import io
import json
import math
from pathlib import Path

import numpy as np
import pytest

import powergraph as pg
from powergraph.analyses.cycle import CycleResult, CycleRow, cycle
from powergraph.cli.main import main
from powergraph.errors import UsageError

MODELS = Path(__file__).resolve().parents[2] / "models"
THS = MODELS / "ths2_power_split.yaml"
PLANETARY = MODELS / "planetary_2kh_carrier_to_ring.yaml"
RPM = math.pi / 30
HEADER = "engine.speed [rpm],engine.power [kW],wheels.speed [rpm],dc.battery [kW]\n"
#: engine rpm, engine kW, wheels rpm, battery kW: a positive split drawing 5 kW from the
#: battery, a negative split charging it with 3 kW, charge-sustaining at 40 kW.
ROWS = ((2000, 30, 400, 5), (1500, 15, 1400, -3), (2500, 40, 200, 0))


def _single(model, engine_rpm, engine_kw, wheels_rpm, battery_kw):
    """The single solve of one row."""
    variant = (model.with_port(0, speed=engine_rpm * RPM, power=engine_kw * 1e3)
               .with_port(3, speed=wheels_rpm * RPM).with_bus("dc", battery=battery_kw * 1e3))
    return pg.solve(variant)


@pytest.mark.slow          # compiles the plain train's sweep and solves each row alone
def test_issue37_every_row_carries_its_single_solves_machines_and_battery():
    model = pg.load_model(THS)
    result = cycle(model, io.StringIO(HEADER + "".join(
        ",".join(map(str, row)) + "\n" for row in ROWS)))
    assert result.method == "sweep with bus balance"
    assert list(result.machines) == ["MG1", "MG2"]
    assert list(result.port_power) == ["engine", "wheels"]
    assert list(result.battery_power) == ["dc"]
    for i, row in enumerate(ROWS):
        single = _single(model, *row)
        for machine in single.machines:
            got = result.machines[machine.name]
            for key in ("speed", "torque", "power", "electrical_power"):
                assert got[key][i] == pytest.approx(getattr(machine, key), rel=1e-9,
                                                    abs=1e-9), (i, machine.name, key)
            assert result.machine_states(machine.name)[i] == machine.state
            assert result.rows[i].to_dict()["machines"][machine.name]["state"] == machine.state
        assert result.battery_power["dc"][i] == single.buses["dc"].battery_power == row[3] * 1e3
        # ports: the engine feeds power in, the wheels take it out (the model's signs)
        assert result.port_power["engine"][i] == pytest.approx(single.ports[0].power, rel=1e-12)
        assert result.port_power["wheels"][i] == pytest.approx(-single.ports[3].power,
                                                               rel=1e-9)
        # the speeds by hand: ring = 78/19 wheels, sun = 3.6 carrier - 2.6 ring
        ring = row[2] * RPM * 78 / 19
        assert result.machines["MG2"]["speed"][i] == pytest.approx(ring, rel=1e-12)
        assert result.machines["MG1"]["speed"][i] == pytest.approx(
            (1 + 2.6) * row[0] * RPM - 2.6 * ring, rel=1e-12)
        # the bus balances: what the machines draw is the battery's power
        assert sum(m["electrical_power"][i] for m in result.machines.values()) == \
            pytest.approx(row[3] * 1e3, abs=1e-6)
    # row 2, the negative split: MG1 turns backwards and motors, MG2 generates
    assert [result.machine_states(n)[1] for n in ("MG1", "MG2")] == ["motoring", "generating"]


@pytest.mark.slow          # compiles the plain train's sweep
def test_issue37_json_rows_and_csv_columns_carry_the_machines(tmp_path, capsys):
    points = tmp_path / "points.csv"
    points.write_text(HEADER + "2000,30,400,5\n0,30,400,0\n")      # the second fails
    out = tmp_path / "rows.csv"
    assert main(["cycle", str(THS), "--points", str(points), "--keep-going", "--json",
                 "-o", str(out)]) == 0
    rows = json.loads(capsys.readouterr().out)["rows"]
    result = cycle(pg.load_model(THS), points, keep_going=True)
    first = rows[0]
    assert set(first["machines"]) == {"MG1", "MG2"}
    assert set(first["machines"]["MG1"]) == {"speed", "torque", "power", "electrical_power",
                                            "state"}
    assert first["buses"] == {"dc": {"battery_power": 5000.0}}
    assert first["port_power"] == {"engine": 30000.0,
                                   "wheels": float(result.port_power["wheels"][0])}
    assert first["machines"]["MG2"]["power"] == float(result.machines["MG2"]["power"][0])
    # a row not solved carries no flows
    assert rows[1]["verdict"].startswith("error: ")
    assert (rows[1]["machines"], rows[1]["buses"], rows[1]["port_power"]) == ({}, {}, {})
    table = list(csv.DictReader(out.open(encoding="utf-8")))
    header = list(table[0])
    assert header[11:] == [
        "engine.power [W]", "wheels.power [W]",
        "MG1.speed [rad/s]", "MG1.torque [N*m]", "MG1.power [W]", "MG1.electrical_power [W]",
        "MG1.state",
        "MG2.speed [rad/s]", "MG2.torque [N*m]", "MG2.power [W]", "MG2.electrical_power [W]",
        "MG2.state", "dc.battery [W]"]
    for name, values in first["machines"].items():
        for key, unit in (("speed", "rad/s"), ("torque", "N*m"), ("power", "W"),
                          ("electrical_power", "W")):
            assert float(table[0][f"{name}.{key} [{unit}]"]) == values[key]
        assert table[0][f"{name}.state"] == values["state"]
    assert float(table[0]["dc.battery [W]"]) == 5000.0
    assert all(table[1][h] == "" for h in header[11:])


def test_issue37_a_cycle_without_machines_has_no_flow_columns():
    result = CycleResult.from_rows("demo", [CycleRow(0, 1.0, None, 1.0, 0.9, 0.1, 0.9, "ok")],
                                   "sweep")
    assert (result.machines, result.port_power, result.battery_power) == ({}, {}, {})
    row = result.to_dict()["rows"][0]
    assert (row["machines"], row["buses"], row["port_power"]) == ({}, {}, {})
    assert result.to_csv().splitlines()[0].endswith("negative_split,warnings")


def test_issue37_rows_with_machines_round_trip_through_records():
    machines = {"MG1": {"speed": 10.0, "torque": -2.0, "power": -20.0,
                        "electrical_power": -18.0},
                "MG2": {"speed": 5.0, "torque": 4.0, "power": 20.0,
                        "electrical_power": 22.5}}
    rows = [CycleRow(0, 2.0, None, 100.0, 95.5, 4.5, 0.955, "ok", electrical_share=0.2,
                     negative_split=False, port_power={"engine": 100.0, "wheels": 95.5},
                     machines=machines, battery_power={"dc": 4.5}),
            CycleRow(1, 1.0, None, 0.0, 0.0, 0.0, None, "error: no speed")]
    result = CycleResult.from_rows("demo", rows, "single solves")
    assert [r.to_dict() for r in result.rows] == [r.to_dict() for r in rows]
    assert result.to_dict()["rows"] == [r.to_dict() for r in rows]
    assert result.machine_states("MG1") == ["generating", ""]
    assert result.rows[0].to_dict()["machines"]["MG2"]["state"] == "motoring"
    assert result.battery_energy == {"dc": 9.0}        # 4.5 W for 2 s


def _refused(capsys, tmp_path, text: str, model=THS) -> str:
    points = tmp_path / "points.csv"
    points.write_text(text)
    assert main(["cycle", str(model), "--points", str(points)]) == 2
    err = capsys.readouterr().err
    assert len(err.splitlines()) == 1 and "Traceback" not in err
    assert err.startswith(f"powergraph: error: {points}: ")
    return err.strip()


BASE = "engine.speed [rpm],engine.power [kW],wheels.speed [rpm]"


@pytest.mark.parametrize("text,words", [
    (f"{BASE},hv.battery [kW]\n2000,30,400,1\n",
     "column 'hv.battery [kW]': unknown bus 'hv' (the model's buses: dc)"),
    (f"{BASE},dc.battery [rpm]\n2000,30,400,1\n",
     "column 'dc.battery [rpm]': 'rpm' is not a power"),
    (f"{BASE},dc.battery [kwh]\n2000,30,400,1\n", "column 'dc.battery [kwh]': unknown unit"),
    (f"{BASE},dc.battery [kW],dc.battery [W]\n2000,30,400,1,1\n",
     "column 'dc.battery [W]': the same quantity as column 'dc.battery [kW]' "
     "(buses.dc.battery); one column per quantity"),
    (f"{BASE},dc.battery [kW]\n2000,30,400,1\n2000,30,400,\n",
     "row 3, column 'dc.battery [kW]': empty cell: a BUS.battery column gives the bus's "
     "battery power in every row"),
    (f"{BASE},dc.battery [kW]\n2000,30,400,free\n",
     "row 2, column 'dc.battery [kW]': not a number: 'free'"),
    (f"{BASE},dc.battery [kW]\n2000,30,400,1e10\n",
     "row 2, column 'dc.battery [kW]': '1e10' is out of range: a battery's power is at most"),
    (f"{BASE},dc.power [kW]\n2000,30,400,1\n", "column 'dc.power [kW]': expected PORT.speed, "
     "PORT.power or PORT.torque with PORT one of C, MG1, MG2, R, S, W, engine, wheels, "
     "BUS.battery with BUS one of dc, duration [s], time [s] or mode"),
])
def test_issue37_bad_battery_columns_are_one_error_line(capsys, tmp_path, text, words):
    assert words in _refused(capsys, tmp_path, text)


def test_issue37_a_battery_column_on_a_train_without_buses_is_refused(capsys, tmp_path):
    err = _refused(capsys, tmp_path, "carrier.speed [rpm],carrier.power [kW],dc.battery [kW]\n"
                   "1000,1,1\n", model=PLANETARY)
    assert "column 'dc.battery [kW]': the model '2K-H carrier -> ring gear, sun gear fixed' " \
        "has no buses" in err


def test_issue37_a_battery_header_is_read_before_any_row():
    with pytest.raises(UsageError, match="unknown bus 'DC'"):
        cycle(pg.load_model(THS), io.StringIO(f"{BASE},DC.battery\nnot,a,row,at,all\n"))


@pytest.mark.slow          # matplotlib, and the sweep's compilation
def test_issue37_the_plot_shows_ports_machines_battery_and_the_share():
    import matplotlib.pyplot as plt

    text = HEADER + "2000,30,400,5\n0,30,400,0\n1500,15,1400,-3\n"
    result = cycle(pg.load_model(THS), io.StringIO(text), keep_going=True)
    top, bottom = result.plot()
    labels = [t.get_text() for t in top.get_legend().get_texts()]
    assert labels == ["engine", "wheels", "MG1", "MG2", "battery dc"]
    battery = top.patches[4].get_data()
    assert battery.values[[0, 2]].tolist() == [5.0, -3.0] and np.isnan(battery.values[1])
    share = next(p for p in bottom.patches if p.get_label() == "electrical share").get_data()
    assert share.values[0] == pytest.approx(100 * result.electrical_share[0])
    assert np.isnan(share.values[1]) and share.values[2] < 0
    assert bottom.get_xlabel() == "time [s]"
    plt.close(top.figure)


@pytest.mark.slow          # matplotlib
def test_issue37_a_share_without_bound_runs_off_a_scale_that_says_so():
    import matplotlib.pyplot as plt

    # a row whose wheels take almost no power: 8000 % on the electrical path
    machine = {"speed": 10.0, "torque": 1.0, "power": 10.0, "electrical_power": 12.5}
    rows = [CycleRow(i, 1.0, None, 100.0, 90.0, 10.0, 0.9, "ok", electrical_share=share,
                     negative_split=share < 0, port_power={"engine": 100.0},
                     machines={"MG": machine}, battery_power={"dc": 12.5})
            for i, share in enumerate([0.3, 80.0, -2.0])]
    top, bottom = CycleResult.from_rows("demo", rows, "single solves").plot()
    low, high = bottom.get_ylim()
    assert low < -200 and 500 < high < 600          # -200 % shown, 8000 % off the scale
    assert [t.get_text() for t in bottom.texts] == ["off the scale:\nrows beyond ±500 %"]
    plt.close(top.figure)
