"""Pan & Wang (2019) volume formulas, Eqs. (1)–(7), as plain functions of numbers (mm, mm³).

The paper's symbols are kept in the docstrings; the arguments use the plain words of the
model's ``geometry`` blocks (:mod:`powergraph.model.block_geometry`).

Reading of the damaged equations (the seed is an OCR of the paper)
------------------------------------------------------------------
Eq. (3), cycloid disc, printed ``V3 = π B2 [(r_p − r_rp)² − 6(r8 + a)² − 2 r3² − r4²]``.
  Kept as printed, with the two integer factors read as hole counts:

  * outer radius r_p − r_rp: the paper's "average circle method" takes the mean of the tip
    radius r_p + a − r_rp and the root radius r_p − a − r_rp, which is r_p − r_rp;
  * ``6 (r8 + a)²``: six clearance holes for the pillars of planet frame II ("r8, the pin
    radius of planet frame II"; "two" in the OCR is "II"). The disc orbits with the crank
    eccentricity a around pillars fixed to the frame, so each hole has radius r8 + a. Six
    pillars is what Eq. (7) says too: its ``12 π B2 r8²`` is six pillars of length 2·B2;
  * ``2 r3²``: one hole per crankshaft, radius r3 = the roller bearing's outer radius; two
    cranks, as in Eq. (7) (2 Z2², 2 π r7² B3) and Eq. (6);
  * ``r4²``: the central hole.

  The counts are parameters here (``pillar_holes``, ``crank_holes``), 6 and 2 in the paper.

Eq. (4), needle gear, printed ``V4 = π B2 (4 t r_p + 2 t² + r_rp² Z3)``.
  Read as ``2·B2 · [π((r_p + t)² − r_p²) + Z3 · π r_rp² / 2]``: a shell of radial thickness t
  outside the pin circle, plus the half of each of the Z3 needles that stands out of the shell
  (the paper: needles "half buried" in the shell), both over the width 2·B2 of the two discs.
  Expanding gives exactly the printed 4, 2 and 1; a full-pin or inner-ring reading does not.
  ``width`` here is that axial length (2·B2 in the paper).

Eq. (5), crankshaft, printed ``V5 = π α2² (B1 + 2B3) + 2π α5² B2``.
  ``α2``/``α5`` are OCR for r2/r5: the text defines r5 (roller bearing inner radius) right
  below, and r2 (the planet gear bore, Eq. 2) is where the planet sits on the crank.
  Read as ``π r2² (B1 + 2 B3) + 2 π r5² B2``: the shaft through the planet (length B1) and
  its two end bearings (B3 each), plus two eccentric journals of radius r5 and length B2 (one
  per disc). The 2 is ``journals``.

Examples
--------
>>> round(gear_volume(module=1.0, teeth=20, face_width=10.0, bore_radius=0.0), 6)
3141.592654
"""
from __future__ import annotations

import math


def gear_volume(module: float, teeth: int, face_width: float, bore_radius: float) -> float:
    """Eqs. (1)–(2): pitch-circle cylinder minus bore, ``π B (m² z²/4 − r²)``.

    Parameters
    ----------
    module, face_width, bore_radius : float
        m, B and r in mm.
    teeth : int
        z.

    Returns
    -------
    float
        Volume in mm³.

    Examples
    --------
    >>> round(gear_volume(2.0, 10, 5.0, 3.0) / math.pi, 9)   # 5·(100 − 9)
    455.0
    """
    return math.pi * face_width * (module ** 2 * teeth ** 2 / 4 - bore_radius ** 2)


def cycloid_disc_volume(width: float, pin_circle_radius: float, pin_radius: float,
                        eccentricity: float, crank_hole_radius: float, crank_holes: int,
                        pillar_radius: float, pillar_holes: int,
                        center_bore_radius: float) -> float:
    """Eq. (3): ``π B2 [(r_p − r_rp)² − n8 (r8 + a)² − n3 r3² − r4²]`` (n8 = 6, n3 = 2).

    Examples
    --------
    >>> v = cycloid_disc_volume(10, 64, 3, 1.3, 17, 2, 9, 2, 15)
    >>> round(v / (10 * math.pi), 6)      # 61² − 2·10.3² − 2·17² − 15²
    2705.82
    """
    outline = (pin_circle_radius - pin_radius) ** 2
    holes = (pillar_holes * (pillar_radius + eccentricity) ** 2
             + crank_holes * crank_hole_radius ** 2 + center_bore_radius ** 2)
    return math.pi * width * (outline - holes)


