"""Volume analysis, Pan & Wang 2019: every formula against a hand computation,
the polygon areas against closed forms, and the pitch-circle error for z = 12…80.

Expected values are written out as arithmetic from the paper's printed equations (with the
reading documented in powergraph/analyses/volume/formulas.py), from closed forms, or from
the model file's numbers — never pasted from the code's output.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from scipy.special import ellipe

from powergraph.analyses import volume as vol
from powergraph.errors import ModelError
from powergraph.model import load_model, loads_model

ROOT = Path(__file__).resolve().parents[2]
RV40E = ROOT / "models" / "rv40e_wang2021.yaml"
PI = math.pi
ALPHA = math.radians(20)


def inv(angle: float) -> float:
    return math.tan(angle) - angle


# --- Eqs. (1)–(7) against the printed equations -----------------------------------------

def test_eq1_eq2_gear_is_exactly_pitch_cylinder_minus_bore() -> None:
    m, z, b, r = 2.5, 17, 14.0, 6.0
    assert vol.gear_volume(m, z, b, r) == pytest.approx(PI * b * (m**2 * z**2 / 4 - r**2),
                                                        rel=1e-15)
    assert vol.gear_volume(1.0, 20, 10.0, 0.0) == pytest.approx(1000 * PI, rel=1e-15)


def test_eq3_cycloid_disc_as_printed_with_the_paper_counts() -> None:
    B2, rp, rrp, r8, a, r3, r4 = 12.0, 80.0, 4.0, 7.0, 1.5, 20.0, 18.0
    printed = PI * B2 * ((rp - rrp)**2 - 6 * (r8 + a)**2 - 2 * r3**2 - r4**2)
    got = vol.cycloid_disc_volume(B2, rp, rrp, a, r3, 2, r8, 6, r4)
    assert got == pytest.approx(printed, rel=1e-14)
    # by hand: 76² − 6·8.5² − 2·20² − 18² = 5776 − 433.5 − 800 − 324 = 4218.5
    assert got == pytest.approx(PI * 12 * 4218.5, rel=1e-14)


def test_eq3_outer_radius_is_the_mean_of_tip_and_root() -> None:
    # "average circle method": tip r_p + a − r_rp, root r_p − a − r_rp, mean r_p − r_rp
    rp, rrp, a = 64.0, 3.0, 1.3
    mean = ((rp + a - rrp) + (rp - a - rrp)) / 2
    solid = vol.cycloid_disc_volume(1.0, rp, rrp, a, 1.0, 0, 1.0, 0, 0.0)
    assert solid == pytest.approx(PI * mean**2, rel=1e-14)


def test_eq4_needle_gear_as_printed_and_as_read() -> None:
    B2, t, rp, rrp, z3 = 10.0, 8.0, 64.0, 3.0, 40
    printed = PI * B2 * (4 * t * rp + 2 * t**2 + rrp**2 * z3)
    # reading: a shell r_p … r_p + t and half of each pin, both over 2·B2
    reading = 2 * B2 * (PI * ((rp + t)**2 - rp**2) + z3 * PI * rrp**2 / 2)
    got = vol.needle_gear_volume(2 * B2, rp, rrp, t, z3)
    assert got == pytest.approx(printed, rel=1e-14)
    assert got == pytest.approx(reading, rel=1e-14)
    assert got == pytest.approx(PI * 10 * (2048 + 128 + 360), rel=1e-14)   # = 25360 π


def test_eq5_crankshaft_with_alpha_read_as_r() -> None:
    r2, B1, B3, r5, B2 = 9.0, 11.0, 8.0, 12.0, 9.5
    printed = PI * r2**2 * (B1 + 2 * B3) + 2 * PI * r5**2 * B2
    assert vol.crankshaft_volume(r2, B1, B3, r5, B2, 2) == pytest.approx(printed, rel=1e-14)
    # 81·27 + 2·144·9.5 = 2187 + 2736 = 4923
    assert vol.crankshaft_volume(r2, B1, B3, r5, B2, 2) == pytest.approx(4923 * PI, rel=1e-14)


def test_eq6_planet_frame_1() -> None:
    r6, B4, r7, B3 = 55.0, 14.0, 17.0, 10.0
    printed = PI * r6**2 * B4 - 2 * PI * r7**2 * B3
    assert vol.planet_frame_1_volume(r6, B4, r7, B3, 2) == pytest.approx(printed, rel=1e-14)
    assert printed == pytest.approx(PI * (3025 * 14 - 2 * 289 * 10))        # 36570 π


def test_eq7_planet_frame_2_as_printed() -> None:
    r9, r6, B4, r7, B3, r8, B2, m1, z1, z2, B1 = 50, 55, 14, 17, 10, 6, 9, 1.25, 12, 36, 12
    printed = (PI * r9**2 * (B1 + B3 - B4) + 12 * PI * B2 * r8**2 + PI * r6**2 * B4
               - (PI / 4 * m1**2 * (z1**2 + 2 * z2**2) * B1 + 2 * PI * r7**2 * B3
                  + PI / 4 * m1**2 * z1**2 * B3))
    got = vol.planet_frame_2_volume(r9, r6, B4, r7, B3, 2, r8, 6, 2 * B2, m1, z1, z2, 2, B1)
    assert got == pytest.approx(printed, rel=1e-13)


# --- the RV-40E model: each part by hand from the numbers in models/rv40e_wang2021.yaml ------------

RV40E_BY_HAND = {            # one part, / π
    "1": 12 * (1.5**2 * 12**2 / 4 - 0**2),                      # 972
    "2": 12 * (1.5**2 * 36**2 / 4 - 10**2),                     # 7548
    "3": 10**2 * (12 + 2 * 12) + 2 * 13**2 * 10,                # 6980
    "4": 10 * ((64 - 3)**2 - 2 * (9 + 1.3)**2 - 2 * 17**2 - 15**2),   # 27058.2
    "5": 20 * ((64 + 10)**2 - 64**2 + 40 * 3**2 / 2),           # 31200
    "6": 58**2 * 14 - 2 * 18.5**2 * 12,                         # 38882
    "7": (50**2 * (12 + 12 - 14) + 2 * 9**2 * 20 + 58**2 * 14
          - (1.5**2 / 4 * (12**2 + 2 * 36**2) * 12 + 2 * 18.5**2 * 12
             + 1.5**2 / 4 * 12**2 * 12)),                       # 47682
}
RV40E_COUNTS = {"1": 1, "2": 2, "3": 2, "4": 2, "5": 1, "6": 1, "7": 1}


@pytest.fixture(scope="module")
def rv40e():
    model = load_model(RV40E)
    return model, vol.volume(model)


def test_rv40e_each_component_by_hand(rv40e) -> None:
    _, result = rv40e
    assert list(result.components) == list(RV40E_BY_HAND)
    for cid, by_hand in RV40E_BY_HAND.items():
        part = result.components[cid]
        assert part.unit_mm3 == pytest.approx(PI * by_hand, rel=1e-13), cid
        assert part.count == RV40E_COUNTS[cid]
        assert part.volume_mm3 == pytest.approx(PI * by_hand * RV40E_COUNTS[cid], rel=1e-13)


def test_rv40e_sun_and_planet_exactly_pi_b_m2z2_over_4_minus_r2(rv40e) -> None:
    _, result = rv40e
    assert result.components["1"].unit_mm3 == pytest.approx(PI * 12 * 81, rel=1e-15)
    assert result.components["2"].unit_mm3 == pytest.approx(PI * 12 * (729 - 100), rel=1e-15)


def test_rv40e_total_is_eq8(rv40e) -> None:
    _, result = rv40e
    v = {cid: PI * x for cid, x in RV40E_BY_HAND.items()}
    n = 2
    eq8 = v["1"] + n * v["2"] + 2 * v["4"] + v["5"] + n * v["3"] + v["6"] + v["7"]
    assert result.total_mm3 == pytest.approx(eq8, rel=1e-13)
    assert eq8 == pytest.approx(PI * 201908.4, rel=1e-12)      # ≈ 634 314 mm³ ≈ 0.634 L
    data = result.to_dict()
    assert data["total_mm3"] == pytest.approx(eq8, rel=1e-13)
    assert data["components"] == {cid: pytest.approx(p.volume_mm3)
                                  for cid, p in result.components.items()}


def test_model_volume_is_none_without_geometry_and_volume_raises() -> None:
    text = RV40E.read_text()
    plain = load_model(ROOT / "models" / "rv40e_wang2021.yaml")
    assert vol.model_volume(plain) is not None
    bare = loads_model(text.split("components:")[0] + """components:
  0: {role: frame}
  1: {teeth: 12}
  2: {teeth: 36}
