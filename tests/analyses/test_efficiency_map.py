"""Efficiency maps: flat for constant efficiencies, the friction law's trends otherwise;
both sides, driving and coasting (the output driving the train), and the VECTO loss map
of both quadrants. The command line's own checks are in tests/cli/test_cmd_map.py."""
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


# --- coasting: the output drives the train (torque < 0) -----------------------------------

PAIR = {"name": "pair", "components": {0: {"role": "frame"}, 1: {"teeth": 20}, 2: {"teeth": 40}},
        "links": [{"type": "mesh", "between": [1, 2], "efficiency": 0.98}],
        "ports": [{"component": 1, "role": "input", "speed": 100.0},
                  {"component": 2, "role": "output"}]}


def _vecto_rows_hold(rows: dict, ratio: float) -> None:
    """What VECTO asks of a loss map, on every row: the torque loss is >= 0, and its
    ``T_out = (T_in − T_loss)·i`` (i = |ω_in/ω_out|) gives the output torque back."""
    assert np.all(rows["torque_loss"] >= 0.0)
    assert np.allclose((rows["input_torque"] - rows["torque_loss"]) * ratio,
                       rows["output_torque"], rtol=1e-12, atol=1e-12)


def test_coasting_pair_is_the_hand_derivation() -> None:
    """One mesh, z 20 → 40 (i = |ω_in/ω_out| = 2), η = 0.98, input speed n.

    Driving, load T > 0 on gear 2: gear 1 drives, the mesh passes η of its power, so
    T_in·ω_in·η = T·ω_out: T_in = T/(i·η), efficiency η; torque loss (the lost power over
    ω_in) T_in − T/i = T·(1/η − 1)/i.

    Coasting, output torque −T (the load feeds T·ω_out): gear 2 drives, the mesh passes η
    of it to gear 1, and that leaves at the input: T_in·ω_in = −η·T·ω_out, so
    T_in = −η·T/i (negative: the input takes power out, VECTO's drag side), efficiency
    (power leaving at the input / power entering at the output) η·T·ω_out/(T·ω_out) = η;
    torque loss T_in − (−T)/i = (1 − η)·T/i ≥ 0. At −10 N·m: −4.9 N·m in, 0.1 N·m lost;
    VECTO's (T_in − T_loss)·i = (−4.9 − 0.1)·2 = −10. No load: nothing passes, NaN."""
    eta, i = 0.98, 2.0
    torques = np.array([-20.0, -10.0, 0.0, 10.0, 20.0])
    emap = efficiency_map(model_from_dict(PAIR), torques, [500.0, -1500.0])
    assert np.allclose(emap.efficiency[:, [0, 1, 3, 4]], eta, rtol=1e-12, atol=0)
    assert np.all(np.isnan(emap.efficiency[:, 2]))
    assert emap.self_locking == () and emap.sides.tolist() == [-1, -1, 0, 1, 1]
    rows = emap.loss_map()
    t_out = rows["output_torque"]
    expected_in = np.where(t_out < 0, eta * t_out / i, t_out / (i * eta))
    assert np.allclose(rows["input_torque"], expected_in, rtol=1e-12, atol=1e-15)
    assert np.allclose(rows["torque_loss"], np.where(t_out < 0, (1 - eta) * -t_out / i,
                                                     t_out * (1 / eta - 1) / i),
                       rtol=1e-10, atol=1e-15)
    assert rows["input_torque"][1] == pytest.approx(-4.9, rel=1e-12)
    assert rows["torque_loss"][1] == pytest.approx(0.1, rel=1e-10)
    _vecto_rows_hold(rows, i)
    # Both quadrants: negative input torques for the negative output torques.
    assert np.all(rows["input_torque"][t_out < 0] < 0)
    assert np.all(rows["input_torque"][t_out > 0] > 0)


def test_coasting_with_drag_is_the_hand_derivation_and_may_self_lock() -> None:
    """The pair with a drag a + b·n (n in rpm) on gear 1's shaft: coasting at −T the mesh
    still passes η·T/i to gear 1 (gear 2 drives it), the drag takes a + b·n, and the rest
    leaves at the input: T_in = a + b·n − η·T/i. When η·T/i < a + b·n nothing comes out
    (T_in > 0: the input must drive too): self-locking, efficiency 0, as the solve says.
    Otherwise the efficiency is (η·T/i − a − b·n)/(T/i). No load: T_in = a + b·n, all of it
    lost (the loss map's torque loss is the drag), the efficiency NaN."""
    from powergraph.analyses.efficiency_grid import at_point
    from powergraph.statics.verdicts import verdict_of
    from powergraph.testing import assert_conservation

    a, b, eta, i = 0.1, 0.001, 0.98, 2.0
    model = model_from_dict(_pair_with_shaft_bearing({"drag": {"a": a, "b": b}}))
    torques = np.array([-100.0, -10.0, -1.0, 0.0, 10.0])
    emap = efficiency_map(model, torques, [500.0, 2000.0])
    for k, rpm in enumerate((500.0, 2000.0)):
        drag = a + b * rpm
        for j, torque in enumerate(torques[:3]):
            passed = eta * -torque / i
            expected = max(passed - drag, 0.0) / (-torque / i)
            assert emap.efficiency[k, j] == pytest.approx(expected, rel=1e-10, abs=1e-15)
            result = pg.solve(at_point(model, rpm * math.pi / 30, torque, -1.0))
            assert_conservation(result)
            assert emap.efficiency[k, j] == pytest.approx(result.efficiency, rel=1e-12,
                                                          abs=1e-15)
            assert (verdict_of(result) == "self-locking") == (passed < drag)
        assert np.isnan(emap.efficiency[k, 3])
    assert emap.self_locking == ((500.0, -1.0), (2000.0, -1.0))
    rows = emap.loss_map()
    speed, t_out = rows["speed_rpm"], rows["output_torque"]
    drag = a + b * speed
    expected_in = np.where(t_out < 0, drag + eta * t_out / i, drag + t_out / (i * eta))
    assert np.allclose(rows["input_torque"], expected_in, rtol=1e-10)
    none = t_out == 0
    assert np.allclose(rows["torque_loss"][none], drag[none], rtol=1e-10)
    _vecto_rows_hold(rows, i)
    text = emap.text_report()
    assert "2 point(s) self-locking" in text and "-1 N·m (every speed)" in text
    assert "torque 0: no load, the efficiency is undefined" in text


