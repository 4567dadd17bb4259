"""The geometric conditions of a planetary set: coaxiality, equal-spacing assembly,
meshing planets' reach, neighbouring planets' clearance, rack-cut undercut.

One copy of these conditions, vectorised with numpy (an array of tooth numbers gives an
array of answers): the tooth-number synthesis filters whole grids with them
(:mod:`powergraph.analyses.synthesis.teeth`), and the model's feasibility caveats check one
train with them (:mod:`powergraph.model.feasibility`, docs/feasibility.md).

Units: a centre distance ``D`` counted in teeth is in **half-modules** (``z_sun + z_planet``
for a sun mesh, ``z_ring - z_planet`` for a ring mesh: one module, no profile shift).

Examples
--------
Sun 12, planet 30, ring 72 with three planets: coaxial (12 + 30 = 72 − 30), assembles
((12 + 72)/3 = 28) and the tips clear (32 < 42 sin 60° = 36.4):

>>> import numpy as np
>>> one = lambda v: np.array([v])
>>> bool(assembles([one(12), one(72)], [one(-30), one(30)], 3)[0])
True
>>> bool(neighbours_clear(np.array(30), np.array(42), 3))
True
"""
from __future__ import annotations

import math
from typing import Any, Sequence

import numpy as np


def centre_distance(central: Any, planet: Any, internal: bool) -> Any:
    """Centre distance of a planet gear meshing a central gear, in half-modules:
    ``z_sun + z_planet`` (external central gear) or ``z_ring - z_planet`` (internal).

    >>> centre_distance(24, 24, False), centre_distance(72, 24, True)
    (48, 48)
    """
    return central - planet if internal else central + planet


def assembles(coaxial: list[np.ndarray], coefficients: list[np.ndarray], planets: int,
              phased: bool = False) -> np.ndarray:
    """Can ``planets`` identical planet clusters be assembled at equal spacing?

    Turn the whole train by ``theta = 2 pi / n``: the carrier looks the same, and a copy
    fits the next place if turning the cluster's planets about their own axes (by ``t``
    times a fixed vector, the one degree of freedom the cluster has with its carrier held)
    brings every coaxial gear ``j`` back onto its own teeth:
    ``z_j / n + a_j t`` is an integer for every coaxial mesh ``j``, where ``a_j`` is
    ``-z_pj`` for a sun, ``+z_pj`` for a ring (``z_pj`` the planet gear meshing it), times
    the cluster's speed ratio for a planet reached through planet-planet meshes (scaled to
    integers, :func:`relative_turns`). One mesh always fits; two give the closed form
    ``(a_2 z_1 - a_1 z_2) = 0 mod n gcd(a_1, a_2)`` — for a simple planet
    ``(z_s + z_r) / n`` whole, for a stepped one ``(z_s z_p2 + z_r z_p1) / (n gcd(z_p1, z_p2))``;
    more are searched over ``t = (m - z_1/n) / a_1``, ``m = 0 .. |a_1| - 1``. A ``phased``
    cluster (a crank carrying a disc, identical in every copy) cannot turn: ``t = 0`` and
    every ``z_j / n`` must be whole.

    >>> ones = lambda v: np.array([v])
    >>> bool(assembles([ones(12), ones(72)], [ones(-30), ones(30)], 3)[0])   # (12+72)/3
    True
    >>> bool(assembles([ones(13), ones(72)], [ones(-30), ones(30)], 3)[0])
    False
    """
    n = planets
    size = len(coaxial[0]) if coaxial else 0
    if n <= 1 or not coaxial:
        return np.ones(size, dtype=bool)
    z = [np.asarray(v, dtype=np.int64) for v in coaxial]
    a = [np.asarray(v, dtype=np.int64) for v in coefficients]
    if phased:
        return np.logical_and.reduce([zj % n == 0 for zj in z])
    if len(z) == 1:
        return np.ones(size, dtype=bool)
    if len(z) == 2:
        return (a[1] * z[0] - a[0] * z[1]) % (n * np.gcd(a[0], a[1])) == 0
    pairwise = np.logical_and.reduce([assembles([z[0], zj], [a[0], aj], n)
                                      for zj, aj in zip(z[1:], a[1:])])
    found = np.zeros(size, dtype=bool)
    if not pairwise.any():
        return found
    index = np.flatnonzero(pairwise)
    found[index] = _search_turn([v[index] for v in z], [v[index] for v in a], n)
    return found


def _search_turn(z: list[np.ndarray], a: list[np.ndarray], n: int) -> np.ndarray:
    """Three or more meshes: try ``t = (m - z_1/n) / a_1`` for ``m = 0 .. |a_1| - 1``,
    each row until one fits (the rows left shrink as ``m`` grows: most fit at a small
    ``m``, while ``|a_1|`` runs to the thousands)."""
    found = np.zeros(len(z[0]), dtype=bool)
    rows = np.arange(len(z[0]))
    bound = np.abs(a[0])
    modulus = np.abs(n * a[0])
    for m in range(int(bound.max(initial=0))):
        left = m < bound
        if not left.all():
            rows, z, a, bound, modulus = _rows(left, rows, z, a, bound, modulus)
        if rows.size == 0:
            break
        fits = np.ones(rows.size, dtype=bool)
        for zj, aj in zip(z[1:], a[1:]):
            fits &= (zj * a[0] + aj * (n * m - z[0])) % modulus == 0
        if fits.any():
            found[rows[fits]] = True
            rows, z, a, bound, modulus = _rows(~fits, rows, z, a, bound, modulus)
    return found


