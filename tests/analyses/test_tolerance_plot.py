"""Plots of a tolerance analysis: they draw into the axes given and compute nothing."""
from __future__ import annotations

import numpy as np
import pytest

from powergraph.analyses.tolerance import tolerance_analysis
from powergraph.model import loads_model

plt = pytest.importorskip("matplotlib.pyplot")

PAIR = """
name: pair
components: {0: {role: frame}, 1: {teeth: 20}, 2: {teeth: 60}, 3: {teeth: 20}, 4: {teeth: 20}}
links:
  - {type: mesh, between: [1, 2], backlash_arcmin: 3.0}
  - {type: fixed, between: [2, 3]}
  - {type: mesh, between: [3, 4], backlash_arcmin: 1.0}
ports: [{component: 1, role: input}, {component: 4, role: output}]
tolerances:
  links.0.backlash_arcmin: {distribution: uniform, min: 0, max: 6}
  links.2.backlash_arcmin: {nominal: 1, tolerance: 0.5}
"""


def test_histogram_and_tornado_draw_into_given_axes() -> None:
    from powergraph.plot.tolerance import output_histogram, tornado

    fig, (top, bottom) = plt.subplots(2, 1)
    values = np.array([0.1, 0.2, 0.2, np.nan, 0.9])
    assert output_histogram(values, "lost motion (arcmin)", [0.5], ax=top, bins=4) is top
    heights = [p.get_height() for p in top.patches]
    assert len(heights) == 4                                  # NaN left out, 4 bins
    assert [line.get_xdata()[0] for line in top.get_lines()] == [0.5]
    indices = {"a": {"first": 0.2, "total": 0.3}, "b": {"first": 0.6, "total": 0.7}}
    assert tornado(indices, ax=bottom) is bottom
    assert [t.get_text() for t in bottom.get_yticklabels()] == ["a", "b"]   # largest on top
    widths = sorted(p.get_width() for p in bottom.patches)
    assert widths == pytest.approx([0.2, 0.3, 0.6, 0.7])
    plt.close(fig)


def test_result_plot_has_one_panel_per_output_and_the_tornado() -> None:
    result = tolerance_analysis(loads_model(PAIR), samples=2000, seed=1, sobol_samples=256,
                                specs=["lost_motion<=2.5arcmin"])
    axes = result.plot()
    assert len(axes) == 2
    assert axes[0].get_lines()[0].get_xdata()[0] == 2.5
    plt.close(axes[0].figure)
