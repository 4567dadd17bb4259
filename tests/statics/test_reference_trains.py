"""REFERENCE §B and §C (and hand-derived trains), driven by tests/data/reference_trains.yaml.

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


def _expected(spec: dict, variables: dict) -> float:
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
    "rv40e_friction.yaml": "tests/statics/test_trains.py::"
                           "test_rv40e_friction_model_is_the_khv_formula_composed_with_the_first_stage",
}


@pytest.mark.parametrize("path", sorted(MODELS.glob("*.yaml")), ids=lambda p: p.name)
def test_every_library_model_has_a_source_and_its_own_test(path: Path) -> None:
    model = pg.load_model(path)
    assert model.description and len(model.description) > 40, "description gives the source"
    covered = {case["model"] for case in CASES} | set(HAND_TESTED)
    assert path.name in covered, f"{path.name} has no closed-form or hand-derivation test"
    result = pg.solve(model)
    assert_conservation(result)
