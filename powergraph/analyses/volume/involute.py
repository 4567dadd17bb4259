"""Exact outline of a rack-generated external spur gear, and its area.

The paper's Eqs. (1)–(2) take a gear as a cylinder of the pitch radius m·z/2. Here the real
tooth outline is generated the way a hob or rack cutter makes it: a basic rack (pressure
angle α = 20°, gear addendum 1·m, dedendum 1.25·m, cutter tip fillet radius 0.38·m, no
profile shift) rolls on the pitch circle. Its straight flank envelopes the involute, its tip
fillet the trochoidal root fillet, its tip line the root circle; undercut (z < 17) comes out
of the same envelope with no special case.

Method. For each point of the cutter's half profile the meshing condition (the profile
normal passes through the pitch point) gives the roll angle at which that point touches the
gear, hence a point (R, θ) of the gear in polar form (θ from the tooth-space centre line).
At each radius R the tooth space is the union of the cutter positions, an interval
[−ψ(R), ψ(R)], and ψ(R) is the largest θ among the envelope points at that radius (this is
what trims the undercut loop). The gear outline is then root arc, ψ(R) up to the tip circle,
tip arc, and the mirror flank, repeated z times; its area is the shoelace area.

Examples
--------
>>> round(pitch_circle_error(40), 4)     # pitch-circle cylinder over-estimates by ~0.7 %
0.0066
"""
from __future__ import annotations

import math
from functools import lru_cache
from typing import Iterable

import numpy as np

from powergraph.analyses.volume.polygon import shoelace_area
from powergraph.records import record


@record
class BasicRack:
    """Basic rack of the generating cutter, per unit module (ISO 53 profile A by default).

    Attributes
    ----------
    pressure_angle_deg : float
        Pressure angle α in degrees.
    addendum : float
        Gear addendum (tip radius = m·z/2 + addendum·m).
    dedendum : float
        Gear dedendum (root radius = m·z/2 − dedendum·m) = cutter addendum.
    tip_radius : float
        Radius of the cutter's tip fillet (ρ), which generates the root fillet.
    """

    pressure_angle_deg: float = 20.0
    addendum: float = 1.0
    dedendum: float = 1.25
    tip_radius: float = 0.38

    @property
    def alpha(self) -> float:
        return math.radians(self.pressure_angle_deg)

    @property
    def fillet_centre(self) -> tuple[float, float]:
        """Centre (x, y) of the cutter's tip fillet; y = 0 is the pitch line."""
        yc = -self.dedendum + self.tip_radius
        xc = math.pi / 4 + yc * math.tan(self.alpha) - self.tip_radius / math.cos(self.alpha)
        return xc, yc


STANDARD_RACK = BasicRack()


def _cutter_half_profile(rack: BasicRack, n: int) -> tuple[np.ndarray, ...]:
    """Right half of one cutter tooth (unit module): points and outward normals.

    The tooth points towards the gear (−y); y = 0 is the pitch line, x = 0 its centre line.
    """
    alpha, rho = rack.alpha, rack.tip_radius
    xc, yc = rack.fillet_centre
    if xc < 0:
        raise ValueError("the cutter's tip fillets overlap: tip_radius too large")
    flat_x = np.linspace(0.0, xc, n)
    beta = np.linspace(-math.pi / 2, -alpha, n)[1:]
    y_start = yc - rho * math.sin(alpha)
    flank_y = np.linspace(y_start, rack.addendum + 0.25, n)[1:]
    x = np.concatenate([flat_x, xc + rho * np.cos(beta),
                        math.pi / 4 + flank_y * math.tan(alpha)])
    y = np.concatenate([np.full(n, -rack.dedendum), yc + rho * np.sin(beta), flank_y])
    nx = np.concatenate([np.zeros(n), np.cos(beta), np.full(n - 1, math.cos(alpha))])
    ny = np.concatenate([np.full(n, -1.0), np.sin(beta), np.full(n - 1, -math.sin(alpha))])
    return x, y, nx, ny


