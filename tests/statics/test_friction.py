"""Mesh efficiencies from friction: constant μ, ISO/TR 14179-2 with the load, validation.

Expected values: Ohlendorf's loss factor and the ISO fit evaluated by hand in the tests
from the pair's geometry and the power balance (force = torque / working pitch radius).
"""
from __future__ import annotations

import math

import pytest

import powergraph as pg
from powergraph.errors import ModelError
from powergraph.model import model_from_dict
from powergraph.testing import assert_conservation

ALPHA = math.radians(20.0)


def _pair(friction: dict, geometry: dict, ports: list | None = None) -> dict:
    return {"name": "pair", "components": {0: {"role": "frame"}, 1: {"teeth": 20},
                                           2: {"teeth": 40}},
            "links": [{"type": "mesh", "between": [1, 2], "friction": friction,
                       "geometry": geometry}],
            "ports": ports or [{"component": 1, "role": "input", "speed": 157.07963267948966,
                                "power": 5000.0}, {"component": 2, "role": "output"}]}


def _hand_loss_factor() -> float:
    # z 20/40, α 20°, standard: ε_1, ε_2 from the tip circles (module cancels).
    p_b = math.pi * math.cos(ALPHA)
    e1 = (math.sqrt(11**2 - (10 * math.cos(ALPHA))**2) - 10 * math.sin(ALPHA)) / p_b
    e2 = (math.sqrt(21**2 - (20 * math.cos(ALPHA))**2) - 20 * math.sin(ALPHA)) / p_b
    return math.pi * 3 / (20 * 2) * (1 - (e1 + e2) + e1**2 + e2**2)


def test_constant_mu_gives_one_minus_mu_hv() -> None:
    model = model_from_dict(_pair({"mu": 0.05}, {"module": 2}))
    result = pg.solve(model)
    assert_conservation(result)
    assert result.efficiency == pytest.approx(1 - 0.05 * _hand_loss_factor(), rel=1e-12)
    assert model.links[0].efficiency == pytest.approx(1 - 0.05 * _hand_loss_factor(), rel=1e-12)
    assert result.friction[0].mu == 0.05


def test_zero_friction_is_ideal() -> None:
    result = pg.solve(model_from_dict(_pair({"mu": 0.0}, {"module": 2})))
    assert_conservation(result)
    assert result.efficiency == 1.0


def test_iso14179_from_the_solved_load_and_speed() -> None:
    model = model_from_dict(_pair({"model": "iso14179", "viscosity": "30 mPa*s",
                                   "roughness": "0.5 um"}, {"module": 2, "face_width": 20}))
    result = pg.solve(model)
    assert_conservation(result)
    # Input 5 kW at 157.08 rad/s: T1 = 31.831 N·m on r_w1 = 20 mm -> F_t = 1591.5 N;
    # v_t = 157.08 · 0.020 = 3.1416 m/s; ρ_red = 6.8404·13.6808/20.5212 mm.
    force, speed = 5000.0 / 157.07963267948966 / 0.020, 157.07963267948966 * 0.020
    rho_red = (20 * math.sin(ALPHA)) * (40 * math.sin(ALPHA)) / (60 * math.sin(ALPHA))
    mu = 0.048 * ((force / math.cos(ALPHA) / 20) / (2 * speed * math.sin(ALPHA) * rho_red)) \
        ** 0.2 * 30 ** -0.05 * 0.5 ** 0.25
    state = result.friction[0]
    assert state.tangential_force == pytest.approx(force, rel=1e-12)
    assert state.pitch_speed == pytest.approx(speed, rel=1e-12)
    assert state.mu == pytest.approx(mu, rel=1e-12)
    assert result.efficiency == pytest.approx(1 - mu * _hand_loss_factor(), rel=1e-12)


def test_load_given_at_the_output_is_a_fixed_point() -> None:
    # The output torque is given, so the input torque (and the pinion's load) depends on the
    # efficiency: the passes must end where μ(F(η)) gives back η.
    ports = [{"component": 1, "role": "input", "speed": 100.0},
             {"component": 2, "role": "output", "torque": 200.0}]
    model = model_from_dict(_pair({"model": "iso14179", "viscosity": 30, "roughness": 0.5},
                                  {"module": 2, "face_width": 20}, ports))
    result = pg.solve(model)
    assert_conservation(result)
    state = result.friction[0]
    assert result.friction_passes >= 2
    # Output torque 200 N·m on z 40 -> input torque 100/η N·m (ratio 2): F_t = T1 / 0.020 m.
    t1 = 200.0 / 2 / state.efficiency
    assert state.tangential_force == pytest.approx(t1 / 0.020, rel=1e-9)
    again = model.links[0].blocks["friction"].efficiency(state.tangential_force,
                                                          state.pitch_speed)
    assert again[1] == pytest.approx(state.efficiency, abs=1e-12)


