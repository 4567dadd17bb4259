"""``powergraph cycle MODEL --points FILE.csv [--keep-going] [--json] [-o OUT.csv]
[--plot FILE]``.

Evaluates the train at every operating point of a duty cycle (docs/hybrid.md): columns
``PORT.speed``, ``PORT.power``, ``PORT.torque`` with units in the header, optional
``BUS.battery``, ``duration [s]`` or ``time [s]`` and ``mode``. Prints the totals (energy
in, out and lost per element, cycle efficiency, time per mode, rows that lock); ``-o``
writes the per-row results as CSV (with machines, each machine's and battery's columns). A row that cannot be solved is an error (exit 2) unless ``--keep-going``
leaves it out of the totals.
"""
from __future__ import annotations

import argparse

from powergraph.cli.common import (check_figure_path, check_output_file, load, new_figure,
                                   print_json, save_figure, say_wrote, write_atomically)


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``cycle`` command."""
    parser = subparsers.add_parser(
        "cycle", help="a duty cycle: operating points from CSV, energies over the cycle",
        description="Evaluate the train at every row of a CSV of operating points "
                    "(PORT.speed [rpm], PORT.power [kW], PORT.torque [N*m], BUS.battery "
                    "[kW], duration [s] or time [s], mode) and total the energies over the "
                    "cycle. A row that "
                    "cannot be solved is an error (exit 2) unless --keep-going.")
    parser.add_argument("model", help="model file (YAML)")
    parser.add_argument("--points", required=True, metavar="POINTS.csv",
                        help="the operating points, one per row")
    parser.add_argument("--keep-going", action="store_true",
                        help="leave the rows that cannot be solved out of the totals (the "
                             "report counts them) instead of stopping at the first")
    parser.add_argument("--json", action="store_true", help="print the result as JSON")
    parser.add_argument("-o", "--output", metavar="FILE.csv",
                        help="write the per-row results as CSV")
    parser.add_argument("--plot", metavar="FILE",
                        help="plot power in, out and loss over time; with machines the "
                             "ports', machines' and batteries' power and the electrical "
                             "share (.png/.svg/.pdf)")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Run ``cycle``; returns the exit status (errors propagate to main: exit 2)."""
    from powergraph.analyses.cycle import cycle

    figure = check_figure_path(args.plot, "--plot") if args.plot else None
    if args.output:
        check_output_file(args.output, "-o", (".csv",))
    model = load(args.model)
    result = cycle(model, args.points, keep_going=args.keep_going)
    if args.output:
        write_atomically(args.output, lambda tmp: result.to_csv(tmp))
    if figure is not None:
        from powergraph.plot.cycle import cycle_axes, figure_size

        fig = new_figure(figure_size(result))
        result.plot(ax=cycle_axes(fig, result))
        save_figure(fig, figure, dpi=150, bbox_inches="tight")
    print_json(result.to_dict()) if args.json else print(result.text_report())
    for written in (args.output, figure):
        if written:
            say_wrote(written, data_on_stdout=args.json)
    return 0
