"""Spin losses (issue 36): the oil's viscosity (Walther, ASTM D341), lip seals (ISO/TR
14179-2), the laminar drag of open wet clutches and the heat balance that sets the oil
temperature. Every expected value is a hand computation written here, or the issue's
published example (32/5.4 cSt gives 8.53 cSt at 80 °C).

The train of most tests: a pair z 20/40 (η 0.98 or ideal), the input 1 at 1000 rpm feeding
1 kW, the output 2 at −500 rpm; a seal of 30 mm on the input shaft against the housing, and
a drum 3 turning with the output, dragged by a wet brake (6 faces, r 60…80 mm, gap 0.2 mm)
against the housing.
"""
from __future__ import annotations

import json
import math

import pytest

import powergraph as pg
from powergraph.cli.main import main
from powergraph.errors import ModelError
from powergraph.model import model_from_dict
from powergraph.model.lubricant import GRADES, at_temperature
from powergraph.model.yaml_loader import load_yaml_file
from powergraph.statics.case import TrainCase
from powergraph.statics.loss_sources import losses
from powergraph.testing import assert_conservation

OIL = {"viscosity_40": "32 cSt", "viscosity_100": "5.4 cSt", "density": "870 kg/m^3",
       "temperature": "80 degC"}
WET = {"faces": 6, "inner_radius": "60 mm", "outer_radius": "80 mm", "clearance": "0.2 mm"}
W_IN = 1000 * math.pi / 30            # rad/s


def walther_cst(nu40: float, nu100: float, celsius: float) -> float:
    """ASTM D341 by hand: log log (ν + 0.7) is linear in log T (K)."""
    def w(nu):
        return math.log10(math.log10(nu + 0.7))
    b = (w(nu40) - w(nu100)) / (math.log10(373.15) - math.log10(313.15))
    walther = w(nu40) - b * (math.log10(celsius + 273.15) - math.log10(313.15))
    return 10 ** 10 ** walther - 0.7


def train(oil=OIL, efficiency=0.98, seal=True, wet=True, thermal=None, output_power=None):
    links = [{"type": "mesh", "between": [1, 2], "efficiency": efficiency},
             {"type": "coupling", "between": [2, 3]}]
    if seal:
        links.append({"type": "seal", "between": [1, 0], "diameter": "30 mm"})
    if wet:
        links.append({"type": "bearing", "between": [3, 0], "drag": {"wet": WET}})
    output = {"component": 2, "role": "output"}
    if output_power is not None:
        output["power"] = output_power
    data = {"name": "oiled pair", "components": {0: {"role": "frame"}, 1: {"teeth": 20},
                                                  2: {"teeth": 40}, 3: {"name": "drum"}},
            "links": links,
            "ports": [{"component": 1, "role": "input", "speed": "1000 rpm",
                       **({} if output_power is not None else {"power": "1 kW"})}, output]}
    if oil is not None:
        data["lubricant"] = oil
    if thermal is not None:
        data["thermal"] = thermal
    return model_from_dict(data)


def test_viscosity_at_80_degc_is_the_issues_8_53_cst() -> None:
    oil = train().lubricant
    assert oil.viscosity() * 1e6 == pytest.approx(8.53, abs=0.005)
    assert oil.viscosity() * 1e6 == pytest.approx(walther_cst(32, 5.4, 80), rel=1e-12)
    assert oil.viscosity(313.15) == pytest.approx(32e-6, rel=1e-12)
    assert oil.viscosity(373.15) == pytest.approx(5.4e-6, rel=1e-12)
    assert oil.dynamic_viscosity() == pytest.approx(oil.viscosity() * 870.0, rel=1e-15)


