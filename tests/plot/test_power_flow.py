"""``plot_power_flow``: the drawn arrows and labels are the result's flow graph.

Checked on the returned artists (never on pixels): one arrow and one label per flow,
labels reading the flow's power and share, widths proportional to power, heads at the
target, no two texts overlapping once rendered, for every model in models/ in the
actual view and from each moving carrier, and for trains the code has never seen.
"""
from __future__ import annotations

import itertools
from pathlib import Path

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import powergraph as pg  # noqa: E402
from powergraph.plot.layout.view import flow_view, format_power, format_share  # noqa: E402
from powergraph.errors import UsageError  # noqa: E402
from powergraph.model import loads_model  # noqa: E402
from powergraph.plot.power_flow import COLOURS, plot_power_flow  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
MODEL_FILES = sorted((ROOT / "models").glob("*.yaml"))

UNSEEN = {
    # closed differential: the ring is driven back from the carrier -> circulating power
    "closed differential": (ROOT / "tests" / "data"
                            / "closed_differential_carrier_loop.yaml").read_text(),
    # 3K (Wolfrom): stepped planet, one ring fixed, the other the output, free carrier
    "3K Wolfrom": """
name: 3K Wolfrom
components:
  0: {role: frame}
  s: {teeth: 12}
  p1: {teeth: 24, count: 3}
  p2: {teeth: 21, count: 3}
  r1: {teeth: 60, internal: true}
  r2: {teeth: 57, internal: true}
  c: {}
links:
  - {type: mesh, between: [s, p1], carrier: c, efficiency: 0.98}
  - {type: mesh, between: [p1, r1], carrier: c, efficiency: 0.99}
  - {type: mesh, between: [p2, r2], carrier: c, efficiency: 0.99}
  - {type: fixed, between: [p1, p2]}
  - {type: fixed, between: [r1, 0]}
ports:
  - {component: s, role: input, speed: 3000 rpm, power: 500 W}
  - {component: r2, role: output}
""",
    # Ravigneaux: small sun -> short planet -> long planet -> ring; large sun held
    "Ravigneaux": """
name: Ravigneaux set
components:
  0: {role: frame}
  s1: {teeth: 30}
  s2: {teeth: 36}
  ps: {teeth: 18, count: 3}
  pl: {teeth: 18, count: 3}
  r: {teeth: 72, internal: true}
  c: {}
links:
  - {type: mesh, between: [s1, ps], carrier: c, efficiency: 0.98}
  - {type: mesh, between: [ps, pl], carrier: c, efficiency: 0.98}
  - {type: mesh, between: [pl, s2], carrier: c, efficiency: 0.98}
  - {type: mesh, between: [pl, r], carrier: c, efficiency: 0.99}
  - {type: fixed, between: [s2, 0]}
ports:
  - {component: s1, role: input, speed: 2000 rpm, power: 10 kW}
  - {component: r, role: output}
""",
}


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


def carriers(model) -> list[str]:
    return sorted({link.carrier for link in model.meshes
                   if model.body_of[link.carrier] != model.frame_body})


def check_drawing(result, frame, ax) -> None:
    """The drawing is the flow graph of ``result`` seen from ``frame``, legibly."""
    flows = result.flows(frame)
    view = ax.powergraph_view
    artists = ax.powergraph_artists
    # one arrow and one label per flow, zero-power links included
    assert len(artists) == len(flows)
    assert set(artists) == {f.key for f in flows}
    largest = max(f.power for f in flows)
    widths = {}
    for flow in flows:
        arrow, label = artists[flow.key]
        assert arrow in ax.patches and label in ax.texts
        power = 0.0 if flow.power <= 1e-9 * largest else flow.power
        assert label.get_text() == (f"{format_power(power)}\n"
                                    f"{format_share(power, result.input_power)}")
        head = ax.powergraph_heads.get(flow.key)
        if power == 0.0:
            assert head is None and arrow.get_linestyle() == "--"
        else:
            assert head in ax.patches and arrow.get_linestyle() == "-"
            widths[flow.key] = (arrow.get_linewidth(), power)
            _check_ends(ax, flow, arrow, head)
    # width proportional to power (above the thin floor)
    floor = ax.powergraph_layout.style.min_width
    ratios = [w / p for w, p in widths.values() if w > floor * 1.0001]
    assert ratios and np.ptp(ratios) <= 1e-9 * max(ratios)
    # title: whose frame
    title = ax.get_title()
    if view.frame_body is None:
        assert "actual powers (ground frame)" in title
    else:
        assert f"virtual powers seen from {view.frame_body}" in title
    _check_no_overlap(ax)


