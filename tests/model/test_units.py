"""The fast unit table agrees with pint, and bad quantities are refused with their path."""
from __future__ import annotations

import math

import pint
import pytest

from powergraph.errors import ModelError
from powergraph.model.units import _CASE_SENSITIVE_POWER, _FAST, SI_UNITS, parse_quantity

UREG = pint.UnitRegistry()
PINT_SPELLING = {"n m": "N*m", "nm": "N*m", "n·m": "N*m", "n.m": "N*m", "kn*m": "kN*m",
                 "n*mm": "N*mm", "nmm": "N*mm", "n*m": "N*m", "µm": "um",
                 "rev/min": "revolution/minute", "rev/s": "revolution/second"}


@pytest.mark.parametrize("kind,unit", [(k, u) for k, table in _FAST.items() for u in table]
                         + [("power", u) for u in _CASE_SENSITIVE_POWER])
def test_fast_table_matches_pint(kind: str, unit: str) -> None:
    expected = UREG.Quantity(2.5, PINT_SPELLING.get(unit, unit)).to(SI_UNITS[kind]).magnitude
    assert parse_quantity(f"2.5 {unit}", kind, "x") == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize("text,kind,si", [("1500 rpm", "speed", 1500 * 2 * math.pi / 60),
                                          ("2.27 kW", "power", 2270.0),
                                          ("3 hp", "power", 3 * 745.69987158227022),
                                          ("120 N*m", "torque", 120.0),
                                          ("1 kN*m", "torque", 1000.0),
                                          ("42", "power", 42.0)])
def test_known_quantities(text: str, kind: str, si: float) -> None:
    assert parse_quantity(text, kind, "p") == pytest.approx(si, rel=1e-12)


@pytest.mark.parametrize("value,message", [("3 parsecs", "is not a speed"),
                                           ("3 blorps", "unknown unit"),
                                           (True, "expected a speed"),
                                           ([1], "expected a speed"),
                                           (float("nan"), "finite")])
def test_bad_quantities(value, message: str) -> None:
    with pytest.raises(ModelError, match=message) as info:
        parse_quantity(value, "speed", "ports[0].speed")
    assert info.value.path == "ports[0].speed"
