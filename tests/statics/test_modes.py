"""Trains solved in their modes (powergraph.statics.modes, docs/modes.md).

Ratios: the published ratios (tests/data/published_values.yaml) and the closed forms in
each model's description. Equivalence: every mode of every bundled model equals the same
gear written as a plain model with `fixed` links (hand-written YAML for a few, built by
replacing each engaged element with a `fixed` link for all). Freewheels and drag: a
two-speed derived by hand below.
"""
from __future__ import annotations

import copy
import math
from pathlib import Path

import pytest
import yaml

import powergraph as pg
from powergraph.errors import KinematicsError, ModelError
from powergraph.model import load_model, loads_model, model_from_dict
from powergraph.statics.modes import solve_mode
from powergraph.testing import assert_conservation

ROOT = Path(__file__).resolve().parents[2]
MODELS = ROOT / "models"
PUBLISHED = yaml.safe_load((ROOT / "tests" / "data" / "published_values.yaml").read_text())
SLOW = pytest.mark.slow
# The Ravigneaux 4-speed stays in the quick suite; the larger trains run in the full one.
MODE_MODELS = [pytest.param("simpson_3speed.yaml", marks=SLOW), "ravigneaux_4speed.yaml",
               pytest.param("lepelletier_6speed.yaml", marks=SLOW),
               pytest.param("zf8hp_8speed.yaml", marks=SLOW)]
K_SIMPSON = 72 / 24
Z_RAV = {"s1": 30, "s2": 36, "r": 72}
K_LEP = 1 + 37 / 71


def solved(model, mode):
    result = solve_mode(model, mode)
    assert result.result is not None, result.verdict
    assert_conservation(result.result)
    return result


# Closed forms from the models' descriptions (Simpson, Ravigneaux and Lepelletier sets).
CLOSED_FORMS = {
    "simpson_3speed.yaml": {"1": 1 + (1 + K_SIMPSON) / K_SIMPSON, "2": 1 + 1 / K_SIMPSON,
                            "3": 1.0, "R": -K_SIMPSON},
    "ravigneaux_4speed.yaml": {
        "1": Z_RAV["r"] / Z_RAV["s1"],
        "2": Z_RAV["r"] * (Z_RAV["s1"] + Z_RAV["s2"]) / (Z_RAV["s1"] * (Z_RAV["s2"] + Z_RAV["r"])),
        "3": 1.0, "4": Z_RAV["r"] / (Z_RAV["r"] + Z_RAV["s2"]), "R": -Z_RAV["r"] / Z_RAV["s2"]},
    "lepelletier_6speed.yaml": {"1": K_LEP * 85 / 31,
                                "2": K_LEP * 85 * (31 + 38) / (31 * (38 + 85)),
                                "3": K_LEP, "6": 85 / (85 + 38), "R": -K_LEP * 85 / 38},
    "zf8hp_8speed.yaml": {"1": 1 + 85 / 23, "6": 1.0},
}


@pytest.mark.parametrize("name", MODE_MODELS)
def test_published_and_closed_form_ratios(name: str) -> None:
    model = load_model(MODELS / name)
    published = PUBLISHED["automatic_transmissions"].get(name, {})
    for mode in model.modes:
        ratio = solved(model, mode).result.ratio
        if mode in published:
            assert ratio == pytest.approx(published[mode], abs=1e-3), mode
        if mode in CLOSED_FORMS[name]:
            assert ratio == pytest.approx(CLOSED_FORMS[name][mode], rel=1e-12), mode
    assert set(published) <= set(model.modes)


def _as_plain_file(path: Path, mode_result) -> dict:
    """The same gear written without shift elements: each engaged element (a freewheel
    holding included) a `fixed` link, the open ones left out (they have no drag here)."""
    data = yaml.safe_load(path.read_text())
    engaged = {e.name for e in mode_result.elements if e.engaged}
    links = []
    for link in data["links"]:
        if link["type"] in ("clutch", "brake", "freewheel"):
            assert "drag" not in link
            if link["name"] in engaged:
                links.append({"type": "fixed", "between": link["between"]})
        else:
            links.append(link)
    data["links"] = links
    data.pop("modes")
    return data


