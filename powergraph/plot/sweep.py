"""Plots of design sweeps. Every function takes ``ax=None``, returns the axes, and computes
nothing: the numbers come from :mod:`powergraph.analyses.sweep`.

Examples
--------
>>> import numpy as np
>>> eta = np.linspace(0.9, 1.0, 11)
>>> ax = efficiency_plot(eta, {"a": 0.5 + 0.4 * eta}, "links.1.efficiency")  # doctest: +SKIP
"""
from __future__ import annotations

from typing import Mapping, Sequence

import matplotlib.pyplot as plt
import numpy as np

from powergraph.plot.text import PLAIN, plain


def efficiency_plot(x: Sequence[float], curves: Mapping[str, Sequence[float]], xlabel: str,
                    ax: plt.Axes | None = None, title: str | None = None,
                    percent: bool = True) -> plt.Axes:
    """Efficiency against a swept value, one curve per label.

    Parameters
    ----------
    x : sequence of float
        The swept value (shared by every curve), or use :func:`curve_plot` for curves
        with their own x.
    curves : mapping label -> sequence of float
        Efficiency (output / input power) of each curve at ``x``.
    xlabel : str
    ax : matplotlib Axes, optional
        Where to draw; a new figure when None.
    title : str, optional
    percent : bool
        Plot in % (default) or as a fraction.

    Returns
    -------
    matplotlib Axes
    """
    scale = 100.0 if percent else 1.0
    return curve_plot({label: (x, scale * np.asarray(y, float)) for label, y in curves.items()},
                      xlabel, "efficiency [%]" if percent else "efficiency", ax=ax,
                      title=title, zero_line="self-locking below 0")


def ratio_plot(x: Sequence[float], curves: Mapping[str, Sequence[float]], xlabel: str,
               ax: plt.Axes | None = None, title: str | None = None) -> plt.Axes:
    """Ratio (input speed / output speed) against a swept value, one curve per label."""
    return curve_plot({label: (x, y) for label, y in curves.items()}, xlabel,
                      "ratio (input / output speed)", ax=ax, title=title)


def curve_plot(curves: Mapping[str, tuple[Sequence[float], Sequence[float]]], xlabel: str,
               ylabel: str, ax: plt.Axes | None = None, title: str | None = None,
               zero_line: str | None = None) -> plt.Axes:
    """Curves ``{label: (x, y)}``; NaN points (variants not solved) leave gaps.

    ``zero_line`` draws and labels y = 0 when the curves cross it.
    """
    if ax is None:
        _, ax = plt.subplots(figsize=(6.4, 4.0))
    low = np.inf
    for label, (xs, ys) in curves.items():
        ys = np.asarray(ys, dtype=float)
        ax.plot(np.asarray(xs, dtype=float), ys, marker="." if len(ys) <= 40 else None,
                lw=1.3, label=label or None)
        if np.isfinite(ys).any():
            low = min(low, float(np.nanmin(ys)))
    if zero_line and low <= 0:
        ax.axhline(0.0, color="0.3", lw=0.8, ls="--", label=zero_line)
    ax.set_xlabel(xlabel, **PLAIN)
    ax.set_ylabel(ylabel, **PLAIN)
    if title:
        ax.set_title(title, fontsize=9, **PLAIN)
    ax.grid(True, alpha=0.3)
    if any(curves) and len(curves) <= 12 or zero_line and low <= 0:
        plain(ax.legend(fontsize=7))
    return ax
