"""Hybrid duty cycles solved together (powergraph.analyses.cycle_hybrid): every row the
same as its single solve — powers in and out, loss, each element's and machine's loss,
efficiency, verdict, electrical share, negative split, warnings, each port's power, each
machine's speed, torque, mechanical and electrical power and state, each bus's battery
power (issue 37), with the batteries given per row or not — and a row that cannot
be solved together (it does not turn, does not settle, its torque is out of range...)
solved alone, for the single solve's reason.

Every test compiles the plain train's sweep (sympy, about 0.3 s) and most run single
solves to compare with: all are slow.
"""
from __future__ import annotations

import dataclasses
import io
from pathlib import Path
from types import MappingProxyType

import numpy as np
import pytest

import powergraph as pg
from powergraph.analyses import cycle_hybrid
from powergraph.analyses.cycle import _single_rows, cycle
from powergraph.analyses.cycle_hybrid import METHOD
from powergraph.analyses.cycle_points import read_points
from powergraph.analyses.cycle_rows import RowError
from powergraph.statics import machines

pytestmark = pytest.mark.slow

MODELS = Path(__file__).resolve().parents[2] / "models"
THS = MODELS / "ths2_power_split.yaml"
HEADER = "engine.speed [rpm],engine.power [kW],wheels.speed [rpm]\n"


def _random_points(n: int, seed: int) -> str:
    """Rows as benchmarks/cycle.py draws them: engine 1000-4000 rpm, 5-50 kW, wheels
    50-900 rpm (MG1 beyond its max_speed in some, negative splits in others)."""
    rng = np.random.default_rng(seed)
    rows = zip(rng.uniform(1000, 4000, n).tolist(), rng.uniform(5, 50, n).tolist(),
               rng.uniform(50, 900, n).tolist())
    return HEADER + "".join(f"{e!r},{p!r},{w!r}\n" for e, p, w in rows)


def _same_as_single(model, text: str, alone: tuple[int, ...] = ()):
    """The cycle of ``text`` solved together but for the rows ``alone``, checked row by
    row against single solves (with ``keep_going``)."""
    points = read_points(io.StringIO(text), model)
    solved_alone, single_row = [], cycle_hybrid.single_row

    def counted(base, points, i, *args):
        solved_alone.append(i)
        return single_row(base, points, i, *args)

    cycle_hybrid.single_row = counted
    try:
        batched = cycle(model, points, keep_going=True)
    finally:
        cycle_hybrid.single_row = single_row
    assert solved_alone == list(alone)
    single = _single_rows(model, points, keep_going=True)
    assert batched.method == METHOD and single.method == "single solves"
    for key in ("power_in", "power_out", "loss"):
        np.testing.assert_allclose(getattr(batched, key), getattr(single, key), rtol=1e-9,
                                   atol=1e-9)
    for key in ("efficiencies", "electrical_share"):
        np.testing.assert_allclose(getattr(batched, key), getattr(single, key), rtol=1e-9,
                                   atol=1e-15, equal_nan=True)
    assert list(batched.losses) == list(single.losses)
    for label, column in single.losses.items():
        np.testing.assert_allclose(batched.losses[label], column, rtol=1e-9, atol=1e-9,
                                   equal_nan=True, err_msg=label)
    verdicts = lambda r: [r.verdict_texts[c] for c in r.verdict_codes.tolist()]  # noqa: E731
    assert verdicts(batched) == verdicts(single)
    assert batched.negative_split.tolist() == single.negative_split.tolist()
    assert batched.with_machines.tolist() == single.with_machines.tolist()
    assert list(batched.warned_rows.items()) == list(single.warned_rows.items())
    assert [r.to_dict()["warnings"] for r in batched.rows] == \
        [r.to_dict()["warnings"] for r in single.rows]
    _same_flows(batched, single)
    return batched, single