links: [{type: mesh, between: [1, 2], carrier: 0}]
ports: [{component: 1, role: input}, {component: 2, role: output}]
""")
    assert vol.model_volume(bare) is None
    with pytest.raises(ModelError) as info:
        vol.volume(bare)
    assert info.value.path == "components" and "no component has a geometry" in str(info.value)


def test_power_density_in_kw_per_litre(rv40e) -> None:
    _, result = rv40e
    assert vol.power_density(2270.0, 1e6) == pytest.approx(2.27)
    assert result.power_density(2270.0) == pytest.approx(2.27 / (PI * 201908.4 * 1e-6))
    assert vol.POWER_DENSITY_UNIT == "kW/L"
    from powergraph.analyses.volume import model_volume

    assert model_volume is vol.model_volume


# --- analysis errors ----------------------------------------------------------------------

TWO_GEARS = """
name: pair
components:
  0: {role: frame}
  1: {teeth: 12, INTERNAL geometry: {shape: gear, module: 1.5, face_width: 12, bore_radius: BORE}}
  2: {teeth: 36, count: 2}
  7: {geometry: FRAME}
links: [{type: mesh, between: [1, 2], carrier: 7}, {type: fixed, between: [7, 0]}]
ports: [{component: 1, role: input}, {component: 2, role: output}]
"""
FRAME2 = ("{shape: planet_frame_2, seal_radius: 50, bearing_seat_radius: 58, bearing_width: "
          "BW, crank_bearing_radius: 18.5, crank_bearing_width: 12, crank_bearings: 2, "
          "pillar_radius: 9, pillars: 2, pillar_length: 20, sun: SUN, planet: 2}")


def pair(bore="0", internal="", bw="14", sun="1"):
    frame = FRAME2.replace("BW", bw).replace("SUN", sun)
    return loads_model(TWO_GEARS.replace("BORE", bore).replace("INTERNAL ", internal)
                       .replace("FRAME", frame))


def test_frame2_reads_teeth_and_planet_count_from_the_model() -> None:
    result = vol.volume(pair())
    # same frame as the RV-40E: planets = count of component 2 = 2
    assert result.components["7"].unit_mm3 == pytest.approx(PI * RV40E_BY_HAND["7"], rel=1e-13)


@pytest.mark.parametrize("kwargs, path, words", [
    ({"bore": "7.125"}, "components.1.geometry.bore_radius", "root radius"),
    ({"internal": "internal: true, "}, "components.1.geometry.shape", "external"),
    ({"sun": "9"}, "components.7.geometry.sun", "unknown component"),
    ({"sun": "2"}, "components.7.geometry.sun", "gear geometry"),
    ({"bw": "24"}, "components.7.geometry.bearing_width", "B1 + B3 − B4"),
])
def test_analysis_errors_name_the_place(kwargs, path, words) -> None:
    with pytest.raises(ModelError) as info:
        vol.volume(pair(**kwargs))
    assert info.value.path == path
    assert words in info.value.message


def test_holes_larger_than_the_part_are_an_error() -> None:
    model = loads_model("""