def test_planets_share_the_load() -> None:
    data = _pair({"model": "iso14179", "viscosity": 30, "roughness": 0.5},
                 {"module": 2, "face_width": 20})
    one = pg.solve(model_from_dict(data)).friction[0].tangential_force
    data["components"][2]["count"] = 3
    three = pg.solve(model_from_dict(data)).friction[0].tangential_force
    assert three == pytest.approx(one / 3, rel=1e-12)


def test_models_without_friction_are_unchanged() -> None:
    result = pg.solve(pg.load_model("models/rv40e_wang2021.yaml"))
    assert result.friction == () and result.friction_passes == 0
    assert result.efficiency == pytest.approx(0.287376, abs=5e-7)   # tests/data/published_values.yaml


@pytest.mark.parametrize("friction, geometry, path, fragment", [
    ({"mu": 0.05}, None, "links[0].geometry", "must be a mapping"),
    ({"mu": 0.05}, {"face_width": 3}, "links[0].geometry", "module"),
    ({"mu": 1.5}, {"module": 2}, "links[0].friction.mu", r"in \[0, 1\)"),
    ({"mu": 0.05, "viscosity": 30}, {"module": 2}, "links[0].friction.viscosity", "unknown field"),
    ({"model": "iso14179", "viscosity": 30, "roughness": 0.5}, {"module": 2},
     "links[0].geometry", "face_width"),
    ({"model": "magic"}, {"module": 2}, "links[0].friction.model", "unknown model 'magic'"),
    ({"mu": 0.05}, {"module": 2, "colour": "red"}, "links[0].geometry.colour", "unknown field"),
    ({"mu": 0.05}, {"module": 2, "addendum": 0.2}, "links[0].geometry", "contact ratio"),
    ({"model": "iso14179", "viscosity": "3 m", "roughness": 0.5}, {"module": 2, "face_width": 9},
     "links[0].friction.viscosity", "viscosity"),
])
def test_bad_friction_blocks_name_the_place(friction, geometry, path, fragment) -> None:
    with pytest.raises(ModelError, match=fragment) as info:
        model_from_dict(_pair(friction, geometry))
    assert str(info.value).startswith(path)


def test_efficiency_beside_friction_is_refused() -> None:
    data = _pair({"mu": 0.05}, {"module": 2})
    data["links"][0]["efficiency"] = 0.98
    with pytest.raises(ModelError, match="not both") as info:
        model_from_dict(data)
    assert str(info.value).startswith("links[0].efficiency")


def test_geometry_without_friction_describes_the_pair_and_keeps_the_efficiency() -> None:
    # A geometry alone (docs/feasibility.md) is the pair's involute geometry for the
    # feasibility checks: the efficiency stays the one given (no friction law).
    data = _pair({"mu": 0.05}, {"module": 2, "shifts": [0.1, -0.1]})
    del data["links"][0]["friction"]
    data["links"][0]["efficiency"] = 0.97
    model = model_from_dict(data)
    mesh = model.links[0]
    assert mesh.efficiency == 0.97 and "friction" not in mesh.blocks
    assert (mesh.blocks["geometry"].module, mesh.blocks["geometry"].shift_1) == (2.0, 0.1)
    result = pg.solve(model)
    assert_conservation(result)
    assert result.efficiency == pytest.approx(0.97)


def test_a_geometry_alone_must_mesh() -> None:
    # 20/40 with the pinion shifted by -1.5: inv α_w = inv 20° + 2 tan 20° (-1.5)/60 < 0,
    # no working pressure angle: the pair cannot mesh, refused as with friction.
    data = _pair({"mu": 0.05}, {"module": 2, "shifts": [-1.5, 0]})
    del data["links"][0]["friction"]
    with pytest.raises(ModelError) as info:
        model_from_dict(data)
    assert str(info.value).startswith("links[0].geometry")


# --- Cycloid stages: pins, output pins and crank bearing (docs/losses.md) -------------------

