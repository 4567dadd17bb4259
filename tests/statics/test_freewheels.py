"""Issue 34, freewheels in bounded time (powergraph.statics.freewheels, docs/modes.md).

Parallel freewheels are one element: the Simpson 3-speed with 16 more freewheels beside F1
answers as the plain Simpson (ratio 7/3, the closed form of models/simpson_3speed.yaml)
with one solve. The pruned search keeps what the exhaustive one keeps: compared with a
plain brute force written here (every combination solved, the consistency rules of
docs/modes.md) on random variants of the bundled trains. More freewheel groups than the
limit are refused.
"""
from __future__ import annotations

import copy
import dataclasses
import itertools
import random
from pathlib import Path

import pytest
import yaml

import powergraph as pg
from powergraph.cli.main import main
from powergraph.errors import ModelError
from powergraph.kinematics.speeds import degrees_of_freedom
from powergraph.kinematics.variants import backdriven
from powergraph.model import loads_model, model_from_dict
from powergraph.model.modes import resolve
from powergraph.statics.modes import MAX_FREEWHEELS, solve_mode
from powergraph.statics.shift_torques import joint_torque
from powergraph.testing import assert_conservation

MODELS = Path(__file__).resolve().parents[2] / "models"
SIMPSON = MODELS / "simpson_3speed.yaml"
K = 72 / 24                         # both Simpson sets: z_r / z_s
FIRST = 1 + (1 + K) / K             # Simpson 1st gear (C1, F1): 7/3


def counting(limit: int = 10_000):
    """The solver, counting its calls (and refusing more than ``limit``: a search that
    tries every combination fails fast instead of running for minutes)."""
    calls = []

    def solve(model):
        calls.append(model.name)
        if len(calls) > limit:
            raise AssertionError(f"more than {limit} solves")
        return pg.solve(model)

    return solve, calls


def simpson_with(lines: list[str]) -> str:
    """models/simpson_3speed.yaml's text with more links (YAML flow mappings)."""
    text = SIMPSON.read_text()
    extra = "".join(f"  - {line}\n" for line in lines)
    assert "\nmodes:\n" in text
    return text.replace("\nmodes:\n", "\n" + extra + "modes:\n")


def train_balance(result) -> float:
    """Minus the external torques on input and output: what the frame must take (the
    train's torque balance), i.e. what the freewheels holding c2 apply to c2."""
    return -(result.torques["in"] + result.torques["c1"])


def test_issue34_sixteen_parallel_freewheels_answer_as_one_with_one_solve() -> None:
    text = simpson_with([f"{{type: freewheel, name: F{k}, between: [c2, 0], holds: positive}}"
                         for k in range(2, 18)])
    model = loads_model(text)
    solve, calls = counting(limit=4)
    result = solve_mode(model, "1", solve)
    assert_conservation(result.result)
    assert len(calls) == 1                      # one group, decided once (2**17 solves before)
    assert result.verdict == "ok"
    assert result.result.ratio == pytest.approx(FIRST, rel=1e-12)
    names = [f"F{k}" for k in range(1, 18)]
    assert dict(result.freewheels) == {n: "holding" for n in names}
    total = train_balance(result.result)
    assert total > 0                            # c2 is held against turning backward
    for name in names:
        element = result.element(name)
        assert element.torque is None           # each one's share is indeterminate
        assert element.parallel == tuple(names)
        assert element.parallel_torque == pytest.approx(total, rel=1e-9)
    (caveat,) = [w for w in result.warnings if w.code == "indeterminate"]
    assert str(caveat).startswith("modes.1: F1, F2, F3, F4, F5, F6, F7, F8, F9, F10, F11, "
                                  "F12, F13, F14, F15, F16, F17 hold together in parallel: "
                                  "the torque each carries is statically indeterminate "
                                  "(together ")
    plain = solve_mode(loads_model(SIMPSON.read_text()), "1")
    assert result.result.efficiency == pytest.approx(plain.result.efficiency, rel=1e-12)


def test_issue34_sixteen_parallel_freewheels_from_the_command_line(tmp_path, capsys) -> None:
    path = tmp_path / "simpson16.yaml"
    path.write_text(simpson_with([
        f"{{type: freewheel, name: F{k}, between: [c2, 0], holds: positive}}"
        for k in range(2, 18)]))
    assert main(["solve", str(path), "--mode", "1"]) == 0
    out = capsys.readouterr().out
    assert "mode 1: engages C1 — ok" in out and "hold together in parallel" in out


