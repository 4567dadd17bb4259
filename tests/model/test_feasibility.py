"""powergraph.model.feasibility: each rule on a set that breaks it (hand numbers in the
test) and on one that does not; every bundled model is feasible (docs/feasibility.md)."""
from __future__ import annotations

import math
from pathlib import Path

import pytest

from powergraph.errors import ModelError
from powergraph.model import load_model, model_from_dict

MODELS = sorted((Path(__file__).resolve().parents[2] / "models").glob("*.yaml"))


def simple(zs: int, zp: int, zr: int, n: int = 3, internal: bool = True,
           sun_carrier: bool = True) -> dict:
    """Sun s in, ring r fixed, carrier c out; ``n`` planets p."""
    return {"name": "2K-H", "components": {
                0: {"role": "frame"}, "s": {"teeth": zs}, "p": {"teeth": zp, "count": n},
                "r": {"teeth": zr, "internal": internal}, "c": {}},
            "links": [{"type": "mesh", "between": ["s", "p"],
                       **({"carrier": "c"} if sun_carrier else {})},
                      {"type": "mesh", "between": ["p", "r"], "carrier": "c"},
                      {"type": "fixed", "between": ["r", 0]}],
            "ports": [{"component": "s", "role": "input"},
                      {"component": "c", "role": "output"}]}


def stepped(zs: int, zp1: int, zp2: int, zr: int, n: int = 3) -> dict:
    """models/planetary_stepped.yaml's layout: sun s on step p1, ring r on step p2."""
    return {"name": "stepped", "components": {
                0: {"role": "frame"}, "s": {"teeth": zs}, "p1": {"teeth": zp1, "count": n},
                "p2": {"teeth": zp2, "count": n}, "r": {"teeth": zr, "internal": True},
                "c": {}},
            "links": [{"type": "mesh", "between": ["s", "p1"], "carrier": "c"},
                      {"type": "mesh", "between": ["p2", "r"], "carrier": "c"},
                      {"type": "fixed", "between": ["p1", "p2"]},
                      {"type": "fixed", "between": ["r", 0]}],
            "ports": [{"component": "s", "role": "input"},
                      {"component": "c", "role": "output"}]}


def double_planet(zs: int, za: int, zb: int, zr: int, n: int = 3) -> dict:
    """models/planetary_double_planet.yaml's layout: s - a - b - r on carrier c."""
    return {"name": "double", "components": {
                0: {"role": "frame"}, "s": {"teeth": zs}, "a": {"teeth": za, "count": n},
                "b": {"teeth": zb, "count": n}, "r": {"teeth": zr, "internal": True},
                "c": {}},
            "links": [{"type": "mesh", "between": ["s", "a"], "carrier": "c"},
                      {"type": "mesh", "between": ["a", "b"], "carrier": "c"},
                      {"type": "mesh", "between": ["b", "r"], "carrier": "c"},
                      {"type": "fixed", "between": ["r", 0]}],
            "ports": [{"component": "s", "role": "input"},
                      {"component": "c", "role": "output"}]}


def caveats(doc: dict) -> list[tuple[str, str, str]]:
    return [(c.code, c.path, c.message) for c in model_from_dict(doc).warnings]


def codes(doc: dict) -> list[str]:
    return [code for code, _, _ in caveats(doc)]


@pytest.mark.parametrize("path", MODELS, ids=[p.stem for p in MODELS])
def test_every_bundled_model_is_feasible(path: Path) -> None:
    assert load_model(path).warnings == ()


# --- coaxiality ---------------------------------------------------------------------------
def test_simple_set_off_axis_by_one_tooth() -> None:
    # 23 + 2·24 = 71 ≠ 72 (and (23 + 72)/3 = 31.67: not assembled either)
    code, path, message = caveats(simple(23, 24, 72))[0]
    assert (code, path) == ("coaxiality", "links[0..1]")
    assert message.startswith("sun 23 + 2 × planet 24 = 71 ≠ ring 72: the planets cannot "
                              "share the axis of sun and ring")
    assert codes(simple(23, 24, 72)) == ["coaxiality", "assembly"]
    assert codes(simple(24, 24, 72)) == []          # 24 + 48 = 72, 96/3 = 32


def test_stepped_planet_centre_distances() -> None:
    # sun 18 + step 36 = 54 half-modules, ring 72 − step 20 = 52: off axis
    code, path, message = caveats(stepped(18, 36, 20, 72))[0]
    assert (code, path) == ("coaxiality", "links[0..1]")
    assert "sun 18 + planet 36 = 54; ring 72 − planet 20 = 52" in message
    assert codes(stepped(18, 36, 18, 72)) == []     # 54 = 72 − 18; models/planetary_stepped


