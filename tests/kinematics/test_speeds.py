"""Kinematics alone: the RV-40E speeds (tests/data/published_values.yaml), DOF counts,
slips, derived operating cases, and given speeds that contradict each other (the links
whose rows conflict, hand-derived)."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import yaml

import powergraph as pg
from powergraph.errors import KinematicsError
from powergraph.kinematics import backdriven, degrees_of_freedom, solve_speeds
from powergraph.model import loads_model, model_from_dict
from powergraph.testing_trains import gear_chain_text

MODELS = Path(__file__).resolve().parents[2] / "models"


def test_rv40e_speeds_are_reference_b() -> None:
    kin = solve_speeds(pg.load_model(MODELS / "rv40e_wang2021.yaml"))
    assert kin.speed("2") == pytest.approx(-50.6290, abs=5e-5) == kin.speed("3")
    assert kin.speed("4") == pytest.approx(1.29818, abs=5e-6)
    assert kin.speed("6") == kin.speed("7") == kin.speed("4")
    assert kin.speed("0") == 0.0 == kin.speed("5")
    assert kin.ratio == pytest.approx(1 + 36 * 40 / 12, rel=1e-12)   # i = 1 + z2 z5 / z1


@pytest.mark.parametrize("name,dof", [("rv40e_wang2021.yaml", 1), ("bevel_differential.yaml", 2),
                                      ("wolfrom_3k.yaml", 1), ("ravigneaux_second.yaml", 1)])
def test_degrees_of_freedom(name: str, dof: int) -> None:
    assert degrees_of_freedom(pg.load_model(MODELS / name)) == dof


def test_slip_on_a_fixed_axis_pair() -> None:
    """Pair 20/40 on the frame, input held: the row (w_1 - 0) - i (w_2 - 0) = s with
    i = -z_2/z_1 = -2 and w_1 = 0 gives w_2 = s/2."""
    model = loads_model("""
name: pair
components: {0: {role: frame}, 1: {teeth: 20}, 2: {teeth: 40}}
links: [{type: mesh, between: [1, 2]}]
ports: [{component: 1, role: input}, {component: 2, role: output}]
""")
    kin = solve_speeds(model, speeds={"1": 0.0}, slips={0: 1.0})
    assert kin.speed("2") == pytest.approx(0.5, rel=1e-15)


def test_backdriven_swaps_ports_and_keeps_the_motion() -> None:
    model = pg.load_model(MODELS / "rv40e_wang2021.yaml")
    back = backdriven(model)
    assert [(p.component, p.role) for p in back.ports] == [("1", "output"), ("6", "input")]
    assert back.inputs[0].power == model.inputs[0].power
    assert solve_speeds(back).speed("1") == pytest.approx(solve_speeds(model).speed("1"),
                                                          rel=1e-12)


def test_the_structure_cached_per_model_does_not_leak_into_a_changed_copy() -> None:
    """The rank and matchings are kept on the model; a copy with another tooth number
    (dataclasses.replace) starts without them and gets its own ratio, 1 + z2 z5 / z1."""
    import dataclasses
    from types import MappingProxyType

    model = pg.load_model(MODELS / "rv40e_wang2021.yaml")
    assert solve_speeds(model).ratio == pytest.approx(1 + 36 * 40 / 12, rel=1e-12)
    assert "kinematics.structure" in model.derived
    components = dict(model.components)
    components["2"] = dataclasses.replace(components["2"], teeth=30)
    copy = dataclasses.replace(model, components=MappingProxyType(components))
    assert copy.derived == {}
    assert solve_speeds(copy).ratio == pytest.approx(1 + 30 * 40 / 12, rel=1e-12)
    assert solve_speeds(model).ratio == pytest.approx(1 + 36 * 40 / 12, rel=1e-12)
    assert copy != model and dataclasses.replace(model) == model


# --- given speeds that contradict each other: the links whose rows conflict ---------------
def contradiction(model, **kwargs) -> str:
    with pytest.raises(KinematicsError, match="the given speeds contradict each other") as err:
        solve_speeds(model, **kwargs)
    return str(err.value)


def test_contradictory_speeds_name_the_ring_meshes_left_without_carrier() -> None:
    """models/planetary_2kh_sun_to_carrier.yaml with both `carrier:` keys deleted: both
    meshes become fixed-axis pairs. Ring held: links[1] (planet 24 in ring 72) gives
    w_p = (72/24)·w_ring = 0; links[0] (sun 24, planet 24) gives w_sun = -w_p = 0. The
    port gives the sun 1000 rpm = 104.72 rad/s. Both rows are needed (either alone holds)."""
    doc = yaml.safe_load((MODELS / "planetary_2kh_sun_to_carrier.yaml").read_text())
    for link in doc["links"][:2]:
        del link["carrier"]
    message = contradiction(model_from_dict(doc))
    assert ("links[0] (mesh sun-planet, fixed axes) and links[1] (mesh planet-ring, fixed "
            "axes) together require w_sun = 0 rad/s, but ports[0] gives w_sun = 104.72 "
            "rad/s") in message
    # the model's warning on links[1] comes along (the CLI shows no warning on an error)
    assert "— warning: links[1]: mesh planet-ring has no carrier" in message
    assert "write carrier: carrier, here and on links[0]" in message


def test_a_contradiction_names_only_the_links_involved() -> None:
    """tests/data/unsolvable.yaml's case: x (10 teeth) meshes a (20) on fixed axes, so
    w_x = -(20/10)·w_a = -2·3 = -6 rad/s, not the given 10; links[0] (a-b on carrier c)
    takes no part."""
    model = loads_model("""
