"""Backlash of internal involute pairs (Li et al. 2012; tests/data/published_values.yaml) and
the lost motion of whole trains (hand derivations).

Expected values come from tests/data/published_values.yaml (Li et al. 2012), the paper's
printed Tables 2-3 and
Conclusions, closed forms, or hand derivations written here -- never from the code.
"""
from __future__ import annotations

import math
from pathlib import Path

import pytest

from powergraph.analyses.backlash import (
    analyse_backlash,
    centre_distance,
    centre_distance_curve,
    format_arcmin,
    lost_motion_arcmin,
    over_pin_distance,
    shift_coefficient,
)
from powergraph.errors import ModelError, UsageError
from powergraph.model import load_model, model_from_dict

ROOT = Path(__file__).resolve().parents[2]
LI2012 = ROOT / "models" / "backlash_li2012.yaml"
ALPHA = math.radians(20.0)
SECOND = 1.0 / 60.0  # one arc-second in arc-minutes


def arcmin(minutes: int, seconds: float) -> float:
    return minutes + seconds / 60.0


@pytest.fixture(scope="module")
def pairs():
    report = analyse_backlash(load_model(LI2012))
    return {1: report.meshes[0].pair, 2: report.meshes[1].pair}


# --- M values, equivalent shift (Eqs. 12-14) -------------------------------------------

@pytest.mark.parametrize("teeth,internal,printed", [(45, True, 42.434), (40, False, 42.436)])
def test_standard_m_of_an_unshifted_gear_is_the_printed_one(teeth, internal, printed) -> None:
    # The paper prints the standard M to 0.001 mm: m = 1, α = 20°, d_p = 1.732 mm, x = 0.
    assert over_pin_distance(0.0, teeth, 1.0, ALPHA, 1.732, internal) == \
        pytest.approx(printed, abs=0.0005)


def _m_by_hand(x: float, z: int, internal: bool) -> float:
    """Eqs. (14) then (12)/(13) with a Newton solve of inv α_M written out here."""
    s = -1.0 if internal else 1.0
    target = (math.tan(ALPHA) - ALPHA) + s * 1.732 / (z * math.cos(ALPHA)) \
        - s * math.pi / (2 * z) + 2 * x * math.tan(ALPHA) / z
    a = 0.4
    for _ in range(60):
        a -= (math.tan(a) - a - target) / math.tan(a) ** 2
    odd = math.cos(math.pi / (2 * z)) if z % 2 else 1.0
    return z * math.cos(ALPHA) / math.cos(a) * odd + s * 1.732


@pytest.mark.parametrize("pair,gear,z,internal,m_used", [
    (1, "R1", 45, True, 42.479), (1, "G1", 40, False, 42.404),
    (2, "R2", 45, True, 42.476), (2, "G2", 40, False, 42.412)])
def test_equivalent_shift_reproduces_the_measured_m(pairs, pair, gear, z, internal,
                                                    m_used) -> None:
    # The smallest internal M and the largest external M (Table 2) are the ones used;
    # the shift is relative to the standard M, so x_abs(M_std) + shift gives back M.
    result = pairs[pair]
    assert result.m_used[gear] == pytest.approx(m_used, abs=1e-12)
    x_standard = shift_coefficient(42.434 if internal else 42.436, z, 1.0, ALPHA, 1.732,
                                   internal)
    x_total = x_standard + result.equivalent_shift[gear]
    assert _m_by_hand(x_total, z, internal) == pytest.approx(m_used, abs=1e-9)


@pytest.mark.parametrize("pair,internal,external", [(1, 0.0192, -0.0179), (2, 0.0179, -0.0134)])
def test_equivalent_shift_matches_reference_recomputation(pairs, pair, internal,
                                                          external) -> None:
    # published_values.yaml (Li 2012): "recomputation gives 0.0192 / -0.0179 and 0.0179 / -0.0134"
    # (printed in Table 3: 0.019 / -0.016 and 0.017 / -0.014).
    shift = pairs[pair].equivalent_shift
    assert shift[pairs[pair].internal] == pytest.approx(internal, abs=0.00005)
    assert shift[pairs[pair].external] == pytest.approx(external, abs=0.00005)


