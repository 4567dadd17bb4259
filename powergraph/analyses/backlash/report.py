"""Readable reports of the backlash results (what ``powergraph backlash`` prints).

Examples
--------
>>> from powergraph.analyses.backlash import centre_distance_curve
>>> print(curve_text(centre_distance_curve(2.5, 0.025, 0.018, 45, 40)).splitlines()[0])
centre distance |AB|, Z1 = 45, Z2 = 40, offset 2.5 mm (period 8 turns)
"""
from __future__ import annotations

from powergraph.analyses.backlash.format import format_arcmin


def report_text(model, report) -> str:
    """The readable report of a :class:`BacklashReport` of ``model``."""
    lines = [f"{report.name}: backlash and lost motion (Li et al. 2012)", ""]
    for mesh in report.meshes:
        lines += _mesh_lines(model, mesh, format_arcmin) + [""]
    if report.meshes_without_backlash:
        pairs = ", ".join(f"{a}-{b}" for a, b in report.meshes_without_backlash)
        lines += [f"meshes without backlash data (taken as no play): {pairs}", ""]
    output = model.components[report.output].label
    lines.append(f"lost motion at {output}, inputs held: worst case "
                 f"{format_arcmin(report.worst_case)} ({report.worst_case:.4f} arcmin), "
                 f"RSS {format_arcmin(report.rss)} ({report.rss:.4f} arcmin)")
    return "\n".join(lines)


def _mesh_lines(model, mesh, fmt) -> list[str]:
    a, b = mesh.raw_between
    link = model.links[mesh.link]
    title = f"links[{mesh.link}]" + (f" {link.name}" if link.name else "")
    lines = [f"{title}: {a}-{b}, carrier {model.raw_id(mesh.carrier)}"]
    if mesh.pair is not None:
        lines += _pair_lines(model, mesh.pair, fmt)
    else:
        lines.append("  backlash_arcmin given")
    lines.append(f"  play of {a} (gear held: {b}) {fmt(mesh.play_arcmin)}; at the output "
                 f"x {mesh.sensitivity:+.6g} -> {fmt(mesh.output_arcmin)}")
    return lines


def _pair_lines(model, pair, fmt) -> list[str]:
    rid = model.raw_id if model is not None else str
    i, e = pair.internal, pair.external
    shift = pair.equivalent_shift
    variants = ("paper", "standard")
    row = "  {:<30}" + "{:>18}" * 2
    terms = pair.lost_motion_arcmin
    return [
        f"  internal {rid(i)} (z = {pair.teeth[i]}), external {rid(e)} (z = {pair.teeth[e]}),"
        f" module {pair.module:g} mm, pressure angle {pair.pressure_angle:g} deg",
        f"  M used: {rid(i)} {pair.m_used[i]:.4f} (E_M {pair.m_deviation[i]:+.4f}), "
        f"{rid(e)} {pair.m_used[e]:.4f} (E_M {pair.m_deviation[e]:+.4f}) mm",
        f"  equivalent shift: {rid(i)} {shift[i]:+.4f} mm, {rid(e)} {shift[e]:+.4f} mm",
        row.format("Eq. 15 variant", "paper", "standard (tan a)"),
        row.format("working pressure angle (deg)",
                   *(f"{pair.working_pressure_angle[v]:.4f}" for v in variants)),
        row.format("no-backlash a' (mm)",
                   *(f"{pair.no_backlash_centre_distance[v]:.4f}" for v in variants)),
        row.format("eccentric offset a'' (mm)",
                   *(f"{pair.eccentric_offset[v]:.4f}" for v in variants)),
        f"  lost motion (internal gear, Eq. 1): thickness {fmt(terms['thickness'])}, runout "
        f"{fmt(terms['runout'])}, bearing {fmt(terms['bearing'])}",
        f"    before (a = {pair.standard_centre_distance:g} mm) {fmt(terms['before'])}, "
        f"after (a'') {fmt(terms['after'])}; assembled: {pair.assembly}",
    ]


def pair_text(pair) -> str:
    """The readable report of one :class:`PairBacklash` (gear ids as given)."""
    return "\n".join(line[2:] for line in _pair_lines(None, pair, format_arcmin))


def curve_text(curve) -> str:
    """The bounds of a :class:`CentreDistanceCurve` (Eqs. 5-6)."""
    return "\n".join([
        f"centre distance |AB|, Z1 = {curve.z_internal}, Z2 = {curve.z_external}, offset "
        f"{curve.offset:g} mm (period {curve.period_turns} turns)",
        f"  sampled: {min(curve.distance):.6f} … {max(curve.distance):.6f} mm",
        f"  Eq. (5) maximum {curve.maximum:.6f} mm, Eq. (6) minimum {curve.minimum:.6f} mm"])
