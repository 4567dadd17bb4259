"""Layout of power-flow diagrams (powergraph.plot.layout): no matplotlib here.

The layout must follow the power (motor left, generator right, every arrow that carries
power pointing rightwards unless it lies on a circulating loop), keep labels clear of
nodes and of each other, and be the same from run to run.
"""
from __future__ import annotations

import hashlib
import itertools
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import powergraph as pg
from powergraph.plot.layout.geometry import (CURVE4, Box, bezier_chain, head_polygon,
                                               place_label, sample, trim_end)
from powergraph.plot.layout.layout import LOSS_STUB, layout_flow, skeleton_of
from powergraph.plot.layout.place import _project
from powergraph.plot.layout.view import flow_view, format_power, format_share, loop_edges
from powergraph.errors import UsageError
from powergraph.model import loads_model, model_from_dict
from powergraph.statics.flow import Flow, Node

ROOT = Path(__file__).resolve().parents[2]
MODEL_FILES = sorted((ROOT / "models").glob("*.yaml"))

# A 2K-H differential whose ring is driven back from the carrier through two fixed-axis
# pairs: power circulates round carrier -> a-b -> b/b2 -> b2-re -> ring -> p-r -> carrier.
CLOSED_DIFFERENTIAL = (Path(__file__).resolve().parents[1] / "data"
                       / "closed_differential_carrier_loop.yaml").read_text()


def views_of(model, solve_ok):
    """The actual view and the view from every moving mesh carrier."""
    result = solve_ok(model)
    carriers = sorted({link.carrier for link in model.meshes
                       if model.body_of[link.carrier] != model.frame_body})
    return result, [flow_view(result)] + [flow_view(result, c) for c in carriers]


@pytest.fixture(scope="module")
def rv40e():
    return pg.load_model(str(ROOT / "models" / "rv40e_wang2021.yaml"))


# --- content: the view -----------------------------------------------------------------
def test_formats() -> None:
    assert [format_power(p) for p in (0.0, 0.0147, 71.66, 135.07, 2270.0, 3001.65, 26093.7,
                                      1.2e6)] == \
        ["0 W", "14.7 mW", "71.7 W", "135 W", "2.27 kW", "3.00 kW", "26.1 kW", "1.20 MW"]
    assert [format_share(p, 2270.0) for p in (0.0, 2270.0, 2063.26, 11.1, 26093.7)] == \
        ["0 %", "100 %", "90.9 %", "0.489 %", "1,150 %"]


@pytest.mark.parametrize("frame", [None, "7", "3", "2", "6", "1"])
def test_view_is_the_results_flow_graph(rv40e, solve_ok, frame) -> None:
    result = solve_ok(rv40e)
    view = flow_view(result, frame)
    assert view.flows == tuple(result.flows(frame))
    graph = result.flow_graph(frame)
    assert set(view.kinds) >= set(graph.nodes)
    for node, kind in graph.nodes(data="kind"):
        if node.name == view.held:
            assert view.kinds[node] == "frame"
        else:
            assert view.kinds[node] == ("body" if kind == "frame" else kind)
    assert view.input_power == pytest.approx(2270.0)


def test_titles_say_whose_frame(rv40e, solve_ok) -> None:
    result = solve_ok(rv40e)
    assert flow_view(result).title == "RV-40E (Wang 2021): actual powers (ground frame)"
    assert flow_view(result, "0").frame_body is None          # a member of the housing
    assert flow_view(result, 5).frame_body is None
    seen = flow_view(result, "3")
    assert seen.frame_body == "2/3" and seen.held == "2/3"
    assert "virtual powers seen from 2/3" in seen.title
    assert flow_view(result, "2/3").flows == seen.flows     # a body id works too
    assert flow_view(result, "7").held == "6/7"
    assert flow_view(result).held == "0/5"


def test_unknown_frame_is_a_usage_error(rv40e, solve_ok) -> None:
    with pytest.raises(UsageError, match=r"--frame 9: unknown component '9'"):
        flow_view(solve_ok(rv40e), "9")


