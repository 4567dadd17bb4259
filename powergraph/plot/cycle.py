"""A duty cycle's power in, power out and loss per operating point (``powergraph cycle
--plot``)."""
from __future__ import annotations

from typing import Any

import matplotlib.pyplot as plt
import numpy as np

from powergraph.plot.text import PLAIN, plain


def plot_cycle(result: Any, ax: Any = None, **kwargs: Any):
    """Draw power in, power out and loss (kW) against time over the cycle; returns the axes.

    >>> from powergraph.analyses.cycle import CycleResult, CycleRow
    >>> row = CycleRow(0, 1.0, None, 1000.0, 900.0, 100.0, 0.9, "ok")
    >>> plot_cycle(CycleResult("demo", (row,), "sweep")).get_ylabel()
    'power [kW]'
    """
    if ax is None:
        _, ax = plt.subplots()
    durations = np.array([r.duration for r in result.rows])
    t = np.concatenate([[0.0], np.cumsum(durations)])
    for key, label in (("power_in", "in"), ("power_out", "out"), ("loss", "loss")):
        values = np.array([getattr(r, key) for r in result.rows]) / 1e3
        ax.stairs(values, t, label=label, **kwargs)
    ax.set_xlabel("time [s]", **PLAIN)
    ax.set_ylabel("power [kW]", **PLAIN)
    ax.set_title(f"{result.name}: duty cycle", **PLAIN)
    plain(ax.legend())
    return ax
