"""Trains beyond the closed forms: hand derivations written here, and physical laws.

Every solve is followed by powergraph.testing.assert_conservation.
"""
from __future__ import annotations

import math
from pathlib import Path

import pytest

import powergraph as pg
from powergraph.kinematics import backdriven
from powergraph.model import loads_model
from powergraph.statics.flow import Node
from powergraph.testing import assert_conservation

MODELS = Path(__file__).resolve().parents[2] / "models"


def solve(model, **kwargs):
    result = pg.solve(model, **kwargs)
    assert_conservation(result)
    return result


def load(name: str):
    return pg.load_model(MODELS / name)


def test_wolfrom_efficiency_hand_derivation() -> None:
    """Wolfrom: w_c = 1, w_s = 1 + z_r1/z_s = 7, w_2 = 1 - (z_r1 z_p2)/(z_p1 z_r2).

    Carrier frame: the sun (mesh A) and ring 2 (mesh C) feed the planet, ring 1 (mesh B)
    receives: T_1 w_c = eB (eA T_s (w_s - w_c) + eC T_2 (w_2 - w_c)); the free carrier gives
    T_s + T_1 + T_2 = 0. Eliminating T_1:
    -T_2 [w_c + eB eC (w_2 - w_c)] = T_s [w_c + eA eB (w_s - w_c)].
    """
    model = load("wolfrom_3k.yaml").with_link(0, efficiency=0.97).with_link(2, efficiency=0.985)
    eA, eB, eC = 0.97, 0.98, 0.985
    ws, w2 = 1 + 72 / 12, 1 - (72 * 27) / (30 * 69)
    t_s = 1.0
    t_2 = -t_s * (1 + eA * eB * (ws - 1)) / (1 + eB * eC * (w2 - 1))
    expected = -t_2 * w2 / (t_s * ws)
    result = solve(model)
    assert result.efficiency == pytest.approx(expected, rel=1e-12)
    drivers = [e.driver for e in result.meshes]
    assert drivers == ["s", "p1", "r2"]  # the pattern the derivation assumed


def test_wolfrom_backdriven_self_locks_at_095() -> None:
    result = solve(backdriven(load("wolfrom_3k.yaml").with_mesh_efficiency(0.95)))
    assert result.self_locking and result.formal_efficiency < 0
    assert result.efficiency == 0.0     # both ports take power in: nothing leaves
    # at 0.99 it back-drives: efficiency between 0 and the forward one
    back = solve(backdriven(load("wolfrom_3k.yaml").with_mesh_efficiency(0.99)))
    forward = solve(load("wolfrom_3k.yaml").with_mesh_efficiency(0.99))
    assert 0 < back.efficiency < forward.efficiency and not back.self_locking


def test_closed_differential_circulates_twice_the_input_when_ideal() -> None:
    """Hand derivation (ideal): w_s = w, w_r = -w/2, w_c = -w/8, T_c = 8P/w.
    Moment and power balance of the planetary: T_s + T_r + T_c = 0 and
    T_s - T_r/2 - T_c/8 = 0 give T_r = -6P/w, T_s = -2P/w: the sun hands 2P back to the
    input shaft, the fixed-axis pair carries 3P to the ring. 2P circulates."""
    model = load("closed_differential.yaml").with_mesh_efficiency(1.0)
    result = solve(model)
    power = 1000.0
    assert result.ratio == pytest.approx(-8.0, rel=1e-12)
    assert result.circulating_power == pytest.approx(2 * power, rel=1e-9)
    assert result.element(2).carrier_frame_power == pytest.approx(3 * power, rel=1e-9)
    lossy = solve(load("closed_differential.yaml"))
    assert 0 < lossy.circulating_power < 2 * power and lossy.efficiency < 1