@pytest.mark.parametrize("grade", sorted(GRADES))
def test_a_grade_is_its_iso_3448_midpoint_at_40_degc(grade: int) -> None:
    oil = train(oil={"grade": f"ISO VG {grade}", "temperature": "60 degC"}).lubricant
    nu40, nu100, density = GRADES[grade]
    assert oil.viscosity(313.15) * 1e6 == pytest.approx(grade, rel=1e-12)
    assert oil.viscosity() * 1e6 == pytest.approx(walther_cst(nu40, nu100, 60), rel=1e-12)
    assert oil.density == density


def test_seal_loses_7_69e_6_d2_n() -> None:
    """ISO/TR 14179-2: P = 7.69e-6 · 30² · 1000 = 6.921 W on the input shaft."""
    result = pg.solve(train(efficiency=1.0, wet=False))
    assert_conservation(result)
    seal = dict((s.path, w) for s, w in losses(result))["links[2]"]
    assert seal == pytest.approx(7.69e-6 * 30 ** 2 * 1000, rel=1e-12)
    assert result.efficiency == pytest.approx(1 - 6.921 / 1000, rel=1e-12)


def test_wet_drag_is_laminar_shear_at_the_oils_viscosity() -> None:
    """T = faces π μ |Δω| (r_o⁴ − r_i⁴) / (2h), μ = ν(80 °C) ρ, Δω = 500 rpm."""
    result = pg.solve(train(seal=False))
    assert_conservation(result)
    mu = walther_cst(32, 5.4, 80) * 1e-6 * 870
    slip = W_IN / 2
    torque = 6 * math.pi * mu * slip * (0.08 ** 4 - 0.06 ** 4) / (2 * 0.2e-3)
    brake, = result.bearings
    assert brake.torque == pytest.approx(torque, rel=1e-12)
    assert brake.loss == pytest.approx(torque * slip, rel=1e-12)
    # colder oil, thicker: the drag scales with the viscosity
    cold = pg.solve(at_temperature(train(seal=False), 313.15)).bearings[0]
    assert cold.torque / brake.torque == pytest.approx(32 / walther_cst(32, 5.4, 80),
                                                       rel=1e-12)


def test_an_open_wet_brake_of_a_transmission_drags_in_its_slip() -> None:
    """Simpson 3-speed: each brake or clutch open in a mode gets a wet drag; its loss is
    its laminar torque times its own slip speed, and the balance holds."""
    raw = load_yaml_file("models/simpson_3speed.yaml")
    raw["lubricant"] = OIL
    for link in raw["links"]:
        if link["type"] in ("clutch", "brake"):
            link["drag"] = {"wet": WET}
    model = model_from_dict(raw)
    mu = walther_cst(32, 5.4, 80) * 1e-6 * 870
    per_rad_s = 6 * math.pi * mu * (0.08 ** 4 - 0.06 ** 4) / (2 * 0.2e-3)
    checked = 0
    for mode in model.modes:
        result = TrainCase.of(model, mode).point().required().result
        assert_conservation(result)
        for state in result.bearings:
            slip = abs(state.relative_speed)
            assert state.torque == pytest.approx(per_rad_s * slip if slip else 0.0, rel=1e-12)
            assert state.loss == pytest.approx(per_rad_s * slip ** 2, rel=1e-12)
            checked += slip > 0
    assert checked >= 3


def test_heat_balance_closes_and_the_laws_run_at_its_temperature() -> None:
    balance = {"ambient": "20 degC", "heat_transfer": "18 W/(m^2*K)", "area": "0.3 m^2"}
    result = pg.solve(train(thermal=balance))
    assert_conservation(result)
    state = result.thermal
    assert state.verdict == "ok"
    heat = 18 * 0.3 * (state.temperature - 293.15)
    assert result.total_loss == pytest.approx(heat, rel=1e-6)
    assert state.heat_dissipated == pytest.approx(heat, rel=1e-6)
    # the answer is the plain solve at that temperature
    fixed = pg.solve(at_temperature(train(), state.temperature))
    assert result.total_loss == pytest.approx(fixed.total_loss, rel=1e-12)
    assert result.model.lubricant.temperature == state.temperature
    # the oil warms above ambient and below 80 °C's drag-free limit; hotter oil drags less
    assert 293.15 < state.temperature < 373.15