def _same(a, b) -> None:
    assert a.ratio == pytest.approx(b.ratio, rel=1e-9, abs=1e-12)
    assert a.efficiency == pytest.approx(b.efficiency, rel=1e-9, abs=1e-12)
    losses_a = {tuple(m.a + m.b) if False else (m.a, m.b): m.loss for m in a.meshes}
    losses_b = {(m.a, m.b): m.loss for m in b.meshes}
    assert losses_a.keys() == losses_b.keys()
    for key in losses_a:
        assert losses_a[key] == pytest.approx(losses_b[key], rel=1e-9, abs=1e-9), key


@pytest.mark.parametrize("name", MODE_MODELS)
def test_every_mode_equals_its_gear_written_with_fixed_links(name: str) -> None:
    path = MODELS / name
    model = load_model(path)
    for mode in model.modes:
        by_mode = solved(model, mode)
        plain = pg.solve(model_from_dict(_as_plain_file(path, by_mode)))
        assert_conservation(plain)
        _same(by_mode.result, plain)


@pytest.mark.parametrize("mode, file", [("1", "ravigneaux_first.yaml"),
                                        ("2", "ravigneaux_second.yaml"),
                                        ("R", "ravigneaux_reverse.yaml")])
def test_ravigneaux_modes_equal_the_one_file_per_gear_models(mode: str, file: str) -> None:
    """The hand-written gear files of the same set (the input shaft clutched to the sun is
    the sun's own shaft there)."""
    by_mode = solved(load_model(MODELS / "ravigneaux_4speed.yaml"), mode)
    plain = pg.solve(load_model(MODELS / file))
    assert_conservation(plain)
    _same(by_mode.result, plain)


def test_simpson_first_gear_through_its_freewheel_equals_the_file_with_c2_fixed() -> None:
    by_mode = solved(load_model(MODELS / "simpson_3speed.yaml"), "1")
    plain = pg.solve(load_model(MODELS / "simpson_first.yaml"))
    assert_conservation(plain)
    _same(by_mode.result, plain)
    assert by_mode.freewheels == {"F1": "holding"}


RAVIGNEAUX_THIRD = """
name: Ravigneaux third gear, small sun fixed to its own carrier
description: hand-written equivalent of ravigneaux_4speed.yaml mode 3 (a locked set)
defaults: {mesh_efficiency: 0.98}
components:
  0: {role: frame}
  s1: {teeth: 30}
  s2: {teeth: 36}
  p1: {teeth: 18, count: 3}
  p2: {teeth: 18, count: 3}
  r: {teeth: 72, internal: true}
  c: {}
links:
  - {type: mesh, between: [s1, p1], carrier: c}
  - {type: mesh, between: [p1, p2], carrier: c}
  - {type: mesh, between: [s2, p2], carrier: c}
  - {type: mesh, between: [p2, r], carrier: c}
  - {type: fixed, between: [s1, c]}
ports:
  - {component: s1, role: input, speed: 2000 rpm, power: 10 kW}
  - {component: r, role: output}
"""


def test_a_sun_fixed_to_its_own_carrier_locks_the_set_without_loss() -> None:
    """A locked set turns as a block: ratio 1, no mesh passes power in its carrier's
    frame, efficiency 1 -- and the mode with C1 + C3 gives the same."""
    plain = pg.solve(loads_model(RAVIGNEAUX_THIRD))
    assert_conservation(plain)
    assert plain.ratio == pytest.approx(1.0, rel=1e-12)
    assert plain.efficiency == pytest.approx(1.0, rel=1e-12)
    assert all(m.loss == pytest.approx(0.0, abs=1e-9) for m in plain.meshes)
    _same(solved(load_model(MODELS / "ravigneaux_4speed.yaml"), "3").result, plain)


