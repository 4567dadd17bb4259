"""The lever drawing (powergraph.plot.lever)."""
from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import pytest

from powergraph.analyses.lever import lever_diagram
from powergraph.model import load_model

MODELS = Path(__file__).resolve().parents[2] / "models"


@pytest.mark.slow
def test_one_lever_line_per_set_and_one_arrow_per_node() -> None:
    model = load_model(MODELS / "simpson_first.yaml")
    import powergraph as pg

    result = pg.solve(model)
    diagram = lever_diagram(model, result.speeds)
    fig, ax = plt.subplots()
    try:
        assert diagram.plot(ax=ax) is ax
        arrows = [t for t in ax.texts if getattr(t, "arrow_patch", None) is not None]
        assert len(arrows) == sum(len(lev.nodes) for lev in diagram.levers)
    finally:
        plt.close(fig)