def test_labels_give_power_and_share(rv40e, solve_ok) -> None:
    view = flow_view(solve_ok(rv40e))
    labels = {(f.source, f.target): view.label(f) for f in view.flows}
    assert labels[("motor", "1")] == "2.27 kW\n100 %"
    assert labels[("2/3", "mesh 4-5")] == "2.06 kW\n90.9 %"
    assert labels[("0/5", "mesh 4-5")] == "0 W\n0 %"


def test_loop_edges_are_the_cycles() -> None:
    flows = [Flow("a", "b", 5.0), Flow("b", "c", 3.0), Flow("c", "a", 2.0),
             Flow("c", "d", 1.0), Flow("d", "e", 0.0), Flow("e", "d", 0.0)]
    body = {name: Node("body", name) for name in "abc"}
    assert loop_edges(flows) == {(body["a"], body["b"]), (body["b"], body["c"]),
                                 (body["c"], body["a"])}


def test_closed_differential_circulates(solve_ok) -> None:
    result = solve_ok(loads_model(CLOSED_DIFFERENTIAL))
    view = flow_view(result)
    assert result.circulating_power > 0
    assert view.circulating == pytest.approx(result.circulating_power)
    assert (Node("body", "c/a"), Node("mesh", "mesh a-b")) in view.loop_edges
    assert (Node("motor", "motor"), Node("body", "s")) not in view.loop_edges


# --- geometry helpers ------------------------------------------------------------------
def test_projection_keeps_order_and_gaps() -> None:
    target = [(0.0, 1.0), (5.0, 1.0), (-3.0, 2.0), (-3.5, 1.0)]
    y = _project(target, [10.0, 4.0, 4.0])
    assert all(a - b >= s - 1e-9 for a, b, s in zip(y[:-1], y[1:], [10.0, 4.0, 4.0]))
    # feasible targets are kept as they are
    assert _project([(30.0, 1.0), (10.0, 1.0)], [5.0]) == [30.0, 10.0]


def test_arrowhead_and_shaft() -> None:
    vertices, codes = bezier_chain([(0.0, 0.0), (100.0, 40.0)])
    assert codes == (1, CURVE4, CURVE4, CURVE4)
    tip, left, right = head_polygon(vertices, codes, 8.0, 3.0)
    assert tip == pytest.approx((100.0, 40.0))
    base = np.add(left, right) / 2
    assert np.hypot(*(np.subtract(tip, base))) == pytest.approx(8.0)
    assert np.hypot(*(np.subtract(left, right))) == pytest.approx(6.0)
    assert (tip[0] - base[0]) / 8.0 > 0.97          # horizontal tangent at the end
    trimmed, _ = trim_end(vertices, codes, 8.0)
    assert np.hypot(*np.subtract(trimmed[-1], tip)) == pytest.approx(8.0, abs=1e-6)
    assert trimmed[0] == vertices[0]
    # the trimmed curve lies on the original one
    original = sample(vertices, codes, 400)
    for point in sample(trimmed, codes, 20):
        assert np.min(np.hypot(*(original - point).T)) < 0.5


def test_place_label_refuses_when_everything_collides() -> None:
    wall = [Box(-100, -100, 100, 100)]
    assert place_label([(0.0, 0.0), (10.0, 0.0)], (20.0, 10.0), wall, np.zeros((0, 2))) \
        is None
    ink = np.array([[0.0, 0.0]])       # prefers the spot that hides no arrow
    (xy, _), = [place_label([(0.0, 0.0), (50.0, 0.0)], (20.0, 10.0), [], ink)]
    assert xy == (50.0, 0.0)


