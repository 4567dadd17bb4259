"""``powergraph draw MODEL -o FILE [--frame ID] [--method M] [--mesh-efficiency E]
[--mode NAME]``.

Draws the power-flow diagram (PNG, SVG or PDF by the suffix of FILE), written atomically:
on any error no file (and no half-written file) is left. ``--frame ID`` draws the
virtual powers seen from component ID's body (the paper's transformation gear train).
"""
from __future__ import annotations

import argparse

from powergraph.cli.common import check_figure_path, efficiency_arg, load, new_figure, save_figure
from powergraph.errors import PowerGraphError

METHODS = ("virtual-power", "wang2021")
DPI_RANGE = (10, 1200)


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser(
        "draw", help="draw the power-flow diagram (PNG, SVG or PDF)",
        description="Draw the power-flow graph of a gear train: bodies, meshes (circles), "
                    "motor and generator, arrows as wide as their power, labelled with "
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
    parser.add_argument("--mesh-efficiency", type=efficiency_arg, metavar="E",
                        help="override every mesh's basic efficiency")
    parser.add_argument("--mode", metavar="NAME",
                        help="draw the model in this mode of its modes table (docs/modes.md)")
    parser.add_argument("--dpi", type=_dpi, default=150.0, metavar="N",
                        help=f"resolution of a PNG (dots per inch, {DPI_RANGE[0]}-"
                             f"{DPI_RANGE[1]}, default 150)")
    parser.set_defaults(handler=run)


def _dpi(text: str) -> float:
    """argparse type of --dpi: a number in DPI_RANGE (a huge figure exhausts memory)."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number: {text!r}") from None
    if not DPI_RANGE[0] <= value <= DPI_RANGE[1]:
        raise argparse.ArgumentTypeError(f"must be between {DPI_RANGE[0]} and {DPI_RANGE[1]}, "
                                         f"got {text}")
    return value


def run(args: argparse.Namespace) -> int:
    target = check_figure_path(args.output)
    model = load(args.model, args.mesh_efficiency)
    if model.modes or args.mode is not None:
        from powergraph.cli.cmd_modes import solve_one_mode

        result = solve_one_mode(model, args.mode, args.method).result
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
    try:
        save_figure(ax.figure, target, dpi=args.dpi)
    except OSError as exc:
        raise PowerGraphError(f"cannot write {target}: {exc.strerror or exc}") from exc
    print(f"wrote {target} ({view.title})")
    return 0
