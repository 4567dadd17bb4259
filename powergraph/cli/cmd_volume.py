"""``powergraph volume MODEL [--json] [--plot FILE]``: component volumes (seeds/004).

JSON: ``{name, components: {id: volume_mm3}, total_mm3, total_exact_profile_mm3,
parts: {id: {name, shape, equation, count, unit_volume_mm3, volume_mm3,
exact_profile_mm3, profile_error}}}``.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

from powergraph.cli.common import (
    aligned_table,
    check_figure_path,
    load,
    print_json,
    write_atomically,
)

#: Tooth numbers of the pitch-circle error plot.
PLOT_TEETH = range(12, 81)


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``volume`` command."""
    parser = subparsers.add_parser(
        "volume", help="component volumes and total (Pan & Wang 2019, seeds/004)",
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
        print(format_table(result))
    if target is not None:
        _plot(target, model, result)
        print(f"wrote {target}", file=sys.stderr if args.json else sys.stdout)
    return 0


def format_table(result) -> str:
    """Aligned text table: one row per component, then the total."""
    header = ("id", "name", "shape", "eq.", "count", "each mm³", "volume mm³",
              "exact outline mm³", "circle error")
    rows = [header]
    for cid, part in result.components.items():
        rows.append((cid, part.name or "", part.shape, part.equation, str(part.count),
                     f"{part.unit_mm3:,.1f}", f"{part.volume_mm3:,.1f}",
                     "" if part.exact_mm3 is None else f"{part.exact_mm3:,.1f}",
                     "" if part.profile_error is None else f"{100 * part.profile_error:+.3f} %"))
    rows.append(("", "total (Eq. 8)", "", "", "", "", f"{result.total_mm3:,.1f}",
                 f"{result.total_exact_profile_mm3:,.1f}", ""))
    lines = [f"{result.name}: volume by Pan & Wang (2019), lengths in mm"]
    lines += aligned_table(rows, {4, 5, 6, 7, 8}, rules_after=(0, len(rows) - 2))
    lines.append(f"total: {result.total_mm3:,.1f} mm³ = {result.total_litres:.4f} L")
    if any(part.exact_mm3 is not None for part in result.components.values()):
        lines.append("exact outline: gears and cycloid discs with their generated profile "
                     "(other parts as the paper);")
        lines.append("circle error: (paper − exact) / exact")
    return "\n".join(lines)


def _plot(target: Path, model, result) -> None:
    from powergraph.analyses.volume import pitch_circle_error, pitch_circle_errors
    from powergraph.plot.volume import pitch_circle_error_plot

    table = pitch_circle_errors(PLOT_TEETH)
    marks = {f"{part.name or cid} (component {cid})":
             (model.components[cid].teeth, pitch_circle_error(model.components[cid].teeth))
             for cid, part in result.components.items()
             if part.shape == "gear" and part.exact_mm3 is not None}
    import matplotlib.pyplot as plt

    ax = pitch_circle_error_plot(table.teeth, table.relative_error, marks=marks)
    try:
        write_atomically(target, lambda tmp: ax.figure.savefig(tmp, dpi=150,
                                                               bbox_inches="tight"))
    finally:
        plt.close(ax.figure)
