"""The torque a rigid joint carries (powergraph.statics.shift_torques), by hand."""
from __future__ import annotations

import pytest

import powergraph as pg
from powergraph.model import model_from_dict
from powergraph.statics.shift_torques import joint_torque
from powergraph.testing import assert_conservation


def test_a_brake_holding_a_ring_takes_k_times_the_sun_torque() -> None:
    """2K-H, k = 72/24 = 3, sun in at torque T = 2 N·m, carrier out, ring braked. Lossless,
    the external torques are T on the sun and k T on the ring: the brake applies
    +k T = 6 N·m to the ring (its first member)."""
    model = model_from_dict({
        "name": "2K-H", "components": {0: {"role": "frame"}, "s": {"teeth": 24},
                                       "p": {"teeth": 24}, "r": {"teeth": 72, "internal": True},
                                       "c": {}},
        "links": [{"type": "mesh", "between": ["s", "p"], "carrier": "c"},
                  {"type": "mesh", "between": ["p", "r"], "carrier": "c"},
                  {"type": "brake", "name": "B", "between": ["r", 0], "engaged": True}],
        "ports": [{"component": "s", "role": "input", "speed": 10.0, "torque": 2.0},
                  {"component": "c", "role": "output"}]})
    result = pg.solve(model)
    assert_conservation(result)
    assert joint_torque(result, 2) == pytest.approx(6.0, rel=1e-12)


def test_two_joints_in_parallel_are_indeterminate() -> None:
    model = model_from_dict({
        "name": "pair", "components": {0: {"role": "frame"}, 1: {"teeth": 20},
                                       2: {"teeth": 40}, 3: {}},
        "links": [{"type": "mesh", "between": [1, 2]},
                  {"type": "fixed", "between": [2, 3]}, {"type": "fixed", "between": [3, 2]}],
        "ports": [{"component": 1, "role": "input", "speed": 10.0},
                  {"component": 3, "role": "output"}]})
    result = pg.solve(model)
    assert_conservation(result)
    assert joint_torque(result, 1) is None
