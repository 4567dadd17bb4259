"""``powergraph import FILE.rexs|FILE.rexsj -o MODEL.yaml [--points POINTS.csv]
[--mesh-efficiency E]``: a REXS gear unit as a model file, its load spectrum as
duty-cycle points (docs/exchange.md). What the file holds that the model does not is
listed in one summary."""
from __future__ import annotations

import argparse

from powergraph.cli.common import (check_output_file, efficiency_option, say_wrote,
                                   write_text_atomically)
from powergraph.errors import UsageError


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser(
        "import", help="read a REXS file (.rexs, .rexsj) into a model file",
        description="Read a REXS gear unit (XML .rexs or JSON .rexsj) into a model file: "
                    "shafts, cylindrical and planetary stages with their geometry, "
                    "bearings, the lubricant, the ports and the first load case; the load "
                    "spectrum as duty-cycle points for 'powergraph cycle'. Attributes not "
                    "mapped are listed (docs/exchange.md).")
    parser.add_argument("file", help="REXS file (.rexs XML or .rexsj JSON)")
    parser.add_argument("-o", "--output", required=True, metavar="FILE",
                        help="model file to write (.yaml)")
    parser.add_argument("--points", metavar="FILE",
                        help="write the load spectrum as duty-cycle points (.csv)")
    parser.add_argument("--mesh-efficiency", metavar="E",
                        help="basic efficiency of every mesh the file gives none for "
                             "(defaults.mesh_efficiency; default 1)")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from powergraph.exchange.rexs_import import (ideal_meshes, import_rexs, model_yaml,
                                                 points_csv)
    from powergraph.model.input_files import is_rexs_path

    target = check_output_file(args.output, "-o", (".yaml", ".yml"))
    points = check_output_file(args.points, "--points", (".csv",)) if args.points else None
    efficiency = (None if args.mesh_efficiency is None
                  else efficiency_option(args.mesh_efficiency))
    if not is_rexs_path(args.file):
        raise UsageError(f"{args.file}: not a REXS file name (.rexs or .rexsj)")
    result = import_rexs(args.file, efficiency)
    text = model_yaml(result, args.file)
    table = points_csv(result.points) if points is not None else None
    write_text_atomically(target, text)
    say_wrote(target, f"({len(result.data['components'])} components, "
                      f"{len(result.data['links'])} links, {len(result.data['ports'])} ports)")
    if points is not None:
        write_text_atomically(points, table)
        say_wrote(points, f"({len(result.points)} load cases)")
    for caveat in ideal_meshes(result):
        print(f"warning: {caveat}")
    if result.unmapped:
        print(f"not mapped from {args.file} ({len(result.unmapped)} kinds; also in the "
              "model file's header):")
        print("\n".join(f"  {line}" for line in result.unmapped))
    return 0

