"""Placing clutches and brakes on a 2-DOF gearset, against the Simpson set by hand.

The Simpson gearset: two simple sets on a common sun s, rings r1 and r2 (z = 72, sun 24,
k = 3), the front carrier c1 joined to the rear ring r2 and driving the output. Willis:

    front: w_s = (1 + k) w_c1 − k w_r1        rear: w_s = (1 + k) w_c2 − k w_r2, w_r2 = w_c1

States, output w = w_c1, input at 1 on the clutched member:
- r1 in, c2 held: rear w_s = −k w; front −k w = (1 + k) w − k  →  ratio 1/w = 1 + (1 + k)/k
- r1 in, s held:  front 0 = (1 + k) w − k                      →  ratio (1 + k)/k
- s in, c2 held:  rear 1 = −k w                                 →  ratio −k
- two clutches:   the sets turn as a block                      →  ratio 1
so the ratios 7/3, 4/3, 1, −3 need clutches to r1 and s and brakes on c2 and s: four
elements, the Simpson transmission's own (models/simpson_3speed.yaml).
"""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from powergraph.analyses.gear_table import gear_table
from powergraph.analyses.shift_placement import (gear_states, place_shift_elements,
                                                 transmission_document)
from powergraph.cli.main import main
from powergraph.errors import UsageError
from powergraph.model import load_model, model_from_dict
from powergraph.model.yaml_loader import load_yaml_file
from powergraph.statics.modes import solve_mode
from powergraph.testing import assert_conservation

MODELS = Path(__file__).resolve().parents[2] / "models"
GEARSET = MODELS / "gearsets" / "simpson.yaml"
K = 3.0
HAND = {(("r1",), ("c2",)): 1 + (1 + K) / K, (("r1",), ("s",)): (1 + K) / K,
        (("s",), ("c2",)): -K}
TARGETS = [7 / 3, 4 / 3, 1.0, -3.0]


def test_the_gear_states_are_the_hand_derived_ratios() -> None:
    states = {(s.clutches, s.brakes): s.ratio for s in gear_states(load_model(GEARSET), "c1")}
    for key, ratio in HAND.items():
        assert states[key] == pytest.approx(ratio, rel=1e-12)
    blocks = [r for (clutches, brakes), r in states.items() if len(clutches) == 2]
    assert blocks == pytest.approx([1.0] * len(blocks), rel=1e-12) and len(blocks) == 3


def test_the_simpson_ratios_need_the_simpson_elements() -> None:
    best = place_shift_elements(load_model(GEARSET), TARGETS).plans[0]
    assert best.size == 4
    assert set(best.names) == {("clutch", "r1"), ("clutch", "s"), ("brake", "c2"),
                               ("brake", "s")}
    assert [g.ratio for g in best.gears] == pytest.approx(TARGETS, rel=1e-12)
    assert best.error < 1e-12


def test_the_written_transmission_gives_the_ratios_through_the_modes(tmp_path) -> None:
    model = load_model(GEARSET)
    plan = place_shift_elements(model, TARGETS).plans[0]
    transmission = model_from_dict(transmission_document(load_yaml_file(GEARSET), model, plan))
    table = gear_table(transmission)
    assert [row.ratio for row in table.rows] == pytest.approx(TARGETS, rel=1e-9)
    for mode in transmission.modes:
        assert_conservation(solve_mode(transmission, mode).result)


def test_a_tolerance_admits_nearby_ratios_and_refuses_far_ones() -> None:
    model = load_model(GEARSET)
    # 2.35 and 1.33 are within 1 % of 7/3 (C r1 + B c2) and 4/3 (C r1 + B s): one
    # clutch and two brakes, the larger error that of 7/3.
    best = place_shift_elements(model, [2.35, 1.33], tolerance=0.01).plans[0]
    assert set(best.names) == {("clutch", "r1"), ("brake", "c2"), ("brake", "s")}
    assert best.error == pytest.approx(abs(7 / 3 - 2.35) / 2.35, rel=1e-12)
    with pytest.raises(UsageError, match="no pair of shift elements gives ratio 10"):
        place_shift_elements(model, [10.0])


@pytest.mark.parametrize("path, words", [
    (MODELS / "simpson_first.yaml", "2-DOF gearset; this one has 1"),
    (MODELS / "simpson_3speed.yaml", "already has shift elements"),
])
def test_other_trains_are_refused(path, words) -> None:
    with pytest.raises(UsageError, match=words):
        place_shift_elements(load_model(path), [2.0])


@pytest.mark.filterwarnings("error")        # an unclosed file once warned here
def test_the_command_writes_a_model_that_modes_accepts(tmp_path, capsys) -> None:
    out = tmp_path / "placed.yaml"
    assert main(["shifts", str(GEARSET), "--ratios", "2.3333333333333,1.3333333333333,1,-3",
                 "--json", "-o", str(out)]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["plans"][0]["size"] == 4
    assert [row["ratio"] for row in data["gear_table"]["modes"]] == \
        pytest.approx(TARGETS, rel=1e-9)
    assert main(["modes", str(out), "--json"]) == 0
    assert [row["ratio"] for row in json.loads(capsys.readouterr().out)["modes"]] == \
        pytest.approx(TARGETS, rel=1e-9)


@pytest.mark.parametrize("argv, words", [
    (["--ratios", "2,x"], "--ratios"),
    (["--ratios", "0"], "--ratios"),
    (["--ratios", "10"], "no pair of shift elements"),
    (["--ratios", "2", "--tolerance", "200%"], "--tolerance"),
])
def test_bad_arguments_exit_2_in_one_line(argv, words, capsys) -> None:
    assert main(["shifts", str(GEARSET), *argv]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and words in err[0] and "Traceback" not in err[0]
