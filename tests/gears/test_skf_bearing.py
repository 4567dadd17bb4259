"""SKF's four-component frictional moment (powergraph.gears.skf_bearing).

No worked example of the model was found in the public SKF material that could be read
(docs/losses.md), so the expected values are hand computations of each component, written
out step by step in catalogue units (mm, N, r/min, mm²/s, N·mm) with the intermediate
powers as a calculator gives them, and limits the catalogue states.

The bearing of the hand computations is a 6208 (d = 40 mm, D = 80 mm, C_0 = 19 000 N, SKF's
product table) or an NU 208 (same d, D), at n = 1500 r/min in an oil of ν = 20 mm²/s,
low-level oil bath (K_rs = 3e-8), μ_bl = 0.15.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from powergraph.errors import ModelError
from powergraph.gears.skf_bearing import (K_RS, SERIES, BearingSeries, OilBathDrag, Seal,
                                          skf_moment)
from powergraph.units_si import rad_s

D_BORE, D_OUT = 0.040, 0.080          # m
N_RPM, NU = 1500.0, 20e-6             # r/min, m²/s
OMEGA = rad_s(N_RPM)


def test_deep_groove_radial_load_by_hand() -> None:
    """6208 (series 62: R1 3.9e-7, S1 3.23e-3, K_z 3.1), F_r 2000 N, F_a 0.

    d_m = 60 mm.
    G_rr = R1·d_m^1.96·F_r^0.54 = 3.9e-7 × 3056.1626 × 60.611663 = 0.0722432
    G_sl = S1·d_m^−0.26·F_r^(5/3) = 3.23e-3 × 0.34489006 × 317480.21 = 353.67133
    φ_ish: (n·d_m)^1.28 = 90 000^1.28 = 2 194 979.2, ν^0.64 = 6.8023535,
           φ_ish = 1/(1 + 1.84e-9 × 2 194 979.2 × 6.8023535) = 1/1.0274731 = 0.9732615
    φ_rs: K_rs·ν·n·(d + D)·sqrt(K_z/(2(D − d))) = 3e-8 × 20 × 1500 × 120 × sqrt(3.1/80)
          = 0.108 × 0.19685019 = 0.02125982, φ_rs = e^−0.02125982 = 0.9789646
    (ν·n)^0.6 = 30 000^0.6 = 485.59337
    M_rr (with φ) = 0.9732615 × 0.9789646 × 0.0722432 × 485.59337 = 33.42462 N·mm
    φ_bl: (n·ν)^1.4 = 30 000^1.4 = 1 853 402.6, exponent 2.6e-8 × 1 853 402.6 × 60
          = 2.8913080, φ_bl = e^−2.8913080 = 0.0555036
    μ_sl = 0.0555036 × 0.15 + 0.9444964 × 0.05 = 0.0555504
    M_sl = 353.67133 × 0.0555504 = 19.64657 N·mm;  M = 53.07119 N·mm.
    (SKF's constant-coefficient estimate μ·F·d/2 = 0.0015 × 2000 × 20 = 60 N·mm.)
    """
    m = skf_moment("62", D_BORE, D_OUT, 2000.0, 0.0, OMEGA, NU)
    assert m.phi_ish == pytest.approx(0.9732615, rel=1e-6)
    assert m.phi_rs == pytest.approx(0.9789646, rel=1e-6)
    assert m.phi_bl == pytest.approx(0.0555036, rel=1e-5)
    assert m.mu_sl == pytest.approx(0.0555504, rel=1e-6)
    assert m.rolling * 1e3 == pytest.approx(33.42462, rel=1e-6)
    assert m.sliding * 1e3 == pytest.approx(19.64657, rel=1e-6)
    assert (m.seal, m.drag) == (0.0, 0.0)
    assert m.total * 1e3 == pytest.approx(53.07119, rel=1e-6)


def test_deep_groove_axial_load_by_hand() -> None:
    """Same 6208 with F_a = 500 N, C_0 = 19 000 N.

    α_F = 24.6·(500/19 000)^0.24 = 24.6 × 0.41768794 = 10.275123°, sin α_F = 0.17837502
    G_rr = R1·d_m^1.96·(F_r + R2/sin α_F·F_a)^0.54: F_r + 1.7/0.17837502 × 500 = 6765.2414,
           ^0.54 = 117.04503, G_rr = 3.9e-7 × 3056.1626 × 117.04503 = 0.1395064
    G_sl = S1·d_m^−0.145·(F_r^5 + S2·d_m^1.5/sin α_F·F_a^4)^(1/3): d_m^1.5 = 464.75800,
           bracket = 3.2e16 + 36.5 × 464.758 / 0.17837502 × 6.25e10 = 3.7943821e16,
           cube root 336 031.78, d_m^−0.145 = 0.55229113, G_sl = 599.44721
    M_rr = 0.9732615 × 0.9789646 × 0.1395064 × 485.59337 = 64.54511 N·mm
    M_sl = 599.44721 × 0.0555504 = 33.29951 N·mm;  M = 97.84461 N·mm.
    """
    m = skf_moment("62", D_BORE, D_OUT, 2000.0, 500.0, OMEGA, NU, static_load_rating=19000.0)
    assert m.rolling * 1e3 == pytest.approx(64.54511, rel=1e-6)
    assert m.sliding * 1e3 == pytest.approx(33.29951, rel=1e-6)
    assert m.total * 1e3 == pytest.approx(97.84461, rel=1e-6)


def test_cylindrical_roller_by_hand() -> None:
    """NU 208 (series NU 2: R1 1.09e-6, S1 0.16, S2 0.0015, K_z 5.1, μ_EHL 0.02).

    F_r = 2000 N: G_rr = 1.09e-6 × 60^2.41 × 2000^0.31 = 1.09e-6 × 19 290.546 × 10.551624
    = 0.2218658; G_sl = S1·d_m^0.9·F_a + S2·d_m·F_r = 0 + 0.0015 × 60 × 2000 = 180.
    φ_rs = exp(−0.108 × sqrt(5.1/80)) = exp(−0.02726866) = 0.9730998
    M_rr = 0.9732615 × 0.9730998 × 0.2218658 × 485.59337 = 102.03519 N·mm
    μ_sl = 0.0555036 × 0.15 + 0.9444964 × 0.02 = 0.0272155, M_sl = 4.89878 N·mm.
    F_r = 8000 N: 8000^0.31 = 16.216529, G_rr = 0.3409800, M_rr = 156.81535;
    G_sl = 720, M_sl = 19.59513.
    """
    m = skf_moment("NU 2", D_BORE, D_OUT, np.array([2000.0, 8000.0]), 0.0, OMEGA, NU)
    assert m.mu_sl == pytest.approx(0.0272155, rel=1e-5)
    np.testing.assert_allclose(m.rolling * 1e3, [102.03519, 156.81535], rtol=1e-6)
    np.testing.assert_allclose(m.sliding * 1e3, [4.89878, 19.59513], rtol=1e-5)
    np.testing.assert_allclose(m.total * 1e3, [106.93397, 176.41049], rtol=1e-6)
    # an axial load on an NJ/NUP bearing adds S1·d_m^0.9·F_a to G_sl: 0.16 × 60^0.9 × 100
    # = 0.16 × 39.841541 × 100 = 637.46465, M_sl grows by 637.46465 × 0.0272155 = 17.34890
    axial = skf_moment("NU 2", D_BORE, D_OUT, 2000.0, 100.0, OMEGA, NU)
    assert (axial.sliding - m.sliding[0]) * 1e3 == pytest.approx(17.34890, rel=1e-5)


def test_at_rest_factors_are_one_and_sliding_is_boundary() -> None:
    """n → 0: φ_ish, φ_rs, φ_bl → 1, μ_sl → μ_bl, M_rr → 0; M_sl = G_sl·μ_bl."""
    m = skf_moment("62", D_BORE, D_OUT, 2000.0, 0.0, 0.0, NU)
    assert (m.phi_ish, m.phi_rs, m.phi_bl, m.mu_sl) == (1.0, 1.0, 1.0, 0.15)
    assert m.rolling == 0.0
    assert m.sliding * 1e3 == pytest.approx(353.67133 * 0.15, rel=1e-6)
    slow = skf_moment("62", D_BORE, D_OUT, 2000.0, 0.0, rad_s(1e-3), NU)
    assert slow.phi_ish == pytest.approx(1.0, abs=1e-7)
    assert slow.phi_rs == pytest.approx(1.0, abs=1e-7)


def test_moment_grows_with_load() -> None:
    loads = np.linspace(100.0, 10000.0, 50)
    for series in ("60", "62", "63", "64", "NU 2", "NU 3", "NU 4"):
        m = skf_moment(series, D_BORE, D_OUT, loads, 0.0, OMEGA, NU)
        assert np.all(np.diff(m.total) > 0), series
        assert np.all(np.diff(m.rolling) > 0) and np.all(np.diff(m.sliding) > 0), series


def test_moment_and_viscosity() -> None:
    """The rolling moment grows with ν (M_rr ∝ ν^0.6 while φ_ish·φ_rs stay near 1); the
    total does in full film (φ_bl ≈ 0), but falls first in mixed lubrication, where the
    sliding coefficient drops from μ_bl to μ_EHL (the catalogue's diagram 1, zones 1–3)."""
    nu = np.array([2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0]) * 1e-6
    m = skf_moment("62", D_BORE, D_OUT, 2000.0, 0.0, OMEGA, nu)
    assert np.all(np.diff(m.rolling) > 0)
    full_film = m.phi_bl < 0.06
    assert np.all(np.diff(m.total[full_film]) > 0)
    assert m.total[2] < m.total[0]


def test_starvation_and_inlet_heating_at_high_speed() -> None:
    """Both factors fall with speed; grease/oil-air (K_rs 6e-8) starves twice as fast (in
    the exponent) as a low oil bath (3e-8)."""
    speeds = rad_s(np.array([500.0, 2000.0, 8000.0]))
    bath = skf_moment("62", D_BORE, D_OUT, 2000.0, 0.0, speeds, NU)
    grease = skf_moment("62", D_BORE, D_OUT, 2000.0, 0.0, speeds, NU, lubrication="grease")
    assert np.all(np.diff(bath.phi_ish) < 0) and np.all(np.diff(bath.phi_rs) < 0)
    np.testing.assert_allclose(np.log(grease.phi_rs), 2.0 * np.log(bath.phi_rs), rtol=1e-12)
    assert K_RS["oil_jet"] == K_RS["oil_bath"] and K_RS["oil_air"] == K_RS["grease"]


def test_broadcasting_matches_scalars() -> None:
    loads = np.array([[500.0], [3000.0]])
    speeds = rad_s(np.array([200.0, 1500.0, 4000.0]))
    grid = skf_moment("63", 0.040, 0.090, loads, 0.0, speeds, NU)
    assert grid.total.shape == (2, 3)
    for i, load in enumerate(loads[:, 0]):
        for j, speed in enumerate(speeds):
            assert grid.total[i, j] == pytest.approx(
                skf_moment("63", 0.040, 0.090, load, 0.0, speed, NU).total, rel=1e-14)
    negative = skf_moment("63", 0.040, 0.090, -500.0, 0.0, -speeds[1], NU)
    assert negative.total == pytest.approx(grid.total[0, 1], rel=1e-14)


def test_seal_and_drag_by_hand() -> None:
    """Seal with illustrative constants (not a catalogue row): K_S1 0.028, β 2.25, K_S2 2,
    d_s 52 mm, two seals: 2 × (0.028 × 52^2.25 + 2) = 2 × (0.028 × 7261.1854 + 2)
    = 2 × 205.31319 = 410.62638 N·mm.
    Oil-bath drag (2005 form) with V_M = 1e-4: K_ball = 3.1 × 120/40 × 1e-12 = 9.3e-12,
    M_drag = 1e-4 × 9.3e-12 × 60^5 × 1500² = 1e-4 × 9.3e-12 × 7.776e8 × 2.25e6 = 1.627128 N·mm.
    Roller (NU 2, K_L 0.65, B 18 mm): K_roll = 0.65 × 5.1 × 3 × 1e-12 = 9.945e-12,
    M_drag = 10 × 1e-4 × 9.945e-12 × 18 × 60^4 × 1500² (60^4 = 1.296e7) = 5.2199316 N·mm."""
    seal = Seal(K_S1=0.028, beta=2.25, K_S2=2.0, counterface_diameter=0.052, count=2)
    m = skf_moment("62", D_BORE, D_OUT, 2000.0, 0.0, OMEGA, NU, seal=seal,
                   drag=OilBathDrag(loss_factor=1e-4))
    assert m.seal * 1e3 == pytest.approx(410.62638, rel=1e-6)
    assert m.drag * 1e3 == pytest.approx(1.627128, rel=1e-6)
    assert m.total * 1e3 == pytest.approx(53.07119 + 410.62638 + 1.627128, rel=1e-6)
    roller = skf_moment("NU 2", D_BORE, D_OUT, 2000.0, 0.0, OMEGA, NU,
                        drag=OilBathDrag(loss_factor=1e-4, width=0.018))
    assert roller.drag * 1e3 == pytest.approx(5.2199316, rel=1e-6)


def test_custom_series_and_table() -> None:
    assert SERIES["62"].R1 == 3.9e-7 and SERIES["63"].S2 == 92.8
    assert SERIES["NU 4"].R1 == 1.00e-6 and SERIES["NU 2"].K_z == 5.1
    row = BearingSeries("deep_groove_ball", "62 copy", 3.9e-7, 1.7, 3.23e-3, 36.5, 3.1)
    a = skf_moment(row, D_BORE, D_OUT, 2000.0, 0.0, OMEGA, NU)
    assert a.total == skf_moment("62", D_BORE, D_OUT, 2000.0, 0.0, OMEGA, NU).total


@pytest.mark.parametrize("kwargs, match", [
    (dict(series="69"), "unknown bearing series"),
    (dict(axial_load=100.0), "basic static load rating"),
    (dict(axial_load=100.0, static_load_rating=0.0), "static_load_rating"),
    (dict(lubrication="mist"), "unknown lubrication"),
    (dict(lubricant="water"), "unknown lubricant"),
    (dict(bore=0.09), "bore < outside"),
    (dict(viscosity=0.0), "viscosity"),
])
def test_refusals(kwargs, match) -> None:
    args = dict(series="62", bore=D_BORE, outside=D_OUT, radial_load=2000.0, axial_load=0.0,
                speed=OMEGA, viscosity=NU)
    args.update(kwargs)
    series = args.pop("series")
    with pytest.raises(ModelError, match=match):
        skf_moment(series, **args)


def test_roller_drag_needs_width() -> None:
    with pytest.raises(ModelError, match="width"):
        skf_moment("NU 2", D_BORE, D_OUT, 2000.0, 0.0, OMEGA, NU,
                   drag=OilBathDrag(loss_factor=1e-4))
    assert math.isclose(SERIES["NU 3"].R1, SERIES["NU 2"].R1)