name: differential with dependent speeds
components: {0: {role: frame}, a: {teeth: 20}, b: {teeth: 20}, x: {teeth: 10}, c: {}}
links:
  - {type: mesh, between: [a, b], carrier: c}
  - {type: mesh, between: [x, a]}
ports: [{component: x, role: input, speed: 10}, {component: a, role: input, speed: 3},
        {component: c, role: output}]
""")
    message = contradiction(model)
    assert message == ("the given speeds contradict each other: links[1] (mesh x-a, fixed "
                       "axes) requires w_x = -2·w_a (= -6 rad/s), but ports[0] gives w_x = "
                       "10 rad/s and ports[1] gives w_a = 3 rad/s")


def test_a_contradiction_through_a_planetary_set_and_a_separate_pair() -> None:
    """Sun 24, planet 24, ring 72 held, carrier c: w_s = (1 + 72/24)·w_c = 4·w_c = 12
    rad/s for w_c = 3, not the given 10. The pair u-v beside it (its own DOF) is not named."""
    model = loads_model("""
name: 2K-H beside a pair
components: {0: {role: frame}, s: {teeth: 24}, p: {teeth: 24, count: 3},
             r: {teeth: 72, internal: true}, c: {}, u: {teeth: 20}, v: {teeth: 30}}
links:
  - {type: mesh, between: [u, v]}
  - {type: mesh, between: [s, p], carrier: c}
  - {type: mesh, between: [p, r], carrier: c}
  - {type: fixed, between: [r, 0]}
ports: [{component: s, role: input, speed: 10}, {component: c, role: output, speed: 3},
        {component: v, role: output}]