def _rows(keep: np.ndarray, rows: np.ndarray, z: list, a: list, bound: np.ndarray,
          modulus: np.ndarray) -> tuple:
    """The rows of the turn search still searched."""
    return (rows[keep], [v[keep] for v in z], [v[keep] for v in a], bound[keep],
            modulus[keep])


def relative_turns(first: Any, pp_meshes: Sequence[tuple[Any, Any, Any, Any]]
                   ) -> dict[Any, tuple[Any, Any]]:
    """How far each planet of a cluster turns about its axis when ``first`` turns by one,
    the carrier held: ``{planet: (num, den)}`` (integers, or integer arrays).

    ``pp_meshes`` lists the cluster's planet-planet meshes as ``(p, q, z_p, z_q)`` (planet
    ``p``'s gear of ``z_p`` teeth meshing planet ``q``'s of ``z_q``, external):
    ``z_p dθ_p = -z_q dθ_q``. Planets not reached are left out.

    >>> relative_turns("a", [("a", "b", 15, 20)])        # b turns -15/20 of a
    {'a': (1, 1), 'b': (-15, 20)}
    """
    turns = {first: (1, 1)}
    changed = True
    while changed:
        changed = False
        for p, q, zp, zq in pp_meshes:
            for (a, za), (b, zb) in (((p, zp), (q, zq)), ((q, zq), (p, zp))):
                if a in turns and b not in turns:
                    num, den = turns[a]
                    turns[b] = (-num * za, den * zb)
                    changed = True
    return turns


def planets_meet(centre_a: Any, centre_b: Any, teeth_a: Any, teeth_b: Any) -> Any:
    """Two planets on one carrier can mesh: their axes (at ``D_a``, ``D_b`` half-modules
    from the central axis) and the central axis form a triangle whose third side is the
    planets' centre distance ``z_a + z_b``: ``|D_a − D_b| < z_a + z_b < D_a + D_b``.

    >>> bool(planets_meet(45, 60, 15, 15))      # models/planetary_double_planet.yaml
    True
    >>> bool(planets_meet(45, 80, 15, 15))      # 30 < |45 − 80| = 35: too far apart
    False
    """
    reach = teeth_a + teeth_b
    return (abs(centre_a - centre_b) < reach) & (reach < centre_a + centre_b)


def neighbours_clear(teeth: np.ndarray, centre: np.ndarray, planets: int,
                     tip: float = 2.0) -> np.ndarray:
    """Tip circles of adjacent planets clear: ``z + tip < D sin(pi/n)`` (``D`` in
    half-modules, so ``D sin(pi/n)`` is the distance between neighbouring axes in modules,
    and ``z + tip`` the tip diameter in modules: ``tip = 2 h_a*`` for an unshifted gear).

    The same condition in millimetres: ``d_a < 2 a sin(pi/n)``, ``a`` the centre distance.

    >>> bool(neighbours_clear(np.array(30), np.array(60), 3))   # 32 < 51.96
    True
    """
    if planets < 2:
        return np.ones(np.shape(teeth), dtype=bool)
    return teeth + tip < centre * np.sin(np.pi / planets)


def undercut_limit(pressure_angle_deg: float = 20.0, shift: float = 0.0,
                   addendum: float = 1.0, helix_angle_deg: float = 0.0) -> float:
    """Fewest teeth an external gear cut by a rack can have without undercut:
    ``2 (h_a* - x) cos β / sin² α_t`` (``α_t`` the transverse pressure angle; for a spur
    gear ``2 (1 - x) / sin² α``, 17.1 at 20° without shift).

    >>> round(undercut_limit(20.0), 2), round(undercut_limit(20.0, shift=0.3), 2)
    (17.1, 11.97)
    """
    beta = math.radians(helix_angle_deg)
    alpha_t = math.atan(math.tan(math.radians(pressure_angle_deg)) / math.cos(beta))
    return 2.0 * (addendum - shift) * math.cos(beta) / math.sin(alpha_t) ** 2


def undercut_gears(pair: Any) -> list[tuple[int, int, float]]:
    """``(gear, teeth, limit)`` of each external gear of an involute ``pair`` (a
    :class:`~powergraph.gears.mesh_loss.MeshGeometry`; gear 1 the pinion, 2 the wheel)
    that a rack cuts with undercut: fewer teeth than :func:`undercut_limit` at its shift.

    >>> from powergraph.gears.mesh_loss import MeshGeometry
    >>> undercut_gears(MeshGeometry(14, 40))[0][:2]               # 14 < 2/sin²20° = 17.1
    (1, 14)
    >>> undercut_gears(MeshGeometry(14, 40, shift_1=0.2))         # 14 ≥ 2·0.8/sin²20°
    []
    """
    sides = [(1, pair.teeth_1, pair.shift_1)]
    if not pair.internal:
        sides.append((2, pair.teeth_2, pair.shift_2))
    out = []
    for gear, teeth, shift in sides:
        limit = undercut_limit(pair.pressure_angle_deg, shift, pair.addendum,
                               pair.helix_angle_deg)
        if teeth < limit:
            out.append((gear, teeth, limit))
    return out