def _check_ends(ax, flow, arrow, head) -> None:
    """The line leaves the source's symbol; the head's tip touches the target's."""
    nodes = ax.powergraph_nodes
    target = f"loss@{flow.source}" if flow.target == "loss" else flow.target_node
    start = arrow.get_path().vertices[0]
    tip = head.get_xy()[0]
    assert _near(nodes[flow.source_node][0], start), (flow, start)
    assert _near(nodes[target][0], tip), (flow, tip)


def _near(patch, point, tol: float = 1.5) -> bool:
    box = patch.get_extents().transformed(patch.axes.transData.inverted())
    x, y = point
    return box.x0 - tol <= x <= box.x1 + tol and box.y0 - tol <= y <= box.y1 + tol


def _check_no_overlap(ax) -> None:
    """No two texts overlap once rendered; no edge label covers a node symbol."""
    fig = ax.figure
    fig.draw_without_rendering()     # a draw's layout and text extents, no pixels
    renderer = fig.canvas.get_renderer()
    texts = [t for t in ax.texts if t.get_text()] + [ax.title]
    if ax.get_legend() is not None:
        texts += list(ax.get_legend().get_texts())
    boxes = [t.get_window_extent(renderer) for t in texts]
    clashes = [(texts[i].get_text(), texts[j].get_text())
               for i, j in itertools.combinations(range(len(texts)), 2)
               if boxes[i].overlaps(boxes[j])]
    assert not clashes
    if ax.get_subplotspec() is None:     # a figure of its own: every text inside it
        page = fig.bbox
        for text, box in zip(texts, boxes):
            assert page.x0 <= box.x0 and box.x1 <= page.x1 and page.y0 <= box.y0 \
                and box.y1 <= page.y1, text.get_text()
    symbols = [p.get_window_extent(renderer) for p, _ in ax.powergraph_nodes.values()]
    for _, label in ax.powergraph_artists.values():
        box = label.get_window_extent(renderer)
        assert not any(box.overlaps(s) for s in symbols), label.get_text()


#: One model of each kind of train, drawn from every carrier too (the others share their
#: kind with one of these: the 2K-H sets differ only in which members are ports, the RV
#: files only in their data): RV, K-H-V cycloid, Wolfrom, two-stage and double-planet
#: 2K-H, stepped planet, Ravigneaux, Simpson, the 6- and 8-speed automatics, the
#: differentials, the power split and the oil-bath pair.
EVERY_CARRIER = {"rv40e", "cycloid_khv", "wolfrom_3k", "planetary_2kh_two_stages",
                 "planetary_double_planet", "planetary_stepped", "ravigneaux_4speed",
                 "simpson_3speed", "lepelletier_6speed", "zf8hp_8speed", "closed_differential",
                 "bevel_differential", "ths2_power_split", "oil_bath_reducer", "volt_gen1"}
FRAME_CASES = [pytest.param(path, False, id=f"{path.stem}-ground") for path in MODEL_FILES] + [
    pytest.param(path, True, id=f"{path.stem}-every-carrier", marks=pytest.mark.slow)
    for path in MODEL_FILES if path.stem in EVERY_CARRIER]


@pytest.mark.parametrize("path, every_frame", FRAME_CASES)
def test_every_model_in_every_carriers_frame(path, every_frame, solve_ok) -> None:
    """Every library model drawn as seen from the ground (quick), and one of each kind of
    train from each of its carriers (the ground's drawing is the other case's)."""
    model = pg.load_model(str(path))
    result = solve_ok(model)
    for frame in carriers(model) if every_frame else [None]:
        ax = plot_power_flow(result, frame)
        check_drawing(result, frame, ax)
        # a report's figure: long trains folded onto bands near 16 : 9
        b = ax.powergraph_layout.bounds
        assert 1.2 <= (b.x1 - b.x0) / (b.y1 - b.y0) <= 2.4, (frame, b)
        plt.close(ax.figure)