def test_a_cooler_and_the_oils_limit_are_verdicts() -> None:
    cooled = pg.solve(train(thermal={"ambient": "20 degC", "heat_transfer": 18,
                                     "area": 0.3, "cooler": "1 kW"}))
    assert cooled.thermal.verdict == "at ambient"
    assert cooled.thermal.temperature == pytest.approx(293.15)
    assert any(c.code == "cooler-exceeds-losses" for c in cooled.warnings)
    hot = pg.solve(train(thermal={"ambient": "20 degC", "heat_transfer": 18,
                                  "area": "1 cm^2"}))
    assert hot.thermal.verdict == "over the oil's limit"
    assert hot.thermal.temperature == pytest.approx(273.15 + 150)
    assert any(c.code == "overheats" for c in hot.warnings)


def test_no_load_running_torque_is_the_seal_and_drag_at_the_input() -> None:
    """Nothing taken at the output: the input torque is the seal's 7.69e-6·30²·30/π N·m
    plus the drum's wet drag reflected through the ideal 2:1 pair (÷ 2)."""
    result = pg.solve(train(efficiency=1.0, output_power=0.0))
    assert_conservation(result)
    mu = walther_cst(32, 5.4, 80) * 1e-6 * 870
    drum = 6 * math.pi * mu * (W_IN / 2) * (0.08 ** 4 - 0.06 ** 4) / (2 * 0.2e-3)
    expected = 7.69e-6 * 900 * 30 / math.pi + drum / 2
    assert result.to_dict()["no_load_torque"] == pytest.approx(expected, rel=1e-9)
    assert "no-load running torque" in result.text_report()


