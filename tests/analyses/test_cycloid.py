"""Cycloid transmission fluctuation: Csobán A. (2021), "Impacts of a Profile Failure of the
Cycloidal Drive of a Planetary Gear on Transmission Gear", Lubricants 9(7): 71.

Expected values come from the paper (its fitted surfaces of Section 5 and its Tables 1 and
3, written in tests/data/published_values.yaml, section ``csoban2021``), the laws of the
geometry described in docs/cycloid.md, or closed forms derived in the tests; never from
this code's own output.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import yaml
from scipy.optimize import brentq

from powergraph.analyses.cycloid import (PAPER_FITS, central_difference_ratio,
                                         cycloid_fluctuation, cycloid_geometry,
                                         fluctuation_study, iso_tolerance,
                                         profile_error_for_grade)
from powergraph.analyses.cycloid.contact import contact_curve
from powergraph.gears.iso286 import GRADE_FACTORS, ISO_286_TABLE
from powergraph.errors import UsageError

CSOBAN = yaml.safe_load((Path(__file__).resolve().parents[1] / "data" /
                         "published_values.yaml").read_text())["csoban2021"]

# ---------------------------------------------------------------- laws of the geometry


@pytest.mark.parametrize("teeth", [9, 25, 117])
def test_zero_error_gives_ratio_z1(teeth: int) -> None:
    r = cycloid_fluctuation(1, teeth, 0.0)
    assert np.max(np.abs(r.ratio - teeth)) < 1e-9
    # ideal drive: the disc turns by exactly -θ/z1
    assert np.max(np.abs(r.output_angle + r.crank_angle / teeth)) < 1e-12
    assert r.max_deviation_percent < 1e-9
    assert np.max(np.abs(r.paper_ratio - teeth)) < 1e-9
    assert r.segments == 0   # the driving pins share the contact: no hand-over


@pytest.mark.parametrize("module, error", [(2, 0.01), (3, 0.0045), (5, 0.05)])
def test_scales_as_d_over_m(module: float, error: float) -> None:
    # Every length of the stage is proportional to m, so Δi(m, d) = Δi(1, d/m) exactly.
    scaled = cycloid_fluctuation(module, 25, error)
    unit = cycloid_fluctuation(1, 25, error / module)
    assert scaled.max_deviation_percent == pytest.approx(unit.max_deviation_percent, rel=1e-9)
    assert np.allclose(scaled.ratio, unit.ratio, rtol=1e-11, atol=0)
    assert np.allclose(scaled.handover_angle, unit.handover_angle, rtol=0, atol=1e-9)


def test_linear_in_d_only_for_small_d_over_m() -> None:
    # Paper §3: a tenth of the error gives about a tenth of the fluctuation.
    small = [cycloid_fluctuation(1, 9, d).max_deviation_percent for d in (1e-4, 1e-3)]
    assert small[1] / small[0] == pytest.approx(10.0, rel=0.01)
    large = [cycloid_fluctuation(1, 9, d).max_deviation_percent for d in (0.01, 0.1)]
    assert abs(large[1] / large[0] - 10.0) > 0.1


@pytest.mark.parametrize("teeth", [9, 43])
def test_fluctuation_repeats_z2_times_per_input_revolution(teeth: int) -> None:
    per_segment = 16
    r = cycloid_fluctuation(1, teeth, 0.01, points_per_segment=per_segment)
    pins = teeth + 1
    assert r.segments == pins
    # hand-overs 2π/z2 apart; the curve shifted by one segment is the same curve
    assert np.allclose(np.diff(r.handover_angle), 2 * np.pi / pins, rtol=0, atol=1e-9)
    assert np.allclose(np.roll(r.ratio, -per_segment), r.ratio, rtol=1e-9, atol=0)
    # each pin carries exactly one segment, in order
    segment_pins = [pin for pin, _, _ in r.contact_segments()]
    assert sorted(segment_pins) == list(range(pins))
    assert all((b - a) % pins == 1 for a, b in zip(segment_pins, segment_pins[1:]))


def test_large_teeth_limit() -> None:
    # For large z1, max Δi → 100π·d/(e·z2) (rack-like contact near the pin whose normal is
    # perpendicular to the line of centres; docs/cycloid.md).
    module, teeth, error = 1, 1001, 0.001
    r = cycloid_fluctuation(module, teeth, error, points_per_segment=4)
    limit = 100 * math.pi * error / ((1 - 0.3) * module / 2 * (teeth + 1))
    assert r.max_deviation_percent == pytest.approx(limit, rel=0.005)


def test_pin_radius_does_not_change_the_motion() -> None:
    # Equidistants add: a pin of radius r_p on the profile offset r_p + d moves like a point
    # on the trochoid offset d. rc only decides whether the profile is undercut.
    thin = cycloid_fluctuation(1, 9, 0.01, rc=0.5)
    thick = cycloid_fluctuation(1, 9, 0.01, rc=1.4)
    assert np.allclose(thin.ratio, thick.ratio, rtol=1e-12, atol=0)


# ---------------------------------------------------------------- the ratio itself


def _pole_point_ratio(module, teeth, error, theta, psi, pin, shift=0.3):
    """Paper Eqs. (6)–(8), by hand: i = r_g/e, r_g = |C − pole|, the pole where the contact
    normal at pin ``pin`` crosses the line of centres."""
    z2 = teeth + 1
    radius, e = module * z2 / 2, (1 - shift) * module / 2

    def trochoid(t):  # pin-centre curve in the disc frame, and its derivative
        return (radius * np.exp(1j * t) - e * np.exp(1j * z2 * t),
                1j * (radius * np.exp(1j * t) - z2 * e * np.exp(1j * z2 * t)))

    def locus(t):  # moved inward by d along the normal
        point, tangent = trochoid(t)
        return point - error * (-1j * tangent / abs(tangent))

    centre = e * np.exp(1j * theta)
    pin_centre = radius * np.exp(2j * np.pi * pin / z2)
    target = abs(pin_centre - centre)
    # the tooth flank the pin drives: |T(t)|² = R² + e² − 2Re·cos(z1·t) falls from the tip
    # (z1·t = (2j − 1)π) to the root (z1·t = 2jπ); the ideal contact is at t0
    t0 = 2 * np.pi * pin / z2 + theta / teeth
    root = 2 * np.pi * math.ceil(teeth * t0 / (2 * np.pi)) / teeth
    t = brentq(lambda s: abs(locus(s)) - target, root - np.pi / teeth, root, xtol=1e-15)
    # the contact point must be where the disc actually is
    assert abs(np.exp(1j * psi) * locus(t) + centre - pin_centre) < 1e-9
    normal = np.exp(1j * psi) * (-1j * trochoid(t)[1])          # direction only
    axis = np.exp(1j * theta)                                    # line of centres
    # pin_centre + a·normal = b·axis  ->  solve for b (real 2x2)
    matrix = np.array([[normal.real, -axis.real], [normal.imag, -axis.imag]])
    _, b = np.linalg.solve(matrix, [-pin_centre.real, -pin_centre.imag])
    return abs(b * axis - centre) / e


def test_ratio_equals_pole_point_construction() -> None:
    module, teeth, error = 1, 9, 0.1   # paper Table 2
    r = cycloid_fluctuation(module, teeth, error)
    for j in range(3, r.crank_angle.size, 37):
        expected = _pole_point_ratio(module, teeth, error, r.crank_angle[j],
                                     r.output_angle[j], r.contact_pin[j])
        assert r.ratio[j] == pytest.approx(expected, rel=1e-8)


def test_ratio_equals_differences_of_the_output_angle() -> None:
    per_segment = 400
    r = cycloid_fluctuation(1, 9, 0.1, points_per_segment=per_segment)
    step = r.crank_angle[1] - r.crank_angle[0]
    psi, pin = r.output_angle, r.contact_pin
    inner = (pin == np.roll(pin, 1)) & (pin == np.roll(pin, -1))
    inner[[0, -1]] = False
    estimate = -2 * step / (np.roll(psi, -1) - np.roll(psi, 1))
    assert np.allclose(estimate[inner], r.ratio[inner], rtol=1e-5, atol=0)


def test_paper_central_differences_by_hand() -> None:
    # Eq. (10) on a 2° grid, done by hand from the output angles sampled every 2°
    # (z2 = 10: a segment is 36°, so 18 points per segment fall on the 2° grid).
    r = cycloid_fluctuation(1, 9, 0.1, points_per_segment=18)
    psi = np.append(r.output_angle, r.output_angle[0] - 2 * np.pi / 9)
    psi = np.insert(psi, 0, r.output_angle[-1] + 2 * np.pi / 9)
    by_hand = 2 * math.radians(2) / (psi[:-2] - psi[2:])
    assert np.allclose(r.paper_crank_angle, r.crank_angle)
    assert np.allclose(r.paper_ratio, by_hand, rtol=1e-12, atol=0)


def test_exact_maximum_is_at_a_handover_and_beats_the_2deg_grid() -> None:
    r = cycloid_fluctuation(1, 9, 0.1)
    sides = np.concatenate([r.ratio_before, r.ratio_after])
    assert r.max_deviation_percent == pytest.approx(np.max(np.abs(9 - sides) / 9 * 100),
                                                    rel=1e-12)
    assert r.max_deviation_percent >= np.max(np.abs(r.deviation_percent))
    assert r.max_deviation_percent > r.max_deviation_percent_2deg
    # The paper's 2° grid (its Eq. 10) misses the maximum badly for large z1
    wide = cycloid_fluctuation(1, 117, profile_error_for_grade(1, 117, 5))
    assert wide.max_deviation_percent_2deg < 0.5 * wide.max_deviation_percent


@pytest.mark.parametrize("teeth", [3, 9, 117])
@pytest.mark.parametrize("shift", [0.05, 0.3, 0.9])
def test_deviation_is_monotonic_between_handovers(teeth: int, shift: float) -> None:
    # Why the maximum is a one-sided value at a hand-over (docs/cycloid.md).
    r = cycloid_fluctuation(1, teeth, 0.005, shift=shift, rc=0.3, points_per_segment=12)
    for _, _, ratio in r.contact_segments():
        steps = np.diff(ratio)
        assert np.all(steps > 0) or np.all(steps < 0)


def test_candidate_pins_do_not_change_the_contact() -> None:
    g = cycloid_geometry(1, 9)
    theta = np.linspace(0, 2 * np.pi, 721)
    few, every = contact_curve(g, 0.1, theta), contact_curve(g, 0.1, theta, candidates=None)
    assert np.array_equal(few[0], every[0])
    assert np.allclose(few[2], every[2], rtol=1e-12, atol=0)


# ---------------------------------------------------------------- the paper's study


def test_table1_profile_errors_m3() -> None:
    # Paper Table 1 (m = 3), rows IT5…IT9, columns z1 = 9, 25, 43, 53, 117.
    for grade, row in CSOBAN["table1_m3"].items():
        for z1, d in zip(CSOBAN["teeth"], row):
            assert profile_error_for_grade(3, z1, grade) == pytest.approx(d, abs=1e-12)


def test_iso_table_follows_the_standard_formula() -> None:
    # ISO 286-1: IT = k·i, i = 0.45·D^(1/3) + 0.001·D (µm), D the geometric mean of the
    # step; the table rounds, so within 10 % (the first step, 0–3 mm, uses D = sqrt(1·3)).
    lower = 0
    for upper, values in ISO_286_TABLE:
        mean = math.sqrt(max(lower, 1) * upper)
        unit = 0.45 * mean ** (1 / 3) + 0.001 * mean
        for grade, value in zip((5, 6, 7, 8, 9), values):
            if lower >= 3:
                assert value == pytest.approx(GRADE_FACTORS[grade] * unit, rel=0.10)
            assert iso_tolerance(upper, grade) == value / 1000
        lower = upper


@pytest.fixture(scope="module", params=[1, 2, pytest.param(3, marks=pytest.mark.slow),
                                        pytest.param(5, marks=pytest.mark.slow)])
def study(request):
    return fluctuation_study(request.param)


def test_refit_matches_the_paper_within_3_percent(study) -> None:
    # The paper's fitted surfaces for m = 1, 2, 3, 5 (Section 5). Measured: m = 1, 2 to the
    # printed digits; m = 3: a +0.7 %, m = 5: a +1.9 % (b within 0.2 %).
    fit = CSOBAN["fits"][int(study.module)]
    a, b = fit["a"], fit["b"]
    assert PAPER_FITS[int(study.module)] == (a, b)
    assert study.a == pytest.approx(a, rel=0.03)
    assert study.b == pytest.approx(b, rel=0.03)
    assert (study.paper_a, study.paper_b) == (a, b)


def test_study_grid_is_the_papers(study) -> None:
    # Paper §4: 5 z1 × IT5…IT9, but m = 5, z1 = 117 (585 mm > 500 mm) is left out.
    expected_teeth = [9, 25, 43, 53] + ([] if study.module == 5 else [117])
    assert sorted(set(study.teeth.tolist())) == expected_teeth
    assert study.teeth.size == 5 * len(expected_teeth)
    assert study.left_out == ((117,) if study.module == 5 else ())


# ---------------------------------------------------------------- bad input


@pytest.mark.parametrize("kwargs, words", [
    ({"module": -1}, "module"), ({"module": 0}, "module"), ({"teeth": 2}, "teeth"),
    ({"teeth": 9.5}, "teeth"), ({"profile_error": -0.01}, "profile error"),
    ({"shift": 0.0}, "shift"), ({"shift": 1.0}, "shift"), ({"rc": 0}, "rc"),
    ({"rc": 2.0}, "overlap"), ({"profile_error": 1.0}, "undercut"),
    ({"module": float("nan")}, "module"),
])
def test_impossible_stages_are_usage_errors(kwargs, words) -> None:
    args = {"module": 1, "teeth": 9, "profile_error": 0.01, **kwargs}
    with pytest.raises(UsageError, match=words):
        cycloid_fluctuation(**args)


def test_central_difference_step_must_divide_a_turn() -> None:
    with pytest.raises(UsageError):
        central_difference_ratio(cycloid_geometry(1, 9), 0.01, step_deg=7.0)


def test_results_are_immutable() -> None:
    r = cycloid_fluctuation(1, 9, 0.01)
    with pytest.raises(Exception):
        r.profile_error = 0.0
    with pytest.raises(ValueError):
        r.ratio[0] = 1.0
