"""Geometry of a cycloid stage: pins, eccentricity, the pin-centre trochoid.

Csobán (2021) does not state its geometry. We use the one below (docs/cycloid.md),
which reproduces the paper's four fitted surfaces (see :mod:`.fit`):

- ``z1`` disc teeth, ``z2 = z1 + 1`` pins on the reference circle ``R_p = m·z2/2``;
- eccentricity ``e = (1 − x)·m/2`` (so the trochoid's shortening ratio ``e·z2/R_p = 1 − x``);
- pin radius ``r_p = rc*·m``;
- the disc profile is the inner equidistant, at ``r_p``, of the pin-centre trochoid

  ``T(t) = R_p·exp(i t) − e·exp(i z2 t)``   (disc frame, disc centre at 0);

- the faulty profile is moved a further ``d`` inward along its normal. Equidistants add, so a
  pin touches the faulty profile exactly when its centre lies on ``T`` moved ``d`` inward: the
  *contact locus* ``Γ_d(t) = T(t) − d·n(t)`` (``n`` the outward unit normal). The pin radius
  therefore does not change the motion; it only has to leave the profile free of undercut.

Lengths are in mm, angles in radians.
"""
from __future__ import annotations

import math
from dataclasses import asdict

import numpy as np

from powergraph.errors import UsageError
from powergraph.gears.cycloid import smallest_convex_radius as _smallest
from powergraph.gears.cycloid import trochoid as _trochoid
from powergraph.records import record

#: Samples of one tooth used to find the trochoid's largest curvature (undercut check).
_CURVATURE_SAMPLES = 2001
#: Largest tooth count accepted (work grows like z1; the paper stops at 117).
MAX_TEETH = 5000


@record
class CycloidGeometry:
    """A cycloid disc and its pin ring.

    Attributes
    ----------
    module : float
        Module ``m`` (mm).
    teeth : int
        Disc teeth ``z1``; the ratio of the stage (pins fixed, crank in, disc out) is ``z1``.
    shift : float
        Profile-shift (addendum modification) coefficient ``x``.
    rc : float
        Pin-radius ("generating circle radius") factor ``rc*``.
    """

    module: float
    teeth: int
    shift: float = 0.3
    rc: float = 1.0

    @property
    def pins(self) -> int:
        """Number of pins ``z2 = z1 + 1``."""
        return self.teeth + 1

    @property
    def pin_circle_radius(self) -> float:
        """Radius of the pin-centre circle ``R_p = m·z2/2`` (mm)."""
        return self.module * self.pins / 2.0

    @property
    def eccentricity(self) -> float:
        """Crank eccentricity ``e = (1 − x)·m/2`` (mm)."""
        return (1.0 - self.shift) * self.module / 2.0

    @property
    def pin_radius(self) -> float:
        """Pin radius ``r_p = rc*·m`` (mm)."""
        return self.rc * self.module

    def to_dict(self) -> dict:
        return {**asdict(self), "pins": self.pins, "pin_circle_radius": self.pin_circle_radius,
                "eccentricity": self.eccentricity, "pin_radius": self.pin_radius}


def cycloid_geometry(module: float, teeth: int, shift: float = 0.3, rc: float = 1.0,
                     profile_error: float = 0.0) -> CycloidGeometry:
    """Check the parameters of a cycloid stage and return its geometry.

    Parameters
    ----------
    module : float
        Module ``m`` > 0 (mm).
    teeth : int
        Disc teeth ``z1``, 3 ≤ z1 ≤ 5000.
    shift : float
        Profile-shift coefficient, 0 < x < 1 (x ≤ 0 gives a cusped or looped trochoid).
    rc : float
        Pin-radius factor ``rc*`` > 0.
    profile_error : float
        Profile error ``d`` ≥ 0 (mm), checked together with the pin radius for undercut.

    Raises
    ------
    UsageError
        For an impossible stage, saying which parameter is wrong.

    Examples
    --------
    >>> g = cycloid_geometry(1, 9)
    >>> g.pins, g.pin_circle_radius, g.eccentricity, g.pin_radius
    (10, 5.0, 0.35, 1.0)
    """
    for name, value in (("module", module), ("shift", shift), ("rc", rc),
                        ("profile error", profile_error)):
        if isinstance(value, bool) or not isinstance(value, (int, float)) \
                or not math.isfinite(value):
            raise UsageError(f"{name} must be a finite number, got {value!r}")
    if isinstance(teeth, bool) or not isinstance(teeth, (int, np.integer)) \
            or not 3 <= teeth <= MAX_TEETH:
        raise UsageError(f"teeth must be an integer from 3 to {MAX_TEETH}, got {teeth!r}")
    if module <= 0:
        raise UsageError(f"module must be > 0, got {module}")
    if not 0.0 < shift < 1.0:
        raise UsageError(f"shift must be in (0, 1) (the trochoid needs 0 < e·z2/R_p < 1), "
                         f"got {shift}")
    if rc <= 0:
        raise UsageError(f"rc must be > 0, got {rc}")
    if profile_error < 0:
        raise UsageError(f"profile error must be >= 0, got {profile_error}")
    geometry = CycloidGeometry(float(module), int(teeth), float(shift), float(rc))
    _check_pins_fit(geometry, float(profile_error))
    return geometry


