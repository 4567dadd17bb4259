"""Lever diagrams (powergraph.analyses.lever): node spacing from the tooth numbers, and
the speeds of a mode on one straight line across each lever."""
from __future__ import annotations

from pathlib import Path

import pytest

from powergraph.analyses.lever import lever_diagram
from powergraph.model import load_model
from powergraph.statics.modes import solve_mode
from powergraph.testing import assert_conservation

MODELS = Path(__file__).resolve().parents[2] / "models"


def test_simple_set_spacing_is_zr_to_zs() -> None:
    """Simpson set (z_s 24, z_r 72): sun at 1, carrier at 0, ring at -z_s/z_r, so
    sun-carrier : carrier-ring = z_r : z_s = 3."""
    diagram = lever_diagram(load_model(MODELS / "simpson_first.yaml"))
    front = diagram.levers[0]
    assert front.carrier == "c1"
    assert [(n.component, n.position) for n in front.nodes] == [
        ("s", 1.0), ("c1", 0.0), ("r1", pytest.approx(-24 / 72, rel=1e-12))]
    assert [n.grounded for n in diagram.levers[1].nodes] == [False, True, False]


def test_ravigneaux_lever_has_four_nodes_and_speeds_on_a_line() -> None:
    """Ravigneaux (z_s1 30, z_s2 36, z_r 72), carrier held, s1 at 1: the ring turns at
    +z_s1/z_r (two external meshes and an internal one), s2 at -(z_s1/z_r)(z_r/z_s2)."""
    mode = solve_mode(load_model(MODELS / "ravigneaux_4speed.yaml"), "2")
    assert_conservation(mode.result)
    speeds = mode.result.speeds
    lever = lever_diagram(mode.result.model, speeds, "2").levers[0]
    positions = {n.component: n.position for n in lever.nodes}
    assert positions == pytest.approx({"s1": 1.0, "r": 30 / 72, "c": 0.0, "s2": -30 / 36},
                                      rel=1e-12)
    w_c, w_ref = speeds["c"], speeds["s1"]
    for node in lever.nodes:
        assert node.speed == pytest.approx(w_c + node.position * (w_ref - w_c), rel=1e-9,
                                           abs=1e-9)
    assert [n.grounded for n in lever.nodes] == [False, False, False, True]   # B1 holds s2


def test_stepped_planets_are_one_planet_not_a_node() -> None:
    """A stepped planet's steps (fixed to each other) turn together and are no lever node:
    the stepped 2K-H has sun, carrier and ring, the ring at -(z_s/z_p1)(z_p2/z_r) = -1/8
    (k = 8); the Wolfrom set has its sun, carrier and both rings, the output ring at
    -(12/30)(27/69)."""
    stepped = lever_diagram(load_model(MODELS / "planetary_stepped.yaml")).levers[0]
    assert [(n.component, n.position) for n in stepped.nodes] == [
        ("s", 1.0), ("c", 0.0), ("r", pytest.approx(-1 / 8, rel=1e-12))]
    wolfrom = lever_diagram(load_model(MODELS / "wolfrom_3k.yaml")).levers[0]
    assert {n.component: n.position for n in wolfrom.nodes} == pytest.approx(
        {"s": 1.0, "c": 0.0, "r1": -12 / 72, "r2": -(12 / 30) * (27 / 69)}, rel=1e-12)


def test_a_train_without_a_planetary_set_has_no_lever(capsys) -> None:
    """The i-MMD's gears all turn on fixed axes: no lever, one line and exit 2."""
    from powergraph.cli.main import main
    from powergraph.errors import MethodNotApplicableError

    path = Path(__file__).resolve().parents[2] / "models" / "honda_immd.yaml"
    with pytest.raises(MethodNotApplicableError, match="no planetary set"):
        lever_diagram(load_model(path))
    assert main(["lever", str(path), "--mode", "EV drive", "-o", "unused.png"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("powergraph: error: no planetary set") and len(err.splitlines()) == 1
