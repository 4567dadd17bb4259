"""Port flows, the efficiency from the actual flows, and the result's caveats
(powergraph.statics.ports, PowerFlowResult.ports/efficiency/formal_efficiency/warnings).

Every expected value is derived by hand in the test."""
from __future__ import annotations

import math

import pytest

import powergraph as pg
from powergraph.model import model_from_dict
from powergraph.statics.ports import flow_efficiency
from powergraph.testing import assert_conservation

RPM = math.pi / 30.0

# Power-split device: one simple planetary. Engine on the carrier c (input, 2000 rpm,
# 100 N·m), generator MG1 on the sun s (declared output), ring r to the wheels (output,
# 4000 rpm). z_s = 30, z_r = 78, k = z_r / z_s = 2.6; sun-planet 0.98, planet-ring 0.99.
Z_S, Z_R, ETA_SP, ETA_PR = 30, 78, 0.98, 0.99
W_C, W_R, T_C = 2000 * RPM, 4000 * RPM, 100.0


def power_split(load_on_mg1: bool = False) -> pg.Model:
    return model_from_dict({
        "name": "power split",
        "components": {0: {"role": "frame"}, "c": {"name": "carrier"},
                       "s": {"name": "sun", "teeth": Z_S}, "p": {"teeth": 24, "count": 3},
                       "r": {"name": "ring", "teeth": Z_R, "internal": True}},
        "links": [{"type": "mesh", "between": ["s", "p"], "carrier": "c",
                   "efficiency": ETA_SP},
                  {"type": "mesh", "between": ["p", "r"], "carrier": "c",
                   "efficiency": ETA_PR}],
        "ports": [{"component": "c", "role": "input", "name": "engine",
                   "speed": f"{W_C!r} rad/s", "torque": T_C},
                  {"component": "s", "role": "output", "name": "MG1"},
                  {"component": "r", "role": "output", "name": "wheels", "speed": f"{W_R!r} rad/s"}]})


def test_power_split_mg1_motors_and_the_efficiency_comes_from_the_flows() -> None:
    """Hand derivation.

    Willis (carrier held): (w_s - w_c) / (w_r - w_c) = -k, so
    w_s = w_c - k (w_r - w_c) = 2000 - 2.6 × 2000 = -3200 rpm: the sun turns backwards.
    Torques on the train: T_c + T_s + T_r = 0 (the frame takes nothing: the carrier is a
    port). In the carrier's frame the sun's power is T_s (w_s - w_c); with T_s < 0 and
    w_s - w_c < 0 it is > 0, so the sun drives there and the ring receives
    η = η_sp η_pr of it: T_r (w_r - w_c) = -η T_s (w_s - w_c) = η k T_s (w_r - w_c), so
    T_r = η k T_s and T_s = -T_c / (1 + η k), T_r = -η k T_c / (1 + η k)
    (T_s < 0 confirms the assumed direction).
    Port powers (positive into the train): P_c = T_c w_c > 0, P_s = T_s w_s > 0 (MG1
    motors: it was declared an output), P_r = T_r w_r < 0.
    Efficiency from the flows: -P_r / (P_c + P_s); formal (declared roles):
    (-P_s - P_r) / P_c.
    """
    k, eta = Z_R / Z_S, ETA_SP * ETA_PR
    w_s = W_C - k * (W_R - W_C)
    t_s = -T_C / (1 + eta * k)
    t_r = -eta * k * T_C / (1 + eta * k)
    p_c, p_s, p_r = T_C * W_C, t_s * w_s, t_r * W_R
    assert p_s > 0 and p_r < 0

    result = pg.solve(power_split())
    assert_conservation(result)
    engine, mg1, wheels = result.ports
    assert (engine.name, mg1.name, wheels.name) == ("engine", "MG1", "wheels")
    assert mg1.speed == pytest.approx(w_s, rel=1e-12)
    assert [p.power for p in result.ports] == pytest.approx([p_c, p_s, p_r], rel=1e-12)
    assert [p.direction for p in result.ports] == ["in", "in", "out"]
    assert result.efficiency == pytest.approx(-p_r / (p_c + p_s), rel=1e-12)
    assert result.formal_efficiency == pytest.approx((-p_s - p_r) / p_c, rel=1e-12)
    assert result.efficiency < 1 and not result.self_locking
    reversed_ = [w for w in result.warnings if w.code == "role-reversed"]
    assert len(reversed_) == 1
    text = str(reversed_[0])
    assert text.startswith("ports[1] (MG1, component s): declared output, but power enters")
    assert f"+{p_s / 1000:.3g} kW" in text and "motors" in text


def test_port_powers_balance_the_losses_in_any_train() -> None:
    """Conservation: the ports' powers (into the train) add up to the losses."""
    result = pg.solve(power_split())
    assert sum(p.power for p in result.ports) == pytest.approx(result.total_loss, rel=1e-12)


