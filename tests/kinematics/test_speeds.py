"""Kinematics alone: the RV-40E speeds (tests/data/published_values.yaml), DOF counts,
slips, and derived operating cases."""
from __future__ import annotations

from pathlib import Path

import pytest

import powergraph as pg
from powergraph.kinematics import backdriven, degrees_of_freedom, solve_speeds
from powergraph.model import loads_model

MODELS = Path(__file__).resolve().parents[2] / "models"


def test_rv40e_speeds_are_reference_b() -> None:
    kin = solve_speeds(pg.load_model(MODELS / "rv40e_wang2021.yaml"))
    assert kin.speed("2") == pytest.approx(-50.6290, abs=5e-5) == kin.speed("3")
    assert kin.speed("4") == pytest.approx(1.29818, abs=5e-6)
    assert kin.speed("6") == kin.speed("7") == kin.speed("4")
    assert kin.speed("0") == 0.0 == kin.speed("5")
    assert kin.ratio == pytest.approx(1 + 36 * 40 / 12, rel=1e-12)   # i = 1 + z2 z5 / z1


@pytest.mark.parametrize("name,dof", [("rv40e_wang2021.yaml", 1), ("bevel_differential.yaml", 2),
                                      ("wolfrom_3k.yaml", 1), ("ravigneaux_second.yaml", 1)])
def test_degrees_of_freedom(name: str, dof: int) -> None:
    assert degrees_of_freedom(pg.load_model(MODELS / name)) == dof


def test_slip_on_a_fixed_axis_pair() -> None:
    """Pair 20/40 on the frame, input held: the row (w_1 - 0) - i (w_2 - 0) = s with
    i = -z_2/z_1 = -2 and w_1 = 0 gives w_2 = s/2."""
    model = loads_model("""
name: pair
components: {0: {role: frame}, 1: {teeth: 20}, 2: {teeth: 40}}
links: [{type: mesh, between: [1, 2]}]
ports: [{component: 1, role: input}, {component: 2, role: output}]
""")
    kin = solve_speeds(model, speeds={"1": 0.0}, slips={0: 1.0})
    assert kin.speed("2") == pytest.approx(0.5, rel=1e-15)


def test_backdriven_swaps_ports_and_keeps_the_motion() -> None:
    model = pg.load_model(MODELS / "rv40e_wang2021.yaml")
    back = backdriven(model)
    assert [(p.component, p.role) for p in back.ports] == [("1", "output"), ("6", "input")]
    assert back.inputs[0].power == model.inputs[0].power
    assert solve_speeds(back).speed("1") == pytest.approx(solve_speeds(model).speed("1"),
                                                          rel=1e-12)


def test_the_structure_cached_per_model_does_not_leak_into_a_changed_copy() -> None:
    """The rank and matchings are kept on the model; a copy with another tooth number
    (dataclasses.replace) starts without them and gets its own ratio, 1 + z2 z5 / z1."""
    import dataclasses
    from types import MappingProxyType

    model = pg.load_model(MODELS / "rv40e_wang2021.yaml")
    assert solve_speeds(model).ratio == pytest.approx(1 + 36 * 40 / 12, rel=1e-12)
    assert "kinematics.structure" in model.derived
    components = dict(model.components)
    components["2"] = dataclasses.replace(components["2"], teeth=30)
    copy = dataclasses.replace(model, components=MappingProxyType(components))
    assert copy.derived == {}
    assert solve_speeds(copy).ratio == pytest.approx(1 + 30 * 40 / 12, rel=1e-12)
    assert solve_speeds(model).ratio == pytest.approx(1 + 36 * 40 / 12, rel=1e-12)
    assert copy != model and dataclasses.replace(model) == model
