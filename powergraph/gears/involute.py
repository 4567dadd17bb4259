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
    """The angle α in (0, π/2) with inv α = ``value``.

    Newton's method from the right of the root. On (0, π/2) inv is increasing and convex
    (inv' = tan² α, inv'' = 2 tan α / cos² α), so Newton steps taken from any angle where
    inv α ≥ ``value`` decrease monotonically to the root and never cross it. The start is
    the smaller of two such angles: (3·value)^(1/3), because inv α ≥ α³/3, and
    atan(value + π/2), because the root has tan α = value + α < value + π/2. The
    iteration stops when a step no longer decreases the angle (to the last bit).
    No scipy: importing ``scipy.optimize`` would cost a third of a second on every
    ``powergraph solve`` of a model with tooth geometry.

    Raises ModelError when ``value`` <= 0 (no such angle).

    >>> round(math.degrees(inverse_involute(involute(math.radians(22.5)))), 12)
    22.5
    """
    if not value > 0 or not math.isfinite(value):
        raise ModelError(f"no pressure angle has involute {value!r} (it must be > 0)")
    angle = math.atan(value + math.pi / 2)
    cube_root = (3.0 * value) ** (1.0 / 3.0)
    if cube_root < angle:
        angle = cube_root
    for _ in range(200):
        tangent = math.tan(angle)
        step = (tangent - angle - value) / (tangent * tangent)
        if not step > 0:                  # at the root, or rounding below it
            break
        following = angle - step
        if not following < angle:         # the step is below the last bit
            break
        angle = following
    return angle
