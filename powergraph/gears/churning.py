"""Churning torque of a gear dipping in an oil bath: Changenet & Velex (2007).

A gear partly immersed in its sump drags the oil with it. Changenet and Velex fitted the
measured churning torque of single spur and helical gears with a drag law

    C_ch = ½·ρ·ω²·S_m·R_p³·C_m

where ``ρ`` is the oil density, ``ω`` the gear's speed, ``R_p`` its pitch radius, ``S_m``
the immersed (wetted) surface and ``C_m`` a dimensionless churning torque that depends on
the flow regime, told apart by the critical Reynolds number ``Re_c = ω·R_p·h/ν``
(``h`` the immersion depth, ``ν`` the kinematic viscosity):

- ``Re_c < 6000`` (low speed): ``C_m = 1.366·(h/D_p)^0.45·(V_0/D_p³)^0.1·Fr^−0.6·Re^−0.21``;
- ``Re_c > 9000`` (high speed): ``C_m = 3.644·(h/D_p)^0.1·(V_0/D_p³)^−0.35·Fr^−0.88·(b/D_p)^0.85``;

with ``D_p = 2R_p``, ``b`` the face width, ``V_0`` the oil volume of the sump,
``Fr = ω²·R_p/g`` and ``Re = ω·R_p·b/ν``. The paper gives no formula between 6000 and 9000:
this module interpolates linearly in ``Re_c`` between the two (``transition="interpolate"``,
an assumption of this project) or returns NaN there (``transition="nan"``).

The immersed surface (``θ`` the half immersion angle, ``cos θ = 1 − h/R_p``): the two
side faces below the oil level (circular segments, ``R_p²·(2θ − sin 2θ)`` together), the
periphery (``2θ·R_p·b``) and the flanks of the ``z·θ/π`` immersed teeth, each two flanks
of ``h_t/cos α`` by ``b``:

    S_m = R_p²·(2θ − sin 2θ) + 2·R_p·b·θ + 2·z·θ·h_t·b/(π·cos α).

Without teeth (``teeth=0``) ``S_m`` is that of a smooth disc of radius ``R_p``.

Units: SI throughout (m, m³, rad/s — magnitude —, m²/s, kg/m³); the torque in N·m, its
magnitude (it opposes the rotation), and the power in W.

Not modelled: flanges, deflectors and housing walls near the gear (Changenet & Velex 2008),
the later refinements of the flow regimes (Changenet, Leprince, Ville & Velex 2011, whose
text this project could not retrieve), windage in air, the pocketing of oil in the mesh,
ISO/TR 14179-2's no-load gear losses. docs/losses.md discusses the range of validity.

Examples
--------
>>> c = churning_torque(pitch_radius=0.1, face_width=0.02, immersion=0.05, oil_volume=2e-3,
...                     speed=300.0, viscosity=2e-5, density=870.0)
>>> c.regime, round(c.torque, 4), round(c.power, 1)
('high', 1.1598, 347.9)

References
----------
C. Changenet, P. Velex, "A model for the prediction of churning losses in geared
transmissions — preliminary results", *J. Mech. Des.* 129(1) (2007) 128–133.
C. Changenet, P. Velex, "Housing influence on churning losses in geared transmissions",
*J. Mech. Des.* 130 (2008), doi:10.1115/1.2900714.
C. Changenet, G. Leprince, F. Ville, P. Velex, "A note on flow regimes and churning loss
modeling", *J. Mech. Des.* 133 (2011) 121009 (not retrieved).
"""
from __future__ import annotations

import math

import numpy as np

from powergraph.errors import ModelError
from powergraph.records import record

__all__ = ["Churning", "immersed_surface", "churning_coefficient", "churning_torque",
           "RE_C_LOW", "RE_C_HIGH", "GRAVITY"]

#: Critical Reynolds numbers bounding the low-speed and the high-speed fits.
RE_C_LOW = 6000.0
RE_C_HIGH = 9000.0
#: Standard gravity, m/s² (the Froude number's g).
GRAVITY = 9.80665


