"""Unit conversions the code needs in more than one place (base layer, no imports).

Speeds are rad/s inside powergraph; revolutions per minute appear only at the edges (the
model file's ``rpm``, the reports' rpm column, the efficiency map's axes, a bearing law
written in rpm). One name per direction, so a factor is never applied the wrong way round:

- :data:`RAD_S_PER_RPM` — multiply a speed in rpm by it to get rad/s (2π/60);
- :data:`RPM_PER_RAD_S` — multiply a speed in rad/s by it to get rpm (60/2π).

Examples
--------
>>> round(1500 * RAD_S_PER_RPM, 4), round(rpm(157.0796), 2)
(157.0796, 1500.0)
"""
from __future__ import annotations

import math

#: rad/s in one rpm (one revolution, 2π rad, per 60 s).
RAD_S_PER_RPM = 2.0 * math.pi / 60.0
#: rpm in one rad/s.
RPM_PER_RAD_S = 60.0 / (2.0 * math.pi)


def rpm(speed_rad_s):
    """A speed (rad/s, float or array) in rpm.

    >>> rpm(2 * math.pi)
    60.0
    """
    return speed_rad_s * RPM_PER_RAD_S


def rad_s(speed_rpm):
    """A speed in rpm (float or array) in rad/s.

    >>> round(rad_s(60.0), 6)
    6.283185
    """
    return speed_rpm * RAD_S_PER_RPM