def test_issue34_a_freewheel_written_reversed_is_in_parallel_with_f1() -> None:
    """F2 [0, c2] holds negative: w_0 - w_c2 <= 0, i.e. w_c2 - w_0 >= 0 -- F1's sense.
    Together they hold c2 with the train's balance, each seeing it on its own first
    member: F1 on c2 (+), F2 on the housing (-)."""
    result = solve_mode(loads_model(simpson_with(
        ["{type: freewheel, name: F2, between: [0, c2], holds: negative}"])), "1")
    assert_conservation(result.result)
    assert result.freewheels == {"F1": "holding", "F2": "holding"}
    total = train_balance(result.result)
    assert result.element("F1").parallel_torque == pytest.approx(total, rel=1e-9)
    assert result.element("F2").parallel_torque == pytest.approx(-total, rel=1e-9)
    assert result.result.ratio == pytest.approx(FIRST, rel=1e-12)


def coasting_of(model, mode):
    """The mode back-driven (the output drives at the forward input's power)."""
    forward = solve_mode(model, mode)
    return solve_mode(_with_ports(model, backdriven(forward.result.model).ports), mode)


def _with_ports(model, ports):
    return dataclasses.replace(model, ports=ports)


def test_issue34_opposite_freewheels_on_one_pair_act_as_a_two_way_lock() -> None:
    """F2 beside F1 holds the other sense. Driving in 1st, c2 needs a torque >= 0 (the
    train's balance): F1 holds it alone (a determinate torque), F2 overruns at zero slip.
    Coasting, c2 needs the opposite: F2 holds it, F1 overruns -- the pair gives engine
    braking, as B2 does: the same numbers as the mode [C1, B2] coasting."""
    text = simpson_with(["{type: freewheel, name: F2, between: [c2, 0], holds: negative}"])
    model = loads_model(text.replace('  "1": [C1]\n', '  "1": [C1]\n  "1B2": [C1, B2]\n'))
    drive = solve_mode(model, "1")
    assert_conservation(drive.result)
    assert drive.freewheels == {"F1": "holding", "F2": "overrunning"}
    assert drive.element("F1").torque == pytest.approx(train_balance(drive.result), rel=1e-9)
    assert drive.element("F1").torque > 0 and drive.element("F2").slip_speed == 0.0
    coast = coasting_of(model, "1")
    assert_conservation(coast.result)
    assert coast.verdict == "ok"
    assert coast.freewheels == {"F1": "overrunning", "F2": "holding"}
    braked = coasting_of(model, "1B2")
    assert coast.element("F2").torque == pytest.approx(braked.element("B2").torque, rel=1e-9)
    assert coast.element("F2").torque < 0
    assert coast.result.efficiency == pytest.approx(braked.result.efficiency, rel=1e-12)


# --- the pruned search against brute force --------------------------------------------

def brute_force(model, mode) -> list[tuple[dict, object]]:
    """Every combination of freewheel states solved, in itertools.product order, kept
    when (docs/modes.md) the train has its designed DOF, every holding freewheel carries
    a torque of the sign it holds (or an indeterminate one), every overrunning one slips
    with the sign it allows; torques and slips below 1e-9 of the largest are zero."""
    base = resolve(model, mode)
    free = [e for e in model.shift_elements if e.kind == "freewheel"
            and base.body_of[e.between[0]] != base.body_of[e.between[1]]]
    need = max(1, sum(p.speed is not None for p in model.ports))
    kept = []
    for states in itertools.product((False, True), repeat=len(free)):
        choice = {e.name: on for e, on in zip(free, states)}
        try:
            derived = resolve(model, mode, choice)
        except ModelError:
            continue
        if degrees_of_freedom(derived) != need:
            continue
        try:
            result = pg.solve(derived)
        except ModelError:          # e.g. loads this state leaves undetermined
            continue
        torque_scale = max(abs(t) for t in result.external_torques.values())
        speed_scale = max(abs(w) for w in result.kinematics.body_speeds.values())
        ok = True
        for e in free:
            sign = 1.0 if e.holds == "positive" else -1.0
            if choice[e.name]:
                t = joint_torque(result, e.index)
                ok &= t is None or abs(t) <= 1e-9 * torque_scale or sign * t >= 0
            else:
                speed = result.kinematics.speed
                w = speed(e.between[0]) - speed(e.between[1])
                ok &= abs(w) <= 1e-9 * speed_scale or sign * w >= 0
        if ok:
            kept.append((choice, result))
    return kept


