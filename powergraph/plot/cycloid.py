"""Figures of the cycloid fluctuation (Csobán 2021, Figs. 9–18).

Every function takes a result of :mod:`powergraph.analyses.cycloid` and ``ax=None``, draws,
and returns the axes. Nothing is computed here: the curves (the deviations too) come from
the result, and this module never imports :mod:`powergraph.analyses.cycloid`.
"""
from __future__ import annotations

import numpy as np
import matplotlib.pyplot as plt

from powergraph.plot.text import PLAIN, plain


def _axes(ax, projection: str | None = None):
    if ax is not None:
        return ax
    fig = plt.figure(figsize=(7.5, 4.5) if projection is None else (7.5, 6.0))
    return fig.add_subplot(projection=projection)


def _title(result) -> str:
    g = result.geometry
    return (f"m = {g.module:g} mm, z1 = {g.teeth}, x = {g.shift:g}, rc* = {g.rc:g}, "
            f"d = {result.profile_error:g} mm")


def plot_ratio_fluctuation(result, ax=None, paper: bool = True):
    """Instantaneous ratio against crank angle, one colour per contact segment (Figs. 10).

    The segment ends are the exact one-sided ratios at the pin hand-overs (dotted lines);
    with ``paper=True`` the paper's 2° central differences (Eq. 10) are drawn as markers.
    """
    ax = _axes(ax)
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for j, (_, angle, ratio) in enumerate(result.contact_segments()):
        degrees = np.degrees(angle)
        colour = colours[j % 2]
        ax.plot(degrees, ratio, color=colour, lw=1.2,
                label="exact (contact segments)" if j == 0 else None)
        if degrees[-1] > 360.0:  # the segment that runs past one revolution
            ax.plot(degrees - 360.0, ratio, color=colour, lw=1.2)
    for angle in np.degrees(result.handover_angle):
        ax.axvline(angle, color="0.75", lw=0.6, ls=":")
    if paper:
        ax.plot(np.degrees(result.paper_crank_angle), result.paper_ratio, "k.", ms=3,
                label="paper: 2° central differences (Eq. 10)")
    ax.axhline(result.ratio_nominal, color="0.4", lw=0.8, ls="--",
               label=f"no error: i = {result.ratio_nominal:g}")
    ax.set_xlim(0.0, 360.0)
    ax.set_xlabel("crank (input) angle φ1, °", **PLAIN)
    ax.set_ylabel("ratio i = dφ1/dφ2", **PLAIN)
    ax.set_title(_title(result), fontsize=9, **PLAIN)
    plain(ax.legend(fontsize=8, loc="best"))
    return ax


def plot_deviation(result, ax=None, label: str | None = None):
    """Percentage deviation ``Δi`` (Eq. 11) against crank angle (Figs. 11–14).

    Call repeatedly on one axes to compare cases (``label`` names the curve).
    """
    ax = _axes(ax)
    colour = None
    for _, angle, deviation in result.deviation_segments():
        degrees = np.degrees(angle)
        for offset in ((0.0, 360.0) if degrees[-1] > 360.0 else (0.0,)):
            (line,) = ax.plot(degrees - offset, deviation, lw=1.1, color=colour,
                              label=label if colour is None else None)
            colour = line.get_color()
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.set_xlim(0.0, 360.0)
    ax.set_xlabel("crank (input) angle φ1, °", **PLAIN)
    ax.set_ylabel("Δi = (i_ideal − i)/i_ideal, %", **PLAIN)
    if label is None:
        ax.set_title(_title(result), fontsize=9, **PLAIN)
    else:
        plain(ax.legend(fontsize=8))
    return ax


def plot_output_angle(result, ax=None):
    """Output (disc) angle against crank angle, with the ideal straight line (Fig. 9)."""
    ax = _axes(ax)
    crank = np.degrees(result.crank_angle)
    ax.plot(crank, -np.degrees(result.output_angle), ".", ms=2, label="with profile error")
    ax.plot(crank, crank / result.ratio_nominal, lw=0.8, label="no error")
    ax.set_xlabel("crank (input) angle φ1, °", **PLAIN)
    ax.set_ylabel("disc (output) angle −φ2, °", **PLAIN)
    ax.set_title(_title(result), fontsize=9, **PLAIN)
    plain(ax.legend(fontsize=8))
    return ax


def plot_fluctuation_study(study, ax=None, paper: bool = True):
    """Maximum fluctuation over the grid and the fitted surfaces, 3-D (Figs. 15–18)."""
    ax = _axes(ax, projection="3d")
    teeth = np.linspace(study.teeth.min(), study.teeth.max(), 40)
    error = np.linspace(0.0, study.profile_error.max(), 20)
    z_grid, d_grid = np.meshgrid(teeth, error)
    ax.plot_wireframe(z_grid, d_grid, study.fitted(d_grid, z_grid), color="C0", lw=0.5,
                      rstride=2, cstride=4,
                      label=f"refit: {study.a:.4g}·d + {study.b:.6g}·d·z1^-1.5")
    if paper and study.paper_a is not None:
        ax.plot_wireframe(z_grid, d_grid, study.paper_fitted(d_grid, z_grid), color="C1",
                          lw=0.5, rstride=2, cstride=4,
                          label=f"paper: {study.paper_a:g}·d + {study.paper_b:g}·d·z1^-1.5")
    ax.scatter(study.teeth, study.profile_error, study.max_deviation_percent, color="k",
               s=10, depthshade=False, label="exact maxima (IT5…IT9)")
    ax.set_xlabel("z1", **PLAIN)
    ax.set_ylabel("d, mm", **PLAIN)
    ax.set_zlabel("max |Δi|, %", **PLAIN)
    ax.set_title(f"maximum transmission fluctuation, m = {study.module:g} mm", fontsize=9,
                 **PLAIN)
    plain(ax.legend(fontsize=7, loc="upper right"))
    return ax


def plot_fit_comparison(study, ax=None):
    """Exact maxima against the refit and the paper's surface, point by point (2-D)."""
    ax = _axes(ax)
    exact = study.max_deviation_percent
    ax.loglog(exact, study.fitted(study.profile_error, study.teeth), "o", ms=4,
              label="refit")
    if study.paper_a is not None:
        ax.loglog(exact, study.paper_fitted(study.profile_error, study.teeth), "x", ms=5,
                  label="paper's surface")
    ax.loglog(exact, study.max_deviation_percent_2deg, "+", ms=5,
              label="paper's 2° method")
    span = [exact.min(), exact.max()]
    ax.loglog(span, span, color="0.5", lw=0.8)
    ax.set_xlabel("exact max |Δi|, %", **PLAIN)
    ax.set_ylabel("surface / 2° method, %", **PLAIN)
    ax.set_title(f"m = {study.module:g} mm", fontsize=9, **PLAIN)
    plain(ax.legend(fontsize=8))
    return ax
