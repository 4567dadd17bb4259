"""``powergraph tolerance MODEL --samples N [--seed S] [--spec SPEC ...] [--json] [-o FILE]``.

Monte Carlo over the model's ``tolerances:`` block (docs/tolerance.md): statistics of the
lost motion, ratio fluctuation and efficiency, the yield of each specification with its
95 % Wilson interval, and the Sobol indices of every toleranced PATH.
"""
from __future__ import annotations

import argparse

from powergraph.cli.cmd_modes import add_mode_option
from powergraph.cli.common import (check_figure_path, load, print_json, say_wrote,
                                   save_figure, whole_option)
from powergraph.errors import UsageError


#: Largest --samples (memory grows with it) and --sobol-samples; largest --seed.
MAX_SAMPLES = 10**7
MAX_SOBOL = 2**20
MAX_SEED = 2**63 - 1


def _sobol(text: str) -> int:
    value = whole_option(text, "--sobol-samples", 0, MAX_SOBOL)
    if value != 0 and (value < 2 or value & (value - 1)):
        raise UsageError(f"--sobol-samples {text}: must be a power of 2 (or 0: none)")
    return value


def register(subparsers) -> None:
    """Add the ``tolerance`` command."""
    parser = subparsers.add_parser(
        "tolerance", help="Monte Carlo tolerance analysis: lost motion, fluctuation, yield, "
                          "Sobol indices",
        description="Sample the model's tolerances: block and report, over the units, the "
                    "output lost motion (worst case within a unit), the cycloid ratio "
                    "fluctuation and the efficiency (mean, sd, p50, p95, p99.73, max), the "
                    "yield of each --spec with its 95 %% Wilson score interval, and the "
                    "first-order and total Sobol indices of every toleranced PATH (SALib).")
    parser.add_argument("model", help="YAML model file with a tolerances: block")
    parser.add_argument("--samples", default="100000", metavar="N",
                        help=f"Monte Carlo units, 2 to {MAX_SAMPLES:.0e} (default 100000)")
    parser.add_argument("--seed", default=None, metavar="S",
                        help="random seed (default: fresh, reported)")
    parser.add_argument("--spec", action="append", default=[], metavar="SPEC",
                        help='specification, e.g. "lost_motion<=1arcmin", '
                             '"fluctuation<=0.5%%", "efficiency>=0.85"; repeatable')
    parser.add_argument("--sobol-samples", default="4096", metavar="N",
                        help="base size N of the Sobol design, a power of 2 (N*(D+2) "
                             "evaluations; 0: no sensitivities; at most 2^20; default 4096)")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.add_argument("-o", "--output", metavar="FILE.png",
                        help="write the histograms and the tornado chart (.png/.svg/.pdf)")
    add_mode_option(parser, "analyse")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Analyse, print the report or JSON, write the figure if asked."""
    from powergraph.analyses.tolerance import parse_spec, tolerance_analysis

    target = check_figure_path(args.output, "-o") if args.output else None
    samples = whole_option(args.samples, "--samples", 2, MAX_SAMPLES)
    seed = None if args.seed is None else whole_option(args.seed, "--seed", 0, MAX_SEED)
    sobol_samples = _sobol(args.sobol_samples)
    specs = [parse_spec(text) for text in args.spec]
    from powergraph.statics.case import TrainCase

    model = TrainCase.of(load(args.model), args.mode).plain_model()
    progress = False if args.json else None   # None: a bar on a terminal, long runs
    result = tolerance_analysis(model, samples=samples, seed=seed, specs=specs,
                                sobol_samples=sobol_samples, progress=progress)
    if target is not None:
        _write_plot(result, target)
    if args.json:
        print_json(result.to_dict())
    else:
        print(result.text_report())
    if target is not None:
        say_wrote(target, data_on_stdout=args.json)
    return 0


def _write_plot(result, target) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    axes = result.plot()
    fig = axes[0].figure
    try:
        save_figure(fig, target, dpi=120)
    finally:
        plt.close(fig)