def test_shifted_meshes_compare_working_centre_distances() -> None:
    # models/tuplin_256.yaml: 51 − 16 = 35 and 48 − 15 = 33 half-modules unshifted; its
    # shifts bring both to 17.1 mm. Without them the set is off axis; with the second
    # pair's ring shift 0.6 instead of 0.874 it is again (a smaller working distance).
    tuplin = load_model(MODELS[[p.stem for p in MODELS].index("tuplin_256")])
    assert tuplin.warnings == ()
    import yaml
    doc = yaml.safe_load(MODELS[[p.stem for p in MODELS].index("tuplin_256")].read_text())
    bare = {**doc, "links": [{k: v for k, v in link.items() if k != "geometry"}
                             for link in doc["links"]]}
    code, path, message = caveats(bare)[0]
    assert (code, path) == ("coaxiality", "links[0..1]")
    assert "ring 51 − planet 16 = 35; ring 48 − planet 15 = 33" in message
    doc["links"][1]["geometry"] = {"module": 1, "shifts": [0.2, 0.6]}
    code, path, message = caveats(doc)[0]
    assert (code, path) == ("coaxiality", "links[0..1]") and "links[0] 17.1003 mm" in message


def test_double_planets_must_reach_each_other() -> None:
    # sun 30 + inner 15: D_a = 45; ring 93 − outer 15: D_b = 78 half-modules; the planets'
    # mesh needs 15 + 15 = 30 > |45 − 78| = 33: they cannot meet ((93 − 30)/3 = 21 assembles)
    code, path, message = caveats(double_planet(30, 15, 15, 93))[0]
    assert (code, path) == ("coaxiality", "links[1]")
    assert "between |45 − 78| = 33 and 123" in message
    assert codes(double_planet(30, 15, 15, 75)) == []    # |45 − 60| = 15 < 30 < 105


# --- assembly -----------------------------------------------------------------------------
def test_simple_set_assembly() -> None:
    # (24 + 72)/5 = 19.2: five planets do not fit at equal spacing; four do (96/4 = 24)
    code, path, message = caveats(simple(24, 24, 72, n=5))[0]
    assert (code, path) == ("assembly", "components.p.count")
    assert message.startswith("(24 + 72)/5 = 19.2 is not whole")
    assert codes(simple(24, 24, 72, n=4)) == []


def test_stepped_set_assembly() -> None:
    # (z_s z_p2 + z_r z_p1)/(n gcd(z_p1, z_p2)) = (18·18 + 72·36)/(n·18) = 162/n: whole
    # for n = 3, 162/4 = 40.5 for n = 4 (whose tips still clear: 38 < 54 sin 45° = 38.18)
    assert codes(stepped(18, 36, 18, 72, n=3)) == []
    code, path, message = caveats(stepped(18, 36, 18, 72, n=4))[0]
    assert (code, path) == ("assembly", "components.p1.count")
    assert "= 40.5 is not whole" in message


def test_double_planet_assembly() -> None:
    # a double planet turns its outer planet the other way: (z_r − z_s)/n whole;
    # (75 − 30)/3 = 15 (models/planetary_double_planet.yaml), (75 − 30)/4 = 11.25
    assert codes(double_planet(30, 15, 15, 75, n=3)) == []
    code, path, message = caveats(double_planet(30, 15, 15, 75, n=4))[0]
    assert (code, path) == ("assembly", "components.a.count")
    assert message.startswith("(75 − 30)/4 = 11.25 is not whole")


def test_planets_carrying_a_stage_are_phased() -> None:
    # RV-40E: the planets are cranks carrying the discs, every copy identical: z_sun/n
    # whole, 12/2 = 6; a 13-tooth sun (13/2 = 6.5) cannot be assembled
    rv = load_model(MODELS[[p.stem for p in MODELS].index("rv40e")])
    assert rv.warnings == ()
    import yaml
    doc = yaml.safe_load(MODELS[[p.stem for p in MODELS].index("rv40e")].read_text())
    doc["components"][1] = {"teeth": 13}
    code, path, message = caveats(doc)[0]
    assert (code, path) == ("assembly", "components.2.count") and "13/2 = 6.5" in message