# --- freewheels and drag: a two-speed derived by hand ----------------------------------
#
# A 2K-H set, k = z_r/z_s = 72/24 = 3: input on the sun s, output on the carrier c. The
# freewheel F holds the ring r against the frame (holds: positive: the ring may turn
# forward only); clutch C joins sun and ring (direct drive: the set turns as a block).
# Low (C open): ring held, ratio 1 + k = 4. Lossless, the external torques are T on the
# sun, k T on the ring, -(1 + k) T on the carrier, so F must apply +k T to the ring: with
# T > 0 that is the sign it holds. Driven backward (speed < 0, power > 0: T < 0) it would
# have to apply k T < 0: it cannot; overrunning leaves 2 DOF: no consistent state.
# High (C engaged): the set turns as a block, the ring at the input speed w > 0: F
# overruns (its slip w_r - 0 = w has the sign it allows); holding would lock the train.
TWO_SPEED = {
    "name": "two-speed", "description": "hand-derived test train",
    "components": {0: {"role": "frame"}, "s": {"teeth": 24}, "p": {"teeth": 24},
                   "r": {"teeth": 72, "internal": True}, "c": {}},
    "links": [{"type": "mesh", "between": ["s", "p"], "carrier": "c"},
              {"type": "mesh", "between": ["p", "r"], "carrier": "c"},
              {"type": "clutch", "name": "C", "between": ["s", "r"]},
              {"type": "freewheel", "name": "F", "between": ["r", 0], "holds": "positive"}],
    "modes": {"low": [], "high": ["C"]},
    "ports": [{"component": "s", "role": "input", "speed": 100.0, "power": 1000.0},
              {"component": "c", "role": "output"}],
}


def two_speed(speed=100.0, holds="positive", drag=None):
    data = copy.deepcopy(TWO_SPEED)
    data["ports"][0]["speed"] = speed
    data["links"][3]["holds"] = holds
    if drag is not None:
        data["links"][2]["drag"] = drag
    return model_from_dict(data)


def test_freewheel_holds_when_driven_forward_with_the_hand_derived_torque() -> None:
    low = solved(two_speed(), "low")
    torque = 1000.0 / 100.0
    assert low.freewheels == {"F": "holding"}
    assert low.result.ratio == pytest.approx(4.0, rel=1e-12)
    assert low.element("F").torque == pytest.approx(3 * torque, rel=1e-12)
    assert low.element("C").slip_speed == pytest.approx(100.0, rel=1e-12)   # w_s - w_r


def test_freewheel_overruns_in_high_gear_at_the_input_speed() -> None:
    high = solved(two_speed(), "high")
    assert high.freewheels == {"F": "overrunning"}
    assert high.element("F").slip_speed == pytest.approx(100.0, rel=1e-12)
    assert high.result.ratio == pytest.approx(1.0, rel=1e-12)


def test_freewheel_driven_backward_has_no_consistent_state() -> None:
    backward = solve_mode(two_speed(speed=-100.0), "low")
    assert backward.result is None
    assert "no consistent freewheel state" in backward.verdict
    assert "holds positive only" in backward.verdict and "2 DOF" in backward.verdict


def test_a_negative_freewheel_holds_the_backward_drive() -> None:
    backward = solved(two_speed(speed=-100.0, holds="negative"), "low")
    assert backward.freewheels == {"F": "holding"}
    assert backward.element("F").torque == pytest.approx(3 * 1000.0 / -100.0, rel=1e-12)


def test_drag_of_an_open_clutch_is_in_the_power_balance() -> None:
    """C open in low gear slips at w_s - w_r = 100 rad/s (the ring held); a drag of
    0.5 N·m loses 50 W, which the power balance (assert_conservation) accounts for."""
    ideal = solved(two_speed(), "low")
    dragged = solved(two_speed(drag={"no_load_torque": 0.5}), "low")
    assert dragged.element("C").drag_loss == pytest.approx(0.5 * 100.0, rel=1e-12)
    assert dragged.result.total_loss - ideal.result.total_loss == pytest.approx(50.0,
                                                                               rel=1e-9)
    assert dragged.result.output_power == pytest.approx(1000.0 - 50.0, rel=1e-12)
    high = solved(two_speed(drag={"no_load_torque": 0.5}), "high")
    assert high.element("C").drag_loss == 0.0      # engaged: no slip, no drag


# --- refusals (docs/modes.md) ----------------------------------------------------------

