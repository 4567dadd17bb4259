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
    result = pg.solve(pg.load_model("models/rv40e.yaml"))
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


def test_geometry_without_friction_is_refused() -> None:
    data = _pair({"mu": 0.05}, {"module": 2})
    del data["links"][0]["friction"]
    with pytest.raises(ModelError, match="friction"):
        model_from_dict(data)
