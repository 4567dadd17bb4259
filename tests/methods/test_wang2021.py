"""Wang (2021)'s split/virtual power method and its comparison with the virtual-power
method (docs/theory.md).

Expected values come from tests/data/published_values.yaml or from the paper's
Eqs. (1)–(20) written out below as formulas in the teeth — never from the code under test.
"""
from __future__ import annotations

import copy
from pathlib import Path

import pytest
import yaml

import powergraph as pg
from powergraph.errors import MethodNotApplicableError, ModelError
from powergraph.methods.method_comparison import compare_methods, equivalent_cycloid_efficiency
from powergraph.methods.rv_roles import find_rv_roles
from powergraph.methods.wang2021 import solve_wang2021
from powergraph.testing import assert_conservation

ROOT = Path(__file__).resolve().parents[2]
RV40E = ROOT / "models" / "rv40e_wang2021.yaml"
RENAMED = ROOT / "tests" / "data" / "rv_renamed_shuffled.yaml"
SMALL = ROOT / "tests" / "data" / "rv_small.yaml"

SPEC_KEYS = {"name", "method", "dof", "ratio", "efficiency", "input_power", "output_power",
             "total_loss", "speeds", "torques", "meshes", "flows", "circulating_power",
             "self_locking", "split_power", "virtual_power", "losses", "beta", "alpha"}


def paper_by_hand(z1: int, z2: int, z4: int, z5: int, power: float, eta1: float,
                  eta2: float) -> dict[str, float]:
    """The paper's Eqs. (1)–(15) written out for an RV reducer (no code under test)."""
    i16 = 1 + z2 * z5 / z1                    # Eqs. (1)-(3): ratio of the RV
    w3_over_w4 = z4 / (z4 - z5)               # Eq. (4); w2 = w3 (Eq. 3)
    beta = -w3_over_w4                        # Eq. (8): beta = -w2/w4
    alpha = 1 - w3_over_w4                    # Eq. (10)/(12): (w4 - w3)/w4
    split = power * (1 - 1 / beta)            # beta = P/(P - V)
    virtual = alpha * (power - split) - power  # alpha = (P + U)/(P - V)
    loss1 = power * (1 - eta1)                # Eq. (13)
    loss2 = (power + virtual - loss1) * (1 - eta2)  # Eq. (14)
    eta = (power - loss1 - loss2) / power     # Eq. (15)
    return {"ratio": i16, "beta": beta, "alpha": alpha, "V": split, "U": virtual,
            "L1": loss1, "L2": loss2, "eta": eta,
            "i24": (z1 + z2 - z1 * i16) / z2}  # Eq. (5)


RV40E_HAND = paper_by_hand(12, 36, 39, 40, 2270.0, 0.94, 0.94)


def check(result) -> None:
    """Conservation of every virtual-power solve behind a result."""
    for solved in (result.virtual_power_result, result.realisation):
        if solved is not None:
            assert_conservation(solved)


@pytest.fixture(scope="module")
def rv40e():
    result = solve_wang2021(pg.load_model(RV40E))
    check(result)
    return result


def test_rv40e_printed_digits(rv40e) -> None:
    # tests/data/published_values.yaml (Wang 2021), "printed" column (Eqs. 16-20).
    assert round(rv40e.split_power, 1) == 2211.8
    assert round(rv40e.paper_virtual_power, 4) == 58.2051
    assert round(rv40e.losses[0], 1) == 136.2
    assert round(rv40e.losses[1], 2) == 131.52
    assert round(rv40e.efficiency * 100, 1) == 88.2


