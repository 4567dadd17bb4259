"""A duty cycle's power in, power out and loss per operating point (``powergraph cycle
--plot``)."""
from __future__ import annotations

from typing import Any

import matplotlib.pyplot as plt
import numpy as np

from powergraph.plot.text import PLAIN, plain


def plot_cycle(result: Any, ax: Any = None, **kwargs: Any):
    """Draw power in, power out and loss (kW) against time over the cycle, from the
    result's columns; returns the axes. A row that could not be solved (``keep_going``)
    is a gap in the three lines (its powers are unknown, not zero).

    >>> from powergraph.analyses.cycle import CycleResult, CycleRow
    >>> row = CycleRow(0, 1.0, None, 1000.0, 900.0, 100.0, 0.9, "ok")
    >>> plot_cycle(CycleResult.from_rows("demo", (row,), "sweep")).get_ylabel()
    'power [kW]'
    """
    if ax is None:
        _, ax = plt.subplots()
    t = np.concatenate([[0.0], np.cumsum(result.durations)])
    failed = result.failed
    for values, label in ((result.power_in, "in"), (result.power_out, "out"),
                          (result.loss, "loss")):
        ax.stairs(np.where(failed, np.nan, values / 1e3), t, label=label, **kwargs)
    ax.set_xlabel("time [s]", **PLAIN)
    ax.set_ylabel("power [kW]", **PLAIN)
    ax.set_title(f"{result.name}: duty cycle", **PLAIN)
    plain(ax.legend())
    return ax
