"""A duty cycle over time (``powergraph cycle --plot``): power in, power out and loss per
operating point; for a train with machines, the engine's (every other port's), each
machine's and each battery's power, and under it the electrical path's share.

A row that could not be solved (``keep_going``) is a gap in every line: its values are
unknown, not zero. In a cycle in modes every other run of rows in one mode is shaded, and
each run wide enough for it is named at the top of the powers' axes.
"""
from __future__ import annotations

from typing import Any

import matplotlib.pyplot as plt
import numpy as np

from powergraph.plot.text import PLAIN, plain

#: The figure of a cycle with machines: its size (inches) and the panels' heights.
HYBRID_FIGSIZE, HYBRID_HEIGHTS = (7.5, 5.4), (2.2, 1.0)
#: The electrical share's scale stops at ± this (%).
SHARE_LIMIT = 500.0
#: The figure of a cycle without machines.
FIGSIZE = (6.4, 4.8)
#: A run of rows in one mode is named when it spans at least this share of the time.
NAMED_RUN = 0.07


def cycle_axes(figure: Any, result: Any) -> Any:
    """The axes :func:`plot_cycle` draws ``result`` into on ``figure``: one, or for a
    cycle with machines two sharing the time axis (powers above, the share below)."""
    if not result.machines:
        return figure.subplots()
    return list(figure.subplots(2, 1, sharex=True, height_ratios=HYBRID_HEIGHTS))


def figure_size(result: Any) -> tuple[float, float]:
    """The size (inches) of the figure :func:`cycle_axes` fills."""
    return HYBRID_FIGSIZE if result.machines else FIGSIZE


def plot_cycle(result: Any, ax: Any = None, **kwargs: Any):
    """Draw the cycle against time from the result's columns.

    Without machines: power in, power out and loss (kW) on one axes, returned. With
    machines: each port's power other than the machines' (fed in at an input, taken out
    at an output), each machine's mechanical power (> 0 motoring) and each battery's
    power (> 0 discharging into its bus), kW; then the electrical share (%), the rows
    in a negative split shaded. ``ax`` None draws both panels on a new figure, a
    sequence of two axes takes them, and one axes takes the powers only; returns the
    axes drawn (a list of two for both panels). ``kwargs`` go to every line.

    >>> from powergraph.analyses.cycle import CycleResult, CycleRow
    >>> row = CycleRow(0, 1.0, None, 1000.0, 900.0, 100.0, 0.9, "ok")
    >>> plot_cycle(CycleResult.from_rows("demo", (row,), "sweep")).get_ylabel()
    'power [kW]'
    """
    if not result.machines:
        if ax is None:
            _, ax = plt.subplots()
        _plain_powers(result, ax, kwargs)
        return ax
    if ax is None:
        _, axes = plt.subplots(2, 1, sharex=True, figsize=HYBRID_FIGSIZE,
                               height_ratios=HYBRID_HEIGHTS)
        ax = list(axes)
    if not isinstance(ax, (list, tuple, np.ndarray)):
        _hybrid_powers(result, ax, kwargs)
        ax.set_xlabel("time [s]", **PLAIN)
        return ax
    top, bottom = ax[0], ax[1]
    _hybrid_powers(result, top, kwargs)
    _share(result, bottom, kwargs)
    top.tick_params(labelbottom=False)
    return [top, bottom]


def _edges(result: Any) -> np.ndarray:
    """The rows' start and end times: 0, then the durations' running sum."""
    return np.concatenate([[0.0], np.cumsum(result.durations)])


def _plain_powers(result: Any, ax: Any, kwargs: dict) -> None:
    t, failed = _edges(result), result.failed
    for values, label in ((result.power_in, "in"), (result.power_out, "out"),
                          (result.loss, "loss")):
        ax.stairs(np.where(failed, np.nan, values / 1e3), t, label=label, **kwargs)
    _modes(result, ax)
    ax.set_xlabel("time [s]", **PLAIN)
    ax.set_ylabel("power [kW]", **PLAIN)
    ax.set_title(f"{result.name}: duty cycle", **PLAIN)
    plain(ax.legend())


