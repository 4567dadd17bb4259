"""The lever drawing (powergraph.plot.lever, laid out by powergraph.plot.lever_layout).

A figure a report can take: every node's speed written (in rpm, as the diagram gives
it), the ports marked by their names, a speed scale, no arrow over a text, no two texts
overlapping once rendered (the renderer's own extents), readable with long ids. Checked
on the returned artists, never on pixels, for the bundled trains with planetary sets.
"""
from __future__ import annotations

import itertools
from pathlib import Path

import matplotlib
import pytest
import yaml

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from powergraph.analyses.lever import lever_diagram  # noqa: E402
from powergraph.format import format_number  # noqa: E402
from powergraph.model import load_model, model_from_dict  # noqa: E402
from powergraph.plot.layout.geometry import shortened  # noqa: E402
from powergraph.plot.lever_layout import format_rpm, layout_levers, nice_step  # noqa: E402
from powergraph.statics.case import TrainCase  # noqa: E402
from powergraph.units_si import rpm  # noqa: E402

MODELS = Path(__file__).resolve().parents[2] / "models"

CASES = [("simpson_3speed", "R"), ("ths2_power_split", None), ("simpson_3speed", "1"),
         ("ravigneaux_4speed", "2"),
        ("ravigneaux_4speed", "R"), ("zf8hp_8speed", "4"), ("zf8hp_8speed", "R"),
        ("lepelletier_6speed", "1"), ("lepelletier_6speed", "6"), ("rv40e", None),
        ("cycloid_khv", None), ("planetary_2kh_two_stages_100", None)]


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


def diagram_of(model, mode=None):
    result = TrainCase.of(model, mode).point().required().result
    return lever_diagram(result.model, result.speeds, mode)


def check_levers(diagram, ax) -> None:
    """Everything the drawing promises, read back from its artists."""
    texts = ax.powergraph_texts
    fastest = max(abs(n.speed) for lev in diagram.levers for n in lev.nodes)
    zero = 1e-9 * fastest
    for k, lever in enumerate(diagram.levers):
        for node in lever.nodes:
            # every node's speed written, as the diagram gives it (rad/s -> rpm)
            written = texts[("speed", k, node.component)].get_text()
            assert written == format_number(rpm(node.speed), 4, zero).replace("-", "−")
            # the ports on its body marked by their names
            for port in diagram.ports_on(node):
                assert texts[(port.role, k, node.component)].get_text() == port.name
            name = texts[("name", k, node.component)].get_text()
            assert name.startswith(shortened(node.component).rstrip("…"))
            assert all(e.split()[0] in name for e in node.elements)
            # an arrow for every node that turns
            assert ((k, node.component) in ax.powergraph_arrows) == (abs(node.speed) > zero)
    # ports on no lever: named, with their speeds, in the note under the levers
    notes = [t.get_text() for t in ax.texts if t.get_text().startswith("not on a lever")]
    assert len(notes) == (1 if diagram.ports_off else 0)
    for port in diagram.ports_off:
        assert f"{port.name}" in notes[0] and f"{format_rpm(port.speed, zero)} rpm" in notes[0]
    # a speed scale: a bar as long as its label says, at the arrows' scale
    layout = ax.powergraph_layout
    x0, x1, _ = layout.scale
    label = next(t for t in layout.texts if t.kind == "scale" and t.text.endswith("rpm"))
    step = float(label.text.split()[0].replace(",", ""))
    (start, end) = layout.arrows[0]
    node = next(n for n in layout.nodes if (n.x, n.y) == start)
    speed = next(m.speed for m in diagram.levers[node.lever].nodes
                 if m.component == node.component)
    assert (x1 - x0) / step == pytest.approx((end[0] - start[0]) / rpm(speed), rel=1e-9)
    check_legible(ax)


def check_legible(ax) -> None:
    """No two texts overlap once rendered (title and key included), no arrow crosses a
    text, everything inside the figure."""
    fig = ax.figure
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    items = [t for t in ax.texts if t.get_text()] + [ax.title]
    if ax.get_legend() is not None:
        items += list(ax.get_legend().get_texts())
    boxes = [t.get_window_extent(renderer) for t in items]
    clashes = [(items[i].get_text(), items[j].get_text())
               for i, j in itertools.combinations(range(len(items)), 2)
               if boxes[i].overlaps(boxes[j])]
    assert not clashes
    for arrow in ax.powergraph_arrows.values():
        reach = arrow.get_window_extent(renderer)
        assert not [t.get_text() for t, box in zip(items, boxes) if reach.overlaps(box)]
    page = fig.bbox
    for box in boxes + [ax.get_legend().get_window_extent(renderer)]:
        assert page.x0 <= box.x0 and box.x1 <= page.x1 and page.y0 <= box.y0 \
            and box.y1 <= page.y1


