"""``powergraph backlash MODEL [--json] [--output ID] [--plot FILE]`` (docs/backlash.md)."""
from __future__ import annotations

import argparse

from powergraph.cli.common import (check_figure_path, load, new_figure, print_json, save_figure,
                                   say_wrote)
from powergraph.errors import UsageError


def register(subparsers) -> None:
    """Add the ``backlash`` command."""
    parser = subparsers.add_parser(
        "backlash", help="backlash and lost motion, per mesh and at the output (Li et al. 2012)",
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
        print(report.text_report())
    if target is not None:
        say_wrote(target, data_on_stdout=args.json)
    return 0


def _write_plot(report, target) -> None:
    """Fig. 3 of Li et al. (2012) for every pair with a backlash: block, one axes each."""
    from powergraph.analyses.backlash import centre_distance_curve

    pairs = [m for m in report.meshes if m.pair is not None]
    if not pairs:
        raise UsageError("--plot needs a mesh with a backlash: block (runouts and teeth)")
    fig = new_figure((7, 3.2 * len(pairs)))
    axes = fig.subplots(len(pairs), 1, squeeze=False)
    for mesh, ax in zip(pairs, axes[:, 0]):
        pair = mesh.pair
        curve = centre_distance_curve(pair.standard_centre_distance, pair.runout[pair.internal],
                                      pair.runout[pair.external], pair.teeth[pair.internal],
                                      pair.teeth[pair.external])
        curve.plot(ax=ax, label=f"links[{mesh.link}] {mesh.raw_between[0]}"
                                f"-{mesh.raw_between[1]}")
    fig.tight_layout()
    save_figure(fig, target)