def needle_gear_volume(width: float, pin_circle_radius: float, pin_radius: float,
                       shell_thickness: float, pins: int) -> float:
    """Eq. (4) read as ``W [π((r_p + t)² − r_p²) + Z3 π r_rp²/2]`` with W = 2·B2.

    Examples
    --------
    >>> v = needle_gear_volume(20, 64, 3, 8, 40)
    >>> round(v / (10 * math.pi), 6)      # = 4·8·64 + 2·8² + 3²·40 with B2 = 10
    2536.0
    """
    shell = math.pi * ((pin_circle_radius + shell_thickness) ** 2 - pin_circle_radius ** 2)
    return width * (shell + pins * math.pi * pin_radius ** 2 / 2)


def crankshaft_volume(shaft_radius: float, gear_seat_length: float, bearing_width: float,
                      journal_radius: float, journal_length: float, journals: int) -> float:
    """Eq. (5) read as ``π r2² (B1 + 2 B3) + n π r5² B2`` (n = 2).

    Examples
    --------
    >>> round(crankshaft_volume(10, 12, 10, 13, 10, 2) / math.pi, 6)  # 100·32 + 2·169·10
    6580.0
    """
    return (math.pi * shaft_radius ** 2 * (gear_seat_length + 2 * bearing_width)
            + journals * math.pi * journal_radius ** 2 * journal_length)


def planet_frame_1_volume(bearing_seat_radius: float, bearing_width: float,
                          crank_bearing_radius: float, crank_bearing_width: float,
                          crank_bearings: int) -> float:
    """Eq. (6): ``π r6² B4 − n π r7² B3`` (n = 2): a plate with the crank bearing seats.

    Examples
    --------
    >>> round(planet_frame_1_volume(55, 14, 17, 10, 2) / math.pi, 6)  # 3025·14 − 2·289·10
    36570.0
    """
    return (math.pi * bearing_seat_radius ** 2 * bearing_width
            - crank_bearings * math.pi * crank_bearing_radius ** 2 * crank_bearing_width)


def planet_frame_2_volume(seal_radius: float, bearing_seat_radius: float,
                          bearing_width: float, crank_bearing_radius: float,
                          crank_bearing_width: float, crank_bearings: int,
                          pillar_radius: float, pillars: int, pillar_length: float,
                          module: float, sun_teeth: int, planet_teeth: int, planets: int,
                          gear_width: float) -> float:
    """Eq. (7), the planet frame II (printed legibly in the seed).

    ``π r9² (B1 + B3 − B4) + 12 π B2 r8² + π r6² B4
    − [¼ π m² (Z1² + 2 Z2²) B1 + 2 π r7² B3 + ¼ π m² Z1² B3]``

    with 12 π B2 r8² = ``pillars`` · π r8² · ``pillar_length`` (6 pillars of length 2·B2),
    the 2 of 2 Z2² = ``planets`` and the 2 of 2 π r7² B3 = ``crank_bearings``. B1 is the
    gear face width (``gear_width``), m the first-stage module.

    Examples
    --------
    >>> v = planet_frame_2_volume(50, 55, 14, 17, 10, 2, 9, 2, 20, 1.5, 12, 36, 2, 12)
    >>> round(v / math.pi, 6)   # 2500·8 + 2·81·20 + 3025·14 − 2.25·2736/4·12 − 5780 − 810
    40532.0
    """
    body = (seal_radius ** 2 * (gear_width + crank_bearing_width - bearing_width)
            + pillars * pillar_radius ** 2 * pillar_length
            + bearing_seat_radius ** 2 * bearing_width)
    gear_pockets = module ** 2 * (sun_teeth ** 2 + planets * planet_teeth ** 2) / 4 * gear_width
    seats = crank_bearings * crank_bearing_radius ** 2 * crank_bearing_width
    sun_bore = module ** 2 * sun_teeth ** 2 / 4 * crank_bearing_width
    return math.pi * (body - gear_pockets - seats - sun_bore)
