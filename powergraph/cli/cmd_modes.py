"""``powergraph modes MODEL [--json] [-o FILE] [--mesh-efficiency E]``: the gear table
(docs/modes.md); and the ``--mode`` option of ``solve``."""
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
                                        "slip speeds, drag; the spread (docs/modes.md).")
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
    print_json(table.to_dict()) if args.json else print(table.text_report())
    if target is not None:
        ax = new_axes((7.0, 4.2))
        table.plot(ax=ax)
        save_figure(ax.figure, target, dpi=150, bbox_inches="tight")
        say_wrote(target, data_on_stdout=args.json)
    return 0


def solve_one_mode(model, mode: str | None, method: str = "virtual-power"):
    """``solve --mode``: the model solved in ``mode`` (a ModeResult). A model with modes
    needs ``--mode``; a model without cannot take it."""
    if not model.modes and mode is not None:
        raise UsageError(f"--mode {mode}: the model has no modes table")
    if model.modes and mode is None:
        raise UsageError("the model has modes " + ", ".join(model.modes)
                         + ": choose one with --mode NAME (or see them all with "
                           "`powergraph modes`)")
    if model.modes and mode not in model.modes:
        raise UsageError(f"--mode {mode}: unknown mode (the model's modes: "
                         + ", ".join(model.modes) + ")")
    if method != "virtual-power":
        raise UsageError("--mode works with the virtual-power method")
    from powergraph.statics.modes import solve_mode

    result = solve_mode(model, mode)
    if result.result is None:
        raise ModelError(result.verdict, f"modes.{mode}" if mode is not None else "links")
    return result


def add_mode_option(parser, what: str) -> None:
    """The ``--mode NAME`` option of a command that evaluates one gear of a model."""
    parser.add_argument("--mode", metavar="NAME",
                        help=f"{what} the model in this mode of its modes table "
                             "(freewheels decided at the model's own load; docs/modes.md)")


def gear_model(model, mode: str | None):
    """The model of one gear: ``model`` itself when it has neither modes nor freewheels,
    else the plain train of ``mode`` (engaged elements rigid, freewheels decided at the
    model's own load by :func:`solve_one_mode`). For the sweep, the map and the tolerance
    analysis, which evaluate a plain train at many values."""
    if mode is None and not model.modes and not any(
            e.kind == "freewheel" for e in model.shift_elements):
        return model
    return solve_one_mode(model, mode).result.model


def compare_row_of(text: str, mesh_efficiency, compare_row):
    """``compare``'s row of ``MODEL`` or ``MODEL:MODE``: a mode is compared as its gear
    (freewheels decided), back-driven as coasting with its freewheels decided again."""
    import dataclasses
    import os

    path, mode = text, None
    if not os.path.exists(text) and ":" in text:     # False, not an error, for any name
        path, mode = text.rsplit(":", 1)
    model = load(path, mesh_efficiency)
    if not model.modes and mode is None:
        return compare_row(model)
    if mode is None:
        raise UsageError(f"{text}: the model has modes " + ", ".join(model.modes)
                         + ": write MODEL:MODE")
    from powergraph.analyses.gear_table import coasting

    forward = solve_one_mode(model, mode)
    gear = forward.result.model
    row = compare_row(gear)
    coast = coasting(model, forward)
    if coast.result is None:
        return dataclasses.replace(row, backdrive_efficiency=None,
                                   backdrive_self_locking=None,
                                   backdrive_note=f"coasting: {coast.verdict}")
    return dataclasses.replace(row, backdrive_efficiency=coast.result.efficiency,
                               backdrive_self_locking=coast.result.self_locking,
                               backdrive_note=None)
