"""Geometry and contact forces of a cycloid disc in its pin ring: the one copy of that physics.

Both the ratio-fluctuation analysis (:mod:`powergraph.analyses.cycloid`) and the mesh-loss
model (:mod:`powergraph.gears.cycloid_loss`) use these functions. Base layer: numpy only.

Conventions (lengths in mm, angles in rad). ``z_c`` lobes on the disc, ``z_p = z_c + 1``
pins of radius ``r_p`` with centres on the circle ``R_p``; eccentricity ``e``. In the
crank's frame the ring centre ``O_r`` is at 0, the disc centre ``O_d`` at ``e`` (on the
x axis) and the pitch point ``I`` — the instant centre of the disc's motion relative to the
ring — at ``z_p·e``. Pin ``k`` sits at the phase ``u_k = θ − 2πk/z_p`` from the line of
centres, ``P_k = R_p·exp(i u_k)``. The contact normal of every pin passes through ``I``, so
the force of pin ``k`` on the disc points from ``P_k`` to ``I``, its moment arm about the
disc centre is

``λ_k = −z_c·e·R_p·sin u_k / D_k``,   ``D_k = |I − P_k| = sqrt(R_p² + (z_p e)² − 2 R_p z_p e cos u_k)``

(positive on the flank that drives the disc forward), and the contact point lies at
``D_k − r_p`` from ``I``.

**Equal-load model** (Blagojevic et al. 2011; Gorla et al. 2008): a rigid disc without
clearances touches every pin of its driving half (``λ_k > 0``), and the pins' deflections,
hence their forces, are proportional to their lever arms, ``F_k = T·λ_k / Σ λ_j²`` for a
torque ``T`` on the disc.

Examples
--------
>>> round(float(lever_arm(39, 64.0, 1.3, -math.pi / 2)), 4)   # 39·64·1.3/sqrt(64² + 52²)
39.349
"""
from __future__ import annotations

import math

import numpy as np


def trochoid(circle_radius: float, eccentricity: float, pins: int, t):
    """The pin-centre trochoid ``T(t) = R_p e^{it} − e·e^{i z_p t}`` and its first two
    derivatives (complex, disc frame, disc centre at 0).

    The disc profile is its inner equidistant at the pin radius. ``T`` runs
    counter-clockwise, so its outward normal is ``−i·T'/|T'|``.

    >>> T, _, _ = trochoid(5.0, 0.35, 10, np.array([0.0]))
    >>> float(T[0].real)          # R_p − e on the line of centres
    4.65
    """
    ring = circle_radius * np.exp(1j * np.asarray(t))
    crank = eccentricity * np.exp(1j * pins * np.asarray(t))
    return ring - crank, 1j * (ring - pins * crank), -(ring - pins * pins * crank)


def smallest_convex_radius(circle_radius: float, eccentricity: float, lobes: int,
                           samples: int = 2001) -> float:
    """Smallest radius of curvature (mm) of the convex parts of the pin-centre trochoid.

    An inner equidistant (a disc profile for pins of radius ``r_p``) at a distance at least
    this value is undercut (swallow-tails).

    >>> round(smallest_convex_radius(5.0, 0.35, 9), 3)
    1.526
    """
    t = np.linspace(0.0, 2.0 * np.pi / lobes, samples)
    _, d1, d2 = trochoid(circle_radius, eccentricity, lobes + 1, t)
    curvature = np.imag(np.conj(d1) * d2) / np.abs(d1) ** 3
    return float(1.0 / curvature.max())


def pitch_distance(lobes: int, circle_radius: float, eccentricity: float, phase):
    """``D = |I − P|`` (mm): from the pitch point to the centre of a pin at ``phase``.

    >>> float(pitch_distance(39, 64.0, 1.3, 0.0))     # R_p − z_p·e on the line of centres
    12.0
    """
    z_p_e = (lobes + 1) * eccentricity
    return np.sqrt(circle_radius ** 2 + z_p_e ** 2
                   - 2.0 * circle_radius * z_p_e * np.cos(phase))


