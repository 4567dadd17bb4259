"""Regenerate Wang (2021)'s Figs. 12–13 by both methods, as PNG and SVG.

Usage::

    python scripts/wang2021_figures.py [-o docs/img] [--model models/rv40e_wang2021.yaml]

Writes, for the model (default the RV-40E):

- ``fig12_mesh_efficiency``: η against the single-pair mesh efficiency (0.90–1.00);
- ``fig12_equivalent_cycloid_efficiency``: the cycloid–pin efficiency at which the
  virtual-power method gives the paper's η;
- ``fig13_ratio_cycloid_teeth``: η against the ratio, z5 varied with z4 = z5 − 1, with a
  zoom on the paper's curve (it rises: tests/data/published_values.yaml);
- ``fig13_ratio_first_stage``: η against the ratio, z2/z1 varied.

Each figure carries its caption; the captions are also printed.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _figure(name: str, data):
    from matplotlib.figure import Figure   # files only: no pyplot, no backend chosen

    from powergraph.plot.wang2021 import add_caption, plot_figure, plot_paper_trend

    if name == "fig13_ratio_cycloid_teeth":
        figure = Figure(figsize=(11.5, 4.4))
        left, right = figure.subplots(1, 2)
        plot_figure(data, ax=left, marks=False)
        plot_paper_trend(data, ax=right)
        figure.subplots_adjust(wspace=0.3, left=0.07, right=0.98)
    else:
        figure = Figure(figsize=(7.5, 4.6))
        ax = figure.subplots()
        plot_figure(data, ax=ax)
    add_caption(figure, data.caption)
    return figure


def write_figures(model_path: str | Path, out_dir: str | Path) -> list[Path]:
    """Compute every figure of the model and write ``NAME.png`` and ``NAME.svg``.

    Returns the written paths.
    """
    import matplotlib

    from powergraph.methods.figures import FIGURES
    from powergraph.model import load_model

    matplotlib.rcParams["svg.hashsalt"] = "powergraph"   # reproducible SVG ids
    model = load_model(model_path)
    out = Path(out_dir)
    written: list[Path] = []
    for name, build in FIGURES.items():
        data = build(model)
        figure = _figure(name, data)
        for suffix, metadata in ((".png", {"Software": None}), (".svg", {"Date": None})):
            path = out / f"{name}{suffix}"
            figure.savefig(path, dpi=130, metadata=metadata)
            written.append(path)
        print(f"{name}: {data.caption}\n")
    return written


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("-o", "--output", default=str(ROOT / "docs" / "img"),
                        help="folder for the PNG and SVG files (default docs/img)")
    parser.add_argument("--model", default=str(ROOT / "models" / "rv40e_wang2021.yaml"),
                        help="RV-type model file (default models/rv40e_wang2021.yaml)")
    args = parser.parse_args(argv)
    out = Path(args.output)
    out.mkdir(parents=True, exist_ok=True)
    for path in write_figures(args.model, out):
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
