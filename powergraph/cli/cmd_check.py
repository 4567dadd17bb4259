"""``powergraph check MODEL``: validate only (and say what the train is)."""
from __future__ import annotations

import argparse

from powergraph.cli.common import load


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser("check", help="validate a model file",
                            description="Validate a model file: format, references, and "
                                        "that the given speeds determine the motion.")
    parser.add_argument("model", help="model file (YAML)")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from powergraph.kinematics import solve_speeds

    model = load(args.model)
    kin = solve_speeds(model)
    meshes = len(model.meshes)
    print(f"{args.model}: ok — {model.name}: {len(model.components)} components, "
          f"{len(model.bodies)} bodies, {meshes} mesh{'es' if meshes != 1 else ''}, "
          f"{kin.dof} DOF")
    return 0
