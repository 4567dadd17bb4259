"""``powergraph solve MODEL [--json] [--method virtual-power|wang2021] [--mesh-efficiency E]
[--backdrive] [--mode NAME] [--oil-temperature T] [--strict]`` (``--strict``: a model with
warnings is refused before solving, exit 2; ``--oil-temperature``: the oil at T degC, its
heat balance set aside)."""
from __future__ import annotations

import argparse

from powergraph.cli.common import (add_oil_temperature, add_strict, load, oil_temperature,
                                   print_json, refuse_caveats)
from powergraph.model.lubricant import fixed_temperature

METHODS = ("virtual-power", "wang2021")


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser("solve", help="solve speeds, torques, power flow and efficiency",
                            description="Solve a gear-train model and report speeds, "
                                        "torques, per-mesh virtual power and loss, "
                                        "and the efficiency.")
    parser.add_argument("model", help="model file (YAML)")
    parser.add_argument("--json", action="store_true",
                        help="print the JSON object (docs/format.md)")
    parser.add_argument("--method", choices=METHODS, default="virtual-power",
                        help="virtual-power (default, any train) or wang2021 (the seed "
                             "paper's split/virtual power method, RV-type trains)")
    parser.add_argument("--mesh-efficiency", metavar="E",
                        help="override every mesh's basic efficiency")
    add_strict(parser)
    _result_options(parser)
    parser.add_argument("--mode", metavar="NAME",
                        help="solve the model in this mode of its modes table (docs/modes.md)")
    add_oil_temperature(parser)
    parser.set_defaults(handler=run)


def _result_options(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--backdrive", action="store_true",
                        help="report the train driven from its output: the output becomes "
                             "the input and is fed the power the forward solve takes in")


def run(args: argparse.Namespace) -> int:
    model = load(args.model, args.mesh_efficiency)
    if args.oil_temperature is not None:
        model = fixed_temperature(model, oil_temperature(args.oil_temperature))
    if args.strict and model.warnings:
        return refuse_caveats(model.warnings)
    from powergraph.statics.case import TrainCase

    case = TrainCase.of(model, args.mode, args.backdrive)
    if args.method == "wang2021":
        result = _wang2021(case)
    else:
        result = case.point().required().report
    if args.json:
        print_json(result.to_dict())
    else:
        print(result.text_report())
        if any("cycloid" in link.blocks for link in model.meshes):
            print(f"\nthe output's ratio fluctuation from the cycloid stages: "
                  f"powergraph cycloid --model {args.model}")
    return 0


def _wang2021(case):
    """The seed paper's method: a plain train, forward or back-driven."""
    from powergraph.errors import UsageError
    from powergraph.methods.wang2021 import solve_wang2021
    from powergraph.statics.case import TrainCase

    if case.shifting:
        raise UsageError("--method wang2021 takes trains without shift elements; "
                         "--mode works with the virtual-power method")
    model = case.model
    if case.backdrive:
        from powergraph.kinematics.variants import backdriven

        model = backdriven(model, TrainCase.of(model).point().result.input_power)
    return solve_wang2021(model)
