"""How numbers are written for a person: the one copy every text report and command uses.

- :func:`format_number`, :func:`format_fixed` — significant digits or fixed decimals, never
  ``-0``, ``-`` for a missing value;
- :func:`format_ratio` — a reduction as ``121 : 1``, a step-up as ``1 : 100``;
- :func:`format_power`, :func:`format_share` — one power with its own unit (``2.27 kW``), a
  share of a reference in percent (the labels of the power-flow diagrams);
- :func:`unit_scale` and :func:`format_column` — one unit for a whole column, chosen from
  its largest value (``W`` or ``kW``, ``mm³`` or ``L``...), so a column never mixes units;
- :func:`aligned_table` — rows padded to widths computed from their cells, so long names
  never run into the next column;
- :func:`csv_header` — a column name with its unit, ``output_power [W]``.

This module sits in the base layer and imports nothing heavy, so every layer may use it.

Examples
--------
>>> format_ratio(121.00000000000075), format_ratio(0.01), format_ratio(-119.0)
('121 : 1', '1 : 100', '-119 : 1')
>>> format_number(-0.0), format_number(-1e-13, zero=1e-9), format_number(None)
('0', '0', '-')
>>> format_column([2270.0, 652.34, 1617.66], POWER_UNITS)
('kW', ['2.27', '0.6523', '1.618'])
"""
from __future__ import annotations

import math
import unicodedata
from typing import Iterable, Sequence

#: (unit, size of one unit in the base unit), smallest first.
POWER_UNITS = (("mW", 1e-3), ("W", 1.0), ("kW", 1e3), ("MW", 1e6))
VOLUME_UNITS = (("mm³", 1.0), ("L", 1e6), ("m³", 1e9))
TORQUE_UNITS = (("N·m", 1.0), ("kN·m", 1e3))


def _missing(value: object) -> bool:
    return value is None or (isinstance(value, float) and math.isnan(value))


def format_number(value: float | None, digits: int = 4, zero: float = 0.0) -> str:
    """``value`` with ``digits`` significant digits; ``0`` for anything within ``zero`` of
    zero (never ``-0``), ``-`` for None or NaN, thousands separated by commas.

    >>> [format_number(v) for v in (1617.66, -0.0, 0.000123456, float("nan"), 1.5e7)]
    ['1,618', '0', '0.0001235', '-', '15,000,000']
    >>> format_number(1000.0, 5), format_number(1234.5, 5)
    ('1,000', '1,234.5')
    """
    if _missing(value):
        return "-"
    value = float(value)
    if math.isinf(value):
        return "inf" if value > 0 else "-inf"
    if abs(value) <= zero or float(f"{value:.{digits}g}") == 0.0:
        return "0"
    if 1000 <= abs(value) < 1e15:
        decimals = digits - 1 - math.floor(math.log10(abs(value)))
        text = f"{round(value, decimals):,.{max(decimals, 0)}f}"
        return text.rstrip("0").rstrip(".") if "." in text else text
    return f"{value:.{digits}g}"


def format_fixed(value: float | None, decimals: int = 2) -> str:
    """``value`` with a fixed number of decimals (a column of percentages), never ``-0``;
    ``-`` for None or NaN.

    >>> [format_fixed(v) for v in (93.0, -0.001, 55.4321, None)]
    ['93.00', '0.00', '55.43', '-']
    """
    if _missing(value):
        return "-"
    text = f"{float(value):,.{decimals}f}"
    return text[1:] if text.startswith("-") and float(text.replace(",", "")) == 0 else text


def format_ratio(ratio: float | None, digits: int = 4) -> str:
    """A speed ratio (input speed / output speed) as a person reads it: a reduction as
    ``N : 1``, a step-up (``|ratio| < 1``) as ``1 : N``; the sign (output turning the other
    way) stays on the first number. ``-`` when there is no ratio.

    >>> [format_ratio(r) for r in (121.0, 4, 0.01, -0.25, 99.75, 1.0, None)]
    ['121 : 1', '4 : 1', '1 : 100', '-1 : 4', '99.75 : 1', '1 : 1', '-']
    >>> format_ratio(0.0), format_ratio(float("inf"))
    ('0 : 1', '1 : 0')
    """
    if _missing(ratio):
        return "-"
    ratio = float(ratio)
    if math.isinf(ratio):
        return "1 : 0" if ratio > 0 else "-1 : 0"
    if ratio == 0.0:
        return "0 : 1"
    if abs(ratio) >= 1.0:
        return f"{format_number(ratio, digits)} : 1"
    sign = "-" if ratio < 0 else ""
    return f"{sign}1 : {format_number(1.0 / abs(ratio), digits)}"


