"""The involute function and its inverse (powergraph.gears.involute)."""
from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, strategies as st
from scipy.optimize import brentq

from powergraph.errors import ModelError
from powergraph.gears.involute import involute, inverse_involute


def test_involute_of_twenty_degrees_is_the_table_value() -> None:
    """inv 20° = tan 20° − 20° in radians = 0.014904 (every gear handbook's table)."""
    assert involute(math.radians(20)) == pytest.approx(0.0149044, abs=5e-8)


@pytest.mark.parametrize("value", [1e-4, 1e-3, 0.0149044, 0.05, 0.1, 0.5, 1.0, 5.0, 100.0])
def test_inverse_matches_an_independent_root_finder(value) -> None:
    """Brent's method on tan α − α − value over (0, π/2) finds the same angle."""
    expected = brentq(lambda a: involute(a) - value, 1e-9, math.pi / 2 - 1e-12,
                      xtol=1e-15, rtol=1e-15, maxiter=200)
    assert inverse_involute(value) == pytest.approx(expected, rel=1e-14)


@given(st.floats(min_value=0.02, max_value=math.pi / 2 - 1e-3))
def test_inverse_undoes_the_involute(angle) -> None:
    """Round trip to rounding: inv is well conditioned for pressure angles above ~1°."""
    assert inverse_involute(involute(angle)) == pytest.approx(angle, rel=1e-13)


def test_inverse_lies_in_the_open_quarter_turn_for_extreme_values() -> None:
    for value in (1e-12, 1e6, 1e300):
        angle = inverse_involute(value)
        assert 0 < angle <= math.pi / 2
    assert np.isclose(inverse_involute(1e6), math.pi / 2, atol=1e-5)


@pytest.mark.parametrize("value", [0.0, -0.01, math.nan, math.inf])
def test_no_angle_has_a_non_positive_or_non_finite_involute(value) -> None:
    with pytest.raises(ModelError, match="no pressure angle has involute"):
        inverse_involute(value)
