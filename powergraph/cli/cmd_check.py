"""``powergraph check MODEL``: validate a model and say what the train is.

Beyond the file format, ``check`` runs the train's analysis: the given speeds must
determine the motion, and the ports' powers/torques the loads (a train with P ports and D
degrees of freedom takes the power or torque of P - D ports), so that a model that passes
``check`` also solves.

The model's warnings (``Model.warnings``: a planetary set that cannot be built, ...;
docs/feasibility.md) follow the ok line on stdout as ``warning: PATH: MESSAGE`` lines, and
the status stays 0. With ``--strict`` a model with warnings is refused: one
``powergraph: error: PATH: MESSAGE`` line per warning on stderr, exit status 2.
"""
from __future__ import annotations

import argparse

from powergraph.cli.common import add_strict, load, print_caveats, refuse_caveats


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser("check", help="validate a model file",
                            description="Validate a model file: format, references, that the "
                                        "given speeds determine the motion and the given "
                                        "powers/torques the loads.")
    parser.add_argument("model", help="model file (YAML)")
    add_strict(parser)
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from powergraph.kinematics import solve_speeds
    from powergraph.statics import solve
    from powergraph.statics.equilibrium import loads_of

    model = load(args.model)
    if args.strict and model.warnings:
        return refuse_caveats(model.warnings)
    if model.modes:
        return _check_modes(args, model)
    kin = solve_speeds(model)
    needed = loads_of(model, kin).needed
    solve(model)  # missing or contradictory loads, power directions
    given = sum(p.power is not None or p.torque is not None for p in model.ports)
    loads = (f"loads of {given} of {needed} port(s) given" if given
             else "no load given (solved per watt of input)")
    balances = sum(bus.battery is not None for bus in model.buses.values())
    if balances:
        loads += f" and {balances} bus balance(s)"
    meshes = len(model.meshes)
    print(f"{args.model}: ok — {model.name}: {len(model.components)} components, "
          f"{len(model.bodies)} bodies, {meshes} mesh{'es' if meshes != 1 else ''}, "
          f"{kin.dof} DOF, {loads}")
    print_caveats(model.warnings)
    return 0


def _check_modes(args: argparse.Namespace, model) -> int:
    """A model with modes: every mode must solve (docs/modes.md)."""
    from powergraph.statics.case import TrainCase
    from powergraph.statics.modes import designed_dof

    dofs = {}
    for mode in model.modes:
        case = TrainCase.of(model, mode)
        case.point().required()
        dofs[mode] = designed_dof(case.base_model)
    each = (f"each solves with {next(iter(dofs.values()))} DOF" if len(set(dofs.values())) == 1
            else "DOF " + ", ".join(f"{m} {d}" for m, d in dofs.items()))
    print(f"{args.model}: ok — {model.name}: {len(model.components)} components, "
          f"{len(model.shift_elements)} shift element{'s' * (len(model.shift_elements) != 1)}, "
          f"modes {', '.join(model.modes)}: "
          f"{each}")
    print_caveats(model.warnings)
    return 0