def internal_pair(output_torque: float) -> pg.Model:
    """Gear 1 (20 teeth) inside ring 2 (60 teeth), frame-held: w2 = w1 / 3, same sense."""
    return model_from_dict({
        "name": "internal pair", "defaults": {"mesh_efficiency": 0.97},
        "components": {0: {"role": "frame"}, 1: {"name": "pinion", "teeth": 20},
                       2: {"name": "ring", "teeth": 60, "internal": True}},
        "links": [{"type": "mesh", "between": [1, 2]}],
        "ports": [{"component": 1, "role": "input", "name": "motor", "speed": "30 rad/s"},
                  {"component": 2, "role": "output", "name": "drum",
                   "torque": output_torque}]})


def test_a_positive_output_torque_back_drives_and_is_warned_about() -> None:
    """Hand derivation: w2 = 10 rad/s; the torque +12 N·m ON the train at the output
    feeds P2 = 120 W in there; the ring drives the mesh, which passes 0.97 of it, so the
    pinion gives 116.4 W out at the 'input' port. Efficiency from the flows 116.4 / 120
    = 0.97; formal (declared output / declared input) (-120) / (-116.4) = 1/0.97 > 1."""
    result = pg.solve(internal_pair(12.0))
    assert_conservation(result)
    motor, drum = result.ports
    assert drum.power == pytest.approx(120.0, rel=1e-12)
    assert motor.power == pytest.approx(-116.4, rel=1e-12)
    assert result.efficiency == pytest.approx(0.97, rel=1e-12)
    assert result.formal_efficiency == pytest.approx(1 / 0.97, rel=1e-12)
    assert not result.self_locking
    codes = [w.code for w in result.warnings]
    assert codes == ["role-reversed", "output-drives"]     # in the order of the ports
    assert str(result.warnings[0]).startswith("ports[0] (motor, component 1): declared "
                                              "input, but power leaves here (-116 W)")
    drives = str(result.warnings[1])
    assert drives.startswith("ports[1] (drum, component 2): declared output")
    assert "torque: -12 N*m" in drives     # how to write the resisting load


def test_a_resisting_output_torque_gives_no_warning() -> None:
    result = pg.solve(internal_pair(-12.0))
    assert_conservation(result)
    assert result.warnings == () and result.efficiency == pytest.approx(0.97, rel=1e-12)


def test_no_power_passing_gives_no_efficiency_and_is_not_self_locking() -> None:
    """Output torque 0 on a train without drag: every torque is 0, so every port's power
    is 0: the efficiency is undefined (None), not 'self-locking'."""
    result = pg.solve(internal_pair(0.0))
    assert_conservation(result)
    assert [p.direction for p in result.ports] == ["none", "none"]
    assert result.efficiency is None and result.efficiency_note
    assert not result.self_locking
    assert [w.code for w in result.warnings] == ["no-power"]
    data = result.to_dict()
    assert data["efficiency"] is None and data["self_locking"] is False
    assert "no power" in data["efficiency_note"]
    assert "self-locking" not in result.text_report().lower()
    assert "nan" not in result.text_report()


@pytest.mark.parametrize("powers, expected", [
    ([1000.0, -950.0], 0.95),               # forward
    ([-970.0, 1000.0], 0.97),               # back-driven: in at the declared output
    ([500.0, 20.0], 0.0),                   # every port takes power in (self-locking)
    ([100.0, -30.0, -60.0], 0.9),           # three ports
    ([60.0, 40.0, -90.0], 0.9),             # two sources
])
def test_flow_efficiency_is_out_over_in(powers, expected) -> None:
    assert flow_efficiency(powers) == pytest.approx(expected, rel=1e-15)


def test_model_warnings_come_first_in_the_result() -> None:
    from powergraph.errors import Caveat

    model = internal_pair(12.0)
    caveat = Caveat("a model caveat", "ports[0]", "test")
    import dataclasses

    result = pg.solve(dataclasses.replace(model, warnings=(caveat,)))
    assert result.warnings[0] == caveat and len(result.warnings) == 3


@pytest.mark.parametrize("changes, where", [
    ({"speed": 1.0, "power": 1e308}, "ports[0].power"),   # once gave η = 1, no loss
    ({"speed": 1e7}, "ports[0].speed"),                   # beyond 1e6 rad/s
    ({"speed": 1.0, "power": None, "torque": math.inf}, "ports[0].torque"),
])
def test_port_values_beyond_a_files_ranges_are_refused_by_solve(changes, where) -> None:
    """A model changed in Python is held to the ranges of the file format (speed 1e6
    rad/s, power 1e12 W, torque 1e12 N·m): 1e308 W at 1 rad/s is a torque of 1e308 N·m,
    whose products overflow and once came back as a lossless train."""
    model = pg.load_model("models/planetary_2kh_carrier_to_ring.yaml")
    with pytest.raises(pg.ModelError, match="out of range") as info:
        pg.solve(model.with_port(0, **changes))
    assert info.value.path == where
    inside = pg.solve(model.with_port(0, speed=1.0, power=1e12))   # the edge is allowed
    assert_conservation(inside)
    assert inside.efficiency == pytest.approx(pg.solve(model).efficiency, rel=1e-12)
