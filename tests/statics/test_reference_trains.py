"""Reference trains against closed forms and hand derivations, driven by
tests/data/reference_trains.yaml: the 2K-H and K-H-V closed forms of docs/theory.md, the
virtual-power RV-40E of Wang (2021)'s Table 1 worked by hand (values in
tests/data/published_values.yaml), and hand-derived Wolfrom, Ravigneaux, Simpson and Tuplin
trains.

Every solve is followed by the conservation checks of powergraph.testing.
"""
from __future__ import annotations

import math
from pathlib import Path

import pytest
import yaml

import powergraph as pg
from powergraph.kinematics import backdriven
from powergraph.testing import assert_conservation

TESTS = Path(__file__).resolve().parents[1]
MODELS = TESTS.parent / "models"
CASES = yaml.safe_load((TESTS / "data" / "reference_trains.yaml").read_text())
PUBLISHED = yaml.safe_load((TESTS / "data" / "published_values.yaml").read_text())


def _published(keys: str) -> float:
    """A value of published_values.yaml named by its keys joined with "/"."""
    node = PUBLISHED
    for key in keys.split("/"):
        node = node[key]
    return float(node)


def _expected(spec: dict, variables: dict) -> float:
    if "published" in spec:
        return _published(spec["published"])
    value = spec["value"]
    if isinstance(value, str):
        return float(eval(value, {"__builtins__": {}, **vars(math)}, variables))  # noqa: S307
    return float(value)


def _quantity(result, key: str) -> float:
    if key.startswith("loss_"):
        return result.element(int(key.split("_")[1])).loss
    if key.startswith("speed_"):
        return result.speeds[key.split("_", 1)[1]]
    return getattr(result, key)


def _solve(case: dict):
    model = pg.load_model(MODELS / case["model"])
    for index, changes in case.get("links", {}).items():
        model = model.with_link(int(index), **changes)
    if case.get("backdrive"):
        model = backdriven(model)
    result = pg.solve(model)
    assert_conservation(result)
    return result


@pytest.mark.parametrize("case", CASES, ids=[c["id"] for c in CASES])
def test_reference_train(case: dict) -> None:
    result = _solve(case)
    for key, spec in case["expect"].items():
        expected = _expected(spec, case.get("vars", {}))
        assert _quantity(result, key) == pytest.approx(
            expected, rel=spec.get("rtol", 0.0), abs=spec.get("atol", 0.0)), key


# Models tested by hand derivations outside the data file (file -> test that covers it).
HAND_TESTED = {
    "bevel_differential.yaml": "tests/statics/test_trains.py::test_bevel_differential_torque_bias",
    "closed_differential.yaml":
        "tests/statics/test_trains.py::test_closed_differential_circulates_twice_the_input_when_ideal",
    "rv40e.yaml": "tests/statics/test_trains.py::"
                           "test_rv40e_friction_model_is_the_khv_formula_composed_with_the_first_stage",
    "simpson_3speed.yaml": "tests/statics/test_modes.py::test_published_and_closed_form_ratios",
    "ravigneaux_4speed.yaml": "tests/statics/test_modes.py::test_published_and_closed_form_ratios",
    "lepelletier_6speed.yaml": "tests/statics/test_modes.py::test_published_and_closed_form_ratios",
    "zf8hp_8speed.yaml": "tests/statics/test_modes.py::test_published_and_closed_form_ratios",
    "oil_bath_reducer.yaml": "tests/statics/test_spin_losses.py::"
                             "test_the_oil_bath_reducer_is_its_laws_at_its_oil_temperature",
    "ths2_power_split.yaml": "tests/statics/test_machines.py::"
                             "test_the_ths2_model_file_with_ideal_meshes_is_the_hand_derivation",
    "volt_gen1.yaml": "tests/statics/test_hybrid_modes.py (every mode, by hand)",
    "honda_immd.yaml": "tests/statics/test_honda_immd.py (every mode, by hand)",
}


@pytest.mark.parametrize("path", sorted(MODELS.glob("*.yaml")), ids=lambda p: p.name)
def test_every_library_model_has_a_source_and_its_own_test(path: Path) -> None:
    model = pg.load_model(path)
    assert model.description and len(model.description) > 40, "description gives the source"
    covered = {case["model"] for case in CASES} | set(HAND_TESTED)
    assert path.name in covered, f"{path.name} has no closed-form or hand-derivation test"
    result = pg.solve(model)
    assert_conservation(result)


def test_the_worked_example_of_docs_theory() -> None:
    """docs/theory.md, section 6, step by step: 2K-H, sun in (1 kW at 1000 rpm), ring fixed.

    k = z_r/z_s; w_s = (1 + k) w_c, w_p = w_c (1 - z_r/z_p); T_s = P/w_s;
    λ_0 = -T_s (sun drives, f_0 = η_sp); λ_1 = (z_p/z_s) η_sp T_s (planet drives,
    f_1 = η_pr); T_c = -(1 + k η_sp η_pr) T_s; T_r = k η_sp η_pr T_s; virtual powers
    P k/(1 + k) and η_sp P k/(1 + k); losses (1 - η) times each.
    """
    z_s, z_p, z_r, eta_sp, eta_pr = 24, 24, 72, 0.98, 0.99
    k, power = z_r / z_s, 1000.0
    w_s = 1000 * math.pi / 30
    w_c = w_s / (1 + k)
    t_s = power / w_s
    result = pg.solve(pg.load_model(MODELS / "planetary_2kh_sun_to_carrier.yaml"))
    assert_conservation(result)
    assert result.speeds["carrier"] == pytest.approx(w_c, rel=1e-12)
    assert result.speeds["planet"] == pytest.approx(w_c * (1 - z_r / z_p), rel=1e-12)
    assert result.torques["sun"] == pytest.approx(t_s, rel=1e-12)
    assert result.torques["carrier"] == pytest.approx(-(1 + k * eta_sp * eta_pr) * t_s,
                                                      rel=1e-12)
    assert result.torques["frame"] == pytest.approx(k * eta_sp * eta_pr * t_s, rel=1e-12)
    sun_planet, planet_ring = result.meshes
    assert sun_planet.force == pytest.approx(-t_s, rel=1e-12)
    assert planet_ring.force == pytest.approx(z_p / z_s * eta_sp * t_s, rel=1e-12)
    assert (sun_planet.driver, planet_ring.driver) == ("sun", "planet")
    assert (sun_planet.factor, planet_ring.factor) == (eta_sp, eta_pr)
    rolled = power * k / (1 + k)
    assert sun_planet.carrier_frame_power == pytest.approx(rolled, rel=1e-12)
    assert planet_ring.carrier_frame_power == pytest.approx(eta_sp * rolled, rel=1e-12)
    assert sun_planet.loss == pytest.approx((1 - eta_sp) * rolled, rel=1e-9)
    assert planet_ring.loss == pytest.approx((1 - eta_pr) * eta_sp * rolled, rel=1e-9)
    assert result.efficiency == pytest.approx((1 + k * eta_sp * eta_pr) / (1 + k), rel=1e-12)
    assert result.passes == 1
