"""``powergraph compare MODEL[:MODE] MODEL[:MODE]... [--json] [-o FILE] [--mesh-efficiency E]``."""
from __future__ import annotations

import argparse

from powergraph.cli.common import (
    check_figure_path,
    load,
    new_axes,
    print_json,
    save_figure,
    say_wrote,
)
from powergraph.errors import UsageError


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser("compare", help="compare trains side by side",
                            description="Ratio, efficiency both ways, self-locking, "
                                        "circulating power and mesh rolling of several "
                                        "trains, one row each.")
    parser.add_argument("models", nargs="+", metavar="MODEL",
                        help="model files (YAML); MODEL:MODE for one mode of a model with "
                             "modes (docs/modes.md)")
    parser.add_argument("--json", action="store_true", help="print a JSON list of rows")
    parser.add_argument("-o", "--output", metavar="FILE",
                        help="write a grouped bar chart (.png, .svg or .pdf)")
    parser.add_argument("--mesh-efficiency", metavar="E",
                        help="compare at equal mesh quality: every mesh at E")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from powergraph.analyses.compare import ComparisonTable, compare_row

    target = check_figure_path(args.output) if args.output else None
    table = ComparisonTable(tuple(compare_row(*_model_and_mode(text, args.mesh_efficiency))
                                  for text in args.models))
    if args.json:
        print_json(table.to_dict()["rows"])
    else:
        print(table.text_report())
    if target is not None:
        ax = table.plot(ax=new_axes(figsize=(max(6.0, 1.6 * len(table) + 2), 4.2)))
        save_figure(ax.figure, target, bbox_inches="tight")
        say_wrote(target, data_on_stdout=args.json)
    return 0


def _model_and_mode(text: str, mesh_efficiency):
    """``MODEL`` or ``MODEL:MODE`` (a file name with a colon is taken whole when it
    exists): the loaded model and the mode (None)."""
    import os

    path, mode = text, None
    if not os.path.exists(text) and ":" in text:     # False, not an error, for any name
        path, mode = text.rsplit(":", 1)
    model = load(path, mesh_efficiency)
    if model.modes and mode is None:
        raise UsageError(f"{text}: the model has modes " + ", ".join(model.modes)
                         + ": write MODEL:MODE")
    return model, mode