def test_a_coasting_point_is_the_single_solve_and_the_back_driven_case() -> None:
    """The friction RV-40E (ISO first stage, pins, bearings, drags: every point its own
    fixed point, the grid batched by side): a coasting point of the map is the single
    solve with the output torque given negative, and the back-driven case
    (``TrainCase.of(..., backdrive=True)``) fed that power at the output — the same
    operating point, the same efficiency and verdict."""
    from powergraph.analyses.efficiency_grid import at_point
    from powergraph.statics.case import TrainCase
    from powergraph.statics.verdicts import VERDICTS, verdict_of
    from powergraph.testing import assert_conservation

    model = pg.load_model("models/rv40e.yaml")
    torques, speeds = np.array([-400.0, -60.0, -3.0, 0.0, 150.0]), np.array([-1815.0, 700.0])
    emap = efficiency_map(model, torques, speeds)
    assert emap.unconverged == ()
    for k, rpm in enumerate(speeds):
        omega = rpm * math.pi / 30
        for j, torque in enumerate(torques):
            single = pg.solve(at_point(model, omega, torque, 1.0))
            assert_conservation(single)
            assert VERDICTS[emap.verdicts[k, j]] == verdict_of(single)
            assert emap.input_power[k, j] == pytest.approx(single.input_power, rel=1e-9)
            assert emap.output_power[k, j] == pytest.approx(single.output_power, rel=1e-9,
                                                            abs=1e-12)
            if torque >= 0:
                continue
            assert emap.efficiency[k, j] == pytest.approx(single.efficiency, rel=1e-9,
                                                          abs=1e-12)
            fed = -single.output_power          # the power the load feeds at the output
            forward = model.with_port(0, speed=omega, power=fed, torque=None) \
                .with_port(1, speed=None, power=None, torque=None)
            back = TrainCase.of(forward, backdrive=True).point()
            assert back.verdict == verdict_of(single)
            assert back.efficiency == pytest.approx(single.efficiency, rel=1e-9, abs=1e-12)
    assert emap.efficiency[1, 0] > 0.8 and emap.self_locking == ((-1815.0, -3.0), (700.0, -3.0))
    _vecto_rows_hold(emap.loss_map(), 121.0)


def test_a_self_locking_train_locks_on_the_coasting_side() -> None:
    """Wang's RV-40E (every mesh 0.94) cannot be back-driven: coasting, the input must
    drive too, nothing comes out (efficiency 0, self-locking), as ``solve --backdrive``
    says; its loss map still loses >= 0 at every point, the input torque positive."""
    from powergraph.statics.case import TrainCase

    model = pg.load_model("models/rv40e_wang2021.yaml")
    emap = efficiency_map(model, [-200.0, 200.0], [1500.0])
    assert TrainCase.of(model, backdrive=True).point().verdict == "self-locking"
    assert emap.efficiency[0, 0] == 0.0 and emap.self_locking == ((1500.0, -200.0),)
    assert emap.efficiency[0, 1] == pytest.approx(pg.solve(model).efficiency, rel=1e-12)
    rows = emap.loss_map()
    assert np.all(rows["torque_loss"] >= 0) and np.all(rows["input_torque"] > 0)
    data = emap.to_dict()
    assert data["self_locking"] == [[1500.0, -200.0]] and data["sides"] == ["coasting", "driving"]
    json.dumps(data, allow_nan=False)


def test_a_mode_coasts_as_its_back_driven_case() -> None:
    """ZF 8HP, 3rd gear (clutches only, no freewheel): the map's coasting side is the
    mode's back-driven case at the same output torque; Simpson first gear drives through
    a freewheel that overruns when the output drives: no consistent state (NaN)."""
    from powergraph.statics.case import TrainCase

    model = pg.load_model("models/zf8hp_8speed.yaml")
    emap = efficiency_map(model, [-300.0, 300.0], [2000.0], mode="3")
    ratio = TrainCase.of(model, "3").point().result.ratio
    omega = 2000.0 * math.pi / 30
    forward = model.with_port(0, speed=omega, power=300.0 * omega / abs(ratio), torque=None)
    back = TrainCase.of(forward, "3", backdrive=True).point()
    assert back.verdict == "ok"
    assert emap.efficiency[0, 0] == pytest.approx(back.efficiency, rel=1e-10)
    simpson = pg.load_model("models/simpson_3speed.yaml")
    coasting = efficiency_map(simpson, [-100.0, 100.0], [1000.0], mode="1")
    assert np.isnan(coasting.efficiency[0, 0]) and coasting.efficiency[0, 1] > 0.9
    assert coasting.no_freewheel_state == ((1000.0, -100.0),)
