"""Properties of random valid trains from the stage templates (powergraph.testing_trains),
checked with hypothesis: every train gets an answer that conserves power (or a consistent
locking verdict); ratios equal the product of the stages' closed forms; renaming and
shuffling ids changes nothing; a constant-η train scales linearly in power."""
from __future__ import annotations

import pytest

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

import powergraph as pg  # noqa: E402
from powergraph.model import model_from_dict  # noqa: E402
from powergraph.testing import assert_conservation  # noqa: E402
from powergraph.testing_trains import random_train, renamed, train_strategy  # noqa: E402

SETTINGS = settings(max_examples=25, deadline=None, derandomize=True,
                    suppress_health_check=[HealthCheck.too_slow])


def asked(result):
    """The kinematics of the motion asked (a locked result is at rest)."""
    return result.lock.asked if result.lock is not None else result.kinematics


@SETTINGS
@given(train_strategy())
def test_every_train_conserves_power_or_locks_consistently(train) -> None:
    result = pg.solve(train.model)
    assert_conservation(result)
    if result.lock is not None:
        assert result.efficiency == 0.0 and result.self_locking and result.lock.reasons


@SETTINGS
@given(train_strategy())
def test_ratio_and_speeds_equal_the_stages_closed_forms(train) -> None:
    kin = asked(pg.solve(train.model))
    if train.ratio is not None:
        assert kin.ratio == pytest.approx(train.ratio, rel=1e-9)
    for component, w in train.speeds.items():
        assert kin.speed(component) == pytest.approx(w, rel=1e-9, abs=1e-9)


@SETTINGS
@given(train_strategy(), st.integers(0, 1000))
def test_renaming_and_shuffling_ids_changes_nothing(train, shuffle) -> None:
    result = pg.solve(train.model)
    data, new = renamed(train.data, shuffle)
    model = model_from_dict(data)
    if train.backdriven:
        from powergraph.kinematics import backdriven

        model = backdriven(model)
    other = pg.solve(model)
    assert_conservation(other)
    assert (other.lock is None) == (result.lock is None)
    assert other.efficiency == pytest.approx(result.efficiency, rel=1e-9, abs=1e-12)
    assert other.input_power == pytest.approx(result.input_power, rel=1e-9, abs=1e-9)
    for cid, torque in result.torques.items():
        assert other.torques[new[cid]] == pytest.approx(torque, rel=1e-7, abs=1e-9)
    for e in result.meshes:
        twin = next(m for m in other.meshes
                    if {m.a, m.b} == {new[e.a], new[e.b]} and m.carrier == new[e.carrier])
        assert twin.loss == pytest.approx(e.loss, rel=1e-7, abs=1e-9)


@SETTINGS
@given(st.integers(0, 2**32 - 1), st.floats(0.9, 1.0), st.floats(1e-3, 1e3))
def test_constant_eta_train_scales_linearly_in_power(seed, eta, factor) -> None:
    train = random_train(seed, eta=(eta, eta), drive="forward", dof=1)
    base = pg.solve(train.model)
    scaled_ports = [dict(p, power=p["power"] * factor) if "power" in p else p
                    for p in train.data["ports"]]
    scaled = pg.solve(model_from_dict(dict(train.data, ports=scaled_ports)))
    assert_conservation(scaled)
    assert scaled.efficiency == pytest.approx(base.efficiency, rel=1e-9, abs=1e-12)
    assert scaled.total_loss == pytest.approx(base.total_loss * factor, rel=1e-9, abs=1e-12)
    for cid, torque in base.torques.items():
        assert scaled.torques[cid] == pytest.approx(torque * factor, rel=1e-9, abs=1e-12)


#: Ids that spell the flow graph's own nodes, a body's joined name, or use "/", spaces,
#: "-", "#" and other scripts; digits so that joined names ("3/7") can meet other ids.
TRICKY_IDS = ("motor", "generator", "loss", "ground", "mesh 1-2", "coupling a-b", "drag x",
              "bearing y", "motor 1", "generator 2", "F/R", "F", "R", "a b", "loss/motor",
              "mesh loss-motor", "2/3", "1/2 #2", "歯車", "太阳轮", "１２", "🚀", "x-", "-",
              " ", "#2", "ground/ground") + tuple(str(n) for n in range(200))


