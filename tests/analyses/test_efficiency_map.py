"""Efficiency maps: flat for constant efficiencies, the friction law's trends otherwise."""
from __future__ import annotations

import json
import math

import numpy as np
import pytest

import powergraph as pg
from powergraph.analyses.efficiency_map import efficiency_map
from powergraph.cli.main import main
from powergraph.model import model_from_dict

ISO_PAIR = {"name": "iso pair", "components": {0: {"role": "frame"}, 1: {"teeth": 20},
                                               2: {"teeth": 40}},
            "links": [{"type": "mesh", "between": [1, 2],
                       "friction": {"model": "iso14179", "viscosity": 30, "roughness": 0.5},
                       "geometry": {"module": 2, "face_width": 20}}],
            "ports": [{"component": 1, "role": "input", "speed": 100.0, "power": 1000.0},
                      {"component": 2, "role": "output"}]}


def test_constant_efficiencies_give_a_flat_map_equal_to_the_closed_form() -> None:
    # Sun -> carrier, ring fixed: (1 + η0·k)/(1 + k) with η0 = η(s-p)·η(p-r) (closed form).
    model = pg.load_model("models/planetary_2kh_sun_to_carrier.yaml")
    result = pg.solve(model)
    meshes = model.meshes
    sun, ring = (model.components[c] for c in (meshes[0].between[0], meshes[1].between[1]))
    k = ring.teeth / sun.teeth
    eta0 = meshes[0].efficiency * meshes[1].efficiency
    closed = (1 + eta0 * k) / (1 + k)
    assert result.efficiency == pytest.approx(closed, rel=1e-9)
    emap = efficiency_map(model, [10.0, 50.0, 90.0], [300.0, 3000.0])
    assert not emap.load_dependent
    assert np.allclose(emap.efficiency, closed, rtol=1e-9, atol=0)


def test_friction_map_points_are_fixed_points_of_the_iso_law() -> None:
    model = model_from_dict(ISO_PAIR)
    emap = efficiency_map(model, [20.0, 100.0, 200.0], [500.0, 3000.0])
    assert emap.load_dependent
    friction = model.links[0].blocks["friction"]
    for i, rpm in enumerate(emap.speeds_rpm):
        for j, torque in enumerate(emap.torques):
            eta = emap.efficiency[i, j]
            # Ratio 2: the pinion carries T_out/(2η) on r_w1 = 20 mm at v_t = ω1·0.020.
            force = torque / 2 / eta / 0.020
            speed = rpm * 2 * math.pi / 60 * 0.020
            assert friction.efficiency(force, speed)[1] == pytest.approx(eta, abs=1e-11)
    # μ grows as the load^0.2 and falls as the speed^-0.2: efficiency falls with torque
    # and rises with speed.
    assert np.all(np.diff(emap.efficiency, axis=1) < 0)
    assert np.all(np.diff(emap.efficiency, axis=0) > 0)


def test_cli_json_and_picture(tmp_path, capsys) -> None:
    path = tmp_path / "pair.yaml"
    path.write_text(json.dumps(ISO_PAIR))
    picture = tmp_path / "map.png"
    assert main(["map", str(path), "--torque", "20:200:4", "--speed", "500:3000:3",
                 "--rated", "150", "--json", "-o", str(picture)]) == 0
    data = json.loads(capsys.readouterr().out)
    assert len(data["efficiency"]) == 3 and len(data["efficiency"][0]) == 4
    assert data["rated_torque"] == 150 and data["load_dependent"] is True
    assert picture.stat().st_size > 1000


def _status(argv: list[str]) -> int:
    """Exit status of the command line (argparse exits on its own for bad syntax)."""
    try:
        return main(argv)
    except SystemExit as exc:
        return int(exc.code)


@pytest.mark.parametrize("args, fragment", [
    (["--torque", "0:10:3", "--speed", "100"], "torques must be > 0"),
    (["--torque", "10:20:x", "--speed", "100"], "START:STOP:N"),
    (["--torque", "10", "--speed", "0"], "non-zero"),
])
def test_cli_bad_arguments_exit_2(tmp_path, capsys, args, fragment) -> None:
    path = tmp_path / "pair.yaml"
    path.write_text(json.dumps(ISO_PAIR))
    assert _status(["map", str(path), *args]) == 2
    assert fragment in capsys.readouterr().err


