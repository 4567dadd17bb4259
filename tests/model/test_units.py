"""The fast unit table agrees with pint, speeds follow one rule (a frequency is revolutions
per time), quantity strings outside the grammar are refused at once, and bad quantities
are refused with their path."""
from __future__ import annotations

import math
import re
import threading
from pathlib import Path

import pint
import pytest

from powergraph.errors import ModelError
from powergraph.model import loads_model
from powergraph.model.units import (
    _TABLES,
    TABLE_UNITS,
    parse_in_unit,
    parse_quantity,
    unit_expression,
    unit_factor,
)

UREG = pint.UnitRegistry()
# The table's juxtaposed spellings, as pint spells them (pint reads "Nm" as one name).
PINT_SPELLING = {"Nm": "N*m", "kNm": "kN*m", "mNm": "mN*m", "MNm": "MN*m", "Nmm": "N*mm",
                 "µm": "um"}
FORMAT_MD = (Path(__file__).resolve().parents[2] / "docs" / "format.md").read_text()

# The speed units docs/format.md lists, with pint's spelling. Angular units name an angle
# and convert through it; frequencies name none and count revolutions (ω = 2π·f). The
# split is written here by hand: pint alone cannot make it (its radian is dimensionless).
ANGULAR = {"rad/s": "rad/s", "rad/min": "rad/min", "deg/s": "deg/s", "°/s": "degree/s",
           "rpm": "rpm", "rev/min": "revolution/minute", "r/min": "revolution/minute",
           "rps": "rps", "rev/s": "revolution/second", "turn/s": "turn/s"}
FREQUENCY = {"Hz": "Hz", "kHz": "kHz", "1/s": "1/s", "1/min": "1/min", "/min": "1/min",
             "1/h": "1/hour", "s^-1": "s**-1", "min^-1": "min**-1"}


TABLE_SPELLINGS = [(kind, spelling) for kind, table in _TABLES.items()
                   for spellings, _ in table for spelling in spellings]


def _read(kind: str, text: str) -> float:
    if kind in ("speed", "power", "torque", "length"):
        return parse_quantity(text, kind, "x")
    return parse_in_unit(text, TABLE_UNITS[kind], kind, "x")


@pytest.mark.parametrize("kind,unit", [(k, u) for k, u in TABLE_SPELLINGS if k != "speed"])
def test_fast_table_matches_pint(kind: str, unit: str) -> None:
    pint_unit = unit_expression(PINT_SPELLING.get(unit, unit), kind, "x")
    expected = UREG.Quantity(2.5, pint_unit).to(TABLE_UNITS[kind]).magnitude
    assert _read(kind, f"2.5 {unit}") == pytest.approx(expected, rel=1e-12)


def _expected_rad_s(number: float, unit: str) -> float:
    if unit in ANGULAR:
        return UREG.Quantity(number, ANGULAR[unit]).to("rad/s").magnitude
    return UREG.Quantity(number, FREQUENCY[unit]).to("Hz").magnitude * 2 * math.pi


@pytest.mark.parametrize("unit", [*ANGULAR, *FREQUENCY])
def test_every_documented_speed_unit_follows_the_rule(unit: str) -> None:
    assert f"`{unit}`" in FORMAT_MD  # the docs list it
    texts = [f"2.5 {unit}"] + ([f"2.5{unit}"] if not unit[0].isdigit() else [])  # 2.51/s!
    for text in texts:
        assert parse_quantity(text, "speed", "x") == pytest.approx(
            _expected_rad_s(2.5, unit), rel=1e-12), text


def test_every_fast_speed_unit_is_documented_and_checked() -> None:
    assert {u for k, u in TABLE_SPELLINGS if k == "speed"} <= {*ANGULAR, *FREQUENCY}


@pytest.mark.parametrize("text", ["3000 1/min", "50 Hz", "3000 min^-1", "3000 rpm",
                                  "3000 rev/min", "50 s^-1", "0.05 kHz", "50 rps"])
def test_a_frequency_is_revolutions_per_time(text: str) -> None:
    # 3000 revolutions a minute = 50 a second = 50 * 2π rad/s = 100π rad/s.
    assert parse_quantity(text, "speed", "p") == pytest.approx(100 * math.pi, rel=1e-12)


