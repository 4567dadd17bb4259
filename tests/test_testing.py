"""powergraph.testing catches broken results (so the conservation checks cannot pass
vacuously), and the direction iteration reports a cycle instead of answering."""
from __future__ import annotations

import dataclasses
from pathlib import Path
from types import MappingProxyType

import numpy as np
import pytest

import powergraph as pg
from powergraph.errors import SolveError
from powergraph.kinematics import elements_of
from powergraph.statics.directions import settle
from powergraph.testing import (
    assert_conservation,
    assert_equilibrium,
    assert_kinematics,
    assert_mesh_law,
    assert_power_balance,
)

RV = Path(__file__).resolve().parents[1] / "models" / "rv40e.yaml"


@pytest.fixture(scope="module")
def result():
    r = pg.solve(pg.load_model(RV))
    assert_conservation(r)
    return r


def test_power_balance_catches_a_wrong_total(result) -> None:
    broken = dataclasses.replace(result, total_loss=result.total_loss * 1.001)
    with pytest.raises(AssertionError, match="power in"):
        assert_power_balance(broken)


def test_kinematics_catches_a_wrong_speed(result) -> None:
    speeds = dict(result.kinematics.body_speeds)
    speeds["4"] *= 1.0001
    kin = dataclasses.replace(result.kinematics, body_speeds=MappingProxyType(speeds))
    with pytest.raises(AssertionError, match="Willis|equal speeds"):
        assert_kinematics(dataclasses.replace(result, kinematics=kin))


def test_equilibrium_catches_a_wrong_torque(result) -> None:
    torques = dict(result.external_torques)
    torques["6/7"] *= 1.001
    with pytest.raises(AssertionError, match="torque balance"):
        assert_equilibrium(dataclasses.replace(result, external_torques=MappingProxyType(torques)))


def test_mesh_law_catches_efficiency_applied_the_wrong_way(result) -> None:
    element = result.elements[1]
    wrong = dataclasses.replace(element, factor=1 / element.factor)
    elements = (result.elements[0], wrong) + result.elements[2:]
    with pytest.raises(AssertionError, match="links\\[1\\]"):
        assert_mesh_law(dataclasses.replace(result, elements=elements))


def test_a_cycling_direction_iteration_is_an_error_not_an_answer() -> None:
    elements = elements_of(pg.load_model(RV))
    rel = np.array([1.0, 1.0, 1.0])
    calls = {"n": 0}

    def flipping(factors: np.ndarray) -> np.ndarray:
        calls["n"] += 1
        return np.array([-1.0, 1.0, -1.0]) * (1 if calls["n"] % 2 else -1)

    with pytest.raises(SolveError, match="did not settle"):
        settle(flipping, elements, rel, 1e-12)
