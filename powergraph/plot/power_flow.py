"""Power-flow diagrams in the style of Wang (2021), Figs. 5-10 (drawing only).

Bodies are boxes labelled with their components ("2/3"), meshes are circles, couplings
squares, the input port ⊙ and the output port ⊗ captioned with the ports' names
(:meth:`~powergraph.plot.layout.view.FlowView.text`); every arrow carries a power, its width
proportional to it, labelled with the power and its share of the input power P.
Zero-power links (the held frame's, the paper's converting principle 1) are dashed.
Bearings with friction or drag ("bearing 2-7") and body drags ("drag 6") are rounded
boxes with a loss outline. Losses leave each mesh, bearing and drag into a "loss" sink;
arrows on a circulating loop are red.
``frame`` draws the transformation gear train: the virtual powers seen from that body.

The content comes from :func:`powergraph.plot.layout.view.flow_view` and the geometry
from :func:`powergraph.plot.layout.layout.layout_flow`; this module only draws them.

Examples
--------
>>> import powergraph as pg
>>> result = pg.solve(pg.load_model("models/rv40e_wang2021.yaml"))       # doctest: +SKIP
>>> ax = plot_power_flow(result, frame="3")                      # doctest: +SKIP
>>> arrow, label = ax.powergraph_artists[("2/3", "mesh 4-5")]     # doctest: +SKIP
>>> label.get_text()                                             # doctest: +SKIP
'0 W\\n0 %'
"""
from __future__ import annotations

import warnings
from typing import Any

import matplotlib.pyplot as plt
from matplotlib.lines import Line2D
from matplotlib.patches import (Circle, FancyBboxPatch, Patch, PathPatch, Polygon,
                                Rectangle)
from matplotlib.path import Path

from powergraph.plot.fonts import GlyphWarning, drawing_fonts, undrawable
from powergraph.plot.layout.geometry import Box
from powergraph.plot.layout.layout import FlowLayout, LayoutStyle, NodePlace, layout_flow
from powergraph.plot.layout.nodes import NodeMap
from powergraph.plot.layout.place import LABEL_PAD
from powergraph.plot.layout.view import FlowView, flow_view, format_power, format_share
from powergraph.plot.natural import (fit_figure, fitted_legend, fitted_scale, measurer,
                                     natural_axes)
from powergraph.plot.text import PLAIN

INK = "#1f3b5c"
COLOURS = {"power": "#2c6fad", "zero": "#8a8a8a", "loss": "#b5651d", "loop": "#c0392b"}
FILLS = {"body": "#e8f0fa", "frame": "#e3e3e3", "mesh": "white", "coupling": "#f1f1f1",
         "bearing": "#fdf3e7", "seal": "#fdf3e7", "drag": "#fdf3e7",
         "churning": "#fdf3e7",
         "loss": "#fbe9d6", "motor": "white", "generator": "white", "ground": "white"}


def plot_power_flow(result: Any, frame: str | int | None = None, ax=None, *,
                    font_size: float = 9.0, legend: bool = True, subtitle: bool = True,
                    view: FlowView | None = None, figure: Any = None):
    """Draw the power-flow graph of ``result`` seen from the body of ``frame``.

    Parameters
    ----------
    result : PowerFlowResult, or a result with ``to_dict()["flows"]`` (wang2021)
    frame : component id, optional
        Draw the virtual powers seen from this component's body (None: actual powers).
    ax : matplotlib axes, optional
        Drawn into at a uniform scale; a figure of the diagram's natural size otherwise.
    font_size : float
        Node font size (points) at natural size; labels are 85 % of it.
    legend, subtitle : bool
        Draw the symbol key under the diagram, and the P / efficiency line in the title.
    view : FlowView, optional
        ``flow_view(result, frame)`` if already at hand.
    figure : matplotlib Figure, optional
        When ``ax`` is None, the (empty) figure to size and draw in; a new pyplot figure
        otherwise.

    Returns
    -------
    matplotlib.axes.Axes
        With ``ax.powergraph_artists = {(source, target): (arrow, label)}`` for every
        flow of the view (zero-power ones included), ``ax.powergraph_nodes =
        {node: (patch, text)}``, ``ax.powergraph_layout`` and ``ax.powergraph_view``.
        Keys are :class:`~powergraph.statics.flow.Node` (``Flow.key`` for arrows); a
        node's name may stand for it when no other node has that name
        (:class:`~powergraph.plot.layout.nodes.NodeMap`). ``ax.powergraph_undrawable``
        lists the names no installed font can draw (then one
        :class:`~powergraph.plot.fonts.GlyphWarning` is issued; docs/draw.md).
    """
    view = view if view is not None else flow_view(result, frame)
    fig = ax.figure if ax is not None else figure if figure is not None else plt.figure()
    with drawing_fonts():
        ax = _draw(fig, ax, view, result, font_size, legend, subtitle)
    ax.powergraph_undrawable = tuple(undrawable(_texts(ax.powergraph_layout)))
    if ax.powergraph_undrawable:
        warnings.warn(GlyphWarning(ax.powergraph_undrawable), stacklevel=2)
    return ax