def test_bevel_differential_torque_bias() -> None:
    """In the case's frame the slower wheel drives the faster: T_fast = η1 η2 T_slow."""
    result = solve(load("bevel_differential.yaml"))
    assert result.dof == 2
    speeds = result.speeds
    assert speeds["R"] == pytest.approx(2 * 50 - 55, rel=1e-12)  # (w_L - w_c) = -(w_R - w_c)
    torques = result.torques
    assert torques["L"] == pytest.approx(0.97 * 0.97 * torques["R"], rel=1e-12)
    assert result.input_power == pytest.approx(30e3, rel=1e-12)


def test_two_input_differential_ideal_torque_split() -> None:
    """2-DOF planetary, sun and ring driven, carrier loaded: ideal torques are
    T_s : T_r : T_c = 1 : k : -(1 + k), whatever the two input speeds."""
    text = """
name: two-input differential
components: {0: {role: frame}, s: {teeth: 24}, p: {teeth: 24}, r: {teeth: 72, internal: true}, c: {}}
links: [{type: mesh, between: [s, p], carrier: c}, {type: mesh, between: [p, r], carrier: c}]
ports:
  - {component: s, role: input, speed: 100}
  - {component: r, role: input, speed: -10}
  - {component: c, role: output, torque: -80}
"""
    result = solve(loads_model(text))
    k = 3.0
    w_c = (100 + k * -10) / (1 + k)
    assert result.speeds["c"] == pytest.approx(w_c, rel=1e-12)
    assert result.torques["s"] == pytest.approx(80 / (1 + k), rel=1e-12)
    assert result.torques["r"] == pytest.approx(80 * k / (1 + k), rel=1e-12)
    assert result.efficiency == pytest.approx(1.0, rel=1e-12)


def test_two_input_differential_with_losses_obeys_the_mesh_law() -> None:
    text = """
name: two-input differential, lossy
defaults: {mesh_efficiency: 0.97}
components: {0: {role: frame}, s: {teeth: 24}, p: {teeth: 24}, r: {teeth: 72, internal: true}, c: {}}
links: [{type: mesh, between: [s, p], carrier: c}, {type: mesh, between: [p, r], carrier: c}]
ports:
  - {component: s, role: input, speed: 100, power: 500}
  - {component: r, role: input, speed: 20}
  - {component: c, role: output}
"""
    result = solve(loads_model(text))
    # carrier frame: sun at 100 - 35 = 65 rad/s drives, ring at 20 - 35 receives ... the
    # planet passes eta0 = 0.97^2 of the sun's carrier-frame power to the ring:
    w_c = (100 + 3 * 20) / 4
    t_s = 500 / 100
    t_r = -0.97**2 * t_s * (100 - w_c) / (20 - w_c)
    assert result.torques["r"] == pytest.approx(t_r, rel=1e-12)
    assert result.dof == 2 and result.input_power > 0


def test_count_changes_no_speed_and_no_total_torque() -> None:
    base = load("planetary_2kh_sun_to_carrier.yaml")
    text = (MODELS / "planetary_2kh_sun_to_carrier.yaml").read_text()
    more = loads_model(text.replace("count: 3", "count: 5"))
    a, b = solve(base), solve(more)
    assert a.speeds == b.speeds and a.torques == pytest.approx(b.torques, rel=1e-15)
    assert a.efficiency == b.efficiency


def test_solve_never_mutates_the_model() -> None:
    model = load("rv40e_wang2021.yaml")
    before = (model.links, model.ports, dict(model.components), model.bodies)
    solve(model)
    solve(backdriven(model))
    assert (model.links, model.ports, dict(model.components), model.bodies) == before


def test_losses_are_the_same_in_every_frame() -> None:
    result = solve(load("rv40e_wang2021.yaml"))
    for body in result.model.bodies:
        graph = result.flow_graph(body.members[0])
        into_loss = sum(d["power"] for _, v, d in graph.in_edges(Node("loss", "loss"), data=True))
        assert into_loss == pytest.approx(result.total_loss, rel=1e-12)


