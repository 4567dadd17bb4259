"""Draw Wang (2021)'s Figs. 12–13 from :class:`powergraph.methods.figures.FigureData`.

Every function takes ``ax=None`` (a new figure when omitted), returns the axes and
computes nothing: the data, labels and captions come from the ``FigureData`` it is given
(made by :mod:`powergraph.methods.figures`, which this module never imports: its
``FigureData.plot()`` imports this one).

Examples
--------
>>> from powergraph.model import load_model
>>> from powergraph.methods.figures import mesh_efficiency_curves
>>> ax = plot_figure(mesh_efficiency_curves(load_model("models/rv40e_wang2021.yaml")))  # doctest: +SKIP
"""
from __future__ import annotations

import textwrap
from typing import Any, Iterable

from powergraph.plot.text import PLAIN, plain

#: Line style per curve key: the paper's method solid, the virtual-power method broken.
STYLES: dict[str, dict[str, Any]] = {
    "wang2021": {"color": "C0", "linestyle": "-", "linewidth": 2.0},
    "virtual-power": {"color": "C3", "linestyle": "--", "linewidth": 1.8},
    "virtual-power-needle": {"color": "C2", "linestyle": ":", "linewidth": 2.2},
    "equivalent": {"color": "C1", "linestyle": "-", "linewidth": 2.0},
}


def _axes(ax: Any) -> Any:
    if ax is None:
        import matplotlib.pyplot as plt

        _, ax = plt.subplots(figsize=(6.4, 4.4))
    return ax


def plot_figure(data: FigureData, ax: Any = None, marks: bool = True,
                title: bool = True) -> Any:
    """Every curve of ``data`` on one axes, with a legend and the marked points.

    Parameters
    ----------
    data : FigureData
        From :mod:`powergraph.methods.figures`.
    ax : matplotlib Axes, optional
    marks : bool
        Annotate ``data.marks`` (e.g. published values).
    title : bool
        Use ``data.title`` as the axes title.

    Returns
    -------
    matplotlib Axes
    """
    ax = _axes(ax)
    for curve in data.curves:
        ax.plot(curve.x, curve.y, label=curve.label, **STYLES.get(curve.key, {}))
    if marks:
        _marks(ax, data.marks)
    ax.set_xlabel(data.xlabel, **PLAIN)
    ax.set_ylabel(data.ylabel, **PLAIN)
    if title:
        ax.set_title(data.title, **PLAIN)
    ax.grid(True, alpha=0.3)
    plain(ax.legend(fontsize="small"))
    return ax


def _marks(ax: Any, marks: Iterable[Any]) -> None:
    """A dot and its text at each mark (the paper's values above, the others below)."""
    for mark in marks:
        ax.plot([mark.x], [mark.y], "o", color=STYLES.get(mark.curve, {}).get("color", "k"),
                markersize=4)
        above = mark.curve == "wang2021"   # the paper's values above, the others below
        ax.annotate(mark.text, (mark.x, mark.y), textcoords="offset points",
                    xytext=(-6, 7) if above else (4, -12), ha="right" if above else "left",
                    fontsize="x-small", **PLAIN)


def plot_paper_trend(data: FigureData, ax: Any = None, curve: str = "wang2021") -> Any:
    """Zoom on one curve (default the paper's) so a small trend and its marks show.

    Returns
    -------
    matplotlib Axes
    """
    ax = _axes(ax)
    line = data.curve(curve)
    ax.plot(line.x, line.y, label=line.label, **STYLES.get(curve, {}))
    _marks(ax, [m for m in data.marks if m.curve == curve])
    ax.set_xlabel(data.xlabel, **PLAIN)
    ax.set_ylabel(f"{data.ylabel} (zoom)", **PLAIN)
    ax.set_title("the paper's equations alone", **PLAIN)
    ax.grid(True, alpha=0.3)
    ax.ticklabel_format(axis="y", useOffset=False)
    return ax


def add_caption(figure: Any, text: str) -> Any:
    """Write ``text`` wrapped under the axes of ``figure``, making the figure taller by
    the caption's height; returns the text artist (for a figure without a layout engine).
    """
    width, height = figure.get_size_inches()
    wrapped = textwrap.fill(text, width=int(width * 15))
    extra = 0.16 * (wrapped.count("\n") + 1) + 0.15
    total = height + extra
    figure.set_size_inches(width, total)
    figure.subplots_adjust(bottom=(0.65 + extra) / total, top=1 - 0.45 / total)
    return figure.text(0.015, 0.08 / total, wrapped, ha="left", va="bottom",
                       fontsize="small", **PLAIN)
