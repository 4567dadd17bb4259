"""A solve's tables (powergraph.statics.tables): rows and DataFrames.

Expected values: the RV-40E's ratio 1 + z2 z5 / z1 = 121 (Willis), the input given in the
file (1500 rpm, 2.27 kW), the mesh loss law ``loss = (1 - eta) * virtual power``, and the
power balance (what the ports feed in is what the meshes lose).
"""
from __future__ import annotations

import sys
from pathlib import Path

import pytest

import powergraph as pg
from powergraph.errors import UsageError
from powergraph.statics.tables import records, to_dataframe
from powergraph.testing import assert_conservation

RV40E = Path(__file__).resolve().parents[2] / "models" / "rv40e_wang2021.yaml"


@pytest.fixture(scope="module")
def rv():
    result = pg.solve(pg.load_model(RV40E))
    assert_conservation(result)
    return result


def test_ports_carry_speeds_torques_and_powers(rv) -> None:
    inlet, outlet = records(rv, "ports")
    assert (inlet["role"], inlet["component"], inlet["name"]) == ("input", 1, "center gear")
    assert inlet["rpm"] == pytest.approx(1500.0) and inlet["power_w"] == pytest.approx(2270.0)
    assert outlet["rpm"] == pytest.approx(1500.0 / 121.0)
    assert inlet["power_w"] + outlet["power_w"] == pytest.approx(
        sum(m["loss_w"] for m in records(rv, "meshes")))


def test_meshes_follow_the_loss_law_and_name_their_gears(rv) -> None:
    rows = records(rv, "meshes")
    assert [(m["a_name"], m["b_name"]) for m in rows] == [
        ("center gear", "planet gear"), ("cycloid gear", "needle gear")]
    for m in rows:
        assert m["loss_w"] == pytest.approx((1 - m["efficiency"]) * m["virtual_power_w"])


def test_flows_into_loss_add_up_to_the_total_loss(rv) -> None:
    into_loss = sum(f["power_w"] for f in records(rv, "flows") if f["to"] == "loss")
    assert into_loss == pytest.approx(rv.total_loss)


@pytest.mark.slow  # imports pandas
def test_dataframes_are_indexed_by_id(rv) -> None:
    pytest.importorskip("pandas")
    speeds = to_dataframe(rv, "speeds")
    assert speeds.loc[1, "rpm"] == pytest.approx(1500.0)
    assert speeds.loc[6, "rpm"] == pytest.approx(1500.0 / 121.0)
    assert list(to_dataframe(rv, "meshes").index) == [0, 1]
    assert len(to_dataframe(rv, "flows")) == len(rv.flows())


def test_bad_table_and_missing_pandas_are_usage_errors(rv, monkeypatch) -> None:
    with pytest.raises(UsageError, match="meshes, ports, flows, speeds"):
        records(rv, "gears")
    monkeypatch.setitem(sys.modules, "pandas", None)
    with pytest.raises(UsageError, match="pip install pandas"):
        to_dataframe(rv, "ports")


def test_the_result_gives_its_tables_as_dataframes() -> None:
    pytest.importorskip("pandas")
    result = pg.solve(pg.load_model(RV40E))
    assert_conservation(result)
    ports = result.to_dataframe("ports")
    assert len(ports) == len(result.model.ports)
    # power into the train at the ports sums to the losses (power balance)
    power = next(c for c in ports.columns if c.startswith("power"))
    assert ports[power].sum() == pytest.approx(result.total_loss, rel=1e-9)
    assert len(result.to_dataframe("meshes")) == len(result.meshes)