@pytest.mark.parametrize("pair,deviations", [(1, (0.045, -0.032)), (2, (0.042, -0.024))])
def test_m_deviation_is_table_3(pairs, pair, deviations) -> None:
    result = pairs[pair]
    assert result.m_deviation[result.internal] == pytest.approx(deviations[0], abs=1e-9)
    assert result.m_deviation[result.external] == pytest.approx(deviations[1], abs=1e-9)


# --- eccentric offset a'' (Eqs. 15, 16, 9) ----------------------------------------------

@pytest.mark.parametrize("pair,printed", [(1, 2.572), (2, 2.565)])
def test_eccentric_offset_paper_variant_is_table_3(pairs, pair, printed) -> None:
    # Acceptance: a'' within 0.01 mm of the printed value (Eq. 15 as printed, no tan α).
    assert pairs[pair].eccentric_offset["paper"] == pytest.approx(printed, abs=0.01)


@pytest.mark.parametrize("pair,reference", [(1, 2.522), (2, 2.514)])
def test_eccentric_offset_standard_variant_is_reference(pairs, pair, reference) -> None:
    # tests/data/published_values.yaml (Li 2012): with tan α in Eq. 15, a'' ≈ 2.522 / 2.514 mm.
    assert pairs[pair].eccentric_offset["standard"] == pytest.approx(reference, abs=0.001)


def _no_backlash_distance_by_tooth_thickness(x_int: float, x_ext: float, z_int: int,
                                             z_ext: int) -> float:
    """a' from the tooth geometry, not from Eq. (15).

    On the working pitch circles (radius r' = m z cos α / (2 cos α')) the external gear's
    tooth thickness equals the internal gear's space width:
        s'(α') = 2 r'_ext (s0/(m z_ext) + inv α − inv α'),  s0 = m(π/2 + 2 x_ext tan α)
        e'(α') = 2 r'_int (e0/(m z_int) + inv α − inv α'),  e0 = m(π/2 + 2 x_int tan α)
    (x_int > 0 widens the internal gear's spaces, the convention of Eq. 14). Solve
    s' = e' for α' by bisection; a' = r'_int − r'_ext.
    """
    inv = lambda a: math.tan(a) - a  # noqa: E731

    def radius(z, a):
        return z * math.cos(ALPHA) / (2 * math.cos(a))

    def gap(a):
        s0 = math.pi / 2 + 2 * x_ext * math.tan(ALPHA)
        e0 = math.pi / 2 + 2 * x_int * math.tan(ALPHA)
        s = 2 * radius(z_ext, a) * (s0 / z_ext + inv(ALPHA) - inv(a))
        e = 2 * radius(z_int, a) * (e0 / z_int + inv(ALPHA) - inv(a))
        return s - e

    lo, hi = math.radians(5), math.radians(40)
    for _ in range(200):
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if gap(lo) * gap(mid) > 0 else (lo, mid)
    a = (lo + hi) / 2
    return radius(z_int, a) - radius(z_ext, a)


@pytest.mark.parametrize("pair", [1, 2])
def test_standard_variant_is_the_tooth_thickness_condition(pairs, pair) -> None:
    result = pairs[pair]
    shift = result.shift_coefficient
    expected = _no_backlash_distance_by_tooth_thickness(
        shift[result.internal], shift[result.external], 45, 40)
    assert result.no_backlash_centre_distance["standard"] == pytest.approx(expected, abs=1e-9)
    # Eq. (9): a'' = a' − (F_r1 + F_r2)/2 + Σ u_r/2 with Table 3's runouts and clearances.
    runout, bearings = {1: (0.037, 0.011), 2: (0.043, 0.010)}[pair]
    assert result.eccentric_offset["standard"] == pytest.approx(
        expected - runout / 2 + bearings / 2, abs=1e-9)


