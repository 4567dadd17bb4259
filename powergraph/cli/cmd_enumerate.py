"""``powergraph enumerate --links N [--dof D] [--json] [-o DIR]`` (docs/synthesis.md).

Lists the non-isomorphic planetary gear train graphs of N links: counts of rotation and
displacement graphs, then one line per displacement graph. ``--json`` prints
``{links, dof, rotation_graphs, displacement_graphs, graphs: [...]}``. ``-o DIR`` writes
each displacement graph as a model file (``dgraph_NNN.yaml``: a frame and ports among the
coaxial links, placeholder tooth numbers) and the sheet of graphs ``graphs.png`` (sheets
``graphs_001.png``, ... of 100 graphs when there are more).
"""
from __future__ import annotations

import argparse
from pathlib import Path

from powergraph.cli.common import (check_output_folder, new_axes, print_json, save_figure,
                                   say_wrote, whole_option, write_atomically)
from powergraph.errors import UsageError

#: Graphs per picture sheet (10 x 10).
SHEET = 100
#: Basic efficiency written as the model files' default (a typical spur mesh).
MESH_EFFICIENCY = 0.98


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``enumerate`` command."""
    parser = subparsers.add_parser(
        "enumerate", help="non-isomorphic planetary gear train graphs of N links",
        description="Enumerate the non-isomorphic graphs of planetary gear trains with N "
                    "links and D degrees of freedom (N - 1 - D gear pairs): rotation "
                    "graphs and displacement graphs (the trains), as Yang & Ding (2019) "
                    "count them. 8 links take about 15 s, 9 links minutes.")
    parser.add_argument("--links", metavar="N", help="number of links, frame included (3-9)")
    parser.add_argument("--dof", metavar="D", default="1",
                        help="degrees of freedom (default 1; at most N - 2)")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.add_argument("-o", dest="out", metavar="DIR",
                        help="write each displacement graph as a model file, and the sheet "
                             "of graphs graphs.png, into DIR (created if missing)")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Run ``enumerate``; returns the exit status (errors propagate to main: exit 2)."""
    from powergraph.analyses.synthesis import enumerate_trains
    from powergraph.analyses.synthesis.enumerate import MAX_LINKS

    if args.links is None:
        raise UsageError("enumerate needs --links N")
    target = check_output_folder(args.out, "-o") if args.out else None
    links = whole_option(args.links, "--links", 3, MAX_LINKS)
    dof = whole_option(args.dof, "--dof", 1, links - 2)
    result = enumerate_trains(links, dof)
    if args.json:
        print_json(result.to_dict())
    else:
        print(result.text_report())
    if target is not None:
        written = _write(target, result)
        sheets = "graphs.png" if written <= SHEET else "graphs_001.png ..."
        say_wrote(target, f"({written} model files and {sheets})", data_on_stdout=args.json)
    return 0


def _write(folder: Path, result) -> int:
    import yaml

    from powergraph.analyses.synthesis.enumerate_models import model_document
    from powergraph.plot.synthesis import plot_graphs

    folder.mkdir(exist_ok=True)
    for index, graph in enumerate(result.graphs, start=1):
        text = yaml.safe_dump(model_document(graph, mesh_efficiency=MESH_EFFICIENCY),
                              sort_keys=False, allow_unicode=True)

        def write(tmp: str, text: str = text) -> None:
            Path(tmp).write_text(text, encoding="utf-8")

        write_atomically(folder / f"dgraph_{index:03d}.yaml", write)
    sheets = [result.graphs[i:i + SHEET] for i in range(0, len(result.graphs), SHEET)]
    for number, graphs in enumerate(sheets, start=1):
        columns = max(1, min(10, round(len(graphs) ** 0.5 + 0.49)))
        rows = -(-len(graphs) // columns)
        ax = new_axes((2.0 * columns, 2.1 * rows + 0.4))
        part = f" (sheet {number} of {len(sheets)})" if len(sheets) > 1 else ""
        plot_graphs(graphs, ax=ax, columns=columns,
                    title=f"{result.links}-link {result.dof}-DOF: {result.displacement_graphs} "
                          f"d-graphs, {result.rotation_graphs} r-graphs{part}; thick = turning "
                          "pair (axis letter), thin = gear pair (/carrier)")
        name = "graphs.png" if len(sheets) == 1 else f"graphs_{number:03d}.png"
        save_figure(ax.figure, folder / name, dpi=100, bbox_inches="tight")
    return len(result.graphs)
