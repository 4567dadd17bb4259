"""Lever diagrams (powergraph.analyses.lever), drawn for a report: each planetary set a
vertical lever, its coaxial members as nodes, held members grounded, members of one
body joined by dashed lines, the speeds of the mode as horizontal arrows whose tips lie
on a straight line (dotted), every node's speed written in rpm, the ports (input,
output, machines) marked by their names on the nodes of their bodies, and a speed scale.

The geometry comes from :func:`powergraph.plot.lever_layout.layout_levers` (in points,
with the renderer's text extents); this module only draws it. Without ``ax`` the figure
takes the diagram's natural size (one data unit is one point, texts at ``font_size``);
into a given axes everything is scaled alike.
"""
from __future__ import annotations

from matplotlib.lines import Line2D
from matplotlib.patches import FancyArrow, Patch
from matplotlib.path import Path

from powergraph.plot.fonts import drawing_fonts
from powergraph.plot.lever_layout import BADGE_PAD, TEXT_PAD, LeverLayout, layout_levers
from powergraph.plot.natural import (fit_figure, fitted_legend, fitted_scale, measurer,
                                     natural_axes)
from powergraph.plot.text import PLAIN

INK = "#1f3b5c"
#: The key's ground symbol: a bar with hatching, as drawn at a held node.
GROUND_MARK = Path([(-1, 0), (0.2, 0), (0.2, -0.7), (0.2, 0.7), (0.2, -0.7), (0.7, -0.2),
                    (0.2, 0.0), (0.7, 0.5), (0.2, 0.7), (0.7, 1.2)],
                   [1, 2, 1, 2, 1, 2, 1, 2, 1, 2])
SPEED = "#c44e52"
#: Badge colours (face, edge) by port role.
ROLES = {"input": ("#e3f1e0", "#2e7d32"), "output": ("#fde8e6", "#b03a2e"),
         "machine": ("#e6eefa", "#2c6fad")}


def plot_levers(diagram, ax=None, *, font_size: float = 9.0, legend: bool = True,
                figure=None):
    """Draw ``diagram`` (a LeverDiagram).

    Parameters
    ----------
    diagram : LeverDiagram
    ax : matplotlib Axes, optional
        Drawn into at a uniform scale; a figure of the diagram's natural size otherwise.
    font_size : float
        Name font size (points) at natural size; speeds, badges and notes are 90 % of it.
    legend : bool
        Draw the key under the levers.
    figure : matplotlib Figure, optional
        When ``ax`` is None, the (empty) figure to size and draw in; a new pyplot figure
        otherwise.

    Returns
    -------
    matplotlib Axes
        With ``ax.powergraph_layout`` (the :class:`~powergraph.plot.lever_layout.LeverLayout`
        drawn), ``ax.powergraph_texts = {(kind, lever, component): Text}`` (``kind``
        ``name``, ``speed``, ``carrier`` or a port's role) and ``ax.powergraph_arrows =
        {(lever, component): arrow}``.

    Examples
    --------
    >>> from powergraph.model import load_model                      # doctest: +SKIP
    >>> from powergraph.analyses.lever import lever_diagram          # doctest: +SKIP
    >>> ax = lever_diagram(load_model("models/simpson_first.yaml")).plot()  # doctest: +SKIP
    """
    if ax is None:
        if figure is None:
            import matplotlib.pyplot as plt

            figure = plt.figure()
    fig = ax.figure if ax is not None else figure
    with drawing_fonts():
        layout = layout_levers(diagram, measurer(fig), font_size)
        natural = ax is None
        if natural:
            ax = natural_axes(fig, layout.bounds, top=3.6 * font_size, bottom=6.0)
            scale = 1.0
        else:
            scale = fitted_scale(ax, layout.bounds)
        _draw(ax, diagram, layout, scale)
        speeds = bool(layout.arrows) or any(t.kind == "speed" for t in layout.texts)
        ax.set_title(diagram.title + ("\nspeeds in rpm (arrows to scale)" if speeds else ""),
                     fontsize=font_size * 1.1 * scale, color=INK, linespacing=1.5, **PLAIN)
        if legend:
            _legend(ax, layout, scale, font_size)
        if natural:
            fit_figure(ax)
    return ax