def test_paper_variant_with_printed_shifts_is_reference() -> None:
    # published_values.yaml (Li 2012): "without it (as printed) ≈ 2.573 / 2.561 mm": Eq. 15
    # without tan α fed
    # with the printed shifts 0.019/-0.016 and 0.017/-0.014.
    from powergraph.analyses.backlash import no_backlash_centre_distance, working_pressure_angle

    for (xi, xe, runout, bearings), expected in [((0.019, -0.016, 0.037, 0.011), 2.573),
                                                 ((0.017, -0.014, 0.043, 0.010), 2.561)]:
        angle = working_pressure_angle(xi, xe, 45, 40, ALPHA, "paper")
        a2 = no_backlash_centre_distance(2.5, ALPHA, angle) - runout / 2 + bearings / 2
        assert a2 == pytest.approx(expected, abs=0.0005)


# --- lost motion (Eqs. 1-3, 7, 8) -------------------------------------------------------

def test_eq1_constant() -> None:
    # Eq. (1): j_φ = 180·60/(1000π) · j_t / (m Z1 / 2) = 6.876 j_t / (m Z1), j_t in µm.
    # The exact coefficient is 6.87549; the printed 6.876 is its (slightly high) rounding.
    assert lost_motion_arcmin(0.001, 1.0, 1) == pytest.approx(180 * 60 / (1000 * math.pi) * 2,
                                                              rel=1e-12)
    assert lost_motion_arcmin(0.001, 1.0, 1) == pytest.approx(6.876, abs=0.001)


@pytest.mark.parametrize("pair,thickness_runout,before,after", [
    (1, arcmin(6, 20.4), arcmin(6, 57.1), arcmin(2, 3.5)),
    (2, arcmin(6, 3.7), arcmin(6, 37.1), arcmin(2, 23.5))])
def test_lost_motion_terms_are_reference(pairs, pair, thickness_runout, before, after) -> None:
    # tests/data/published_values.yaml (Li et al. 2012), to its printed 0.1".
    terms = pairs[pair].lost_motion_arcmin
    assert terms["thickness"] + terms["runout"] == pytest.approx(thickness_runout,
                                                                 abs=0.06 * SECOND)
    assert terms["before"] == pytest.approx(before, abs=0.06 * SECOND)
    assert terms["after"] == pytest.approx(after, abs=0.06 * SECOND)
    assert terms["runout"] == pytest.approx(after, abs=0.06 * SECOND)
    assert terms["before"] == pytest.approx(
        terms["thickness"] + terms["runout"] + terms["bearing"], rel=1e-12)


def test_lost_motion_terms_by_hand(pairs) -> None:
    # Pair 1 by hand: E_M = 0.045 + 0.032 = 0.077 mm, ΣF_r = 0.037 mm, Σu_r = 0.011 mm;
    # j_t = E_M tan α, tan α ΣF_r, tan α Σu_r; Eq. (1) with Z1 = 45: j_t / 22.5 mm in rad.
    to_arcmin = 180 * 60 / math.pi / 22.5
    terms = pairs[1].lost_motion_arcmin
    assert terms["thickness"] == pytest.approx(0.077 * math.tan(ALPHA) * to_arcmin, rel=1e-9)
    assert terms["runout"] == pytest.approx(0.037 * math.tan(ALPHA) * to_arcmin, rel=1e-9)
    assert terms["bearing"] == pytest.approx(0.011 * math.tan(ALPHA) * to_arcmin, rel=1e-9)


# Which printed lost motion contains which terms (README table). Printed values within 10".
PRINTED = [
    # (pair, where, printed arcmin, terms it contains)
    (1, "Table 3, pair 1 (a = 2.5 mm)", arcmin(6, 20), ("thickness", "runout")),
    (2, "Table 3, pair 2 (a = 2.5 mm)", arcmin(6, 10), ("thickness", "runout")),
    (1, "Conclusions, pair 1 before", arcmin(6, 52), ("thickness", "runout", "bearing")),
    (2, "Conclusions, pair 2 before", arcmin(6, 37), ("thickness", "runout", "bearing")),
    (1, "Table 3, pair 3 (= pair 1 at a'')", arcmin(2, 3), ("runout",)),
    (2, "Table 3, pair 4 (= pair 2 at a'')", arcmin(2, 23), ("runout",)),
]


