"""Churning torque of a dip-lubricated gear (powergraph.gears.churning).

The validation points of Changenet & Velex (2007) could not be retrieved (docs/losses.md),
so the expected values are hand computations of the published formulas, written out step by
step, and the scaling laws the two fits imply. The gear of the hand computations: pitch
radius R_p = 0.1 m (D_p = 0.2 m), face width b = 0.02 m, immersion h = 0.05 m (θ = 60°),
sump V_0 = 2 L, oil density 870 kg/m³; g = 9.80665 m/s².
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from powergraph.errors import ModelError
from powergraph.gears.churning import (GRAVITY, churning_coefficient, churning_torque,
                                       immersed_surface)

R, B, H, V0, RHO = 0.1, 0.02, 0.05, 2e-3, 870.0


def paper_low(r, b, h, v0, omega, nu):
    """Changenet & Velex (2007), Re_c < 6000, written again from the formula."""
    d_p = 2 * r
    return (1.366 * (h / d_p) ** 0.45 * (v0 / d_p ** 3) ** 0.1 * (omega ** 2 * r / GRAVITY) ** -0.6
            * (omega * r * b / nu) ** -0.21)


def paper_high(r, b, h, v0, omega):
    """Changenet & Velex (2007), Re_c > 9000."""
    d_p = 2 * r
    return (3.644 * (h / d_p) ** 0.1 * (v0 / d_p ** 3) ** -0.35
            * (omega ** 2 * r / GRAVITY) ** -0.88 * (b / d_p) ** 0.85)


def test_immersed_surface_by_hand() -> None:
    """θ = arccos(1 − 0.05/0.1) = π/3.
    Faces: R_p²(2θ − sin 2θ) = 0.01 × (2.0943951 − 0.8660254) = 0.012283697 m²;
    periphery: 2R_p·b·θ = 2 × 0.1 × 0.02 × 1.0471976 = 0.0041887902 m²; S_m = 0.0164724872.
    Teeth, z = 50, h_t = 2.25 × 4 mm = 9 mm, α = 20°: 2·z·θ·h_t·b/(π cos α)
    = 100 × (π/3) × 0.009 × 0.02 / (π × 0.93969262) = 0.006/0.93969262 = 0.0063850666 m²."""
    assert immersed_surface(R, B, H) == pytest.approx(0.0164724872, rel=1e-8)
    with_teeth = immersed_surface(R, B, H, teeth=50, tooth_height=0.009)
    assert with_teeth - immersed_surface(R, B, H) == pytest.approx(0.0063850666, rel=1e-8)
    # wholly immersed (h ≥ 2R_p, θ = π): two full discs and the whole periphery
    assert immersed_surface(R, B, 0.3) == pytest.approx(2 * math.pi * R ** 2 + 2 * math.pi * R * B)
    assert immersed_surface(R, B, 0.0) == 0.0
    depths = np.linspace(0.0, 2 * R, 21)
    assert np.all(np.diff(immersed_surface(R, B, depths)) > 0)


def test_low_speed_by_hand() -> None:
    """ω = 10 rad/s, ν = 1e-4 m²/s (100 cSt).
    Fr = 100 × 0.1/9.80665 = 1.0197162; Re = 10 × 0.1 × 0.02/1e-4 = 200;
    Re_c = 10 × 0.1 × 0.05/1e-4 = 500 < 6000: low speed.
    C_m = 1.366 × 0.25^0.45 × 0.25^0.1 × Fr^−0.6 × 200^−0.21
        = 1.366 × 0.53588673 × 0.87055056 × 0.98835373 × 0.32868789 = 0.20702072
    C_ch = ½ × 870 × 100 × 0.016472487 × 0.001 × 0.20702072 = 0.14834136 N·m; P = 1.4834136 W."""
    c = churning_torque(R, B, H, V0, 10.0, 1e-4, RHO)
    assert c.regime == "low"
    assert (c.froude, c.reynolds, c.critical_reynolds) == pytest.approx((1.0197162, 200, 500))
    assert c.coefficient == pytest.approx(0.20702072, rel=1e-7)
    assert c.torque == pytest.approx(0.14834136, rel=1e-7)
    assert c.power == pytest.approx(1.4834136, rel=1e-7)


def test_high_speed_by_hand() -> None:
    """ω = 300 rad/s, ν = 2e-5 m²/s: Re_c = 300 × 0.1 × 0.05/2e-5 = 75 000 > 9000.
    Fr = 9e4 × 0.1/9.80665 = 917.74459.
    C_m = 3.644 × 0.25^0.1 × 0.25^−0.35 × Fr^−0.88 × 0.1^0.85
        = 3.644 × 0.87055056 × 1.6245048 × 0.0024706134 × 0.14125375 = 0.0017984491
    C_ch = ½ × 870 × 9e4 × 0.016472487 × 0.001 × 0.0017984491 = 1.1598160 N·m; P = 347.94480 W."""
    c = churning_torque(R, B, H, V0, 300.0, 2e-5, RHO)
    assert c.regime == "high"
    assert c.coefficient == pytest.approx(0.0017984491, rel=1e-7)
    assert c.torque == pytest.approx(1.1598160, rel=1e-7)
    assert c.power == pytest.approx(347.94480, rel=1e-7)
    assert churning_coefficient(R, B, H, V0, 300.0, 2e-5) == (c.coefficient, "high")


def test_scaling_laws() -> None:
    """Low speed: C_ch ∝ ω²·Fr^−0.6·Re^−0.21 ∝ ω^0.59, ∝ ν^0.21, ∝ V_0^0.1;
    high speed: ∝ ω^(2 − 1.76) = ω^0.24, independent of ν, ∝ V_0^−0.35; both ∝ ρ."""
    low = [churning_torque(R, B, H, V0, w, 1e-3, RHO).torque for w in (1.0, 2.0)]
    assert low[1] / low[0] == pytest.approx(2 ** 0.59, rel=1e-12)
    low_nu = [churning_torque(R, B, H, V0, 1.0, nu, RHO).torque for nu in (1e-3, 2e-3)]
    assert low_nu[1] / low_nu[0] == pytest.approx(2 ** 0.21, rel=1e-12)
    low_v0 = [churning_torque(R, B, H, v, 1.0, 1e-3, RHO).torque for v in (V0, 2 * V0)]
    assert low_v0[1] / low_v0[0] == pytest.approx(2 ** 0.1, rel=1e-12)
    high = [churning_torque(R, B, H, V0, w, 1e-5, RHO).torque for w in (200.0, 400.0)]
    assert high[1] / high[0] == pytest.approx(2 ** 0.24, rel=1e-12)
    high_nu = [churning_torque(R, B, H, V0, 300.0, nu, RHO).torque for nu in (1e-5, 2e-5)]
    assert high_nu[1] == pytest.approx(high_nu[0], rel=1e-12)
    high_v0 = [churning_torque(R, B, H, v, 300.0, 1e-5, RHO).torque for v in (V0, 2 * V0)]
    assert high_v0[1] / high_v0[0] == pytest.approx(2 ** -0.35, rel=1e-12)
    assert churning_torque(R, B, H, V0, 300.0, 1e-5, 2 * RHO).torque == pytest.approx(
        2 * high[0] * (300 / 200) ** 0.24, rel=1e-12)


def test_transition_interpolates_or_refuses() -> None:
    """Re_c = ω·R_p·h/ν = 7500 at ω = 15 rad/s, ν = 1e-5: halfway between the fits."""
    c = churning_torque(R, B, H, V0, 15.0, 1e-5, RHO)
    assert c.regime == "transition"
    assert c.critical_reynolds == pytest.approx(7500.0)
    expected = 0.5 * (paper_low(R, B, H, V0, 15.0, 1e-5) + paper_high(R, B, H, V0, 15.0))
    assert c.coefficient == pytest.approx(expected, rel=1e-12)
    strict = churning_torque(R, B, H, V0, 15.0, 1e-5, RHO, transition="nan")
    assert math.isnan(strict.torque)
    # just outside the band each fit applies alone
    at_low = churning_coefficient(R, B, H, V0, 11.9, 1e-5)          # Re_c = 5950
    assert at_low == (pytest.approx(paper_low(R, B, H, V0, 11.9, 1e-5), rel=1e-12), "low")
    at_high = churning_coefficient(R, B, H, V0, 18.1, 1e-5)         # Re_c = 9050
    assert at_high == (pytest.approx(paper_high(R, B, H, V0, 18.1), rel=1e-12), "high")


def test_arrays_rest_and_direction() -> None:
    speeds = np.array([-300.0, 0.0, 10.0, 300.0])
    c = churning_torque(R, B, H, V0, speeds, 2e-5, RHO)
    assert c.torque.shape == (4,)
    assert c.torque[1] == 0.0 and c.power[1] == 0.0
    assert c.torque[0] == c.torque[3] > 0
    for k, w in enumerate(speeds):
        assert c.torque[k] == pytest.approx(churning_torque(R, B, H, V0, w, 2e-5, RHO).torque,
                                            rel=1e-14)
    grid = churning_torque(R, B, np.array([[0.02], [0.05]]), V0, np.array([10.0, 300.0]),
                           2e-5, RHO)
    assert grid.torque.shape == (2, 2)
    assert np.all(np.diff(grid.torque, axis=0) > 0)        # deeper dips churn more


@pytest.mark.parametrize("kwargs, match", [
    (dict(pitch_radius=0.0), "pitch_radius"),
    (dict(immersion=-0.01), "immersion"),
    (dict(viscosity=0.0), "viscosity"),
    (dict(density=-1.0), "density"),
    (dict(oil_volume=0.0), "oil_volume"),
    (dict(transition="linear"), "transition"),
])
def test_refusals(kwargs, match) -> None:
    args = dict(pitch_radius=R, face_width=B, immersion=H, oil_volume=V0, speed=100.0,
                viscosity=2e-5, density=RHO)
    args.update(kwargs)
    with pytest.raises(ModelError, match=match):
        churning_torque(**args)
    with pytest.raises(ModelError, match="speed"):
        churning_coefficient(R, B, H, V0, 0.0, 2e-5)
