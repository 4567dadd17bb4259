"""``powergraph sweep MODEL --set PATH=START:STOP:N ... [-o FILE.csv] [--plot FILE]
[--workers N | --scheduler dask://ADDRESS]``.

Compiles the model once and evaluates every point of the Cartesian grid of the ``--set``
values (docs/sweep.md). CSV columns: each PATH (first varies slowest), then ``ratio`` and
``efficiency`` (``--all-columns`` adds input/output power, total loss, self-locking,
converged, status and each element's loss). Without ``-o`` the CSV goes to stdout.
"""
from __future__ import annotations

import argparse
import io
import sys

from powergraph.cli.cmd_modes import add_mode_option
from powergraph.cli.common import (add_cluster_arguments, check_figure_path, check_output_file,
                                   cluster_options, load, new_figure, save_figure,
                                   say_wrote, write_atomically)


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``sweep`` command."""
    parser = subparsers.add_parser(
        "sweep", help="compiled, vectorised design sweep over model values",
        description="Evaluate the train over a grid of model values (tooth numbers, mesh "
                    "efficiencies, ratios, port speeds/powers) by the virtual-power "
                    "method, compiled once. PATHs: components.<id>.teeth, "
                    "links.<i>.efficiency, links.*.efficiency (every mesh), "
                    "links.<i>.ratio, ports.<i>.speed|power|torque.")
    parser.add_argument("model", help="model file (YAML)")
    parser.add_argument("--set", dest="sets", action="append", required=True,
                        metavar="PATH=START:STOP:N",
                        help="values of one model value: N points from START to STOP "
                             "(or a list V1,V2,...); several --set make a Cartesian grid")
    parser.add_argument("-o", "--output", metavar="FILE.csv",
                        help="write the CSV here (atomically) instead of stdout")
    parser.add_argument("--plot", metavar="FILE",
                        help="plot efficiency and ratio against the first PATH, one curve "
                             "per value of the others (.png/.svg/.pdf)")
    parser.add_argument("--all-columns", action="store_true",
                        help="add powers, losses and flags to the CSV")
    parser.add_argument("--mesh-efficiency", metavar="E",
                        help="set every mesh's basic efficiency first")
    parser.add_argument("--quiet", action="store_true", help="no progress bar")
    add_cluster_arguments(parser)
    add_mode_option(parser, "sweep")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Run ``sweep``; returns the exit status (errors propagate to main: exit 2)."""
    from powergraph.analyses.sweep import cartesian, compile_sweep, parse_sets

    figure = check_figure_path(args.plot, "--plot") if args.plot else None
    if args.output:
        check_output_file(args.output, "-o")
    model = load(args.model, args.mesh_efficiency)
    grid = cartesian(parse_sets(model, args.sets))
    cluster = cluster_options(args)
    if cluster["workers"] is None and cluster["scheduler"] is None:
        result = compile_sweep(model, list(grid), mode=args.mode)(grid, quiet=args.quiet)
    else:
        from powergraph.analyses.sweep.distributed import sweep_on_cluster

        result = sweep_on_cluster(model, grid, mode=args.mode, **cluster)
    if args.output:
        write_atomically(args.output, lambda tmp: result.to_csv(tmp, extra=args.all_columns))
    else:
        buffer = io.StringIO()
        result.to_csv(buffer, extra=args.all_columns)
        sys.stdout.write(buffer.getvalue())
    if figure is not None:
        _plot(figure, result)
    csv_on_stdout = not args.output
    print(result.text_report(), file=sys.stderr if csv_on_stdout else sys.stdout)
    for written in (args.output, figure):
        if written:
            say_wrote(written, data_on_stdout=csv_on_stdout)
    return 0


def _plot(target, result) -> None:
    """Efficiency above, ratio below, against the first swept path."""
    from powergraph.plot.sweep import curve_plot

    fig = new_figure((6.4, 7.0))
    top, bottom = fig.subplots(2, 1, sharex=True)
    result.plot(ax=top, xlabel="")
    x_path, curves = result.curves()
    x = result.parameters[x_path].ravel()
    curve_plot({label: (x[i], result.ratio.ravel()[i]) for label, i in curves.items()},
               x_path, "ratio (input / output speed)", ax=bottom)
    save_figure(fig, target, dpi=150, bbox_inches="tight")
