"""Lever diagrams (powergraph.analyses.lever): each planetary set a vertical lever, its
coaxial members as nodes, held members grounded, members of one body joined by dashed
lines, and the speeds of the mode as horizontal arrows whose tips lie on a straight line."""
from __future__ import annotations

from collections import defaultdict

from powergraph.plot.text import PLAIN

SPACING = 1.6
ARROW = 0.6


def plot_levers(diagram, ax=None):
    """Draw ``diagram`` (a LeverDiagram).

    Parameters
    ----------
    diagram : LeverDiagram
    ax : matplotlib Axes, optional

    Returns
    -------
    matplotlib Axes

    Examples
    --------
    >>> from powergraph.model import load_model                      # doctest: +SKIP
    >>> from powergraph.analyses.lever import lever_diagram          # doctest: +SKIP
    >>> ax = lever_diagram(load_model("models/simpson_first.yaml")).plot()  # doctest: +SKIP
    """
    if ax is None:
        import matplotlib.pyplot as plt

        _, ax = plt.subplots(figsize=(max(4.0, 2.2 * len(diagram.levers) + 1), 5.0))
    speeds = [abs(n.speed) for lev in diagram.levers for n in lev.nodes if n.speed is not None]
    scale = ARROW / max(speeds) if speeds and max(speeds) > 0 else 0.0
    places = defaultdict(list)
    for k, lever in enumerate(diagram.levers):
        x = k * SPACING
        ys = [n.position for n in lever.nodes]
        ax.plot([x, x], [min(ys), max(ys)], color="black", linewidth=3, solid_capstyle="round")
        tips = []
        for node in lever.nodes:
            _node(ax, x, node)
            places[node.body].append((x, node.position))
            if node.speed is not None and scale:
                dx = node.speed * scale
                ax.annotate("", xy=(x + dx, node.position), xytext=(x, node.position),
                            arrowprops={"arrowstyle": "->", "color": "#c44e52", "lw": 1.5},
                            **PLAIN)
                tips.append((x + dx, node.position))
        if len(tips) >= 2:
            ax.plot(*zip(*tips), color="#c44e52", linewidth=0.8, linestyle=":")
        ax.text(x, min(ys) - 0.25, f"carrier {lever.carrier}", ha="center", fontsize=8,
                **PLAIN)
    for body, points in places.items():
        for (x0, y0), (x1, y1) in zip(points, points[1:]):
            if x0 != x1:
                ax.plot([x0, x1], [y0, y1], color="gray", linestyle="--", linewidth=0.8)
    title = diagram.title
    ax.set_title(title + ("\narrows: speeds" if scale else ""), fontsize=10, **PLAIN)
    ax.set_xlim(-1.0, (len(diagram.levers) - 1) * SPACING + 1.0)
    ax.margins(y=0.2)
    ax.set_axis_off()
    return ax


def _node(ax, x: float, node) -> None:
    ax.plot([x], [node.position], "o", color="white", markeredgecolor="black", markersize=8,
            zorder=3)
    label = f"{node.component}" + (f" [{', '.join(node.elements)}]" if node.elements else "")
    # on a white ground: the dashed lines joining members of one body pass behind it
    ax.text(x - 0.12, node.position, label, ha="right", va="center", fontsize=8, zorder=4,
            bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none"}, **PLAIN)
    if node.grounded:
        ax.plot([x + 0.08, x + 0.3], [node.position] * 2, color="black", linewidth=1)
        for i in range(4):
            y = node.position - 0.06 + 0.04 * i
            ax.plot([x + 0.3, x + 0.36], [y, y + 0.04], color="black", linewidth=0.8)
