"""Draw docs/img/architecture.png: the layers of powergraph and the three ways a train is
evaluated, all on the one element stencil (docs/architecture.md).

Usage::

    python scripts/architecture_figure.py [-o docs/img/architecture.png]

Uses :class:`matplotlib.figure.Figure` directly, so no backend is chosen.
"""
from __future__ import annotations

import argparse
from pathlib import Path

from matplotlib.figure import Figure
from matplotlib.patches import FancyArrowPatch, FancyBboxPatch

ROOT = Path(__file__).resolve().parents[1]

#: (label, detail) of each layer, earliest first; drawn bottom-up.
LAYERS = (
    ("base", "powergraph · errors · result · gears"),
    ("model", "YAML, schema, validation, units, bodies"),
    ("kinematics", "element_stencil · Willis rows · DOF · speeds"),
    ("statics (+ testing)", "torques · directions · locking · flow graph"),
    ("methods / analyses", "Wang 2021 · sweep · formula · backlash · cycloid · volume · …"),
    ("plot", "matplotlib, imported lazily"),
    ("cli", "powergraph COMMAND"),
)
LAYER_COLOURS = ("#e8e8e8", "#dbe9f6", "#cfe3c8", "#f9e0c0", "#f3d1dc", "#e3d7f0", "#d9d9d9")


def box(ax, x, y, w, h, text, colour, *, size=9, weight="normal"):
    """A rounded box with centred text; returns its centre."""
    ax.add_patch(FancyBboxPatch((x, y), w, h, boxstyle="round,pad=0.02,rounding_size=0.08",
                                facecolor=colour, edgecolor="#444444", linewidth=0.8))
    ax.text(x + w / 2, y + h / 2, text, ha="center", va="center", fontsize=size,
            weight=weight, wrap=True)
    return x + w / 2, y + h / 2


def arrow(ax, start, end, text="", *, colour="#333333", style="-|>", rad=0.0):
    ax.add_patch(FancyArrowPatch(start, end, arrowstyle=style, mutation_scale=11,
                                 color=colour, linewidth=1.0,
                                 connectionstyle=f"arc3,rad={rad}"))
    if text:
        ax.text((start[0] + end[0]) / 2, (start[1] + end[1]) / 2, text, fontsize=7.5,
                ha="center", va="center", color=colour,
                bbox={"facecolor": "white", "edgecolor": "none", "pad": 0.5})


def draw(figure: Figure) -> None:
    ax = figure.add_axes((0, 0, 1, 1))
    ax.set_xlim(0, 16.2)
    ax.set_ylim(0, 9)
    ax.axis("off")

    # Left: the layers, earliest at the bottom; imports go downwards only.
    ax.text(2.9, 8.6, "Layers (a module imports only from layers below it)", ha="center",
            fontsize=10, weight="bold")
    height, gap = 0.92, 0.22
    for k, ((name, detail), colour) in enumerate(zip(LAYERS, LAYER_COLOURS)):
        y = 0.3 + k * (height + gap)
        box(ax, 0.2, y, 5.4, height, f"{name}\n{detail}", colour, size=8.5)
    arrow(ax, (5.95, 7.6), (5.95, 0.6), "imports", style="-|>")

    # Right: the three ways a train is evaluated.
    ax.text(11.0, 8.6, "Three ways to evaluate a train, one physics core", ha="center",
            fontsize=10, weight="bold")
    box(ax, 6.6, 0.4, 6.0, 1.1,
        "element_stencil(i, f) = (1, −i·f, i·f − 1)\n"
        "kinematic row (f = 1) and static column", "#cfe3c8", size=8.5, weight="bold")
    box(ax, 7.4, 2.5, 3.4, 1.2,
        "symbolic systems (sympy)\nWillis rows + torque balance,\nsolved once per train",
        "#fff3c4", size=8)
    box(ax, 12.0, 2.5, 3.8, 1.2,
        "single solve\npowergraph.statics.solve\nnumpy, one operating point", "#f9e0c0",
        size=8)
    box(ax, 6.6, 4.7, 3.8, 1.3,
        "compiled sweep\npowergraph.analyses.sweep\n10⁶ variants, vectorised;\n"
        "agrees with the single solve", "#f3d1dc", size=8)
    box(ax, 11.4, 4.7, 3.8, 1.3,
        "symbolic formula\npowergraph.analyses.formula\nclosed-form ratio and η",
        "#f3d1dc", size=8)
    box(ax, 6.6, 7.0, 9.2, 0.8,
        "frozen results (Result protocol): to_dict · text_report · plot", "#e3d7f0", size=8.5)

    arrow(ax, (9.1, 1.5), (9.1, 2.5), "symbols")
    arrow(ax, (12.4, 1.5), (13.0, 2.5), "numbers")
    arrow(ax, (6.95, 1.5), (6.95, 4.7), "arrays")
    arrow(ax, (9.1, 3.7), (9.1, 4.7), "closed form per\ndirection pattern")
    arrow(ax, (10.8, 3.4), (11.4, 5.0), "derive")
    arrow(ax, (13.3, 3.7), (13.3, 4.7), "direction pattern")
    arrow(ax, (8.5, 6.0), (8.5, 7.0))
    arrow(ax, (13.3, 6.0), (13.3, 7.0))
    arrow(ax, (15.5, 3.7), (15.5, 7.0))


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-o", "--output", type=Path,
                        default=ROOT / "docs" / "img" / "architecture.png")
    args = parser.parse_args(argv)
    figure = Figure(figsize=(13, 7.3))
    draw(figure)
    figure.savefig(args.output, dpi=110)
    print(args.output)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
