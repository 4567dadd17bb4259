"""Contact of the faulty disc with the pins, vectorised over crank angles (Csobán 2021, §3).

Frames and signs. The pins are fixed, pin ``k`` at ``P_k = R_p·exp(2πik/z2)``. The crank
(input) turns by ``θ``; the disc centre is at ``C = e·exp(iθ)`` and the disc (output) turns
by ``ψ``. In the ideal drive ``ψ = −θ/z1``; with a profile error the disc turns by
``ψ = −θ/z1 + δ(θ)``. The stage is driven (crank drives, the output resists), so the disc
lags until it meets a pin: pin ``k`` would stop it at ``δ_k(θ) > 0`` and the pin that stops
it first, ``δ = min_k δ_k``, is the pin in contact. Reversing the load mirrors the curves
(same maximum).

Pin ``k`` touches when ``P_k − C = exp(iψ)·Γ_d(t)`` (paper Eq. 4). Taking moduli,
``|Γ_d(t)| = |P_k − C|``; on one flank of a tooth ``|Γ_d|`` is monotonic, so ``t`` has a
unique bracketed root (solved elementwise by scipy), and then
``ψ = arg(P_k − C) − arg Γ_d(t)``. Differentiating both relations with respect to ``θ``
gives the exact instantaneous ratio ``i = −dθ/dψ`` on each contact segment.
"""
from __future__ import annotations

import numpy as np
from scipy.optimize.elementwise import find_root

from powergraph.analyses.cycloid.geometry import CycloidGeometry, contact_locus
from powergraph.errors import SolveError, UsageError
from powergraph.gears.cycloid import lever_arm as gear_lever_arm

#: Pins (largest ideal lever arm first) solved exactly at each crank angle. The pin that
#: stops the disc first has δ_k ≈ d/λ_k, i.e. one of the largest lever arms λ_k.
CANDIDATES = 4
#: Hand-overs are located to this crank angle (rad); the one-sided ratios there then agree
#: with their limits to far better than 1e-9.
HANDOVER_XATOL = 1e-12


def lever_arm(geometry: CycloidGeometry, theta, pins) -> np.ndarray:
    """Moment arm (mm) about the disc centre of pin ``k``'s contact normal, ideal drive.

    Positive on the driving flank. To first order in ``d`` the disc turns by ``d/λ_k``
    before pin ``k`` stops it. With ``u = z1·t`` at the pin's trochoid parameter ``t``,
    ``−Im(conj(n)·T) = −z1·R_p·e·sin u / |R_p − z2·e·exp(iu)|`` (closed form:
    :func:`powergraph.gears.cycloid.lever_arm`).

    Examples
    --------
    >>> from powergraph.analyses.cycloid.geometry import cycloid_geometry
    >>> g = cycloid_geometry(1, 9)
    >>> abs(float(lever_arm(g, 0.0, 0))) < 1e-15   # pin on the line of centres: no arm
    True
    """
    u = geometry.teeth * _ideal_parameter(geometry, theta, pins)
    return gear_lever_arm(geometry.teeth, geometry.pin_circle_radius, geometry.eccentricity, u)


def pin_contact(geometry: CycloidGeometry, profile_error: float, theta, pins):
    """Disc rotation ``δ_k`` (rad) at which pin ``k`` stops the disc, and ``dψ/dθ`` there.

    Parameters
    ----------
    geometry : CycloidGeometry
    profile_error : float
        ``d`` (mm).
    theta, pins : array_like
        Crank angles (rad) and pin indices, broadcast together.

    Returns
    -------
    delta, rate : ndarray
        ``δ_k`` and ``dψ/dθ`` (the instantaneous ratio is ``−1/rate``); NaN where pin ``k``
        cannot touch on the driving flank.

    Examples
    --------
    >>> from powergraph.analyses.cycloid.geometry import cycloid_geometry
    >>> delta, rate = pin_contact(cycloid_geometry(1, 9), 0.0, 0.3, 1)
    >>> abs(float(delta)) < 1e-12, round(-1 / float(rate), 9)
    (True, 9.0)
    """
    z1 = geometry.teeth
    theta, pins = np.broadcast_arrays(np.asarray(theta, float), np.asarray(pins))
    gap = geometry.pin_circle_radius * np.exp(2j * np.pi * pins / geometry.pins) \
        - geometry.eccentricity * np.exp(1j * theta)
    distance = np.abs(gap)
    # The driving flank of the tooth the pin ideally touches at t0: |T| falls from the tip
    # (z1·t = (2j − 1)π) to the root (z1·t = 2jπ). A pin whose ideal contact lies on the
    # other flank cannot stop the lagging disc (NaN).
    t0 = _ideal_parameter(geometry, theta, pins)
    upper = 2.0 * np.pi * np.ceil(z1 * t0 / (2.0 * np.pi)) / z1
    lower = upper - np.pi / z1

    def radius_gap(t, target):
        return np.abs(contact_locus(geometry, profile_error, t)[0]) - target

    with np.errstate(invalid="ignore", divide="ignore"):
        root = find_root(radius_gap, (lower, upper), args=(distance,))
        t = np.where(root.success & (t0 >= lower), root.x, np.nan)
        locus, slope = contact_locus(geometry, profile_error, t)
        psi = np.angle(gap) - np.angle(locus)
        delta = np.angle(np.exp(1j * z1 * (psi + theta / z1))) / z1
        # With ρ·exp(iα) = P_k − C and g·exp(ih) = Γ_d(t): ρ(θ) = g(t) and ψ = α − h, so
        # dψ/dθ = α' − h'(t)·ρ'/g'(t), where g'/g + i·h' = Γ_d'/Γ_d.
        crank_velocity = -1j * geometry.eccentricity * np.exp(1j * theta)
        along = crank_velocity * np.conj(gap) / distance
        q = slope / locus
        rate = along.imag / distance - q.imag * along.real / (np.abs(locus) * q.real)
    return delta, rate


