"""A cycloid stage's fluctuation carried to a train's output (a mesh with a ``cycloid:``
block, docs/cycloid.md).

Hand derivations (input speed held constant, the stage's instantaneous ratio i_s(θ)):

- RV-40E (Wang 2021, Table 1: z1 = 12, z2 = 36, z4 = 39, z5 = 40; pin ring 5 fixed, crank
  2/3 the carrier of the cycloid mesh, output 6/7 the carrier of the first stage, 4 coupled
  to 6).
  Disc: w4 = ρ·w3 with ρ = −1/i_s. First stage: w1 − w7 = −(36/12)(w3 − w7), w7 = w4.
  So w1 = w3·(4ρ − 3) and w6/w1 = ρ/(4ρ − 3), i.e. i_train = 4 + 3·i_s (121 for i_s = 39):
  a stage deviation Δi (%) is (3·39/121)·Δi at the output, and the crank turns
  1/(4ρ − 3) = −39/121 times per input turn.
- K-H-V (crank in, disc out through the coupling, ring fixed): w_out = ρ·w_H, so
  i_train = −i_s and the output sees the stage's deviation unchanged.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import yaml

from powergraph.analyses.cycloid import train_fluctuation
from powergraph.errors import ModelError
from powergraph.model import load_model, model_from_dict

MODELS = Path(__file__).resolve().parents[2] / "models"
# RV-40E cycloid stage of the model file's geometry block: R_p = 64 = m·40/2 -> m = 3.2;
# e = 1.3 = (1 - x)·m/2 -> x = 0.1875; r_p = 3 = rc·m -> rc = 0.9375.
RV_STAGE = {"module": 3.2, "shift": 0.1875, "rc": 0.9375, "profile_error": 0.01}


def with_cycloid(path: Path, mesh: int, block: dict, reverse: bool = False):
    data = yaml.safe_load(path.read_text())
    link = data["links"][mesh]
    link["cycloid"] = block
    if reverse:
        link["between"] = link["between"][::-1]
    return model_from_dict(data)


@pytest.fixture(scope="module")
def rv():
    return train_fluctuation(with_cycloid(MODELS / "rv40e_wang2021.yaml", 1, RV_STAGE))


def test_rv40e_output_fluctuation_by_hand(rv) -> None:
    assert rv.ratio_nominal == pytest.approx(121, rel=1e-12)
    (stage,) = rv.stages
    assert (stage.link, stage.disc, stage.ring, stage.carrier) == (1, "4", "5", "3")
    assert stage.stage.geometry.teeth == 39 and stage.stage.geometry.pins == 40
    assert stage.crank_turns_per_input_turn == pytest.approx(-39 / 121, rel=1e-12)
    assert np.allclose(stage.train_ratio, 4 + 3 * stage.stage_ratio, rtol=1e-12, atol=0)
    assert stage.max_deviation_percent == pytest.approx(
        3 * 39 / 121 * stage.stage.max_deviation_percent, rel=1e-9)
    # one input turn = 40·39/121 ≈ 12.9 periods of the stage's fluctuation
    assert stage.stage.max_deviation_percent > 0


def test_rv40e_json_block(rv) -> None:
    data = rv.to_dict()
    assert (data["input"], data["output"]) == ("1", "6")
    (entry,) = data["stages"]
    for key in ("link", "stage_max_deviation_percent", "max_deviation_percent",
                "input_angle_deg", "ratio", "deviation_percent", "crank_turns_per_input_turn"):
        assert key in entry
    assert len(entry["input_angle_deg"]) == len(entry["ratio"])


@pytest.mark.parametrize("reverse", [False, True])
def test_khv_output_sees_the_stage_unchanged(reverse: bool) -> None:
    model = with_cycloid(MODELS / "cycloid_khv.yaml", 0,
                         {"module": 1, "profile_error": 0.005}, reverse=reverse)
    result = train_fluctuation(model)
    (stage,) = result.stages
    assert result.ratio_nominal == pytest.approx(-39, rel=1e-12)
    assert np.allclose(stage.train_ratio, -stage.stage_ratio, rtol=1e-12, atol=0)
    assert stage.max_deviation_percent == pytest.approx(stage.stage.max_deviation_percent,
                                                        rel=1e-9)


def test_train_without_cycloid_blocks_has_no_stages() -> None:
    assert train_fluctuation(load_model(MODELS / "rv40e_wang2021.yaml")).stages == ()


def test_impossible_stage_is_a_model_error_with_its_place() -> None:
    model = with_cycloid(MODELS / "rv40e_wang2021.yaml", 1, {**RV_STAGE, "rc": 1.5})
    with pytest.raises(ModelError) as info:
        train_fluctuation(model)
    assert info.value.path == "links[1].cycloid"


def test_an_output_that_does_not_turn_is_a_model_error_not_a_division() -> None:
    # Found by the hostile-input benchmark: a merge key copied the cycloid mesh over the
    # first stage's, so both meshes join 4 and 5 (carriers 3 and 7), the planet gear no
    # longer turns and the output stands still (ratio infinite). `tolerance` ended in
    # "numerical problem (divide by zero)", exit 1.
    data = yaml.safe_load((MODELS / "rv40e_wang2021.yaml").read_text())
    cycloid = {**data["links"][1], "cycloid": RV_STAGE}
    data["links"][:2] = [cycloid, {**cycloid, "carrier": 7}]
    model = model_from_dict(data)
    with pytest.raises(ModelError, match="does not turn") as info:
        train_fluctuation(model)
    assert info.value.path == "ports"