# --- neighbours ---------------------------------------------------------------------------
def test_neighbouring_planets_collide() -> None:
    # 12/30/72, a = 21 modules: 4 planets' axes 2·21·sin 45° = 29.70 apart < tip 32
    code, path, message = caveats(simple(12, 30, 72, n=4))[0]
    assert (code, path) == ("planet-clearance", "components.p.count")
    assert "tip diameter 32 modules ≥ 2·a·sin(π/4) = 29.7 modules" in message
    assert codes(simple(12, 30, 72, n=3)) == []     # 2·21·sin 60° = 36.37 > 32


def test_neighbouring_planets_in_mm_with_a_module() -> None:
    # 18/27/72 at module 2 mm: a = 2·(18 + 27)/2 = 45 mm, tip d_a = 2·(27 + 2) = 58 mm;
    # 5 planets: 2·45·sin 36° = 52.90 mm < 58 (and (18 + 72)/5 = 18 assembles); 3 planets:
    # 2·45·sin 60° = 77.94 mm clears (and 90/3 = 30)
    doc = simple(18, 27, 72, n=5)
    for link in doc["links"][:2]:
        link["geometry"] = {"module": 2}
    code, path, message = caveats(doc)[0]
    assert (code, path) == ("planet-clearance", "components.p.count")
    assert "tip diameter 58 mm ≥ 2·a·sin(π/5) = 52.9 mm" in message
    doc["components"]["p"]["count"] = 3
    assert codes(doc) == []


# --- internal gears and carriers ----------------------------------------------------------
def test_a_ring_not_marked_internal() -> None:
    # 72 external: sun 24 + 24 = 48 but 72 + 24 = 96; as a ring 72 − 24 = 48 fits
    found = caveats(simple(24, 24, 72, internal=False))
    assert [(c, p) for c, p, _ in found] == [("ring-not-internal", "components.r")]
    assert "72 − 24 = 48" in found[0][2]
    # 74 external: as a ring 74 − 24 = 50 ≠ 48, but its pitch radius (74 half-modules)
    # reaches beyond the planets' (48 + 24 = 72): a ring all the same (off axis once
    # internal); a 30-tooth gear (30 − 24 = 6 < 48) is no ring, only off axis
    found = caveats(simple(24, 24, 74, internal=False))
    assert [(c, p) for c, p, _ in found] == [("ring-not-internal", "components.r")]
    assert "surrounds the planets' (48 + 24 = 72)" in found[0][2]
    assert codes(simple(24, 24, 30, internal=False))[0] == "coaxiality"


def test_a_planet_meshing_with_and_without_its_carrier() -> None:
    code, path, message = caveats(simple(24, 24, 72, sun_carrier=False))[0]
    assert (code, path) == ("planet-carrier", "links[0].carrier")
    assert "write carrier: c" in message


def test_a_held_carrier_is_the_frame_for_its_planets() -> None:
    # the carrier fixed to the frame: the sun mesh on the frame is on the same body
    doc = simple(24, 24, 72, sun_carrier=False)
    doc["links"][2] = {"type": "fixed", "between": ["c", 0]}
    doc["ports"][1] = {"component": "r", "role": "output"}
    assert codes(doc) == []


def without_carriers(doc: dict, *indices: int) -> dict:
    for index in indices:
        del doc["links"][index]["carrier"]
    return doc


def bundled(stem: str) -> dict:
    import yaml
    return yaml.safe_load(MODELS[[p.stem for p in MODELS].index(stem)].read_text())


def test_a_ring_without_carrier_is_warned_with_the_carrier_to_write() -> None:
    # models/planetary_2kh_sun_to_carrier.yaml without its two carrier keys: both meshes
    # are fixed-axis pairs; the planet is borne by the carrier (links[3]: [planet, carrier])
    found = caveats(without_carriers(bundled("planetary_2kh_sun_to_carrier"), 0, 1))
    assert [(c, p) for c, p, _ in found] == [("ring-without-carrier", "links[1]")]
    assert found[0][2] == (
        "mesh planet-ring has no carrier, so it is a fixed-axis pair (both axes held by the "
        "housing), but ring is internal: a ring nearly always meshes planets, whose axes "
        "turn with their carrier; planet is borne by carrier (links[3]): write carrier: "
        "carrier, here and on links[0]")


def test_one_carrier_left_out_is_told_once() -> None:
    # the other mesh keeps carrier: the planet meshes with and without it (planet-carrier),
    # which already says what to write: no second warning on the ring mesh
    for index in (0, 1):
        found = caveats(without_carriers(bundled("planetary_2kh_sun_to_carrier"), index))
        assert [(c, p) for c, p, _ in found] == [("planet-carrier",
                                                  f"links[{index}].carrier")]


