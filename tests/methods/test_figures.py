"""Data and drawings of Wang (2021)'s Figs. 12–13 by both methods.

Wang C. (2021), "A calculation method of transmission efficiency for RV reducer". Expected
values: the paper's closed form η = η1 − (η1 + 1/β)(1 − η2) with β = z4/(z5 − z4) (from its
Eqs. 8–15), the hand-derived virtual-power closed form of the RV
(tests/methods/test_wang2021.py::_vp_closed_form, repeated here), and the values of both
written in tests/data/published_values.yaml (sections ``wang2021`` and
``rv40e_virtual_power``).
"""
from __future__ import annotations

import importlib.util
from pathlib import Path

import numpy as np
import pytest
import yaml

import powergraph as pg
from powergraph.methods.figures import (
    FIGURES,
    cycloid_ratio_curves,
    equivalent_efficiency_curve,
    first_stage_ratio_curves,
    mesh_efficiency_curves,
    with_teeth,
)

ROOT = Path(__file__).resolve().parents[2]
RV40E = ROOT / "models" / "rv40e_wang2021.yaml"
PUBLISHED = yaml.safe_load((ROOT / "tests" / "data" / "published_values.yaml").read_text())
VIRTUAL_POWER = PUBLISHED["rv40e_virtual_power"]


def paper_eta(eta1: float, eta2: float, z4: int, z5: int) -> float:
    """Wang (2021), Eqs. (8)-(15): eta = eta1 - (eta1 + 1/beta)(1 - eta2), beta = z4/(z5 - z4)."""
    beta = z4 / (z5 - z4)
    return eta1 - (eta1 + 1 / beta) * (1 - eta2)


def vp_eta(z1: int, z2: int, z4: int, z5: int, eta1: float, eta2: float) -> float:
    """Virtual-power η of the RV by hand (derivation in test_wang2021._vp_closed_form)."""
    k = z2 / z1
    return (1 + k * eta1 + k * eta1 / (z5 / (z4 * eta2) - 1)) / (1 + k * z5)


@pytest.fixture(scope="module")
def model():
    return pg.load_model(RV40E)


@pytest.fixture(scope="module")
def fig12(model):
    return mesh_efficiency_curves(model)


@pytest.fixture(scope="module")
def fig13_cycloid(model):
    return cycloid_ratio_curves(model)


@pytest.fixture(scope="module")
def fig13_first(model):
    return first_stage_ratio_curves(model)


def test_fig12_grid_and_paper_curve(fig12) -> None:
    x = fig12.curve("wang2021").x
    assert x[0] == pytest.approx(0.90) and x[-1] == pytest.approx(1.00) and len(x) == 21
    expected = [paper_eta(e, e, 39, 40) for e in x]
    assert fig12.curve("wang2021").y == pytest.approx(expected, rel=1e-12)


def test_fig12_virtual_power_curves(fig12) -> None:
    x = fig12.curve("virtual-power").x
    both = fig12.curve("virtual-power").y
    needle = fig12.curve("virtual-power-needle").y
    assert both == pytest.approx([vp_eta(12, 36, 39, 40, e, e) for e in x], rel=1e-9)
    assert needle == pytest.approx([vp_eta(12, 36, 39, 40, e, 0.998) for e in x], rel=1e-9)
    at = int(np.argmin(abs(x - 0.94)))
    assert both[at] == pytest.approx(VIRTUAL_POWER["both_094"]["efficiency"], abs=5e-7)
    assert needle[at] == pytest.approx(VIRTUAL_POWER["needle_0998"]["efficiency"], abs=5e-7)
    assert both[-1] == pytest.approx(1.0, abs=1e-12)          # ideal meshes
    assert {m.curve for m in fig12.marks} == {"wang2021", "virtual-power",
                                               "virtual-power-needle"}