def _texts(layout: FlowLayout) -> list[str]:
    """The names drawn: every node's text or caption (a port's name), the model's name,
    the held body."""
    view = layout.view
    names = [view.name] + ([view.held] if view.held else [])
    return [view.text(n.node) for n in layout.nodes.values() if n.kind != "loss"] + names


def _draw(fig, ax, view: FlowView, result: Any, font_size: float, legend: bool,
          subtitle: bool):
    style = LayoutStyle(font_size=font_size)
    layout = layout_flow(view, measurer(fig), style)
    scale = fitted_scale(ax, layout.bounds) if ax is not None else 1.0
    natural = ax is None
    if ax is None:
        ax = _natural_axes(fig, layout, legend)
    ax.set_axis_off()
    ax.powergraph_nodes = NodeMap({n: _draw_node(ax, node, scale, style)
                                   for n, node in layout.nodes.items()})
    heads: dict = {}
    ax.powergraph_artists = NodeMap({e.key: _draw_edge(ax, e, scale, style, heads)
                                     for e in layout.edges})
    ax.powergraph_heads = NodeMap(heads)
    ax.powergraph_layout, ax.powergraph_view = layout, view
    ax.set_title(_title(view, result, subtitle), fontsize=font_size * 1.1 * scale,
                 color=INK, linespacing=1.5, **PLAIN)
    if legend:
        _legend(ax, view, scale, font_size)
    if natural:
        fit_figure(ax)
    return ax


# --- figure and axes -------------------------------------------------------------------
def _natural_axes(fig, layout: FlowLayout, legend: bool):
    """A figure in which one data unit is one point."""
    font = layout.style.font_size
    return natural_axes(fig, layout.bounds, top=3.4 * font,
                        bottom=(2.6 * font) if legend else 6.0)


# --- nodes -----------------------------------------------------------------------------
def _draw_node(ax, node: NodePlace, s: float, style: LayoutStyle):
    font = style.font_size * s
    kind, box = node.kind, node.box
    draw = {"mesh": _round, "motor": _motor, "generator": _generator, "ground": _ground}
    patch = draw.get(kind, _boxed)(ax, node, box, s)
    text = None
    if node.shape.text:
        text = ax.text(node.x, node.y, node.shape.text, ha="center", va="center",
                       fontsize=font, color=COLOURS["loss"] if kind == "loss" else INK,
                       zorder=5, style="italic" if kind == "loss" else "normal",
                       **PLAIN)
        if kind == "frame":
            text.set_bbox(dict(boxstyle="round,pad=0.12", fc="white", ec="none"))
    elif node.shape.caption:
        cx, cy = node.caption_box.center
        text = ax.text(cx, cy, node.shape.caption, ha="center", va="center",
                       fontsize=font * 0.9, color=INK, zorder=5, **PLAIN)
    return patch, text


def _boxed(ax, node: NodePlace, box: Box, s: float):
    kind = node.kind
    style = "square,pad=0" if kind == "coupling" else "round,pad=0,rounding_size=3"
    patch = FancyBboxPatch((box.x0, box.y0), box.x1 - box.x0, box.y1 - box.y0,
                           boxstyle=style, fc=FILLS.get(kind, "white"),
                           ec=COLOURS["loss"] if kind in ("loss", "bearing", "seal", "drag", "churning") else INK,
                           lw=(1.6 if kind == "frame" else 1.0) * s, zorder=4,
                           hatch="////" if kind == "frame" else None)
    ax.add_patch(patch)
    if kind == "coupling":   # a double outline: an equal-speed mechanism, not a mesh
        inset = 2.0
        ax.add_patch(Rectangle((box.x0 + inset, box.y0 + inset), box.x1 - box.x0 - 2 * inset,
                               box.y1 - box.y0 - 2 * inset, fill=False, ec=INK,
                               lw=0.6 * s, zorder=4))
    return patch