def _pair_with_shaft_bearing(bearing: dict | None) -> dict:
    """Gears z 20/40 (η 0.98, r1 = m·z/2 = 20 mm from gear 1's geometry); gear 1's shaft in
    a bearing on the housing."""
    links = [{"type": "mesh", "between": [1, 2], "efficiency": 0.98}]
    if bearing is not None:
        links.append({"type": "bearing", "between": [1, 0], **bearing})
    return {"name": "pair with a shaft bearing",
            "components": {0: {"role": "frame"},
                           1: {"teeth": 20, "geometry": {"module": 2, "face_width": 10,
                                                         "bore_radius": 0}},
                           2: {"teeth": 40}},
            "links": links,
            "ports": [{"component": 1, "role": "input", "speed": 100.0},
                      {"component": 2, "role": "output", "torque": 50.0}]}


def test_drag_makes_the_map_rise_with_torque_as_the_closed_form() -> None:
    # Output load T on gear 2 (ratio 2): gear 1's teeth carry T/(2η); the shaft bearing
    # adds M = c·T/(2η) + T0 with c = mu·d/(2·r1), so T_in = (1 + c)·T/(2η) + T0 and
    #   η_train = T·(w/2)/(T_in·w) = T / ((1 + c)·T/η + 2·T0),
    # which rises with T towards η/(1 + c) and does not depend on the speed (T0 constant).
    from powergraph.testing import assert_conservation

    eta, mu, d, r1, t0 = 0.98, 0.002, 0.020, 0.020, 0.4
    c = mu * d / (2 * r1)
    model = model_from_dict(_pair_with_shaft_bearing(
        {"friction": {"mu": mu, "bore": "20 mm"}, "drag": {"no_load_torque": t0}}))
    torques = np.array([5.0, 20.0, 60.0, 150.0])
    emap = efficiency_map(model, torques, [300.0, 3000.0])
    closed = torques / ((1 + c) * torques / eta + 2 * t0)
    assert emap.load_dependent
    assert np.allclose(emap.efficiency, closed[None, :], rtol=1e-10, atol=0)
    assert np.all(np.diff(emap.efficiency, axis=1) > 0)
    # Points between the two solved ends are the train's own solves (gear 2 turns
    # backwards, so the resisting load torque on it is positive).
    for rpm in (300.0, 3000.0):
        result = pg.solve(model.with_port(0, speed=rpm * math.pi / 30)
                          .with_port(1, torque=20.0))
        assert_conservation(result)
        assert result.efficiency == pytest.approx(emap.efficiency[0 if rpm == 300 else 1, 1],
                                                  rel=1e-10)


def test_without_drag_the_map_is_flat() -> None:
    emap = efficiency_map(model_from_dict(_pair_with_shaft_bearing(None)), [5.0, 50.0, 150.0],
                          [300.0, 3000.0])
    assert not emap.load_dependent
    assert np.allclose(emap.efficiency, 0.98, rtol=1e-12, atol=0)


def test_speed_dependent_drag_lowers_the_efficiency_with_speed() -> None:
    # Drag a + b·|n|: at n1 rpm on gear 1, T_in = T/(2η) + a + b·n1.
    model = model_from_dict(_pair_with_shaft_bearing({"drag": {"a": 0.1, "b": 0.001}}))
    emap = efficiency_map(model, [10.0, 100.0], [500.0, 2000.0])
    for i, rpm in enumerate((500.0, 2000.0)):
        for j, torque in enumerate((10.0, 100.0)):
            t_in = torque / (2 * 0.98) + 0.1 + 0.001 * rpm
            assert emap.efficiency[i, j] == pytest.approx(torque / (2 * t_in), rel=1e-10)
    assert np.all(np.diff(emap.efficiency, axis=0) < 0)


