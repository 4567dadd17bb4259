"""Plots for the backlash analysis (Li et al. 2012, docs/backlash.md). Each takes ``ax=None``, returns the axes,
and computes nothing: give it results of :mod:`powergraph.analyses.backlash`.

Examples
--------
>>> from powergraph.analyses.backlash import centre_distance_curve
>>> ax = plot_centre_distance(centre_distance_curve(2.5, 0.025, 0.018, 45, 40))
>>> ax.get_xlabel()
'eccentric shaft angle (turns)'
"""
from __future__ import annotations

from typing import Mapping, Sequence

import matplotlib.pyplot as plt

from powergraph.plot.text import PLAIN, plain

TERM_COLOURS = {"thickness": "tab:blue", "runout": "tab:orange", "bearing": "tab:green"}


def _axes(ax):
    if ax is None:
        _, ax = plt.subplots(figsize=(7, 3.5))
    return ax


def plot_centre_distance(curve, ax=None, label: str | None = None, bounds: bool = True):
    """Fig. 3 of Li et al. (2012): centre distance |AB| over the eccentric's turns.

    Parameters
    ----------
    curve : CentreDistanceCurve
    ax : matplotlib axes, optional
    label : str, optional
        Legend label of the curve.
    bounds : bool
        Also draw Eq. (5)'s maximum and Eq. (6)'s minimum as dashed lines.
    """
    ax = _axes(ax)
    line, = ax.plot(curve.turns, curve.distance, lw=1.2,
                    label=label or f"|AB|, offset {curve.offset:g} mm")
    if bounds:
        ax.axhline(curve.maximum, ls="--", lw=0.8, color=line.get_color(),
                   label=f"Eq. (5) max {curve.maximum:.4f} mm")
        ax.axhline(curve.minimum, ls=":", lw=0.8, color=line.get_color(),
                   label=f"Eq. (6) min {curve.minimum:.4f} mm")
    ax.set_xlabel("eccentric shaft angle (turns)", **PLAIN)
    ax.set_ylabel("centre distance |AB| (mm)", **PLAIN)
    ax.set_title(f"Centre distance, Z1 = {curve.z_internal}, Z2 = {curve.z_external} "
                 f"(period {curve.period_turns} turns)", **PLAIN)
    ax.margins(y=0.3)
    plain(ax.legend(fontsize="small", loc="upper center", ncol=3, frameon=False))
    return ax


def plot_lost_motion(pairs: Mapping[str, object], ax=None,
                     printed: Mapping[str, Sequence[tuple[str, float]]] | None = None):
    """Stacked bars of each pair's lost-motion terms before compensation and after.

    Parameters
    ----------
    pairs : mapping
        ``{label: PairBacklash}``.
    ax : matplotlib axes, optional
    printed : mapping, optional
        ``{label: [(what, arcmin), ...]}`` printed values to mark beside each pair's bars.
    """
    ax = _axes(ax)
    labels = list(pairs)
    for i, name in enumerate(labels):
        terms = pairs[name].lost_motion_arcmin
        bottom = 0.0
        for term, colour in TERM_COLOURS.items():
            ax.bar(i - 0.18, terms[term], 0.34, bottom=bottom, color=colour,
                   label=term if i == 0 else None)
            bottom += terms[term]
        ax.bar(i + 0.18, terms["after"], 0.34, color=TERM_COLOURS["runout"], hatch="//",
               edgecolor="white", label="after (at a'')" if i == 0 else None)
        for what, value in (printed or {}).get(name, ()):
            ax.plot([i - 0.4, i + 0.4], [value, value], color="black", lw=0.8)
            ax.annotate(what, (i + 0.4, value), fontsize="x-small", va="center", **PLAIN)
    ax.set_xticks(range(len(labels)), labels, **PLAIN)
    ax.set_ylabel("lost motion (arcmin, internal gear)", **PLAIN)
    ax.set_title("Lost motion: before compensation (stacked terms) and after", **PLAIN)
    ax.margins(y=0.25)
    plain(ax.legend(fontsize="small", loc="upper center", ncol=4, frameon=False))
    return ax
