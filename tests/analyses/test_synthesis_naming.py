"""Readable names of synthesised trains (powergraph.analyses.synthesis.naming) and the
names and planet counts of the model files synthesis writes.

Expected values: the roles follow from the definitions (a gear on a coaxial link is a ring
when internal, else a sun; a gear on a link off the main axis is a planet), the axes are
those ``powergraph enumerate --links 6`` prints for d-graphs 29 and 30
(``{0,1,4,5} {1,2,3}`` against ``{0,1,4,5} {1,2} {1,3}``), and every written model is
solved again (``assert_conservation``): a planet count changes no speed or efficiency.
"""
from __future__ import annotations

import pytest

import powergraph as pg
from powergraph.analyses.synthesis import enumerate_trains
from powergraph.analyses.synthesis.naming import gear_names, pin_note, teeth_text
from powergraph.analyses.synthesis.synthesize import synthesize
from powergraph.analyses.synthesis.synthesize_classics import CLASSICS, classic_graphs
from powergraph.analyses.synthesis.teeth import layouts
from powergraph.model import model_from_dict
from powergraph.testing import assert_conservation


@pytest.mark.slow  # layouts / enumeration / synthesis
def test_gear_names_follow_the_roles_of_the_layout() -> None:
    for layout in layouts(CLASSICS["2K-H"]):
        st, internal = layout.structure, layout.internal
        for gear, name in gear_names(layout).items():
            pair, side = int(gear[1:-1]), "ab".index(gear[-1])
            link = CLASSICS["2K-H"].gear_pairs[pair][side]
            role = name.split(" ")[0]
            assert name.endswith(f"L{link}")
            if link in st.coaxial:
                assert role == ("ring" if internal.get(pair) == side else "sun")
            else:
                assert role == "planet"


def test_teeth_text_merges_a_simple_planet_and_shows_a_stepped_one() -> None:
    names = {"g0a": "ring L1", "g0b": "planet L2", "g1a": "planet L2", "g1b": "sun L0"}
    assert teeth_text({"g0a": 72, "g0b": 24, "g1a": 24, "g1b": 24}, names) == \
        "sun L0=24, planet L2=24, ring L1=72"
    assert teeth_text({"g0a": 72, "g0b": 30, "g1a": 18, "g1b": 24}, names) == \
        "sun L0=24, planet L2=30/18, ring L1=72"


@pytest.mark.slow  # layouts / enumeration / synthesis
def test_pin_note_tells_two_d_graphs_with_the_same_gears_apart() -> None:
    graphs = {g.name: g for g in enumerate_trains(6).graphs}
    one_pin = next(iter(layouts(graphs["6-link d-graph 29 (r-graph 8)"])))
    two_pins = next(iter(layouts(graphs["6-link d-graph 30 (r-graph 8)"])))
    assert pin_note(one_pin) == "L2+L3 on one pin"
    assert pin_note(two_pins) == ""


@pytest.mark.slow  # layouts / enumeration / synthesis
def test_rows_name_gears_and_written_models_carry_names_and_planet_counts() -> None:
    result = synthesize(4.0, graphs=classic_graphs(4), top=3, planets=3)
    assert result.rows
    for row in result.rows:
        assert "g0a" not in row.teeth_text() and "sun" in row.teeth_text()
        doc = row.model_document()
        assert doc["name"] == row.name
        for cid, component in doc["components"].items():
            assert component.get("name"), cid
        model = model_from_dict(doc)
        planets = [c for c in model.components.values() if c.name.startswith("planet")]
        assert planets and all(c.count == 3 for c in planets)
        solved = pg.solve(model)
        assert_conservation(solved)
        assert solved.ratio == pytest.approx(row.ratio, rel=1e-9)
        assert solved.efficiency == pytest.approx(row.efficiency, rel=1e-9)


def test_members_are_named_by_role_and_set() -> None:
    # two 2K-H stages (synthesize_classics): common ring 0, sun 1, planet 2 on carrier 3
    # (set 1: the carrier of lower link number), carrier 3 also the second sun, planet 4 on
    # carrier 5 (set 2). Whether a coaxial gear is a sun or a ring is the layout's choice.
    from powergraph.analyses.synthesis.naming import member_names

    for layout in layouts(CLASSICS["two 2K-H stages"], (12, 40)):
        names = member_names(layout)
        internal = layout.internal
        kind = {k: "ring" if k in internal else "sun" for k in range(4)}
        assert names["L1"] == f"{kind[0]} 1"
        assert names["L0"] == f"{kind[1]} 1+{kind[3]} 2"
        assert names["L3"] == f"carrier 1+{kind[2]} 2"
        assert names["L5"] == "carrier 2"
        assert (names["L2"], names["L4"]) == ("planet 1", "planet 2")
    single = member_names(layouts(CLASSICS["Wolfrom 3K"], (12, 40))[0])
    assert single["L3"] == "carrier" and single["L4"] == "planet"    # one set: no number
    assert len(set(single.values())) == len(single)                  # two suns: a, b