def _hybrid_powers(result: Any, ax: Any, kwargs: dict) -> None:
    """The ports', machines' and batteries' powers, kW; a line at zero."""
    t = _edges(result)
    colors = iter(plt.rcParams["axes.prop_cycle"].by_key()["color"] * 4)
    ax.axhline(0.0, color="0.6", linewidth=0.8, zorder=0)
    lines = [(v, name, "-") for name, v in result.port_power.items()]
    lines += [(m["power"], name, "--") for name, m in result.machines.items()]
    lines += [(v, f"battery {bus}", ":") for bus, v in result.battery_power.items()]
    for values, label, style in lines:
        options = {"linewidth": 1.6 if style == "-" else 1.4, "linestyle": style,
                   "color": next(colors), **kwargs}
        ax.stairs(values / 1e3, t, label=label, baseline=None, **options)
    _modes(result, ax)
    ax.set_ylabel("power [kW]", **PLAIN)
    ax.set_title(f"{result.name}: duty cycle", **PLAIN)
    ax.grid(True, linewidth=0.4, alpha=0.5)
    plain(ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0,
                    fontsize="small", title="> 0: an input feeding in,\nan output taking out,\n"
                    "a machine motoring,\na battery discharging", title_fontsize="small", alignment="left"))


def _modes(result: Any, ax: Any) -> None:
    """Every other run of rows in one mode shaded, the runs that span at least
    :data:`NAMED_RUN` of the time named at the top (nothing without a mode column)."""
    if result.mode_codes is None or not len(result.mode_codes):
        return
    t, codes = _edges(result), np.asarray(result.mode_codes)
    starts = np.flatnonzero(np.diff(codes, prepend=-1) != 0)
    ends = np.append(starts[1:], len(codes))
    runs = list(zip(t[starts], t[ends]))
    ax.broken_barh([(a, b - a) for a, b in runs[1::2]], (0.0, 1.0), color="0.5", alpha=0.1,
                   linewidth=0, transform=ax.get_xaxis_transform(), zorder=0)
    ax.set_ylim(top=ax.get_ylim()[1] + 0.12 * np.ptp(ax.get_ylim()))   # room for the names
    for (a, b), first in zip(runs, starts):
        if b - a >= NAMED_RUN * t[-1]:
            ax.text((a + b) / 2, 0.985, result.mode_names[codes[first]], ha="center",
                    va="top", fontsize="x-small", transform=ax.get_xaxis_transform(),
                    clip_on=True, **PLAIN)


def _clip(ax: Any, share: np.ndarray) -> None:
    """Keep the share's scale within ±:data:`SHARE_LIMIT` % (a row whose outputs take
    almost no power has a share without bound), saying so when a row runs off it."""
    finite = share[np.isfinite(share)]
    if not len(finite) or np.max(np.abs(finite)) <= SHARE_LIMIT:
        return
    low, high = max(np.min(finite), -SHARE_LIMIT), min(np.max(finite), SHARE_LIMIT)
    pad = 0.05 * (high - low) or 1.0
    ax.set_ylim(low - pad, high + pad)
    ax.text(1.01, 0.0, f"off the scale:\nrows beyond ±{SHARE_LIMIT:g} %",
            transform=ax.transAxes, ha="left", va="bottom", fontsize="small", **PLAIN)


def _share(result: Any, ax: Any, kwargs: dict) -> None:
    """The electrical share (%) over time; the rows in a negative split shaded."""
    t = _edges(result)
    ax.axhline(0.0, color="0.6", linewidth=0.8, zorder=0)
    split = np.asarray(result.negative_split, dtype=bool)
    if split.any():
        padded = np.concatenate([[False], split, [False]]).astype(np.int8)
        starts = np.flatnonzero(np.diff(padded) == 1)
        ends = np.flatnonzero(np.diff(padded) == -1)
        ax.broken_barh(list(zip(t[starts], t[ends] - t[starts])), (0.0, 1.0),
                       transform=ax.get_xaxis_transform(), color="tab:red", alpha=0.12,
                       linewidth=0, label="negative split")
    share = 100 * np.asarray(result.electrical_share)
    ax.stairs(share, t, baseline=None, label="electrical share",
              **{"color": "black", "linewidth": 1.2, **kwargs})
    _clip(ax, share)
    ax.set_ylabel("electrical\nshare [%]", **PLAIN)
    ax.set_xlabel("time [s]", **PLAIN)
    ax.grid(True, linewidth=0.4, alpha=0.5)
    plain(ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0,
                    fontsize="small"))