def tricky_renaming(data: dict, order: list[int]) -> tuple[dict, dict[str, str]]:
    """``data`` with every component id replaced by one of :data:`TRICKY_IDS` (in the
    given order), links and ports rewritten; file order kept, so link indices too."""
    ids = list(data["components"])
    new = {c: TRICKY_IDS[k] for c, k in zip(ids, order)}
    links = [dict(link, between=[new[b] for b in link["between"]],
                  **({"carrier": new[link["carrier"]]} if "carrier" in link else {}))
             for link in data["links"]]
    ports = [dict(port, component=new[port["component"]]) for port in data["ports"]]
    return dict(data, components={new[c]: v for c, v in data["components"].items()},
                links=links, ports=ports), new


def canonical(result, old_of: dict[str, str]) -> dict:
    """Node of ``result`` -> a key that does not depend on the ids: bodies by their
    members' original ids, elements and bearings by link, ports by role and component."""
    from powergraph.statics.flow import (GROUND, LOSS, Node, body_node, element_nodes,
                                         port_node)

    model = result.model
    keys = {Node(LOSS, LOSS): LOSS, Node(GROUND, GROUND): GROUND}
    keys.update({body_node(result, b.id): ("body", tuple(old_of[m] for m in b.members))
                 for b in model.bodies})
    keys.update({node: ("element", link) for link, node in element_nodes(result).items()})
    keys.update({Node(b.kind, b.node): (b.kind, b.link, old_of[b.between[0]])
                 for b in result.bearings})
    keys.update({port_node(result, p.component, p.role): (p.role, old_of[p.component])
                 for p in model.ports})
    return keys


def canonical_splits(result, old_of: dict[str, str], frame=None) -> dict:
    key = canonical(result, old_of)
    return {key[n]: {key[t]: p for t, p in to.items()}
            for n, to in result.split_powers(frame).items()}


@SETTINGS
@given(train_strategy(), st.randoms(use_true_random=False))
def test_ids_that_spell_the_tools_own_names_change_nothing(train, rng) -> None:
    """Renaming every component to a reserved word ("motor", "loss", "mesh 1-2"...), a
    name with "/" (a body's joined name), spaces or other scripts gives the same answer:
    efficiency, total loss, each mesh's virtual power and loss, circulating power and
    split powers (nodes matched through the renaming)."""
    from powergraph.kinematics import backdriven

    order = rng.sample(range(len(TRICKY_IDS)), len(train.data["components"]))
    data, new = tricky_renaming(train.data, order)
    model = model_from_dict(data)
    model = backdriven(model) if train.backdriven else model
    result, other = pg.solve(train.model), pg.solve(model)
    assert_conservation(other)
    assert (other.lock is None) == (result.lock is None)
    assert other.efficiency == pytest.approx(result.efficiency, rel=1e-9, abs=1e-12)
    assert other.total_loss == pytest.approx(result.total_loss, rel=1e-9, abs=1e-9)
    for e, twin in zip(result.meshes, other.meshes):
        assert (twin.link, twin.a, twin.b) == (e.link, new[e.a], new[e.b])
        assert twin.loss == pytest.approx(e.loss, rel=1e-9, abs=1e-9)
        assert twin.carrier_frame_power == pytest.approx(e.carrier_frame_power, rel=1e-9,
                                                         abs=1e-9)
    assert other.circulating_power == pytest.approx(result.circulating_power, rel=1e-9,
                                                    abs=1e-9)
    old_of = {v: k for k, v in new.items()}
    same = {c: c for c in train.data["components"]}
    frames = [None] + [e.carrier for e in result.meshes[:1]]
    for frame in frames:
        mine = canonical_splits(result, same, frame)
        theirs = canonical_splits(other, old_of, None if frame is None else new[frame])
        assert theirs.keys() == mine.keys()
        for node, targets in mine.items():
            assert theirs[node] == pytest.approx(targets, rel=1e-9, abs=1e-9)