# --- the layout follows the power ------------------------------------------------------
def test_rv40e_actual_layers_in_flow_order(rv40e, solve_ok) -> None:
    layout = layout_flow(flow_view(solve_ok(rv40e)))
    at = {n.name: reading(p) for n, p in layout.nodes.items()}   # folded: band, then x
    chain = ["motor", "1", "mesh 1-2", "2/3", "mesh 4-5", "4", "coupling 4-6", "6/7",
             "generator"]
    assert [at[n] for n in chain] == sorted(at[n] for n in chain)
    assert len({at[n] for n in chain}) == len(chain)


def test_frame_7_keeps_idle_members_in_their_actual_order(rv40e, solve_ok) -> None:
    layout = layout_flow(flow_view(solve_ok(rv40e), "7"))
    at = {n.name: reading(p) for n, p in layout.nodes.items()}
    assert at["4"] < at["coupling 4-6"] < at["6/7"]      # all three carry 0 W in this view


@pytest.mark.parametrize("path", MODEL_FILES, ids=lambda p: p.stem)
def test_every_model_every_carrier(path, solve_ok) -> None:
    _, views = views_of(pg.load_model(str(path)), solve_ok)
    for view in views:
        layout = layout_flow(view)
        check_layout(view, layout)
        assert 1.2 <= aspect(layout) <= 2.4, view.title      # folded near 16 : 9


def aspect(layout) -> float:
    b = layout.bounds
    return (b.x1 - b.x0) / (b.y1 - b.y0)


@pytest.mark.parametrize("frame", [None, "c"])
def test_closed_differential_loop_drawn_backwards_at_its_weakest(solve_ok, frame) -> None:
    view = flow_view(solve_ok(loads_model(CLOSED_DIFFERENTIAL)), frame)
    layout = layout_flow(view)
    check_layout(view, layout)
    if frame is None:
        loop = [e for e in layout.edges if e.loop]
        nodes = layout.nodes
        backwards = [e for e in loop if reading(nodes[e.flow.source_node])
                     > reading(nodes[e.flow.target_node])]
        assert len(backwards) == 1
        assert backwards[0].flow.power == min(e.flow.power for e in loop)
        assert backwards[0].key == (Node("mesh", "mesh p-r"), Node("body", "c/a"))


def check_layout(view, layout) -> None:
    """Everything a layout promises, for any view."""
    nodes, style = layout.nodes, layout.style
    # one route per flow, in order, from source to target
    assert [e.flow for e in layout.edges] == list(view.flows)
    for edge in layout.edges:
        source = nodes[edge.flow.source_node]
        target = nodes[_stub(edge) if edge.loss else edge.flow.target_node]
        assert _touches(source.box, edge.vertices[0]), edge.key
        assert _touches(target.box, edge.vertices[-1]), edge.key
    # motor first (leftmost, top band), generator last (rightmost of the bottom band)
    xs = [p.x for p in nodes.values()]
    last = max(p.band for p in nodes.values())
    for name, node in nodes.items():
        if node.kind == "motor":
            assert node.x == min(xs) and node.band == 0, name
        if node.kind == "generator":
            assert node.band == last, name
            assert node.x == max(p.x for p in nodes.values() if p.band == last), name
    # arrows that carry power point on in reading order (right, or to a later band),
    # except on a loop or at a port fed backwards
    for edge in layout.edges:
        kinds = {view.kinds[edge.flow.source_node], view.kinds.get(edge.flow.target_node)}
        if edge.zero or edge.loss or edge.loop or kinds & {"motor", "generator"}:
            continue
        assert reading(nodes[edge.flow.source_node]) < reading(nodes[edge.flow.target_node]), \
            edge.key
    # bands stacked top to bottom without overlapping
    for upper, lower in zip(range(last), range(1, last + 1)):
        assert min(b.y0 for p in nodes.values() if p.band == upper for b in p.boxes) > \
            max(b.y1 for p in nodes.values() if p.band == lower for b in p.boxes)
    # widths proportional to power above the floor; 0 W links thin
    ratios = [e.width / e.flow.power for e in layout.edges
              if not e.zero and e.width > style.min_width]
    assert ratios and np.ptp(ratios) <= 1e-9 * max(ratios)
    assert all(e.width == style.zero_width for e in layout.edges if e.zero)
    # loss sinks straight under their element
    for edge in (e for e in layout.edges if e.loss):
        owner, sink = nodes[edge.flow.source_node], nodes[_stub(edge)]
        assert sink.x == owner.x and sink.y < owner.y
    # labels: placed, clear of every node and of each other
    assert layout.clean
    boxes = [b for node in nodes.values() for b in node.boxes]
    labels = [e.label_box for e in layout.edges]
    for label in labels:
        assert not any(label.overlaps(b) for b in boxes)
    for a, b in itertools.combinations(labels, 2):
        assert not a.overlaps(b)
    # nodes do not overlap each other
    for a, b in itertools.combinations(boxes, 2):
        assert not a.overlaps(b)


