"""The efficiency map of a reducer: contours over output torque × input speed.

Takes an :class:`~powergraph.analyses.efficiency_map.EfficiencyMap`, computes nothing.
The coasting side (output torque < 0: the output drives the train) and the driving side
(> 0) are drawn apart, each with its own contours on one colour scale, named at the top;
the no-load line (torque 0, where the efficiency is undefined) is a dashed line between
them, and self-locking points (no power comes out) are crossed.
"""
from __future__ import annotations

from typing import Any

import numpy as np

from powergraph.plot.text import PLAIN, plain

#: The names of the sides, drawn at the top of each.
SIDE_LABELS = {-1: "coasting (output drives)", 1: "driving (input drives)"}
#: Self-locking points are crossed when there are at most this many (more would hide
#: the map; the contours then show their 0 %).
MOST_MARKS = 400


def plot_efficiency_map(result: Any, ax: Any = None, levels: int = 12) -> Any:
    """Filled contours of the efficiency (%) with labelled lines, per side, and the rated
    torque.

    Parameters
    ----------
    result : EfficiencyMap
    ax : matplotlib Axes, optional
    levels : int
        Number of contour levels (shared by both sides).

    Returns
    -------
    matplotlib Axes
    """
    import matplotlib.pyplot as plt
    from matplotlib.ticker import MaxNLocator

    torques, speeds = np.asarray(result.torques), np.asarray(result.speeds_rpm)
    sides = np.sign(torques).astype(int)
    both = bool(np.any(sides < 0) and np.any(sides > 0))
    if ax is None:
        _, ax = plt.subplots(figsize=(9, 5) if both else (7, 5))
    percent = 100.0 * np.asarray(result.efficiency, dtype=float)
    finite = percent[np.isfinite(percent)]
    varies = finite.size > 1 and np.ptp(finite) > 1e-9
    bounds = MaxNLocator(levels).tick_values(finite.min(), finite.max()) if varies else None
    filled = None
    for side in (-1, 1):
        columns = np.flatnonzero(sides == side)
        if not columns.size:
            continue
        values = percent[:, columns]
        shown = values[np.isfinite(values)]
        if (bounds is not None and columns.size > 1 and speeds.size > 1 and shown.size
                and np.ptp(shown) > 1e-9):
            torque, speed = np.meshgrid(torques[columns], speeds)
            filled = ax.contourf(torque, speed, values, levels=bounds, cmap="viridis")
            lines = ax.contour(torque, speed, values, levels=bounds, colors="k",
                               linewidths=0.5)
            plain(ax.clabel(lines, fmt="%.2f", fontsize=7))
        else:
            _flat_side(ax, result, torques[columns], shown, side, both)
    if filled is not None:
        ax.figure.colorbar(filled, ax=ax).set_label("efficiency (%)", **PLAIN)
    _limits(ax, torques, speeds)
    _marks(ax, result, torques, speeds, sides)
    ax.set_xlabel("output torque (N·m; < 0: coasting, the output drives)" if np.any(sides < 0)
                  else "output torque (N·m)", **PLAIN)
    ax.set_ylabel("input speed (rpm)", **PLAIN)
    ax.set_title(f"{result.name}: efficiency map", **PLAIN)
    return ax


def _flat_side(ax: Any, result: Any, torques: np.ndarray, shown: np.ndarray, side: int,
               both: bool) -> None:
    """A side that does not vary (or has one column): its value written in its middle."""
    if not shown.size:
        text = "efficiency undefined"
    elif not shown.any():
        text = "self-locking: efficiency 0 %" + ("" if both else " everywhere")
    elif np.ptp(shown) <= 1e-9:
        text = f"efficiency {shown[0]:.3f} %" + ("" if both else " everywhere")
    else:
        text = f"efficiency {shown.min():.3f}–{shown.max():.3f} %"
    if not result.load_dependent:
        text += "\n(constant mesh efficiencies)"
    middle = 0.5 * (torques.min() + torques.max())
    ax.text(middle, 0.5, text, ha="center", va="center", transform=ax.get_xaxis_transform(),
            bbox={"facecolor": "white", "alpha": 0.8, "edgecolor": "none"}, **PLAIN)


def _limits(ax: Any, torques: np.ndarray, speeds: np.ndarray) -> None:
    """The torque and speed ranges, widened a little when a range is one value."""
    for values, setter in ((torques, ax.set_xlim), (speeds, ax.set_ylim)):
        low, high = float(values.min()), float(values.max())
        if high == low:
            pad = 0.1 * abs(low) or 1.0
            low, high = low - pad, high + pad
        setter(low, high)


def _marks(ax: Any, result: Any, torques: np.ndarray, speeds: np.ndarray,
           sides: np.ndarray) -> None:
    """The sides' names, the no-load line, the self-locking points and the rated torque,
    with a legend when any of them is drawn."""
    if np.any(sides < 0):
        for side, x in ((-1, 0.01), (1, 0.99)):
            if np.any(sides == side):
                ax.text(x, 0.98, SIDE_LABELS[side], ha="left" if side < 0 else "right",
                        va="top", fontsize=9, transform=ax.transAxes,
                        bbox={"facecolor": "white", "alpha": 0.8, "edgecolor": "none"},
                        **PLAIN)
        if torques.min() <= 0.0 <= torques.max():
            ax.axvline(0.0, color="0.4", lw=1.0, ls=":",
                       label="no load (efficiency undefined)")
    locking = result.self_locking
    if 0 < len(locking) <= MOST_MARKS:
        rpm, torque = np.array(locking).T
        ax.plot(torque, rpm, "x", color="tab:orange", ms=5, clip_on=False,
                label="self-locking (no power comes out)")
    if result.rated_torque is not None:
        ax.axvline(result.rated_torque, color="tab:red", lw=1.5, ls="--",
                   label=f"rated torque {result.rated_torque:g} N·m")
    if ax.get_legend_handles_labels()[0]:
        plain(ax.legend(loc="lower right", fontsize=8))
