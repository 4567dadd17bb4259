"""``powergraph lever MODEL -o FILE [--mode NAME] [--json]``: lever diagrams of the
planetary sets, with the speeds of a mode (docs/modes.md)."""
from __future__ import annotations

import argparse

from powergraph.cli.common import (check_figure_path, load, new_figure, print_json,
                                   save_figure, say_wrote)


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser("lever", help="lever diagrams of the planetary sets",
                            description="Each planetary set as a vertical lever (nodes "
                                        "spaced by tooth numbers), held members grounded, "
                                        "the speeds of a mode as arrows, written in rpm, "
                                        "the ports marked by their names (docs/modes.md).")
    parser.add_argument("model", help="model file (YAML)")
    parser.add_argument("-o", "--output", metavar="FILE",
                        help="figure file (.png, .svg or .pdf)")
    parser.add_argument("--mode", metavar="NAME", help="the mode whose speeds are drawn")
    parser.add_argument("--json", action="store_true", help="print the levers as JSON")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from powergraph.analyses.lever import lever_diagram

    target = check_figure_path(args.output) if args.output else None
    model = load(args.model)
    from powergraph.statics.case import TrainCase

    result = TrainCase.of(model, args.mode).point().required().result
    diagram = lever_diagram(result.model, result.speeds, args.mode)
    print_json(diagram.to_dict()) if args.json else print(diagram.text_report())
    if target is not None:
        ax = diagram.plot(figure=new_figure())      # its natural size (docs/modes.md)
        save_figure(ax.figure, target, dpi=150)
        say_wrote(target, data_on_stdout=args.json)
    return 0