@pytest.mark.parametrize("text,kind,si", [("1500 rpm", "speed", 1500 * 2 * math.pi / 60),
                                          ("2.27 kW", "power", 2270.0),
                                          ("3 hp", "power", 3 * 745.69987158227022),
                                          ("120 N*m", "torque", 120.0),
                                          ("1 kN*m", "torque", 1000.0),
                                          ("120 N·m", "torque", 120.0),
                                          ("5 kg*m^2/s^3", "power", 5.0),
                                          ("5 (kg*m**2)/(s^2)", "torque", 5.0),
                                          ("2 kW·h/h", "power", 2000.0),
                                          ("42", "power", 42.0)])
def test_known_quantities(text: str, kind: str, si: float) -> None:
    assert parse_quantity(text, kind, "p") == pytest.approx(si, rel=1e-12)


@pytest.mark.parametrize("value,message", [("3 parsecs", "is not a speed"),
                                           ("3 blorps", "unknown unit"),
                                           ("2 m/s", "is not a speed"),
                                           ("1 rad^2/s", "is not a speed"),
                                           ("1 count/s", "is not a speed"),
                                           (True, "expected a speed"),
                                           ([1], "expected a speed"),
                                           (float("nan"), "finite")])
def test_bad_quantities(value, message: str) -> None:
    with pytest.raises(ModelError, match=message) as info:
        parse_quantity(value, "speed", "ports[0].speed")
    assert info.value.path == "ports[0].speed"


HOSTILE = ["9**9**9 W", "1 " + "k" * 300, "1 " + "k" * 30 + "W", "1 W**9**9**9", "1 W^99",
           "1 W^5", "1 W**-5", "1 ((((W))))", "2**1000 W", "1e5e5 W", "1 W)", "1 (W",
           "1 W/", "inf W", "1,5 W", "1 W;", "1 W + 1 W", "1 " + "W*" * 40 + "W",
           "1 __import__", "0x10 W", "1 W^1.5"]


def _refused_at_once(call) -> ModelError:
    """Run ``call`` in a thread: it must raise ModelError (a generous 20 s bound only keeps
    a hanging parser from hanging the suite)."""
    outcome: list = []

    def target() -> None:
        try:
            call()
        except Exception as exc:  # noqa: BLE001 - kept for the assertion
            outcome.append(exc)
        else:
            outcome.append(None)

    thread = threading.Thread(target=target, daemon=True)
    thread.start()
    thread.join(20)
    assert outcome, "never returned"
    assert isinstance(outcome[0], ModelError), outcome[0]
    return outcome[0]


@pytest.mark.parametrize("text", HOSTILE)
def test_text_outside_the_grammar_is_refused(text: str) -> None:
    error = _refused_at_once(lambda: parse_quantity(text, "power", "ports[0].power"))
    assert error.path == "ports[0].power" and "\n" not in str(error)
    assert str(error).startswith("ports[0].power: cannot read ")


def test_a_hostile_power_in_a_model_names_its_place() -> None:
    text = ("name: t\ncomponents: {0: {role: frame}, 1: {teeth: 20}, 2: {teeth: 40}}\n"
            "links: [{type: mesh, between: [1, 2]}]\n"
            "ports: [{component: 1, role: input, power: '9**9**9 W'}, "
            "{component: 2, role: output}]\n")
    error = _refused_at_once(lambda: loads_model(text))
    assert str(error).startswith("ports[0].power: cannot read '9**9**9 W' as a power: ")


def test_a_hostile_viscosity_is_refused() -> None:
    error = _refused_at_once(lambda: parse_in_unit("1 mPa*s**9**9**9", "mPa*s",
                                                   "dynamic viscosity", "v"))
    assert error.path == "v"
    assert parse_in_unit("0.03 Pa*s", "mPa*s", "dynamic viscosity", "v") == \
        pytest.approx(30.0, rel=1e-12)


@pytest.mark.parametrize("unit,pint_text", [("N·m", "N*m"), ("N.m", "N*m"), ("N m", "N*m"),
                                            ("/min", "1/min"), ("s^-1", "s**-1"),
                                            ("m^(2)", "m**2"), ("(N*m)/(s)", "(N*m)/(s)")])
def test_the_grammar_spells_units_for_pint(unit: str, pint_text: str) -> None:
    assert unit_expression(unit, "x", "p") == pint_text


def test_limits_are_stated_in_the_docs() -> None:
    assert re.search(r"64 characters", FORMAT_MD)


@pytest.mark.parametrize("unit", ["mPa*s", "mPa s", "mPa·s", "mPa.s", "cP", "Pa*s", "Pa s",
                                  "Pa·s", "Pa.s"])
