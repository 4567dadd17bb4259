"""Tolerance analysis: nominal reproduction, closed-form distributions, Sobol shares, yields.

Expected values are closed forms derived here (the convolution of two uniform plays, the
variance shares of an additive model, a truncated normal's standard deviation, Eq. (1)-(2)
of Li et al. 2012 by hand) or the nominal analyses of the same model (``backlash``,
``cycloid``, ``solve``).
"""
from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest
import yaml

import powergraph as pg
from powergraph.analyses.backlash import analyse_backlash
from powergraph.analyses.cycloid import train_fluctuation
from powergraph.analyses.tolerance import (ToleranceEvaluator, it_tolerance, parse_spec,
                                           tolerance_analysis, wilson_interval)
from powergraph.errors import ModelError, UsageError
from powergraph.model import load_model, model_from_dict
from powergraph.testing import assert_conservation

ROOT = Path(__file__).resolve().parents[2]
N = 1_000_000

# Two meshes in series: gear 1 (20) - gear 2 (60), gear 2 fixed to gear 3 (20) - gear 4 (20).
# With the input (1) held, a play s0 of gear 1 in mesh 0 turns the output 4 by s0/3
# ((w1) + 3 (w2) = s0 -> w2 = s0/3, w4 = -w3 = -w2); a play s1 of gear 3 in mesh 1 turns it
# by s1 ((w3) + (w4) = s1 with w3 = 0). Sensitivities 1/3 and 1.
CHAIN = {
    "name": "two meshes in series",
    "components": {0: {"role": "frame"}, 1: {"teeth": 20}, 2: {"teeth": 60},
                   3: {"teeth": 20}, 4: {"teeth": 20}},
    "links": [{"type": "mesh", "between": [1, 2], "backlash_arcmin": 1.5, "efficiency": 0.98},
              {"type": "fixed", "between": [2, 3]},
              {"type": "mesh", "between": [3, 4], "backlash_arcmin": 1.0, "efficiency": 0.97}],
    "ports": [{"component": 1, "role": "input", "speed": "1000 rpm", "power": "1 kW"},
              {"component": 4, "role": "output"}],
}
A, B = 1.0, 2.0     # output shares: play0 ~ U(0, 3A) on gear 1, play1 ~ U(0, B)


def chain(tolerances: dict | None = None, **changes) -> pg.Model:
    data = {**CHAIN, **changes}
    if tolerances is not None:
        data["tolerances"] = tolerances
    return model_from_dict(data)


def uniform_chain() -> pg.Model:
    return chain({"links.0.backlash_arcmin": {"distribution": "uniform", "min": 0, "max": 3 * A},
                  "links.2.backlash_arcmin": {"distribution": "uniform", "min": 0, "max": B}})


def trapezoid_cdf(z: float) -> float:
    """CDF of X + Y, X ~ U(0, A), Y ~ U(0, B), A <= B (convolution: a trapezoid density
    rising as z/(AB) on [0, A], flat 1/B on [A, B], falling on [B, A + B])."""
    if z <= 0:
        return 0.0
    if z <= A:
        return z * z / (2 * A * B)
    if z <= B:
        return (2 * z - A) / (2 * B)
    if z <= A + B:
        return 1 - (A + B - z) ** 2 / (2 * A * B)
    return 1.0


def trapezoid_quantile(p: float) -> float:
    if p <= A / (2 * B):
        return math.sqrt(2 * A * B * p)
    if p <= 1 - A / (2 * B):
        return (2 * B * p + A) / 2
    return A + B - math.sqrt(2 * A * B * (1 - p))


def trapezoid_density(z: float) -> float:
    return z / (A * B) if z <= A else (1 / B if z <= B else (A + B - z) / (A * B))


def with_tolerances(path: str, tolerances: dict) -> pg.Model:
    data = yaml.safe_load((ROOT / path).read_text())
    data["tolerances"] = tolerances
    return model_from_dict(data)


