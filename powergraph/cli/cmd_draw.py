"""``powergraph draw MODEL -o FILE [--frame ID] [--method M] [--mesh-efficiency E]
[--mode NAME]``.

Draws the power-flow diagram (PNG, SVG or PDF by the suffix of FILE), written atomically:
on any error no file (and no half-written file) is left. ``--frame ID`` draws the
virtual powers seen from component ID's body (the paper's transformation gear train).
"""
from __future__ import annotations

import argparse

from powergraph.cli.common import (check_figure_path, load, new_figure,
                                   number_option, save_figure, say_wrote)
from powergraph.errors import UsageError

METHODS = ("virtual-power", "wang2021")
DPI_RANGE = (10, 1200)


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser(
        "draw", help="draw the power-flow diagram (PNG, SVG or PDF)",
        description="Draw the power-flow graph of a gear train: bodies, meshes (circles), "
                    "the ports by their names, arrows as wide as their power, labelled with "
                    "the power and its share of the input power.")
    parser.add_argument("model", help="model file (YAML)")
    parser.add_argument("-o", "--output", required=True, metavar="FILE",
                        help="figure file; the format follows the suffix (.png, .svg, .pdf)")
    parser.add_argument("--frame", metavar="ID",
                        help="draw the virtual powers seen from component ID's body "
                             "(the transformation gear train with that body held)")
    parser.add_argument("--method", choices=METHODS, default="virtual-power",
                        help="virtual-power (default) or wang2021 (the seed paper's "
                             "method; RV-type trains)")
    parser.add_argument("--mesh-efficiency", metavar="E",
                        help="override every mesh's basic efficiency")
    parser.add_argument("--mode", metavar="NAME",
                        help="draw the model in this mode of its modes table (docs/modes.md)")
    parser.add_argument("--dpi", default="150", metavar="N",
                        help=f"resolution of a PNG (dots per inch, {DPI_RANGE[0]}-"
                             f"{DPI_RANGE[1]}, default 150)")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    target = check_figure_path(args.output)
    dpi = number_option(args.dpi, "--dpi", *DPI_RANGE)  # a huge figure exhausts memory
    model = load(args.model, args.mesh_efficiency)
    if model.modes or model.shift_elements or args.mode is not None:
        from powergraph.statics.case import TrainCase

        if args.method != "virtual-power":
            raise UsageError("--mode works with the virtual-power method")
        result = TrainCase.of(model, args.mode).point().required().result
    elif args.method == "wang2021":
        from powergraph.methods.wang2021 import solve_wang2021

        result = solve_wang2021(model)
    else:
        from powergraph.statics import solve

        result = solve(model)
    from powergraph.plot.layout.view import flow_view

    view = flow_view(result, args.frame)     # a bad --frame fails before matplotlib
    from powergraph.plot.power_flow import plot_power_flow

    ax = plot_power_flow(result, frame=args.frame, view=view, figure=new_figure())
    save_figure(ax.figure, target, dpi=dpi)
    say_wrote(target, f"({view.title})")
    return 0
