"""Readable reports of the cycloid results (what ``powergraph cycloid`` and ``solve`` print).

Examples
--------
>>> from powergraph.analyses.cycloid import cycloid_fluctuation
>>> r = cycloid_fluctuation(module=1, teeth=9, profile_error=0.0)
>>> stage_text(r).splitlines()[0]
'cycloid stage: m = 1 mm, z1 = 9 teeth, z2 = 10 pins, x = 0.3, rc* = 1'
"""
from __future__ import annotations

import math

from powergraph.format import format_ratio

def stage_text(r) -> str:
    """Report of one stage (:class:`CycloidFluctuation`)."""
    g = r.geometry
    lines = [
        f"cycloid stage: m = {g.module:g} mm, z1 = {g.teeth} teeth, z2 = {g.pins} pins, "
        f"x = {g.shift:g}, rc* = {g.rc:g}",
        f"  pin circle radius {g.pin_circle_radius:g} mm, eccentricity "
        f"{g.eccentricity:g} mm, pin radius {g.pin_radius:g} mm",
        f"profile error d = {r.profile_error:g} mm",
        f"  nominal ratio                     {format_ratio(r.ratio_nominal, 6)}",
        f"  ratio over a revolution           {r.ratio.min():.6g} … {r.ratio.max():.6g}",
        f"  max |Δi| exact (pin hand-over)    {r.max_deviation_percent:.6g} %  at crank "
        f"angle {math.degrees(r.max_deviation_angle):.4g}°",
        f"  max |Δi| paper (2° differences)   {r.max_deviation_percent_2deg:.6g} %",
        f"  contact segments per revolution   {r.segments}",
    ]
    return "\n".join(lines)


def study_text(s) -> str:
    """Report of the paper's grid and fit (:class:`FluctuationStudy`)."""
    lines = [f"cycloid fluctuation study: m = {s.module:g} mm, x = {s.shift:g}, "
             f"rc* = {s.rc:g}; d = half the ISO 286 tolerance of m·z1",
             f"  {'z1':>4} {'grade':>5} {'d mm':>8} {'max |Δi| %':>11} {'2° %':>9} "
             f"{'fitted %':>9}"]
    for z, g, d, v, w in zip(s.teeth, s.grade, s.profile_error, s.max_deviation_percent,
                             s.max_deviation_percent_2deg):
        lines.append(f"  {z:>4} {'IT' + str(g):>5} {d:>8.4f} {v:>11.5f} {w:>9.5f} "
                     f"{float(s.fitted(d, z)):>9.5f}")
    if s.left_out:
        lines.append(f"  left out (m·z1 > 500 mm): z1 = {', '.join(map(str, s.left_out))}")
    lines.append("Δi = a·d + b·d·z1^-1.5   (Δi in %, d in mm)")
    for name, ours, theirs in (("a", s.a, s.paper_a), ("b", s.b, s.paper_b)):
        paper = "paper gives none" if theirs is None else \
            f"paper {theirs:g}  ({100 * (ours / theirs - 1):+.2f} %)"
        lines.append(f"  {name} = {ours:.6g}   {paper}")
    return "\n".join(lines)


def train_text(t) -> str:
    """Report of a train's fluctuation at its output (:class:`TrainFluctuation`)."""
    lines = ["ratio fluctuation from cycloid profile errors (input speed held)"]
    for stage in t.to_dict()["stages"]:
        lines.append(
            f"  mesh {stage['disc']}-{stage['ring']}: profile error "
            f"{stage['profile_error'] * 1000:g} um -> stage max |di| "
            f"{stage['stage_max_deviation_percent']:.4f} % (paper's 2-degree method "
            f"{stage['stage_max_deviation_percent_2deg']:.4f} %), at the output "
            f"{stage['max_deviation_percent']:.4f} % of the ratio {t.ratio_nominal:.6g}")
    return "\n".join(lines)