@pytest.mark.slow
def test_hybrid_ports_are_drawn_by_their_names(solve_ok) -> None:
    """THS-II: the engine, the wheels and both machines are called by their port names."""
    result = solve_ok(pg.load_model(str(ROOT / "models" / "ths2_power_split.yaml")))
    ax = plot_power_flow(result)
    drawn = {text.get_text() for _, text in ax.powergraph_nodes.values() if text is not None}
    assert {"engine", "wheels", "MG1", "MG2"} <= drawn
    assert "motor" not in drawn and "generator" not in drawn
    assert max(p.band for p in ax.powergraph_layout.nodes.values()) >= 1   # folded


@pytest.mark.parametrize("name", sorted(UNSEEN))
def test_trains_never_seen(name, solve_ok) -> None:
    model = loads_model(UNSEEN[name])
    result = solve_ok(model)
    assert result.circulating_power > 0          # all three circulate power
    for frame in [None, *carriers(model)]:
        ax = plot_power_flow(result, frame)
        check_drawing(result, frame, ax)
        view = ax.powergraph_view
        for key, (arrow, _) in ax.powergraph_artists.items():
            on_loop = key in view.loop_edges
            assert (arrow.get_edgecolor()[:3] == matplotlib.colors.to_rgb(COLOURS["loop"])) \
                == on_loop, key
        if frame is None:
            assert view.loop_edges
            assert f"circulating power {format_power(result.circulating_power)}" \
                in ax.get_title()
        plt.close(ax.figure)


def test_rv40e_paper_views(solve_ok) -> None:
    result = solve_ok(pg.load_model(str(ROOT / "models" / "rv40e_wang2021.yaml")))
    ax = plot_power_flow(result)
    arrow, label = ax.powergraph_artists[("0/5", "mesh 4-5")]   # principle 1: 0 W
    assert label.get_text() == "0 W\n0 %"
    nodes = ax.powergraph_nodes
    assert nodes["2/3"][1].get_text() == "2/3" and nodes["mesh 1-2"][1].get_text() == "1-2"
    assert nodes["motor"][1].get_text() == "input"       # the port has no name: its role
    assert nodes["generator"][1].get_text() == "output"
    assert nodes["0/5"][0].get_hatch()                           # the held frame
    seen = plot_power_flow(result, "3")
    assert seen.powergraph_nodes["2/3"][0].get_hatch()           # 2/3 held ...
    assert not seen.powergraph_nodes["0/5"][0].get_hatch()       # ... the housing moves
    _, label = seen.powergraph_artists[("ground", "0/5")]
    assert label.get_text().startswith("24.7 kW")


def test_draws_into_given_axes_and_via_result(solve_ok) -> None:
    result = solve_ok(pg.load_model(str(ROOT / "models" / "rv40e_wang2021.yaml")))
    fig, axes = plt.subplots(3, 1, figsize=(8, 8))
    for ax, frame in zip(axes, [None, "7", "3"]):
        assert result.plot(frame=frame, ax=ax) is ax
        check_drawing(result, frame, ax)
    assert len(fig.axes) == 3


def test_same_drawing_twice(solve_ok) -> None:
    model = loads_model(UNSEEN["closed differential"])
    first = plot_power_flow(solve_ok(model), "c")
    second = plot_power_flow(solve_ok(model), "c")
    for key, (arrow, label) in first.powergraph_artists.items():
        other_arrow, other_label = second.powergraph_artists[key]
        assert label.get_position() == other_label.get_position()
        assert np.array_equal(arrow.get_path().vertices, other_arrow.get_path().vertices)


def test_wang2021_result_draws(solve_ok) -> None:
    wang = pytest.importorskip("powergraph.methods.wang2021")
    result = wang.solve_wang2021(pg.load_model(str(ROOT / "models" / "rv40e_wang2021.yaml")))
    ax = plot_power_flow(result)
    assert set(ax.powergraph_artists) == {f.key for f in result.flows()}
    assert "method wang2021" in ax.get_title()
    _check_no_overlap(ax)


class FlowsOnly:
    """A result that only offers the ``solve --json`` object (how other methods' results look)."""

    name = "listed"

    def to_dict(self):
        return {"input_power": 10.0, "flows": [
            {"from": "motor", "to": "a", "power": 10.0},
            {"from": "a", "to": "mesh a-b", "power": 10.0},
            {"from": "mesh a-b", "to": "b", "power": 9.0},
            {"from": "mesh a-b", "to": "loss", "power": 1.0},
            {"from": "b", "to": "generator", "power": 9.0}]}