def reading(node) -> tuple[int, float]:
    """Where a node comes in reading order: its band (top first), then left to right."""
    return (node.band, node.x)


def _stub(edge) -> Node:
    """The loss sink drawn under the element of a loss arrow."""
    return Node(LOSS_STUB, f"loss@{edge.flow.source}")


def _touches(box: Box, point, tol: float = 1.0) -> bool:
    x, y = point
    return box.x0 - tol <= x <= box.x1 + tol and box.y0 - tol <= y <= box.y1 + tol


# --- determinism -----------------------------------------------------------------------
def _digest(layout) -> str:
    data = [(n, round(p.x, 6), round(p.y, 6)) for n, p in sorted(layout.nodes.items())]
    data += [(e.key, [list(map(lambda v: round(v, 6), p)) for p in e.vertices],
              [round(v, 6) for v in e.label_xy]) for e in layout.edges]
    return hashlib.sha256(json.dumps(data, default=str).encode()).hexdigest()


def test_same_layout_twice(rv40e, solve_ok) -> None:
    for frame in (None, "3", "7"):
        first = layout_flow(flow_view(solve_ok(rv40e), frame))
        second = layout_flow(flow_view(solve_ok(rv40e), frame))
        assert _digest(first) == _digest(second)
        assert skeleton_of(first.view) == skeleton_of(second.view)


def test_same_layout_in_other_processes() -> None:
    """String hashing changes between processes; the layout must not."""
    code = ("import sys, powergraph as pg\n"
            "from powergraph.model import loads_model\n"
            "from powergraph.plot.layout.view import flow_view\n"
            "from powergraph.plot.layout.layout import layout_flow\n"
            f"sys.path.insert(0, {str(Path(__file__).parent)!r})\n"
            "import test_layout as t\n"
            "r = pg.solve(loads_model(t.CLOSED_DIFFERENTIAL))\n"
            "print(t._digest(layout_flow(flow_view(r))), "
            "t._digest(layout_flow(flow_view(r, 'c'))))\n")
    digests = set()
    for seed in ("1", "2", "3"):
        env = {**os.environ, "PYTHONHASHSEED": seed}
        out = subprocess.run([sys.executable, "-c", code], env=env, cwd=ROOT, check=True,
                             capture_output=True, text=True).stdout
        digests.add(out.strip())
    assert len(digests) == 1


def test_ids_that_spell_layout_helpers_stay_nodes_of_their_own(solve_ok) -> None:
    # The loss sink under mesh "mesh s-planet" and the waypoints of long arrows are
    # layout nodes of their own kinds: a carrier called "loss@mesh s-planet" (once taken
    # for that sink, and drawn as a loss) and a ring called "·0·1" stay bodies.
    import yaml

    data = yaml.safe_load((ROOT / "models" / "planetary_2kh_sun_to_carrier.yaml").read_text())
    new = {"sun": "s", "carrier": "loss@mesh s-planet", "ring": "·0·1"}
    get = lambda c: new.get(c, c)  # noqa: E731
    data["components"] = {get(c): v for c, v in data["components"].items()}
    for link in data["links"]:
        link.update(between=[get(c) for c in link["between"]],
                    **({"carrier": get(link["carrier"])} if "carrier" in link else {}))
    for port in data["ports"]:
        port["component"] = get(port["component"])
    result = solve_ok(model_from_dict(data))
    view = flow_view(result)
    layout = layout_flow(view)
    flow_nodes = {n for f in view.flows for n in f.key if n.kind != "loss"}
    stubs = [f for f in view.flows if f.target_kind == "loss"]
    assert len(layout.nodes) == len(flow_nodes) + len(stubs) == 8 + 2
    carrier = layout.nodes[Node("body", "loss@mesh s-planet")]
    assert carrier.kind == "body" and carrier.shape.text == "loss@mesh s-planet"
    assert layout.nodes[Node("frame", "frame/·0·1")].kind == "frame"
    check_layout(view, layout)


