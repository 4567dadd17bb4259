"""powergraph.testing catches broken results (so the conservation checks cannot pass
vacuously), and a cycling direction iteration gives no answer of its own (the solver then
searches: tests/statics/test_locking.py)."""
from __future__ import annotations

import dataclasses
from pathlib import Path
from types import MappingProxyType

import numpy as np
import pytest

import powergraph as pg
from powergraph.kinematics import elements_of
from powergraph.model import model_from_dict
from powergraph.statics.directions import settle
from powergraph.testing import (
    assert_conservation,
    assert_equilibrium,
    assert_kinematics,
    assert_locked,
    assert_mesh_law,
    assert_power_balance,
)

RV = Path(__file__).resolve().parents[1] / "models" / "rv40e_wang2021.yaml"


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


def test_a_cycling_direction_iteration_gives_no_pattern() -> None:
    elements = elements_of(pg.load_model(RV))
    rel = np.array([1.0, 1.0, 1.0])
    calls = {"n": 0}

    def flipping(factors: np.ndarray):
        calls["n"] += 1
        return np.array([-1.0, 1.0, -1.0]) * (1 if calls["n"] % 2 else -1), np.ones(3)

    pattern, passes, visited = settle(flipping, elements, rel)
    assert pattern is None and passes == 2
    assert visited == [(1, -1, 1), (-1, 1, -1)]


LOCKED = {"name": "K-H-V back-driven, load on the crank",
          "components": {0: {"role": "frame"}, "H": {}, "d": {"teeth": 39},
                         "pins": {"teeth": 40, "internal": True}},
          "links": [{"type": "mesh", "between": ["d", "pins"], "carrier": "H",
                     "efficiency": 0.94}, {"type": "fixed", "between": ["pins", 0]}],
          "ports": [{"component": "d", "role": "input", "speed": 1.0},
                    {"component": "H", "role": "output", "power": 10.0}]}


def test_locked_checks_catch_a_locked_train_that_moves() -> None:
    locked = pg.solve(model_from_dict(LOCKED))
    assert locked.lock is not None
    assert_conservation(locked)
    moving = dataclasses.replace(locked, kinematics=locked.lock.asked)
    with pytest.raises(AssertionError, match="at rest"):
        assert_locked(moving)
    driving = dataclasses.replace(locked, elements=tuple(
        dataclasses.replace(e, driver=e.a) for e in locked.elements))
    with pytest.raises(AssertionError, match="stick"):
        assert_locked(driving)


def test_mesh_law_catches_a_sticking_factor_outside_its_interval() -> None:
    locked = pg.solve(model_from_dict(LOCKED))
    assert_mesh_law(locked)
    wrong = dataclasses.replace(locked.elements[0], factor=0.5)  # [η, 1/η] = [0.94, 1.064]
    with pytest.raises(AssertionError, match="outside"):
        assert_mesh_law(dataclasses.replace(locked, elements=(wrong,) + locked.elements[1:]))


def test_random_trains_are_reproducible_and_cover_every_template() -> None:
    from powergraph.testing_trains import TEMPLATES, random_train

    assert random_train(5).data == random_train(5).data
    trains = [random_train(seed) for seed in range(200)]
    names = " ".join(" ".join(t.stages) for t in trains)
    for template in ("fixed-axis pair", "2K-H s->c", "2K-H r->c", "2K-H s->r",
                     "double-planet", "stepped-planet", "K-H-V", "RV", "Wolfrom",
                     "Ravigneaux first", "Ravigneaux second", "Ravigneaux reverse",
                     "closed differential", "2K-H differential", "(reversed)"):
        assert template in names, template
    assert {t.dof for t in trains} == {1, 2} and any(t.backdriven for t in trains)
    assert len(TEMPLATES) == 9
    etas = [link["efficiency"] for t in trains for link in t.data["links"]
            if "efficiency" in link]
    assert 0.90 <= min(etas) and max(etas) <= 1.0
