"""``powergraph modes MODEL [--json] [-o FILE] [--mesh-efficiency E]``: the gear table
(docs/modes.md); and the ``--mode`` option of the commands that evaluate one gear."""
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
from powergraph.errors import ModelError, UsageError


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser("modes", help="gear table of a train with modes",
                            description="Per mode: engaged elements, ratio, step, "
                                        "efficiency forward and coasting, element torques, "
                                        "slip speeds, drag; the spread. For a hybrid: each "
                                        "mode's DOF, inactive ports, speed relation, "
                                        "machines, battery power and electrical share "
                                        "(docs/modes.md).")
    parser.add_argument("model", help="model file (YAML) with a modes table")
    parser.add_argument("--json", action="store_true", help="print the JSON object")
    parser.add_argument("-o", "--output", metavar="FILE",
                        help="write a chart of ratios and efficiencies (.png, .svg or .pdf)")
    parser.add_argument("--mesh-efficiency", metavar="E",
                        help="every mesh at E")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from powergraph.analyses.gear_table import gear_table

    target = check_figure_path(args.output) if args.output else None
    model = load(args.model, args.mesh_efficiency)
    if not model.modes:
        raise ModelError("the model has no modes table (docs/modes.md)", "modes")
    table = gear_table(model)
    if target is not None:
        several = [r for r in table.rows if r.ratio is None]
        if several:
            raise UsageError(f"-o: the chart draws each mode's ratio; mode "
                             f"{several[0].mode!r} has {several[0].dof} DOF (no single "
                             "ratio): see its speed relation in the table or --json")
    print_json(table.to_dict()) if args.json else print(table.text_report())
    if target is not None:
        ax = new_axes((7.0, 4.2))
        table.plot(ax=ax)
        save_figure(ax.figure, target, dpi=150, bbox_inches="tight")
        say_wrote(target, data_on_stdout=args.json)
    return 0


def add_mode_option(parser, what: str) -> None:
    """The ``--mode NAME`` option of a command that evaluates one gear of a model."""
    parser.add_argument("--mode", metavar="NAME",
                        help=f"{what} the model in this mode of its modes table "
                             "(freewheels decided at the model's own load; docs/modes.md)")
