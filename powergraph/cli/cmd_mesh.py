"""``powergraph mesh Z1 Z2 [--internal] [--module M] [--pressure-angle DEG] [--helix DEG]
[--shift X1 X2] [--addendum HA] [--mu MU] [--json]``: contact ratios, Ohlendorf's loss
factor and the basic efficiency of one involute pair (docs/losses.md)."""
from __future__ import annotations

import argparse

from powergraph.cli.common import number_option, print_json, whole_option
from powergraph.errors import UsageError
from powergraph.model.schema_parts import MAX_TEETH


#: The option that gives each field of the geometry, to name it in messages.
OPTIONS = {"teeth_1": "Z1", "teeth_2": "Z2", "module": "--module",
           "pressure_angle_deg": "--pressure-angle", "helix_angle_deg": "--helix",
           "shift_1": "--shift X1", "shift_2": "--shift X2", "addendum": "--addendum"}


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser(
        "mesh", help="contact ratios, loss factor and efficiency of an involute pair",
        description="Contact ratio, addendum contact ratios and Ohlendorf's tooth loss "
                    "factor H_V of an involute pair; with --mu its basic efficiency "
                    "1 - mu*H_V.")
    parser.add_argument("z1", help="teeth of the pinion (external)")
    parser.add_argument("z2", help="teeth of the wheel")
    parser.add_argument("--internal", action="store_true", help="the wheel is an internal gear")
    parser.add_argument("--module", default="1", metavar="M",
                        help="normal module, mm (default 1)")
    parser.add_argument("--pressure-angle", default="20", metavar="DEG",
                        help="normal pressure angle, degrees (default 20)")
    parser.add_argument("--helix", default="0", metavar="DEG",
                        help="helix angle, degrees (default 0)")
    parser.add_argument("--shift", nargs=2, default=("0", "0"),
                        metavar=("X1", "X2"), help="profile shift coefficients (default 0 0)")
    parser.add_argument("--addendum", default="1", metavar="HA",
                        help="addendum coefficient (default 1)")
    parser.add_argument("--mu", default=None, metavar="MU",
                        help="mean coefficient of friction: gives the basic efficiency")
    parser.add_argument("--json", action="store_true", help="print a JSON object")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from powergraph.gears.mesh_loss import MeshGeometry, mesh_loss
    from powergraph.errors import ModelError

    geometry = MeshGeometry(
        teeth_1=whole_option(args.z1, "Z1", 3, MAX_TEETH),
        teeth_2=whole_option(args.z2, "Z2", 3, MAX_TEETH), internal=args.internal,
        module=number_option(args.module, "--module"),
        pressure_angle_deg=number_option(args.pressure_angle, "--pressure-angle"),
        helix_angle_deg=number_option(args.helix, "--helix"),
        shift_1=number_option(args.shift[0], "--shift X1"),
        shift_2=number_option(args.shift[1], "--shift X2"),
        addendum=number_option(args.addendum, "--addendum"))
    mu = None if args.mu is None else number_option(args.mu, "--mu")
    try:
        result = mesh_loss(geometry, mu=mu, strict=False)
    except ModelError as exc:
        field = exc.message.split(" ", 1)[0]
        place = OPTIONS.get(field, "--mu" if "friction" in exc.message else None)
        raise UsageError(exc.message, place) from None
    if args.json:
        print_json(result.to_dict())
    else:
        print(result.text_report())
    return 0
