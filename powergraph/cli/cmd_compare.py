"""``powergraph compare MODEL MODEL... [--json] [-o FILE] [--mesh-efficiency E]``."""
from __future__ import annotations

import argparse

from powergraph.cli.common import (
    aligned_table,
    check_figure_path,
    efficiency_arg,
    load,
    print_json,
    write_atomically,
)

COLUMNS = (("name", "train", "{}"), ("ratio", "ratio", "{:.4g}"),
           ("efficiency", "eff %", "{:.2%}"), ("backdrive_efficiency", "back %", "{:.2%}"),
           ("backdrive_self_locking", "locks back", "{}"),
           ("circulating_power", "circ. W", "{:.4g}"),
           ("max_virtual_power_ratio", "max Pv/P", "{:.3g}"), ("meshes", "meshes", "{}"),
           ("volume_mm3", "volume mm³", "{:.4g}"),
           ("power_density_kw_per_l", "kW/L", "{:.3g}"))


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser("compare", help="compare trains side by side",
                            description="Ratio, efficiency both ways, self-locking, "
                                        "circulating power and mesh rolling of several "
                                        "trains, one row each.")
    parser.add_argument("models", nargs="+", metavar="MODEL", help="model files (YAML)")
    parser.add_argument("--json", action="store_true", help="print a JSON list of rows")
    parser.add_argument("-o", "--output", metavar="FILE",
                        help="write a grouped bar chart (.png, .svg or .pdf)")
    parser.add_argument("--mesh-efficiency", type=efficiency_arg, metavar="E",
                        help="compare at equal mesh quality: every mesh at E")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from powergraph.analyses.compare import compare_row

    target = check_figure_path(args.output) if args.output else None
    rows = [compare_row(load(path, args.mesh_efficiency)) for path in args.models]
    if args.json:
        print_json([row.to_dict() for row in rows])
    else:
        print(table(rows))
    if target is not None:
        from powergraph.plot.compare import plot_comparison

        def write(tmp: str) -> None:
            ax = plot_comparison(rows)
            ax.figure.savefig(tmp, bbox_inches="tight")

        write_atomically(target, write)
    return 0


#: Efficiency columns shown as "locks" where the train self-locks that way (the formal
#: value, <= 0, stays in the JSON; docs/locking.md).
LOCKING = {"efficiency": "self_locking", "backdrive_efficiency": "backdrive_self_locking"}


def table(rows) -> str:
    """Aligned text table, one row per train; columns with no data anywhere are left out.
    A self-locking direction shows "locks" instead of its formal (<= 0) efficiency.

    >>> from types import SimpleNamespace as Row
    >>> row = Row(name="K-H-V", ratio=-39.0, efficiency=0.29, self_locking=False,
    ...           backdrive_efficiency=-1.4, backdrive_self_locking=True,
    ...           circulating_power=0.0, max_virtual_power_ratio=39.0, meshes=1,
    ...           volume_mm3=None, power_density_kw_per_l=None)
    >>> print(table([row]))
    train  ratio   eff %  back %  locks back  circ. W  max Pv/P  meshes
    -----  -----  ------  ------  ----------  -------  --------  ------
    K-H-V    -39  29.00%   locks         yes        0        39       1
    """
    columns = [c for c in COLUMNS if any(getattr(r, c[0]) is not None for r in rows)]
    cells = [[header for _, header, _ in columns]]
    for row in rows:
        cells.append(["locks" if key in LOCKING and getattr(row, LOCKING[key])
                      else _cell(getattr(row, key), fmt) for key, _, fmt in columns])
    return "\n".join(aligned_table(cells, set(range(1, len(columns)))))


def _cell(value, fmt: str) -> str:
    if value is None:
        return "-"
    if isinstance(value, bool):
        return "yes" if value else "no"
    return fmt.format(value)