@pytest.mark.parametrize("pair,where,printed,terms", PRINTED, ids=[p[1] for p in PRINTED])
def test_printed_lost_motion_within_ten_seconds(pairs, pair, where, printed, terms) -> None:
    computed = sum(pairs[pair].lost_motion_arcmin[t] for t in terms)
    assert abs(computed - printed) <= 10 * SECOND, (where, format_arcmin(computed))


def test_format_arcmin() -> None:
    assert format_arcmin(arcmin(6, 20.4)) == "6'20.4\""
    assert format_arcmin(arcmin(2, 59.99)) == "3'0.0\""


# --- centre distance over the eccentric's turns (Eqs. 4-6, Fig. 3) ----------------------

def test_fig3_example_bounds_and_period() -> None:
    # Fig. 3: m = 1, Z1 = 45, Z2 = 40, F_r1 = 0.025, F_r2 = 0.018; |O1O2| = 2.5 mm.
    curve = centre_distance_curve(2.5, 0.025, 0.018, 45, 40, points_per_turn=720)
    assert curve.maximum == pytest.approx(2.5 + 0.0125 + 0.009, abs=1e-12)  # Eq. (5)
    assert curve.minimum == pytest.approx(2.5 - 0.0125 - 0.009, abs=1e-12)  # Eq. (6)
    # Z2/(Z1 − Z2) = 40/5 = 8 turns (the paper prints "= 20 r").
    assert curve.period_turns == 8
    assert max(curve.distance) <= curve.maximum + 1e-12
    assert min(curve.distance) >= curve.minimum - 1e-12
    # With β = 0 all three vectors line up at θ = 0: Eq. (5) is reached.
    assert curve.distance[0] == pytest.approx(curve.maximum, abs=1e-12)
    assert curve.distance[-1] == pytest.approx(curve.distance[0], abs=1e-12)


def test_eq6_reached_for_the_right_phase() -> None:
    # Eq. (4) as printed: the external gear's eccentricity is at angle θ/8 + β. At θ = π,
    # O1O2 points along −x; with β = −π/8 the gear's eccentricity points along +x, like
    # AO1, so |AB| = |O1O2| − |AO1| − |BO2| (Eq. 6) by hand.
    value = centre_distance(math.pi, 2.5, 0.0125, 0.009, 45, 40, beta=-math.pi / 8)
    assert float(value) == pytest.approx(2.5 - 0.0125 - 0.009, abs=1e-12)
    # Quarter turn, β = 0, by hand: (0.0125 + 0.009 cos(π/16), 2.5 + 0.009 sin(π/16)).
    value = centre_distance(math.pi / 2, 2.5, 0.0125, 0.009, 45, 40)
    assert float(value) == pytest.approx(math.hypot(0.0125 + 0.009 * math.cos(math.pi / 16),
                                                    2.5 + 0.009 * math.sin(math.pi / 16)),
                                         abs=1e-12)


# --- train level ------------------------------------------------------------------------

def khv_stage(prefix: str, z_planet: int, z_ring: int, mesh: dict, planet_first: bool) -> tuple:
    """Components and links of one K-H-V stage: eccentric H in, ring R fixed, planet G out
    through an equal-speed coupling to W."""
    h, r, g, w = (prefix + x for x in "HRGW")
    components = {h: {}, r: {"teeth": z_ring, "internal": True}, g: {"teeth": z_planet}, w: {}}
    between = [g, r] if planet_first else [r, g]
    links = [dict({"type": "mesh", "between": between, "carrier": h}, **mesh),
             {"type": "fixed", "between": [r, 0]},
             {"type": "coupling", "between": [g, w]}]
    return components, links