def _round(ax, node: NodePlace, box: Box, s: float):
    patch = Circle((node.x, node.y), node.shape.width / 2, fc=FILLS[node.kind], ec=INK,
                   lw=1.2 * s, zorder=4)
    ax.add_patch(patch)
    return patch


def _motor(ax, node: NodePlace, box: Box, s: float):
    patch = _round(ax, node, box, s)
    ax.add_patch(Circle((node.x, node.y), node.shape.width * 0.12, fc=INK, ec="none",
                        zorder=5))
    return patch


def _generator(ax, node: NodePlace, box: Box, s: float):
    patch = _round(ax, node, box, s)
    r = node.shape.width / 2 * 0.7071
    for sign in (+1, -1):
        ax.add_line(Line2D([node.x - r, node.x + r], [node.y - sign * r, node.y + sign * r],
                           color=INK, lw=1.2 * s, zorder=5))
    return patch


def _ground(ax, node: NodePlace, box: Box, s: float):
    patch = Rectangle((box.x0, box.y0), box.x1 - box.x0, (box.y1 - box.y0) * 0.6,
                      fill=False, hatch="////", ec=INK, lw=0, zorder=4)
    ax.add_patch(patch)
    ax.add_line(Line2D([box.x0, box.x1], [box.y0 + (box.y1 - box.y0) * 0.6] * 2,
                       color=INK, lw=1.6 * s, zorder=5))
    return patch


# --- arrows and labels -----------------------------------------------------------------
def _colour(edge) -> str:
    if edge.zero:
        return COLOURS["zero"]
    if edge.loop:
        return COLOURS["loop"]
    return COLOURS["loss"] if edge.loss else COLOURS["power"]


def _draw_edge(ax, edge, s: float, style: LayoutStyle, heads: dict):
    """The arrow's line (returned) with its head (``ax.powergraph_heads``) and label."""
    colour = _colour(edge)
    arrow = PathPatch(Path(*edge.shaft), fill=False, lw=edge.width * s, ec=colour,
                      linestyle="--" if edge.zero else "-", capstyle="butt",
                      joinstyle="round", zorder=2)
    ax.add_patch(arrow)
    if edge.head is not None:
        head = Polygon(edge.head, closed=True, fc=colour, ec="none", zorder=3)
        ax.add_patch(head)
        heads[edge.key] = head
    font = style.label_size * s
    label = ax.text(*edge.label_xy, edge.label, ha="center", va="center", fontsize=font,
                    color=colour if not edge.zero else "#666666", zorder=6,
                    bbox=dict(boxstyle=f"round,pad={LABEL_PAD / style.label_size:.3f}",
                              fc="white", ec="none", alpha=0.92), **PLAIN)
    return arrow, label


# --- title and key ---------------------------------------------------------------------
def _title(view, result, subtitle: bool) -> str:
    if not subtitle:
        return view.title
    parts = [f"P = {format_power(view.input_power)} in"]
    efficiency = getattr(result, "efficiency", None)
    if efficiency is not None:
        parts.append(f"efficiency {format_share(efficiency, 1.0)}")
    if getattr(result, "self_locking", False):
        parts.append("SELF-LOCKING")
    if view.circulating > 0:
        parts.append(f"circulating power {format_power(view.circulating)}")
    parts.append("arrows: power and % of P")
    if view.method != "virtual-power":
        parts.append(f"method {view.method}")
    return f"{view.title}\n" + "  ·  ".join(parts)


def _legend(ax, view, s: float, font_size: float) -> None:
    handles = [Line2D([], [], marker="o", ls="none", mfc="white", mec=INK, ms=8,
                      label="gear mesh"),
               Line2D([], [], marker="s", ls="none", mfc=FILLS["body"], mec=INK, ms=8,
                      label="body (components)"),
               Line2D([], [], color=COLOURS["power"], lw=2.5, label="power"),
               Line2D([], [], color=COLOURS["loss"], lw=2.5, label="loss"),
               Line2D([], [], color=COLOURS["zero"], lw=1, ls="--", label="0 W link")]
    if view.held is not None:
        handles.insert(2, Patch(fc=FILLS["frame"], ec=INK, hatch="////",
                                label=(f"held frame: {view.held}" if view.frame_body
                                       else f"frame: {view.held}")))
    if view.loop_edges:
        handles.append(Line2D([], [], color=COLOURS["loop"], lw=2.5, label="circulating"))
    fitted_legend(ax, handles, font_size * 0.85 * s, handlelength=1.6, columnspacing=1.2,
                  borderaxespad=0.3)
