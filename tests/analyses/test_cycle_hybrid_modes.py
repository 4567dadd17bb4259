"""A duty cycle of a multi-mode hybrid (powergraph.analyses.cycle_modes, cycle_rows): a
column gives its quantity in every row in place of the model's, and an empty cell is "not
given in this row" — the mode's value if it sets one, else none (a load the mode's other
values fix, a free battery); a port the mode switches off takes no value; a row that
lacks a value it needs is an error naming the row, the mode and the quantity; every
row's machine columns are the single solve's.

The train is ``models/volt_gen1.yaml`` with ideal meshes (as in
``tests/statics/test_hybrid_modes.py``), so the numbers follow by hand:

- one-motor EV (C1 holds the ring): MG-B on the sun turns at (1 + k)·2.16·w_wheels with
  k = 83/37, and with ideal meshes its shaft power is the wheels' power; at eta = 0.9 it
  draws P/0.9 from the bus, which a free battery supplies;
- series (C1 + C3): the engine's power P_e goes into MG-A (generating, P_e·0.9 to the
  bus); at 0 W battery MG-B draws it all and puts 0.81·P_e on the wheels.
"""
from __future__ import annotations

import io
import math
from pathlib import Path

import pytest
import yaml

from powergraph.analyses.cycle import cycle
from powergraph.cli.main import main
from powergraph.errors import UsageError
from powergraph.model import load_model, model_from_dict
from powergraph.statics.case import TrainCase
from powergraph.testing import assert_conservation

ROOT = Path(__file__).resolve().parents[2]
VOLT = ROOT / "models" / "volt_gen1.yaml"
RPM = math.pi / 30
K, FD, ETA = 83 / 37, 54 / 25, 0.9
HEADER = ("time [s],mode,engine.speed [rpm],engine.power [kW],MG-A.speed [rpm],"
          "wheels.speed [rpm],wheels.power [kW],dc.battery [kW]\n")
ROWS = ("0,one-motor EV,,,,400,10,\n"         # the row's 10 kW, not the mode's 20 kW
        "10,one-motor EV,,,,600,,\n"          # wheels' power empty: the mode's 20 kW
        "20,two-motor EV,,,1500,800,20,\n"
        "30,series,2500,40,,500,,0\n"
        "40,power split,2000,,,800,25,0\n"    # engine's power empty: the balance fixes it
        "50,power split,2000,30,,900,,-5\n")


@pytest.fixture(scope="module")
def volt():
    return load_model(VOLT).with_mesh_efficiency(1.0)


@pytest.fixture(scope="module")
def result(volt):
    return cycle(volt, io.StringIO(HEADER + ROWS))


def test_empty_cells_take_the_mode_then_the_model_by_hand(result) -> None:
    rows = result.rows
    for i, (power, wheels_rpm) in enumerate([(10e3, 400), (20e3, 600)]):
        mg_b = rows[i].machines["MG-B"]
        assert mg_b["speed"] == pytest.approx((1 + K) * FD * wheels_rpm * RPM, rel=1e-12)
        assert mg_b["power"] == pytest.approx(power, rel=1e-12)
        assert mg_b["electrical_power"] == pytest.approx(power / ETA, rel=1e-12)
        assert rows[i].battery_power["dc"] == pytest.approx(power / ETA, rel=1e-12)
        assert rows[i].power_out == pytest.approx(power, rel=1e-12)
    series = rows[3]
    assert series.machines["MG-A"]["power"] == pytest.approx(-40e3, rel=1e-12)
    assert series.machines["MG-A"]["speed"] == pytest.approx(2500 * RPM, rel=1e-12)
    assert series.battery_power["dc"] == pytest.approx(0.0, abs=1e-6)
    assert series.port_power["wheels"] == pytest.approx(0.81 * 40e3, rel=1e-12)
    split = rows[4]     # 25 kW at the wheels, the battery at 0 W: the engine gives
    assert split.port_power["wheels"] == pytest.approx(25e3, rel=1e-12)
    electric = sum(m["electrical_power"] for m in split.machines.values())
    assert electric == pytest.approx(0.0, abs=1e-6)
    mechanical = sum(m["power"] for m in split.machines.values())
    # ideal meshes: what the engine gives is the wheels' power plus the machines' losses
    assert split.port_power["engine"] == pytest.approx(25e3 - mechanical, rel=1e-12)
    assert split.machines["MG-A"]["speed"] == pytest.approx(2000 * RPM, rel=1e-12)


def test_a_machine_the_mode_switches_off_is_inactive_in_every_form(result) -> None:
    rows = result.rows
    assert math.isnan(rows[0].machines["MG-A"]["speed"])
    assert rows[0].to_dict()["machines"]["MG-A"]["state"] == "inactive"
    assert rows[0].to_dict()["machines"]["MG-A"]["speed"] is None
    assert result.machine_states("MG-A")[:4] == ["inactive", "inactive", "motoring",
                                                 "generating"]
    dumped = result.to_dict()["rows"][1]["machines"]["MG-A"]
    assert dumped == {"speed": None, "torque": 0.0, "power": 0.0, "electrical_power": 0.0,
                      "state": "inactive"}
    csv_lines = result.to_csv().splitlines()
    header = csv_lines[0].split(",")
    first = csv_lines[1].split(",")
    assert first[header.index("MG-A.state")] == "inactive"
    assert first[header.index("MG-A.speed [rad/s]")] == ""


