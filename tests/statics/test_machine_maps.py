"""Machines whose efficiency is a map over speed and torque, derived by hand.

The device: a single planetary power split (k = z_r/z_s = 78/30), engine on the carrier
at 2000 rpm and 30 kW, MG1 on the sun, MG2 on the ring, the ring to the wheels through an
ideal 40:40 pair, ideal meshes, a charge-sustaining bus. Both machines read one map whose
grid (0, 2000, 4000 rpm × 0, 50, 100 N·m) samples

    η(n, T) = 0.80 + 0.001·|T| + 0.03·|n|/4000,

linear in each variable, so the bilinear interpolation between grid points is exact.

Hand derivation (wheels at n_r rpm, the ring's speed):
- Willis: n_s = (1 + k)·2000 − k·n_r; the ideal balance fixes the sun's torque
  T_s = −T_c/(1 + k) whatever the machines' efficiencies, so MG1's point, P_1 = T_s·ω_s
  and η_1 = η(n_s, T_s) are known first; MG1 generates: P_e1 = P_1·η_1.
- The bus: P_e2 = −P_e1 > 0, MG2 motors. Its torque T = P_2/ω_r enters its own
  efficiency: P_2 = P_e2·(a + b·P_2/ω_r) with a = 0.80 + 0.03·n_r/4000, b = 0.001, so
  P_2 = a·P_e2 / (1 − b·P_e2/ω_r).
- Ideal meshes: the wheels take P_engine + P_1 + P_2.
"""
from __future__ import annotations

import json
import math

import pytest

from powergraph.cli.main import main
from powergraph.errors import ModelError
from powergraph.model import load_model, model_from_dict
from powergraph.statics import solve
from powergraph.testing import assert_conservation

K = 78 / 30
RPM = math.pi / 30


def eta(n_rpm: float, torque: float) -> float:
    return 0.80 + 0.001 * abs(torque) + 0.03 * abs(n_rpm) / 4000


def write_map(folder, name: str = "mg.csv", law=eta) -> str:
    rows = ["speed [rpm],torque [N·m],efficiency"]
    rows += [f"{n},{t},{law(n, t)!r}" for n in (0, 2000, 4000) for t in (0, 50, 100)]
    (folder / name).write_text("\n".join(rows) + "\n")
    return name


def device(wheel_rpm: float, efficiency) -> dict:
    machine = lambda name, part: {"component": part, "role": "machine", "name": name,  # noqa: E731
                                  "efficiency": efficiency, "bus": "dc"}
    return {
        "name": "power split with maps",
        "components": {"frame": {"role": "frame"}, "S": {"teeth": 30},
                       "P": {"teeth": 24, "count": 4}, "R": {"teeth": 78, "internal": True},
                       "C": {}, "R2": {"teeth": 40}, "W": {"teeth": 40}},
        "links": [{"type": "mesh", "between": ["S", "P"], "carrier": "C"},
                  {"type": "mesh", "between": ["P", "R"], "carrier": "C"},
                  {"type": "bearing", "between": ["P", "C"]},
                  {"type": "fixed", "between": ["R", "R2"]},
                  {"type": "mesh", "between": ["R2", "W"]}],
        "ports": [{"component": "C", "role": "input", "name": "engine", "speed": "2000 rpm",
                   "power": "30 kW"},
                  machine("MG1", "S"), machine("MG2", "R"),
                  {"component": "W", "role": "output", "name": "wheels",
                   "speed": f"{-wheel_rpm} rpm"}],
        "buses": {"dc": {"battery": "0 W"}},
    }


def model_with_map(tmp_path, wheel_rpm: float, law=eta):
    path = tmp_path / "split.yaml"
    path.write_text(json.dumps(device(wheel_rpm, {"map": write_map(tmp_path, law=law)})))
    return load_model(path)


def by_hand(wheel_rpm: float) -> dict:
    w_c, w_r = 2000 * RPM, wheel_rpm * RPM
    n_s = (1 + K) * 2000 - K * wheel_rpm
    t_s = -(30e3 / w_c) / (1 + K)
    p_1 = t_s * n_s * RPM
    eta_1 = eta(n_s, t_s)
    p_e2 = -p_1 * eta_1
    a, b = 0.80 + 0.03 * wheel_rpm / 4000, 0.001
    p_2 = a * p_e2 / (1 - b * p_e2 / w_r)
    return {"p_1": p_1, "eta_1": eta_1, "p_2": p_2, "eta_2": p_2 / p_e2,
            "wheels": 30e3 + p_1 + p_2}


