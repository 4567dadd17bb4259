"""Chart of a gear table (powergraph.analyses.gear_table): ratio per mode as bars,
efficiency forward and coasting as markers on a second axis."""
from __future__ import annotations

import numpy as np

from powergraph.plot.text import PLAIN, plain


def plot_gear_table(table, ax=None):
    """Bars of |ratio| per mode (reverse hatched), efficiencies on the right axis.

    Parameters
    ----------
    table : GearTable
    ax : matplotlib Axes, optional

    Returns
    -------
    matplotlib Axes

    Examples
    --------
    >>> from powergraph.model import load_model                          # doctest: +SKIP
    >>> from powergraph.analyses.gear_table import gear_table            # doctest: +SKIP
    >>> ax = gear_table(load_model("models/zf8hp_8speed.yaml")).plot()   # doctest: +SKIP
    """
    if ax is None:
        import matplotlib.pyplot as plt

        _, ax = plt.subplots(figsize=(7.0, 4.2))
    rows = table.rows
    x = np.arange(len(rows))
    ratios = [abs(r.ratio) for r in rows]
    bars = ax.bar(x, ratios, color=["#4c72b0" if r.ratio > 0 else "#dd8452" for r in rows],
                  hatch=None)
    ax.bar_label(bars, labels=[f"{r.ratio:.3f}" for r in rows], fontsize=7, padding=2,
                 **PLAIN)
    ax.set_xticks(x, [r.mode for r in rows], **PLAIN)   # mode names as written
    ax.set_xlabel("mode", **PLAIN)
    ax.set_ylabel("|ratio| (input/output speed); orange: reverse", **PLAIN)
    right = ax.twinx()
    # Forward gears joined in their order; a reverse gear is a point of its own.
    groups = [[i for i, r in enumerate(rows) if (r.ratio > 0) == sign] for sign in (True, False)]
    for k, index in enumerate(groups):
        style = "-" if k == 0 else ""
        right.plot(index, [np.nan if rows[i].efficiency is None
                           else 100 * rows[i].efficiency for i in index], "o" + style,
                   color="black", label=None if k else "efficiency, driving")
        right.plot(index, [np.nan if rows[i].coast_efficiency is None
                           else 100 * rows[i].coast_efficiency for i in index],
                   "s--" if k == 0 else "s", color="gray",
                   label=None if k else "efficiency, coasting")
    right.set_ylabel("efficiency (%)", **PLAIN)
    plain(right.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=2,
                       frameon=False))
    spread = table.spread
    ax.set_title(f"{table.name}" + (f" — spread {spread:.3f}" if spread else ""),
                 **PLAIN)
    return ax