def lever_arm(lobes: int, circle_radius: float, eccentricity: float, phase):
    """Moment arm (mm) about the disc centre of the contact normal of a pin at ``phase``.

    ``−z_c·e·R_p·sin u / D(u)``: positive on the driving flank (``sin u < 0``).

    >>> abs(float(lever_arm(9, 5.0, 0.35, 0.0))) < 1e-15   # pin on the line of centres
    True
    """
    return -lobes * circle_radius * eccentricity * np.sin(phase) \
        / pitch_distance(lobes, circle_radius, eccentricity, phase)


def pin_phases(lobes: int, theta) -> np.ndarray:
    """Phases ``u_k = θ − 2πk/z_p`` of all pins at crank angles ``theta`` (shape (…, z_p)).

    >>> pin_phases(3, 0.0).round(4).tolist()
    [0.0, -1.5708, -3.1416, -4.7124]
    """
    pins = lobes + 1
    return np.asarray(theta, float)[..., None] - 2.0 * np.pi * np.arange(pins) / pins


def pin_forces(lobes: int, circle_radius: float, eccentricity: float, theta):
    """Equal-load pin forces per unit disc torque, and their resultant on the disc.

    Parameters
    ----------
    lobes : int
        ``z_c``.
    circle_radius, eccentricity : float
        ``R_p`` and ``e`` (mm).
    theta : array_like
        Crank angles (rad).

    Returns
    -------
    forces : ndarray, shape (…, z_p)
        ``F_k / T = λ_k⁺ / Σ λ_j⁺²`` (1/mm: N per N·mm), zero on the unloaded flank.
    resultant : ndarray of complex, shape (…)
        ``Σ F_k n_k / T`` with ``n_k`` the unit vector from pin ``k`` to the pitch point
        (x along the line of centres, from the ring centre to the disc centre).

    Examples
    --------
    >>> f, _ = pin_forces(39, 64.0, 1.3, 0.1)
    >>> arms = lever_arm(39, 64.0, 1.3, pin_phases(39, 0.1))
    >>> round(float((f * arms).sum()), 12)            # they carry the unit torque
    1.0
    """
    phase = pin_phases(lobes, theta)
    arms = np.maximum(lever_arm(lobes, circle_radius, eccentricity, phase), 0.0)
    forces = arms / (arms ** 2).sum(axis=-1, keepdims=True)
    pins = circle_radius * np.exp(1j * phase)
    to_pitch = (lobes + 1) * eccentricity - pins
    return forces, (forces * to_pitch / np.abs(to_pitch)).sum(axis=-1)


def stage_problem(lobes: int, circle_radius: float, pin_radius: float,
                  eccentricity: float) -> str | None:
    """Why a cycloid stage cannot exist, or None: the checks of a pin ring and its disc.

    >>> stage_problem(39, 64.0, 3.0, 1.3) is None
    True
    >>> stage_problem(39, 64.0, 3.0, 1.7)
    'the trochoid is looped: z_p·e = 68 mm must be below the pin circle radius 64 mm'
    """
    if isinstance(lobes, bool) or not isinstance(lobes, (int, np.integer)) or lobes < 3:
        return f"the disc needs an integer number of lobes >= 3, got {lobes!r}"
    for name, value in (("pin circle radius", circle_radius), ("pin radius", pin_radius),
                        ("eccentricity", eccentricity)):
        if not (math.isfinite(value) and value > 0):
            return f"the {name} must be a finite number > 0, got {value!r}"
    if (lobes + 1) * eccentricity >= circle_radius:
        return (f"the trochoid is looped: z_p·e = {(lobes + 1) * eccentricity:g} mm must be "
                f"below the pin circle radius {circle_radius:g} mm")
    spacing = 2.0 * circle_radius * math.sin(math.pi / (lobes + 1))
    if 2.0 * pin_radius >= spacing:
        return f"pins of radius {pin_radius:g} mm overlap (pin spacing {spacing:.4g} mm)"
    smallest = smallest_convex_radius(circle_radius, eccentricity, lobes)
    if pin_radius >= smallest:
        return (f"the disc profile is undercut: the pin radius {pin_radius:g} mm is not below "
                f"the trochoid's smallest radius of curvature {smallest:.4g} mm")
    return None
