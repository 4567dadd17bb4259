"""``powergraph formula MODEL [--latex] [--json] [--let NAME=EXPR ...]``: closed-form ratio
and efficiency (sympy is imported only when the command runs)."""
from __future__ import annotations

import argparse

from powergraph.cli.cmd_modes import add_mode_option
from powergraph.cli.common import load, print_json
from powergraph.errors import UsageError


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser(
        "formula", help="closed-form ratio and efficiency in the tooth numbers",
        description="Derive the ratio as a rational function of the tooth numbers (z_<id>) "
                    "and the efficiency as a function of the tooth numbers and the basic "
                    "efficiencies (eta_<i> of links[i]), for the power-flow direction "
                    "pattern at the model's values, with the conditions that keep it.")
    parser.add_argument("model", help="model file (YAML)")
    output = parser.add_mutually_exclusive_group()
    output.add_argument("--json", action="store_true",
                        help="print a JSON object (ratio, efficiency, latex, directions, "
                             "conditions, symbols)")
    output.add_argument("--latex", action="store_true", help="print the formulas as LaTeX")
    parser.add_argument("--let", action="append", default=[], metavar="NAME=EXPR",
                        help="substitute a relation between symbols before simplifying, "
                             "e.g. --let z_4=z_5-1 (one-tooth-difference cycloid stage); "
                             "repeatable; it must hold at the model's values")
    add_mode_option(parser, "derive the formulas of")
    parser.set_defaults(handler=run)


def parse_lets(items: list[str]) -> dict[str, str]:
    """``["z_4=z_5-1"]`` -> ``{"z_4": "z_5-1"}``.

    Examples
    --------
    >>> parse_lets(["z_4 = z_5 - 1"])
    {'z_4': 'z_5 - 1'}
    """
    out = {}
    for item in items:
        name, sep, expr = item.partition("=")
        if not sep or not name.strip() or not expr.strip():
            raise UsageError(f"--let {item}: expected NAME=EXPR, e.g. z_4=z_5-1")
        out[name.strip()] = expr.strip()
    return out


def run(args: argparse.Namespace) -> int:
    relations = parse_lets(args.let)
    model = load(args.model)
    from powergraph.analyses.formula import derive_formulas
    from powergraph.analyses.formula.report import latex_report

    result = derive_formulas(model, relations, args.mode)
    if args.json:
        print_json(result.to_dict())
    elif args.latex:
        print(latex_report(result))
    else:
        print(result.text_report())
    return 0