def _draw(ax, diagram, layout: LeverLayout, s: float) -> None:
    ax.set_axis_off()
    ax.powergraph_layout = layout
    for (x0, y0), (x1, y1) in layout.links:
        ax.add_line(Line2D([x0, x1], [y0, y1], color="gray", ls="--", lw=0.8 * s, zorder=1))
    for x, top, bottom in layout.levers:
        ax.add_line(Line2D([x, x], [bottom, top], color="black", lw=3.0 * s,
                           solid_capstyle="round", zorder=2))
    for tips in layout.speed_lines:
        xs, ys = zip(*sorted(tips, key=lambda p: -p[1]))
        ax.add_line(Line2D(xs, ys, color=SPEED, lw=0.8 * s, ls=":", zorder=2))
    arrows = {}
    keys = [(n.lever, n.component) for n in layout.nodes]
    by_point = {(n.x, n.y): (n.lever, n.component) for n in layout.nodes}
    for start, end in layout.arrows:
        length = end[0] - start[0]
        head = min(6.0, abs(length) * 0.6)
        arrow = FancyArrow(start[0], start[1], length, 0.0, width=1.3 * s,
                           head_width=5.0 * s, head_length=head, length_includes_head=True,
                           color=SPEED, lw=0, zorder=3)
        ax.add_patch(arrow)
        arrows[by_point.get(start, keys[0])] = arrow
    for node in layout.nodes:
        ax.add_line(Line2D([node.x], [node.y], marker="o", ms=7 * s, mfc="white", mec="black",
                           mew=1.2 * s, zorder=4))
        if node.grounded:
            _ground(ax, node.x, node.y, s)
    texts = {}
    for t in layout.texts:
        texts[(t.kind, t.lever, t.component)] = _text(ax, t, s)
    if layout.scale is not None:
        x0, x1, y = layout.scale
        ax.add_line(Line2D([x0, x1], [y, y], color=SPEED, lw=1.3 * s, zorder=3))
        for x in (x0, x1):
            ax.add_line(Line2D([x, x], [y - 3, y + 3], color=SPEED, lw=1.0 * s, zorder=3))
    ax.powergraph_texts, ax.powergraph_arrows = texts, arrows
    ax.powergraph_diagram = diagram


def _text(ax, t, s: float):
    colour = {"speed": SPEED, "scale": SPEED}.get(t.kind, INK)
    kw = {}
    if t.kind in ROLES:
        face, edge = ROLES[t.kind]
        kw["bbox"] = dict(boxstyle=f"round,pad={BADGE_PAD / t.size:.3f}", fc=face, ec=edge,
                          lw=0.8 * s)
        colour = edge
    elif t.kind in ("name", "speed"):
        kw["bbox"] = dict(boxstyle=f"square,pad={TEXT_PAD / t.size:.3f}", fc="white",
                          ec="none")
    return ax.text(t.x, t.y, t.text, ha=t.ha, va="center", fontsize=t.size * s,
                   color=colour, zorder=5, style="italic" if t.kind == "note" else "normal",
                   **kw, **PLAIN)


def _ground(ax, x: float, y: float, s: float) -> None:
    """A held member: a short bar to the right with hatching."""
    ax.add_line(Line2D([x + 4, x + 11], [y, y], color="black", lw=1.0 * s, zorder=3))
    ax.add_line(Line2D([x + 11, x + 11], [y - 5, y + 5], color="black", lw=1.0 * s, zorder=3))
    for i in range(4):
        yy = y - 5 + 3.3 * i
        ax.add_line(Line2D([x + 11, x + 15], [yy, yy + 3], color="black", lw=0.7 * s,
                           zorder=3))


def _legend(ax, layout: LeverLayout, s: float, font_size: float) -> None:
    roles = {t.kind for t in layout.texts if t.kind in ROLES}
    handles = [Patch(fc=ROLES[r][0], ec=ROLES[r][1], label=f"{r} port") for r in ROLES
               if r in roles]
    if layout.arrows:
        handles.append(Line2D([], [], color=SPEED, lw=1.5, label="speed (rpm)"))
    if any(n.grounded for n in layout.nodes):
        handles.append(Line2D([], [], color="black", marker=GROUND_MARK, ls="none", ms=10,
                              mew=1.0, label="held"))
    if layout.links:
        handles.append(Line2D([], [], color="gray", ls="--", lw=0.8, label="one body"))
    if handles:
        fitted_legend(ax, handles, font_size * 0.85 * s, handlelength=1.6,
                      columnspacing=1.2, borderaxespad=0.3)