def one_stage(z_planet: int, z_ring: int, mesh: dict, planet_first: bool = True):
    components, links = khv_stage("", z_planet, z_ring, mesh, planet_first)
    return model_from_dict({"name": "KHV", "components": {0: {"role": "frame"}, **components},
                            "links": links,
                            "ports": [{"component": "H", "role": "input"},
                                      {"component": "W", "role": "output"}]})


def test_khv_stage_play_of_the_planet() -> None:
    # Hand derivation: the input eccentric H held, the ring fixed: the planet's axis and
    # the ring do not move, so a play φ of the planet relative to the ring (carrier frame
    # = H, which is still) is a free rotation φ of the planet, passed 1:1 by the
    # equal-speed coupling: the output's lost motion is φ (N = 30/2 = 15 does not enter).
    report = analyse_backlash(one_stage(30, 32, {"backlash_arcmin": 4.0}))
    assert report.worst_case == pytest.approx(4.0, rel=1e-12)
    assert report.rss == pytest.approx(4.0, rel=1e-12)
    assert abs(report.meshes[0].sensitivity) == pytest.approx(1.0, rel=1e-12)


def test_khv_stage_play_given_on_the_ring() -> None:
    # The same backlash stated as the ring's play φ_r (gear a = ring): the arc j = φ_r·r_r
    # lets the planet turn j/r_p = φ_r·z_r/z_p = φ_r·(N + 1)/N with N = z_p/(z_r − z_p).
    z_p, z_r = 30, 32
    n = z_p / (z_r - z_p)
    report = analyse_backlash(one_stage(z_p, z_r, {"backlash_arcmin": 4.0},
                                        planet_first=False))
    assert report.worst_case == pytest.approx(4.0 * (n + 1) / n, rel=1e-12)


def test_khv_stage_with_the_paper_block() -> None:
    # Pair 1 in a K-H-V stage, ring first: play = the paper's angle (Eq. 1, internal gear),
    # the paper's 6'57.1" (tests/data/published_values.yaml); at the output × z_r/z_p = 45/40.
    block = {"module": 1, "pin_diameter": 1.732, "standard_M": {"R": 42.434, "G": 42.436},
             "measured_M": {"R": [42.479], "G": [42.404]}, "runout": {"R": 0.022, "G": 0.015},
             "bearing_clearance": [0.005, 0.006]}
    for first, play in ((False, arcmin(6, 57.1)), (True, arcmin(6, 57.1) * 45 / 40)):
        report = analyse_backlash(one_stage(40, 45, {"backlash": block}, planet_first=first))
        assert report.meshes[0].play_arcmin == pytest.approx(play, abs=0.06 * SECOND)
        assert report.worst_case == pytest.approx(arcmin(6, 57.1) * 45 / 40,
                                                  abs=0.07 * SECOND)
    block["assembly"] = "compensated"   # pairs 3-4 of the paper: eccentric at a''
    report = analyse_backlash(one_stage(40, 45, {"backlash": block}, planet_first=False))
    assert report.meshes[0].play_arcmin == pytest.approx(arcmin(2, 3.5), abs=0.06 * SECOND)


def two_stages(mesh_1: dict, mesh_2: dict, extra_mesh: bool = False):
    c1, l1 = khv_stage("a", 30, 32, mesh_1, True)      # N1 = 15
    c2, l2 = khv_stage("b", 40, 45, mesh_2, True)      # N2 = 8
    links = l1 + l2 + [{"type": "fixed", "between": ["aW", "bH"]}]
    return model_from_dict({"name": "two KHV", "components": {0: {"role": "frame"}, **c1, **c2},
                            "links": links,
                            "ports": [{"component": "aH", "role": "input"},
                                      {"component": "bW", "role": "output"}]})