def _same_flows(batched, single) -> None:
    """Issue 37: the machine columns of the batched rows are the single solves'."""
    assert batched.machines and list(batched.machines) == list(single.machines)
    assert list(batched.port_power) == list(single.port_power)
    assert list(batched.battery_power) == list(single.battery_power)
    close = lambda a, b, what: np.testing.assert_allclose(  # noqa: E731
        a, b, rtol=1e-9, atol=1e-9, equal_nan=True, err_msg=what)
    for name, column in single.port_power.items():
        close(batched.port_power[name], column, name)
    for bus, column in single.battery_power.items():
        close(batched.battery_power[bus], column, bus)
    for name, quantities in single.machines.items():
        assert list(batched.machines[name]) == list(quantities)
        for key, column in quantities.items():
            close(batched.machines[name][key], column, f"{name}.{key}")
        assert batched.machine_states(name) == single.machine_states(name), name
    # the rows not solved carry no flows, in both
    for result in (batched, single):
        for column in [*result.port_power.values(), *result.battery_power.values()]:
            assert np.isnan(column[result.failed]).all()
            assert not np.isnan(column[~result.failed]).any()


def test_random_rows_are_their_single_solves():
    model = pg.load_model(THS)
    batched, _ = _same_as_single(model, _random_points(300, 35))
    assert 0 < batched.negative_split.sum() < 300
    assert 0 < len(batched.warned_rows["over-max-speed"]) < 300
    # each row conserves energy: power in = power out + losses (elements and machines)
    solved = ~batched.failed
    assert solved.all()
    np.testing.assert_allclose(batched.power_in, batched.power_out + batched.loss, rtol=1e-9)
    np.testing.assert_allclose(batched.loss, sum(batched.losses.values()), rtol=1e-9)


def test_the_urban_cycle_keeps_its_documented_totals():
    # docs/performance.md: the totals of the single solves, to the last digits
    result = cycle(pg.load_model(THS), MODELS / "cycles" / "urban_synthetic.csv")
    assert result.method == METHOD and not result.failed.any()
    assert result.energy_in == pytest.approx(2_537_500.0, rel=1e-12)
    assert result.energy_out == pytest.approx(2_235_801.023615854, rel=1e-9)
    assert result.efficiency == pytest.approx(0.8811038516712725, rel=1e-9)
    assert result.negative_split_time == 46.0
    assert result.energy_in == pytest.approx(result.energy_out
                                             + sum(result.energy_lost.values()), rel=1e-9)


EDGE_ROWS = (HEADER
             + "2000,30,400\n"        # a positive split
             + "0,30,400\n"           # the engine's power given, but it does not turn
             + "2000,30,0\n"          # MG2 stands still: no machine determines the train
             + "2000,0,400\n"         # no power at all
             + "2000,-10,400\n"       # the engine takes power: role-reversed
             + "1500,15,1400\n"       # a negative split
             + "2000,30,1e-9\n"       # MG2's torque beyond a model's range
             + "2000,30,-400\n")      # backwards: MG1 over its max_speed


def test_rows_that_cannot_be_solved_together_are_solved_alone_for_their_reason():
    model = pg.load_model(THS)
    batched, _ = _same_as_single(model, EDGE_ROWS, alone=(1, 2, 6))
    assert [r.verdict.split(":")[0] for r in batched.rows] == \
        ["ok", "error", "error", "no power", "ok", "ok", "error", "ok"]
    assert "is out of range" in batched.rows[6].verdict
    assert batched.warned_rows == {"no-power": [3], "role-reversed": [4],
                                   "over-max-speed": [7]}
    assert batched.negative_split.tolist() == [False] * 5 + [True, False, True]
    # without keep_going the first such row stops the cycle, named as the single solves do
    points = read_points(io.StringIO(EDGE_ROWS), model)
    with pytest.raises(RowError) as alone:
        _single_rows(model, points, keep_going=False)
    with pytest.raises(RowError) as together:
        cycle(model, points)
    assert str(together.value) == str(alone.value)
    assert "row 3: cannot be solved" in str(together.value)


