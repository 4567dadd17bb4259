"""A REXS file read as a model (powergraph.model.rexs_reader) and solved.

The two files in tests/exchange/data were written by hand from the format's public
description (their header comments say how). Expected values are derived here:

- two-stage helical unit, pinion 17 → wheel 58, pinion 19 → wheel 67: the output turns
  (17/58)(19/67) times the input, so i = (58/17)(67/19); with every mesh at η the
  efficiency of two meshes in series is η²;
- 2K-H stage, sun 24 in, ring 72 held, carrier out: Willis with the carrier as the arm,
  (ω_s − ω_c)/(ω_r − ω_c) = −72/24 and ω_r = 0 give i = 1 + 72/24 = 4; power through the
  carrier frame's meshes (sun → planet → ring, η0 = 0.985 · 0.99) gives
  η = (1 + η0 k)/(1 + k), k = 3.
"""
from __future__ import annotations

import math
from pathlib import Path

import pytest

import powergraph as pg
from powergraph.errors import ModelError
from powergraph.model.rexs_reader import SPECTRUM_SECONDS, read_rexs
from powergraph.testing import assert_conservation

DATA = Path(__file__).resolve().parents[1] / "exchange" / "data"
HELICAL = DATA / "two_stage_helical.rexs"
PLANETARY = DATA / "planetary_2kh.rexsj"


def test_two_stage_helical_ratio_and_efficiency() -> None:
    model = pg.model_from_dict(read_rexs(HELICAL, mesh_efficiency=0.98).data)
    result = pg.solve(model)
    assert_conservation(result)
    assert result.ratio == pytest.approx((58 / 17) * (67 / 19), rel=1e-12)
    assert result.efficiency == pytest.approx(0.98 ** 2, rel=1e-12)
    # the first load case: 1480 rpm and 200 N·m on the input shaft
    assert result.input_power == pytest.approx(200.0 * 1480 * math.pi / 30, rel=1e-12)


def test_two_stage_helical_geometry_and_parts() -> None:
    data = read_rexs(HELICAL).data
    meshes = [link for link in data["links"] if link["type"] == "mesh"]
    # stage 1: the shifts from the flanks (pinion 0.3) and the wheel (-0.1) beat the
    # centre distance; stage 2 has no shifts, so its centre distance stands for them
    assert meshes[0]["geometry"] == {"module": 3.0, "face_width": 38.0, "helix_angle": 15.0,
                                     "pressure_angle": 20.0, "shifts": [0.3, -0.1]}
    assert meshes[1]["geometry"]["centre_distance"] == 176.0
    assert data["components"][2]["role"] == "frame"
    assert sum(link["type"] == "bearing" for link in data["links"]) == 3
    assert data["lubricant"] == {"viscosity_40": "220.0 cSt", "viscosity_100": "19.0 cSt",
                                 "density": "890.0 kg/m^3", "temperature": "70.0 degC"}
    assert [p["role"] for p in data["ports"]] == ["input", "output"]


def test_load_spectrum_as_points() -> None:
    points = read_rexs(HELICAL).points
    assert [p["duration [s]"] for p in points] == [0.75 * SPECTRUM_SECONDS,
                                                   0.25 * SPECTRUM_SECONDS]
    assert [p["10.speed [rpm]"] for p in points] == [1480.0, 980.0]
    assert [p["10.torque [N*m]"] for p in points] == [200.0, 120.0]


def test_unmapped_attributes_are_listed() -> None:
    unmapped = read_rexs(HELICAL).unmapped
    assert "cylindrical_gear: tip_diameter" in unmapped
    assert "concept_bearing: axial_force_absorption" in unmapped
    assert "load cases, external_load: force_v_direction" in unmapped
    # what is mapped is not listed
    assert not any("number_of_teeth" in line or "rotational_speed" in line for line in unmapped)


def test_planetary_stage_from_json() -> None:
    model = pg.load_model(PLANETARY)
    result = pg.solve(model)
    assert_conservation(result)
    assert result.ratio == pytest.approx(4.0, rel=1e-12)
    eta0 = 0.985 * 0.99
    assert result.efficiency == pytest.approx((1 + eta0 * 3) / 4, rel=1e-12)
    assert all(link.carrier == "3" for link in model.meshes)       # the carrier shaft
    assert model.components["12"].count == 3                       # number_of_planets
    assert model.components["13"].internal


def test_a_shaft_turned_the_other_way_gives_its_speed_and_torque_negated(tmp_path) -> None:
    # REXS gives speeds and torques about each shaft's own u axis; the input shaft's axis
    # reversed against the gear unit's means -1480 rpm and -200 N·m about the common one:
    # the same power and the same ratio
    text = HELICAL.read_text(encoding="utf-8").replace(
        '<attribute id="u_axis_vector" unit="mm"><array><c>1</c>',
        '<attribute id="u_axis_vector" unit="mm"><array><c>-1</c>').replace(
        '<attribute id="reference_temperature" unit="C">20</attribute>',
        '<attribute id="u_axis_vector" unit="mm"><array><c>2</c><c>0</c><c>0</c></array>'
        '</attribute>')
    path = tmp_path / "reversed.rexs"
    path.write_text(text, encoding="utf-8")
    ports = read_rexs(path).data["ports"]
    assert ports[0]["speed"] == "-1480.0 rpm" and ports[0]["torque"] == "-200.0 N*m"
    result = pg.solve(pg.load_model(path))
    assert_conservation(result)
    assert result.ratio == pytest.approx((58 / 17) * (67 / 19), rel=1e-12)
    assert result.input_power == pytest.approx(200.0 * 1480 * math.pi / 30, rel=1e-12)


