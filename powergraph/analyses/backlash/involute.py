"""Involute geometry of Li et al. (2012), Eqs. (12)-(16): over-pin distance M, equivalent
profile shift, no-backlash working pressure angle and centre distance.

Sign convention of Eqs. (12)-(14) (the paper's): where ``±``/``∓`` appear the upper sign is
for the external gear, the lower for the internal gear. With it, an internal gear with a
*larger* M and an external gear with a *smaller* M than standard have thinner teeth, and
come out with x > 0 (internal) and x < 0 (external). Angles are in radians unless a name
ends in ``_deg``; lengths in mm.

Examples
--------
>>> import math
>>> alpha = math.radians(20)
>>> round(over_pin_distance(0.0, 45, 1.0, alpha, 1.732, internal=True), 3)   # paper: 42.434
42.434
>>> round(over_pin_distance(0.0, 40, 1.0, alpha, 1.732, internal=False), 3)  # paper: 42.436
42.436
"""
from __future__ import annotations

import math

from powergraph.errors import ModelError
from powergraph.gears.involute import involute, inverse_involute

#: Eq. (15) variants: "paper" as printed (no tan α), "standard" (with tan α).
VARIANTS = ("paper", "standard")


def _sign(internal: bool) -> float:
    """The upper sign (+1) for an external gear, the lower (−1) for an internal gear."""
    return -1.0 if internal else 1.0


def _odd_factor(teeth: int) -> float:
    """cos(90°/z) for an odd tooth count (Eq. 13), 1 for an even one (Eq. 12)."""
    return math.cos(math.pi / (2 * teeth)) if teeth % 2 else 1.0


def pin_pressure_angle(m_value: float, teeth: int, module: float, alpha: float,
                       pin_diameter: float, internal: bool) -> float:
    """Pressure angle α_M at the pin centres from an over-pin distance, Eqs. (12)-(13).

    ``M = m z cos α / cos α_M · [cos(90°/z) if z odd] ± d_p`` solved for α_M.

    >>> round(math.degrees(pin_pressure_angle(42.434, 45, 1.0, math.radians(20), 1.732,
    ...                                       internal=True)), 4)
    16.8921
    """
    across = (m_value - _sign(internal) * pin_diameter) / _odd_factor(teeth)
    cosine = module * teeth * math.cos(alpha) / across
    if not 0.0 < cosine < 1.0:
        raise ModelError(f"M = {m_value:g} mm puts the pins inside the base circle "
                         f"(z = {teeth}, module {module:g})")
    return math.acos(cosine)


def shift_coefficient(m_value: float, teeth: int, module: float, alpha: float,
                      pin_diameter: float, internal: bool) -> float:
    """Profile-shift coefficient x of a gear with over-pin distance M, Eqs. (12)-(14).

    ``inv α_M = inv α ± d_p/(m z cos α) ∓ π/(2z) + 2 x tan α / z`` solved for x.

    >>> round(shift_coefficient(42.434, 45, 1.0, math.radians(20), 1.732, True), 4)
    -0.0001
    """
    s = _sign(internal)
    alpha_m = pin_pressure_angle(m_value, teeth, module, alpha, pin_diameter, internal)
    rest = involute(alpha_m) - involute(alpha) - s * pin_diameter / (
        module * teeth * math.cos(alpha)) + s * math.pi / (2 * teeth)
    return rest * teeth / (2.0 * math.tan(alpha))


def over_pin_distance(x: float, teeth: int, module: float, alpha: float,
                      pin_diameter: float, internal: bool) -> float:
    """Over-pin distance M of a gear with shift coefficient x (Eqs. 14 then 12-13).

    The inverse of :func:`shift_coefficient`.

    >>> round(over_pin_distance(0.0, 40, 1.0, math.radians(20), 1.732, False), 4)
    42.4361
    """
    s = _sign(internal)
    target = involute(alpha) + s * pin_diameter / (module * teeth * math.cos(alpha)) \
        - s * math.pi / (2 * teeth) + 2.0 * x * math.tan(alpha) / teeth
    alpha_m = inverse_involute(target)
    return module * teeth * math.cos(alpha) / math.cos(alpha_m) * _odd_factor(teeth) \
        + s * pin_diameter


def working_pressure_angle(x_internal: float, x_external: float, z_internal: int,
                           z_external: int, alpha: float, variant: str = "standard") -> float:
    """No-backlash working pressure angle α′ of an internal pair, Eq. (15).

    ``variant="paper"``: ``inv α′ = inv α + 2(x1 − x2)/(z1 − z2)`` as printed;
    ``variant="standard"``: ``inv α′ = inv α + 2 tan α (x1 − x2)/(z1 − z2)``.
    Index 1 is the internal gear, 2 the external gear.

    >>> round(math.degrees(working_pressure_angle(0, 0, 45, 40, math.radians(20))), 9)
    20.0
    """
    if variant not in VARIANTS:
        raise ValueError(f"variant must be one of {VARIANTS}, got {variant!r}")
    factor = 1.0 if variant == "paper" else math.tan(alpha)
    value = involute(alpha) + 2.0 * factor * (x_internal - x_external) / (z_internal - z_external)
    if value <= 0:
        raise ModelError("the gears' teeth are so thick that no working pressure angle gives "
                         "a backlash-free mesh (inv α′ <= 0 in Eq. 15)")
    return inverse_involute(value)


def standard_centre_distance(module: float, z_internal: int, z_external: int) -> float:
    """a = m (z1 − z2)/2 of an internal pair.

    >>> standard_centre_distance(1.0, 45, 40)
    2.5
    """
    return module * (z_internal - z_external) / 2.0


def no_backlash_centre_distance(centre_distance: float, alpha: float,
                                working_angle: float) -> float:
    """a′ = a cos α / cos α′, Eq. (16).

    >>> no_backlash_centre_distance(2.5, 0.3, 0.3)
    2.5
    """
    return centre_distance * math.cos(alpha) / math.cos(working_angle)