def test_rv40e_exact_values(rv40e) -> None:
    # Closed forms of Eqs. (16)-(17): V = (2 z4 - z5)/z4 P, U = (z5 - z4)/z4 P.
    P = 2270.0
    assert abs(rv40e.split_power - (2 * 39 - 40) / 39 * P) < 1e-6
    assert abs(rv40e.paper_virtual_power - (40 - 39) / 39 * P) < 1e-6
    for key, value in (("V", rv40e.split_power), ("U", rv40e.paper_virtual_power),
                       ("L1", rv40e.losses[0]), ("L2", rv40e.losses[1]),
                       ("eta", rv40e.efficiency)):
        assert abs(value - RV40E_HAND[key]) < 1e-6, key
    # published_values.yaml (Wang 2021) "exact" column, to its last printed digit
    # (0.882061 is within 1e-6:
    # the exact value is 0.88206154, so the column truncates).
    assert rv40e.split_power == pytest.approx(2211.7949, abs=0.5e-4)
    assert rv40e.paper_virtual_power == pytest.approx(58.20513, abs=0.5e-5)
    assert rv40e.losses[1] == pytest.approx(131.52031, abs=0.5e-5)
    assert abs(rv40e.efficiency - 0.882061) < 1e-6
    # tests/data/published_values.yaml (Wang 2021): eta = eta1 - (eta1 + 1/beta)(1 - eta2).
    assert rv40e.efficiency == pytest.approx(0.94 - (0.94 + 1 / 39) * 0.06, abs=1e-12)


def test_rv40e_ratios_from_speeds(rv40e) -> None:
    assert rv40e.ratio == pytest.approx(121, rel=1e-12)
    assert rv40e.beta == pytest.approx(39, rel=1e-12)      # z4/(z5 - z4)
    assert rv40e.alpha == pytest.approx(40, rel=1e-12)     # z5/(z5 - z4)
    w = rv40e.speeds
    assert w["2"] / w["4"] == pytest.approx(RV40E_HAND["i24"], rel=1e-12)  # Eq. (5)
    # tests/data/published_values.yaml (virtual-power RV-40E) speeds with w1 = 1500 rpm.
    assert w["3"] == pytest.approx(-50.6290, abs=5e-5)
    assert w["6"] == pytest.approx(1.29818, abs=5e-6)


def test_roles_found_from_the_graph() -> None:
    roles = find_rv_roles(pg.load_model(RENAMED))
    assert (roles.input_gear, roles.planet_gear, roles.cycloid, roles.pin_gear) == \
        ("pinion", "spur", "disc", "needles")
    assert roles.planet_body == "crank/spur" and roles.output_body == "cage/flange"
    assert (roles.first_mesh, roles.cycloid_mesh, roles.coupling) == (5, 2, 0)


def test_renamed_shuffled_copy_gives_the_same_numbers(rv40e) -> None:
    result = solve_wang2021(pg.load_model(RENAMED))
    check(result)
    for name in ("split_power", "paper_virtual_power", "efficiency", "beta", "alpha", "ratio"):
        assert getattr(result, name) == pytest.approx(getattr(rv40e, name), rel=1e-12), name
    assert result.losses == pytest.approx(rv40e.losses, rel=1e-12)
    data = result.to_dict()
    assert data["losses"][0] == pytest.approx(136.2, abs=1e-9)   # L1 first, whatever order
    # meshes in file order: the cycloid-pin mesh is written first in this file.
    assert [m["between"] for m in data["meshes"]] == [["needles", "disc"], ["spur", "pinion"]]
    assert [m["loss"] for m in data["meshes"]] == pytest.approx(data["losses"][::-1])
    assert [m["driver"] for m in data["meshes"]] == ["needles", "pinion"]


def test_small_rv_from_the_issue() -> None:
    hand = paper_by_hand(10, 30, 29, 30, 1000.0, 0.97, 0.96)
    result = solve_wang2021(pg.load_model(SMALL))
    check(result)
    # The issue's printed values ...
    assert round(result.split_power, 3) == 965.517
    assert round(result.paper_virtual_power, 3) == 34.483
    assert round(result.losses[0], 3) == 30.0
    assert round(result.losses[1], 3) == 40.179
    assert round(result.efficiency, 6) == 0.929821
    # ... and the hand derivation, exactly.
    assert result.ratio == pytest.approx(hand["ratio"], rel=1e-12)
    assert result.beta == pytest.approx(hand["beta"], rel=1e-12)
    assert result.alpha == pytest.approx(hand["alpha"], rel=1e-12)
    for key, value in (("V", result.split_power), ("U", result.paper_virtual_power),
                       ("L1", result.losses[0]), ("L2", result.losses[1]),
                       ("eta", result.efficiency)):
        assert abs(value - hand[key]) < 1e-6, key


