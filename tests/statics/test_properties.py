"""Properties of random valid trains from the stage templates (powergraph.testing_trains),
checked with hypothesis: every train gets an answer that conserves power (or a consistent
locking verdict); ratios equal the product of the stages' closed forms; renaming and
shuffling ids changes nothing; a constant-η train scales linearly in power."""
from __future__ import annotations

import pytest

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

import powergraph as pg  # noqa: E402
from powergraph.model import model_from_dict  # noqa: E402
from powergraph.testing import assert_conservation  # noqa: E402
from powergraph.testing_trains import random_train, renamed, train_strategy  # noqa: E402

SETTINGS = settings(max_examples=25, deadline=None, derandomize=True,
                    suppress_health_check=[HealthCheck.too_slow])


def asked(result):
    """The kinematics of the motion asked (a locked result is at rest)."""
    return result.lock.asked if result.lock is not None else result.kinematics


@SETTINGS
@given(train_strategy())
def test_every_train_conserves_power_or_locks_consistently(train) -> None:
    result = pg.solve(train.model)
    assert_conservation(result)
    if result.lock is not None:
        assert result.efficiency == 0.0 and result.self_locking and result.lock.reasons


@SETTINGS
@given(train_strategy())
def test_ratio_and_speeds_equal_the_stages_closed_forms(train) -> None:
    kin = asked(pg.solve(train.model))
    if train.ratio is not None:
        assert kin.ratio == pytest.approx(train.ratio, rel=1e-9)
    for component, w in train.speeds.items():
        assert kin.speed(component) == pytest.approx(w, rel=1e-9, abs=1e-9)


@SETTINGS
@given(train_strategy(), st.integers(0, 1000))
def test_renaming_and_shuffling_ids_changes_nothing(train, shuffle) -> None:
    result = pg.solve(train.model)
    data, new = renamed(train.data, shuffle)
    model = model_from_dict(data)
    if train.backdriven:
        from powergraph.kinematics import backdriven

        model = backdriven(model)
    other = pg.solve(model)
    assert_conservation(other)
    assert (other.lock is None) == (result.lock is None)
    assert other.efficiency == pytest.approx(result.efficiency, rel=1e-9, abs=1e-12)
    assert other.input_power == pytest.approx(result.input_power, rel=1e-9, abs=1e-9)
    for cid, torque in result.torques.items():
        assert other.torques[new[cid]] == pytest.approx(torque, rel=1e-7, abs=1e-9)
    for e in result.meshes:
        twin = next(m for m in other.meshes
                    if {m.a, m.b} == {new[e.a], new[e.b]} and m.carrier == new[e.carrier])
        assert twin.loss == pytest.approx(e.loss, rel=1e-7, abs=1e-9)


@SETTINGS
@given(st.integers(0, 2**32 - 1), st.floats(0.9, 1.0), st.floats(1e-3, 1e3))
def test_constant_eta_train_scales_linearly_in_power(seed, eta, factor) -> None:
    train = random_train(seed, eta=(eta, eta), drive="forward", dof=1)
    base = pg.solve(train.model)
    scaled_ports = [dict(p, power=p["power"] * factor) if "power" in p else p
                    for p in train.data["ports"]]
    scaled = pg.solve(model_from_dict(dict(train.data, ports=scaled_ports)))
    assert_conservation(scaled)
    assert scaled.efficiency == pytest.approx(base.efficiency, rel=1e-9, abs=1e-12)
    assert scaled.total_loss == pytest.approx(base.total_loss * factor, rel=1e-9, abs=1e-12)
    for cid, torque in base.torques.items():
        assert scaled.torques[cid] == pytest.approx(torque * factor, rel=1e-9, abs=1e-12)
