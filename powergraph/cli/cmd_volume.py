"""``powergraph volume MODEL [--json] [--plot FILE]``: component volumes (docs/volume.md).

JSON: ``{name, components: {id: volume_mm3}, total_mm3, total_exact_profile_mm3,
parts: {id: {name, shape, equation, count, unit_volume_mm3, volume_mm3,
exact_profile_mm3, profile_error}}}``.
"""
from __future__ import annotations

import argparse
from pathlib import Path

from powergraph.cli.common import (check_figure_path, load, new_axes, print_json, save_figure,
                                   say_wrote)

#: Tooth numbers of the pitch-circle error plot.
PLOT_TEETH = range(12, 81)


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``volume`` command."""
    parser = subparsers.add_parser(
        "volume", help="component volumes and total (Pan & Wang 2019)",
        description="Volume of each component that has a geometry block, by Pan & Wang "
                    "(2019) Eqs. (1)-(7), times its count, and the total (Eq. 8), in mm³. "
                    "Gears and cycloid discs also get the volume of their exact generated "
                    "outline, to show the error of the paper's circle approximations.")
    parser.add_argument("model", help="model file (YAML)")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.add_argument("--plot", metavar="FILE",
                        help="also plot the pitch-circle volume error against the tooth "
                             "number (z = 12…80, the model's gears marked); .png/.svg/.pdf")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Run ``volume``; returns the exit status (errors propagate to main: exit 2)."""
    from powergraph.analyses.volume import volume

    target = check_figure_path(args.plot, "--plot") if args.plot else None
    model = load(args.model)
    result = volume(model)
    if args.json:
        print_json(result.to_dict())
    else:
        print(result.text_report())
    if target is not None:
        _plot(target, model, result)
        say_wrote(target, data_on_stdout=args.json)
    return 0


def _plot(target: Path, model, result) -> None:
    from powergraph.analyses.volume import pitch_circle_error, pitch_circle_errors

    table = pitch_circle_errors(PLOT_TEETH)
    marks = {f"{part.name or cid} (component {cid})":
             (model.components[cid].teeth, pitch_circle_error(model.components[cid].teeth))
             for cid, part in result.components.items()
             if part.shape == "gear" and part.exact_mm3 is not None}
    ax = table.plot(ax=new_axes((6.4, 4.0)), marks=marks)
    save_figure(ax.figure, target, dpi=150, bbox_inches="tight")
