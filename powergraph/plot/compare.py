"""Grouped bar chart of a comparison (rows from :mod:`powergraph.analyses.compare`)."""
from __future__ import annotations

from typing import Sequence

import matplotlib.pyplot as plt
import numpy as np

from powergraph.plot.text import PLAIN, plain


def plot_comparison(rows: Sequence, ax=None):
    """Efficiency forward and back (and mesh rolling) per train, as grouped bars.

    Parameters
    ----------
    rows : sequence of ComparisonRow
    ax : matplotlib Axes, optional

    Returns
    -------
    matplotlib Axes
    """
    if ax is None:
        _, ax = plt.subplots(figsize=(max(6.0, 1.6 * len(rows) + 2), 4.2))
    names = [r.name for r in rows]
    x = np.arange(len(rows))
    series = [("efficiency", [100 * r.efficiency if r.efficiency is not None else np.nan
                              for r in rows]),
              ("back-driven efficiency",
               [100 * r.backdrive_efficiency if r.backdrive_efficiency is not None else np.nan
                for r in rows])]
    width = 0.38
    for i, (label, values) in enumerate(series):
        bars = ax.bar(x + (i - 0.5) * width, values, width, label=label)
        ax.bar_label(bars, labels=[f"{v:.1f}" if np.isfinite(v) else "n/a" for v in values],
                     fontsize=7, padding=2, **PLAIN)
    ax.axhline(0.0, color="black", linewidth=0.8)
    ax.set_xticks(x, names, rotation=20, ha="right", fontsize=8, **PLAIN)
    ax.set_ylabel("efficiency (%)  — below 0: self-locking", **PLAIN)
    ax.set_title("Trains compared (virtual-power method)", **PLAIN)
    plain(ax.legend(fontsize=8))
    return ax
