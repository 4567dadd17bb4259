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
    _CASE_SENSITIVE_POWER,
    _FAST,
    _FAST_IN,
    SI_UNITS,
    parse_in_unit,
    parse_quantity,
    unit_expression,
)

UREG = pint.UnitRegistry()
PINT_SPELLING = {"n m": "N*m", "nm": "N*m", "n·m": "N*m", "n.m": "N*m", "kn*m": "kN*m",
                 "n*mm": "N*mm", "nmm": "N*mm", "n*m": "N*m", "µm": "um"}
FORMAT_MD = (Path(__file__).resolve().parents[2] / "docs" / "format.md").read_text()

# The speed units docs/format.md lists, with pint's spelling. Angular units name an angle
# and convert through it; frequencies name none and count revolutions (ω = 2π·f). The
# split is written here by hand: pint alone cannot make it (its radian is dimensionless).
ANGULAR = {"rad/s": "rad/s", "rad/min": "rad/min", "deg/s": "deg/s", "°/s": "degree/s",
           "rpm": "rpm", "rev/min": "revolution/minute", "r/min": "revolution/minute",
           "rps": "rps", "rev/s": "revolution/second", "turn/s": "turn/s"}
FREQUENCY = {"Hz": "Hz", "kHz": "kHz", "1/s": "1/s", "1/min": "1/min", "/min": "1/min",
             "1/h": "1/hour", "s^-1": "s**-1", "min^-1": "min**-1"}


@pytest.mark.parametrize("kind,unit", [(k, u) for k, table in _FAST.items() for u in table
                                       if k != "speed"]
                         + [("power", u) for u in _CASE_SENSITIVE_POWER])
def test_fast_table_matches_pint(kind: str, unit: str) -> None:
    expected = UREG.Quantity(2.5, PINT_SPELLING.get(unit, unit)).to(SI_UNITS[kind]).magnitude
    assert parse_quantity(f"2.5 {unit}", kind, "x") == pytest.approx(expected, rel=1e-12)


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
    documented = {u.lower() for u in [*ANGULAR, *FREQUENCY]}
    assert set(_FAST["speed"]) <= documented


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


@pytest.mark.parametrize("target,unit", [(t, u) for t, table in _FAST_IN.items() for u in table])
def test_fast_viscosity_table_matches_pint(target: str, unit: str) -> None:
    """The viscosities read without pint are pint's conversions."""
    expected = UREG.Quantity(2.5, unit.replace(" ", "*").replace("·", "*")).to(target).magnitude
    assert parse_in_unit(f"2.5 {unit}", target, "dynamic viscosity", "v") == \
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