def test_rv_cycloid_mesh_rolls_n_plus_one_times_its_power() -> None:
    """docs/theory.md: in the crank's frame the cycloid-pin mesh passes (N + 1) = 40 × the power
    it delivers to the cycloid: |w4 - w3| / |w4| with w3/w4 = z4/(z4 - z5) = -39 (Eq. 4)."""
    result = solve(load("rv40e_wang2021.yaml").with_mesh_efficiency(1.0))
    mesh = result.element(1)
    into_cycloid = next(f.power for f in result.flows()
                        if f.source == "mesh 4-5" and f.target == "4")
    assert mesh.carrier_frame_power / into_cycloid == pytest.approx(40.0, rel=1e-12)


def test_self_locking_reports_no_positive_efficiency_and_consistent_directions() -> None:
    result = solve(backdriven(load("tuplin_256.yaml")))
    assert result.self_locking
    assert result.to_dict()["self_locking"] is True


def test_zero_power_input_is_refused_cleanly() -> None:
    text = """
name: pair
components: {0: {role: frame}, 1: {teeth: 20}, 2: {teeth: 40}}
links: [{type: mesh, between: [1, 2]}]
ports: [{component: 1, role: input, speed: 0, power: 10}, {component: 2, role: output}]
"""
    with pytest.raises(pg.ModelError, match="does not turn"):
        pg.solve(loads_model(text))


def test_default_input_is_one_watt_at_one_rad_per_second() -> None:
    text = """
name: pair
defaults: {mesh_efficiency: 0.9}
components: {0: {role: frame}, 1: {teeth: 20}, 2: {teeth: 40}}
links: [{type: mesh, between: [1, 2]}]
ports: [{component: 1, role: input}, {component: 2, role: output}]
"""
    result = solve(loads_model(text))
    assert result.speeds["1"] == 1.0 and result.input_power == pytest.approx(1.0, rel=1e-15)
    assert result.output_power == pytest.approx(0.9, rel=1e-12)
    assert math.isclose(result.ratio, -2.0, rel_tol=1e-12)


def _rv40e_friction_data() -> dict:
    from powergraph.model.yaml_loader import load_yaml_file

    return load_yaml_file(MODELS / "rv40e.yaml")


def _eta_c() -> float:
    """The cycloid mesh's basic efficiency from the file's pins and crank bearing blocks."""
    from powergraph.gears.cycloid_loss import (CrankBearing, PinContact, PinRing,
                                               cycloid_mesh_loss)

    return cycloid_mesh_loss(PinRing(39, 64.0, 3.0, 1.3), PinContact(0.05, rolling=True),
                             bearing=CrankBearing(0.0025, 13.0, 36.0)).efficiency


def test_rv40e_friction_model_is_the_khv_formula_composed_with_the_first_stage() -> None:
    """models/rv40e.yaml without its support bearings' friction and drag blocks,
    against a hand derivation (docs/losses.md).

    Speeds: the output body 6/7 turns at ω, the crank 2/3 at −N ω (N = z4 = 39, the
    cycloid Willis row (ω − ω3)/(0 − ω3) = z5/z4), the centre gear at (1 + a(N + 1)) ω with
    a = z2/z1 = 3. Torques (the mesh's on each gear; driver 1 in the first stage, the pins
    5 in the cycloid mesh, as the solver reports): first stage T2 = 3 η1 T1 with
    T1 = −T_in; cycloid mesh T5 = −(z5/z4) T4/η_c. The crank body balances T2 against the
    cycloid mesh's reaction T4 + T5, so T4 = 3 η1 T_in / (z5/(z4 η_c) − 1)
    = a η1 T_in · N η_K with η_K = η_c/(1 + N(1 − η_c)), the K-H-V stage efficiency.
    The output body (disc through the coupling, planet frame) gives
    P_out = (T4 + (1 + a η1) T_in) ω, P_in = (1 + a(N + 1)) T_in ω, so

        η = (a N η1 η_K + 1 + a η1) / (1 + a (N + 1)).

    η1 is the first stage's load-dependent ISO/TR 14179-2 efficiency at the solution; η_c
    the cycloid mesh's, from the pin ring and crank bearings of the file (computed here).
    """
    from powergraph.model import model_from_dict

    data = _rv40e_friction_data()
    for link in data["links"]:
        if link["type"] == "bearing":
            link.pop("friction", None)
            link.pop("drag", None)
    result = solve(model_from_dict(data))
    assert result.bearings == ()
    eta_1 = result.friction[0].efficiency
    a, n = 36 / 12, 39
    eta_k = _eta_c() / (1 + n * (1 - _eta_c()))
    assert result.efficiency == pytest.approx((a * n * eta_1 * eta_k + 1 + a * eta_1)
                                              / (1 + a * (n + 1)), rel=1e-9)