def test_a_ring_without_carrier_meshing_several_planets_and_no_bearing() -> None:
    # no bearing to guess from; count 3 says planets (or a star set on fixed axes)
    found = caveats(without_carriers(simple(24, 24, 72), 0, 1))
    assert [(c, p) for c, p, _ in found] == [("ring-without-carrier", "links[1]")]
    assert found[0][2].endswith("write carrier: <the planets' carrier>, or, if p turns on "
                                "a fixed axis, give it a bearing on the housing (type: "
                                "bearing, between: [p, 0])")


def test_a_single_gear_borne_by_a_carrier_is_a_planet() -> None:
    # one gear (count 1) in a ring, mounted on an eccentric H (a K-H-V stage written
    # without its carrier): the bearing [p, H] says its axis turns with H
    doc = {"name": "khv", "components": {0: {"role": "frame"}, "p": {"teeth": 40},
                                         "r": {"teeth": 45, "internal": True}, "H": {}},
           "links": [{"type": "mesh", "between": ["r", "p"]},
                     {"type": "fixed", "between": ["r", 0]},
                     {"type": "bearing", "between": ["p", "H"]}],
           "ports": [{"component": "H", "role": "input"}, {"component": "p", "role": "output"}]}
    found = caveats(doc)
    assert [(c, p) for c, p, _ in found] == [("ring-without-carrier", "links[0]")]
    assert found[0][2].startswith("mesh p-r has no carrier")
    assert found[0][2].endswith("p is borne by H (links[2]): write carrier: H")


def test_internal_pairs_on_fixed_axes_are_not_warned() -> None:
    # a star set: its 3 gears on housing bearings; a carrier fixed to the frame, written
    # (a held carrier); a single pinion inside a ring with no sign of a moving axis
    star = without_carriers(simple(24, 24, 72), 0, 1)
    star["links"].append({"type": "bearing", "between": ["p", 0]})
    assert codes(star) == []
    held = simple(24, 24, 72)
    held["links"][2] = {"type": "fixed", "between": ["c", 0]}
    held["ports"][1] = {"component": "r", "role": "output"}
    assert codes(held) == []
    pair = {"name": "internal pair", "components": {0: {"role": "frame"}, 1: {"teeth": 20},
                                                    2: {"teeth": 60, "internal": True}},
            "links": [{"type": "mesh", "between": [1, 2]}],
            "ports": [{"component": 1, "role": "input"}, {"component": 2, "role": "output"}]}
    assert codes(pair) == []
    pair["links"].append({"type": "bearing", "between": [1, 0]})
    assert codes(pair) == []


# --- undercut -----------------------------------------------------------------------------
def pair(geometry: dict) -> dict:
    return {"name": "pair", "components": {0: {"role": "frame"}, 1: {"teeth": 14},
                                           2: {"teeth": 14}},
            "links": [{"type": "mesh", "between": [1, 2], "geometry": geometry}],
            "ports": [{"component": 1, "role": "input"}, {"component": 2, "role": "output"}]}


def test_undercut_needs_a_shift() -> None:
    # 14 < 2/sin²20° = 17.10: both unshifted 14-tooth gears are undercut; a shift of
    # 1 − 14 sin²20°/2 = 0.181 is needed. With x = 0.2: 2·0.8/sin²20° = 13.68 < 14.
    found = caveats(pair({"module": 2}))
    assert [(c, p) for c, p, _ in found] == [("undercut", "links[0].geometry")] * 2
    assert "fewer than 2·(h_a* − x)·cos β/sin²α_t = 17.1 teeth" in found[0][2]
    assert "at least 0.181" in found[0][2]
    assert codes(pair({"module": 2, "shifts": [0.2, 0.2]})) == []


def test_khv_stages_are_not_2kh_sets() -> None:
    # planets with a coupling (K-H-V) are left alone: two 40-tooth planets in a 45 ring
    # would "collide" as 2K-H planets (tip 42 > 5 sin 90°, a = 45 − 40 half-modules).
    # (Bevel gears, meshes by ratio: models/bevel_differential.yaml, bundled-model test.)
    doc = {"name": "khv", "components": {0: {"role": "frame"}, "p": {"teeth": 40, "count": 2},
                                         "r": {"teeth": 45, "internal": True}, "out": {}},
           "links": [{"type": "mesh", "between": ["p", "r"], "carrier": "H"},
                     {"type": "fixed", "between": ["r", 0]},
                     {"type": "coupling", "between": ["p", "out"]}],
           "ports": [{"component": "H", "role": "input"}, {"component": "out", "role": "output"}]}
    doc["components"]["H"] = {}
    assert codes(doc) == []