def format_power(watts: float) -> str:
    """Power with three significant digits in mW, W, kW or MW.

    >>> [format_power(p) for p in (0.0, 0.01473, 135.07, 999.96, 2270.0, 26093.7)]
    ['0 W', '14.7 mW', '135 W', '1.00 kW', '2.27 kW', '26.1 kW']
    """
    if watts == 0 or not math.isfinite(watts):
        return "0 W" if watts == 0 else f"{watts} W"
    for scale, unit in ((1e6, "MW"), (1e3, "kW"), (1.0, "W"), (1e-3, "mW")):
        value = float(f"{abs(watts) / scale:.3g}")
        if value >= 1.0 or unit == "mW":
            sign = "-" if watts < 0 else ""
            text = f"{value:#.3g}".rstrip(".") if value < 1000 else f"{value:,.0f}"
            return f"{sign}{text} {unit}"
    raise AssertionError("unreachable")  # pragma: no cover


def format_share(power: float, reference: float) -> str:
    """``power / reference`` in percent, three significant digits (no exponent).

    >>> [format_share(p, 2270.0) for p in (0.0, 2270.0, 71.66, 26093.7)]
    ['0 %', '100 %', '3.16 %', '1,150 %']
    """
    if not reference or not math.isfinite(reference):
        return "- %"
    share = 100.0 * power / abs(reference)
    if share == 0:
        return "0 %"
    rounded = float(f"{share:.3g}")
    return f"{rounded:,.0f} %" if abs(rounded) >= 100 else f"{rounded:#.3g}".rstrip(".") + " %"


def unit_scale(values: Iterable[float | None], units: Sequence[tuple[str, float]]
               ) -> tuple[str, float]:
    """The one unit of ``units`` (``(name, size)``, smallest first) for a whole column:
    the largest unit in which the column's largest magnitude is at least 0.1 (so no value
    needs more than four digits before the point).

    >>> unit_scale([135.07, 1482.58], POWER_UNITS), unit_scale([0.0], POWER_UNITS)
    (('kW', 1000.0), ('W', 1.0))
    >>> unit_scale([99.0], POWER_UNITS), unit_scale([652.3], POWER_UNITS)
    (('W', 1.0), ('kW', 1000.0))
    """
    finite = [abs(float(v)) for v in values if not _missing(v) and math.isfinite(float(v))]
    largest = max(finite, default=0.0)
    base = next((u for u in units if u[1] == 1.0), units[0])
    if largest == 0.0:
        return base
    chosen = units[0]
    for unit in units:
        if largest >= 0.1 * unit[1]:
            chosen = unit
    return chosen


def format_column(values: Sequence[float | None], units: Sequence[tuple[str, float]],
                  digits: int = 4) -> tuple[str, list[str]]:
    """``(unit, texts)``: the column's values in its one unit (see :func:`unit_scale`).

    >>> format_column([634313.9, None], VOLUME_UNITS)
    ('L', ['0.6343', '-'])
    """
    unit, size = unit_scale(values, units)
    zero = 1e-9 * max((abs(float(v)) for v in values if not _missing(v)
                       and math.isfinite(float(v))), default=0.0)
    return unit, [format_number(None if _missing(v) else float(v) / size, digits,
                                zero=zero / size) for v in values]