# -- zero width = the nominal analyses -------------------------------------------------------

def test_zero_width_gives_the_nominal_backlash_exactly() -> None:
    zero = {"nominal": 0.0, "tolerance": 0}
    model = with_tolerances("models/backlash_li2012.yaml", {
        # the values the nominal analysis uses: smallest internal M, largest external M
        "links.0.backlash.measured_M.R1": {**zero, "nominal": 42.479},
        "links.0.backlash.measured_M.G1": {**zero, "nominal": 42.404},
        "links.0.backlash.runout.R1": {**zero, "nominal": 0.022},
        "links.0.backlash.bearing_clearance.1": {**zero, "nominal": 0.006},
        "links[1].backlash.runout.G2": {**zero, "nominal": 0.018}})
    result = tolerance_analysis(model, samples=1000, seed=0, sobol_samples=0)
    nominal = analyse_backlash(model).worst_case
    assert np.all(result.values["lost_motion_arcmin"] == nominal)


def test_zero_width_gives_the_nominal_fluctuation_and_efficiency() -> None:
    model = with_tolerances("models/rv40e_profile_error.yaml", {
        "links.1.cycloid.profile_error": {"nominal": 0.010, "tolerance": 0},
        "links.1.efficiency": {"nominal": 0.94, "tolerance": 0}})
    result = tolerance_analysis(model, samples=100, seed=0, sobol_samples=0)
    stage = train_fluctuation(model).stages[0]
    assert np.all(result.values["fluctuation_percent"] == stage.max_deviation_percent)
    solved = pg.solve(model)
    assert_conservation(solved)
    assert result.values["efficiency"] == pytest.approx(solved.efficiency, rel=1e-12)


# -- closed forms -----------------------------------------------------------------------------

def test_sum_of_uniform_plays_is_the_trapezoid() -> None:
    model = uniform_chain()
    sensitivities = [abs(m.sensitivity) for m in analyse_backlash(model).meshes]
    assert sensitivities == pytest.approx([1 / 3, 1.0], rel=1e-12)
    result = tolerance_analysis(model, samples=N, seed=12, sobol_samples=0)
    out = result.outputs["lost_motion_arcmin"]
    assert out["mean"] == pytest.approx((A + B) / 2, abs=4 * math.sqrt((A * A + B * B) / 12 / N))
    assert out["sd"] == pytest.approx(math.sqrt((A * A + B * B) / 12), rel=5e-3)
    for key, p in (("p50", 0.5), ("p95", 0.95), ("p99_73", 0.9973)):
        q = trapezoid_quantile(p)
        assert trapezoid_cdf(q) == pytest.approx(p, abs=1e-12)      # the inversion itself
        se = math.sqrt(p * (1 - p) / N) / trapezoid_density(q)       # quantile's std. error
        assert out[key] == pytest.approx(q, abs=5 * se), key
    assert A + B - 0.01 < out["max"] <= A + B


def test_yield_contains_the_analytic_probability() -> None:
    limit = 2.5
    result = tolerance_analysis(uniform_chain(), samples=N, seed=5,
                                specs=[f"lost_motion<={limit}arcmin", "lost_motion<=45arcsec"],
                                sobol_samples=0)
    for y, z in zip(result.yields, (limit, 0.75)):
        low, high = y.interval
        assert low <= trapezoid_cdf(z) <= high
        assert high - low < 0.002


def test_sobol_indices_of_an_additive_model_are_the_variance_shares() -> None:
    result = tolerance_analysis(uniform_chain(), samples=1000, seed=3, sobol_samples=1 << 14)
    shares = {"links.0.backlash_arcmin": A * A / (A * A + B * B),
              "links.2.backlash_arcmin": B * B / (A * A + B * B)}
    indices = result.sensitivity["lost_motion_arcmin"]
    for path, share in shares.items():
        assert indices[path]["first"] == pytest.approx(share, abs=0.02)
        assert indices[path]["total"] == pytest.approx(share, abs=0.02)
    assert [p for p, _ in result.ranked()] == ["links.2.backlash_arcmin",
                                                "links.0.backlash_arcmin"]


