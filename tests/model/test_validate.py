"""Every malformed model is refused with a ModelError naming its place (data file driven)."""
from __future__ import annotations

import re
from pathlib import Path

import pytest
import yaml

import powergraph as pg
from powergraph.errors import ModelError
from powergraph.model import loads_model

DATA = Path(__file__).resolve().parents[1] / "data"
MALFORMED = yaml.safe_load((DATA / "malformed.yaml").read_text())
UNSOLVABLE = yaml.safe_load((DATA / "unsolvable.yaml").read_text())


@pytest.mark.parametrize("case", MALFORMED, ids=[c["id"] for c in MALFORMED])
def test_malformed_model_names_its_place(case: dict) -> None:
    with pytest.raises(ModelError) as info:
        loads_model(case["text"], source="<model>")
    message = str(info.value)
    assert re.search(case["match"], message), message
    if case["path"]:
        assert info.value.path == case["path"], message
        assert message.startswith(case["path"] + ": ")


@pytest.mark.parametrize("case", UNSOLVABLE, ids=[c["id"] for c in UNSOLVABLE])
def test_unsolvable_train_is_a_model_error(case: dict) -> None:
    model = loads_model(case["text"])
    with pytest.raises(ModelError, match=case["match"]):
        pg.solve(model)


def test_valid_model_is_immutable_and_keeps_ids() -> None:
    model = pg.load_model(Path(__file__).resolve().parents[2] / "models" / "rv40e_wang2021.yaml")
    assert [b.id for b in model.bodies] == ["0/5", "1", "2/3", "4", "6/7"]
    assert model.components["5"].internal and model.components["2"].count == 2
    with pytest.raises(Exception):
        model.name = "x"  # frozen dataclass
    with pytest.raises(TypeError):
        model.components["9"] = None  # read-only mapping


def test_mesh_carrier_defaults_to_frame_and_efficiency_to_defaults() -> None:
    model = loads_model("""
name: pair
defaults: {mesh_efficiency: 0.97}
components: {0: {role: frame}, 1: {teeth: 20}, 2: {teeth: 40}}
links: [{type: mesh, between: [1, 2]}]
ports: [{component: 1, role: input}, {component: 2, role: output}]
""")
    assert model.links[0].carrier == "0" and model.links[0].efficiency == 0.97


def test_network_view_has_components_as_nodes_and_links_as_edges() -> None:
    from powergraph.model import to_networkx

    model = pg.load_model(Path(__file__).resolve().parents[2] / "models" / "rv40e_wang2021.yaml")
    graph = to_networkx(model)
    assert set(graph.nodes) == set(model.components)
    assert graph.number_of_edges() == len(model.links)
    assert graph.edges["4", "5", 1]["carrier"] == "3"


PAIR = """name: pair
components: {0: {role: frame}, 1: {teeth: 20}, 2: {teeth: 40}}
links: [{type: mesh, between: [1, 2]}]
ports: [{component: 1, role: input, speed: SPEED, power: 1 kW}, {component: 2, role: output}]
"""


@pytest.mark.parametrize("speed, shown", [("1500", "1500"), ("'1500'", "1500"),
                                          ("-1500", "-1500")])
def test_a_speed_without_a_unit_is_read_as_rad_s_with_a_caveat(speed, shown) -> None:
    model = loads_model(PAIR.replace("SPEED", speed))
    assert model.ports[0].speed == float(shown)  # still rad/s, as the format says
    caveats = [c for c in model.warnings if c.code == "bare-speed"]
    assert len(caveats) == 1 and caveats[0].path == "ports[0].speed"
    # 1500 rad/s * 60 s/min / (2π rad/rev) = 14,323.9 rev/min
    rpm = "14,324" if shown == "1500" else "-14,324"
    assert caveats[0].message == (f"no unit: read as {shown} rad/s ({rpm} rpm); write "
                                  f"'{shown} rad/s' to keep it, or '{shown} rpm'")


@pytest.mark.parametrize("speed", ["1500 rad/s", "1500 rpm", "0", "25 Hz"])
def test_a_speed_with_a_unit_or_zero_has_no_caveat(speed) -> None:
    model = loads_model(PAIR.replace("SPEED", speed))
    assert not [c for c in model.warnings if c.code == "bare-speed"]


def test_bare_powers_and_torques_are_plain_si_without_caveat() -> None:
    model = loads_model(PAIR.replace("SPEED", "10 rad/s").replace("1 kW", "1000"))
    assert model.ports[0].power == 1000.0 and model.warnings == ()


@pytest.mark.slow
def test_the_library_models_write_their_speeds_with_units() -> None:
    for path in sorted((Path(__file__).resolve().parents[2] / "models").glob("*.yaml")):
        assert not pg.load_model(path).warnings, path.name


def test_a_model_with_merge_keys_is_the_expanded_model() -> None:
    merged = loads_model("""
name: merged
components:
  0: {role: frame}
  1: &gear {teeth: 20, count: 1, name: pinion}
  2: {<<: *gear, teeth: 40, name: wheel}
  3: &idler {teeth: 60, count: 2}
  4: {<<: [*idler, *gear], name: last}
links:
  - &mesh {type: mesh, between: [1, 2], efficiency: 0.98}
  - {<<: *mesh, between: [2, 3]}
  - {<<: *mesh, between: [3, 4], efficiency: 0.97}
ports: [{component: 1, role: input, speed: 10 rad/s}, {component: 4, role: output}]
""")
    expanded = loads_model("""
name: merged
components:
  0: {role: frame}
  1: {teeth: 20, count: 1, name: pinion}
  2: {teeth: 40, count: 1, name: wheel}
  3: {teeth: 60, count: 2}
  4: {teeth: 60, count: 2, name: last}
links:
  - {type: mesh, between: [1, 2], efficiency: 0.98}
  - {type: mesh, between: [2, 3], efficiency: 0.98}
  - {type: mesh, between: [3, 4], efficiency: 0.97}
ports: [{component: 1, role: input, speed: 10 rad/s}, {component: 4, role: output}]
""")
    assert merged == expanded
    assert (merged.components["4"].count, merged.components["4"].name) == (2, "last")