""")
    message = contradiction(model)
    assert "links[0]" not in message
    assert message.endswith(
        "links[1] (mesh s-p, carrier c) and links[2] (mesh p-r, carrier c) together require "
        "w_s = 4·w_c (= 12 rad/s), but ports[0] gives w_s = 10 rad/s and ports[1] gives "
        "w_c = 3 rad/s")


def test_a_contradiction_across_fourteen_decades_names_every_stage() -> None:
    """20 compound stages 20 -> 100 teeth: w_out = (-1/5)^20 w_in = 1.048576e-14 w_in.
    Given w_in = 1 and w_out = 1 (and a free body for the second DOF), every one of the
    20 meshes is needed: the smallest rows are not taken for round-off."""
    n = 20
    comps = {0: {"role": "frame"}, "free": {}}
    links = []
    for k in range(n):
        comps[f"a{k}"], comps[f"b{k}"] = {"teeth": 20}, {"teeth": 100}
        links.append({"type": "mesh", "between": [f"a{k}", f"b{k}"]})
        if k:
            links.append({"type": "fixed", "between": [f"b{k - 1}", f"a{k}"]})
    model = model_from_dict({"name": "20 stages", "components": comps, "links": links,
                             "ports": [{"component": "a0", "role": "input", "speed": 1},
                                       {"component": f"b{n - 1}", "role": "output",
                                        "speed": 1},
                                       {"component": "free", "role": "output"}]})
    message = contradiction(model)
    assert "… (20 links in all) together require w_a0 = 9.53674e+13·w_b19" in message


def test_a_contradiction_in_a_long_chain_is_diagnosed_on_the_sparse_path() -> None:
    """2000 fixed-axis gears (teeth 20 + i % 7): w_1/w_2000 = (-1)^1999 z_2000/z_1 =
    -25/21; with both ends given (and a free body) every mesh is named, in bounded time
    (one more sparse factorisation, no dense least squares)."""
    n = 2000
    text = gear_chain_text(n, input_port="speed: 10").replace(
        "components:\n", "components:\n  free: {}\n").replace(
        f"{{component: {n}, role: output}}", f"{{component: {n}, role: output, speed: 3}}")
    message = contradiction(loads_model(text + "  - {component: free, role: output}\n"))
    assert message.startswith("the given speeds contradict each other: links[0] (mesh 1-2, "
                              "fixed axes), links[1] (mesh 2-3, fixed axes)")
    assert (f"… (1999 links in all) together require w_1 = {-25 / 21:.6g}·w_2000 "
            f"(= {-25 / 21 * 3:.6g} rad/s), but ports[0] gives w_1 = 10 rad/s") in message


def test_slips_that_two_parallel_meshes_cannot_take() -> None:
    """Two 20/40 meshes between gears 1 and 2: with w_1 given, a slip on one of them
    (w_1 + 2 w_2 = 1) contradicts the other (w_1 + 2 w_2 = 0); no port takes part."""
    model = loads_model("""
name: pair twice
components: {0: {role: frame}, 1: {teeth: 20}, 2: {teeth: 40}}
links: [{type: mesh, between: [1, 2]}, {type: mesh, between: [1, 2]}]
ports: [{component: 1, role: input}, {component: 2, role: output}]
""")
    assert contradiction(model, speeds={"1": 1.0}, slips={0: 1.0}).endswith(
        "links[0] (mesh 1-2, fixed axes) and links[1] (mesh 1-2, fixed axes) together "
        "cannot take the slips given (links[0] 1 rad/s)")


def test_conflict_without_regular_matched_rows_is_cut_to_an_irreducible_set() -> None:
    """Rows u - v = 0 (twice), u = 2, v = 3, matched (singularly) to the first two: the
    dense fallback keeps one copy of u - v = 0 with u = 2 and v = 3 — drop any of the three
    and the rest hold."""
    from powergraph.kinematics.system import conflict
    from powergraph.linalg import Triplets

    t = Triplets.build([0, 0, 1, 1, 2, 3], [0, 1, 0, 1, 0, 1],
                       [1.0, -1.0, 1.0, -1.0, 1.0, 1.0], (4, 2))
    square = (np.array([0, 1]), np.array([0, 1]), t.part(np.array([0, 1]), np.array([0, 1])))
    y = conflict(t, np.array([0.0, 0.0, 2.0, 3.0]), square)
    assert np.count_nonzero(y[:2]) == 1 and np.all(y[2:] != 0)
    assert np.allclose(y @ t.dense(), 0.0) and y @ np.array([0.0, 0.0, 2.0, 3.0]) != 0
