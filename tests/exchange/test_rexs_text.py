"""REXS text (powergraph.exchange.rexs_text): the XML and JSON forms of one document
read back (powergraph.model.rexs_document) as the same components, relations and load
cases."""
from __future__ import annotations

import pytest

from powergraph.exchange.rexs_text import to_json, to_xml
from powergraph.model.rexs_document import (RexsComponent, RexsDocument, RexsRelation,
                                            parse_rexs)

DOCUMENT = RexsDocument(
    "1.4",
    {1: RexsComponent(1, "shaft", "in", {"defines_speed": (True, "none")}),
     2: RexsComponent(2, "cylindrical_gear", "pinion",
                      {"number_of_teeth": (-17, "none"), "normal_module": (2.5, "mm")})},
    (RexsRelation(3, "assembly", (("assembly", 1, "shaft"), ("part", 2, "cylindrical_gear"))),),
    ({1: {"rotational_speed": (1500.0, "1 / min")}},), "x")


@pytest.mark.parametrize("write", [to_xml, to_json])
def test_written_text_reads_back(write) -> None:
    back = parse_rexs(write(DOCUMENT).encode(), "x")
    assert back.version == "1.4"
    assert back.relations == DOCUMENT.relations
    assert {i: (c.type, c.name) for i, c in back.components.items()} == {
        1: ("shaft", "in"), 2: ("cylindrical_gear", "pinion")}
    teeth, unit = back.components[2].attributes["number_of_teeth"]
    assert int(teeth) == -17 and unit == "none"
    speed, unit = back.load_cases[0][1]["rotational_speed"]
    assert float(speed) == 1500.0 and unit == "1 / min"
