"""``powergraph cycloid``: ratio fluctuation of a cycloid stage (Csobán 2021; docs/cycloid.md).

Two forms::

    powergraph cycloid --module M --teeth Z1 --error D [--shift X] [--rc RC] [--json] [--plot FILE]
    powergraph cycloid --fit --module M [--shift X] [--rc RC] [--json] [--plot FILE]

matplotlib is imported only when ``--plot`` is given.
"""
from __future__ import annotations

import argparse

from powergraph.cli.common import check_figure_path, new_axes, print_json, save_figure, say_wrote
from powergraph.errors import UsageError


def register(subparsers) -> None:
    """Add the ``cycloid`` command to the ``powergraph`` parser."""
    parser = subparsers.add_parser(
        "cycloid", help="cycloid-stage ratio fluctuation from a profile error (Csobán 2021)",
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
    else:
        if args.teeth is None or args.error is None:
            raise UsageError("give --teeth and --error (or --fit)")
        from powergraph.analyses.cycloid import cycloid_fluctuation

        result = cycloid_fluctuation(args.module, args.teeth, args.error, args.shift, args.rc)
    if figure is not None:
        axes = (new_axes((7.5, 6.0), projection="3d") if args.fit else new_axes((7.5, 4.5)))
        ax = result.plot(ax=axes)
        save_figure(ax.figure, figure)
    if args.json:
        print_json(result.to_dict())
    else:
        print(result.text_report())
    if figure is not None:
        say_wrote(figure, data_on_stdout=args.json)
    return 0