MEMBERS = ["in", "s", "r1", "c1", "c2", "0"]
SIMPSON_DATA = yaml.safe_load(SIMPSON.read_text())


def random_simpson(rng: random.Random):
    """The Simpson 3-speed with 1-3 more freewheels between random coaxial members, each
    pair of bodies joined by at most one freewheel in every mode (so that brute force
    over single freewheels is the reference), the input power of either sign."""
    data = copy.deepcopy(SIMPSON_DATA)
    # first a mode engaging nothing: the state as loaded (the first mode, every freewheel
    # holding) must not join the ports to each other or to the frame
    data["modes"] = {"nothing": [], **data["modes"], "C2 only": ["C2"]}
    pairs = [p for p in itertools.combinations(MEMBERS, 2) if p != ("c2", "0")]
    for k, pair in enumerate(rng.sample(pairs, rng.randint(1, 3))):
        if rng.random() < 0.5:
            pair = pair[::-1]
        data["links"].append({"type": "freewheel", "name": f"G{k}",
                              "between": [int(c) if c == "0" else c for c in pair],
                              "holds": rng.choice(["positive", "negative"])})
    if rng.random() < 0.5:
        data["ports"][0]["power"] = "-20 kW"
    try:
        return model_from_dict(data)
    except ModelError:      # every freewheel holding joins a port to the frame or to the
        return None         # other port: refused at load


def single_pairs(model, mode) -> bool:
    base = resolve(model, mode)
    pairs = [frozenset(base.body_of[c] for c in e.between) for e in model.shift_elements
             if e.kind == "freewheel"]
    pairs = [p for p in pairs if len(p) == 2]
    return len(pairs) == len(set(pairs))


@pytest.mark.slow      # ~3 s: 40 trains, each solved in every combination
def test_issue34_pruned_search_equals_brute_force_on_random_simpson_variants() -> None:
    rng = random.Random(34)
    compared = consistent = several = 0
    fewer_solves = 0
    while compared < 40:
        model = random_simpson(rng)
        if model is None:
            continue
        mode = rng.choice(list(model.modes))
        try:
            single = single_pairs(model, mode)
        except ModelError:
            continue
        if not single:
            continue
        expected = brute_force(model, mode)
        solve, calls = counting()
        got = solve_mode(model, mode, solve)
        compared += 1
        fewer_solves += len(calls) < 2 ** sum(e.kind == "freewheel"
                                              for e in model.shift_elements)
        if not expected:
            assert got.result is None and "no consistent freewheel state" in got.verdict
            continue
        consistent += 1
        choice, result = expected[0]
        assert_conservation(got.result)
        states = {n: "holding" if on else "overrunning" for n, on in choice.items()}
        assert {n: s for n, s in got.freewheels.items() if s != "idle"} == states
        assert got.result.ratio == pytest.approx(result.ratio, rel=1e-12)
        assert got.result.efficiency == pytest.approx(result.efficiency, rel=1e-12)
        if len(expected) == 1:
            assert got.verdict == "ok"
        else:
            several += 1
            assert got.verdict == (f"{len(expected)} consistent freewheel states; the first "
                                   "is reported")
    # the draw covers answers, no answer and several answers, and the pruning did prune
    assert consistent >= 10 and compared - consistent >= 5 and several >= 1
    assert fewer_solves >= 20


@pytest.mark.parametrize("mode", ["1", "2", "3", "R"])
def test_issue34_pruned_search_equals_brute_force_on_the_bundled_simpson(mode) -> None:
    """The bundled train forward and coasting (the output driving at the input's power)."""
    model = pg.load_model(SIMPSON)
    forward = solve_mode(model, mode)
    for case in (model, _with_ports(model, backdriven(forward.result.model).ports)):
        expected = brute_force(case, mode)
        got = solve_mode(case, mode)
        assert (got.result is None) == (not expected)
        if expected:
            assert_conservation(got.result)
            choice, result = expected[0]
            assert {n: s for n, s in got.freewheels.items() if s != "idle"} == {
                n: "holding" if on else "overrunning" for n, on in choice.items()}
            assert got.result.efficiency == pytest.approx(result.efficiency, rel=1e-12)


