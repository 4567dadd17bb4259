"""``powergraph synthesize --ratio R [--tolerance 0.5%] [--max-links N] [--teeth 12:120]
[--planets 3] [--mesh-efficiency 0.98] [--top K] [--json] [-o DIR]
[--workers N | --scheduler dask://ADDRESS]``.

Which trains give ratio R, with which teeth, ranked (docs/synthesis.md). Prints the
``compare`` table of the best K; ``-o DIR`` also writes each one's model (``NN_name.yaml``)
and power-flow diagram (``NN_name.png``).
"""
from __future__ import annotations

import argparse
import re
from pathlib import Path

from powergraph.cli.common import (add_cluster_arguments, check_output_folder, cluster_options,
                                   efficiency_option, number_option, print_json,
                                   whole_option)
from powergraph.errors import UsageError
from powergraph.model.schema_parts import MAX_RATIO, MIN_RATIO


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser(
        "synthesize", help="find the trains (and teeth) that give a ratio, ranked",
        description="Search the planetary trains of at most N links for integer teeth "
                    "giving ratio R (coaxial, assemblable, planets clear of each other) "
                    "and rank them by efficiency both ways, circulating power, meshes "
                    "and mesh rolling.")
    parser.add_argument("--ratio", required=True, metavar="R",
                        help="input speed / output speed (negative: output reversed)")
    parser.add_argument("--tolerance", default="0.5%", metavar="T",
                        help="relative tolerance on the ratio, e.g. 0.5%% or 0.005 "
                             "(default 0.5%%)")
    parser.add_argument("--max-links", default="6", metavar="N",
                        help="largest number of links (default 6)")
    parser.add_argument("--teeth", default="12:120", metavar="LOW:HIGH",
                        help="tooth numbers allowed (default 12:120)")
    parser.add_argument("--planets", default="3", metavar="N",
                        help="planets spaced equally (default 3)")
    parser.add_argument("--mesh-efficiency", default="0.98", metavar="E",
                        help="basic efficiency of every mesh (default 0.98)")
    parser.add_argument("--top", default="10", metavar="K", help="rows shown (default 10)")
    parser.add_argument("--max-grid", default=None, metavar="N",
                        help="safety limit: layouts whose tooth grid has more points are "
                             "skipped and reported (default: the library's MAX_GRID)")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.add_argument("-o", "--output", metavar="DIR",
                        help="write the best K models and their power-flow diagrams here")
    add_cluster_arguments(parser)
    parser.set_defaults(handler=run)


def parse_tolerance(text: str) -> float:
    """``0.5%`` -> 0.005; ``0.005`` -> 0.005.

    >>> parse_tolerance("0.5%"), parse_tolerance("0.01")
    (0.005, 0.01)
    """
    value = (number_option(text[:-1], "--tolerance") / 100 if text.endswith("%")
             else number_option(text, "--tolerance"))
    if not 0 < value < 1:
        raise UsageError(f"--tolerance {text}: must be above 0 and below 100%")
    return value


def parse_teeth(text: str) -> tuple[int, int]:
    """``12:120`` -> (12, 120).

    >>> parse_teeth("12:120")
    (12, 120)
    """
    match = re.fullmatch(r"\s*([0-9]{1,6})\s*:\s*([0-9]{1,6})\s*", text)
    if not match:
        raise UsageError(f"--teeth {text}: expected LOW:HIGH, e.g. 12:120")
    low, high = int(match[1]), int(match[2])
    if not 3 <= low < high <= 1000:
        raise UsageError(f"--teeth {text}: need 3 <= LOW < HIGH <= 1000")
    return low, high


def run(args: argparse.Namespace) -> int:
    target = check_output_folder(args.output, "-o") if args.output else None
    ratio = number_option(args.ratio, "--ratio", -MAX_RATIO, MAX_RATIO)
    if abs(ratio) < MIN_RATIO:   # as in a model file
        raise UsageError(f"--ratio {args.ratio}: a ratio cannot be zero or below "
                         f"{MIN_RATIO:g} either way")
    efficiency = efficiency_option(args.mesh_efficiency)
    options = dict(
        tolerance=parse_tolerance(args.tolerance),
        max_links=whole_option(args.max_links, "--max-links", 3, 8),
        teeth=parse_teeth(args.teeth), planets=whole_option(args.planets, "--planets", 1, 64),
        mesh_efficiency=efficiency, top=whole_option(args.top, "--top", 1, 1000),
        **cluster_options(args))
    from powergraph.analyses.synthesis.synthesize import MAX_GRID, synthesize

    options["max_grid"] = (MAX_GRID if args.max_grid is None
                           else whole_option(args.max_grid, "--max-grid", 1, 10**18))
    result = synthesize(ratio, **options)
    if args.json:
        print_json(result.to_dict())
    else:
        print(result.text_report())
    if target is not None:
        _write(result, target, quiet=args.json)
    return 0


def file_stem(name: str, limit: int = 80) -> str:
    """A file name from a train's name: letters and digits joined by ``_``, cut only
    between words (at most ``limit`` characters, a first word longer than that cut).

    >>> file_stem("2K-H simple: sun L1 in, carrier L3 out, ring L0 fixed", 30)
    '2K_H_simple_sun_L1_in_carrier'
    """
    words = re.findall(r"[A-Za-z0-9]+", name) or ["train"]
    stem = words[0][:limit]
    for word in words[1:]:
        if len(stem) + 1 + len(word) > limit:
            break
        stem += "_" + word
    return stem


def _write(result, target: Path, quiet: bool) -> None:
    """Each row's model (YAML) and power-flow diagram (PNG), numbered by rank."""
    import yaml

    from powergraph.cli.common import new_figure, save_figure, say_wrote, write_atomically
    from powergraph.model import model_from_dict
    from powergraph.plot.power_flow import plot_power_flow
    from powergraph.statics import solve

    target.mkdir(exist_ok=True)
    for rank, row in enumerate(result.rows, 1):
        stem = f"{rank:02d}_" + file_stem(row.name)
        document = row.model_document()
        text = yaml.safe_dump(document, sort_keys=False, allow_unicode=True)
        write_atomically(target / f"{stem}.yaml", lambda tmp: Path(tmp).write_text(text))
        ax = plot_power_flow(solve(model_from_dict(document)), figure=new_figure())
        save_figure(ax.figure, target / f"{stem}.png", dpi=110)
        say_wrote(f"{target / stem}.yaml", "and .png", data_on_stdout=quiet)
