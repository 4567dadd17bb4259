"""Plots of a tolerance analysis: output histograms with specification lines, and the
tornado chart of the Sobol indices. Every function takes ``ax=None``, returns the axes and
computes nothing (the numbers, and the outputs' labels, come from the result it is given:
it never imports :mod:`powergraph.analyses.tolerance`);
matplotlib is imported when a function is called.

Examples
--------
>>> import numpy as np
>>> ax = output_histogram(np.random.default_rng(0).random(1000), "lost motion (arcmin)",
...                       limits=[0.9])                                   # doctest: +SKIP
>>> ax = tornado({"a": {"first": 0.7, "total": 0.75}, "b": {"first": 0.2, "total": 0.25}})
...                                                                       # doctest: +SKIP
"""
from __future__ import annotations

from typing import Mapping, Sequence

import numpy as np

from powergraph.plot.text import PLAIN, plain


def _axes(ax, figsize=(6.4, 4.0)):
    if ax is not None:
        return ax
    import matplotlib.pyplot as plt

    return plt.subplots(figsize=figsize)[1]


def output_histogram(values: np.ndarray, label: str, limits: Sequence[float] = (),
                     ax=None, bins: int = 100, title: str | None = None):
    """Histogram (density) of one output over the units, a dashed line at each spec limit.

    Parameters
    ----------
    values : ndarray
        The output of every unit (NaN are left out).
    label : str
        x-axis label, with the unit.
    limits : sequence of float
        Specification limits to mark.
    ax : matplotlib Axes, optional
    bins : int
    title : str, optional

    Returns
    -------
    matplotlib Axes
    """
    ax = _axes(ax)
    finite = np.asarray(values)[np.isfinite(values)]
    ax.hist(finite, bins=bins, density=True, color="#4C72B0", alpha=0.8)
    for limit in limits:
        ax.axvline(limit, color="#C44E52", linestyle="--", linewidth=1.5,
                   label=f"spec {limit:g}")
    if len(limits):
        plain(ax.legend(frameon=False))
    ax.set_xlabel(label, **PLAIN)
    ax.set_ylabel("probability density", **PLAIN)
    if title:
        ax.set_title(title, **PLAIN)
    return ax


def tornado(indices: Mapping[str, Mapping[str, float]], ax=None, title: str | None = None):
    """Horizontal bars of the total (light) and first-order (dark) Sobol index of each
    PATH, largest total on top.

    Parameters
    ----------
    indices : mapping
        ``{PATH: {"first": S1, "total": ST}}``.
    ax : matplotlib Axes, optional
    title : str, optional

    Returns
    -------
    matplotlib Axes
    """
    ax = _axes(ax, figsize=(6.4, 0.5 + 0.45 * max(1, len(indices))))
    ranked = sorted(indices.items(), key=lambda kv: kv[1]["total"])
    names = [name for name, _ in ranked]
    y = np.arange(len(names))
    ax.barh(y, [s["total"] for _, s in ranked], color="#8DA0CB", label="total")
    ax.barh(y, [s["first"] for _, s in ranked], height=0.45, color="#1F3A93",
            label="first order")
    ax.set_yticks(y, names, **PLAIN)
    ax.set_xlim(0, max(1.0, max((s["total"] for _, s in ranked), default=1.0)))
    ax.set_xlabel("Sobol index", **PLAIN)
    plain(ax.legend(frameon=False, loc="lower right"))
    if title:
        ax.set_title(title, **PLAIN)
    return ax


def plot_tolerance(result, ax=None):
    """Every output's histogram with its spec limits, then the tornado chart of the
    top-level sensitivity, in one column.

    Parameters
    ----------
    result : ToleranceResult
    ax : matplotlib Axes or sequence of Axes, optional
        One per panel (outputs, then the tornado if there are indices); a single Axes gets
        the first output's histogram only, and is returned as it is.

    Returns
    -------
    list of matplotlib Axes, or the single Axes given
    """
    outputs = list(result.values)
    panels = len(outputs) + (1 if result.primary else 0)
    if ax is None:
        import matplotlib.pyplot as plt

        fig, axes = plt.subplots(panels, 1, figsize=(6.8, 3.2 * panels), squeeze=False)
        ax = list(axes[:, 0])
    single = not isinstance(ax, (list, tuple, np.ndarray))
    ax = list(np.atleast_1d(ax))
    for name, axis in zip(outputs, ax):
        label, unit = result.output_label(name)
        limits = [y.spec.value for y in result.yields if y.spec.output == name]
        output_histogram(result.values[name], f"{label}{f' ({unit})' if unit else ''}",
                         limits, ax=axis, title=f"{result.name}: {label}, "
                                                f"{result.samples} units")
    if result.primary and len(ax) > len(outputs):
        tornado(dict(result.ranked()), ax=ax[len(outputs)],
                title=f"Sobol indices of {result.output_label(result.primary)[0]}")
    ax[0].figure.tight_layout()
    return ax[0] if single else ax