# --- the limit ---------------------------------------------------------------------------

def with_drums(count: int) -> str:
    """Simpson plus ``count`` empty drums, each held by a freewheel to the housing: each
    drum is a free body, so each freewheel is a group of its own to decide."""
    text = simpson_with([f"{{type: freewheel, name: D{k}, between: [d{k}, 0], "
                         "holds: positive}" for k in range(count)])
    drums = "".join(f"  d{k}: {{name: drum {k}}}\n" for k in range(count))
    return text.replace("  c2: {name: rear carrier}\n",
                        "  c2: {name: rear carrier}\n" + drums)


def test_issue34_more_freewheel_groups_than_the_limit_are_refused(tmp_path, capsys) -> None:
    """F1 and 10 drums: 11 groups to decide, one more than MAX_FREEWHEELS (10)."""
    assert MAX_FREEWHEELS == 10
    model = loads_model(with_drums(10))
    solve, calls = counting()
    with pytest.raises(ModelError) as info:
        solve_mode(model, "1", solve)
    assert str(info.value) == ("modes.1: 11 freewheels (or groups of freewheels joining the "
                               "same two members) to decide, more than the limit of 10")
    assert calls == []
    path = tmp_path / "drums.yaml"
    path.write_text(with_drums(10))
    assert main(["solve", str(path), "--mode", "1"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "limit of 10" in err and "Traceback" not in err


def test_issue34_ten_groups_are_decided_with_one_solve() -> None:
    """F1 and 9 drums: each free drum must be held (else the train has a DOF too many),
    carrying nothing (0 N·m: nothing acts on it); F1 holds as in plain 1st gear: one
    combination is consistent in speed, so one solve instead of 2**10."""
    solve, calls = counting(limit=4)
    result = solve_mode(loads_model(with_drums(9)), "1", solve)
    assert_conservation(result.result)
    assert len(calls) == 1 and result.verdict == "ok"
    assert result.result.ratio == pytest.approx(FIRST, rel=1e-12)
    assert result.freewheels == {"F1": "holding", **{f"D{k}": "holding" for k in range(9)}}
    assert all(result.element(f"D{k}").torque == 0.0 for k in range(9))
    assert result.element("F1").torque == pytest.approx(train_balance(result.result),
                                                        rel=1e-9)


def test_issue34_no_consistent_state_lists_a_bounded_number_of_reasons() -> None:
    """Simpson 1st coasting with the 9 drums: F1 cannot hold the reversed torque and the
    train runs free when it overruns -- no consistent state; the verdict names the
    reasons, at most 12 and how many more, on one line."""
    model = loads_model(with_drums(9))
    forward = solve_mode(model, "1")
    coast = solve_mode(_with_ports(model, backdriven(forward.result.model).ports), "1")
    assert coast.result is None
    assert coast.verdict.startswith("no consistent freewheel state (")
    assert "F1 holding would carry" in coast.verdict
    assert "(it holds positive only)" in coast.verdict
    assert "\n" not in coast.verdict and coast.verdict.count(";") <= 12


def test_a_freewheel_between_input_and_output_loads_and_overruns() -> None:
    """An overdrive-style freewheel F9 from the input to the output (holds positive:
    w_in - w_out >= 0) was refused at load, because the default state held every
    freewheel and so joined the two ports. Now the default state leaves it overrunning,
    and each mode decides it: by hand, 1st (7/3), 2nd (4/3) and reverse (-3) turn the
    output slower than the input or backwards, so F9 slips forward (w_in (1 - 1/i) > 0)
    and carries nothing: every gear is the plain Simpson's."""
    text = SIMPSON.read_text().replace("modes:", "  - {type: freewheel, name: F9, "
                                       "between: [in, c1], holds: positive}\nmodes:")
    model = loads_model(text)
    plain = pg.load_model(SIMPSON)
    for mode, ratio in (("1", 7 / 3), ("2", 4 / 3), ("R", -3.0)):
        got = solve_mode(model, mode)
        assert_conservation(got.result)
        assert got.freewheels["F9"] == "overrunning"
        assert got.element("F9").slip_speed == pytest.approx(
            got.result.kinematics.speed("in") * (1 - 1 / ratio), rel=1e-12)
        assert got.result.efficiency == pytest.approx(
            solve_mode(plain, mode).result.efficiency, rel=1e-12)