@record(eq=False)
class Churning:
    """Churning of one gear (floats, or arrays of the broadcast shape of the inputs).

    ``torque`` N·m (magnitude, opposing the rotation), ``power`` W, ``coefficient`` ``C_m``,
    ``surface`` ``S_m`` m², the dimensionless ``reynolds`` (``ω·R_p·b/ν``),
    ``critical_reynolds`` (``ω·R_p·h/ν``) and ``froude`` (``ω²·R_p/g``), and ``regime``:
    ``"low"``, ``"transition"`` or ``"high"``.
    """

    torque: float | np.ndarray
    power: float | np.ndarray
    coefficient: float | np.ndarray
    surface: float | np.ndarray
    reynolds: float | np.ndarray
    critical_reynolds: float | np.ndarray
    froude: float | np.ndarray
    regime: str | np.ndarray


def _positive(**values) -> None:
    for name, value in values.items():
        v = np.asarray(value, float)
        if not (np.all(np.isfinite(v)) and np.all(v > 0.0)):
            raise ModelError(f"{name} must be finite and > 0, got {value!r}")


def _out(x):
    return x.item() if np.ndim(x) == 0 else x


def immersed_surface(pitch_radius, face_width, immersion, teeth: int = 0,
                     tooth_height: float = 0.0, pressure_angle_deg: float = 20.0):
    """Wetted surface ``S_m`` (m²) of a gear dipping ``immersion`` (m) into the oil.

    ``θ = arccos(1 − h/R_p)`` (``h`` is clipped to ``[0, 2R_p]``: a gear deeper than its
    diameter is wetted all round); see the module docstring for the three terms.

    Examples
    --------
    >>> round(immersed_surface(0.1, 0.02, 0.05), 5)             # θ = 60°, no teeth
    0.01647
    >>> round(immersed_surface(0.1, 0.0, 0.2) / (2 * math.pi * 0.01), 12)   # two full faces
    1.0
    """
    _positive(pitch_radius=pitch_radius)
    if not (np.all(np.asarray(face_width) >= 0.0) and np.all(np.asarray(immersion) >= 0.0)
            and teeth >= 0 and tooth_height >= 0.0 and 0.0 <= pressure_angle_deg < 90.0):
        raise ModelError("face width, immersion, teeth and tooth height must be >= 0 and the "
                         "pressure angle in [0, 90) degrees")
    r = np.asarray(pitch_radius, float)
    h = np.clip(np.asarray(immersion, float), 0.0, 2.0 * r)
    theta = np.arccos(1.0 - h / r)
    b = np.asarray(face_width, float)
    teeth_term = 2.0 * teeth * theta * tooth_height * b / (math.pi * math.cos(math.radians(
        pressure_angle_deg)))
    return _out(r ** 2 * (2.0 * theta - np.sin(2.0 * theta)) + 2.0 * r * b * theta + teeth_term)


def _coefficients(r, b, h, v0, omega, nu, transition):
    """``C_m``, ``Re``, ``Re_c``, ``Fr`` and the regime (arrays, ``ω > 0``)."""
    d_p = 2.0 * r
    fr = omega ** 2 * r / GRAVITY
    re = omega * r * b / nu
    re_c = omega * r * h / nu
    low = 1.366 * (h / d_p) ** 0.45 * (v0 / d_p ** 3) ** 0.1 * fr ** -0.6 * re ** -0.21
    high = 3.644 * (h / d_p) ** 0.1 * (v0 / d_p ** 3) ** -0.35 * fr ** -0.88 * (b / d_p) ** 0.85
    if transition == "interpolate":
        w = np.clip((re_c - RE_C_LOW) / (RE_C_HIGH - RE_C_LOW), 0.0, 1.0)
        c_m = (1.0 - w) * low + w * high
    else:
        c_m = np.where(re_c <= RE_C_LOW, low, np.where(re_c >= RE_C_HIGH, high, np.nan))
    regime = np.where(re_c <= RE_C_LOW, "low", np.where(re_c >= RE_C_HIGH, "high", "transition"))
    return c_m, re, re_c, fr, regime


