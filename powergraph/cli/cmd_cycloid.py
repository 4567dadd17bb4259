"""``powergraph cycloid``: ratio fluctuation of a cycloid stage (seeds/003, Csobán 2021).

Two forms::

    powergraph cycloid --module M --teeth Z1 --error D [--shift X] [--rc RC] [--json] [--plot FILE]
    powergraph cycloid --fit --module M [--shift X] [--rc RC] [--json] [--plot FILE]

matplotlib is imported only when ``--plot`` is given.
"""
from __future__ import annotations

import argparse
import math

from powergraph.cli.common import check_figure_path, print_json, write_atomically
from powergraph.errors import UsageError


def register(subparsers) -> None:
    """Add the ``cycloid`` command to the ``powergraph`` parser."""
    parser = subparsers.add_parser(
        "cycloid", help="cycloid-stage ratio fluctuation from a profile error (seed 003)",
        description="Ratio fluctuation of a cycloid stage (disc z1 teeth, z1 + 1 pins) whose "
                    "profile is off by D mm along its normal (Csobán 2021). With --fit, "
                    "repeat the paper's study for one module and refit "
                    "a*d + b*d*z1^-1.5.")
    parser.add_argument("--module", type=float, required=True, metavar="M", help="module, mm")
    parser.add_argument("--teeth", type=int, metavar="Z1", help="disc teeth z1 (>= 3)")
    parser.add_argument("--error", type=float, metavar="D", help="profile error d, mm (>= 0)")
    parser.add_argument("--shift", type=float, default=0.3, metavar="X",
                        help="profile-shift coefficient x, 0 < x < 1 (default 0.3)")
    parser.add_argument("--rc", type=float, default=1.0, metavar="RC",
                        help="pin-radius factor rc*: pin radius = rc*·m (default 1)")
    parser.add_argument("--fit", action="store_true",
                        help="the paper's grid (z1 = 9, 25, 43, 53, 117; IT5…IT9) and refit")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.add_argument("--plot", metavar="FILE",
                        help="figure (.png/.svg/.pdf): ratio against crank angle, or with "
                             "--fit the maxima and fitted surfaces")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Compute, print, and draw if asked. Bad arguments raise :class:`UsageError`."""
    figure = check_figure_path(args.plot, "--plot") if args.plot else None
    if args.fit:
        if args.teeth is not None or args.error is not None:
            raise UsageError("--fit runs the paper's grid of teeth and errors: "
                             "give no --teeth or --error")
        from powergraph.analyses.cycloid import fluctuation_study

        result = fluctuation_study(args.module, shift=args.shift, rc=args.rc)
        text, draw = _fit_text(result), "plot_fluctuation_study"
    else:
        if args.teeth is None or args.error is None:
            raise UsageError("give --teeth and --error (or --fit)")
        from powergraph.analyses.cycloid import cycloid_fluctuation

        result = cycloid_fluctuation(args.module, args.teeth, args.error, args.shift, args.rc)
        text, draw = _stage_text(result), "plot_ratio_fluctuation"
    if figure is not None:
        _save_figure(figure, draw, result)
    if args.json:
        print_json(result.to_dict())
    else:
        print(text)
    return 0


def _save_figure(path, function_name: str, result) -> None:
    import matplotlib.pyplot as plt

    from powergraph.plot import cycloid as plots

    ax = getattr(plots, function_name)(result)
    try:
        write_atomically(path, ax.figure.savefig)
    finally:
        plt.close(ax.figure)


def _stage_text(r) -> str:
    g = r.geometry
    lines = [
        f"cycloid stage: m = {g.module:g} mm, z1 = {g.teeth} teeth, z2 = {g.pins} pins, "
        f"x = {g.shift:g}, rc* = {g.rc:g}",
        f"  pin circle radius {g.pin_circle_radius:g} mm, eccentricity "
        f"{g.eccentricity:g} mm, pin radius {g.pin_radius:g} mm",
        f"profile error d = {r.profile_error:g} mm",
        f"  nominal ratio                     {r.ratio_nominal:g}",
        f"  ratio over a revolution           {r.ratio.min():.6g} … {r.ratio.max():.6g}",
        f"  max |Δi| exact (pin hand-over)    {r.max_deviation_percent:.6g} %  at crank "
        f"angle {math.degrees(r.max_deviation_angle):.4g}°",
        f"  max |Δi| paper (2° differences)   {r.max_deviation_percent_2deg:.6g} %",
        f"  contact segments per revolution   {r.segments}",
    ]
    return "\n".join(lines)


def _fit_text(s) -> str:
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
