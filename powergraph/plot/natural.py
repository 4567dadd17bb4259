"""Figures at a diagram's natural size: one data unit is one point (1/72 in).

The power-flow and lever diagrams are laid out in points with the renderer's own text
extents (:func:`measurer`), so that at their natural size every text is exactly as
large as it was measured: :func:`natural_axes` makes such a figure, :func:`fitted_scale`
fits a layout into a given axes instead (fonts and lines scaled alike), and
:func:`fit_figure` grows or shrinks the figure round the axes, its title and its key.

Examples
--------
>>> import matplotlib.pyplot as plt                        # doctest: +SKIP
>>> size = measurer(plt.figure())                          # doctest: +SKIP
>>> size("2.27 kW", 9.0)                                   # doctest: +SKIP
(33.0..., 10.4...)
"""
from __future__ import annotations

from matplotlib.transforms import Bbox

from powergraph.plot.layout.geometry import Box
from powergraph.plot.text import PLAIN

INCH = 72.0


def measurer(fig):
    """Text extents in points, measured with the figure's renderer (cached).

    The renderer is the figure's own (whatever backend the user chose); no backend is
    selected here.
    """
    cache: dict[tuple[str, float], tuple[float, float]] = {}

    def size(text: str, font: float) -> tuple[float, float]:
        if (text, font) not in cache:
            probe = fig.text(0, 0, text, fontsize=font, **PLAIN)
            box = probe.get_window_extent()
            probe.remove()
            cache[(text, font)] = (box.width * INCH / fig.dpi, box.height * INCH / fig.dpi)
        return cache[(text, font)]
    return size


def natural_axes(fig, bounds: Box, top: float, bottom: float, side: float = 12.0):
    """Axes showing ``bounds`` at one point per data unit, with ``top``, ``bottom`` and
    ``side`` points of figure round them."""
    width, height = bounds.x1 - bounds.x0, bounds.y1 - bounds.y0
    fw, fh = width + 2 * side, height + top + bottom
    fig.set_size_inches(fw / INCH, fh / INCH)
    ax = fig.add_axes((side / fw, bottom / fh, width / fw, height / fh))
    ax.set_xlim(bounds.x0, bounds.x1)
    ax.set_ylim(bounds.y0, bounds.y1)
    ax.set_aspect("equal")
    return ax


def fitted_scale(ax, bounds: Box) -> float:
    """Show ``bounds`` in the given axes at a uniform scale; returns that scale (the factor
    on fonts and line widths)."""
    fig = ax.figure
    box = ax.get_window_extent()
    w_pt, h_pt = box.width * INCH / fig.dpi, box.height * INCH / fig.dpi
    scale = min(w_pt / (bounds.x1 - bounds.x0), h_pt / (bounds.y1 - bounds.y0))
    ax.set_xlim(bounds.x0, bounds.x1)
    ax.set_ylim(bounds.y0, bounds.y1)
    ax.set_aspect("equal", adjustable="box")
    return scale


def fit_figure(ax, pad: float = 6.0) -> None:
    """Resize ``ax``'s figure round the axes, its title and its legend (``pad`` points
    round them), keeping the axes' size: a folded diagram may be narrower than its title
    or its key."""
    fig = ax.figure           # extents from the figure's own renderer, whatever its canvas
    box = ax.get_window_extent().frozen()     # (the live one follows the figure's size)
    parts = [box, ax.title.get_window_extent()]
    if ax.get_legend() is not None:
        parts.append(ax.get_legend().get_window_extent())
    union = Bbox.union(parts)
    inch, margin = fig.dpi, pad / INCH
    width, height = union.width / inch + 2 * margin, union.height / inch + 2 * margin
    fig.set_size_inches(width, height)
    ax.set_position(((box.x0 - union.x0) / inch / width + margin / width,
                     (box.y0 - union.y0) / inch / height + margin / height,
                     box.width / inch / width, box.height / inch / height))


def fitted_legend(ax, handles, fontsize: float, **kwargs):
    """A legend under the axes in as few rows (up to three) as keep it no wider than the
    axes; its texts plain."""
    from powergraph.plot.text import plain

    width = ax.get_window_extent().width
    for rows in (1, 2, 3):
        key = plain(ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, 0.0),
                              ncol=-(-len(handles) // rows), frameon=False,
                              fontsize=fontsize, **kwargs))
        if key.get_window_extent().width <= width:
            break
    return key
