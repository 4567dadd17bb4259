"""Loss sources (powergraph.statics.loss_sources): one list per model that every evaluator
takes, and the worked example of docs/developer_api.md — a new loss type registered from
outside the package (here, in this test only) reaches the solve, the report's loss
breakdown, the efficiency map, a duty cycle's energy per element and the refusals of the
methods that read plain efficiencies, with no other change.

The train: a pair z 20/40 (ideal mesh), input 1 at 100 rad/s feeding 1 kW; the toy loss, a
seal of constant torque 0.5 N·m between gear 2 and the housing. Hand derivation: gear 2
turns at -100·20/40 = -50 rad/s, the seal loses 0.5·50 = 25 W, so 975 W leave at the
output and the efficiency is 0.975.
"""
from __future__ import annotations

import io
from pathlib import Path

import numpy as np
import pytest

import powergraph as pg
from powergraph.errors import MethodNotApplicableError
from powergraph.model import load_model, model_from_dict
from powergraph.statics.loss_sources import (BUILDERS, LossSource, loss_sources, losses,
                                             registered, torque_sources)
from powergraph.testing import assert_conservation


class ConstantTorque:
    """A toy law: the same torque at any relative speed (N·m per instance)."""

    def __init__(self, torque: float) -> None:
        self.value = torque

    def torque(self, relative):
        return self.value + 0.0 * np.abs(relative)


def seals(model):
    """The toy builder: a 0.5 N·m seal on every component named 'sealed shaft'."""
    for c in model.components.values():
        if c.name == "sealed shaft":
            yield LossSource("seal", f"components.{c.raw_id}.name", f"seal {c.raw_id}", None,
                             (c.id, model.frame), 1, drag=ConstantTorque(0.5))


def pair():
    return model_from_dict({
        "name": "sealed pair",
        "components": {0: {"role": "frame"}, 1: {"teeth": 20},
                       2: {"teeth": 40, "name": "sealed shaft"}},
        "links": [{"type": "mesh", "between": [1, 2]}],
        "ports": [{"component": 1, "role": "input", "speed": 100, "power": 1000},
                  {"component": 2, "role": "output"}]})


def test_builtin_sources_are_meshes_then_bearings_and_drags_in_file_order() -> None:
    model = load_model("models/rv40e.yaml")
    sources = loss_sources(model)
    meshes = [f"links[{link.index}]" for link in model.links if link.type == "mesh"]
    assert [(s.kind, s.path) for s in sources] == [("mesh", path) for path in meshes] + [
        ("bearing", "links[6]"), ("bearing", "links[7]"), ("bearing", "links[8]")]
    assert [s.path for s in torque_sources(model)] == ["links[6]", "links[7]", "links[8]"]
    bearing = torque_sources(model)[0]
    assert bearing.loaded_by and not torque_sources(model)[1].loaded_by  # friction vs drag
    assert [(s.kind, s.applied) for s in loss_sources(pair())] == [("mesh", "element")]
    assert torque_sources(pair()) == ()


def test_every_source_has_its_loss_and_they_make_the_total() -> None:
    """In every bundled model the losses of its sources add up to the result's total loss
    (a loss the sources do not name would break the sum), and a machine's source reads
    the machine's own loss."""
    for path in sorted(Path("models").glob("*.yaml")):
        model = load_model(path)
        if model.modes:
            continue
        result = pg.solve(model)
        found = losses(result)
        assert sum(w for _, w in found) == pytest.approx(result.total_loss, rel=1e-9, abs=1e-9)
        by_name = {s.node: w for s, w in found if s.applied == "machine"}
        assert by_name == {m.name: m.loss for m in result.machines}


def test_a_registered_loss_type_reaches_every_evaluator() -> None:
    from powergraph.analyses.cycle import cycle
    from powergraph.analyses.efficiency_map import efficiency_map
    from powergraph.analyses.formula import derive_formulas
    from powergraph.statics.friction import loss_block_places

    with registered(seals):
        model = pair()
        result = pg.solve(model)
        assert_conservation(result)
        seal, = result.bearings
        assert (seal.kind, seal.node, seal.relative_speed) == ("seal", "seal 2", -50.0)
        assert seal.loss == pytest.approx(25.0, rel=1e-12)
        assert result.total_loss == pytest.approx(25.0, rel=1e-12)
        assert result.efficiency == pytest.approx(0.975, rel=1e-12)
        breakdown = {d["source"]: d["power"] for d in result.to_dict()["loss_breakdown"]}
        assert breakdown == {"links[0] mesh 1-2 (1 / sealed shaft)": 0.0,
                             "seal 2 (sealed shaft / 0)": pytest.approx(25.0, rel=1e-12)}
        assert "seal 2  2-0" in result.text_report()
        grid = efficiency_map(model, [975 / 50, 2 * 975 / 50], [100 * 30 / np.pi])
        # at 975/50 N·m on the output the point is the solve's own; at twice the torque the
        # seal's 25 W is half as large a share: (1950 / (1950 + 25))
        assert grid.efficiency[0, 0] == pytest.approx(0.975, rel=1e-12)
        assert grid.efficiency[0, 1] == pytest.approx(1950 / 1975, rel=1e-12)
        points = io.StringIO("1.speed [rad/s],1.power [W],duration [s]\n100,1000,2\n")
        energy = cycle(model, points).energy_lost
        assert energy["seal 2"] == pytest.approx(50.0, rel=1e-12)      # 25 W for 2 s
        assert loss_block_places(model) == ["components.2.name"]
        with pytest.raises(MethodNotApplicableError):
            derive_formulas(model)
    assert seals not in BUILDERS
    assert pg.solve(pair()).total_loss == 0.0      # a new model without the builder
