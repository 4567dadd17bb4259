"""Folding long power-flow diagrams onto bands near 16 : 9 (powergraph.plot.layout.fold):
no matplotlib here. A long train reads like text, band after band, each left to right;
the arrows between bands run along lanes that never cross; the figure is near 16 : 9."""
from __future__ import annotations

import itertools
import json
from pathlib import Path

import pytest

import powergraph as pg
from powergraph.model import loads_model
from powergraph.plot.layout.fold import rounded
from powergraph.plot.layout.geometry import CURVE4, LINETO, MOVETO
from powergraph.plot.layout.layout import layout_flow
from powergraph.plot.layout.parts import LayoutStyle
from powergraph.plot.layout.view import flow_view

ROOT = Path(__file__).resolve().parents[2]


def aspect(layout) -> float:
    b = layout.bounds
    return (b.x1 - b.x0) / (b.y1 - b.y0)


def reading(node) -> tuple[int, float]:
    return (node.band, node.x)


def check_folded(view, layout) -> None:
    """Clean labels, no overlaps, power in reading order, bands stacked."""
    nodes = layout.nodes
    assert layout.clean
    boxes = [b for node in nodes.values() for b in node.boxes]
    labels = [e.label_box for e in layout.edges]
    for a, b in itertools.combinations(boxes + labels, 2):
        assert not a.overlaps(b)
    for edge in layout.edges:
        if edge.zero or edge.loss or edge.loop:
            continue
        assert reading(nodes[edge.flow.source_node]) < reading(nodes[edge.flow.target_node])
    last = max(p.band for p in nodes.values())
    for upper in range(last):
        assert min(b.y0 for p in nodes.values() if p.band == upper for b in p.boxes) > \
            max(b.y1 for p in nodes.values() if p.band == upper + 1 for b in p.boxes)


def chain(pairs: int) -> str:
    """A train of ``pairs`` spur pairs in series: one long row of layers."""
    components = {"0": {"role": "frame"}, **{f"g{i}": {"teeth": 20 + i}
                                              for i in range(2 * pairs)}}
    links = [{"type": "mesh", "between": [f"g{2 * i}", f"g{2 * i + 1}"], "efficiency": 0.98}
             for i in range(pairs)]
    links += [{"type": "fixed", "between": [f"g{2 * i + 1}", f"g{2 * i + 2}"]}
              for i in range(pairs - 1)]
    return json.dumps({"name": f"{pairs} pairs", "components": components, "links": links,
                       "ports": [{"component": "g0", "role": "input", "speed": "1000 rpm",
                                  "power": "1 kW"},
                                 {"component": f"g{2 * pairs - 1}", "role": "output"}]})


@pytest.mark.parametrize("pairs", [3, pytest.param(8, marks=pytest.mark.slow),
                                   pytest.param(14, marks=pytest.mark.slow)])
def test_long_trains_fold_onto_bands_near_16_9(pairs, solve_ok) -> None:
    """Folded, a chain reads like text: band after band, each left to right, the arrows
    between bands along lanes that never cross; unfolded it is a strip."""
    view = flow_view(solve_ok(loads_model(chain(pairs))))
    strip = layout_flow(view, style=LayoutStyle(aspect=None))
    assert aspect(strip) > 4 and {p.band for p in strip.nodes.values()} == {0}
    layout = layout_flow(view)
    check_folded(view, layout)
    assert 1.2 <= aspect(layout) <= 2.4
    folding = layout.folding
    assert len(folding.bands) >= 2
    assert [b[0] for b in folding.bands[1:]] == [b[1] + 1 for b in folding.bands[:-1]]
    assert all(last > first for first, last in folding.bands)    # no lone layer
    # every arrow that leaves a band is routed along a lane between it and the next
    crossing = [e for e in layout.edges if not e.loss and
                layout.nodes[e.flow.source_node].band != layout.nodes[e.flow.target_node].band]
    assert crossing and len(folding.lanes) >= len(crossing)
    ys = {round(y, 6) for e in crossing for _, y in e.vertices}
    assert {round(lane.y, 6) for lane in folding.lanes.values()} <= ys


def test_lanes_at_one_cut_are_nested(solve_ok) -> None:
    """Several arrows across one cut: the higher an arrow leaves its band, the further
    right it turns and the lower its lane runs (so no two cross)."""
    view = flow_view(solve_ok(pg.load_model(str(ROOT / "models" / "ravigneaux_second.yaml"))))
    folding = layout_flow(view).folding
    by_cut: dict[int, list] = {}
    for (index, step), lane in folding.lanes.items():
        by_cut.setdefault(round(lane.right - lane.left), []).append(lane)
    assert max(len(lanes) for lanes in by_cut.values()) >= 3
    for lanes in by_cut.values():
        lanes.sort(key=lambda lane: lane.y)
        assert [lane.right for lane in lanes] == sorted((lane.right for lane in lanes),
                                                        reverse=True)
        assert [lane.left for lane in lanes] == sorted((lane.left for lane in lanes),
                                                       reverse=True)


def test_rounded_corners_keep_the_corner_points_in_reach() -> None:
    vertices, codes = rounded([(0.0, 0.0), (20.0, 0.0), (20.0, -30.0), (-5.0, -30.0)], 4.0)
    assert codes == (MOVETO, LINETO, CURVE4, CURVE4, CURVE4, LINETO, CURVE4, CURVE4, CURVE4,
                     LINETO)
    assert vertices[0] == (0.0, 0.0) and vertices[-1] == (-5.0, -30.0)
    assert vertices[1] == (16.0, 0.0) and vertices[4] == (20.0, -4.0)     # a 4 pt radius


def test_no_folding_asked() -> None:
    view = flow_view(pg.solve(loads_model(chain(8))))
    layout = layout_flow(view, style=LayoutStyle(aspect=None))
    assert len(layout.folding.bands) == 1 and not layout.folding.lanes
