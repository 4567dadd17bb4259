"""The efficiency map of a reducer: contours over output torque × input speed.

Takes an :class:`~powergraph.analyses.efficiency_map.EfficiencyMap`, computes nothing.
"""
from __future__ import annotations

from typing import Any

import numpy as np

from powergraph.plot.text import PLAIN, plain


def plot_efficiency_map(result: Any, ax: Any = None, levels: int = 12) -> Any:
    """Filled contours of the efficiency (%) with labelled lines and the rated torque.

    Parameters
    ----------
    result : EfficiencyMap
    ax : matplotlib Axes, optional
    levels : int
        Number of contour levels.

    Returns
    -------
    matplotlib Axes
    """
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots(figsize=(7, 5))
    percent = 100.0 * np.asarray(result.efficiency)
    torque, speed = np.meshgrid(result.torques, result.speeds_rpm)
    if np.ptp(percent) > 1e-9 and percent.shape[0] > 1 and percent.shape[1] > 1:
        filled = ax.contourf(torque, speed, percent, levels=levels, cmap="viridis")
        lines = ax.contour(torque, speed, percent, levels=filled.levels, colors="k",
                           linewidths=0.5)
        plain(ax.clabel(lines, fmt="%.2f", fontsize=7))
        ax.figure.colorbar(filled, ax=ax).set_label("efficiency (%)", **PLAIN)
    else:
        ax.text(0.5, 0.5, f"efficiency {percent.flat[0]:.3f} % everywhere\n"
                "(constant mesh efficiencies)", ha="center", va="center",
                transform=ax.transAxes, **PLAIN)
        ax.set_xlim(result.torques.min(), result.torques.max())
        ax.set_ylim(result.speeds_rpm.min(), result.speeds_rpm.max())
    if result.rated_torque is not None:
        ax.axvline(result.rated_torque, color="tab:red", lw=1.5, ls="--",
                   label=f"rated torque {result.rated_torque:g} N·m")
        plain(ax.legend(loc="lower right"))
    ax.set_xlabel("output torque (N·m)", **PLAIN)
    ax.set_ylabel("input speed (rpm)", **PLAIN)
    ax.set_title(f"{result.name}: efficiency map", **PLAIN)
    return ax
