"""``powergraph map MODEL --torque A:B:N --speed C:D:N [--rated T] [-o FILE] [--json]``:
efficiency over output torque (N·m) × input speed (rpm)."""
from __future__ import annotations

import argparse

import numpy as np

from powergraph.cli.common import load, print_json, say_wrote, write_atomically


def span_arg(text: str) -> np.ndarray:
    """argparse type for ``START:STOP:N`` (N evenly spaced values, ends included).

    >>> span_arg("100:400:4").tolist()
    [100.0, 200.0, 300.0, 400.0]
    """
    parts = text.split(":")
    try:
        if len(parts) == 1:
            return np.array([float(parts[0])])
        start, stop, count = float(parts[0]), float(parts[1]), int(parts[2])
    except (ValueError, IndexError):
        raise argparse.ArgumentTypeError(f"expected START:STOP:N, got {text!r}") from None
    if len(parts) != 3 or not 1 <= count <= 500:
        raise argparse.ArgumentTypeError(f"expected START:STOP:N with 1 <= N <= 500, got {text!r}")
    return np.linspace(start, stop, count)


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser(
        "map", help="efficiency over output torque × input speed",
        description="Efficiency map of a 1-DOF train with one input and one output: the "
                    "output drives a load torque at each input speed. Flat unless a mesh's "
                    "friction depends on the load (friction: {model: iso14179, ...}) or "
                    "bearings carry friction or drag (docs/losses.md).")
    parser.add_argument("model", help="model file (YAML)")
    parser.add_argument("--torque", type=span_arg, required=True, metavar="A:B:N",
                        help="output load torques, N·m")
    parser.add_argument("--speed", type=span_arg, required=True, metavar="C:D:N",
                        help="input speeds, rpm")
    parser.add_argument("--rated", type=float, default=None, metavar="T",
                        help="rated output torque, N·m (drawn as a line)")
    parser.add_argument("-o", "--output", metavar="FILE", help="write the map (PNG/SVG/PDF)")
    parser.add_argument("--json", action="store_true", help="print a JSON object")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from powergraph.analyses.efficiency_map import efficiency_map

    result = efficiency_map(load(args.model), args.torque, args.speed, args.rated)
    print_json(result.to_dict()) if args.json else print(result.text_report())
    if args.output:
        ax = result.plot()
        write_atomically(args.output, lambda tmp: ax.figure.savefig(tmp, dpi=150,
                                                                    bbox_inches="tight"))
        say_wrote(args.output, data_on_stdout=args.json)
    return 0