name: disc
components:
  0: {role: frame}
  1: {teeth: 39, geometry: {shape: cycloid_disc, width: 10, pin_circle_radius: 64,
      pin_radius: 3, eccentricity: 1.3, crank_hole_radius: 30, crank_holes: 5,
      pillar_radius: 9, pillar_holes: 2, center_bore_radius: 15}}
  2: {teeth: 40, internal: true}
links: [{type: mesh, between: [1, 2], carrier: 0}]
ports: [{component: 1, role: input}, {component: 2, role: output}]
""")
    # 61² − 2·10.3² − 5·30² − 15² = 3721 − 212.18 − 4500 − 225 < 0
    with pytest.raises(ModelError, match="holes and pockets are larger"):
        vol.volume(model)


# --- shoelace --------------------------------------------------------------------------------

def test_shoelace_simple_shapes() -> None:
    assert vol.shoelace_area([0, 3, 3, 0], [0, 0, 2, 2]) == pytest.approx(6.0)
    assert vol.shoelace_area([0, 0, 3, 3], [0, 2, 2, 0]) == pytest.approx(6.0)   # clockwise
    assert vol.shoelace_area([1e6, 1e6 + 4, 1e6], [5e5, 5e5, 5e5 + 3]) == pytest.approx(6.0)
    # an L shape: 2×2 square minus 1×1 corner
    assert vol.shoelace_area([0, 2, 2, 1, 1, 0], [0, 0, 1, 1, 2, 2]) == pytest.approx(3.0)


@pytest.mark.parametrize("n", [3, 4, 6, 100, 10_000])
def test_shoelace_regular_polygon_and_circle_limit(n) -> None:
    angles = np.linspace(0, 2 * PI, n, endpoint=False)
    area = vol.shoelace_area(2 * np.cos(angles), 2 * np.sin(angles))
    assert area == pytest.approx(n / 2 * 4 * math.sin(2 * PI / n), rel=1e-12)
    if n >= 10_000:
        assert area == pytest.approx(4 * PI, rel=1e-6)


# --- exact involute profile ------------------------------------------------------------------

@pytest.mark.parametrize("z", [12, 40, 80])
def test_space_at_the_pitch_circle_is_half_a_pitch(z) -> None:
    assert vol.space_half_angle(z, [z / 2])[0] == pytest.approx(PI / (2 * z), abs=1e-7)


def test_flank_is_the_involute_above_the_form_circle() -> None:
    z = 40
    rb = z / 2 * math.cos(ALPHA)
    # form circle: lowest straight-flank point of the rack is 1.25 − 0.38(1 − sin α) ≈ 1.0
    # below the pitch line; contact d = 1.0/sin α below the pitch point on the line of action
    h = 1.25 - 0.38 * (1 - math.sin(ALPHA))
    d = h / math.sin(ALPHA)
    form = math.sqrt((z / 2)**2 + d**2 - 2 * (z / 2) * d * math.sin(ALPHA))
    radii = np.linspace(form + 0.01, z / 2 + 1.0, 25)
    expected = [PI / (2 * z) - inv(ALPHA) + inv(math.acos(rb / r)) for r in radii]
    assert vol.space_half_angle(z, radii) == pytest.approx(expected, abs=1e-7)


@pytest.mark.parametrize("z", [12, 30, 80])
def test_root_land_is_the_flat_of_the_rack_tip(z) -> None:
    # rack tip flat half width: x_c = π/4 + (−1.25 + 0.38) tan α − 0.38/cos α (unit module)
    xc = PI / 4 + (-1.25 + 0.38) * math.tan(ALPHA) - 0.38 / math.cos(ALPHA)
    assert xc == pytest.approx(0.0644, abs=1e-4)
    assert vol.space_half_angle(z, [z / 2 - 1.25])[0] == pytest.approx(xc / (z / 2), rel=1e-9)


def test_undercut_below_z17_only() -> None:
    """Undercut limit z = 2h/sin²α with h ≈ 1.0 the depth of the rack's straight flank:
    17.1. Below it the trochoid cuts into the involute just above the base circle (space
    wider than the involute's); above it the flank stops at a form circle outside the base
    circle and the fillet there is narrower than the involute's continuation."""
    h = 1.25 - 0.38 * (1 - math.sin(ALPHA))
    assert 2 * h / math.sin(ALPHA)**2 == pytest.approx(17.1, abs=0.01)

    def widening(z):
        rb = z / 2 * math.cos(ALPHA)
        r = rb + 1e-4
        return (vol.space_half_angle(z, [r])[0]
                - (PI / (2 * z) - inv(ALPHA) + inv(math.acos(rb / r))))
    assert widening(12) > 1e-5
    assert widening(16) > 1e-6
    assert widening(18) < -1e-7
    assert widening(20) < -1e-7


@pytest.mark.parametrize("z", [12, 20, 40, 80])
def test_profile_area_lies_between_root_and_tip_circles(z) -> None:
    area = vol.profile_area(1.0, z)
    assert PI * (z / 2 - 1.25)**2 < area < PI * (z / 2 + 1.0)**2
    assert area < PI * (z / 2)**2                  # more space below pitch than tooth above


def test_profile_area_scales_with_module_squared_and_converges() -> None:
    assert vol.profile_area(2.5, 30) == pytest.approx(6.25 * vol.profile_area(1.0, 30),
                                                      rel=1e-14)
    coarse = vol.profile_area(1.0, 20, radial_points=600)
    fine = vol.profile_area(1.0, 20, radial_points=2400, arc_step=2.5e-4)
    assert coarse == pytest.approx(fine, rel=2e-7)


def test_outline_polygon_matches_the_polar_integral() -> None:
    # A = π r_f² + ∫ (2π − 2 z ψ(R)) R dR over root…tip: independent of the polygon assembly
    z = 24
    rf, ra = z / 2 - 1.25, z / 2 + 1.0
    u = np.linspace(0, 1, 4001)
    radii = rf + (ra - rf) * u**2
    integrand = (2 * PI - 2 * z * vol.space_half_angle(z, radii)) * radii
    integral = PI * rf**2 + np.sum((integrand[1:] + integrand[:-1]) / 2 * np.diff(radii))
    assert vol.profile_area(1.0, z) == pytest.approx(integral, rel=1e-6)


def test_rack_limit_of_the_pitch_circle_error() -> None:
    """For z → ∞ each tooth pitch gives a fixed deficit, the basic rack's:
    space below the pitch line (trapezoid 1.25·(π/2 − 1.25 tan α) minus two fillet corners
    ρ²[cot(γ/2) − (π − γ)/2], γ = 90° + α, ρ = 0.38) minus tooth above it (π/2 − tan α)."""
    gamma = PI / 2 + ALPHA
    corner = 0.38**2 * (1 / math.tan(gamma / 2) - (PI - gamma) / 2)
    space = 1.25 * (PI / 2 - 1.25 * math.tan(ALPHA)) - 2 * corner
    tooth = PI / 2 - math.tan(ALPHA)
    per_tooth = space - tooth
    assert per_tooth == pytest.approx(0.16216, abs=1e-5)

    def deficit(z):
        return (vol.pitch_circle_area(1.0, z) - vol.profile_area(1.0, z)) / z
    extrapolated = 2 * deficit(1000) - deficit(500)       # Richardson: removes the 1/z term
    assert extrapolated == pytest.approx(per_tooth, rel=2e-3)
    # hence error(z) ≈ (4/π)·0.1622/z for large z
    assert vol.pitch_circle_error(1000) == pytest.approx(4 / PI * per_tooth / 1000, rel=0.02)


def test_pitch_circle_error_table_z12_to_80(capsys) -> None:
    table = vol.pitch_circle_errors(range(12, 81))
    assert table.teeth == tuple(range(12, 81))
    errors = np.array(table.relative_error)
    with capsys.disabled():
        print("\npitch-circle volume error, (π(mz/2)² − A_exact)/A_exact:")
        for z in (12, 15, 17, 20, 25, 30, 36, 40, 50, 60, 70, 80):
            print(f"  z = {z:2d}: {100 * errors[z - 12]:.3f} %")
    assert np.all(errors > 0) and np.all(np.diff(errors) < 0)
    # the per-tooth deficit z·e·π/4 falls towards the rack value 0.1622 from above
    per_tooth = errors * np.array(table.teeth) * PI / 4
    assert np.all(per_tooth > 0.1622)
    assert np.all(np.diff(per_tooth[6:]) < 0)        # monotone once out of the undercut range
    data = table.to_dict()
    assert data["pitch_area_mm2_per_m2"][0] == pytest.approx(PI * 36)


def test_rv40e_gears_get_the_exact_outline_volume(rv40e) -> None:
    model, result = rv40e
    sun, planet = result.components["1"], result.components["2"]
    assert sun.exact_unit_mm3 == pytest.approx(vol.profile_area(1.5, 12) * 12, rel=1e-14)
    assert planet.exact_unit_mm3 == pytest.approx(
        (vol.profile_area(1.5, 36) - PI * 10**2) * 12, rel=1e-14)
    assert sun.profile_error == pytest.approx(vol.pitch_circle_error(12), rel=1e-12)
    assert planet.profile_error > vol.pitch_circle_error(36)    # the bore is exact in both


# --- exact cycloid disc ------------------------------------------------------------------

def cycloid_closed_form(rp, rrp, a, zp):
    """Area inside the pin-centre epitrochoid, π(r_p² + z_p a²), offset inwards by r_rp:
    A − r_rp·L + π r_rp², with L = 4 r_p (1 + K1) E(4K1/(1 + K1)²), K1 = a z_p / r_p."""
    k1 = a * zp / rp
    length = 4 * rp * (1 + k1) * ellipe(4 * k1 / (1 + k1)**2)
    return PI * (rp**2 + zp * a**2) - rrp * length + PI * rrp**2


@pytest.mark.parametrize("rp, rrp, a, zp", [(64, 3, 1.3, 40), (50, 4, 1.5, 20),
                                            (30, 2, 0.5, 12)])
def test_cycloid_outline_area_matches_closed_form(rp, rrp, a, zp) -> None:
    assert vol.cycloid_disc_area(rp, rrp, a, zp) == pytest.approx(
        cycloid_closed_form(rp, rrp, a, zp), rel=1e-5)


def test_cycloid_outline_refuses_impossible_profiles() -> None:
    with pytest.raises(ValueError, match="K1"):
        vol.cycloid_disc_area(64, 3, 1.7, 40)            # 1.7·40/64 > 1
    with pytest.raises(ValueError, match="undercut"):
        vol.cycloid_disc_area(64, 20, 1.3, 40)


def test_rv40e_cycloid_exact_outline_and_eq3_error(rv40e) -> None:
    _, result = rv40e
    disc = result.components["4"]
    holes = PI * (2 * (9 + 1.3)**2 + 2 * 17**2 + 15**2)
    exact = (cycloid_closed_form(64, 3, 1.3, 40) - holes) * 10
    assert disc.exact_unit_mm3 == pytest.approx(exact, rel=1e-5)
    assert abs(disc.profile_error) < 1e-3     # the average circle is good to 0.1 % here
