"""``powergraph shifts GEARSET --ratios R1,R2,... [--tolerance 1%] [--top K] [--json]
[-o FILE.yaml]``: clutches and brakes on a 2-DOF gearset for a set of ratios
(docs/modes.md), the best plan checked through the gear table."""
from __future__ import annotations

import argparse
from pathlib import Path

from powergraph.cli.cmd_synthesize import parse_tolerance
from powergraph.cli.common import (check_output_file, load, number_option, print_json,
                                   say_wrote, whole_option, write_atomically)
from powergraph.errors import UsageError
from powergraph.model.schema_parts import MAX_RATIO, MIN_RATIO

#: Most target ratios (gears) at once.
MAX_GEARS = 12


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser(
        "shifts", help="place clutches and brakes on a 2-DOF gearset for a set of ratios",
        description="Find the input clutches and brakes on the coaxial members of a 2-DOF "
                    "gearset that give every target ratio, fewest elements first; the best "
                    "plan is written as a model with a modes table and solved gear by gear "
                    "(docs/modes.md).")
    parser.add_argument("model", help="the gearset (YAML): 2 DOF, one output port")
    parser.add_argument("--ratios", required=True, metavar="R1,R2,...",
                        help="target ratios, input/output speed, negative for reverse")
    parser.add_argument("--tolerance", default="1%", metavar="T",
                        help="relative tolerance on each ratio, e.g. 1%% or 0.01 "
                             "(default 1%%)")
    parser.add_argument("--top", default="5", metavar="K", help="plans kept (default 5)")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.add_argument("-o", "--output", metavar="FILE.yaml",
                        help="write the best plan as a transmission model")
    parser.set_defaults(handler=run)


def parse_ratios(text: str) -> list[float]:
    """``--ratios``: comma-separated ratios, each within a model file's ratio range.

    >>> parse_ratios("4.7, 2.1,1,-3.3")
    [4.7, 2.1, 1.0, -3.3]
    """
    parts = [p.strip() for p in text.split(",")]
    if not 1 <= len(parts) <= MAX_GEARS:
        raise UsageError(f"--ratios {text}: give 1 to {MAX_GEARS} ratios separated by commas")
    ratios = [number_option(p, "--ratios", -MAX_RATIO, MAX_RATIO) for p in parts]
    for ratio in ratios:
        if abs(ratio) < MIN_RATIO:
            raise UsageError(f"--ratios {text}: a ratio cannot be zero or below {MIN_RATIO:g} "
                             "in size")
    return ratios


def run(args: argparse.Namespace) -> int:
    import yaml

    from powergraph.analyses.gear_table import gear_table
    from powergraph.analyses.shift_placement import (place_shift_elements,
                                                     transmission_document)
    from powergraph.model import load_model_data, model_from_dict

    target = check_output_file(args.output, "-o", (".yaml", ".yml")) if args.output else None
    ratios = parse_ratios(args.ratios)
    tolerance = parse_tolerance(args.tolerance)
    top = whole_option(args.top, "--top", 1, 100)
    model = load(args.model)
    placement = place_shift_elements(model, ratios, tolerance, top)
    document = transmission_document(load_model_data(args.model), model, placement.plans[0])
    table = gear_table(model_from_dict(document, source=str(target or args.model)))
    if args.json:
        print_json({**placement.to_dict(), "gear_table": table.to_dict()})
    else:
        print(placement.text_report())
        print("\nthe best plan solved gear by gear (docs/modes.md):\n")
        print(table.text_report())
    if target is not None:
        text = yaml.safe_dump(document, sort_keys=False, allow_unicode=True)
        write_atomically(target, lambda tmp: Path(tmp).write_text(text, encoding="utf-8"))
        say_wrote(target, data_on_stdout=args.json)
    return 0
