"""Locking verdicts, by hand derivation (docs/locking.md): a K-H-V stage of N = 39 lobes
at η0 = 0.94, back-driven behind a forward pair, with the load given at its crank.

Notation: disc d (gear a, z = N), pins (gear b, z = N + 1, fixed), crank H the carrier.
Willis: i = (w_d - w_H)/(w_pins - w_H) = (N + 1)/N, so w_H = -N w_d and, in the crank's
frame, the disc turns at w_d - w_H = (N + 1) w_d. The element applies λ to d and
(i f - 1) λ to H. The crank's load takes P out: T_H = -P/w_H. Balance of H:
T_H + (i f - 1) λ = 0, so the power d feeds in the crank's frame is
P_d = -λ (w_d - w_H) = -P (N + 1)/(N - (N + 1) f).
- d drives (f = η0) needs P_d >= 0: N - (N + 1) η0 = 39 - 37.6 = 1.4 > 0 gives
  P_d = -P·40/1.4 < 0. Contradiction.
- pins drive (f = 1/η0) needs P_d <= 0: N - (N + 1)/η0 = -3.553 gives P_d = +P·40/3.553 > 0.
  Contradiction.
No pattern is consistent: the train is LOCKED, and the pair in front cannot change that
(the crank's balance alone decides). With η0 > N/(N + 1) = 0.975, d drives consistently.
"""
from __future__ import annotations

import re

import numpy as np
import pytest

import powergraph as pg
from powergraph.kinematics import elements_of, solve_speeds
from powergraph.model import model_from_dict
from powergraph.statics.directions import force_scales, relative_speeds
from powergraph.statics.equilibrium import loads_of, solve_equilibrium
from powergraph.statics.locking import decide
from powergraph.statics.report import text_report
from powergraph.testing import assert_conservation, consistent_patterns

N, P, W_IN = 39, 50.0, 100.0


def khv_behind_pair(eta0: float, load_on_output: bool = True, pair_eta: float = 0.98):
    ports = [{"component": "g1", "role": "input", "speed": W_IN},
             {"component": "H", "role": "output", "power": P}]
    if not load_on_output:
        ports = [{"component": "g1", "role": "input", "speed": W_IN, "power": P},
                 {"component": "H", "role": "output"}]
    return model_from_dict({
        "name": "pair, then K-H-V back-driven",
        "components": {0: {"role": "frame"}, "g1": {"teeth": 20}, "g2": {"teeth": 40},
                       "d": {"teeth": N}, "pins": {"teeth": N + 1, "internal": True},
                       "H": {}},
        "links": [{"type": "mesh", "between": ["g1", "g2"], "efficiency": pair_eta},
                  {"type": "fixed", "between": ["g2", "d"]},
                  {"type": "mesh", "between": ["d", "pins"], "carrier": "H",
                   "efficiency": eta0},
                  {"type": "fixed", "between": ["pins", 0]}],
        "ports": ports})


def solve(model):
    result = pg.solve(model)
    assert_conservation(result)
    return result


def test_khv_back_driven_with_its_load_given_locks_and_names_the_stage() -> None:
    result = solve(khv_behind_pair(0.94))
    assert result.lock is not None and result.self_locking
    assert result.lock.meshes == (2,)                      # the K-H-V mesh, not the pair
    assert result.efficiency == 0.0 and result.input_power == 0.0
    assert all(w == 0.0 for w in result.speeds.values())  # at rest
    assert result.ratio == pytest.approx(2 / N, rel=1e-12)  # the motion asked: 20->40, -39
    # the contradiction, with the hand-derived powers of the asked motion
    with_d, with_pins = (float(x) for x in re.findall(r"\(([-+0-9.e]+) W\)", result.lock.reason))
    assert with_d == pytest.approx(-P * (N + 1) / (N - (N + 1) * 0.94), rel=1e-3)
    assert with_pins == pytest.approx(-P * (N + 1) / (N - (N + 1) / 0.94), rel=1e-3)
    assert consistent_patterns(result.model) == []         # the brute force agrees


def test_locked_train_holds_the_load_with_the_lossless_torques() -> None:
    """At rest every mesh sticks (factor in [η, 1/η]); the reported holding torques are
    the lossless ones: T_g1 w_g1 + T_H w_H = 0 with T_H = -P/w_H, so T_g1 = P/w_g1."""
    result = solve(khv_behind_pair(0.94))
    assert result.torques["H"] == pytest.approx(-P / (-N * -W_IN / 2), rel=1e-12)
    assert result.torques["g1"] == pytest.approx(P / W_IN, rel=1e-12)
    assert all(e.factor == 1.0 and e.driver is None for e in result.elements)
    data = result.to_dict()
    assert data["self_locking"] is True and data["efficiency"] == 0.0
    assert data["lock"]["locked"] is True and data["lock"]["meshes"] == [2]
    assert data["lock"]["asked_speeds"]["H"] == pytest.approx(N * W_IN / 2, rel=1e-12)
    assert data["directions"]["solutions"] == 0
    text = text_report(result)
    assert "LOCKED" in text and "links[2]" in text and "docs/locking.md" in text


