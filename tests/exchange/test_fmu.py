"""An FMU built by ``powergraph export --to fmu`` (powergraph.exchange.fmu), simulated
with fmpy: its outputs equal the single solve at the same inputs to 1e-9. pythonfmu and
fmpy are test dependencies (and the ``fmu`` extra); a bare install skips this test."""
from __future__ import annotations

from pathlib import Path

import pytest

import powergraph as pg
from powergraph.testing import assert_conservation

pytest.importorskip("pythonfmu")
fmpy = pytest.importorskip("fmpy")

MODEL = Path(__file__).resolve().parents[2] / "models" / "planetary_2kh_two_stages.yaml"


def test_fmu_outputs_equal_the_solve(tmp_path: Path) -> None:
    from powergraph.exchange.fmu import build_fmu

    fmu = build_fmu(MODEL, tmp_path / "train.fmu")
    names = ["c2.speed_out", "c2.torque_out", "s1.power_out", "efficiency", "total_loss"]
    rows = fmpy.simulate_fmu(str(fmu), stop_time=1.0, output_interval=0.5,
                             start_values={"s1.speed": 250.0, "s1.power": 3000.0},
                             output=names)
    result = pg.solve(pg.load_model(MODEL).with_port(0, speed=250.0, power=3000.0))
    assert_conservation(result)
    expected = [result.ports[1].speed, result.ports[1].torque, result.ports[0].power,
                result.efficiency, result.total_loss]
    for name, value in zip(names, expected):
        assert rows[name][-1] == pytest.approx(value, rel=1e-9)