def test_truncated_normal_nominal_form_has_the_closed_form_spread() -> None:
    # ±T as ±3σ truncated at ±3σ: sd = σ·sqrt(1 − 2·3·φ(3)/(2Φ(3) − 1)).
    model = chain({"links.2.backlash_arcmin": {"nominal": 1.0, "tolerance": 0.3}})
    result = tolerance_analysis(model, samples=N, seed=8, sobol_samples=0)
    phi3 = math.exp(-4.5) / math.sqrt(2 * math.pi)
    mass = math.erf(3 / math.sqrt(2))
    sd = 0.1 * math.sqrt(1 - 6 * phi3 / mass)
    out = result.outputs["lost_motion_arcmin"]
    assert out["sd"] == pytest.approx(sd, rel=5e-3)
    assert out["mean"] == pytest.approx(0.5 + 1.0, abs=5 * sd / math.sqrt(N))   # + play0/3
    assert out["max"] <= 0.5 + 1.3


def test_backlash_block_play_follows_eqs_1_and_2() -> None:
    # Thickness term j_t = (E_int - E_ext)·tan α (Eq. 2): 1 µm more internal M gives
    # tan 20°·1 µm more backlash; Eq. (1) on the internal gear (between[0], z 45, m 1):
    # play += tan20°·0.001/(22.5)·(10800/π) arcmin of the ring R1; given as the ring's play
    # it reaches stage 1's output times z_r/z_p = 45/40 and the train's output ÷ N2 = 8
    # (docs/backlash.md, checks by hand).
    model = with_tolerances("models/backlash_li2012.yaml", {
        "links.0.backlash.measured_M.R1": {"distribution": "uniform", "min": 42.479,
                                           "max": 42.480}})
    evaluate = ToleranceEvaluator(model)
    out = evaluate({"links.0.backlash.measured_M.R1": np.array([42.479, 42.480])})
    step = math.tan(math.radians(20)) * 0.001 / 22.5 * 10800 / math.pi
    sensitivity = abs(analyse_backlash(model).meshes[0].sensitivity)
    assert sensitivity == pytest.approx(45 / 40 / 8, rel=1e-12)
    delta = np.diff(out["lost_motion_arcmin"])[0]
    assert delta == pytest.approx(step * sensitivity, rel=1e-9)


def test_efficiency_of_each_unit_equals_a_single_solve() -> None:
    model = chain({"links.0.efficiency": {"distribution": "uniform", "min": 0.9, "max": 1}})
    values = np.array([0.9, 0.95, 1.0])
    out = ToleranceEvaluator(model)({"links.0.efficiency": values})
    for eta, got in zip(values, out["efficiency"]):
        solved = pg.solve(model.with_link(0, efficiency=float(eta)))
        assert_conservation(solved)
        assert got == pytest.approx(solved.efficiency, rel=1e-12)
        assert got == pytest.approx(eta * 0.97, rel=1e-12)          # two pairs in series


# -- reproducibility ------------------------------------------------------------------------

def test_same_seed_same_result_different_seed_within_intervals() -> None:
    spec = ["lost_motion<=2.5arcmin"]
    one = tolerance_analysis(uniform_chain(), samples=200_000, seed=1, specs=spec,
                             sobol_samples=1 << 10)
    again = tolerance_analysis(uniform_chain(), samples=200_000, seed=1, specs=spec,
                               sobol_samples=1 << 10)
    other = tolerance_analysis(uniform_chain(), samples=200_000, seed=2, specs=spec,
                               sobol_samples=1 << 10)
    assert one.to_dict() == again.to_dict()
    assert np.array_equal(one.values["lost_motion_arcmin"], again.values["lost_motion_arcmin"])
    assert not np.array_equal(one.values["lost_motion_arcmin"],
                              other.values["lost_motion_arcmin"])
    (low1, high1), (low2, high2) = one.yields[0].interval, other.yields[0].interval
    assert low1 <= other.yields[0].fraction <= high1
    assert low2 <= one.yields[0].fraction <= high2
    sd = one.outputs["lost_motion_arcmin"]["sd"]
    assert abs(one.outputs["lost_motion_arcmin"]["mean"]
               - other.outputs["lost_motion_arcmin"]["mean"]) < 4 * sd * math.sqrt(2 / 200_000)


