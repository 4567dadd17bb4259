"""``powergraph mesh Z1 Z2 [--internal] [--module M] [--pressure-angle DEG] [--helix DEG]
[--shift X1 X2] [--addendum HA] [--mu MU] [--json]``: contact ratios, Ohlendorf's loss
factor and the basic efficiency of one involute pair (docs/losses.md)."""
from __future__ import annotations

import argparse

from powergraph.cli.common import print_json
from powergraph.errors import UsageError


def _teeth(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a whole number: {text!r}") from None
    return value


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser(
        "mesh", help="contact ratios, loss factor and efficiency of an involute pair",
        description="Contact ratio, addendum contact ratios and Ohlendorf's tooth loss "
                    "factor H_V of an involute pair; with --mu its basic efficiency "
                    "1 - mu*H_V.")
    parser.add_argument("z1", type=_teeth, help="teeth of the pinion (external)")
    parser.add_argument("z2", type=_teeth, help="teeth of the wheel")
    parser.add_argument("--internal", action="store_true", help="the wheel is an internal gear")
    parser.add_argument("--module", type=float, default=1.0, metavar="M",
                        help="normal module, mm (default 1)")
    parser.add_argument("--pressure-angle", type=float, default=20.0, metavar="DEG",
                        help="normal pressure angle, degrees (default 20)")
    parser.add_argument("--helix", type=float, default=0.0, metavar="DEG",
                        help="helix angle, degrees (default 0)")
    parser.add_argument("--shift", type=float, nargs=2, default=(0.0, 0.0),
                        metavar=("X1", "X2"), help="profile shift coefficients (default 0 0)")
    parser.add_argument("--addendum", type=float, default=1.0, metavar="HA",
                        help="addendum coefficient (default 1)")
    parser.add_argument("--mu", type=float, default=None, metavar="MU",
                        help="mean coefficient of friction: gives the basic efficiency")
    parser.add_argument("--json", action="store_true", help="print a JSON object")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from powergraph.gears.mesh_loss import MeshGeometry, mesh_loss
    from powergraph.errors import ModelError

    geometry = MeshGeometry(teeth_1=args.z1, teeth_2=args.z2, internal=args.internal,
                            module=args.module, pressure_angle_deg=args.pressure_angle,
                            helix_angle_deg=args.helix, shift_1=args.shift[0],
                            shift_2=args.shift[1], addendum=args.addendum)
    try:
        result = mesh_loss(geometry, mu=args.mu, strict=False)
    except ModelError as exc:
        raise UsageError(str(exc)) from None
    if args.json:
        print_json(result.to_dict())
    else:
        print(result.text_report())
    return 0