def test_fig13_cycloid_teeth(fig13_cycloid) -> None:
    paper = fig13_cycloid.curve("wang2021")
    z5 = np.arange(20, 61)
    assert paper.x == pytest.approx(1 + 36 * z5 / 12, rel=1e-12)     # i = 1 + z2 z5/z1
    assert paper.y == pytest.approx([paper_eta(0.94, 0.94, z - 1, z) for z in z5],
                                    rel=1e-12)
    # The paper's equations at z4 = 29, 39, 49: 0.88153, 0.88206, 0.88238 (published_values).
    marks = {m.text.split(":")[0]: m.y for m in fig13_cycloid.marks}
    for z4, value in PUBLISHED["wang2021"]["fig13_trend"].items():
        assert marks[f"z4 = {z4}"] == pytest.approx(value, abs=5e-6)
    # The equations' η rises with the ratio; the virtual-power η falls.
    assert np.all(np.diff(paper.y) > 0)
    assert np.all(np.diff(fig13_cycloid.curve("virtual-power").y) < 0)
    assert np.all(np.diff(fig13_cycloid.curve("virtual-power-needle").y) < 0)
    assert fig13_cycloid.curve("virtual-power").y == pytest.approx(
        [vp_eta(12, 36, z - 1, z, 0.94, 0.94) for z in z5], rel=1e-9)
    assert "RISES" in fig13_cycloid.caption and "text says" in fig13_cycloid.caption


def test_fig13_first_stage(fig13_first) -> None:
    paper = fig13_first.curve("wang2021")
    z2 = np.arange(12, 61, 2)
    assert paper.x == pytest.approx(1 + z2 * 40 / 12, rel=1e-12)
    assert paper.y == pytest.approx(paper_eta(0.94, 0.94, 39, 40), rel=1e-12)  # flat
    vp = fig13_first.curve("virtual-power").y
    assert vp == pytest.approx([vp_eta(12, z, 39, 40, 0.94, 0.94) for z in z2], rel=1e-9)
    assert np.all(np.diff(vp) < 0)


def test_equivalent_efficiency_curve(model) -> None:
    data = equivalent_efficiency_curve(model, [0.90, 0.94, 0.98])
    for x, y in zip(data.curves[0].x, data.curves[0].y):
        # The virtual-power η with the first stage at x and the pin mesh at y is the
        # paper's η at the single efficiency x.
        assert vp_eta(12, 36, 39, 40, x, y) == pytest.approx(paper_eta(x, x, 39, 40),
                                                             rel=1e-10)
    assert data.marks[0].x == pytest.approx(0.94)


def test_curves_are_read_only_and_model_unchanged(model, fig12) -> None:
    with pytest.raises(ValueError):
        fig12.curves[0].y[0] = 0.0
    changed = with_teeth(model, {"5": 50, "4": 49})
    assert changed.components["5"].teeth == 50
    assert model.components["5"].teeth == 40


def test_to_dict(fig13_cycloid) -> None:
    data = fig13_cycloid.to_dict()
    assert [c["key"] for c in data["curves"]] == ["wang2021", "virtual-power",
                                                  "virtual-power-needle"]
    assert len(data["curves"][0]["x"]) == 41 and data["marks"]


def test_plot_functions_draw_what_they_are_given(fig12, fig13_cycloid) -> None:
    pytest.importorskip("matplotlib")
    import matplotlib.pyplot as plt

    from powergraph.plot.wang2021 import add_caption, plot_figure, plot_paper_trend

    figure, (left, right) = plt.subplots(1, 2)
    assert plot_figure(fig12, ax=left) is left
    assert [line.get_label() for line in left.get_lines()][:3] == \
        [c.label for c in fig12.curves]
    np.testing.assert_allclose(left.get_lines()[0].get_ydata(), fig12.curves[0].y)
    assert plot_paper_trend(fig13_cycloid, ax=right) is right
    assert len(right.texts) == len(fig13_cycloid.marks)
    text = add_caption(figure, fig13_cycloid.caption)
    assert "0.88153" in text.get_text()
    plt.close(figure)
    ax = plot_figure(fig12)          # ax=None: a new figure
    assert ax.get_xlabel() == fig12.xlabel
    plt.close(ax.figure)


def test_script_writes_png_and_svg(tmp_path) -> None:
    pytest.importorskip("matplotlib")
    spec = importlib.util.spec_from_file_location("wang2021_figures",
                                                  ROOT / "scripts" / "wang2021_figures.py")
    script = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(script)
    assert script.main(["-o", str(tmp_path)]) == 0
    for name in FIGURES:
        for suffix in (".png", ".svg"):
            path = tmp_path / f"{name}{suffix}"
            assert path.stat().st_size > 10_000, path
    assert (tmp_path / "fig12_mesh_efficiency.png").read_bytes()[:4] == b"\x89PNG"