# -- fluctuation table -----------------------------------------------------------------------

@pytest.mark.slow
def test_fluctuation_interpolation_error_is_within_its_bound() -> None:
    model = load_model(ROOT / "models" / "rv40e_tolerances.yaml")
    table = ToleranceEvaluator(model).tables[1]
    assert 0 < table.error_bound < 1e-3 * table.values.max()
    for d in (table.errors[1:] + table.errors[:-1])[[0, 2, -1]] / 2:   # midpoints
        link = model.links[1]
        blocks = dict(link.blocks)
        blocks["cycloid"] = dataclasses.replace(blocks["cycloid"], profile_error=float(d))
        exact = train_fluctuation(model.with_link(1, blocks=blocks)).stages[0]
        assert abs(table(d) - exact.max_deviation_percent) <= 2 * table.error_bound


# -- helpers ----------------------------------------------------------------------------------

def test_iso_286_grade_width() -> None:
    # ISO 286-1: IT6 = 10 i, i = 0.45 D^(1/3) + 0.001 D (µm), D the geometric mean of the
    # size step 120...180 mm: i = 2.522 µm, IT6 = 25.2 -> 25 µm after the standard's rounding.
    d = math.sqrt(120 * 180)
    assert 10 * (0.45 * d ** (1 / 3) + 0.001 * d) == pytest.approx(25.2, abs=0.05)
    assert it_tolerance("IT6", 124.8, "x") == pytest.approx(0.025)
    model = chain({"links.2.backlash_arcmin": {"nominal": 1.0, "grade": "IT6", "size": 124.8}})
    dist = model.tolerances.entries[0].distribution
    assert (dist.low, dist.high) == pytest.approx((1 - 0.0125, 1 + 0.0125))


def test_wilson_interval_closed_form() -> None:
    # n = 10, 10 successes: the lower bound is n/(n + z²).
    z = 1.959963984540054
    assert wilson_interval(10, 10)[0] == pytest.approx(10 / (10 + z * z), rel=1e-12)
    assert wilson_interval(10, 10)[1] == 1.0


@pytest.mark.parametrize("text, output, value", [
    ("lost_motion<=1arcmin", "lost_motion_arcmin", 1.0),
    ('lost_motion<30"', "lost_motion_arcmin", 0.5),
    ("fluctuation<=0.5%", "fluctuation_percent", 0.5),
    ("efficiency>=85%", "efficiency", 0.85)])
def test_parse_spec(text, output, value) -> None:
    spec = parse_spec(text)
    assert (spec.output, spec.value) == (output, pytest.approx(value))


@pytest.mark.parametrize("text", ["lost_motion<=1kg", "speed<=3", "lost_motion=1", ""])
def test_bad_spec(text) -> None:
    with pytest.raises(UsageError):
        parse_spec(text)


