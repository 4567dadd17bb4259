"""Idle gears in the synthesis: a gear that meshes one gear only and carries nothing.

Expected values: the moment balance of such a link about its own axis (frictionless
bearings, no external torque) leaves its one mesh force zero, so the mesh passes no power
and loses nothing; ``powergraph.solve`` shows it (with ``assert_conservation``). The
ranking leaves out every tooth set in which a mesh passes no power
(:func:`powergraph.analyses.synthesis.rank.evaluate_hits`): the tests show that the
arrangements and graphs the search no longer visits give no row there either.
"""
from __future__ import annotations

import numpy as np
import pytest

import powergraph as pg
from powergraph.analyses.synthesis import TrainGraph, synthesize_bound, synthesize_search
from powergraph.analyses.synthesis.rank import evaluate_hits
from powergraph.analyses.synthesis.synthesize import synthesize
from powergraph.analyses.synthesis.synthesize_bound import search_part
from powergraph.analyses.synthesis.synthesize_classics import CLASSICS
from powergraph.analyses.synthesis.synthesize_search import (graph_layouts, idle_links,
                                                             workable, working)
from powergraph.analyses.synthesis.teeth import structure
from powergraph.model import model_from_dict
from powergraph.testing import assert_conservation

#: A 2K-H (ring 0, sun 1, planet 2, carrier 3) with a second planet 4 on the carrier that
#: meshes the sun only.
IDLE_PLANET = TrainGraph(5, ((0, 1, 0), (0, 3, 0), (3, 2, 1), (3, 4, 2)),
                         ((1, 2, 3), (2, 0, 3), (1, 4, 3)), name="2K-H with an idle planet")


def test_idle_links_of_the_classic_trains() -> None:
    # by hand: a link with one mesh, holding no gear pair and no coupling
    assert idle_links(CLASSICS["2K-H"]) == {0, 1}                  # ring, sun
    assert idle_links(CLASSICS["Wolfrom 3K"]) == {0, 1, 2}         # sun, both rings
    assert idle_links(CLASSICS["Simpson"]) == {3}                  # the ring of stage 1
    assert idle_links(CLASSICS["RV (2K-H + K-H-V)"]) == {0, 1}     # pin ring, centre gear
    assert idle_links(IDLE_PLANET) == {0, 4}
    assert structure(IDLE_PLANET) is not None and IDLE_PLANET.dof == 1
    assert not workable(IDLE_PLANET) and workable(CLASSICS["Wolfrom 3K"])
    assert working(CLASSICS["Wolfrom 3K"], 0, 1, 2)
    assert not working(CLASSICS["Wolfrom 3K"], 3, 1, 2)            # ring 0 would idle


def test_an_idle_planet_passes_no_power() -> None:
    teeth = {(0, 0): 20, (0, 1): 30, (1, 0): 30, (1, 1): 80, (2, 0): 20, (2, 1): 25}
    doc = IDLE_PLANET.to_model_dict(frame=0, inputs=(1,), outputs=(3,), teeth=teeth,
                                    internal={1: 1}, mesh_efficiency=0.98)
    result = pg.solve(model_from_dict(doc))
    assert_conservation(result)
    losses = {flow.link: flow.loss for flow in result.elements}
    power = abs(result.input_power)
    assert abs(losses[2]) <= 1e-9 * power             # sun 1 - idle planet 4
    assert min(abs(losses[0]), abs(losses[1])) > 1e-3 * power
    assert result.ratio == pytest.approx(1 + 80 / 20)  # the 2K-H's Willis ratio


@pytest.mark.slow
@pytest.mark.parametrize("ratio, some_dropped, some_kept", [(-5.0, True, False),
                                                            (5.0, False, True)])
def test_arrangements_left_out_would_give_no_row(monkeypatch, ratio, some_dropped,
                                                 some_kept) -> None:
    """Searched as before (every arrangement), the Wolfrom's arrangements with an idle
    ring or sun (at -5: the carrier driven, a ring or the sun left free) have hits, and the
    ranking leaves every one of them out; the search now drops them, and keeps the others
    (at 5: sun and rings fixed, driven and loaded)."""
    graph, teeth = CLASSICS["Wolfrom 3K"], (12, 40)

    def hits():
        return {(li, h.fixed, h.input, h.output): h
                for li, _ in enumerate(graph_layouts(graph, teeth, 3))
                for h in search_part(graph, 0, li, 0, 1, ratio, 0.01, teeth, 3)}

    kept = hits()
    for module in (synthesize_search, synthesize_bound):
        monkeypatch.setattr(module, "working", lambda *arrangement: True)
    everything = hits()
    dropped = {key: h for key, h in everything.items() if key not in kept}
    assert bool(dropped) == some_dropped and bool(kept) == some_kept
    assert all(not idle_links(graph) <= set(key[1:]) for key in dropped)
    for key, h in dropped.items():
        assert evaluate_hits(graph, h, ratio, teeth, 3, 0.98) is None, key
    for key, h in kept.items():
        np.testing.assert_array_equal(everything[key].flat, h.flat)


@pytest.mark.slow
def test_a_graph_with_an_idle_planet_is_not_searched() -> None:
    result = synthesize(5.0, graphs=[IDLE_PLANET, CLASSICS["2K-H"]], teeth=(12, 40),
                        top=None)
    alone = synthesize(5.0, graphs=[CLASSICS["2K-H"]], teeth=(12, 40), top=None)
    assert result.idle == ("2K-H with an idle planet",) and alone.idle == ()
    assert result.evaluated == alone.evaluated > 0
    assert [r.to_dict() for r in result.rows] == [r.to_dict() for r in alone.rows]
    assert "1 graph(s) not searched" in result.text_report()
    assert result.to_dict()["idle"] == ["2K-H with an idle planet"]