def contact_curve(geometry: CycloidGeometry, profile_error: float, theta,
                  candidates: int | None = CANDIDATES):
    """The pin in contact at each crank angle, its ``δ`` and ``dψ/dθ``.

    Parameters
    ----------
    candidates : int or None
        How many pins (largest lever arm first) to solve exactly; ``None`` solves every pin.
        With ``d = 0`` all pins of the driving flank touch, and the one with the largest
        lever arm is reported.

    Returns
    -------
    pin : ndarray of int
    delta, rate : ndarray

    Raises
    ------
    UsageError
        When at some angle no pin can touch (a profile error far too large).

    Examples
    --------
    >>> from powergraph.analyses.cycloid.geometry import cycloid_geometry
    >>> pin, delta, rate = contact_curve(cycloid_geometry(1, 9), 0.1, [0.0, 0.5])
    >>> pin.tolist()
    [1, 2]
    """
    theta = np.atleast_1d(np.asarray(theta, float))
    chosen = _largest_lever_arms(geometry, theta, candidates)
    delta, rate = pin_contact(geometry, profile_error, theta[:, None], chosen)
    delta = np.where(np.isfinite(delta) & np.isfinite(rate), delta, np.inf)
    first = delta.min(axis=1)
    if not np.all(np.isfinite(first)):
        raise UsageError(f"profile error {profile_error:g} mm is too large for this stage: "
                         "at some crank angles no pin touches the disc")
    # With d = 0 every pin of the driving flank touches; report the largest lever arm.
    pick = np.argmin(delta, axis=1) if profile_error > 0 else np.zeros(theta.size, int)
    rows = np.arange(theta.size)
    return chosen[rows, pick], delta[rows, pick], rate[rows, pick]


def handovers(geometry: CycloidGeometry, profile_error: float, theta: np.ndarray,
              pin: np.ndarray):
    """Crank angles where the contact passes from one pin to the next, located exactly.

    ``theta`` is a sampled revolution ``[θ0, θ0 + 2π)`` and ``pin`` the pin in contact there
    (:func:`contact_curve`). Each change of pin between two samples is refined to the root of
    ``δ_a(θ) = δ_b(θ)``.

    Returns
    -------
    angle : ndarray
        Hand-over crank angles (rad).
    before, after : ndarray
        ``dψ/dθ`` of the outgoing and of the incoming pin at the hand-over.
    """
    change = np.nonzero(pin != np.roll(pin, -1))[0]
    if change.size == 0:
        empty = np.empty(0)
        return empty, empty, empty
    step = np.diff(theta, append=theta[0] + 2.0 * np.pi)
    left, right = theta[change], theta[change] + step[change]
    outgoing, incoming = pin[change], pin[(change + 1) % pin.size]

    def difference(angle, a, b):
        return (pin_contact(geometry, profile_error, angle, a)[0]
                - pin_contact(geometry, profile_error, angle, b)[0])

    root = find_root(difference, (left, right), args=(outgoing, incoming),
                     tolerances={"xatol": HANDOVER_XATOL, "xrtol": 0.0})
    if not np.all(root.success):
        raise SolveError("a pin hand-over could not be located (pins skipped between two "
                         "samples); use more points per segment")
    angle = root.x % (2.0 * np.pi)
    _, before = pin_contact(geometry, profile_error, angle, outgoing)
    _, after = pin_contact(geometry, profile_error, angle, incoming)
    return angle, before, after


def _largest_lever_arms(geometry: CycloidGeometry, theta: np.ndarray,
                        count: int | None) -> np.ndarray:
    """The ``count`` pins with the largest lever arms at each angle, largest first.

    Pin ``k`` sits at the phase ``u = z1·t = θ − 2πk/z2`` (mod 2π) of the trochoid, and the
    lever arm (:func:`lever_arm`) has one maximum on the driving flank, at
    ``cos u* = e·z2/R_p = 1 − x``; so the largest arms belong to the ``2·count + 1`` pins
    nearest to that phase, and only those are ranked.
    """
    z2 = geometry.pins
    if count is None or 2 * count + 1 >= z2:
        pins = np.broadcast_to(np.arange(z2), (theta.size, z2))
    else:
        centre = np.rint((theta + np.arccos(1.0 - geometry.shift)) * z2 / (2.0 * np.pi))
        pins = (centre[:, None].astype(int) + np.arange(-count, count + 1)) % z2
    order = np.argsort(-lever_arm(geometry, theta[:, None], pins), axis=1)
    return np.take_along_axis(pins, order if count is None else order[:, :count], axis=1)


def _ideal_parameter(geometry: CycloidGeometry, theta, pins):
    """Trochoid parameter where pin ``k`` touches the ideal disc: ``2πk/z2 + θ/z1``."""
    return 2.0 * np.pi * np.asarray(pins) / geometry.pins + np.asarray(theta) / geometry.teeth