def test_rv40e_friction_model_with_its_support_bearings_by_hand() -> None:
    """models/rv40e.yaml with its support bearings, against the derivation above
    extended by the bearing torques (docs/losses.md, "Bearing friction and drag").

    The three bearings at ω = 15 rpm output (speeds as above):

    - input shaft [1, 0], drag M_in = 0.02 + 0.00001·1815 N·m, Δω = ω_in = 121 ω: the sun's
      mesh torque is T1' = T_in − M_in;
    - main bearings [6, 0], drag M_m = 2 N·m on the output body, Δω = ω;
    - crank supports [3, 7], two instances (one per crank), Δω = −Nω − ω = −(N + 1) ω:
      M_c = 2 (μ F d/2 + 0.02 N·m) with μ = 0.0018, d = 20 mm and F the tangential tooth
      force on one planet, |T2|/(2 r_2) = a η1 T1'/(2 a r_1) = η1 T1'/(2 r_1) (r_1 = 9 mm,
      the working = reference pitch radius of the V-zero pair, m z1/2). Since Δω < 0 the
      torque is +M_c on the crank and −M_c on the output body.

    The crank body's balance T2 − (T4 + T5) + M_c = 0 with T4 + T5 = −T4/(N η_K) gives
    T4 = (a η1 T1' − M_c) N η_K, and the output body takes
    T4 + (1 + a η1) T1' − M_c − M_m = T_load = 412 N·m. With K = a N η1 η_K + 1 + a η1 and
    M_c = 0.04 + μ d η1 T1'/(2 r_1):

        T1' (K − μ d η1 (N η_K + 1)/(2 r_1)) = 412 + M_m + 0.04 (N η_K + 1),

    T_in = T1' + M_in, and η = 412 ω / (T_in · 121 ω). Each bearing loses M·|Δω|.
    """
    result = solve(load("rv40e.yaml"))
    assert_conservation(result)
    eta_1 = result.friction[0].efficiency
    a, n, mu, d, r_1 = 36 / 12, 39, 0.0018, 0.020, 0.009
    eta_k = _eta_c() / (1 + n * (1 - _eta_c()))
    w = 15 * 2 * math.pi / 60
    m_in, m_m = 0.02 + 0.00001 * 1815, 2.0
    k = a * n * eta_1 * eta_k + 1 + a * eta_1
    t_1 = (412 + m_m + 0.04 * (n * eta_k + 1)) / (k - mu * d * eta_1 * (n * eta_k + 1) / (2 * r_1))
    m_c = 0.04 + mu * d * eta_1 * t_1 / (2 * r_1)
    t_in = t_1 + m_in
    assert result.efficiency == pytest.approx(412 / (121 * t_in), rel=1e-9)
    losses = {b.node: b.loss for b in result.bearings}
    assert losses == pytest.approx({"bearing 1-0": m_in * 121 * w, "bearing 6-0": m_m * w,
                                    "bearing 3-7": m_c * (n + 1) * w}, rel=1e-9)
    # The catalogue's rated point: 412 N·m at 15 rpm output.
    assert result.kinematics.body_speeds[result.model.body_of["6"]] == pytest.approx(w, rel=1e-12)
    assert result.output_power == pytest.approx(412 * w, rel=1e-12)
    # A physically plausible RV efficiency (catalogue curves: 80-90 % at rated torque).
    assert 0.80 < result.efficiency < 0.95