def test_machines_on_a_map_match_the_hand_derivation(tmp_path) -> None:
    result = solve(model_with_map(tmp_path, 1500.0))
    assert_conservation(result)
    expected = by_hand(1500.0)
    mg1, mg2 = result.machines
    assert mg1.power == pytest.approx(expected["p_1"], rel=1e-9)
    assert mg1.efficiency == pytest.approx(expected["eta_1"], rel=1e-12)
    assert mg1.state == "generating" and mg2.state == "motoring"
    assert mg2.power == pytest.approx(expected["p_2"], rel=1e-9)
    assert mg2.efficiency == pytest.approx(expected["eta_2"], rel=1e-9)
    assert mg2.efficiency == pytest.approx(eta(1500.0, mg2.torque), rel=1e-12)
    assert result.output_power == pytest.approx(expected["wheels"], rel=1e-9)
    assert mg1.on_map and mg2.on_map
    assert not [w for w in result.warnings if w.code == "outside-map"]


def test_a_uniform_map_gives_the_constant_efficiency_answer(tmp_path) -> None:
    mapped = solve(model_with_map(tmp_path, 1500.0, law=lambda n, t: 0.9))
    constant = solve(model_from_dict(device(1500.0, 0.9)))
    for a, b in zip(mapped.machines, constant.machines):
        assert a.power == pytest.approx(b.power, rel=1e-12)
        assert a.electrical_power == pytest.approx(b.electrical_power, rel=1e-12)
    assert mapped.total_loss == pytest.approx(constant.total_loss, rel=1e-12)


def test_a_point_beyond_the_map_takes_the_edge_and_warns(tmp_path) -> None:
    # Wheels at 500 rpm: the sun turns at 3.6·2000 − 2.6·500 = 5900 rpm, beyond the map's
    # 4000 rpm, so MG1 takes the 4000 rpm row's value at its torque.
    result = solve(model_with_map(tmp_path, 500.0))
    assert_conservation(result)
    mg1 = result.machines[0]
    assert abs(mg1.speed) / RPM == pytest.approx(5900.0, rel=1e-12)
    assert not mg1.on_map
    assert mg1.efficiency == pytest.approx(eta(4000.0, mg1.torque), rel=1e-12)
    (warning,) = [w for w in result.warnings
                  if w.code == "outside-map" and w.path == "ports[1].efficiency"]
    assert "5900 rpm" in warning.message and "mg.csv" in warning.message
    # Issue 34, item 4: the axis and the distance: 5900 − 4000 = 1900 rpm; the torque
    # (T_s = 143.24/3.6 = 39.79 N·m) lies within 0..100 N·m, so it is not named.
    assert warning.message.startswith("ports[1] (MG1) runs at 5900 rpm and ")
    assert "the speed is 1900 rpm above the map's highest, 4000 rpm; the map's edge" \
        in warning.message and "torque is" not in warning.message


BAD_MAPS = [
    ("speed [rpm],torque,efficiency\n0,0,0.9\n", "expected the columns"),
    ("speed [rpm],torque [N·m],efficiency\n0,0,0.9\n0,10,0.9\n1000,0,0.9\n",
     "1 point(s) of the grid"),
    ("speed [rpm],torque [N·m],efficiency\n0,0,0.9\n0,0,0.8\n", "given twice"),
    ("speed [rpm],torque [N·m],efficiency\n0,0,1.2\n", "line 2: efficiency must be in [1e-06, 1]"),
    ("speed [rpm],torque [N·m],efficiency\n0,0,0\n", "line 2: efficiency must be in [1e-06, 1]"),
    ("speed [rpm],torque [N·m],efficiency\n0,0,0.9\n\n0,0,1e-300\n",
     "line 4: efficiency must be in [1e-06, 1], got 1e-300"),
    ("speed [blorps],torque [N·m],efficiency\n", "line 1: unknown unit 'blorps'"),
    ("speed [rpm],torque [rpm],efficiency\n", "line 1: 'rpm' is not a torque"),
    ("speed [rpm],torque [mnm],efficiency\n", "line 1: cannot read 'mnm' as a torque: 'mnm' "
                                                "could be mN*m or MN*m"),
    ("speed [],torque [N·m],efficiency\n", "line 1: no unit given: a speed is written in"),
    ("speed,torque [N·m],efficiency\n", "expected the columns"),
    ("speed [rpm],torque [N·m],efficiency [%]\n", "expected the columns"),
    ("speed [rpm],torque [N·m],efficiency\n1e7,0,0.9\n", "line 2: beyond the largest speed"),
    ("speed [rpm],torque [N·m],efficiency\n-10,0,0.9\n", "magnitudes"),
    ("speed [rpm],torque [N·m],efficiency\n0,abc,0.9\n", "not a finite number"),
    ("speed [rpm],torque [N·m],efficiency\n0,nan,0.9\n", "not a finite number"),
    ("speed [rpm],torque [N·m],efficiency\n0,0,0.9,1\n", "expected 3 values"),
    ("speed [rpm],torque [N·m],efficiency\n0,0,0.9\n0,10,0.9\n", "two speeds"),
    ("", "empty"),
]