def test_to_dict_has_every_spec_key_and_consistent_torques(rv40e) -> None:
    data = rv40e.to_dict()
    assert SPEC_KEYS <= set(data)
    assert data["method"] == "wang2021" and data["dof"] == 1
    assert data["losses"] == pytest.approx([RV40E_HAND["L1"], RV40E_HAND["L2"]], abs=1e-6)
    assert data["total_loss"] == pytest.approx(sum(data["losses"]), rel=1e-12)
    assert data["output_power"] == pytest.approx(2270 * RV40E_HAND["eta"], rel=1e-12)
    t, w = data["torques"], data["speeds"]
    assert t["1"] * w["1"] == pytest.approx(2270.0, rel=1e-12)
    assert -t["6"] * w["6"] == pytest.approx(data["output_power"], rel=1e-12)
    assert sum(t.values()) == pytest.approx(0.0, abs=1e-9)
    first, second = data["meshes"]
    assert first["between"] == [1, 2] and first["carrier"] == 7 and first["driver"] == 1
    assert second["between"] == [4, 5] and second["carrier"] == 3 and second["driver"] == 5
    # The power each basic efficiency is applied to: P (Eq. 13) and P + U - L1 (Eq. 14).
    assert first["virtual_power"] == pytest.approx(2270.0)
    assert second["virtual_power"] == pytest.approx(
        2270 + RV40E_HAND["U"] - RV40E_HAND["L1"], rel=1e-12)
    assert data["self_locking"] is False


def test_flows_realise_the_paper_losses_consistently(rv40e) -> None:
    realised = rv40e.realisation
    assert_conservation(realised)
    assert realised.element(0).loss == pytest.approx(RV40E_HAND["L1"], rel=1e-9)
    assert realised.element(1).loss == pytest.approx(RV40E_HAND["L2"], rel=1e-9)
    assert realised.efficiency == pytest.approx(RV40E_HAND["eta"], rel=1e-9)
    # Mesh 1-2 passes P (w1 - w7)/w1 = P·120/121 in its carrier's frame, so losing L1
    # there takes eta1* = 1 - L1·121/(120 P).
    assert rv40e.realised_efficiencies[0] == pytest.approx(1 - 0.06 * 121 / 120, rel=1e-9)
    flows = rv40e.to_dict()["flows"]
    assert all(f["power"] >= 0 for f in flows)
    assert {"from": "motor", "to": "1", "power": pytest.approx(2270.0),
            "from_kind": "motor", "to_kind": "body"} in flows


def test_split_flows_are_the_papers_fig5(rv40e) -> None:
    edges = {(f.source, f.target): f.power for f in rv40e.split_flows()}
    assert edges[("2/3", "6/7")] == pytest.approx(RV40E_HAND["V"], rel=1e-12)
    assert edges[("2/3", "mesh 4-5")] == pytest.approx(2270 - RV40E_HAND["V"], rel=1e-12)
    assert edges[("6/7", "generator")] == pytest.approx(2270.0)
    nodes = {n for edge in edges for n in edge} - {"motor", "generator"}
    for node in nodes:   # every node balances (no losses in Fig. 5)
        inflow = sum(p for (a, b), p in edges.items() if b == node)
        outflow = sum(p for (a, b), p in edges.items() if a == node)
        assert inflow == pytest.approx(outflow, rel=1e-12), node


