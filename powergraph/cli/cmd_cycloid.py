"""``powergraph cycloid``: ratio fluctuation of a cycloid stage (Csobán 2021; docs/cycloid.md).

Two forms::

    powergraph cycloid --module M --teeth Z1 --error D [--shift X] [--rc RC] [--json] [--plot FILE]
    powergraph cycloid --fit --module M [--shift X] [--rc RC] [--json] [--plot FILE]
    powergraph cycloid --model MODEL [--json]     (a train's meshes with a cycloid block)

matplotlib is imported only when ``--plot`` is given.
"""
from __future__ import annotations

import argparse

from powergraph.cli.common import (check_figure_path, new_axes, number_option, print_json,
                                   save_figure, say_wrote, whole_option)
from powergraph.errors import UsageError

#: Modules accepted, mm (far beyond any gear, inside what the geometry computes).
MODULE_RANGE = (1e-6, 1e6)
#: Profile-shift coefficients accepted: 0 < x < 1, but below 1e-6 the trochoid's
#: curvature leaves the floating-point range.
SHIFT_RANGE = (1e-6, 1.0)
#: A profile error below this fraction of the module is below the resolution of the
#: contact computation (double precision): give 0 for an exact profile.
SMALLEST_RELATIVE_ERROR = 1e-12


def register(subparsers) -> None:
    """Add the ``cycloid`` command to the ``powergraph`` parser."""
    parser = subparsers.add_parser(
        "cycloid", help="cycloid-stage ratio fluctuation from a profile error (Csobán 2021)",
        description="Ratio fluctuation of a cycloid stage (disc z1 teeth, z1 + 1 pins) whose "
                    "profile is off by D mm along its normal (Csobán 2021). With --fit, "
                    "repeat the paper's study for one module and refit "
                    "a*d + b*d*z1^-1.5.")
    parser.add_argument("--model", metavar="MODEL",
                        help="a model file: carry the fluctuation of each mesh with a "
                             "`cycloid` block to the train's output")
    parser.add_argument("--module", metavar="M",
                        help=f"module, mm ({MODULE_RANGE[0]:g} to {MODULE_RANGE[1]:g})")
    parser.add_argument("--teeth", metavar="Z1", help="disc teeth z1 (>= 3)")
    parser.add_argument("--error", metavar="D", help="profile error d, mm (>= 0)")
    parser.add_argument("--shift", default="0.3", metavar="X",
                        help="profile-shift coefficient x, 1e-6 <= x < 1 (default 0.3)")
    parser.add_argument("--rc", default="1", metavar="RC",
                        help="pin-radius factor rc*: pin radius = rc*·m (default 1)")
    parser.add_argument("--fit", action="store_true",
                        help="the paper's grid (z1 = 9, 25, 43, 53, 117; IT5…IT9) and refit")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.add_argument("--plot", metavar="FILE",
                        help="figure (.png/.svg/.pdf): ratio against crank angle, or with "
                             "--fit the maxima and fitted surfaces")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Compute, print, and draw if asked. Bad arguments raise :class:`UsageError`."""
    if args.model is not None:
        return _of_model(args)
    if args.module is None:
        raise UsageError("give --module M (with --teeth and --error, or --fit), or --model FILE")
    figure = check_figure_path(args.plot, "--plot") if args.plot else None
    module = number_option(args.module, "--module", *MODULE_RANGE)
    shift = number_option(args.shift, "--shift", *SHIFT_RANGE, below=True)
    rc = number_option(args.rc, "--rc", 0, above=True)
    if args.fit:
        if args.teeth is not None or args.error is not None:
            raise UsageError("--fit runs the paper's grid of teeth and errors: "
                             "give no --teeth or --error")
        from powergraph.analyses.cycloid import fluctuation_study

        result = fluctuation_study(module, shift=shift, rc=rc)
    else:
        if args.teeth is None or args.error is None:
            raise UsageError("give --teeth and --error (or --fit)")
        from powergraph.analyses.cycloid import cycloid_fluctuation
        from powergraph.analyses.cycloid.geometry import MAX_TEETH

        teeth = whole_option(args.teeth, "--teeth", 3, MAX_TEETH)
        error = number_option(args.error, "--error", 0)
        if 0 < error < SMALLEST_RELATIVE_ERROR * module:
            raise UsageError(f"--error {args.error}: below {SMALLEST_RELATIVE_ERROR:g} of the "
                             "module, too small to resolve; give 0 for an exact profile")
        result = cycloid_fluctuation(module, teeth, error, shift, rc)
    if figure is not None:
        axes = (new_axes((7.5, 6.0), projection="3d") if args.fit else new_axes((7.5, 4.5)))
        ax = result.plot(ax=axes)
        save_figure(ax.figure, figure)
    if args.json:
        print_json(result.to_dict())
    else:
        print(result.text_report())
    if figure is not None:
        say_wrote(figure, data_on_stdout=args.json)
    return 0


def _of_model(args: argparse.Namespace) -> int:
    """``--model FILE``: the train's output fluctuation (the stage values from the file)."""
    given = [f"--{n}" for n in ("module", "teeth", "error", "plot") if getattr(args, n)]
    if given or args.fit:
        raise UsageError(f"--model takes the stages from the file: give no "
                         f"{', '.join(given) or '--fit'}")
    from powergraph.analyses.cycloid import train_fluctuation
    from powergraph.cli.common import load

    model = load(args.model)
    if not any("cycloid" in link.blocks for link in model.meshes):
        raise UsageError(f"{args.model}: no mesh has a cycloid block (docs/cycloid.md)")
    result = train_fluctuation(model)
    print_json(result.to_dict()) if args.json else print(result.text_report())
    return 0