@pytest.mark.parametrize("text, words", BAD_MAPS)
def test_a_bad_map_is_refused_naming_the_port_and_the_line(tmp_path, text, words) -> None:
    (tmp_path / "mg.csv").write_text(text)
    path = tmp_path / "split.yaml"
    path.write_text(json.dumps(device(1500.0, {"map": "mg.csv"})))
    with pytest.raises(ModelError, match="mg.csv") as info:
        load_model(path)
    assert info.value.path == "ports[1].efficiency.map" and words in info.value.message


@pytest.mark.parametrize("efficiency, words", [
    ({"map": "missing.csv"}, "cannot read the efficiency map"),
    ({"map": "mg.csv", "table": 1}, "table"),
    ({}, "map"),
])
def test_a_bad_map_reference_is_refused(tmp_path, efficiency, words) -> None:
    write_map(tmp_path)
    path = tmp_path / "split.yaml"
    path.write_text(json.dumps(device(1500.0, efficiency)))
    with pytest.raises(ModelError, match=words) as info:
        load_model(path)
    assert info.value.path.startswith("ports[1].efficiency")


def test_the_map_is_read_beside_the_model_file_from_any_folder(tmp_path, monkeypatch,
                                                                 capsys) -> None:
    folder = tmp_path / "models"
    folder.mkdir()
    write_map(folder)
    (folder / "split.yaml").write_text(json.dumps(device(1500.0, {"map": "mg.csv"})))
    monkeypatch.chdir(tmp_path)
    assert main(["solve", "models/split.yaml", "--json"]) == 0
    machines = json.loads(capsys.readouterr().out)["machines"]
    assert machines[0]["power"] == pytest.approx(by_hand(1500.0)["p_1"], rel=1e-9)
    assert machines[0]["efficiency"] == pytest.approx(by_hand(1500.0)["eta_1"], rel=1e-12)
    (folder / "mg.csv").write_text("speed [rpm],torque [N·m],efficiency\n0,0,2\n")
    assert main(["solve", "models/split.yaml"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "ports[1].efficiency.map" in err[0]


def test_a_cycle_names_the_rows_outside_a_machine_map(tmp_path) -> None:
    import io

    from powergraph.analyses.cycle import cycle

    model = model_with_map(tmp_path, 1500.0)
    points = "wheels.speed [rpm],duration [s]\n-1500,1\n-500,2\n-1400,1\n"
    result = cycle(model, io.StringIO(points))
    assert [r.warnings for r in result.rows] == [(), ("outside-map",), ()]
    assert "warning: outside-map in 1 row(s), file lines 3" in result.text_report()
    assert result.to_dict()["warned_rows"] == {"outside-map": [1]}


# Issue 34, item 3: the map is read through the bounded table reader, its problems are
# model errors at ports[1].efficiency.map naming the file; item 4: outside-map says which
# axis and by how much.
HEADER = "speed [rpm],torque [N·m],efficiency\n"


def write_grid(folder, speeds, torques, law=eta, header=HEADER, name="mg.csv") -> str:
    rows = [f"{n},{t},{law(n, t)!r}" for n in speeds for t in torques]
    (folder / name).write_text(header + "\n".join(rows) + "\n")
    return name


def load_device(tmp_path, wheel_rpm: float = 1500.0, name: str = "mg.csv"):
    path = tmp_path / "split.yaml"
    path.write_text(json.dumps(device(wheel_rpm, {"map": name})))
    return load_model(path)


def refused(tmp_path, name: str = "mg.csv") -> str:
    with pytest.raises(ModelError) as info:
        load_device(tmp_path, name=name)
    assert info.value.path == "ports[1].efficiency.map"
    return info.value.message


def test_issue34_a_map_with_a_byte_order_mark_is_the_map_without(tmp_path) -> None:
    write_map(tmp_path)
    plain = load_device(tmp_path).ports[1].efficiency
    (tmp_path / "mg.csv").write_bytes(b"\xef\xbb\xbf" + (tmp_path / "mg.csv").read_bytes())
    marked = load_device(tmp_path).ports[1].efficiency
    assert marked.values == plain.values and marked.speeds == plain.speeds
    # the grid as written: 0, 2000, 4000 rpm = 0, 2000π/30, 4000π/30 rad/s
    assert marked.speeds == pytest.approx((0.0, 2000 * RPM, 4000 * RPM), rel=1e-15)
    assert marked.values[1][2] == eta(2000, 100)


def test_issue34_a_map_that_is_not_utf8_names_the_file_and_the_byte(tmp_path) -> None:
    head = "speed [rpm],torque [Nm],efficiency\n0,0,0.9\n".encode()
    (tmp_path / "mg.csv").write_bytes(head + b"0,10,0.9\xe9\n")
    # the bad byte is the 9th of line 3 (after "0,10,0.9"), at offset len(head) + 8
    assert refused(tmp_path) == (f"mg.csv: not UTF-8 text: byte 0xe9 at byte {len(head) + 8} "
                                 '(line 3, column 9); save the file as UTF-8 (Excel: "CSV '
                                 'UTF-8")')


def test_issue34_a_map_over_the_table_size_limit_is_refused(tmp_path, monkeypatch) -> None:
    name = write_map(tmp_path)
    size = (tmp_path / name).stat().st_size
    monkeypatch.setenv("POWERGRAPH_MAX_TABLE_BYTES", str(size - 1))
    message = refused(tmp_path)
    assert message.startswith("cannot read the efficiency map 'mg.csv': ")
    assert f"is too large for an efficiency map ({size} bytes; the limit is {size - 1} " \
        "bytes" in message
    monkeypatch.setenv("POWERGRAPH_MAX_TABLE_BYTES", str(size))
    assert load_device(tmp_path).ports[1].efficiency.source == "mg.csv"


def test_issue34_dev_zero_as_a_map_stops_at_once_in_bounded_memory(tmp_path) -> None:
    import tracemalloc

    from powergraph.model.input_files import CHUNK

    write_map(tmp_path)
    load_device(tmp_path)            # imports and caches first: the peak is the reading's
    tracemalloc.start()
    try:
        message = refused(tmp_path, name="/dev/zero")
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert message == ("cannot read the efficiency map '/dev/zero': /dev/zero: a NUL byte "
                       "(U+0000) at byte 0 (line 1, column 1): not a text file")
    assert peak < 4 * CHUNK          # one chunk read, not the 100 MB limit


def test_issue34_max_rows_stops_the_reading_before_the_rows_are_held(tmp_path,
                                                                     monkeypatch) -> None:
    from powergraph.model import efficiency_table

    monkeypatch.setattr(efficiency_table, "MAX_ROWS", 4)
    rows = [f"{n},{t},0.9" for n in (0, 1000, 2000) for t in (0, 10)]   # 6 rows
    (tmp_path / "mg.csv").write_text(HEADER + "\n".join(rows) + "\nnot,a,row\n")
    # The 5th data row is line 6: the reading stops there, before the bad line 8.
    assert refused(tmp_path) == "mg.csv line 6: more than 4 rows"


def test_issue34_a_map_of_tiny_efficiencies_exits_2_naming_its_line(tmp_path, capsys) -> None:
    write_map(tmp_path, law=lambda n, t: 1e-300)
    path = tmp_path / "split.yaml"
    path.write_text(json.dumps(device(1500.0, {"map": "mg.csv"})))
    assert main(["solve", str(path)]) == 2
    assert capsys.readouterr().err.strip().splitlines() == [
        "powergraph: error: ports[1].efficiency.map: mg.csv line 2: efficiency must be in "
        "[1e-06, 1], got 1e-300"]
    write_map(tmp_path, law=lambda n, t: 1e-6)      # the bound itself is accepted
    assert load_device(tmp_path).ports[1].efficiency.values[0][0] == 1e-6


def test_issue34_a_scalar_machine_efficiency_has_the_same_bounds() -> None:
    data = device(1500.0, 1e-300)
    with pytest.raises(ModelError) as info:
        model_from_dict(data)
    assert str(info.value) == "ports[1].efficiency: efficiency must be in [1e-06, 1], got 1e-300"


def test_issue34_map_columns_take_any_unit_of_their_kind(tmp_path) -> None:
    write_map(tmp_path)
    in_rpm = load_device(tmp_path).ports[1].efficiency
    # The same grid in rad/s and kN·m: n rpm = n·π/30 rad/s, T N·m = T/1000 kN·m.
    rows = [f"{n * RPM!r},{t / 1000!r},{eta(n, t)!r}" for n in (0, 2000, 4000)
            for t in (0, 50, 100)]
    (tmp_path / "mg.csv").write_text("Speed [RAD/S], torque [kN m] ,EFFICIENCY\n"
                                     + "\n".join(rows) + "\n")
    in_si = load_device(tmp_path).ports[1].efficiency
    assert in_si.speeds == pytest.approx(in_rpm.speeds, rel=1e-15)
    assert in_si.torques == pytest.approx((0.0, 50.0, 100.0), rel=1e-15)
    assert in_si.values == in_rpm.values


def _outside(result):
    return [w for w in result.warnings if w.code == "outside-map"]


def test_issue34_outside_map_names_the_torque_axis_and_the_excess(tmp_path) -> None:
    # Wheels at 1500 rpm: the sun at 3.6·2000 − 2.6·1500 = 3300 rpm (inside 0..4000) with
    # |T_s| = (30 kW / 209.44 rad/s) / 3.6 = 39.789 N·m, beyond a map up to 20 N·m by 19.79.
    write_grid(tmp_path, (0, 2000, 4000), (0, 10, 20))
    result = solve(load_device(tmp_path, 1500.0))
    (warning,) = [w for w in _outside(result) if w.path == "ports[1].efficiency"]
    assert "the torque is 19.79 N·m above the map's highest, 20 N·m;" in warning.message
    assert "speed is" not in warning.message


def test_issue34_outside_map_names_a_speed_below_the_lowest(tmp_path) -> None:
    # Wheels at 1800 rpm: the sun at 7200 − 2.6·1800 = 2520 rpm, 480 rpm below 3000 rpm.
    write_grid(tmp_path, (3000, 4000, 5000), (0, 50, 100))
    result = solve(load_device(tmp_path, 1800.0))
    (warning,) = [w for w in _outside(result) if w.path == "ports[1].efficiency"]
    assert warning.message.startswith("ports[1] (MG1) runs at 2520 rpm and ")
    assert "the speed is 480 rpm below the map's lowest, 3000 rpm;" in warning.message


@pytest.mark.parametrize("end", ["\r\n", "\r"])
def test_issue34_a_map_with_windows_or_old_mac_line_ends_is_the_same_map(tmp_path, end) -> None:
    write_map(tmp_path)
    plain = load_device(tmp_path).ports[1].efficiency
    text = (tmp_path / "mg.csv").read_text()
    (tmp_path / "mg.csv").write_bytes(text.replace("\n", end).encode())
    assert load_device(tmp_path).ports[1].efficiency == plain


def test_issue34_a_map_of_only_its_header_is_refused_without_a_warning(tmp_path) -> None:
    """numpy's parser warns of a file with no data; the map says what is missing."""
    import warnings

    (tmp_path / "mg.csv").write_text(HEADER)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert "at least two speeds and two torques" in refused(tmp_path)


def test_issue34_a_cell_over_the_csv_field_limit_is_refused(tmp_path) -> None:
    (tmp_path / "mg.csv").write_text(HEADER + "0,0," + "9" * 200_000 + "\n")
    assert "field larger than field limit" in refused(tmp_path)


def test_the_map_over_arrays_of_points_is_the_map_at_each_point() -> None:
    # one rule, a point or many (the batched duty cycle reads the maps over its rows)
    import numpy as np

    from powergraph.model.efficiency_table import EfficiencyTable

    table = EfficiencyTable("mg.csv", speeds=(0.0, 100.0, 300.0), torques=(0.0, 10.0),
                            values=((0.7, 0.8), (0.75, 0.9), (0.8, 0.95)))
    speeds = np.array([0.0, 50.0, -100.0, 250.0, 300.0, 400.0, -1.0, 150.0])
    torques = np.array([0.0, -5.0, 10.0, 2.5, 10.0, 3.0, 20.0, 10.0])
    eta, on_map = table.at(speeds, torques)
    assert [table.at(s, t) for s, t in zip(speeds.tolist(), torques.tolist())] == \
        list(zip(eta.tolist(), on_map.tolist()))
    assert table.at(100.0, 10.0) == (0.9, True)            # a grid point, exactly
    assert table.at(400.0, 20.0) == (0.95, False)          # beyond both: the corner
    assert eta[1] == pytest.approx((0.7 + 0.8 + 0.75 + 0.9) / 4, rel=1e-15)
