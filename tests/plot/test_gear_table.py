"""The gear-table chart (powergraph.plot.gear_table)."""
from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import pytest

from powergraph.analyses.gear_table import gear_table
from powergraph.model import load_model

MODELS = Path(__file__).resolve().parents[2] / "models"


@pytest.mark.slow
def test_one_bar_per_mode_with_its_ratio() -> None:
    table = gear_table(load_model(MODELS / "ravigneaux_4speed.yaml"))
    fig, ax = plt.subplots()
    try:
        assert table.plot(ax=ax) is ax
        assert len(ax.patches) == len(table.rows)
        assert [round(p.get_height(), 6) for p in ax.patches] == [
            round(abs(r.ratio), 6) for r in table.rows]
    finally:
        plt.close(fig)
