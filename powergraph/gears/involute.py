"""The involute function and its inverse: the one copy used by every gear calculation.

Angles in radians.
"""
from __future__ import annotations

import math

from powergraph.errors import ModelError


def involute(angle: float) -> float:
    """inv α = tan α − α.

    >>> round(involute(math.radians(20)), 6)
    0.014904
    """
    return math.tan(angle) - angle


def inverse_involute(value: float) -> float:
    """The angle α in (0, π/2) with inv α = ``value`` (scipy root finding).

    Raises ModelError when ``value`` <= 0 (no such angle).

    >>> round(math.degrees(inverse_involute(involute(math.radians(22.5)))), 12)
    22.5
    """
    from scipy.optimize import brentq

    if not value > 0 or not math.isfinite(value):
        raise ModelError(f"no pressure angle has involute {value!r} (it must be > 0)")
    upper = math.pi / 2 - 1e-12
    return brentq(lambda a: involute(a) - value, 0.0, upper, xtol=1e-15, rtol=1e-15,
                  maxiter=200)
