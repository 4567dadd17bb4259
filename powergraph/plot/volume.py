"""Plots of the volume analysis (Pan & Wang 2019, docs/volume.md). Every function takes ``ax=None``, returns the
axes, and computes nothing: the numbers come from :mod:`powergraph.analyses.volume`.

Examples
--------
>>> from powergraph.analyses.volume import pitch_circle_errors
>>> table = pitch_circle_errors(range(12, 81))                  # doctest: +SKIP
>>> ax = pitch_circle_error_plot(table.teeth, table.relative_error)  # doctest: +SKIP
"""
from __future__ import annotations

from typing import Mapping, Sequence

import matplotlib.pyplot as plt

from powergraph.plot.text import PLAIN, plain


def pitch_circle_error_plot(teeth: Sequence[int], relative_error: Sequence[float],
                            ax: plt.Axes | None = None,
                            marks: Mapping[str, tuple[int, float]] | None = None,
                            title: str | None = None) -> plt.Axes:
    """Error of the pitch-circle volume (Eqs. 1–2) against the tooth number.

    Parameters
    ----------
    teeth : sequence of int
        Tooth numbers (e.g. 12…80).
    relative_error : sequence of float
        (π(mz/2)² − A_exact) / A_exact for each, as a fraction (plotted in %).
    ax : matplotlib Axes, optional
        Where to draw; a new figure when None.
    marks : mapping label -> (teeth, relative_error), optional
        Points to highlight, e.g. the gears of a model.
    title : str, optional

    Returns
    -------
    matplotlib Axes
    """
    if ax is None:
        _, ax = plt.subplots(figsize=(6.4, 4.0))
    ax.plot(list(teeth), [100 * e for e in relative_error], marker=".", lw=1.2,
            label="pitch-circle cylinder vs generated involute profile")
    for label, (z, error) in (marks or {}).items():
        ax.plot([z], [100 * error], "o", ms=7, mfc="none", label=label)
        ax.annotate(f"z = {z}: {100 * error:.2f} %", (z, 100 * error),
                    textcoords="offset points", xytext=(8, 6), fontsize=8,
                    **PLAIN)
    ax.set_xlabel("number of teeth z", **PLAIN)
    ax.set_ylabel("volume error of π(mz/2)²·B  [%]", **PLAIN)
    ax.set_title(title or "Pan & Wang Eqs. (1)–(2): error of the pitch-circle volume\n"
                          "(α = 20°, addendum 1·m, dedendum 1.25·m, tip fillet 0.38·m, x = 0)",
                 fontsize=9, **PLAIN)
    ax.grid(True, alpha=0.3)
    ax.margins(y=0.12)
    ax.set_ylim(bottom=0)
    plain(ax.legend(fontsize=8))
    return ax
