"""Number columns for the text reports: one unit per column, aligned decimals, no ``-0``.

Examples
--------
>>> unit, scale = power_unit([2270.0, 652.3, 1.5])
>>> unit, column([2270.0, 652.3, 1.5], scale)
('kW', ['2.27000', '0.65230', '0.00150'])
>>> column([-0.0, -1e-20, 1500.0])
['0.00', '0.00', '1,500.00']
>>> ratio_text(121.0), ratio_text(0.01), ratio_text(-119.0)
('121 : 1', '1 : 100', '119 : 1, output reversed')
"""
from __future__ import annotations

import math
from typing import Sequence

from powergraph.format import display_width, pad

SIGNIFICANT = 6


def table(rows: Sequence[Sequence[str]], numeric: set[int], indent: str = "  ") -> list[str]:
    """Rows padded to common display widths: ``numeric`` columns right-aligned; the first
    row is the header.

    >>> table([["name", "kW"], ["齿轮", "1.5"]], {1})
    ['  name   kW', '  齿轮  1.5']
    """
    widths = [max(display_width(row[i]) for row in rows) for i in range(len(rows[0]))]
    return [(indent + "  ".join(pad(cell, w, i in numeric)
                                for i, (cell, w) in enumerate(zip(row, widths)))).rstrip()
            for row in rows]


def power_unit(values: Sequence[float]) -> tuple[str, float]:
    """The unit (W, kW or MW) that fits the largest of ``values``, and its scale."""
    largest = max((abs(v) for v in values if math.isfinite(v)), default=0.0)
    for unit, scale in (("MW", 1e6), ("kW", 1e3)):
        if largest >= scale:
            return unit, scale
    return "W", 1.0


def column(values: Sequence[float], scale: float = 1.0,
           significant: int = SIGNIFICANT) -> list[str]:
    """``values / scale`` with one number of decimals for the whole column (the largest
    value keeps ``significant`` digits), thousands separated; zero never prints as -0."""
    scaled = [v / scale for v in values]
    largest = max((abs(v) for v in scaled if math.isfinite(v)), default=0.0)
    digits = math.floor(math.log10(largest)) + 1 if largest > 0 else 1
    decimals = max(0, significant - digits)
    return [number(v, decimals) for v in scaled]


def number(value: float, decimals: int) -> str:
    """``value`` with ``decimals`` decimals and thousands separators, never ``-0``.

    >>> number(-0.00001, 3), number(-1.5, 1), number(float("nan"), 2)
    ('0.000', '-1.5', '-')
    """
    if not math.isfinite(value):
        return "-" if math.isnan(value) else ("inf" if value > 0 else "-inf")
    text = f"{value:,.{decimals}f}"
    if text.startswith("-") and not any(c in "123456789" for c in text):
        text = text[1:]
    return text


def ratio_text(ratio: float | None) -> str | None:
    """A speed ratio as a designer reads it: a reduction ``121 : 1``, a step-up ``1 : 100``,
    with ``output reversed`` when the output turns the other way."""
    if ratio is None:
        return None
    if math.isnan(ratio):
        return "undefined"
    if math.isinf(ratio):
        return "output at rest"
    if ratio == 0:
        return "input at rest"
    size = abs(ratio)
    text = f"{size:.6g} : 1" if size >= 1 else f"1 : {1 / size:.6g}"
    return text + (", output reversed" if ratio < 0 else "")
