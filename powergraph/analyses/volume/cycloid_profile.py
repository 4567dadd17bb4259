"""Exact outline of a cycloid disc (one tooth fewer than pins), and its area.

In the disc's frame the centre of a pin traces the epitrochoid
``P(φ) = r_p e^{iφ} − a e^{i z_p φ}`` (z_p pins on radius r_p, crank eccentricity a); the disc
profile is that curve offset inwards by the pin radius r_rp. The offset is loop-free while
r_rp is smaller than the smallest radius of curvature of the convex parts of P, and the
short-width coefficient K1 = a z_p / r_p is below 1 (otherwise the disc is undercut, and this
module raises). The paper's Eq. (3) replaces this outline by the "average circle" of radius
r_p − r_rp.

Examples
--------
>>> area = cycloid_disc_area(64.0, 3.0, 1.3, 40)
>>> bool(math.pi * 59.7 ** 2 < area < math.pi * 62.3 ** 2)   # between root and tip circles
True
"""
from __future__ import annotations

import math

import numpy as np

from powergraph.analyses.volume.polygon import shoelace_area


def _epitrochoid(pin_circle_radius: float, eccentricity: float, pins: int,
                 phi: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Pin-centre curve P and its first two derivatives (complex numbers)."""
    rp, a, z = pin_circle_radius, eccentricity, pins
    main, lobe = np.exp(1j * phi), np.exp(1j * z * phi)
    return (rp * main - a * lobe, 1j * rp * main - 1j * a * z * lobe,
            -rp * main + a * z ** 2 * lobe)


def min_convex_curvature_radius(pin_circle_radius: float, eccentricity: float, pins: int,
                                points_per_lobe: int = 1000) -> float:
    """Smallest radius of curvature of the pin-centre curve where it is convex (mm)."""
    phi = np.linspace(0.0, 2 * math.pi, points_per_lobe * (pins - 1), endpoint=False)
    _, d1, d2 = _epitrochoid(pin_circle_radius, eccentricity, pins, phi)
    curvature = np.imag(np.conj(d1) * d2) / np.abs(d1) ** 3
    return float(1.0 / curvature.max())


def cycloid_disc_outline(pin_circle_radius: float, pin_radius: float, eccentricity: float,
                         pins: int, points_per_lobe: int = 1000
                         ) -> tuple[np.ndarray, np.ndarray]:
    """Vertices (x, y) in mm of the disc outline (z_p − 1 lobes), one closed polygon.

    Parameters
    ----------
    pin_circle_radius, pin_radius, eccentricity : float
        r_p, r_rp, a in mm.
    pins : int
        z_p, the number of pins (the disc has z_p − 1 teeth).
    points_per_lobe : int
        Polygon resolution.

    Raises
    ------
    ValueError
        K1 = a z_p / r_p ≥ 1, or the pins are too big for the curve (undercut profile).
    """
    k1 = eccentricity * pins / pin_circle_radius
    if k1 >= 1:
        raise ValueError(f"short-width coefficient K1 = a·z_p/r_p = {k1:.3f} must be < 1")
    rho = min_convex_curvature_radius(pin_circle_radius, eccentricity, pins, points_per_lobe)
    if pin_radius >= rho:
        raise ValueError(f"undercut cycloid profile: pin radius {pin_radius:g} mm is not "
                         f"below the smallest radius of curvature {rho:.4g} mm")
    phi = np.linspace(0.0, 2 * math.pi, points_per_lobe * (pins - 1), endpoint=False)
    p, d1, _ = _epitrochoid(pin_circle_radius, eccentricity, pins, phi)
    q = p + 1j * pin_radius * d1 / np.abs(d1)      # inward normal of a counter-clockwise curve
    return q.real, q.imag


def cycloid_disc_area(pin_circle_radius: float, pin_radius: float, eccentricity: float,
                      pins: int, points_per_lobe: int = 1000) -> float:
    """Shoelace area (mm²) of :func:`cycloid_disc_outline` (no holes)."""
    x, y = cycloid_disc_outline(pin_circle_radius, pin_radius, eccentricity, pins,
                                points_per_lobe)
    return shoelace_area(x, y)