def _vp_closed_form(z1, z2, z4, z5, eta1, eta2):
    """Virtual-power η of the RV, derived by hand (docs/theory.md), gear 1 driving mesh 1-2
    in the planet frame (f = eta1) and the pin gear driving mesh 4-5 in the crank's frame
    (f = 1/eta2). Torque balance of 2/3, 4 and 6/7 with input torque T:
    T_out = -T [1 + k eta1 + k eta1/(z5/(z4 eta2) - 1)], k = z2/z1, so
    eta = [1 + k eta1 + k eta1/(z5/(z4 eta2) - 1)] / (1 + k z5)."""
    k = z2 / z1
    return (1 + k * eta1 + k * eta1 / (z5 / (z4 * eta2) - 1)) / (1 + k * z5)


def test_virtual_power_side_by_side() -> None:
    model = pg.load_model(RV40E)
    comparison = compare_methods(model)
    assert_conservation(comparison.rigorous)
    # tests/data/published_values.yaml (virtual-power RV-40E): 0.287376, L1 135.0744 W, L2 1482.583 W.
    assert comparison.virtual_power_efficiency == pytest.approx(0.287376, abs=5e-7)
    l1, l2 = comparison.virtual_power_losses
    assert l1 == pytest.approx(135.0744, abs=5e-5)
    assert l2 == pytest.approx(1482.583, abs=5e-4)
    assert comparison.virtual_power_efficiency == pytest.approx(
        _vp_closed_form(12, 36, 39, 40, 0.94, 0.94), rel=1e-10)
    assert comparison.paper_efficiency == pytest.approx(RV40E_HAND["eta"], rel=1e-12)
    # Lossless, the cycloid-pin mesh passes |T_frame w3| = (i - 1) P |w3/w1| = 120·39/121 P.
    assert comparison.lossless_carrier_frame_power == pytest.approx(2270 * 120 * 39 / 121,
                                                              rel=1e-10)


def test_needle_mesh_case() -> None:
    model = pg.load_model(RV40E).with_link(1, efficiency=0.998)
    comparison = compare_methods(model)
    assert_conservation(comparison.rigorous)
    # tests/data/published_values.yaml (virtual-power RV-40E): 0.873043, L2 153.118 W.
    assert comparison.virtual_power_efficiency == pytest.approx(0.873043, abs=5e-7)
    assert comparison.virtual_power_losses[1] == pytest.approx(153.118, abs=5e-4)


def test_equivalent_cycloid_efficiency() -> None:
    model = pg.load_model(RV40E)
    x = equivalent_cycloid_efficiency(model)
    # Invert the closed form above for eta2 at the paper's eta (k = 3, eta1 = 0.94):
    # k eta1/(z5/(z4 x) - 1) = R with R = eta i - 1 - k eta1  =>  x = z5/(z4 (1 + k eta1/R)).
    R = RV40E_HAND["eta"] * 121 - 1 - 3 * 0.94
    assert x == pytest.approx(40 / (39 * (1 + 3 * 0.94 / R)), rel=1e-10)
    solved = pg.solve(model.with_link(1, efficiency=x))
    assert_conservation(solved)
    assert solved.efficiency == pytest.approx(RV40E_HAND["eta"], rel=1e-10)
    assert 0.998 < x < 0.9985


def test_load_at_the_output_or_as_a_torque() -> None:
    raw = yaml.safe_load(SMALL.read_text())
    hand = paper_by_hand(10, 30, 29, 30, 1.0, 0.97, 0.96)
    by_output = copy.deepcopy(raw)
    by_output["ports"] = [{"component": 1, "role": "input", "speed": 100.0},
                          {"component": 6, "role": "output", "power": 500.0}]
    result = solve_wang2021(pg.model_from_dict(by_output))
    check(result)
    assert result.output_power == pytest.approx(500.0, rel=1e-12)
    assert result.input_power == pytest.approx(500.0 / hand["eta"], rel=1e-12)
    by_torque = copy.deepcopy(raw)
    by_torque["ports"] = [{"component": 1, "role": "input", "speed": 100.0, "torque": 2.0},
                          {"component": 6, "role": "output"}]
    result = solve_wang2021(pg.model_from_dict(by_torque))
    assert result.input_power == pytest.approx(200.0, rel=1e-12)
    assert result.losses[0] == pytest.approx(200.0 * 0.03, rel=1e-12)


