"""Numbers for a person (powergraph/format.py): ratios, one unit per column, no -0.

Expected values are the definitions: a speed ratio i = w_in / w_out is a reduction
``i : 1`` when |i| >= 1 and a step-up ``1 : 1/i`` otherwise (a wind-turbine gearbox of
i = 0.01 is ``1 : 100``).
"""
from __future__ import annotations

import math

import pytest

from powergraph.format import (POWER_UNITS, VOLUME_UNITS, aligned_table, csv_header,
                               format_column, format_fixed, format_number, format_ratio)


@pytest.mark.parametrize("ratio, text", [
    (121.0, "121 : 1"), (121.00000000000075, "121 : 1"), (0.01, "1 : 100"),
    (1 / 121, "1 : 121"), (-119.0, "-119 : 1"), (-0.25, "-1 : 4"), (1.0, "1 : 1"),
    (None, "-"), (math.nan, "-")])
def test_format_ratio_reads_as_a_reduction_or_a_step_up(ratio, text) -> None:
    assert format_ratio(ratio) == text


@pytest.mark.parametrize("value", [-0.0, -1e-17, -4e-5])
def test_no_minus_zero(value) -> None:
    assert format_number(value, zero=1e-3) == "0"
    assert format_fixed(value) == "0.00"


def test_a_column_has_one_unit() -> None:
    unit, cells = format_column([135.07, 1482.58, -0.0], POWER_UNITS)
    assert unit == "kW" and cells == ["0.1351", "1.483", "0"]
    unit, cells = format_column([3053.6, 634313.9, None], VOLUME_UNITS)
    assert unit == "L" and cells == ["0.003054", "0.6343", "-"]
    assert format_column([12.0, 50.0], POWER_UNITS)[0] == "W"


def test_columns_are_as_wide_as_their_longest_cell() -> None:
    lines = aligned_table([["#", "link"], ["0", "sun-planetcarrier"], ["10", "a"]], {0})
    assert lines[2] == " 0  sun-planetcarrier"     # never run together
    assert lines[3] == "10  a"
    assert {line.index(word) for line, word in zip(lines, ("link", "-", "sun", "a"))
            if word != "-"} == {4}


def test_csv_header_names_the_unit() -> None:
    assert csv_header("ports.0.speed", "rad/s") == "ports.0.speed [rad/s]"
    assert csv_header("converged", None) == "converged"