def churning_coefficient(pitch_radius, face_width, immersion, oil_volume, speed, viscosity,
                         transition: str = "interpolate"):
    """Dimensionless churning torque ``C_m`` (Changenet & Velex 2007) and its regime.

    Parameters as :func:`churning_torque`; the speed must be > 0 (``C_m`` diverges at rest,
    where the torque itself tends to 0).

    Examples
    --------
    >>> c_m, regime = churning_coefficient(0.1, 0.02, 0.05, 2e-3, speed=10.0, viscosity=1e-4)
    >>> round(c_m, 5), regime
    (0.20702, 'low')
    """
    if transition not in ("interpolate", "nan"):
        raise ModelError(f"transition must be 'interpolate' or 'nan', got {transition!r}")
    _positive(pitch_radius=pitch_radius, face_width=face_width, immersion=immersion,
              oil_volume=oil_volume, speed=np.abs(speed), viscosity=viscosity)
    c_m, _, _, _, regime = _coefficients(*(np.asarray(x, float) for x in (
        pitch_radius, face_width, immersion, oil_volume, np.abs(speed), viscosity)), transition)
    return _out(c_m), _out(regime)


def churning_torque(pitch_radius, face_width, immersion, oil_volume, speed, viscosity,
                    density, *, teeth: int = 0, tooth_height: float = 0.0,
                    pressure_angle_deg: float = 20.0,
                    transition: str = "interpolate") -> Churning:
    """Churning torque of a gear by Changenet & Velex (2007), N·m.

    Parameters
    ----------
    pitch_radius : float or array
        ``R_p``, m.
    face_width : float or array
        ``b``, m.
    immersion : float or array
        ``h``, the depth of the gear's pitch circle below the oil level, m (> 0).
    oil_volume : float or array
        ``V_0``, the sump's oil volume, m³.
    speed : float or array
        ``ω``, rad/s (magnitude; at rest the torque is 0).
    viscosity : float or array
        ``ν``, kinematic viscosity at the oil's temperature, m²/s.
    density : float or array
        ``ρ``, kg/m³.
    teeth, tooth_height, pressure_angle_deg
        ``z``, ``h_t`` (m, e.g. 2.25 × module) and ``α`` of the flank term of ``S_m``;
        the default (no teeth) counts the faces and the periphery only.
    transition : str
        ``"interpolate"`` (default) or ``"nan"`` for ``6000 < Re_c < 9000``.

    Examples
    --------
    >>> c = churning_torque(0.1, 0.02, 0.05, 2e-3, speed=np.array([0.0, 10.0, 300.0]),
    ...                     viscosity=np.array([1e-4, 1e-4, 2e-5]), density=870.0)
    >>> c.regime.tolist(), c.torque.round(4).tolist()
    (['low', 'low', 'high'], [0.0, 0.1483, 1.1598])
    """
    if transition not in ("interpolate", "nan"):
        raise ModelError(f"transition must be 'interpolate' or 'nan', got {transition!r}")
    _positive(pitch_radius=pitch_radius, face_width=face_width, immersion=immersion,
              oil_volume=oil_volume, viscosity=viscosity, density=density)
    r, b, h, v0, omega, nu, rho = np.broadcast_arrays(*(np.asarray(x, float) for x in (
        pitch_radius, face_width, immersion, oil_volume, np.abs(speed), viscosity, density)))
    if not np.all(np.isfinite(omega)):
        raise ModelError(f"speed must be finite, got {speed!r}")
    moving = omega > 0.0
    safe = np.where(moving, omega, 1.0)
    c_m, re, re_c, fr, regime = _coefficients(r, b, h, v0, safe, nu, transition)
    s_m = np.asarray(immersed_surface(r, b, h, teeth, tooth_height, pressure_angle_deg))
    torque = np.where(moving, 0.5 * rho * omega ** 2 * s_m * r ** 3 * c_m, 0.0)
    zero = np.zeros_like(omega)
    return Churning(_out(torque), _out(torque * omega), _out(np.where(moving, c_m, np.inf)),
                    _out(s_m * np.ones_like(omega)), _out(np.where(moving, re, zero)),
                    _out(np.where(moving, re_c, zero)), _out(np.where(moving, fr, zero)),
                    _out(np.where(moving, regime, "low")))