def test_json_reports_the_oil_and_the_heat_balance_in_si(tmp_path, capsys) -> None:
    path = tmp_path / "oiled.yaml"
    path.write_text(
        "name: oiled\n"
        "lubricant: {viscosity_40: 32 cSt, viscosity_100: 5.4 cSt, density: 870 kg/m^3, "
        "temperature: 80 degC}\n"
        "thermal: {ambient: 20 degC, heat_transfer: 18 W/(m^2*K), area: 0.3 m^2}\n"
        "components: {0: {role: frame}, 1: {teeth: 20}, 2: {teeth: 40}}\n"
        "links:\n  - {type: mesh, between: [1, 2], efficiency: 0.98}\n"
        "  - {type: seal, between: [1, 0], diameter: 30 mm}\n"
        "ports:\n  - {component: 1, role: input, speed: 1000 rpm, power: 1 kW}\n"
        "  - {component: 2, role: output}\n")
    assert main(["solve", str(path), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    temperature = out["thermal"]["temperature"]
    assert out["lubricant"]["temperature"] == temperature
    assert out["lubricant"]["viscosity"] == pytest.approx(
        walther_cst(32, 5.4, temperature - 273.15) * 1e-6, rel=1e-12)
    assert out["lubricant"]["density"] == 870.0
    # constant-efficiency mesh and a seal: the loss does not depend on the temperature
    loss = 20.0 * (1000 - 6.921) / 1000 + 6.921
    assert out["total_loss"] == pytest.approx(loss, rel=1e-9)
    assert temperature == pytest.approx(293.15 + loss / (18 * 0.3), rel=1e-9)
    assert out["thermal"]["heat_dissipated"] == pytest.approx(loss, rel=1e-6)


@pytest.mark.parametrize("change,place", [
    ({"lubricant": {**OIL, "temperature": 80}}, "lubricant.temperature"),
    ({"lubricant": {**OIL, "temperature": "80 C"}}, "lubricant.temperature"),
    ({"lubricant": {**OIL, "viscosity_100": "40 cSt"}}, "lubricant.viscosity_100"),
    ({"lubricant": {**OIL, "density": "8.7 kg/m^3"}}, "lubricant.density"),
    ({"lubricant": {"grade": "ISO VG 33"}}, "lubricant.grade"),
    ({"lubricant": None}, "links[3].drag"),
    ({"thermal": {"ambient": "20 degC", "heat_transfer": 18, "area": 0.3},
      "lubricant": None}, "thermal"),
    ({"lubricant": {**OIL, "colour": "amber"}}, "lubricant"),
])
def test_bad_oil_blocks_name_their_place(change, place) -> None:
    oil = change.get("lubricant", OIL)
    with pytest.raises(ModelError) as error:
        train(oil=oil, thermal=change.get("thermal"))
    assert str(error.value).startswith(place)


def test_every_evaluator_has_the_spin_losses() -> None:
    """A duty cycle's energy per source and the map's points are the single solve's: the
    seal's 6.921 W for 2 s is 13.842 J; the map at the solve's own output torque is the
    solve's efficiency; the formulas and the compiled sweep refuse (they read plain
    efficiencies)."""
    import io

    from powergraph.analyses.cycle import cycle
    from powergraph.analyses.efficiency_map import efficiency_map
    from powergraph.analyses.formula import derive_formulas
    from powergraph.analyses.sweep import compile_sweep
    from powergraph.errors import MethodNotApplicableError

    model = train(efficiency=1.0, wet=False)
    result = pg.solve(model)
    points = io.StringIO("1.speed [rpm],1.power [W],duration [s]\n1000,1000,2\n")
    energy = cycle(model, points).energy_lost
    assert energy["seal 1-0"] == pytest.approx(2 * 7.69e-6 * 900 * 1000, rel=1e-12)
    torque = abs(result.ports[1].torque)            # the load the output drives
    grid = efficiency_map(model, [torque], [1000.0])
    assert grid.efficiency[0, 0] == pytest.approx(result.efficiency, rel=1e-12)
    with pytest.raises(MethodNotApplicableError):
        derive_formulas(model)
    with pytest.raises(ModelError, match="constant efficiencies"):
        compile_sweep(model, {"links[0].efficiency": [0.9]})
    balanced = train(thermal={"ambient": "20 degC", "heat_transfer": 18, "area": 0.3})
    solved = pg.solve(balanced)
    mapped = efficiency_map(balanced, [abs(solved.ports[1].torque)], [1000.0])
    assert mapped.efficiency[0, 0] == pytest.approx(solved.efficiency, rel=1e-9)


def _wet_simpson():
    raw = load_yaml_file("models/simpson_3speed.yaml")
    raw["lubricant"] = OIL
    for link in raw["links"]:
        if link["type"] in ("clutch", "brake"):
            link["drag"] = {"wet": WET}
    return model_from_dict(raw)


@pytest.mark.parametrize("backdrive", [False, True], ids=["fwd", "coast"])
def test_wet_clutches_in_every_mode_agree_across_evaluators(backdrive: bool) -> None:
    """The Simpson 3-speed with wet drag on every clutch and brake: in every mode, forward
    and coasting, the case's solve, the gear table and a duty-cycle row give the same
    efficiency and verdict; the open elements' drag is in each."""
    import io

    from powergraph.analyses.cycle import cycle
    from powergraph.analyses.gear_table import gear_table

    model = _wet_simpson()
    rows = {r.mode: r for r in gear_table(model).rows}
    for mode in model.modes:
        point = TrainCase.of(model, mode, backdrive).point()
        row = rows[mode]
        verdict = row.coast_verdict if backdrive else row.verdict
        assert verdict == point.verdict, mode
        if point.result is None:
            continue
        assert_conservation(point.result)
        assert any(s.kind == "bearing" and s.loss > 0 for s in point.result.bearings), mode
        efficiency = row.coast_efficiency if backdrive else row.efficiency
        assert efficiency == pytest.approx(point.result.efficiency, rel=1e-9), mode
        if backdrive:
            continue
        port = model.inputs[0]
        text = (f"mode,{port.component}.speed [rad/s],{port.component}.power [W],"
                f"duration [s]\n{mode},{port.speed!r},{port.power!r},1\n")
        row = cycle(model, io.StringIO(text)).rows[0]
        assert row.efficiency == pytest.approx(point.result.efficiency, rel=1e-9), mode


def _write(tmp_path, model_text: str):
    path = tmp_path / "wet.yaml"
    path.write_text(model_text)
    return str(path)


WET_PAIR = (
    "name: wet pair\n"
    "lubricant: {viscosity_40: 32 cSt, viscosity_100: 5.4 cSt, density: 870 kg/m^3, "
    "temperature: 80 degC}\n"
    "thermal: {ambient: 20 degC, heat_transfer: 18 W/(m^2*K), area: 0.3 m^2}\n"
    "components: {0: {role: frame}, 1: {teeth: 20}, 2: {teeth: 40}, 3: {name: drum}}\n"
    "links:\n  - {type: mesh, between: [1, 2]}\n  - {type: coupling, between: [2, 3]}\n"
    "  - {type: bearing, between: [3, 0], drag: {wet: {faces: 6, inner_radius: 60 mm, "
    "outer_radius: 80 mm, clearance: 0.2 mm}}}\n"
    "ports:\n  - {component: 1, role: input, speed: 1000 rpm, power: 1 kW}\n"
    "  - {component: 2, role: output}\n")


def test_cli_oil_temperature_sets_the_oil_and_drops_the_heat_balance(tmp_path, capsys) -> None:
    """solve --oil-temperature 40: ν = 32 cSt exactly, the drag 6π μ Δω (r_o⁴ − r_i⁴)/(2h)
    at μ = 32e-6·870 Pa·s, Δω = 500 rpm, and no heat balance; map --oil-temperature
    40:100:2 gives, at each temperature, the solve's answer at that temperature (the drag
    scales with the viscosity: 5.4/32 at 100 degC)."""
    path = _write(tmp_path, WET_PAIR)
    assert main(["solve", path, "--oil-temperature", "40", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert "thermal" not in out and out["lubricant"]["temperature"] == pytest.approx(313.15)
    torque = 6 * math.pi * 32e-6 * 870 * (W_IN / 2) * (0.08 ** 4 - 0.06 ** 4) / (2 * 0.2e-3)
    assert out["total_loss"] == pytest.approx(torque * W_IN / 2, rel=1e-12)
    load = 2 * (1000 - out["total_loss"]) / W_IN          # N·m the output drives
    assert main(["map", path, "--torque", repr(load), "--speed", "1000",
                 "--oil-temperature", "40:100:2", "--json"]) == 0
    maps = json.loads(capsys.readouterr().out)
    assert maps["oil_temperatures"] == pytest.approx([313.15, 373.15])
    assert maps["maps"][0]["efficiency"][0][0] == pytest.approx(out["efficiency"], rel=1e-9)
    assert main(["solve", path, "--oil-temperature", "100", "--json"]) == 0
    hot = json.loads(capsys.readouterr().out)
    assert hot["total_loss"] == pytest.approx(out["total_loss"] * 5.4 / 32, rel=1e-12)
    # the 40 degC load at 100 degC: the same output power over it plus the thinner drag
    delivered = 1000 - out["total_loss"]
    assert maps["maps"][1]["efficiency"][0][0] == pytest.approx(
        delivered / (delivered + hot["total_loss"]), rel=1e-9)


@pytest.mark.parametrize("argv,message", [
    (["solve", "{model}", "--oil-temperature", "400"], "--oil-temperature 400"),
    (["solve", "models/wolfrom_3k.yaml", "--oil-temperature", "40"], "no lubricant"),
    (["map", "{model}", "--torque", "10", "--speed", "1000", "--oil-temperature", "40:80:2",
      "--loss-map", "{tmp}/x.vtlm"], "one oil temperature"),
])
def test_cli_oil_temperature_errors_are_one_line(tmp_path, capsys, argv, message) -> None:
    path = _write(tmp_path, WET_PAIR)
    argv = [a.format(model=path, tmp=tmp_path) for a in argv]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and message in err and "Traceback" not in err


DIPPED = {
    "name": "dipped pair", "lubricant": {"grade": "ISO VG 100", "temperature": "60 degC"},
    "components": {
        0: {"role": "frame"},
        1: {"teeth": 20, "geometry": {"shape": "gear", "module": 3, "face_width": 20,
                                      "bore_radius": 10}},
        2: {"teeth": 60, "geometry": {"shape": "gear", "module": 3, "face_width": 20,
                                      "bore_radius": 10},
            "churning": {"immersion": "30 mm", "oil_volume": "2 L"}}},
    "links": [{"type": "mesh", "between": [1, 2], "efficiency": 0.99},
              {"type": "bearing", "between": [1, 0],
               "skf": {"series": "62", "bore": "30 mm", "outside": "62 mm"}}],
    "ports": [{"component": 1, "role": "input", "speed": "1500 rpm", "power": "5 kW"},
              {"component": 2, "role": "output"}]}


def test_skf_bearing_and_churning_gear_are_loss_sources_at_the_oils_viscosity() -> None:
    """The pinion's 6206-size bearing (62 series, 30 x 62 mm) carries the tooth force
    (T_in − M_bearing) / r_1 (r_1 = 3·20/2 mm) at 1500 rpm; the wheel (r = 90 mm, b = 20 mm) dips 30 mm
    into 2 L of ISO VG 100 at 60 degC and turns at 500 rpm. Each loss is its law's
    (powergraph.gears.skf_bearing, powergraph.gears.churning; tested there by hand) at
    these inputs, and the balance holds."""
    from powergraph.gears.churning import churning_torque
    from powergraph.gears.skf_bearing import skf_moment

    model = model_from_dict(DIPPED)
    result = pg.solve(model)
    assert_conservation(result)
    nu = walther_cst(100, 11.2, 60) * 1e-6
    bearing, churning = result.bearings
    w1 = W_IN * 1.5
    # body 1: the input torque holds the mesh's torque and the bearing's own friction
    load = (result.ports[0].torque - bearing.torque) / 0.030
    assert bearing.radial_load == pytest.approx(load, rel=1e-9)
    expected = skf_moment("62", 0.030, 0.062, load, 0.0, w1, nu).total
    assert bearing.torque == pytest.approx(expected, rel=1e-9)
    dip = churning_torque(0.090, 0.020, 0.030, 2e-3, w1 / 3, nu, 885.0, teeth=60,
                          tooth_height=2.25 * 0.003).torque
    assert churning.torque == pytest.approx(dip, rel=1e-12)
    assert churning.loss == pytest.approx(dip * w1 / 3, rel=1e-12)
    labels = [entry["source"] for entry in result.to_dict()["loss_breakdown"]]
    assert any(label.startswith("churning 2") for label in labels)


def test_churning_of_a_planet_is_refused() -> None:
    raw = load_yaml_file("models/planetary_2kh_sun_to_carrier.yaml")
    raw["lubricant"] = OIL
    planet = next(c for c, attrs in raw["components"].items()
                  if "planet" in str((attrs or {}).get("name", "")).lower())
    raw["components"][planet]["churning"] = {"immersion": "10 mm", "oil_volume": "1 L",
                                             "pitch_radius": "20 mm", "face_width": "10 mm"}
    with pytest.raises(ModelError, match="planet"):
        model_from_dict(raw)


def test_a_map_of_the_dipped_pair_is_its_solves() -> None:
    """SKF's moment is not proportional to the load: the map solves its points (the grid),
    each equal to the single solve at that point, both sides of the no-load line."""
    from powergraph.analyses.efficiency_map import efficiency_map

    model = model_from_dict(DIPPED)
    grid = efficiency_map(model, [-60.0, 20.0, 90.0], [700.0, 1500.0])
    for i, rpm in enumerate((700.0, 1500.0)):
        for j, torque in enumerate((-60.0, 20.0, 90.0)):
            port = model.outputs[0]
            point = model.with_port(model.inputs[0].index, speed=rpm * math.pi / 30,
                                    power=None, torque=None)
            # the output turns backwards (a 1:3 external pair): +90 N·m on the train
            # resists it, the map's 90 N·m load; -60 N·m drives it (coasting)
            point = point.with_port(port.index, torque=torque, power=None)
            single = pg.solve(point)
            assert_conservation(single)
            assert grid.efficiency[i, j] == pytest.approx(single.efficiency, rel=1e-9)


def test_churning_between_the_two_fits_is_warned() -> None:
    """Re_c = ω R h / ν: the wheel (R 90 mm, h 30 mm) at 500 rpm in ISO VG 100 at 80 degC
    lies in 6000…9000 (interpolated, warned); at 40 degC it is below 6000 (no warning)."""
    from powergraph.model.lubricant import fixed_temperature

    model = model_from_dict(DIPPED)
    for celsius, warned in ((40, False), (80, True)):
        result = pg.solve(fixed_temperature(model, 273.15 + celsius))
        critical = (W_IN * 1.5 / 3) * 0.090 * 0.030 / (walther_cst(100, 11.2, celsius) * 1e-6)
        assert (6000 < critical < 9000) == warned
        codes = [c.code for c in result.warnings]
        assert ("churning-transition" in codes) == warned


def test_the_oil_bath_reducer_is_its_laws_at_its_oil_temperature() -> None:
    """models/oil_bath_reducer.yaml by hand: z 20/60, so the wheel turns at −1500/3 rpm;
    the two seals lose 7.69e-6·d²·n (30 mm at 1500 rpm, 40 mm at 500 rpm); the wheel
    churns its law's torque at 500 rpm; the mesh loses its virtual power times 1 − η
    (an external pair on the housing: the virtual power is the power the pinion gives the
    mesh, input power minus the pinion's own bearing and seal); the balance closes, and the
    oil settles where the total loss is 18 W/(m² K) · 0.25 m² · (T − 20 °C)."""
    from powergraph.gears.churning import churning_torque

    model = pg.load_model("models/oil_bath_reducer.yaml")
    result = pg.solve(model)
    assert_conservation(result)
    w1 = 1500 * math.pi / 30
    assert result.kinematics.speed("2") == pytest.approx(-w1 / 3, rel=1e-12)
    by = {s.node: w for s, w in losses(result)}
    assert by["seal 1-0"] == pytest.approx(7.69e-6 * 30 ** 2 * 1500, rel=1e-12)
    assert by["seal 2-0"] == pytest.approx(7.69e-6 * 40 ** 2 * 500, rel=1e-12)
    temperature = result.thermal.temperature
    nu = walther_cst(100, 11.2, temperature - 273.15) * 1e-6
    dip = churning_torque(0.090, 0.020, 0.030, 2e-3, w1 / 3, nu, 885.0, teeth=60,
                          tooth_height=2.25 * 0.003).torque
    assert by["churning 2"] == pytest.approx(dip * w1 / 3, rel=1e-9)
    mesh = result.element(0)
    given = 5000.0 - by["bearing 1-0"] - by["seal 1-0"]
    assert mesh.carrier_frame_power == pytest.approx(given, rel=1e-9)
    assert by["links[0] mesh 1-2"] == pytest.approx(given * (1 - mesh.efficiency), rel=1e-9)
    assert result.total_loss == pytest.approx(18 * 0.25 * (temperature - 293.15), rel=1e-6)
    assert result.output_power == pytest.approx(5000.0 - sum(by.values()), rel=1e-12)