@pytest.mark.slow
@pytest.mark.parametrize("name, mode", CASES, ids=lambda v: str(v))
def test_bundled_levers_are_legible(name, mode) -> None:
    diagram = diagram_of(load_model(MODELS / f"{name}.yaml"), mode)
    ax = diagram.plot()
    assert ax.powergraph_diagram is diagram
    check_levers(diagram, ax)


@pytest.mark.slow
def test_ports_mark_the_nodes_of_their_bodies() -> None:
    """THS-II: engine on the carrier, MG1 on the sun, MG2 on the ring, the wheels behind
    the final drive on no lever."""
    diagram = diagram_of(load_model(MODELS / "ths2_power_split.yaml"))
    (lever,) = diagram.levers
    assert {n.component: [p.name for p in diagram.ports_on(n)] for n in lever.nodes} == \
        {"S": ["MG1"], "C": ["engine"], "R": ["MG2"]}
    (wheels,) = diagram.ports_off
    assert (wheels.name, wheels.role, wheels.component) == ("wheels", "output", "W")
    assert rpm(wheels.speed) == pytest.approx(400.0)
    data = diagram.to_dict()["ports"]
    assert [p["name"] for p in data] == ["engine", "MG1", "MG2", "wheels"]


@pytest.mark.slow
def test_one_lever_line_per_set_and_one_arrow_per_turning_node() -> None:
    model = load_model(MODELS / "simpson_first.yaml")
    diagram = diagram_of(model)
    fig, ax = plt.subplots(figsize=(6.5, 4))           # into a given axes: scaled alike
    assert diagram.plot(ax=ax) is ax
    layout = ax.powergraph_layout
    assert len(layout.levers) == len(diagram.levers) == 2
    turning = [n for lev in diagram.levers for n in lev.nodes if abs(n.speed) > 1e-9]
    assert len(ax.powergraph_arrows) == len(turning)
    check_legible(ax)


def test_arrows_never_reach_a_text_in_the_layout() -> None:
    """The geometry itself (no renderer): every arrow stays clear of every text box."""
    diagram = diagram_of(load_model(MODELS / "zf8hp_8speed.yaml"), "R")
    layout = layout_levers(diagram)
    for (x0, y), (x1, _) in layout.arrows:
        lo, hi = sorted((x0, x1))
        for t in layout.texts:
            b = t.box
            assert hi <= b.x0 or lo >= b.x1 or y + 2.5 <= b.y0 or y - 2.5 >= b.y1, t.text
    for a, b in itertools.combinations(layout.texts, 2):
        assert not a.box.overlaps(b.box), (a.text, b.text)


def long_ids(path: Path) -> dict:
    """The model with every component and shift element renamed to a long id."""
    data = yaml.safe_load(path.read_text())
    new = {str(c): f"{c} member with a rather long descriptive id" for c in data["components"]}
    elements = {link["name"]: f"{link['name']} element with a long name"
                for link in data["links"] if "name" in link}
    get = lambda c: new.get(str(c), c)  # noqa: E731
    data["components"] = {get(c): v for c, v in data["components"].items()}
    for link in data["links"]:
        link["between"] = [get(c) for c in link["between"]]
        if "carrier" in link:
            link["carrier"] = get(link["carrier"])
        if "name" in link:
            link["name"] = elements[link["name"]]
    for port in data["ports"]:
        port["component"] = get(port["component"])
    data["modes"] = {m: [elements[e] for e in engaged] for m, engaged in data["modes"].items()}
    return data


@pytest.mark.slow
def test_long_ids_push_the_levers_apart_and_stay_legible() -> None:
    model = model_from_dict(long_ids(MODELS / "simpson_3speed.yaml"))
    diagram = diagram_of(model, "R")
    ax = diagram.plot()
    check_levers(diagram, ax)
    names = [t.text.split("\n") for t in ax.powergraph_layout.texts if t.kind == "name"]
    assert max(len(line) for lines in names for line in lines) == 40
    assert names[0] == ["s member with a rather long descriptive…",
                        "[C2 element with a long name, B1 elemen…"]


def test_nice_steps_and_speeds_in_rpm() -> None:
    assert [nice_step(v) for v in (1.0, 2999.0, 3000.0, 7.5e-3)] == [1.0, 2000.0, 2000.0,
                                                                     5e-3]
    assert format_rpm(-2 * 3.141592653589793 * 1000 / 60) == "−1,000"
    assert format_rpm(None) == "idle"