def _check_pins_fit(geometry: CycloidGeometry, profile_error: float) -> None:
    """Pins must not overlap, and the profile (offset r_p + d) must not be undercut."""
    spacing = 2.0 * geometry.pin_circle_radius * math.sin(math.pi / geometry.pins)
    if 2.0 * geometry.pin_radius >= spacing:
        raise UsageError(f"pins of radius {geometry.pin_radius:g} mm overlap "
                         f"(pin spacing {spacing:g} mm): lower rc")
    offset = geometry.pin_radius + profile_error
    smallest = smallest_convex_radius(geometry)
    if offset >= smallest:
        raise UsageError(f"profile undercut: pin radius + profile error = {offset:g} mm is not "
                         f"below the trochoid's smallest radius of curvature {smallest:.4g} mm "
                         "(lower rc or the error, or raise the shift)")


def smallest_convex_radius(geometry: CycloidGeometry) -> float:
    """Smallest radius of curvature of the convex parts of the pin-centre trochoid (mm).

    An inner equidistant at a distance ≥ this value is undercut (swallow-tails). The
    formula is :func:`powergraph.gears.cycloid.smallest_convex_radius`.

    Examples
    --------
    >>> round(smallest_convex_radius(cycloid_geometry(1, 9)), 3)
    1.526
    """
    return _smallest(geometry.pin_circle_radius, geometry.eccentricity, geometry.teeth,
                     _CURVATURE_SAMPLES)


def trochoid(geometry: CycloidGeometry, t: np.ndarray):
    """The pin-centre trochoid ``T(t)`` and its first two derivatives (complex, disc frame).

    A pin ``k`` (at angle ``2πk/z2``) of the ideal drive sits at ``T(2πk/z2 + θ/z1)`` when the
    crank is at ``θ``. ``T`` runs counter-clockwise, so its outward normal is ``−i·T'/|T'|``.
    The formula is :func:`powergraph.gears.cycloid.trochoid`.

    Examples
    --------
    >>> T, _, _ = trochoid(cycloid_geometry(1, 9), np.array([0.0]))
    >>> float(T[0].real)          # R_p − e on the line of centres
    4.65
    """
    return _trochoid(geometry.pin_circle_radius, geometry.eccentricity, geometry.pins, t)


def contact_locus(geometry: CycloidGeometry, profile_error: float, t: np.ndarray):
    """Where a pin centre touches the faulty profile: ``Γ_d = T − d·n`` and ``Γ_d'``.

    ``Γ_d' = T'·(1 − d·κ)`` with ``κ`` the signed curvature of ``T``.

    Examples
    --------
    >>> G, _ = contact_locus(cycloid_geometry(1, 9), 0.1, np.array([0.0]))
    >>> round(float(G[0].real), 12)   # 0.1 further in on the line of centres
    4.55
    """
    value, d1, d2 = trochoid(geometry, t)
    speed = np.abs(d1)
    normal = -1j * d1 / speed
    curvature = np.imag(np.conj(d1) * d2) / speed ** 3
    return value - profile_error * normal, d1 * (1.0 - profile_error * curvature)