def test_rows_that_do_not_settle_are_the_single_solves_errors(monkeypatch):
    # one Newton step allowed (both solves): the rows needing more do not settle
    monkeypatch.setattr(machines, "MAX_STEPS", 1)
    monkeypatch.setattr(cycle_hybrid, "MAX_STEPS", 1)
    model = pg.load_model(THS)
    text = _random_points(20, 3) + "2000,0,400\n"      # the last row settles at once
    batched, _ = _same_as_single(model, text, alone=tuple(range(20)))
    assert {r.verdict for r in batched.rows[:20]} == {
        "error: buses: the bus balance did not settle (no machine torques meet the battery "
        "powers)"}
    assert batched.rows[20].verdict == "no power"
    with pytest.raises(RowError, match="row 2: cannot be solved: buses: the bus balance"):
        cycle(model, read_points(io.StringIO(text), model))


def _with_battery(model, battery):
    bus = dataclasses.replace(model.buses["dc"], battery=battery)
    return dataclasses.replace(model, buses=MappingProxyType({"dc": bus}))


def _two_buses(efficiency: float) -> dict:
    """The power split of tests/statics/test_machines.py, MG1 and MG2 each on its own bus
    with its battery given (so two balances, two unknown torques), the engine's power
    not given (the train takes it)."""
    machine = lambda name, part, bus: {"component": part, "role": "machine",  # noqa: E731
                                       "name": name, "efficiency": 0.9, "bus": bus}
    mesh = lambda a, b, **more: {"type": "mesh", "between": [a, b],  # noqa: E731
                                 "efficiency": efficiency, **more}
    return {"name": "two buses",
            "components": {"frame": {"role": "frame"}, "S": {"teeth": 30},
                           "P": {"teeth": 24, "count": 4},
                           "R": {"teeth": 78, "internal": True}, "C": {},
                           "R2": {"teeth": 40}, "W": {"teeth": 40}},
            "links": [mesh("S", "P", carrier="C"), mesh("P", "R", carrier="C"),
                      {"type": "bearing", "between": ["P", "C"]},
                      {"type": "fixed", "between": ["R", "R2"]}, mesh("R2", "W")],
            "ports": [{"component": "C", "role": "input", "name": "engine"},
                      machine("MG1", "S", "a"), machine("MG2", "R", "b"),
                      {"component": "W", "role": "output", "name": "wheels"}],
            "buses": {"a": {"battery": "5 kW"}, "b": {"battery": "-2 kW"}}}


@pytest.mark.parametrize("case", ["charging", "free battery", "wheel torque", "two buses",
                                  "ideal meshes"])
def test_other_loads_and_batteries(case):
    ths = pg.load_model(THS)
    rng = np.random.default_rng(4)
    speeds = zip(rng.uniform(1000, 4000, 40).tolist(), rng.uniform(-3000, 3000, 40).tolist())
    if case == "charging":              # the battery takes 5 kW
        _same_as_single(_with_battery(ths, -5000.0), _random_points(40, 5))
    elif case in ("two buses", "ideal meshes"):   # a Newton step in two unknowns
        model = pg.model_from_dict(_two_buses(0.98 if case == "two buses" else 1.0))
        _same_as_single(model, "engine.speed [rpm],wheels.speed [rpm]\n"
                        + "".join(f"{e!r},{w!r}\n" for e, w in speeds))
    elif case == "free battery":        # MG2's torque given, the battery takes the rest
        _same_as_single(_with_battery(ths, None), "engine.speed [rpm],engine.power [kW],"
                        "wheels.speed [rpm],MG2.torque [N*m]\n2000,30,400,50\n"
                        "1500,15,1400,-20\n2500,40,200,0\n")
    else:                               # the wheels' torque given; the engine follows
        batched, _ = _same_as_single(
            ths.with_port(0, power=None), "engine.speed [rpm],wheels.speed [rpm],"
            "wheels.torque [N*m]\n2000,400,-500\n2000,400,300\n1500,1400,-100\n")
        assert list(batched.warned_rows) == ["role-reversed", "output-drives"]