@pytest.mark.parametrize("line, tagged, path, words", [
    (2, "2: {teeth: 40, internal: !!bool 'maybe'}", "components.2.internal",
     "!!bool 'maybe' is not a boolean"),
    (2, "2: {teeth: !!int 'abc'}", "components.2.teeth", "!!int 'abc' is not an integer"),
    (5, "links: [{type: mesh, between: [1, 2], efficiency: !!float ''}]",
     "links[0].efficiency", "!!float '' is not a number"),
    (2, "2: {teeth: !!binary aGVsbG8=}", "components.2.teeth", "unsupported YAML tag !!binary"),
    (2, "2: {teeth: 40, note: !foo x}", "components.2.note", "unsupported YAML tag !foo"),
])
def test_a_bad_tag_in_a_model_names_line_and_path(line, tagged, path, words) -> None:
    rows = TAGGED_PAIR.split("\n")
    rows[line] = ("  " if line == 2 else "") + tagged
    with pytest.raises(ModelError) as info:
        loads_model("\n".join(rows))
    assert info.value.path == path and words in info.value.message
    assert f"(line {line + 1})" in info.value.message


def test_good_tags_in_a_model_read_as_the_plain_values() -> None:
    tagged = loads_model(TAGGED_PAIR.replace("teeth: 40", "teeth: !!int '40'")
                         .replace("efficiency: 0.98", "efficiency: !!float '0.98'")
                         .replace("name: pair", "name: !!str pair"))
    assert tagged == loads_model(TAGGED_PAIR)


TAGGED_PAIR = """name: pair
components:
  2: {teeth: 40}
  0: {role: frame}
  1: {teeth: 20}
links: [{type: mesh, between: [1, 2], efficiency: 0.98}]
ports: [{component: 1, role: input, speed: 10 rad/s}, {component: 2, role: output}]
"""


# Issue 34, item 1: a port's name addresses it (a duty cycle's NAME.speed columns, where a
# component id addresses its port too; a machine's losses and flow-graph node), so names
# are unique, and no port is named like another component.
THS = (Path(__file__).resolve().parents[2] / "models" / "ths2_power_split.yaml").read_text()


def _refused(text: str) -> ModelError:
    with pytest.raises(ModelError) as info:
        loads_model(text)
    return info.value


def test_issue34_two_ports_with_one_name_are_refused_naming_the_earlier() -> None:
    error = _refused(THS.replace("name: MG2", "name: MG1"))
    assert str(error) == ("ports[2].name: port name 'MG1' is already the name of ports[1] "
                          "(port names are unique)")
    # spaces around a name do not make it another (a CSV header's are dropped)
    error = _refused(THS.replace("name: MG2", "name: ' MG1 '"))
    assert error.path == "ports[2].name" and "ports[1]" in error.message


def test_issue34_a_port_named_like_another_ports_component_is_refused() -> None:
    error = _refused(THS.replace("name: wheels", "name: S"))
    assert str(error) == ("ports[3].name: port name 'S' is the id of component 'S', the "
                          "component of ports[1]: a duty cycle's columns would not know "
                          "which port it means; rename the port")


def test_issue34_a_port_named_like_a_component_without_a_port_is_refused() -> None:
    error = _refused(THS.replace("name: wheels", "name: P"))
    assert error.path == "ports[3].name"
    assert error.message.startswith("port name 'P' is the id of component 'P': ")


def test_issue34_ids_and_names_compare_as_text() -> None:
    text = PAIR.replace("SPEED", "10 rad/s").replace("role: output}", "role: output, name: 1}")
    error = _refused(text)
    assert error.path == "ports[1].name" and "component '1', the component of ports[0]" \
        in error.message


def test_issue34_a_port_may_bear_its_own_components_id() -> None:
    model = loads_model(THS.replace("name: engine", "name: C"))
    assert model.ports[0].name == "C" and model.ports[0].component == "C"


def test_issue34_a_blank_port_name_is_refused() -> None:
    error = _refused(THS.replace("name: wheels", "name: '  '"))
    assert str(error) == "ports[3].name: a port name must not be blank (leave name out for none)"


def test_issue34_a_port_named_like_an_unnamed_machine_is_refused() -> None:
    # An unnamed machine on S is 'machine S' in the reports and the flow graph.
    text = THS.replace("name: MG1, ", "").replace("name: MG2", "name: machine S")
    error = _refused(text)
    assert str(error) == ("ports[2].name: port name 'machine S' is the name reports give the "
                          "machine ports[1], which has none; name that port, or rename this "
                          "one")


def test_issue34_a_shift_element_may_share_a_ports_name() -> None:
    """Shift elements are addressed by the modes table only, and ports never are: the two
    sets of names do not meet, so an element named like a port is fine (and two elements
    with one name are refused, tests/model/test_shift.py)."""
    model = loads_model("""name: t
components: {0: {role: frame}, 1: {teeth: 20}, 2: {teeth: 40}, 3: {}}
links: [{type: mesh, between: [1, 2]}, {type: clutch, name: out, between: [2, 3], engaged: true}]
ports: [{component: 1, role: input, speed: 10 rad/s}, {component: 3, role: output, name: out}]
""")
    assert model.shift_elements[0].name == model.ports[1].name == "out"