def test_a_very_long_id_does_not_widen_the_diagram(solve_ok) -> None:
    # a 400-character id is cut to MAX_NAME characters in its box and its mesh circle:
    # the diagram stays about as wide as with short ids (it was ~5300 pt wide)
    import yaml

    data = yaml.safe_load((ROOT / "models" / "planetary_2kh_sun_to_carrier.yaml").read_text())
    data["components"]["S" * 400] = data["components"].pop("sun")
    data["links"][0]["between"][0] = data["ports"][0]["component"] = "S" * 400
    plain = layout_flow(flow_view(solve_ok(loads_model(
        (ROOT / "models" / "planetary_2kh_sun_to_carrier.yaml").read_text()))))
    long = layout_flow(flow_view(solve_ok(model_from_dict(data))))
    width = lambda layout: layout.bounds.x1 - layout.bounds.x0  # noqa: E731
    assert width(long) < 2 * width(plain)
    assert long.nodes[Node("body", "S" * 400)].shape.text == "S" * 39 + "…"


TWO_INPUTS = """
name: two inputs
components:
  0: {role: frame}
  s: {teeth: 20}
  p: {teeth: 20, count: 3}
  r: {teeth: 60, internal: true}
  c: {}
links:
  - {type: mesh, between: [s, p], carrier: c, efficiency: 0.98}
  - {type: mesh, between: [p, r], carrier: c, efficiency: 0.99}
ports:
  - {component: s, role: input, speed: 1000 rpm, power: 1 kW}
  - {component: r, role: input, name: ring drive, speed: 200 rpm}
  - {component: c, role: output}
"""


def test_ports_are_captioned_with_their_names(solve_ok) -> None:
    """Issue 34: a hybrid's wheels are captioned "wheels", not "generator" beside MG1;
    the nodes keep their kinds and names (``motor``, ``generator``)."""
    view = flow_view(solve_ok(pg.load_model(str(ROOT / "models" / "ths2_power_split.yaml"))))
    assert view.text(Node("motor", "motor")) == "engine"
    assert view.text(Node("generator", "generator")) == "wheels"
    assert view.text(Node("machine", "MG1")) == "MG1"          # a machine: its port's name
    assert view.text(Node("body", "R/R2")) == "R/R2"           # others: their names
    layout = layout_flow(view)
    captions = {p.node: p.shape.caption for p in layout.nodes.values() if p.shape.caption}
    assert captions == {Node("motor", "motor"): "engine",
                        Node("generator", "generator"): "wheels"}


def test_unnamed_ports_are_captioned_with_their_role(rv40e, solve_ok) -> None:
    """Without a name: "input"/"output", with the component's id when there are several."""
    layout = layout_flow(flow_view(solve_ok(rv40e)))
    captions = {p.node.name: p.shape.caption for p in layout.nodes.values() if p.shape.caption}
    assert captions == {"motor": "input", "generator": "output"}
    view = flow_view(solve_ok(loads_model(TWO_INPUTS)))
    assert {n.name: view.text(n) for n in view.kinds if n.kind in ("motor", "generator")} \
        == {"motor s": "input s", "motor r": "ring drive", "generator": "output"}