def test_two_stages_in_series() -> None:
    # Hand derivation: inputs held. Play φ1 in stage 1 turns stage 1's output, which is
    # stage 2's eccentric, by φ1 (see the one-stage test); stage 2 (ratio −N2, N2 = 8)
    # turns its output by φ1/N2. Play φ2 in stage 2: stage 1 is locked (its input held, no
    # play), so stage 2's eccentric is held and its output turns by φ2.
    phi1, phi2 = 4.0, 3.0
    report = analyse_backlash(two_stages({"backlash_arcmin": phi1}, {"backlash_arcmin": phi2}))
    assert [abs(m.sensitivity) for m in report.meshes] == pytest.approx([1 / 8, 1.0],
                                                                        rel=1e-12)
    assert report.worst_case == pytest.approx(phi1 / 8 + phi2, rel=1e-12)
    assert report.rss == pytest.approx(math.hypot(phi1 / 8, phi2), rel=1e-12)


def test_li2012_model_train(pairs) -> None:
    # models/backlash_li2012.yaml: pair 1 then pair 2, both K-H-V with Z1 = 45, Z2 = 40
    # (N = 8), ring first. By the two derivations above: output = φ1·(45/40)/8 + φ2·45/40
    # with φ1, φ2 = the paper's "before" values 6'57.1", 6'37.1".
    report = analyse_backlash(load_model(LI2012))
    phi1, phi2 = arcmin(6, 57.1), arcmin(6, 37.1)
    parts = (phi1 * 45 / 40 / 8, phi2 * 45 / 40)
    assert report.worst_case == pytest.approx(sum(parts), abs=0.1 * SECOND)
    assert report.rss == pytest.approx(math.hypot(*parts), abs=0.1 * SECOND)
    assert report.output == "W2" and report.meshes_without_backlash == ()


def test_meshes_without_data_are_listed_not_counted() -> None:
    report = analyse_backlash(two_stages({}, {"backlash_arcmin": 3.0}))
    assert report.worst_case == pytest.approx(3.0, rel=1e-12)
    assert report.meshes_without_backlash == (("aG", "aR"),)


def test_no_backlash_anywhere_is_an_error() -> None:
    with pytest.raises(ModelError, match="no mesh carries backlash"):
        analyse_backlash(two_stages({}, {}))


def test_output_choice() -> None:
    model = two_stages({"backlash_arcmin": 4.0}, {})
    # Read at stage 1's output instead: φ1 directly.
    assert analyse_backlash(model, output="aW").worst_case == pytest.approx(4.0, rel=1e-12)
    with pytest.raises(UsageError):
        analyse_backlash(model, output="nope")


def test_two_dof_train_with_one_input_is_a_model_error() -> None:
    # A 2K-H differential with only one input port: holding it does not fix the motion.
    model = model_from_dict({
        "name": "differential",
        "components": {0: {"role": "frame"}, "s": {"teeth": 20}, "p": {"teeth": 20},
                       "r": {"teeth": 60, "internal": True}, "c": {}},
        "links": [{"type": "mesh", "between": ["s", "p"], "carrier": "c", "backlash_arcmin": 1},
                  {"type": "mesh", "between": ["p", "r"], "carrier": "c"}],
        "ports": [{"component": "s", "role": "input"}, {"component": "c", "role": "output"}]})
    with pytest.raises(ModelError, match="every input held"):
        analyse_backlash(model)


def test_model_is_not_mutated() -> None:
    model = load_model(LI2012)
    before = repr(model)
    analyse_backlash(model)
    assert repr(model) == before


def test_result_to_dict_keys() -> None:
    data = analyse_backlash(load_model(LI2012)).to_dict()
    assert set(data["output_lost_motion_arcmin"]) == {"worst_case", "rss"}
    mesh = data["meshes"][0]
    assert {"between", "equivalent_shift", "eccentric_offset", "lost_motion_arcmin"} <= set(mesh)
    assert set(mesh["eccentric_offset"]) == {"paper", "standard"}
    assert set(mesh["lost_motion_arcmin"]) == {"thickness", "runout", "bearing", "before",
                                               "after"}
    assert set(mesh["equivalent_shift"]) == {"R1", "G1"}