# --- profile-shifted sets -----------------------------------------------------------------
# Sun 22, planet 24, ring 71 (3 planets, (22 + 71)/3 = 31 assembles) at module 2 mm: as
# standard gears the sun pair sits at 2·(22 + 24)/2 = 46 mm, the ring pair at
# 2·(71 − 24)/2 = 47 mm. Shifted to a common 47 mm: the ring pair keeps its standard
# distance with x_r − x_p = 0; the sun pair needs cos α_w = 46 cos 20°/47 = 0.919699,
# α_w = 23.1179°, and x_s + x_p = (inv α_w − inv 20°)·46/(2 tan 20°)
# = (0.0234218 − 0.0149044)·46/0.727940 = 0.53824. With x_p = x_r = 0.2: x_s = 0.33824,
# which a drawing writes 0.338 (then 0.41 µm off 47 mm, within 0.001·m = 2 µm).
def inv(angle: float) -> float:
    return math.tan(angle) - angle


def shifted(sun: dict, ring: dict) -> dict:
    doc = simple(22, 24, 71)
    doc["links"][0]["geometry"], doc["links"][1]["geometry"] = sun, ring
    return doc


def test_shift_sum_from_the_formulas() -> None:
    alpha = math.radians(20)
    cos_w = 46 * math.cos(alpha) / 47
    alpha_w = math.acos(cos_w)
    total = (inv(alpha_w) - inv(alpha)) * 46 / (2 * math.tan(alpha))
    assert (round(cos_w, 6), round(math.degrees(alpha_w), 4)) == (0.919699, 23.1179)
    assert (round(inv(alpha_w), 7), round(inv(alpha), 7)) == (0.0234218, 0.0149044)
    assert total == pytest.approx(0.53824, abs=1e-5)


def test_a_standard_coaxial_set_in_mm() -> None:
    # 24/24/72 at module 2: 2·(24 + 24)/2 = 48 = 2·(72 − 24)/2 mm, unshifted or stated
    doc = simple(24, 24, 72)
    doc["links"][0]["geometry"] = doc["links"][1]["geometry"] = {"module": 2}
    assert codes(doc) == []
    doc["links"][0]["geometry"] = doc["links"][1]["geometry"] = {
        "module": 2, "centre_distance": "48 mm"}
    model = model_from_dict(doc)
    assert model.warnings == ()
    assert [link.blocks["geometry"].shift_sum for link in model.links[:2]] == [0.0, 0.0]


def test_shifts_make_a_non_standard_set_coaxial() -> None:
    assert caveats(simple(22, 24, 71))[0][2].startswith("sun 22 + 2 × planet 24 = 70 ≠ ring 71")
    exact = 0.53824 - 0.2
    for x_s in (exact, 0.338):
        assert codes(shifted({"module": 2, "shifts": [x_s, 0.2]},
                             {"module": 2, "shifts": [0.2, 0.2]})) == []


def test_a_wrong_shift_names_both_centre_distances() -> None:
    # x_s = 0.3: inv α_w = 0.0149044 + 2 tan 20°·(0.3 + 0.2)/46 = 0.0228168, α_w = 22.9259°,
    # a_w = 46 cos 20°/cos α_w = 46.9331 mm, 66.9 µm short of the ring pair's 47 mm
    found = caveats(shifted({"module": 2, "shifts": [0.3, 0.2]},
                            {"module": 2, "shifts": [0.2, 0.2]}))
    assert [(c, p) for c, p, _ in found] == [("coaxiality", "links[0..1]")]
    assert found[0][2] == (
        "the working centre distances of planet p's meshes differ: links[0] 46.9331 mm "
        "(shifts 0.3, 0.2); links[1] 47.0000 mm (shifts 0.2, 0.2); 66.9 µm apart, more "
        "than 0.001 module = 2 µm: the planets cannot share the axis of the central gears")