def test_the_model_is_not_changed() -> None:
    model = pg.load_model(RV40E)
    before = (model.links, model.ports, dict(model.components))
    solve_wang2021(model)
    compare_methods(model)
    assert (model.links, model.ports, dict(model.components)) == before


# --- refusals ----------------------------------------------------------------------

def _rv_dict() -> dict:
    return yaml.safe_load(SMALL.read_text())


def _no_coupling() -> dict:
    data = _rv_dict()
    data["links"] = [link for link in data["links"] if link["type"] != "coupling"]
    return data


def _two_outputs() -> dict:
    data = _rv_dict()
    data["ports"].append({"component": 4, "role": "output"})
    return data


def _output_on_crank() -> dict:
    data = _rv_dict()
    data["ports"][1] = {"component": 3, "role": "output"}
    return data


def _two_inputs() -> dict:
    # The pin ring freed and driven: a 2-DOF differential, not Wang's reducer.
    data = _rv_dict()
    data["links"] = [link for link in data["links"] if link["between"] != [5, 0]]
    data["ports"].append({"component": 5, "role": "input", "speed": 5.0})
    return data


def _back_driven() -> dict:
    data = _rv_dict()
    data["ports"] = [{"component": 6, "role": "input", "speed": 10.0, "power": 100.0},
                     {"component": 1, "role": "output"}]
    return data


@pytest.mark.parametrize("name, found", [
    ("khv_involute.yaml", "found 1 mesh and 1 coupling"),
    ("planetary_2kh_sun_to_carrier.yaml", "found 2 meshes and 0 couplings"),
    ("planetary_2kh_two_stages.yaml", "found 4 meshes"),
])
def test_non_rv_model_files_are_refused(name: str, found: str) -> None:
    with pytest.raises(MethodNotApplicableError) as info:
        solve_wang2021(pg.load_model(ROOT / "models" / name))
    assert "wang2021 method needs an RV-type train" in str(info.value)
    assert found in str(info.value)
    assert isinstance(info.value, ModelError)     # CLI exit 2


@pytest.mark.parametrize("build, found", [
    (_no_coupling, "found 2 meshes and 0 couplings"),
    (_two_outputs, "1 input port and 2 output ports"),
    (_output_on_crank, "no mesh has the input component 1 as a gear and the output body"),
    (_two_inputs, "2 input ports"),
    (_back_driven, "no mesh has the input component 6"),
])
def test_altered_rv_trains_are_refused(build, found: str) -> None:
    model = pg.model_from_dict(build())
    with pytest.raises(MethodNotApplicableError) as info:
        solve_wang2021(model)
    assert found in str(info.value)


def test_cycloid_mesh_with_the_wrong_carrier_is_refused() -> None:
    data = _rv_dict()
    data["links"][1]["carrier"] = 7      # cycloid mesh on the planet frame, not the crank
    with pytest.raises(MethodNotApplicableError, match="not the planet/crank body"):
        solve_wang2021(pg.model_from_dict(data))


def test_friction_derived_efficiencies_are_refused_not_read_as_one(capsys) -> None:
    """The paper's method reads each mesh's constant basic efficiency; a mesh whose
    efficiency comes from friction has none, so the method refuses the model, naming the
    first such block, instead of treating that mesh as ideal."""
    from powergraph.cli.main import main

    friction_rv = ROOT / "models" / "rv40e.yaml"
    with pytest.raises(MethodNotApplicableError) as caught:
        solve_wang2021(pg.load_model(friction_rv))
    assert caught.value.path == "links[0].friction"
    assert main(["solve", str(friction_rv), "--method", "wang2021"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "links[0].friction" in err