def test_fast_viscosity_table_matches_pint(unit: str) -> None:
    """The viscosities read without pint are pint's conversions."""
    expected = UREG.Quantity(2.5, unit.replace(" ", "*").replace("·", "*")).to("mPa*s").magnitude
    assert parse_in_unit(f"2.5 {unit}", "mPa*s", "dynamic viscosity", "v") == \
        pytest.approx(expected, rel=1e-15)


@pytest.mark.slow
def test_solving_the_friction_rv_does_not_load_pint() -> None:
    """Its lubricant viscosity ("100 mPa*s") is a common spelling: pint, slow to import,
    stays unloaded."""
    import subprocess
    import sys

    code = ("import sys, powergraph as pg; pg.solve(pg.load_model('models/rv40e.yaml')); "
            "print('pint' in sys.modules)")
    root = Path(__file__).resolve().parents[2]
    out = subprocess.run([sys.executable, "-c", code], cwd=root, capture_output=True,
                         text=True, check=True)
    assert out.stdout.strip() == "False"


# Issue 34, item 2: one rule for the case of a unit. A unit of the table is read in any
# case when that names one unit of its kind; where case tells two apart, the text is
# refused naming both; the values below are worked by hand.
@pytest.mark.parametrize("text,kind,si", [
    ("5 kw", "power", 5000.0), ("5 KW", "power", 5000.0), ("5 Kw", "power", 5000.0),
    ("3 HP", "power", 3 * 550 * 0.3048 * 4.4482216152605),       # 550 ft·lbf/s each
    ("3000 RPM", "speed", 100 * math.pi),                         # 3000 · 2π / 60
    ("50 HZ", "speed", 100 * math.pi), ("1 KHZ", "speed", 2000 * math.pi),
    ("3000 REV/MIN", "speed", 100 * math.pi), ("180 DEG/S", "speed", math.pi),
    ("120 nm", "torque", 120.0), ("120 NM", "torque", 120.0), ("120 n·m", "torque", 120.0),
    ("2 KNM", "torque", 2000.0), ("500 NMM", "torque", 0.5),
    ("4.5 UM", "length", 0.0045), ("5 CM", "length", 50.0), ("0.1 M", "length", 100.0),
    ("30 CP", "dynamic viscosity", 30.0), ("0.03 PA*S", "dynamic viscosity", 30.0)])
def test_issue34_a_unit_is_read_in_any_case_when_that_names_one_unit(text, kind, si) -> None:
    assert _read(kind, text) == pytest.approx(si, rel=1e-12)


# Spellings of two units that differ only in case, with the two (by hand).
AMBIGUOUS = {"mw": ("mW", "MW"), "mm": ("mm", "Mm"), "mn*m": ("mN*m", "MN*m"),
             "mnm": ("mN*m", "MN*m"), "mpa*s": ("mPa*s", "MPa*s")}


@pytest.mark.parametrize("text,kind", [("5 mw", "power"), ("5 Mw", "power"),
                                       ("5 MM", "length"), ("5 mM", "length"),
                                       ("5 mnm", "torque"), ("5 MNM", "torque"),
                                       ("5 mn·m", "torque"), ("5 MPA*S", "dynamic viscosity")])
def test_issue34_a_unit_whose_case_tells_two_apart_must_be_spelled_exactly(text, kind) -> None:
    unit = text.split(" ", 1)[1]
    with pytest.raises(ModelError) as info:
        _read(kind, text)
    first, second = AMBIGUOUS[unit.lower().replace("·", "*")]
    assert info.value.path == "x"
    assert info.value.message == (f"cannot read {text!r} as a {kind.replace('_', ' ')}: "
                                  f"{unit!r} could be {first} or {second}; write the unit "
                                  "with its exact case")


@pytest.mark.parametrize("text,kind,si", [("5 mW", "power", 0.005), ("5 MW", "power", 5e6),
                                          ("5 mm", "length", 5.0), ("5 Mm", "length", 5e9),
                                          ("5 mN*m", "torque", 0.005),
                                          ("5 MN*m", "torque", 5e6)])
def test_issue34_the_exact_spelling_of_a_case_pair_is_read(text, kind, si) -> None:
    assert _read(kind, text) == pytest.approx(si, rel=1e-12)


