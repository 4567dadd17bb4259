"""A sheet of train graphs, as the synthesis literature draws them; computes nothing.

Each graph sits in its own cell: links are numbered dots on a circle, turning pairs are
thick edges labelled with their axis (a, b, c, ...; coaxial pairs share a letter), gear
pairs are thin edges labelled with their carrier.

Examples
--------
>>> from powergraph.analyses.synthesis import enumerate_trains
>>> ax = plot_graphs(enumerate_trains(4).graphs)          # doctest: +SKIP
"""
from __future__ import annotations

import math
from typing import Any, Sequence

import matplotlib.pyplot as plt

from powergraph.plot.text import PLAIN

AXIS_LETTERS = "abcdefghijklmnopqrstuvwxyz"


def plot_graphs(graphs: Sequence[Any], ax: plt.Axes | None = None, columns: int | None = None,
                title: str | None = None) -> plt.Axes:
    """Draw train graphs (:class:`~powergraph.analyses.synthesis.TrainGraph`) on a grid.

    Parameters
    ----------
    graphs : sequence of TrainGraph
    ax : matplotlib Axes, optional
        Where to draw; a new figure sized to the sheet when None.
    columns : int, optional
        Cells per row (about the square root of the count when None).
    title : str, optional

    Returns
    -------
    matplotlib Axes
    """
    count = max(1, len(graphs))
    columns = columns or max(1, math.ceil(math.sqrt(count)))
    rows = math.ceil(count / columns)
    if ax is None:
        _, ax = plt.subplots(figsize=(min(2.0 * columns, 60), min(2.0 * rows, 60)))
    for index, graph in enumerate(graphs):
        _draw_one(ax, graph, x0=index % columns * 3.0, y0=-(index // columns) * 3.2)
    ax.set_xlim(-1.6, columns * 3.0 - 1.4)
    ax.set_ylim(-rows * 3.2 + 1.4, 1.7)
    ax.set_aspect("equal")
    ax.axis("off")
    ax.set_title(title or f"{len(graphs)} train graphs: thick = turning pair (axis letter), "
                          "thin = gear pair (/carrier)", fontsize=9, **PLAIN)
    return ax


def _draw_one(ax: plt.Axes, graph: Any, x0: float, y0: float) -> None:
    n = graph.links
    where = {k: (x0 + math.cos(math.pi / 2 + 2 * math.pi * k / n),
                 y0 + math.sin(math.pi / 2 + 2 * math.pi * k / n)) for k in range(n)}
    for u, v, axis in graph.turning_pairs:
        (xa, ya), (xb, yb) = where[u], where[v]
        ax.plot([xa, xb], [ya, yb], color="black", lw=3.0, solid_capstyle="round", zorder=1)
        ax.text((xa + xb) / 2, (ya + yb) / 2, AXIS_LETTERS[axis % 26], fontsize=6,
                color="tab:blue", ha="center", va="center", zorder=3,
                bbox={"boxstyle": "round,pad=0.1", "fc": "white", "ec": "none"}, **PLAIN)
    for u, v, carrier in graph.gear_pairs:
        (xa, ya), (xb, yb) = where[u], where[v]
        ax.plot([xa, xb], [ya, yb], color="tab:red", lw=0.9, zorder=1)
        ax.text((xa + xb) / 2, (ya + yb) / 2 - 0.12, f"/{carrier}", fontsize=5,
                color="tab:red", ha="center", va="center", zorder=3, **PLAIN)
    for k, (x, y) in where.items():
        ax.plot([x], [y], "o", ms=9, mfc="white", mec="black", zorder=2)
        ax.text(x, y, str(k), fontsize=6, ha="center", va="center", zorder=4, **PLAIN)
    ax.text(x0, y0 - 1.45, graph.name or "", fontsize=6, ha="center", va="center", **PLAIN)
