"""The Honda i-MMD-type hybrid (``models/honda_immd.yaml``), derived by hand mode by mode:
a multi-mode hybrid without a planetary set, whose engine drive engages a lock-up clutch,
whose series mode has 2 DOF, and whose EV mode leaves a frame-carried gear pair (engine
and generator) idle.

- engine gear 50 -> generator gear 20: the generator turns 2.5 times the engine, the
  other way; one mesh at eta_m = 0.985;
- engine drive: engine -> LC -> overdrive 40 -> countershaft 38, final pinion 22 ->
  wheels 70: i = (38/40)(70/22); two meshes;
- motor pinion 24 -> countershaft 60, then the final drive: i = (60/24)(70/22); two
  meshes; machines at eta = 0.92 (drawing P/eta motoring, returning P·eta generating).
"""
from __future__ import annotations

import math
from pathlib import Path

import pytest

from powergraph.analyses.gear_table import gear_table
from powergraph.statics.case import TrainCase
from powergraph.model import load_model
from powergraph.testing import assert_conservation

MODEL = Path(__file__).resolve().parents[2] / "models" / "honda_immd.yaml"
RPM = math.pi / 30
ETA_M, ETA = 0.985, 0.92
I_ENGINE = (38 / 40) * (70 / 22)
I_MOTOR = (60 / 24) * (70 / 22)
W_WHEELS = 800 * RPM


@pytest.fixture(scope="module")
def model():
    return load_model(MODEL)


def _point(model, mode):
    point = TrainCase.of(model, mode).point()
    assert_conservation(point.result)
    return point.result, {m.name: m for m in point.result.machines}


def test_engine_drive_is_two_meshes_and_an_idle_motor(model) -> None:
    result, mg = _point(model, "engine drive")
    assert result.kinematics.speed("E") == pytest.approx(I_ENGINE * W_WHEELS, rel=1e-12)
    assert result.ratio == pytest.approx(I_ENGINE, rel=1e-12)
    assert result.efficiency == pytest.approx(ETA_M ** 2, rel=1e-12)
    assert mg["motor"].state == "idle" and mg["motor"].power == pytest.approx(0, abs=1e-9)
    assert mg["motor"].speed == pytest.approx(I_MOTOR * W_WHEELS, rel=1e-12)
    assert mg["generator"].state == "inactive"
    assert result.kinematics.speed("G") == pytest.approx(-2.5 * I_ENGINE * W_WHEELS,
                                                         rel=1e-12)


def test_hybrid_drive_is_the_series_path(model) -> None:
    """The engine's 30 kW: eta_m·30 kW into the generator, ETA of that to the bus, ETA of
    that on the motor's shaft, eta_m² of that at the wheels."""
    result, mg = _point(model, "hybrid drive")
    assert result.kinematics.dof == 2
    assert mg["generator"].power == pytest.approx(-ETA_M * 30e3, rel=1e-12)
    assert mg["generator"].speed == pytest.approx(-2.5 * 2000 * RPM, rel=1e-12)
    assert mg["motor"].power == pytest.approx(ETA ** 2 * ETA_M * 30e3, rel=1e-12)
    assert result.efficiency == pytest.approx(ETA_M ** 3 * ETA ** 2, rel=1e-12)
    assert result.buses["dc"].battery_power == pytest.approx(0.0, abs=1e-6)


def test_ev_drive_leaves_the_engine_and_generator_idle(model) -> None:
    """The engine gear and the generator mesh with each other on fixed axes and with
    nothing else once LC is open: idle (no speed), not a missing DOF."""
    result, mg = _point(model, "EV drive")
    assert result.model.idle == {"E", "G"}
    assert mg["motor"].power == pytest.approx(20e3 / ETA_M ** 2, rel=1e-12)
    assert result.buses["dc"].battery_power == pytest.approx(20e3 / ETA_M ** 2 / ETA,
                                                             rel=1e-12)
    assert result.efficiency == pytest.approx(ETA_M ** 2 * ETA, rel=1e-12)
    assert mg["generator"].state == "inactive"


def test_the_gear_table_is_solve_mode_in_every_mode(model) -> None:
    table = gear_table(model)
    assert [r.mode for r in table.rows] == ["engine drive", "hybrid drive", "EV drive"]
    for row in table.rows:
        point = TrainCase.of(model, row.mode).point()
        assert row.efficiency == pytest.approx(point.result.efficiency, rel=1e-12)
        assert row.verdict == point.verdict == "ok"
        assert [m.to_dict() for m in row.machines] == \
            [m.to_dict() for m in point.result.machines]


def test_the_loaded_model_solves_in_its_first_mode_at_that_modes_point(model) -> None:
    """``powergraph.solve`` of the model as loaded: the default state is the first mode,
    engine drive, with its generator inactive (the mode's point), and says so."""
    import powergraph as pg

    result = pg.solve(model)
    assert_conservation(result)
    assert result.efficiency == pytest.approx(ETA_M ** 2, rel=1e-12)
    assert "default-state" in [w.code for w in result.warnings]
    assert {m.name: m.state for m in result.machines}["generator"] == "inactive"