@pytest.mark.parametrize("kind,unit", [(k, u) for k, u in TABLE_SPELLINGS if u.isascii()])
def test_issue34_every_table_unit_reads_alike_in_upper_and_lower_case(kind, unit) -> None:
    exact = _read(kind, f"2.5 {unit}")
    spelled = {u for k, u in TABLE_SPELLINGS if k == kind}
    for variant in {unit.upper(), unit.lower()} - spelled:  # MW is mW's upper case
        if variant.lower() in AMBIGUOUS:
            with pytest.raises(ModelError, match="exact case"):
                _read(kind, f"2.5 {variant}")
        else:
            assert _read(kind, f"2.5 {variant}") == exact, variant


@pytest.mark.parametrize("kind", ["speed", "power", "torque", "length"])
def test_issue34_an_unknown_unit_names_the_units_accepted(kind) -> None:
    with pytest.raises(ModelError) as info:
        parse_quantity("3 blorps", kind, "ports[0].x")
    message = info.value.message
    assert message.startswith(f"unknown unit 'blorps' in '3 blorps': a {kind} is written in ")
    assert message.endswith("or in any unit pint knows, spelled as pint spells it")
    for k, unit in TABLE_SPELLINGS:
        if k == kind:
            assert unit in message


@pytest.mark.parametrize("unit,kind,si", [("rpm", "speed", math.pi / 30),
                                          ("RPM", "speed", math.pi / 30),
                                          ("Hz", "speed", 2 * math.pi),
                                          ("kw", "power", 1000.0), ("hp", "power", 745.6998715822702),
                                          ("N·m", "torque", 1.0), ("kN m", "torque", 1000.0),
                                          ("lbf*ft", "torque", 0.3048 * 4.4482216152605),
                                          ("um", "length", 1e-3)])
def test_issue34_unit_factor_is_the_si_value_of_one_unit(unit, kind, si) -> None:
    assert unit_factor(unit, kind, "points.csv line 1") == pytest.approx(si, rel=1e-12)


@pytest.mark.parametrize("unit,kind,words", [("", "speed", "no unit given: a speed is written"),
                                             ("mw", "power", "could be mW or MW"),
                                             ("blorps", "torque", "unknown unit 'blorps'"),
                                             ("rpm", "power", "'rpm' is not a power"),
                                             ("W" * 70, "power", "longer than 64 characters"),
                                             ("W**9**9", "power", "power must be a whole number from -4 to 4")])
def test_issue34_unit_factor_refuses_naming_the_place(unit, kind, words) -> None:
    where = "points.csv line 1, column 'engine.x [UNIT]'"
    error = _refused_at_once(lambda: unit_factor(unit, kind, where))
    assert error.path == where and words in error.message
    assert "\n" not in str(error)


MODEL_WITH_POWER = """name: pair
components: {0: {role: frame}, 1: {teeth: 20}, 2: {teeth: 40}}
links: [{type: mesh, between: [1, 2], efficiency: 0.98}]
ports: [{component: 1, role: input, speed: 1500 rpm, power: POWER}, {component: 2, role: output}]
"""


def test_issue34_solve_reads_5_kw_and_refuses_5_mw(tmp_path, capsys) -> None:
    import json

    from powergraph.cli.main import main

    good, bad = tmp_path / "kw.yaml", tmp_path / "mw.yaml"
    good.write_text(MODEL_WITH_POWER.replace("POWER", "5 kw"))
    bad.write_text(MODEL_WITH_POWER.replace("POWER", "5 mw"))
    assert main(["solve", str(good), "--json"]) == 0
    ports = json.loads(capsys.readouterr().out)["ports"]
    # 5 kW in; a 0.98 mesh passes 0.98 of it to the output.
    assert ports[0]["power"] == pytest.approx(5000.0, rel=1e-12)
    assert ports[1]["power"] == pytest.approx(-0.98 * 5000.0, rel=1e-12)
    assert main(["solve", str(bad)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err == ["powergraph: error: ports[0].power: cannot read '5 mw' as a power: 'mw' "
                   "could be mW or MW; write the unit with its exact case"]


def test_issue34_docs_list_every_table_unit_and_state_the_case_rule() -> None:
    units = FORMAT_MD[FORMAT_MD.index("## Units"):FORMAT_MD.index("**Speeds.**")]
    for _, spelling in TABLE_SPELLINGS:
        assert f"`{spelling}`" in units, spelling
    assert "**Case.** One rule, wherever a unit is read" in units
    assert "'mw' could be mW or MW; write the unit\nwith its exact case" in units
