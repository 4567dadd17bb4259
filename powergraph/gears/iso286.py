"""ISO 286-1 standard tolerance grades IT5…IT9 and the profile errors of Csobán (2021).

The paper takes the profile error ``d`` as half the IT tolerance of the disc's pitch
diameter ``m·z1`` (tests/data/published_values.yaml; this reproduces its Table 1, e.g.
m = 3, z1 = 9, IT5 → 0.0045 mm). The values are the standard's table (µm) for nominal
sizes up to 500 mm; they follow ``k·i`` with ``i = 0.45·D^(1/3) + 0.001·D`` (µm, ``D``
the geometric mean of the step's limits) and ``k = 7, 10, 16, 25, 40`` for IT5…IT9,
rounded by the standard's rules.
"""
from __future__ import annotations

import math

from powergraph.errors import UsageError

#: Grades the paper uses (IT5…IT9) and their multiples of the tolerance unit i.
GRADES = (5, 6, 7, 8, 9)
GRADE_FACTORS = {5: 7, 6: 10, 7: 16, 8: 25, 9: 40}

#: ISO 286-1 table 1: (upper limit of the size step in mm, (IT5, IT6, IT7, IT8, IT9) in µm).
#: A step includes its upper limit and excludes its lower one (the first starts at 0).
ISO_286_TABLE = (
    (3, (4, 6, 10, 14, 25)),
    (6, (5, 8, 12, 18, 30)),
    (10, (6, 9, 15, 22, 36)),
    (18, (8, 11, 18, 27, 43)),
    (30, (9, 13, 21, 33, 52)),
    (50, (11, 16, 25, 39, 62)),
    (80, (13, 19, 30, 46, 74)),
    (120, (15, 22, 35, 54, 87)),
    (180, (18, 25, 40, 63, 100)),
    (250, (20, 29, 46, 72, 115)),
    (315, (23, 32, 52, 81, 130)),
    (400, (25, 36, 57, 89, 140)),
    (500, (27, 40, 63, 97, 155)),
)
LARGEST_SIZE = ISO_286_TABLE[-1][0]


def iso_tolerance(diameter: float, grade: int) -> float:
    """ISO 286-1 standard tolerance (mm) of grade IT``grade`` for a nominal size (mm).

    Examples
    --------
    >>> iso_tolerance(27.0, 5)      # 18 < D <= 30 mm, IT5 = 9 µm
    0.009
    """
    if grade not in GRADE_FACTORS:
        raise UsageError(f"grade must be one of IT{GRADES[0]}…IT{GRADES[-1]}, got {grade!r}")
    if not (isinstance(diameter, (int, float)) and math.isfinite(diameter)) or diameter <= 0:
        raise UsageError(f"nominal size must be a number > 0 mm, got {diameter!r}")
    if diameter > LARGEST_SIZE:
        raise UsageError(f"nominal size {diameter:g} mm is above {LARGEST_SIZE} mm, the "
                         "range tabulated here (the paper leaves such gears out too)")
    values = next(v for upper, v in ISO_286_TABLE if diameter <= upper)
    return values[GRADES.index(grade)] / 1000.0


def profile_error_for_grade(module: float, teeth: int, grade: int) -> float:
    """The paper's profile error: half the IT tolerance of the pitch diameter ``m·z1`` (mm).

    Examples
    --------
    >>> profile_error_for_grade(3, 9, 5)    # paper Table 1
    0.0045
    """
    return iso_tolerance(float(module) * teeth, grade) / 2.0