def envelope_points(teeth: int, rack: BasicRack = STANDARD_RACK,
                    samples: int = 600) -> tuple[np.ndarray, np.ndarray]:
    """Points the cutter's right half generates on the gear, in polar form (unit module).

    Returns ``(R, θ)``: radius (in modules) and angle from the tooth-space centre line,
    positive towards the tooth on that side, in radians.
    """
    x, y, nx, ny = _cutter_half_profile(rack, samples)
    pitch = teeth / 2
    roll = (x - y * nx / ny) / pitch          # normal through the pitch point
    wx, wy = x - pitch * roll, pitch + y
    return np.hypot(wx, wy), np.arctan2(wx, wy) + roll


def space_half_angle(teeth: int, radii: Iterable[float], rack: BasicRack = STANDARD_RACK,
                     samples: int = 600) -> np.ndarray:
    """Half angle ψ(R) of the tooth space at radii R (in modules, root ≤ R ≤ tip).

    Examples
    --------
    >>> psi = space_half_angle(40, [20.0])       # at the pitch circle: π/(2z)
    >>> bool(abs(psi[0] - math.pi / 80) < 1e-7)
    True
    """
    radii = np.atleast_1d(np.asarray(radii, dtype=float))
    R, theta = envelope_points(teeth, rack, samples)
    root = teeth / 2 - rack.dedendum
    if radii.min() < root * (1 - 1e-12) or radii.max() > R.max():
        raise ValueError("radii must lie between the root and the tip circle")
    psi = np.concatenate([_max_angle_on_segments(R, theta, chunk)
                          for chunk in np.array_split(radii, max(1, radii.size // 256))])
    at_root = radii <= root * (1 + 1e-12)
    psi[at_root] = np.maximum(psi[at_root], theta[R <= root * (1 + 1e-12)].max())
    return psi


def _max_angle_on_segments(R: np.ndarray, theta: np.ndarray, radii: np.ndarray) -> np.ndarray:
    """Largest θ at each radius over the polyline (R, θ), by linear interpolation."""
    r0, r1, t0, t1 = R[:-1, None], R[1:, None], theta[:-1, None], theta[1:, None]
    inside = (radii >= np.minimum(r0, r1)) & (radii <= np.maximum(r0, r1)) & (r1 != r0)
    frac = np.where(inside, (radii - r0) / np.where(r1 != r0, r1 - r0, 1.0), 0.0)
    return np.where(inside, t0 + frac * (t1 - t0), -np.inf).max(axis=0)


def gear_outline(module: float, teeth: int, rack: BasicRack = STANDARD_RACK,
                 radial_points: int = 600, arc_step: float = 1e-3
                 ) -> tuple[np.ndarray, np.ndarray]:
    """Vertices (x, y) in mm of the whole gear's outline, all z teeth, one closed polygon.

    Examples
    --------
    >>> x, y = gear_outline(1.0, 20)
    >>> bool(np.hypot(x, y).max() <= 11.0 + 1e-9 and np.hypot(x, y).min() >= 8.75 - 1e-9)
    True
    """
    root, tip = teeth / 2 - rack.dedendum, teeth / 2 + rack.addendum
    u = np.linspace(0.0, 1.0, radial_points)
    radii = root + (tip - root) * u ** 2      # dense near the root, where ψ turns fastest
    psi = space_half_angle(teeth, radii, rack)
    pitch_angle = 2 * math.pi / teeth
    if psi[-1] >= pitch_angle / 2:
        raise ValueError(f"z = {teeth}: the teeth are pointed (no tip land)")
    root_arc = _arc(-psi[0], psi[0], arc_step)
    tip_arc = _arc(psi[-1], pitch_angle - psi[-1], arc_step)[1:]
    down = slice(-2, 0, -1)                   # below the tip, above the root: no repeats
    r_one = np.concatenate([np.full(root_arc.size, root), radii[1:],
                            np.full(tip_arc.size, tip), radii[down]])
    a_one = np.concatenate([root_arc, psi[1:], tip_arc, pitch_angle - psi[down]])
    angles = (a_one[None, :] + pitch_angle * np.arange(teeth)[:, None]).ravel()
    radius = np.tile(r_one, teeth) * module
    return radius * np.sin(angles), radius * np.cos(angles)


def _arc(start: float, stop: float, step: float) -> np.ndarray:
    return np.linspace(start, stop, max(2, math.ceil(abs(stop - start) / step) + 1))


@lru_cache(maxsize=512)
def _unit_area(teeth: int, rack: BasicRack, radial_points: int, arc_step: float) -> float:
    x, y = gear_outline(1.0, teeth, rack, radial_points, arc_step)
    return shoelace_area(x, y)


def profile_area(module: float, teeth: int, rack: BasicRack = STANDARD_RACK,
                 radial_points: int = 600, arc_step: float = 1e-3) -> float:
    """Area in mm² of the exact generated gear outline (shoelace area of :func:`gear_outline`).

    Examples
    --------
    >>> a = profile_area(2.0, 30)
    >>> bool(math.pi * 27.5 ** 2 < a < math.pi * 32 ** 2)    # between root and tip circles
    True
    """
    return module ** 2 * _unit_area(int(teeth), rack, radial_points, arc_step)


def pitch_circle_area(module: float, teeth: int) -> float:
    """The paper's approximation: area of the pitch circle, π (m z / 2)²."""
    return math.pi * (module * teeth / 2) ** 2


def pitch_circle_error(teeth: int, rack: BasicRack = STANDARD_RACK) -> float:
    """Relative error of the pitch-circle area, (π(mz/2)² − A_exact) / A_exact.

    Independent of the module (both areas scale with m²). Positive: the paper's cylinder
    is larger than the real gear (the tooth spaces below the pitch circle hold more than
    the teeth above it).
    """
    exact = profile_area(1.0, teeth, rack)
    return (pitch_circle_area(1.0, teeth) - exact) / exact


@record
class ProfileErrorTable:
    """Pitch-circle vs exact-profile areas for a range of tooth numbers (unit module)."""

    teeth: tuple[int, ...]
    exact_area: tuple[float, ...]
    pitch_area: tuple[float, ...]
    relative_error: tuple[float, ...]

    def text_report(self) -> str:
        """One line per tooth number: areas per m² and the pitch-circle error."""
        lines = [f"{'z':>4}  {'exact mm²/m²':>14}  {'pitch mm²/m²':>14}  {'error':>9}"]
        lines += [f"{z:>4}  {e:>14.4f}  {p:>14.4f}  {100 * r:>+8.3f}%" for z, e, p, r
                  in zip(self.teeth, self.exact_area, self.pitch_area, self.relative_error)]
        return "\n".join(lines)

    def plot(self, ax=None, **kwargs):
        """The error against the tooth number (delegates, lazily, to
        :func:`powergraph.plot.volume.pitch_circle_error_plot`)."""
        from powergraph.plot.volume import pitch_circle_error_plot

        return pitch_circle_error_plot(self.teeth, self.relative_error, ax=ax, **kwargs)

    def to_dict(self) -> dict:
        """``{teeth, exact_area_mm2_per_m2, pitch_area_mm2_per_m2, relative_error}``."""
        return {"teeth": list(self.teeth), "exact_area_mm2_per_m2": list(self.exact_area),
                "pitch_area_mm2_per_m2": list(self.pitch_area),
                "relative_error": list(self.relative_error)}


def pitch_circle_errors(teeth: Iterable[int] = range(12, 81),
                        rack: BasicRack = STANDARD_RACK) -> ProfileErrorTable:
    """Error of the pitch-circle approximation for each tooth number (default 12…80).

    Examples
    --------
    >>> table = pitch_circle_errors([20, 40])
    >>> table.relative_error[0] > table.relative_error[1] > 0
    True
    """
    teeth = tuple(int(z) for z in teeth)
    exact = tuple(profile_area(1.0, z, rack) for z in teeth)
    pitch = tuple(pitch_circle_area(1.0, z) for z in teeth)
    errors = tuple((p - e) / e for p, e in zip(pitch, exact))
    return ProfileErrorTable(teeth, exact, pitch, errors)