def test_above_n_over_n_plus_one_the_same_train_back_drives() -> None:
    """η0 = 0.98 > 39/40: d drives; back-driven efficiency (N + 1) η0 - N = 0.2, times the
    pair's 0.98 (the load given at the crank does not change the efficiency)."""
    result = solve(khv_behind_pair(0.98))
    assert result.lock is None and not result.self_locking
    assert result.efficiency == pytest.approx(0.98 * ((N + 1) * 0.98 - N), rel=1e-9)
    assert result.element(2).driver == "d"


def test_with_the_input_power_given_the_formal_efficiency_is_reported() -> None:
    """Power given at the input: the disc drives consistently (P_d = (N + 1) P_disc > 0)
    and the formal efficiency η_pair ((N + 1) η0 - N) = 0.98 × (-1.4) < 0 is kept: the
    crank must be driven too. Self-locking, not locked."""
    result = solve(khv_behind_pair(0.94, load_on_output=False))
    assert result.lock is None and result.self_locking
    assert result.formal_efficiency == pytest.approx(0.98 * ((N + 1) * 0.94 - N), rel=1e-9)
    assert result.efficiency == 0.0     # from the flows: every port takes power in


def test_two_consistent_patterns_the_least_loss_one_is_chosen() -> None:
    """A forward K-H-V (crank in, power given) has two consistent patterns when
    η0 < N/(N + 1): pins drive (efficiency η0/(N + 1 - N η0) = 0.2874) or disc drives
    (1/((N + 1) η0 - N) = -0.714, the output pushing too). The search keeps the one of
    least loss, the first."""
    model = model_from_dict({
        "name": "K-H-V", "components": {0: {"role": "frame"}, "H": {}, "d": {"teeth": N},
                                        "pins": {"teeth": N + 1, "internal": True}},
        "links": [{"type": "mesh", "between": ["d", "pins"], "carrier": "H",
                   "efficiency": 0.94}, {"type": "fixed", "between": ["pins", 0]}],
        "ports": [{"component": "H", "role": "input", "speed": 10.0, "power": P},
                  {"component": "d", "role": "output"}]})
    kin = solve_speeds(model)
    elements, loads = elements_of(model), loads_of(model, kin)
    rel = relative_speeds(elements, kin)

    def forces(factors):
        eq = solve_equilibrium(model, elements, loads, factors)
        return eq.forces, force_scales(elements, eq.forces, factors, eq.external, "0")

    decision = decide(model, elements, loads, rel, forces, [])
    assert decision.solutions == 2 and decision.complete
    assert decision.chosen.pattern == (-1,)
    assert decision.chosen.loss == pytest.approx(P * (1 - 0.94 / (N + 1 - N * 0.94)),
                                                 rel=1e-9)
    result = solve(model)  # the fast path reaches the same one from the ideal start
    assert result.efficiency == pytest.approx(0.94 / (N + 1 - N * 0.94), rel=1e-12)
    assert len(consistent_patterns(model)) == 2


@pytest.mark.parametrize("seed, solutions, searched", [
    ("0-419", 2, True), ("0-1436", 2, True), ("0-2904", 1, False)])
def test_random_trains_with_several_patterns_the_brute_force_agrees_with(
        seed: str, solutions: int, searched: bool) -> None:
    """Random 2-DOF trains (found by benchmarks/random_trains.py): two with two consistent
    patterns, where the fixed-point iteration cycles and the search must decide, and one
    with a single pattern, which the iteration reaches. Either way the reported drivers are
    those of the least-loss pattern of the independent brute force."""
    from powergraph.testing_trains import random_train

    result = solve(random_train(seed).model)
    assert_conservation(result)
    assert len(consistent_patterns(result.model)) == solutions
    if searched:
        assert result.search is not None and result.search.solutions == solutions
    best = min(consistent_patterns(result.model), key=lambda p: _loss_of(result.model, p))
    drivers = {e.link: 1 if e.driver == e.a else -1 for e in result.elements
               if e.driver is not None and e.efficiency < 1}
    assert all(best.get(k, c) == c for k, c in drivers.items())