def _ravigneaux_with(modes: dict):
    data = yaml.safe_load((MODELS / "ravigneaux_4speed.yaml").read_text())
    data["modes"] = modes
    return model_from_dict(data)


def test_too_few_elements_leaves_dof_and_says_how_many_more() -> None:
    with pytest.raises(KinematicsError) as info:
        solve_mode(_ravigneaux_with({"x": ["C1"]}), "x")
    assert str(info.value) == ("modes.x: engages C1: leaves 2 DOF, the train needs 1 more "
                               "engaged element (or a given speed on 1 more port)")
    assert info.value.missing == "speed"


def test_elements_that_lock_the_train_are_refused() -> None:
    """C1 + B1 is 2nd gear and C1 + B2 1st: releasing B1 or B2 gives 1 DOF; releasing C1
    leaves the set held by both brakes (the input free: 1 DOF too)."""
    with pytest.raises(KinematicsError) as info:
        solve_mode(_ravigneaux_with({"x": ["C1", "B1", "B2"]}), "x")
    assert str(info.value) == ("modes.x: engages C1, B1, B2: these lock the train (0 DOF, "
                               "it needs 1); without C1 or B1 or B2 it would have 1")


def test_a_brake_holding_the_input_is_refused_naming_the_mode() -> None:
    with pytest.raises(ModelError, match=r"^modes\.x: engages B2, C3: .*fixed to the frame"):
        solve_mode(_ravigneaux_with({"1": ["C1", "B2"], "x": ["C3", "B2"]}), "x")


def test_an_engaged_element_carrying_nothing_is_a_redundant_caveat() -> None:
    """A clutch D to an empty drum d: engaged, it changes no speed and carries no torque."""
    data = yaml.safe_load((MODELS / "ravigneaux_4speed.yaml").read_text())
    data["components"]["d"] = {"name": "empty drum"}
    data["links"].append({"type": "clutch", "name": "D", "between": ["in", "d"]})
    data["modes"] = {"x": ["C1", "B2", "D"]}
    result = solved(model_from_dict(data), "x")
    assert [w.code for w in result.warnings] == ["redundant"]
    assert result.element("D").torque == pytest.approx(0.0, abs=1e-12)


def test_two_clutches_in_parallel_have_indeterminate_torques() -> None:
    data = yaml.safe_load((MODELS / "ravigneaux_4speed.yaml").read_text())
    data["links"].append({"type": "clutch", "name": "C1b", "between": ["in", "s1"]})
    data["modes"] = {"x": ["C1", "C1b", "B2"]}
    with pytest.raises(ModelError, match=r"^modes\.x: C1's torque is statically "
                                         r"indeterminate"):
        solve_mode(model_from_dict(data), "x")


def test_engaged_torques_balance_the_input_in_first_gear() -> None:
    """Ravigneaux 1st: C1 passes the whole input torque (it applies -T_in to the input
    shaft); B2 holds the carrier against T_out - T_in... by the train's balance: the
    brake's torque on the carrier equals minus the sum of the external torques on the
    train's other members (input and output), so the frame takes it."""
    result = solved(load_model(MODELS / "ravigneaux_4speed.yaml"), "1")
    t_in = 10_000.0 / (2000 * math.pi / 30)
    assert result.element("C1").torque == pytest.approx(-t_in, rel=1e-12)
    torques = result.result.torques
    assert result.element("B2").torque == pytest.approx(-(torques["in"] + torques["r"]),
                                                        rel=1e-9)


def test_without_a_modes_table_freewheels_are_decided_too() -> None:
    """The two-speed without `modes`: C open by default, F decides: it holds (low gear),
    as in the hand derivation above; with `engaged: true` on C it overruns."""
    data = copy.deepcopy(TWO_SPEED)
    del data["modes"]
    low = solved(model_from_dict(data), None)
    assert low.mode is None and low.freewheels == {"F": "holding"}
    assert low.result.ratio == pytest.approx(4.0, rel=1e-12)
    data["links"][2]["engaged"] = True
    high = solved(model_from_dict(data), None)
    assert high.freewheels == {"F": "overrunning"}
    assert high.result.ratio == pytest.approx(1.0, rel=1e-12)