def aligned_table(rows: list[list[str]], numeric: set[int],
                  rules_after: tuple[int, ...] = (0,)) -> list[str]:
    """Text rows padded to common column widths: ``numeric`` columns right-aligned, the
    others left-aligned, a dashed rule after each row index in ``rules_after``.

    >>> aligned_table([["a", "n"], ["bb", "1"]], {1})
    ['a   n', '--  -', 'bb  1']
    """
    widths = [max(display_width(row[i]) for row in rows) for i in range(len(rows[0]))]
    lines = []
    for index, row in enumerate(rows):
        lines.append("  ".join(pad(cell, w, i in numeric)
                               for i, (cell, w) in enumerate(zip(row, widths))).rstrip())
        if index in rules_after:
            lines.append("  ".join("-" * w for w in widths))
    return lines


def csv_header(name: str, unit: str | None) -> str:
    """A CSV column name with its unit in brackets (``[-]`` for a pure number); a column
    without a unit (a flag, a status) keeps its bare name.

    >>> csv_header("output_power", "W"), csv_header("efficiency", "-"), csv_header("status", None)
    ('output_power [W]', 'efficiency [-]', 'status')
    """
    return name if unit is None else f"{name} [{unit}]"


def display_width(text: str) -> int:
    """Columns ``text`` takes in a terminal (wide East Asian characters count 2, combining
    marks 0).

    >>> display_width("ab"), display_width("齿轮"), display_width("é")
    (2, 4, 1)
    """
    width = 0
    for char in text:
        if unicodedata.combining(char):
            continue
        width += 2 if unicodedata.east_asian_width(char) in ("W", "F") else 1
    return width


def pad(text: str, width: int, right: bool = False) -> str:
    """``text`` padded with spaces to ``width`` display columns."""
    fill = " " * max(0, width - display_width(text))
    return fill + text if right else text + fill


def table(rows: Sequence[Sequence[str]], numeric: set[int], indent: str = "  ") -> list[str]:
    """:func:`aligned_table` without rules, each line indented: the solve report's tables.

    >>> table([["name", "kW"], ["齿轮", "1.5"]], {1})
    ['  name   kW', '  齿轮  1.5']
    """
    return [(indent + line).rstrip() for line in aligned_table([list(r) for r in rows],
                                                                numeric, rules_after=())]


def power_unit(values: Sequence[float]) -> tuple[str, float]:
    """The unit (W, kW or MW) that fits the largest of ``values``, and its scale.

    >>> power_unit([2270.0, 652.3, 1.5]), power_unit([0.5])
    (('kW', 1000.0), ('W', 1.0))
    """
    largest = max((abs(v) for v in values if math.isfinite(v)), default=0.0)
    for unit, scale in reversed(POWER_UNITS[1:]):
        if largest >= scale or unit == "W":
            return unit, scale
    raise AssertionError("unreachable")  # pragma: no cover


def column(values: Sequence[float], scale: float = 1.0, significant: int = 6) -> list[str]:
    """``values / scale`` with one number of decimals for the whole column (the largest
    value keeps ``significant`` digits), thousands separated; zero never prints as -0.

    >>> column([2270.0, 652.3, 1.5], 1e3)
    ['2.27000', '0.65230', '0.00150']
    >>> column([-0.0, -1e-20, 1500.0])
    ['0.00', '0.00', '1,500.00']
    """
    scaled = [v / scale for v in values]
    largest = max((abs(v) for v in scaled if math.isfinite(v)), default=0.0)
    digits = math.floor(math.log10(largest)) + 1 if largest > 0 else 1
    decimals = max(0, significant - digits)
    return [format_fixed(v, decimals) if math.isfinite(v) or math.isnan(v)
            else ("inf" if v > 0 else "-inf") for v in scaled]


def ratio_text(ratio: float | None) -> str | None:
    """:func:`format_ratio` of the size of ``ratio`` (6 digits), with ``output reversed``
    when the output turns the other way: the solve report's ratio line.

    >>> ratio_text(121.0), ratio_text(0.01), ratio_text(-119.0)
    ('121 : 1', '1 : 100', '119 : 1, output reversed')
    """
    if ratio is None:
        return None
    if math.isnan(ratio):
        return "undefined"
    if math.isinf(ratio):
        return "output at rest"
    if ratio == 0:
        return "input at rest"
    return format_ratio(abs(ratio), 6) + (", output reversed" if ratio < 0 else "")