def _loss_of(model, pattern: dict[int, int]) -> float:
    """Total loss of a pattern, from the plain torque balance (independent of the search)."""
    kin = solve_speeds(model)
    elements, loads = elements_of(model), loads_of(model, kin)
    factors = np.ones(len(elements))
    for k, e in enumerate(elements):
        if e.link in pattern:
            factors[k] = e.efficiency if pattern[e.link] > 0 else 1 / e.efficiency
    forces = solve_equilibrium(model, elements, loads, factors).forces
    rel = np.array([kin.body_speeds[e.body_a] - kin.body_speeds[e.body_c] for e in elements])
    return float(np.sum(-forces * rel * (1 - factors)))


def test_solve_command_prints_the_verdict_and_exits_0(tmp_path, capsys) -> None:
    """A locked train is an answer, not an error: exit 0, LOCKED in the text, the lock in
    the JSON."""
    import json

    import yaml

    from powergraph.cli.main import main

    path = tmp_path / "locked.yaml"
    path.write_text(yaml.safe_dump({
        "name": "K-H-V back-driven, load on the crank",
        "components": {0: {"role": "frame"}, "H": {}, "d": {"teeth": N},
                       "pins": {"teeth": N + 1, "internal": True}},
        "links": [{"type": "mesh", "between": ["d", "pins"], "carrier": "H",
                   "efficiency": 0.94}, {"type": "fixed", "between": ["pins", 0]}],
        "ports": [{"component": "d", "role": "input", "speed": 1.0},
                  {"component": "H", "role": "output", "power": 10.0}]}))
    assert main(["solve", str(path)]) == 0
    assert "LOCKED" in capsys.readouterr().out
    assert main(["solve", str(path), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["lock"]["meshes"] == [0] and data["efficiency"] == 0.0


def _decide(model, speeds=None):
    kin = solve_speeds(model, speeds)
    elements, loads = elements_of(model), loads_of(model, kin)
    rel = relative_speeds(elements, kin)

    def forces(factors):
        eq = solve_equilibrium(model, elements, loads, factors)
        return eq.forces, force_scales(elements, eq.forces, factors, eq.external,
                                       model.frame_body)

    return decide(model, elements, loads, rel, forces, [])


def test_branch_and_bound_agrees_with_the_exhaustive_search(monkeypatch) -> None:
    """The linear-programming search (used beyond 12 lossy meshes) gives the same verdicts:
    the hand-derived lock, and the least-loss pattern of a train with two solutions."""
    from powergraph.statics import locking
    from powergraph.testing_trains import random_train

    cases = [khv_behind_pair(0.94), random_train("0-419").model,
             random_train("0-1436").model]
    exhaustive = [_decide(m) for m in cases]
    monkeypatch.setattr(locking, "EXHAUSTIVE_LIMIT", -1)
    searched = [_decide(m) for m in cases]
    assert [d.method for d in exhaustive] == ["exhaustive"] * 3
    assert [d.method for d in searched] == ["branch and bound"] * 3
    assert searched[0].chosen is None and searched[0].locking == exhaustive[0].locking == (1,)
    for ex, bb in zip(exhaustive[1:], searched[1:]):
        assert ex.solutions == 2 and bb.solutions >= 1
        assert bb.chosen.pattern == ex.chosen.pattern
        assert bb.chosen.loss == pytest.approx(ex.chosen.loss, rel=1e-9)


def test_a_sticking_mesh_takes_a_factor_inside_its_interval() -> None:
    """Bevel differential running straight (case, left and right all at 50 rad/s): the
    spider gears do not turn in the case, both meshes stick. The search treats their
    factors as free in [η, 1/η]: a solution exists, with no loss."""
    from powergraph.statics.search import branch_and_bound, statics_of

    model = pg.load_model("models/bevel_differential.yaml")
    kin = solve_speeds(model, {"case": 50.0, "L": 50.0})
    elements, loads = elements_of(model), loads_of(model, kin)
    rel = relative_speeds(elements, kin)
    assert list(rel) == [0.0, 0.0]
    st = statics_of(model, elements, loads, rel)
    assert st.sticking == (0, 1) and st.lossy == ()
    found, complete = branch_and_bound(st)
    assert complete and found and found[0].loss == pytest.approx(0.0, abs=1e-12)
    for k, f in found[0].factors.items():
        assert 0.97 <= f <= 1 / 0.97
    result = pg.solve(model, speeds={"case": 50.0, "L": 50.0})
    assert_conservation(result)
    assert result.torques["L"] == pytest.approx(result.torques["R"], rel=1e-12)  # f = 1
