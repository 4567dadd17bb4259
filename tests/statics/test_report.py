"""The solve report's presentation (powergraph.statics.report, powergraph.format): names
beside ids, aligned columns whatever the names, one unit per column, no -0, the ratio as
a reduction or a step-up, repr and HTML."""
from __future__ import annotations

import re

import pytest

import powergraph as pg
from powergraph.model import model_from_dict
from powergraph.result import display_width
from powergraph.format import column, power_unit, ratio_text
from powergraph.testing import assert_conservation

LONG = "a very long name for the sun gear of the first stage, ünïcödé"
WIDE = "太阳轮"   # wide characters: two terminal columns each


def named_pair(names: tuple[str, str], port_names: tuple[str, str],
               teeth=(20, 60), internal: bool = True, power: float = 1500.0) -> pg.Model:
    return model_from_dict({
        "name": "pair", "defaults": {"mesh_efficiency": 0.97},
        "components": {0: {"role": "frame", "name": "housing"},
                       1: {"name": names[0], "teeth": teeth[0]},
                       2: {"name": names[1], "teeth": teeth[1], "internal": internal}},
        "links": [{"type": "mesh", "between": [1, 2]}],
        "ports": [{"component": 1, "role": "input", "name": port_names[0], "speed": "30 rad/s",
                   "power": power},
                  {"component": 2, "role": "output", "name": port_names[1]}]})


def _section(text: str, title: str) -> list[str]:
    lines = text.splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith(title)) + 1
    end = next((i for i in range(start, len(lines)) if not lines[i].strip()), len(lines))
    return lines[start:end]


@pytest.mark.parametrize("names, ports", [
    (("s", "r"), ("a", "b")),
    ((LONG, WIDE), (WIDE + WIDE, LONG)),
])
def test_columns_stay_aligned_whatever_the_names(names, ports) -> None:
    result = pg.solve(named_pair(names, ports))
    assert_conservation(result)
    text = result.text_report()
    rows = _section(text, "ports")
    header, body = rows[0], rows[1:]
    assert names[0] in body[0] and ports[0] in body[0]      # names beside the ids
    title = re.search(r"power k?W", header).group(0)
    power_end = display_width(header[:header.index(title) + len(title)])
    for row in body:
        cells = re.split(r"\s{2,}", row.strip())     # no name holds two spaces
        assert len(cells) == 8
        after = row.index(cells[5]) + len(cells[5])
        end = row.index(cells[6], after) + len(cells[6])
        assert display_width(row[:end]) == power_end, (row, header)
    speeds = _section(text, "speeds")
    rpm_end = display_width(speeds[0][:speeds[0].index("rpm") + 3])
    for row in speeds[1:]:
        cells = re.split(r"\s{2,}", row.strip())
        end = row.index(cells[2], row.index(cells[1]) + len(cells[1])) + len(cells[2])
        assert display_width(row[:end]) == rpm_end, (row, speeds[0])


def test_one_unit_per_column_and_no_minus_zero() -> None:
    """The housing's speed is exactly 0 (and may be -0.0 in floating point): never
    '-0'; powers of 1.5 kW and a few W share one unit in each table."""
    result = pg.solve(named_pair(("pinion", "ring"), ("motor", "drum"), teeth=(20, 40),
                                 internal=False))
    assert_conservation(result)
    text = result.text_report()
    assert not re.search(r"(?<![\d.,])-0(\.0*)?(?![\d.,])", text)
    for title in ("ports", "meshes", "where the power goes"):
        rows = _section(text, title)
        assert re.search(r"\b(k?W)\b", rows[0])                          # unit in header
        assert not any(re.search(r"\b(k?W)\b", row) for row in rows[1:])  # not in cells
    assert "power kW" in _section(text, "ports")[0]       # 1.5 kW in: kW for that column
    assert "loss W" in _section(text, "meshes")[0]        # 45 W lost: W for that one


def test_a_step_up_prints_one_to_n_and_a_reduction_n_to_one() -> None:
    """A 1:100 step-up: ring of 1000 teeth driving a pinion of 10 (frame-held internal
    pair: w_pinion = 100 w_ring); a 20/60 pair reduces 3 : 1."""
    up = model_from_dict({
        "name": "wind", "components": {0: {"role": "frame"}, "ring": {"teeth": 1000,
                                                                      "internal": True},
                                       "pinion": {"teeth": 10}},
        "links": [{"type": "mesh", "between": ["ring", "pinion"]}],
        "ports": [{"component": "ring", "role": "input", "speed": "1.5 rad/s", "power": 2e6},
                  {"component": "pinion", "role": "output"}]})
    result = pg.solve(up)
    assert_conservation(result)
    text = result.text_report()
    assert "1 : 100" in text and "0.01" not in text.split("\n\n")[1]
    assert "MW" in text          # 2 MW in: the unit fits the size
    assert ratio_text(3.0) == "3 : 1" and ratio_text(-119.0) == "119 : 1, output reversed"


def test_repr_is_one_line_and_html_a_table() -> None:
    result = pg.solve(named_pair(("pinion", "ring"), ("motor", "drum")))
    text = repr(result)
    assert "\n" not in text and len(text) < 120
    assert "pair" in text and "1 DOF" in text and "3 : 1" in text and "97.00 %" in text
    html = result._repr_html_()
    assert html.startswith("<table>") and "motor" in html and "97.00 %" in html


def test_column_helpers() -> None:
    assert power_unit([999.0]) == ("W", 1.0) and power_unit([-1000.0]) == ("kW", 1e3)
    assert column([-1e-9, 2.5], significant=3) == ["0.00", "2.50"]
    assert column([1234567.0], 1e6) == ["1.23457"]


@pytest.mark.slow
def test_a_cycloid_mesh_loss_is_split_into_its_parts_and_the_table_adds_up() -> None:
    """The cycloid mesh's basic efficiency is the product η_pins · η_bearings
    (powergraph.gears.cycloid_loss), so its loss P (1 − η) is shared as
    −ln η_part / −ln η: the parts add up to the mesh's loss, and every source to the
    total loss."""
    import math

    from powergraph.statics.report import loss_sources

    model = pg.load_model("models/rv40e.yaml")
    result = pg.solve(model)
    assert_conservation(result)
    sources = dict(loss_sources(result))
    assert sum(sources.values()) == pytest.approx(result.total_loss, rel=1e-12)
    stage = model.links[1].blocks["friction"].loss
    pins = next(v for k, v in sources.items() if k.endswith(": pins"))
    bearings = next(v for k, v in sources.items() if k.endswith(": crank bearings"))
    assert pins + bearings == pytest.approx(result.element(1).loss, rel=1e-12)
    assert pins / bearings == pytest.approx(
        math.log(stage.pin_efficiency) / math.log(stage.bearing_efficiency), rel=1e-12)
