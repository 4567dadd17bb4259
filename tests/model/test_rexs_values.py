"""REXS attributes in the model's units (powergraph.model.rexs_values): each unit by its
definition (1 m = 1000 mm, 1 rad = 180/π deg, 1 kg/dm³ = 1000 kg/m³, 1 % = 0.01), and an
unknown unit or a value that is not a number is one error naming the attribute."""
from __future__ import annotations

import math

import pytest

from powergraph.errors import ModelError
from powergraph.model.rexs_document import parse_rexs
from powergraph.model.rexs_values import AttributeReader


def _reader(value: str, unit: str) -> AttributeReader:
    return AttributeReader(parse_rexs(
        f'<model version="1.4"><relations/><components><component id="7" name="" '
        f'type="cylindrical_gear"><attribute id="a" unit="{unit}">{value}</attribute>'
        f'</component></components></model>'.encode(), "u.rexs"))


@pytest.mark.parametrize("value, unit, kind, expected", [
    ("0.25", "m", "length", 250.0), ("1", "rad", "angle", 180 / math.pi),
    ("0.88", "kg / dm^3", "density", 880.0), ("35", "%", "fraction", 0.35),
    ("2", "N mm", "torque", 0.002), ("60", "1 / min", "speed", 60.0),
])
def test_units(value, unit, kind, expected) -> None:
    assert _reader(value, unit).value(7, "a", kind) == pytest.approx(expected, rel=1e-15)


@pytest.mark.parametrize("value, unit, words", [
    ("3", "furlong", "unit 'furlong' is not one of"), ("three", "mm", "is not a number"),
    ("inf", "mm", "not a finite number")])
def test_bad_values(value, unit, words) -> None:
    with pytest.raises(ModelError, match=words) as info:
        _reader(value, unit).value(7, "a", "length")
    assert str(info.value).startswith("u.rexs: component 7 a:")