def working_centre_distance(teeth_1: int, teeth_2: int, internal: bool, module: float,
                            pressure_angle_deg: float = 20.0, helix_angle_deg: float = 0.0,
                            shift_1: float = 0.0, shift_2: float = 0.0) -> float:
    """Working centre distance of an involute pair (mm; DIN 3960): the reference
    ``a = m_t (z_2 ± z_1) / 2`` times ``cos α_t / cos α_w``, where
    ``inv α_w = inv α_t + 2 tan α_n (x_1 ± x_2) / (z_1 ± z_2)`` (− for an internal gear 2).

    >>> working_centre_distance(20, 40, False, 2.0)                 # m (z1 + z2) / 2
    60.0
    >>> round(working_centre_distance(15, 48, True, 1.0, shift_1=0.2, shift_2=0.874), 3)
    17.1
    """
    from powergraph.gears.involute import involute, inverse_involute

    sign = -1.0 if internal else 1.0
    beta = math.radians(helix_angle_deg)
    alpha_n = math.radians(pressure_angle_deg)
    alpha_t = math.atan(math.tan(alpha_n) / math.cos(beta))
    reference = module / math.cos(beta) * abs(teeth_2 + sign * teeth_1) / 2
    shifts = shift_1 + sign * shift_2
    if shifts == 0:
        return reference
    inv_w = involute(alpha_t) + 2 * math.tan(alpha_n) * shifts / (teeth_1 + sign * teeth_2)
    return reference * math.cos(alpha_t) / math.cos(inverse_involute(inv_w))


#: Two working centre distances of one planet are one distance when they differ by at most
#: this many modules (docs/feasibility.md): 1 µm at module 1. A planet that far off one
#: mesh's working distance changes that mesh's normal backlash by 2·δ·sin α_w ≈ 0.0007·m,
#: under 2 % of the smallest backlash recommended (ISO/TR 10064-2: (2/3)(0.06 + 0.0005 a +
#: 0.03 m) mm, at least 40 µm); it is the step of a shift coefficient written to three
#: decimals (``a_w`` moves by about ``m·Δx``), so a set whose shifts were rounded so agrees,
#: and a shift wrong in its second decimal (0.01·m) does not.
CENTRE_TOLERANCE = 1e-3


def centre_tolerance(module: float) -> float:
    """How far apart (mm) two working centre distances of pairs of ``module`` (mm; the
    smaller of two) may be and still be one: :data:`CENTRE_TOLERANCE` modules.

    >>> centre_tolerance(1.0), centre_tolerance(2.5)
    (0.001, 0.0025)
    """
    return CENTRE_TOLERANCE * module


def shift_sum(teeth_1: int, teeth_2: int, internal: bool, module: float,
              centre_distance: float, pressure_angle_deg: float = 20.0,
              helix_angle_deg: float = 0.0) -> float:
    """The profile shift that puts an involute pair at the working centre distance
    ``centre_distance`` (mm): ``x_2 + x_1`` for an external pair, ``x_2 − x_1`` for an
    internal gear 2 (the inverse of :func:`working_centre_distance`). With the reference
    ``a = m_t (z_2 ± z_1)/2``: ``cos α_w = a cos α_t / a_w`` and
    ``x_2 ± x_1 = (inv α_w − inv α_t)(z_2 ± z_1) / (2 tan α_n)``.

    Raises ModelError when ``centre_distance`` is not beyond the base circles' distance
    ``a cos α_t`` (no working pressure angle reaches it).

    >>> round(shift_sum(15, 48, True, 1.0, working_centre_distance(
    ...     15, 48, True, 1.0, shift_1=0.2, shift_2=0.874)), 12)            # 0.874 − 0.2
    0.674
    >>> shift_sum(20, 40, False, 2.0, 60.0)
    0.0
    """
    from powergraph.errors import ModelError
    from powergraph.gears.involute import involute

    sign = -1.0 if internal else 1.0
    beta = math.radians(helix_angle_deg)
    alpha_n = math.radians(pressure_angle_deg)
    alpha_t = math.atan(math.tan(alpha_n) / math.cos(beta))
    teeth = abs(teeth_2 + sign * teeth_1)
    reference = module / math.cos(beta) * teeth / 2
    base = reference * math.cos(alpha_t)
    if not centre_distance > base:
        raise ModelError(f"a working centre distance of {centre_distance:.4f} mm is not "
                         f"beyond the base circles' {base:.4f} mm (a·cos α_t): no profile "
                         "shift puts the pair there")
    if centre_distance == reference:
        return 0.0
    alpha_w = math.acos(base / centre_distance)
    return (involute(alpha_w) - involute(alpha_t)) * teeth / (2 * math.tan(alpha_n))