@pytest.mark.parametrize("tolerances, message", [
    ({"links.9.backlash_arcmin": {"nominal": 1, "tolerance": 0.1}},
     "tolerances['links.9.backlash_arcmin']: no links[9]"),
    ({"links.1.backlash_arcmin": {"nominal": 1, "tolerance": 0.1}},
     "tolerances['links.1.backlash_arcmin']: links[1] is a fixed link"),
    ({"links.0.backlash_arcmin": {"distribution": "uniform", "min": 2, "max": 1}},
     "min must be < max"),
    ({"links.0.backlash_arcmin": {"distribution": "normal", "mean": 2, "sd": 0, "low": 0}},
     "tolerances['links.0.backlash_arcmin'].sd: must be > 0"),
    ({"links.0.backlash_arcmin": {"distribution": "normal", "mean": 2, "sd": 0.1}},
     "untruncated normal"),
    ({"links.0.backlash_arcmin": {"distribution": "uniform", "min": -1, "max": 1}},
     "must be >= 0"),
    ({"links.0.backlash_arcmin": {"distribution": "uniform", "min": 0, "max": float("inf")}},
     "must be finite"),
    ({"links.0.backlash_arcmin": {"distribution": "uniform", "min": 0, "max": 1, "sd": 2}},
     "tolerances['links.0.backlash_arcmin'].sd: unknown field"),
    ({"links.0.backlash_arcmin": {"distribution": "beta", "min": 0, "max": 1}},
     "unknown distribution 'beta'"),
    ({"links.0.efficiency": {"distribution": "uniform", "min": 0.9, "max": 1.1}},
     "must be <= 1"),
    ({"links.*.efficiency": {"nominal": 0.95, "tolerance": 0.01},
      "links[0].efficiency": {"nominal": 0.95, "tolerance": 0.01}}, "sets the same model value"),
    ({"links.0.cycloid.profile_error": {"nominal": 0.01, "tolerance": 0.001}},
     "links[0] has no cycloid: block"),
    ({"components.1.teeth": {"nominal": 20, "tolerance": 1}}, "only links."),
    ({"components.1.geometry.module": {"nominal": 1, "tolerance": 0.1}},
     "component geometry is not toleranced"),
    ({"links.0.cycloid": {"nominal": 1, "tolerance": 0.1}}, "links[0] has no cycloid"),
    ({"links.0.backlash.runout.1": {"nominal": 1, "tolerance": 0.1}},
     "links[0] has no backlash: block"),
    ({"links.0.backlash_arcmin": {"nominal": 1, "grade": "IT3", "size": 10}}, ".grade: grade"),
    ({"links.0.backlash_arcmin": 3}, "must be a mapping"),
    ([], "tolerances: must be a mapping"),
])
def test_invalid_tolerances_name_their_place(tolerances, message) -> None:
    with pytest.raises(ModelError) as info:
        chain(tolerances)
    assert message in str(info.value)


def test_no_tolerances_and_unknown_spec_output() -> None:
    with pytest.raises(ModelError, match="no tolerances"):
        tolerance_analysis(chain(), samples=10)
    with pytest.raises(UsageError, match="no fluctuation_percent"):
        tolerance_analysis(uniform_chain(), samples=10, specs=["fluctuation<=1%"])


@pytest.mark.parametrize("path, message", [
    ("links.0.backlash.runout.X", "'X' is not a gear of links[0]"),
    ("links.0.backlash.bearing_clearance.5", "no bearing_clearance[5] (links[0] gives 2)"),
    ("links.0.backlash.module", "backlash.module is not toleranced"),
    ("links.0.backlash.runout", "expected links.<i>.backlash.runout.<gear>"),
    ("links.0.backlash_arcmin", "links[0] has no backlash_arcmin"),
])
def test_invalid_backlash_paths(path, message) -> None:
    with pytest.raises(ModelError) as info:
        with_tolerances("models/backlash_li2012.yaml",
                        {path: {"distribution": "uniform", "min": 0.01, "max": 0.02}})
    assert f"tolerances[{path!r}]" in str(info.value)
    assert message in str(info.value)


def test_lengths_take_units() -> None:
    model = with_tolerances("models/backlash_li2012.yaml", {
        "links.0.backlash.runout.R1": {"distribution": "uniform", "min": "10 um",
                                       "max": "0.03 mm"}})
    dist = model.tolerances.entries[0].distribution
    assert (dist.low, dist.high) == pytest.approx((0.010, 0.030))