def _khv(lobes: int, mesh: dict, power: str = "1 kW") -> dict:
    """A K-H-V stage: crank H in, pins fixed, disc out through a coupling."""
    return {"name": "K-H-V", "components": {0: {"role": "frame"}, "H": {},
                                            "d": {"teeth": lobes, "count": 2},
                                            "p": {"teeth": lobes + 1, "internal": True},
                                            "out": {}},
            "links": [{"type": "mesh", "between": ["d", "p"], "carrier": "H", **mesh},
                      {"type": "fixed", "between": ["p", 0]},
                      {"type": "coupling", "between": ["d", "out"]}],
            "ports": [{"component": "H", "role": "input", "speed": "1500 rpm", "power": power},
                      {"component": "out", "role": "output"}]}


def khv_efficiency(lobes: int, eta_c: float) -> float:
    """η of a K-H-V stage whose pin mesh has the basic efficiency η_c, by hand.

    Crank H in (ω_H), pins fixed, disc out: Willis (ω_d − ω_H)/(0 − ω_H) = z_p/z_c gives
    ω_d = −ω_H/N (N = z_c lobes). In the crank's frame the ring turns at −ω_H and the disc
    at ω_d − ω_H = (N + 1)·ω_d. The output resists, so the disc receives P_v = (N + 1)·P_out
    in the crank frame: the pins drive it, and they pass P_v/η_c; the mesh loses
    (1 − η_c)·P_v/η_c. The losses are the same in every frame, so
    P_in = P_out + (N + 1)(1 − η_c)/η_c·P_out = P_out·(1 + N(1 − η_c))/η_c, and

        η = η_c / (1 + N (1 − η_c)).
    """
    return eta_c / (1 + lobes * (1 - eta_c))


@pytest.mark.parametrize("lobes", [9, 39, 119])
@pytest.mark.parametrize("eta_c", [0.9, 0.98, 0.998])
def test_khv_stage_efficiency_is_the_hand_formula(lobes: int, eta_c: float) -> None:
    result = pg.solve(model_from_dict(_khv(lobes, {"efficiency": eta_c})))
    assert_conservation(result)
    assert result.efficiency == pytest.approx(khv_efficiency(lobes, eta_c), rel=1e-12)


@pytest.mark.parametrize("lobes, mu, rolling, stage, units", [
    (39, 0.05, False, (64.0, 3.0, 1.3), False),
    (39, 0.002, True, (64.0, 3.0, 1.3), True),
    (9, 0.1, False, (20.0, 2.0, 1.2), False),
])
def test_khv_with_pins_is_the_hand_formula_with_the_friction_eta(lobes, mu, rolling, stage,
                                                                 units) -> None:
    from powergraph.gears.cycloid_loss import PinContact, PinRing, cycloid_mesh_loss

    circle, radius, eccentricity = stage
    eta_c = cycloid_mesh_loss(PinRing(lobes, circle, radius, eccentricity),
                              PinContact(mu, rolling=rolling)).efficiency
    mm = (lambda x: f"{x} mm") if units else (lambda x: x)
    pins = {"mu": mu, "rolling": rolling, "radius": mm(radius), "circle_radius": mm(circle),
            "eccentricity": mm(eccentricity)}
    result = pg.solve(model_from_dict(_khv(lobes, {"pins": pins})))
    assert_conservation(result)
    assert result.efficiency == pytest.approx(khv_efficiency(lobes, eta_c), rel=1e-12)
    state = result.friction[0]
    assert (state.model, state.mu, state.efficiency) == ("cycloid", mu, eta_c)
    # Force at the disc's pitch circle z_c·e times the crank-frame pitch speed, over the
    # two discs: the power the disc receives, η_c times what the pins pass.
    passed = abs(result.element(0).carrier_frame_power)
    assert 2 * state.tangential_force * state.pitch_speed == pytest.approx(eta_c * passed,
                                                                            rel=1e-9)


def test_khv_with_output_pins_and_bearing_multiplies_their_efficiencies() -> None:
    from powergraph.gears.cycloid_loss import (CrankBearing, OutputPins, PinContact, PinRing,
                                               cycloid_mesh_loss)

    mesh = {"pins": {"mu": 0.05, "radius": 3, "circle_radius": 64, "eccentricity": 1.3},
            "output_pins": {"count": 8, "circle_radius": "40 mm", "mu": 0.05},
            "crank_bearing": {"mu": 0.002, "bore_radius": 20}}
    loss = cycloid_mesh_loss(PinRing(39, 64.0, 3.0, 1.3), PinContact(0.05),
                             OutputPins(8, 40.0, 0.05), CrankBearing(0.002, 20.0))
    eta_c = loss.pin_efficiency * loss.output_efficiency * loss.bearing_efficiency
    result = pg.solve(model_from_dict(_khv(39, mesh)))
    assert_conservation(result)
    assert result.efficiency == pytest.approx(khv_efficiency(39, eta_c), rel=1e-12)