def test_an_axis_at_an_angle_is_an_error(tmp_path: Path) -> None:
    text = HELICAL.read_text(encoding="utf-8").replace(
        '<attribute id="reference_temperature" unit="C">20</attribute>',
        '<attribute id="u_axis_vector" unit="mm"><array><c>0</c><c>1</c><c>0</c></array>'
        '</attribute>')
    path = tmp_path / "bevel.rexs"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(ModelError, match="shaft 10: its u_axis_vector is not parallel"):
        read_rexs(path)


def test_load_model_reads_rexs_by_suffix(tmp_path: Path) -> None:
    copy = tmp_path / "unit.REXS"
    copy.write_bytes(HELICAL.read_bytes())
    assert pg.load_model(copy).name == "Two-stage helical unit"


@pytest.mark.parametrize("text, message", [
    ("<model version='1.4'><relations><relation id='1' type='glue'/></relations>"
     "<components/></model>", "relation 1: unknown relation type 'glue'"),
    ("<model version='1.4'><relations><relation id='1' type='stage'>"
     "<ref hint='cylindrical_stage' id='9' role='stage'/></relation></relations>"
     "<components/></model>", "component 9, which is not in the file"),
    ("<gearbox/>", "not a REXS file"),
    ("<model version='1.4'><components>", "not well-formed XML"),
    ('{"model": {"version": "1.4", "components": [', "not valid JSON"),
    ('{"gearbox": {}}', "not a REXS file"),
    ("<!DOCTYPE m [<!ENTITY a 'aaaa'>]><model version='1.4'/>", "entity declarations"),
    ('{"model": {"version": "1.4", "version": "1.5"}}', "JSON key 'version' given twice"),
    ('{"model": {"version": ' + "9" * 5000 + "}}", "a number of thousands of digits"),
])
def test_bad_files_are_one_model_error(tmp_path: Path, text: str, message: str) -> None:
    path = tmp_path / "bad.rexs"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(ModelError, match=message) as info:
        read_rexs(path)
    assert str(path) in str(info.value) and "\n" not in str(info.value)


def test_a_gear_on_no_shaft_is_an_error(tmp_path: Path) -> None:
    path = tmp_path / "loose.rexs"
    path.write_text("<model version='1.4'><relations/><components>"
                    "<component id='1' type='cylindrical_gear' name='g'>"
                    "<attribute id='number_of_teeth' unit='none'>20</attribute></component>"
                    "</components></model>", encoding="utf-8")
    with pytest.raises(ModelError, match="cylindrical gear 1: no assembly relation"):
        read_rexs(path)


def test_a_model_read_straight_from_rexs_warns_that_its_meshes_are_ideal(tmp_path) -> None:
    """REXS carries no mesh efficiency: solved straight from the file, the unit has no
    mesh loss (efficiency 1 exactly, as ideal meshes give), and says so; what was not
    read is a warning too. A file whose stages carry powergraph's own efficiency (an
    export) has no such warning."""
    from powergraph.exchange.rexs_text import to_xml
    from powergraph.exchange.rexs_writer import rexs_export

    model = pg.load_model(HELICAL)
    codes = [w.code for w in model.warnings]
    assert "rexs-ideal-meshes" in codes and "rexs-not-mapped" in codes
    result = pg.solve(model)
    assert_conservation(result)
    assert result.efficiency == 1.0
    assert "rexs-ideal-meshes" in [w.code for w in result.warnings]
    exported = tmp_path / "unit.rexs"
    lossy = pg.load_model(HELICAL).with_mesh_efficiency(0.98)
    exported.write_text(to_xml(rexs_export(lossy, None, str(exported)).document))
    again = pg.load_model(exported)
    assert "rexs-ideal-meshes" not in [w.code for w in again.warnings]
    assert pg.solve(again).efficiency == pytest.approx(0.98 ** 2, rel=1e-12)


def test_a_huge_value_is_named_briefly(tmp_path: Path) -> None:
    """A tooth number of 5,000 digits: refused in one short line, not echoed whole."""
    text = HELICAL.read_text(encoding="utf-8")
    start = text.index('<attribute id="number_of_teeth"')
    start = text.index(">", start) + 1
    end = text.index("<", start)
    path = tmp_path / "huge.rexs"
    path.write_text(text[:start] + "9" * 5000 + text[end:], encoding="utf-8")
    with pytest.raises(ModelError, match="is not a finite number") as info:
        read_rexs(path)
    assert len(str(info.value)) < 300