def test_machines_with_efficiency_maps(tmp_path):
    # the map of tests/statics/test_machine_maps.py (0-4000 rpm, 0-100 N·m): many rows
    # outside it, either sense of rotation, the engine giving and taking power
    rows = ["speed [rpm],torque [N·m],efficiency"]
    rows += [f"{n},{t},{0.80 + 0.001 * t + 0.03 * n / 4000!r}"
             for n in (0, 2000, 4000) for t in (0, 50, 100)]
    (tmp_path / "mg.csv").write_text("\n".join(rows) + "\n")
    model_path = tmp_path / "split.yaml"
    model_path.write_text(THS.read_text().replace("efficiency: 0.9, bus: dc",
                                                  "efficiency: {map: mg.csv}, bus: dc"))
    model = pg.load_model(model_path)
    rng = np.random.default_rng(3)
    points = HEADER + "".join(
        f"{e!r},{p!r},{w!r}\n" for e, p, w in zip(rng.uniform(1000, 4000, 60).tolist(),
                                                  rng.uniform(-5, 50, 60).tolist(),
                                                  rng.uniform(-900, 900, 60).tolist()))
    batched, _ = _same_as_single(model, points)
    assert 0 < len(batched.warned_rows["outside-map"]) < 60


BATTERY_HEADER = "engine.speed [rpm],engine.power [kW],wheels.speed [rpm],dc.battery [kW]\n"


def _battery_points(n: int, seed: int) -> str:
    """Random rows (as :func:`_random_points`) with the battery's power per row, from
    8 kW charging to 8 kW discharging."""
    rng = np.random.default_rng(seed)
    rows = zip(rng.uniform(1000, 4000, n).tolist(), rng.uniform(5, 50, n).tolist(),
               rng.uniform(50, 900, n).tolist(), rng.uniform(-8, 8, n).tolist())
    return BATTERY_HEADER + "".join(f"{e!r},{p!r},{w!r},{b!r}\n" for e, p, w, b in rows)


@pytest.mark.parametrize("battery", [0.0, None], ids=["balanced", "free"])
def test_issue37_a_battery_column_sets_the_bus_per_row(battery):
    # The model's battery (charge-sustaining, or free) is replaced by each row's; the
    # batched rows are the single solves of the model with that row's battery.
    model = _with_battery(pg.load_model(THS), battery)
    text = _battery_points(60, 37)
    batched, _ = _same_as_single(model, text)
    given = np.loadtxt(io.StringIO(text), delimiter=",", skiprows=1)[:, 3] * 1e3
    np.testing.assert_allclose(batched.battery_power["dc"], given, rtol=0, atol=0)
    # each bus balances: what its machines draw is the battery's power, row by row
    drawn = sum(m["electrical_power"] for m in batched.machines.values())
    np.testing.assert_allclose(drawn, given, rtol=1e-9, atol=1e-6)


def test_issue37_two_buses_each_set_per_row():
    model = pg.model_from_dict(_two_buses(0.98))
    rng = np.random.default_rng(6)
    rows = zip(rng.uniform(1000, 4000, 30).tolist(), rng.uniform(-3000, 3000, 30).tolist(),
               rng.uniform(-5, 5, 30).tolist(), rng.uniform(-5, 5, 30).tolist())
    batched, _ = _same_as_single(model, "engine.speed [rpm],wheels.speed [rpm],a.battery [kW],"
                                 "b.battery [W]\n" + "".join(
                                     f"{e!r},{w!r},{a!r},{b * 1e3!r}\n" for e, w, a, b in rows))
    assert list(batched.battery_power) == ["a", "b"]