def test_pins_geometry_from_the_cycloid_block_or_the_disc_geometry() -> None:
    # cycloid: m = 3.2, x = 0.1875, rc = 0.9375 -> R_p = 64, e = 1.3, r_p = 3 (docs/cycloid.md)
    by_pins = model_from_dict(_khv(39, {"pins": {"mu": 0.05, "radius": 3, "circle_radius": 64,
                                                 "eccentricity": 1.3}}))
    by_cycloid = model_from_dict(_khv(39, {
        "pins": {"mu": 0.05},
        "cycloid": {"module": 3.2, "profile_error": 0, "shift": 0.1875, "rc": 0.9375}}))
    data = _khv(39, {"pins": {"mu": 0.05}})
    data["components"]["d"]["geometry"] = {
        "shape": "cycloid_disc", "width": 10, "pin_circle_radius": 64, "pin_radius": 3,
        "eccentricity": 1.3, "crank_hole_radius": 17, "crank_holes": 2, "pillar_radius": 9,
        "pillar_holes": 2, "center_bore_radius": 15}
    by_disc = model_from_dict(data)
    etas = [m.links[0].efficiency for m in (by_pins, by_cycloid, by_disc)]
    assert etas[1] == pytest.approx(etas[0], rel=1e-12)
    assert etas[2] == pytest.approx(etas[0], rel=1e-12)


@pytest.mark.parametrize("mesh, path, fragment", [
    ({"pins": {"mu": 0.05, "radius": 3, "circle_radius": 64}}, "links[0].pins",
     "eccentricity"),
    ({"pins": {"mu": 1.2, "radius": 3, "circle_radius": 64, "eccentricity": 1.3}},
     "links[0].pins.mu", r"\[0, 1\)"),
    ({"pins": {"mu": 0.05, "radius": 3, "circle_radius": 64, "eccentricity": 1.3,
               "colour": "red"}}, "links[0].pins.colour", "unknown field"),
    ({"pins": {"mu": 0.05, "radius": 3, "circle_radius": 64, "eccentricity": 1.7}},
     "links[0].pins", "looped"),
    ({"pins": {"mu": 0.05, "radius": 3, "circle_radius": 64, "eccentricity": 1.3},
      "efficiency": 0.99}, "links[0].efficiency", "not both"),
    ({"crank_bearing": {"mu": 0.002, "bore_radius": 13}}, "links[0].crank_bearing", "pins"),
    ({"pins": {"mu": 0.05, "radius": 3, "circle_radius": 64, "eccentricity": 1.3,
               "seat_radius": 2}}, "links[0].pins.seat_radius", "rolling"),
    ({"pins": {"mu": 0.05, "radius": 3, "circle_radius": 64, "eccentricity": 1.3},
      "output_pins": {"count": 8, "circle_radius": 40, "mu": 0.05},
      "crank_bearing": {"mu": 0.002, "bore_radius": 13, "crank_circle_radius": 36}},
     "links[0].output_pins", "not both"),
    ({"pins": {"mu": 0.05, "radius": 3, "circle_radius": 64, "eccentricity": 1.3},
      "output_pins": {"count": 8, "circle_radius": 40, "mu": 0.01, "rolling": True}},
     "links[0].output_pins.rolling", "seat_radius"),
    ({"pins": {"mu": 0.05, "radius": 3, "circle_radius": 64, "eccentricity": 1.3},
      "output_pins": {"count": 1, "circle_radius": 40, "mu": 0.01}},
     "links[0].output_pins.count", ">= 2"),
    ({"pins": {"mu": 0.05, "eccentricity": 1.2},
      "cycloid": {"module": 3.2, "profile_error": 0, "shift": 0.1875, "rc": 0.9375}},
     "links[0].pins.eccentricity", "disagrees"),
])
def test_bad_pin_blocks_name_the_place(mesh, path, fragment) -> None:
    with pytest.raises(ModelError, match=fragment) as info:
        model_from_dict(_khv(39, mesh))
    assert str(info.value).startswith(path)


def test_pins_on_a_pair_that_is_not_a_cycloid_stage_are_refused() -> None:
    data = _pair({"mu": 0.05}, {"module": 2})
    data["links"][0] = {"type": "mesh", "between": [1, 2],
                        "pins": {"mu": 0.05, "radius": 1, "circle_radius": 20,
                                 "eccentricity": 0.5}}
    with pytest.raises(ModelError, match="internal") as info:
        model_from_dict(data)
    assert str(info.value).startswith("links[0].pins")