def test_a_centre_distance_states_the_shifted_set() -> None:
    # both pairs at 47 mm: the sun pair's shift sum is the 0.53824 above, the ring pair's 0
    at_47 = {"module": 2, "centre_distance": "47 mm"}
    model = model_from_dict(shifted(at_47, at_47))
    assert model.warnings == ()
    sums = [link.blocks["geometry"].shift_sum for link in model.links[:2]]
    assert sums[0] == pytest.approx(0.53824, abs=1e-5) and sums[1] == pytest.approx(0, abs=1e-12)
    found = caveats(shifted(at_47, {"module": 2, "centre_distance": 47.5}))
    assert [(c, p) for c, p, _ in found] == [("coaxiality", "links[0..1]")]
    assert ("links[0] 47.0000 mm (its centre_distance); links[1] 47.5000 mm (its "
            "centre_distance); 500.0 µm apart" in found[0][2])


def test_a_centre_distance_must_be_the_shifts_own() -> None:
    assert codes(shifted({"module": 2, "shifts": [0.338, 0.2], "centre_distance": 47},
                         {"module": 2, "centre_distance": 47})) == []
    with pytest.raises(ModelError) as error:
        model_from_dict(shifted({"module": 2, "shifts": [0.3, 0.2], "centre_distance": 47},
                                {"module": 2, "centre_distance": 47}))
    assert error.value.path == "links[0].geometry.centre_distance"
    assert ("the shifts [0.3, 0.2] put the pair at a working centre distance of 46.9331 mm, "
            "not 47.0000 mm (66.9 µm apart" in str(error.value))


def test_a_centre_distance_no_shift_reaches_is_refused() -> None:
    # 52 mm needs x_s + x_p = 4.07 (each shift at most 2); 40 mm is inside the base
    # circles' 46 cos 20° = 43.2259 mm
    for distance, words in ((52, "it needs x1 + x2 = 4.0689, and no split of it"),
                            (40, "not beyond the base circles' 43.2259 mm")):
        with pytest.raises(ModelError) as error:
            model_from_dict(shifted({"module": 2, "centre_distance": distance}, {"module": 2}))
        assert error.value.path == "links[0].geometry.centre_distance"
        assert words in str(error.value)


def test_friction_needs_the_shifts_off_the_standard_distance() -> None:
    doc = shifted({"module": 2, "centre_distance": 47}, {"module": 2, "centre_distance": 47})
    doc["links"][0]["friction"] = {"mu": 0.05}
    with pytest.raises(ModelError) as error:
        model_from_dict(doc)
    assert error.value.path == "links[0].geometry.centre_distance"
    assert "the sum x1 + x2 = 0.5382: give shifts" in str(error.value)
    doc["links"][0]["geometry"]["shifts"] = [0.338, 0.2]
    assert model_from_dict(doc).warnings == ()


def test_a_planet_has_one_shift() -> None:
    # the ring pair at x_p = x_r = 0.3 is still at 47 mm (x_r − x_p = 0), but the planet
    # has shift 0.2 in the sun pair: one gear, two profiles
    found = caveats(shifted({"module": 2, "shifts": [0.338, 0.2]},
                            {"module": 2, "shifts": [0.3, 0.3]}))
    assert [(c, p) for c, p, _ in found] == [("gear-profile", "links[1].geometry")]
    assert found[0][2].startswith("gear p has shift 0.2 in links[0].geometry but 0.3 here")


def test_one_shifted_mesh_of_a_standard_set() -> None:
    # 24/24/72: the sun shifted by 0.5 in the sun pair's block moves it off 48 mm; the
    # ring pair without a block is unshifted at module 2 (the planet's, from that block)
    doc = simple(24, 24, 72)
    doc["links"][0]["geometry"] = {"module": 2, "shifts": [0.5, 0]}
    found = caveats(doc)
    assert [(c, p) for c, p, _ in found] == [("coaxiality", "links[0..1]")]
    assert "links[1] 48.0000 mm (unshifted, module 2)" in found[0][2]


def test_a_centre_distance_that_leaves_a_gear_undercut() -> None:
    # 14/14 at module 1: each gear needs x >= 1 − 14 sin²20°/2 = 0.1812 against undercut,
    # so x1 + x2 >= 0.3623. 14.5 mm needs 0.5603 (a clean split exists), 14.3 mm 0.3226
    assert codes(pair({"module": 1, "centre_distance": 14.5})) == []
    found = caveats(pair({"module": 1, "centre_distance": 14.3}))
    assert [(c, p) for c, p, _ in found] == [("undercut", "links[0].geometry")]
    assert found[0][2].startswith("every split of the shift sum x1 + x2 = 0.3226")
