"""``powergraph solve MODEL [--json] [--method virtual-power|wang2021] [--mesh-efficiency E]
[--backdrive] [--mode NAME] [--strict]`` (``--strict``: a model with warnings is refused
before solving, exit 2)."""
from __future__ import annotations

import argparse

from powergraph.cli.common import add_strict, load, print_json, refuse_caveats

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
    parser.set_defaults(handler=run)


def _result_options(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--backdrive", action="store_true",
                        help="report the train driven from its output: the output becomes "
                             "the input and is fed the power the forward solve takes in")


def run(args: argparse.Namespace) -> int:
    model = load(args.model, args.mesh_efficiency)
    if args.strict and model.warnings:
        return refuse_caveats(model.warnings)
    if model.modes or args.mode is not None or _has_freewheels(model):
        from powergraph.cli.cmd_modes import solve_one_mode

        result = solve_one_mode(model, args.mode, args.method)
        print_json(result.to_dict()) if args.json else print(result.text_report())
        return 0
    if args.backdrive:
        model = _backdriven(model)
    if args.method == "wang2021":
        from powergraph.methods.wang2021 import solve_wang2021

        result = solve_wang2021(model)
    else:
        from powergraph.statics import solve

        result = solve(model)
    fluctuation = _cycloid_fluctuation(model)
    if args.json:
        data = result.to_dict()
        if fluctuation is not None:
            data["cycloid_fluctuation"] = fluctuation.to_dict()
        print_json(data)
    else:
        print(result.text_report())
        if fluctuation is not None:
            print()
            print(fluctuation.text_report())
    return 0


def _backdriven(model):
    """The model driven from its output at the forward input power (one input, one output)."""
    from powergraph.errors import UsageError
    from powergraph.kinematics.variants import backdriven
    from powergraph.statics import solve

    if len(model.inputs) != 1 or len(model.outputs) != 1:
        raise UsageError("--backdrive needs a train with one input and one output port "
                         f"(this one has {len(model.inputs)} and {len(model.outputs)})")
    return backdriven(model, solve(model).input_power)


def _has_freewheels(model) -> bool:
    return any(e.kind == "freewheel" for e in model.shift_elements)


def _cycloid_fluctuation(model):
    """The output's ratio fluctuation from meshes carrying a ``cycloid`` block (docs/cycloid.md)."""
    if not any("cycloid" in link.blocks for link in model.meshes):
        return None
    from powergraph.analyses.cycloid import train_fluctuation

    return train_fluctuation(model)