def test_loss_map_is_the_hand_derived_input_torque_and_torque_loss(tmp_path) -> None:
    # Drag a + b·|n| on gear 1 (ratio 2, η 0.98): T_in = T/(2η) + a + b·n; the output
    # takes T·ω/2, so the torque loss referred to the input is T_in − T/2.
    model = model_from_dict(_pair_with_shaft_bearing({"drag": {"a": 0.1, "b": 0.001}}))
    emap = efficiency_map(model, [10.0, 100.0], [500.0, 2000.0])
    rows = emap.loss_map()
    expected = [(rpm, t / (2 * 0.98) + 0.1 + 0.001 * rpm) for rpm in (500.0, 2000.0)
                for t in (10.0, 100.0)]
    torques = [10.0, 100.0] * 2
    assert rows["speed_rpm"].tolist() == [rpm for rpm, _ in expected]
    assert np.allclose(rows["input_torque"], [t_in for _, t_in in expected], rtol=1e-10)
    assert np.allclose(rows["torque_loss"],
                       [t_in - t / 2 for (_, t_in), t in zip(expected, torques)], rtol=1e-9)
    # The command writes the same rows under VECTO's header.
    path = tmp_path / "pair.yaml"
    path.write_text(json.dumps(_pair_with_shaft_bearing({"drag": {"a": 0.1, "b": 0.001}})))
    target = tmp_path / "pair.vtlm"
    assert main(["map", str(path), "--torque", "10:100:2", "--speed", "500:2000:2",
                 "--loss-map", str(target)]) == 0
    lines = target.read_text().splitlines()
    assert lines[0] == "Input Speed [rpm],Input Torque [Nm],Torque Loss [Nm]"
    written = np.array([[float(x) for x in line.split(",")] for line in lines[1:]])
    assert np.allclose(written[:, 1], rows["input_torque"], rtol=1e-9)
    assert np.allclose(written[:, 2], rows["torque_loss"], rtol=1e-9)


def test_loss_map_of_the_friction_rv_balances_each_single_solve() -> None:
    # Input torque minus torque loss, times the input speed, is the power the output
    # takes in a single solve at that point (power in = power out + losses).
    from powergraph.analyses.efficiency_grid import at_point
    from powergraph.testing import assert_conservation

    model = pg.load_model("models/rv40e.yaml")
    emap = efficiency_map(model, [120.0, 380.0], [700.0, 1800.0])
    rows = emap.loss_map()
    sense = np.sign(pg.solve(model).ratio)
    for rpm, t_in, t_loss, torque in zip(rows["speed_rpm"], rows["input_torque"],
                                         rows["torque_loss"], [120.0, 380.0] * 2):
        result = pg.solve(at_point(model, rpm * math.pi / 30, torque, sense))
        assert_conservation(result)
        omega = rpm * math.pi / 30
        assert (t_in - t_loss) * omega == pytest.approx(result.output_power, rel=1e-8)
        assert t_loss * omega == pytest.approx(result.total_loss, rel=1e-8)


def test_rows_whose_ends_differ_are_solved_point_by_point(monkeypatch) -> None:
    import powergraph.analyses.efficiency_map as module

    model = model_from_dict(_pair_with_shaft_bearing({"drag": {"no_load_torque": 0.4}}))
    affine = efficiency_map(model, [5.0, 20.0, 60.0], [300.0])
    calls = iter(range(10 ** 6))
    monkeypatch.setattr(module, "load_regime", lambda m, r: next(calls))
    pointwise = efficiency_map(model, [5.0, 20.0, 60.0], [300.0])
    assert np.allclose(pointwise.efficiency, affine.efficiency, rtol=1e-10, atol=0)


def test_a_mode_whose_freewheel_depends_on_the_load_is_mapped_point_by_point() -> None:
    """Simpson first gear drives through F1 (holds the rear carrier against backward
    rotation). Turning the input forward, every point is the case's own answer (constant
    efficiencies: the solve's 97.54 % everywhere); turned backward, F1 would have to hold
    a torque of the sense it cannot: no consistent state, NaN, named in the report."""
    from pathlib import Path

    from powergraph.model import load_model
    from powergraph.statics.case import TrainCase

    model = load_model(Path(__file__).resolve().parents[2] / "models" / "simpson_3speed.yaml")
    expected = TrainCase.of(model, "1").point().result.efficiency
    result = efficiency_map(model, [50.0, 100.0], [-2500.0, 1000.0, 2500.0], mode="1")
    assert np.all(np.isnan(result.efficiency[0]))
    assert result.efficiency[1:] == pytest.approx(np.full((2, 2), expected), rel=1e-12)
    assert result.no_freewheel_state == ((-2500.0, 50.0), (-2500.0, 100.0))
    assert result.unconverged == ()
    assert "2 point(s) have no consistent freewheel state" in result.text_report()