def test_every_row_is_its_single_solve_built_by_hand(volt, result) -> None:
    """Each row against ``solve --mode`` of the model with the row's values set by hand:
    what the row gives, for an empty cell the mode's value or none."""
    kw, rpm = 1e3, RPM
    variants = [
        ("one-motor EV", {3: dict(speed=400 * rpm, power=10 * kw, torque=None)}, {}),
        ("one-motor EV", {3: dict(speed=600 * rpm)}, {}),       # the mode's 20 kW, free
        ("two-motor EV", {1: dict(speed=1500 * rpm), 3: dict(speed=800 * rpm, power=20 * kw,
                                                              torque=None)}, {}),
        ("series", {0: dict(speed=2500 * rpm, power=40 * kw), 3: dict(speed=500 * rpm)},
         {"dc": 0.0}),
        ("power split", {0: dict(speed=2000 * rpm, power=None),
                         3: dict(speed=800 * rpm, power=25 * kw)}, {"dc": 0.0}),
        ("power split", {0: dict(speed=2000 * rpm, power=30 * kw),
                         3: dict(speed=900 * rpm)}, {"dc": -5 * kw}),
    ]
    for row, (mode, ports, buses) in zip(result.rows, variants):
        model = volt
        for index, values in ports.items():
            model = model.with_port(index, **values)
        for bus, battery in buses.items():
            model = model.with_bus(bus, battery=battery)
        single = TrainCase.of(volt, mode).point(model).result
        assert_conservation(single)
        assert row.mode == mode and row.verdict == "ok"
        assert row.power_in == pytest.approx(sum(p for p in _crossing(single) if p > 0),
                                             rel=1e-9)
        for m in single.machines:
            got = row.machines[m.name]
            assert got["power"] == pytest.approx(m.power, rel=1e-9, abs=1e-6)
            assert got["torque"] == pytest.approx(m.torque, rel=1e-9, abs=1e-9)
            assert got["electrical_power"] == pytest.approx(m.electrical_power, rel=1e-9,
                                                            abs=1e-6)
        assert row.battery_power["dc"] == pytest.approx(
            single.buses["dc"].battery_power, rel=1e-9, abs=1e-6)


def _crossing(result):
    from powergraph.statics.machine_report import boundary_powers

    return boundary_powers(result)


def test_a_value_for_a_port_the_mode_switches_off_is_refused(tmp_path, capsys) -> None:
    points = tmp_path / "points.csv"
    points.write_text(HEADER + "0,one-motor EV,2000,,,400,10,\n10,one-motor EV,,,,400,10,\n")
    assert main(["cycle", str(VOLT), "--points", str(points)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith(f"powergraph: error: {points}: row 2 (mode 'one-motor EV'): "
                          "cannot be solved:")
    assert "engine is inactive in mode 'one-motor EV': it takes no speed" in err
    assert "Traceback" not in err and len(err.splitlines()) == 1


def test_a_row_lacking_a_value_names_the_row_the_mode_and_the_quantity() -> None:
    """One-motor EV without the mode's own wheels load, its battery free: a row that
    leaves the wheels' power empty gives the train no load at all."""
    data = yaml.safe_load(VOLT.read_text())
    del data["modes"]["one-motor EV"]["ports"]
    model = model_from_dict(data)
    text = HEADER + "0,one-motor EV,,,,400,10,\n10,one-motor EV,,,,400,,\n"
    with pytest.raises(UsageError) as caught:
        cycle(model, io.StringIO(text))
    message = str(caught.value)
    assert message.startswith("points: row 3 (mode 'one-motor EV'): cannot be solved:")
    assert message.count("wheels.power") == 1
    assert "(not given in this row nor by mode 'one-motor EV': wheels.power)" in message
    kept = cycle(model, io.StringIO(text), keep_going=True)
    assert kept.left_out == [1] and kept.rows[0].power_out == pytest.approx(10e3, rel=1e-9)


def test_a_speed_the_row_leaves_out_is_named_too() -> None:
    """Two-motor EV without the mode's MG-A speed: 2 DOF, the wheels' speed alone."""
    data = yaml.safe_load(VOLT.read_text())
    del data["modes"]["two-motor EV"]["ports"]["MG-A"]
    model = model_from_dict(data)
    with pytest.raises(UsageError, match=r"row 2 \(mode 'two-motor EV'\): cannot be "
                       r"solved: .*\(not given in this row nor by mode 'two-motor EV': "
                       r"MG-A\.speed\)"):
        cycle(model, io.StringIO(HEADER + "0,two-motor EV,,,,800,20,\n1,two-motor EV,,,,800,20,\n"))


def test_blank_rows_are_skipped_and_a_mode_is_still_required(volt) -> None:
    kept = cycle(volt, io.StringIO(HEADER + "0,one-motor EV,,,,400,10,\n,,,,,,,\n"
                                   "10,one-motor EV,,,,400,10,\n"))
    assert len(kept.durations) == 2
    with pytest.raises(UsageError, match=r"row 2, column 'mode': empty cell"):
        cycle(volt, io.StringIO(HEADER + "0,,,,,400,10,\n"))


def test_the_plot_names_the_runs_of_rows_in_one_mode(result) -> None:
    """The six rows run as one-motor EV (2 rows), two-motor EV, series, power split (2):
    four runs over 60 s, each at least 10 s wide: all named, every other one shaded."""
    import matplotlib
    import matplotlib.pyplot as plt

    matplotlib.use("Agg")
    durations = result.durations.tolist()
    assert durations == [10.0] * 6
    top, _ = result.plot()
    names = [t.get_text() for t in top.texts]
    assert names == ["one-motor EV", "two-motor EV", "series", "power split"]
    centres = [t.get_position()[0] for t in top.texts]
    assert centres == pytest.approx([10.0, 25.0, 35.0, 50.0])
    shaded = [c for c in top.collections if c.get_alpha() == 0.1]
    assert len(shaded) == 1 and len(shaded[0].get_paths()) == 2      # runs 2 and 4
    plt.close("all")