def test_draws_a_plain_list_of_flows() -> None:
    ax = plot_power_flow(FlowsOnly())
    # a flow list without kinds (older JSON): kinds read from the names
    assert {(a.name, b.name) for a, b in ax.powergraph_artists} == {
        ("motor", "a"), ("a", "mesh a-b"), ("mesh a-b", "b"), ("mesh a-b", "loss"),
        ("b", "generator")}
    assert {a.kind for a, _ in ax.powergraph_artists} == {"motor", "body", "mesh"}
    assert ax.powergraph_artists[("mesh a-b", "b")][1].get_text() == "9.00 W\n90.0 %"
    assert ax.powergraph_view.kinds["mesh a-b"] == "mesh"
    _check_no_overlap(ax)
    with pytest.raises(UsageError):
        plot_power_flow(FlowsOnly(), frame="a")


def test_bad_frame(solve_ok) -> None:
    result = solve_ok(pg.load_model(str(ROOT / "models" / "rv40e_wang2021.yaml")))
    with pytest.raises(UsageError, match="unknown component"):
        plot_power_flow(result, "nope")
    assert flow_view(result, "7").frame_body == "6/7"


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
  - {component: r, role: input, speed: 100 rpm}
  - {component: c, role: output}
"""


def test_two_motors_both_on_the_left(solve_ok) -> None:
    result = solve_ok(loads_model(TWO_INPUTS))
    for frame in (None, "c"):
        ax = plot_power_flow(result, frame)
        check_drawing(result, frame, ax)
        nodes = ax.powergraph_layout.nodes
        left = min(n.x for n in nodes.values())
        assert nodes["motor s"].x == left and nodes["motor r"].x == left
        # the housing has no link: not drawn, unless it turns (then ground drives it)
        assert ("0" in nodes) == (frame is not None)
        plt.close(ax.figure)


def test_back_driven_rv_is_marked_self_locking(solve_ok) -> None:
    from powergraph.kinematics import backdriven

    result = solve_ok(backdriven(pg.load_model(str(ROOT / "models" / "rv40e_wang2021.yaml"))))
    assert result.self_locking
    ax = plot_power_flow(result)
    check_drawing(result, None, ax)
    assert "SELF-LOCKING" in ax.get_title()
    assert "SELF-LOCKING" not in plot_power_flow(
        solve_ok(pg.load_model(str(ROOT / "models" / "rv40e_wang2021.yaml")))).get_title()


BEARINGS = """
name: pair with bearings
components:
  0: {role: frame}
  1: {teeth: 20, geometry: {module: 2, face_width: 10, bore_radius: 0}}
  2: {teeth: 40, drag: {no_load_torque: 0.5 N*m}}
links:
  - {type: mesh, between: [1, 2], efficiency: 0.98}
  - {type: bearing, between: [1, 0], friction: {mu: 0.0015, bore: 20 mm}, drag: {a: 0.1 N*m, b: 0.002 N*m}}
ports:
  - {component: 1, role: input, speed: 1000 rpm, power: 1 kW}
  - {component: 2, role: output}
"""


def test_bearings_and_drags_are_drawn_as_loss_nodes(solve_ok, tmp_path) -> None:
    from powergraph.cli.main import main

    result = solve_ok(loads_model(BEARINGS))
    for frame in (None, "2"):
        ax = plot_power_flow(result, frame)
        check_drawing(result, frame, ax)
        nodes = ax.powergraph_nodes
        assert nodes["bearing 1-0"][1].get_text() == "bearing 1-0"
        assert nodes["drag 2"][0].get_edgecolor()[:3] == matplotlib.colors.to_rgb(COLOURS["loss"])
        assert ax.powergraph_view.kinds["drag 2"] == "drag"
        assert ("bearing 1-0", "loss") in ax.powergraph_artists
        plt.close(ax.figure)
    path = tmp_path / "pair.yaml"
    path.write_text(BEARINGS)
    assert main(["draw", str(path), "-o", str(tmp_path / "flow.png")]) == 0
    assert (tmp_path / "flow.png").stat().st_size > 1000
