"""The step of a powergraph FMU (powergraph.exchange.fmu_runtime), without pythonfmu:
at new inputs the outputs are the single solve's, and power in = out + loss."""
from __future__ import annotations

from pathlib import Path

import pytest

import powergraph as pg
from powergraph.exchange.fmu_runtime import TrainStepper
from powergraph.testing import assert_conservation

MODEL = Path(__file__).resolve().parents[2] / "models" / "planetary_2kh_two_stages.yaml"


def test_a_step_is_the_solve_at_the_inputs() -> None:
    stepper = TrainStepper(str(MODEL))
    assert stepper.inputs == ("s1.speed", "s1.power")
    stepper.values.update({"s1.speed": 200.0, "s1.power": 5000.0})
    stepper.step()
    model = pg.load_model(MODEL).with_port(0, speed=200.0, power=5000.0)
    result = pg.solve(model)
    assert_conservation(result)
    assert stepper.values["c2.speed_out"] == pytest.approx(200.0 / 20.0, rel=1e-12)
    assert stepper.values["c2.torque_out"] == pytest.approx(result.ports[1].torque, rel=1e-12)
    assert stepper.values["efficiency"] == pytest.approx(result.efficiency, rel=1e-12)
    power_in, power_out = stepper.values["s1.power_out"], -stepper.values["c2.power_out"]
    assert power_in == pytest.approx(power_out + stepper.values["total_loss"], rel=1e-12)
