"""``powergraph export MODEL --to rexs|vgbx|fmu -o FILE [--mode M] [--speed C:D:N]
[--torque A:B:N]``: the train as a REXS gear unit (``.rexs`` XML, ``.rexsj`` JSON), as
a VECTO gearbox file (``.vgbx``, its ``.vtlm`` loss maps written beside it) or as an FMI
2.0 co-simulation FMU (``.fmu``, with the optional extra ``fmu``); see docs/exchange.md.
What the target format cannot hold is listed in one summary."""
from __future__ import annotations

import argparse
import json
from pathlib import Path

from powergraph.cli.cmd_map import SPEED_LIMIT, TORQUE_LIMIT, span_option
from powergraph.cli.common import check_output_file, load, say_wrote, write_text_atomically
from powergraph.errors import UsageError

#: The suffixes each target takes.
SUFFIXES = {"rexs": (".rexs", ".rexsj"), "vgbx": (".vgbx",), "fmu": (".fmu",)}


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser(
        "export", help="write a train as REXS (.rexs, .rexsj), a VECTO gearbox (.vgbx) or "
                       "an FMU (.fmu)",
        description="Write the train as a REXS gear unit (geometry, stages, planetary "
                    "stages, bearings, lubricant, the operating point as a load case) or "
                    "as a VECTO gearbox file with one loss map per forward gear, or as an "
                    "FMI 2.0 co-simulation FMU (needs pythonfmu: pip install -e "
                    "'.[fmu]'; the machine running it needs Python with powergraph) "
                    "(docs/exchange.md).")
    parser.add_argument("model", help="model file (YAML or REXS)")
    parser.add_argument("--to", required=True, choices=sorted(SUFFIXES),
                        help="the format to write")
    parser.add_argument("-o", "--output", required=True, metavar="FILE",
                        help="file to write (.rexs/.rexsj for rexs, .vgbx for vgbx, .fmu "
                             "for fmu)")
    parser.add_argument("--mode", default=None,
                        help="rexs: the mode to write, for a train with shift elements")
    parser.add_argument("--speed", default=None, metavar="C:D:N",
                        help="vgbx: the loss maps' input speeds, rpm (default: 8 from a "
                             "quarter to twice the model's input speed)")
    parser.add_argument("--torque", default=None, metavar="A:B:N",
                        help="vgbx: the loss maps' input torques, N·m, both signs (default: "
                             "9 from -2 to +2 times the model's input torque; a negative "
                             "START as --torque=-A:B:N)")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    target = check_output_file(args.output, "-o", SUFFIXES[args.to])
    if args.to == "vgbx":
        speeds = None if args.speed is None else span_option(args.speed, "--speed",
                                                             SPEED_LIMIT)
        torques = None if args.torque is None else span_option(args.torque, "--torque",
                                                               TORQUE_LIMIT)
        if args.mode is not None:
            raise UsageError("--mode: a .vgbx holds every forward mode; leave --mode out")
        return _vgbx(load(args.model), target, speeds, torques)
    if args.speed is not None or args.torque is not None:
        raise UsageError("--speed and --torque are for --to vgbx")
    if args.to == "fmu":
        if args.mode is not None:
            raise UsageError("--mode: an FMU runs the model as loaded; leave --mode out")
        from powergraph.exchange.fmu import build_fmu

        build_fmu(args.model, target)
        say_wrote(target, "(FMI 2.0 co-simulation; runs where Python has powergraph)")
        return 0
    return _rexs(load(args.model), target, args.mode)


def _rexs(model, target: Path, mode: str | None) -> int:
    from powergraph.exchange.rexs_text import to_json, to_xml
    from powergraph.exchange.rexs_writer import rexs_export

    export = rexs_export(model, mode, str(target))
    text = (to_json if target.suffix.lower() == ".rexsj" else to_xml)(export.document)
    write_text_atomically(target, text)
    say_wrote(target, f"({len(export.document.components)} components, "
                      f"{len(export.document.relations)} relations, 1 load case)")
    if export.unmapped:
        print(f"not written to {target.name} ({len(export.unmapped)}):")
        print("\n".join(f"  {line}" for line in export.unmapped))
    return 0


def _vgbx(model, target: Path, speeds, torques) -> int:
    from powergraph.exchange.vgbx import vgbx_export

    export = vgbx_export(model, target.stem, speeds, torques)
    for name, text in export.maps.items():
        path = target.with_name(name)
        write_text_atomically(path, text)
        say_wrote(path)
    text = json.dumps(export.document, indent=2) + "\n"
    write_text_atomically(target, text)
    gears = export.document["Body"]["Gears"]
    ratios = ", ".join(f"{gear['Ratio']:.6g}" for gear in gears[1:])
    say_wrote(target, f"(axle {gears[0]['Ratio']:.6g}, {len(gears) - 1} gear(s): {ratios})")
    return 0

