"""``powergraph backlash MODEL [--json] [--output ID] [--plot FILE]`` (seeds/002)."""
from __future__ import annotations

import argparse

from powergraph.cli.common import check_figure_path, load, print_json, write_atomically
from powergraph.errors import UsageError


def register(subparsers) -> None:
    """Add the ``backlash`` command."""
    parser = subparsers.add_parser(
        "backlash", help="backlash and lost motion, per mesh and at the output (seeds/002)",
        description="Backlash of internal involute pairs from over-pin measurements (Li et "
                    "al. 2012): equivalent profile shift, eccentric offset a'' (Eq. 15 as "
                    "printed and with tan(alpha)), lost-motion terms; and every mesh's play "
                    "referred to the output with the inputs held (worst case and RSS).")
    parser.add_argument("model", help="YAML model file")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.add_argument("--output", metavar="ID",
                        help="component at which to read the lost motion (default: the "
                             "output port)")
    parser.add_argument("--plot", metavar="FILE",
                        help="write the centre distance over the eccentric's turns (Fig. 3, "
                             "Eqs. 4-6) of every pair with a backlash: block (.png/.svg/.pdf)")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Analyse, then print the report (or JSON) and write the plot if asked."""
    from powergraph.analyses.backlash import analyse_backlash

    target = check_figure_path(args.plot, "--plot") if args.plot else None
    model = load(args.model)
    report = analyse_backlash(model, output=args.output)
    if target is not None:
        _write_plot(report, target)
    if args.json:
        print_json(report.to_dict())
    else:
        print(format_report(model, report))
    return 0


def _write_plot(report, target) -> None:
    from powergraph.analyses.backlash import centre_distance_curve
    from powergraph.plot.backlash import plot_centre_distance
    import matplotlib.pyplot as plt

    pairs = [m for m in report.meshes if m.pair is not None]
    if not pairs:
        raise UsageError("--plot needs a mesh with a backlash: block (runouts and teeth)")
    fig, axes = plt.subplots(len(pairs), 1, figsize=(7, 3.2 * len(pairs)), squeeze=False)
    for mesh, ax in zip(pairs, axes[:, 0]):
        pair = mesh.pair
        curve = centre_distance_curve(pair.standard_centre_distance, pair.runout[pair.internal],
                                      pair.runout[pair.external], pair.teeth[pair.internal],
                                      pair.teeth[pair.external])
        plot_centre_distance(curve, ax=ax, label=f"links[{mesh.link}] {mesh.raw_between[0]}"
                                                 f"-{mesh.raw_between[1]}")
    fig.tight_layout()
    try:
        write_atomically(target, lambda tmp: fig.savefig(tmp))
    finally:
        plt.close(fig)


def format_report(model, report) -> str:
    """The human-readable report."""
    from powergraph.analyses.backlash import format_arcmin

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
    rid = model.raw_id
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
