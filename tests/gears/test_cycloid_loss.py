"""Basic efficiency of a cycloid stage from friction: pins, output pins, crank bearing.

Expected values come from closed forms derived here by hand (the many-pins limits), from
exact identities of the geometry, and from brute-force kinematics of the pin contacts.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from powergraph.errors import ModelError
from powergraph.gears.cycloid import (lever_arm, pin_forces, pin_phases, pitch_distance,
                                      trochoid)
from powergraph.gears.cycloid_loss import (CrankBearing, OutputPins, PinContact, PinRing,
                                           bearing_loss_factor, cycloid_mesh_loss,
                                           output_loss_factor, pin_loss_factor)

#: The RV-40E's cycloid stage as used in published studies (models/rv40e_wang2021.yaml).
RV = PinRing(lobes=39, circle_radius=64.0, pin_radius=3.0, eccentricity=1.3)


def hand_sliding_limit(stage: PinRing) -> float:
    """Many-pins limit of the sliding pins' loss factor, derived by hand.

    In the crank's frame the disc turns at ω (= ω_d − ω_c) and the ring at ω·z_c/z_p, so
    the disc moves relative to the ring about the pitch point I (at z_p·e from the ring
    centre) at ω/z_p: a pin whose contact lies at s = D − r_p from I slides at ω·s/z_p —
    the mean sliding speed over the crank-frame rolling speed is (s/z_p)/λ per unit force.
    The pin at phase u has D = R_p·sqrt(1 + K² − 2K cos u) (K = z_p e/R_p) and lever arm
    λ = z_c·e·sin u/sqrt(1 + K² − 2K cos u) (u ∈ (0, π) up to the flank's sign). With
    F ∝ λ, spread over a continuum of pins,

        H = (1/z_p)·∫ λ (D − r_p) du / ∫ λ² du.

    ∫_0^π λ·D du = z_c e R_p ∫ sin u du = 2 z_c e R_p;
    ∫_0^π λ du = z_c e ∫ sin u/sqrt(1 + K² − 2K cos u) du = z_c e·[(1 + K) − (1 − K)]/K = 2 z_c e
    (substitute w = 1 + K² − 2K cos u); ∫_0^π sin²u/(1 + K² − 2K cos u) du = π/2 for
    K < 1 (expand 1/(1 + K² − 2K cos u) in its Poisson-kernel cosine series: only the
    constant term 1/(1 − K²) and the cos 2u term survive against sin²u, giving
    π/2·(1 − K²)/(1 − K²); checked by quadrature below), so ∫ λ² du = (z_c e)² π/2, and

        H = 4 (R_p − r_p) / (π z_c z_p e).
    """
    return 4 * (stage.circle_radius - stage.pin_radius) / (
        math.pi * stage.lobes * stage.pins * stage.eccentricity)


def test_zero_friction_is_ideal() -> None:
    loss = cycloid_mesh_loss(RV, PinContact(0.0), bearing=CrankBearing(0.0, 13.0, 36.0))
    assert loss.efficiency == 1.0
    loss = cycloid_mesh_loss(RV, PinContact(0.0), OutputPins(8, 40.0, 0.0),
                             CrankBearing(0.0, 20.0))
    assert loss.efficiency == 1.0


def test_small_mu_is_linear() -> None:
    one, two = (1 - cycloid_mesh_loss(RV, PinContact(mu)).efficiency for mu in (1e-4, 2e-4))
    assert two == pytest.approx(2 * one, rel=1e-12)
    assert one == pytest.approx(1e-4 * pin_loss_factor(RV, PinContact(1.0)), rel=1e-12)


@pytest.mark.parametrize("k", [0.3, 0.8125, 0.95])
def test_the_integrals_of_the_hand_limit(k: float) -> None:
    u = (np.arange(200000) + 0.5) * np.pi / 200000
    w = 1 + k * k - 2 * k * np.cos(u)
    assert np.mean(np.sin(u) ** 2 / w) * np.pi == pytest.approx(np.pi / 2, rel=1e-8)
    assert np.mean(np.sin(u) / np.sqrt(w)) * np.pi == pytest.approx(2.0, rel=1e-8)


@pytest.mark.parametrize("lobes, rel", [(39, 1e-5), (119, 1e-7), (1001, 1e-9)])
def test_sliding_pins_approach_the_hand_closed_form(lobes: int, rel: float) -> None:
    stage = PinRing(lobes, circle_radius=(lobes + 1) * 1.3 / 0.8125, pin_radius=1.0,
                    eccentricity=1.3)
    h = pin_loss_factor(stage, PinContact(0.05))
    assert h == pytest.approx(hand_sliding_limit(stage), rel=rel)


def test_rv40e_pin_loss_factor_and_efficiency() -> None:
    # H = 4·61/(π·39·40·1.3) = 0.038298; with μ = 0.05, η = 1 − 0.05·H (within the
    # discrete-pin correction, < 1e-5 relative for 40 pins).
    assert pin_loss_factor(RV, PinContact(0.05)) == pytest.approx(244 / (math.pi * 2028),
                                                                 rel=1e-5)


def test_sliding_speed_brute_force_against_the_pitch_point_rule() -> None:
    """The pitch-point rule (slip = |ω_d − ω_r|·(D − r_p)) against differentiated positions:
    pin k's contact point on the disc, moved with the disc (crank frame, ω_d − ω_c = 1),
    compared with the ring's pin (ω_r − ω_c = z_c/z_p) at the same place."""
    stage, theta = RV, 0.2
    z_c, z_p, e = stage.lobes, stage.pins, stage.eccentricity

    def contact(k: int, angle: float) -> complex:
        # Ring frame: pin k at R_p·exp(2πik/z_p) (phase θ − 2πk/z_p from the line of
        # centres at angle θ); the contact lies r_p from it towards the pitch point.
        pin = stage.circle_radius * np.exp(2j * np.pi * k / z_p)
        pitch = z_p * e * np.exp(1j * angle)
        return pin + stage.pin_radius * (pitch - pin) / abs(pitch - pin)

    for k in range(z_p):
        u = pin_phases(z_c, theta)[k]
        if lever_arm(z_c, stage.circle_radius, e, u) <= 0:
            continue
        # Disc: centre e·exp(iθ), turning by −θ/z_c as the crank turns θ (ring fixed).
        # A material point of the disc at the contact moves with velocity
        # v = d/dθ[C(θ)] + (−1/z_c)·i·(Q − C), per unit crank speed.
        q, centre = contact(k, theta), e * np.exp(1j * theta)
        v = 1j * centre + (-1 / z_c) * 1j * (q - centre)
        d_theta_rel = 1 + 1 / z_c              # |ω_d − ω_c| per unit crank speed
        expected = abs(v) / d_theta_rel        # the ring's point is at rest
        reach = pitch_distance(z_c, stage.circle_radius, e, u) - stage.pin_radius
        assert reach / z_p == pytest.approx(expected, rel=1e-9)
        # and the contact point moves along the disc profile (tangent ⟂ normal).
        normal = (contact(k, theta) - stage.circle_radius * np.exp(2j * np.pi * k / z_p))
        assert abs((v * np.conj(normal)).real) < 1e-9 * abs(v) * abs(normal)


def test_pin_forces_carry_the_torque_and_their_moment_arm_is_the_pitch_radius() -> None:
    # Every normal passes through the pitch point, z_c·e from the disc centre on the line
    # of centres: the resultant's component across that line is exactly T/(z_c e).
    forces, resultant = pin_forces(39, 64.0, 1.3, np.linspace(0, 0.16, 7))
    arms = lever_arm(39, 64.0, 1.3, pin_phases(39, np.linspace(0, 0.16, 7)))
    assert np.allclose((forces * arms).sum(axis=1), 1.0, rtol=1e-12)
    assert np.allclose(resultant.imag, 1 / (39 * 1.3), rtol=1e-12)


def test_trochoid_distance_to_pitch_point_is_the_normal() -> None:
    # The profile normal at a pin's ideal contact passes through the pitch point: the
    # trochoid's normal there points at the pitch point (disc frame, pin 0 at crank 0.3).
    t = 0.3 / 39
    value, d1, _ = trochoid(64.0, 1.3, 40, np.array([t]))
    normal = -1j * d1[0] / abs(d1[0])
    # In the disc frame the pitch point sits z_c·e from the centre along the crank, which
    # turns by θ + θ/z_c relative to the disc: at angle 40·t.
    pitch = 39 * 1.3 * np.exp(1j * 40 * t)
    towards = (pitch - value[0]) / abs(pitch - value[0])
    assert abs((normal * np.conj(towards)).imag) < 1e-9


def test_rolling_pins_in_seats_of_their_own_radius_lose_as_much_per_mu() -> None:
    sliding = pin_loss_factor(RV, PinContact(0.05))
    assert pin_loss_factor(RV, PinContact(0.05, rolling=True)) == pytest.approx(sliding)
    assert pin_loss_factor(RV, PinContact(0.05, rolling=True, seat_radius=1.5)) \
        == pytest.approx(sliding / 2)


def test_output_pins_many_pin_limit() -> None:
    # Loaded half: F_j ∝ |sin φ_j|; Σ|sin| → n/π, Σ sin² → n/4, so H = e·(4/π)/R_w.
    assert output_loss_factor(1.3, OutputPins(4000, 40.0, 0.05)) \
        == pytest.approx(4 * 1.3 / (math.pi * 40.0), rel=1e-6)
    # Two pins: one loaded at a time, F = T/(R_w |sin φ|): H = e·mean(1/|sin φ|) diverges
    # logarithmically — check a finite case by hand instead: four pins at 45°, 135°, ...
    # (β varies, so compare the mean with a direct quadrature).
    beta = (np.arange(100000) + 0.5) * 2 * np.pi / 100000
    phi = beta[:, None] + np.arange(4) * np.pi / 2
    s = np.maximum(-np.sin(phi), 0)
    hand = 1.3 / 40 * np.mean(s.sum(1) / (s ** 2).sum(1))
    assert output_loss_factor(1.3, OutputPins(4, 40.0, 0.05)) == pytest.approx(hand, rel=1e-4)


def test_rolling_output_sleeves_scale_with_the_seat() -> None:
    plain = output_loss_factor(1.3, OutputPins(8, 40.0, 0.05))
    sleeve = output_loss_factor(1.3, OutputPins(8, 40.0, 0.05, rolling=True, radius=6.0,
                                                seat_radius=4.0))
    assert sleeve == pytest.approx(plain * 4 / 6, rel=1e-12)


def test_rv_crank_bearings_limits() -> None:
    # N cranks on R_c: Σ|F_i| = mean_β |R + e^{iβ}/R_c|. With R_c → 0 the tangential
    # forces dominate: r_b/R_c; with R_c → ∞ only the pin resultant is left.
    h_small = bearing_loss_factor(RV, CrankBearing(0.002, 13.0, 1e-6))
    assert h_small == pytest.approx(13.0 / 1e-6, rel=1e-3)
    h_far = bearing_loss_factor(RV, CrankBearing(0.002, 13.0, 1e12))
    _, resultant = pin_forces(39, 64.0, 1.3, (np.arange(256) + 0.5) * 2 * np.pi / 40 / 256)
    assert h_far == pytest.approx(13.0 * np.abs(resultant).mean(), rel=1e-9)
    # The resultant is at least its cross-line part T/(z_c e) (exact, see above).
    assert h_far >= 13.0 / (39 * 1.3)


def test_central_crank_bearing_carries_pins_and_output_pins() -> None:
    # Many output pins push along −x with Σ F = (4/π)/R_w per unit torque; the pin
    # resultant is (R_x, 1/(z_c e)). Their sum's magnitude, times the bore radius.
    h = bearing_loss_factor(RV, CrankBearing(0.002, 20.0), OutputPins(4000, 40.0, 0.05))
    _, resultant = pin_forces(39, 64.0, 1.3, (np.arange(256) + 0.5) * 2 * np.pi / 40 / 256)
    hand = 20.0 * np.abs(resultant - 4 / (math.pi * 40.0)).mean()
    assert h == pytest.approx(hand, rel=1e-5)


def test_efficiency_is_the_product_of_the_three() -> None:
    loss = cycloid_mesh_loss(RV, PinContact(0.05), OutputPins(8, 40.0, 0.04),
                             CrankBearing(0.002, 20.0))
    assert loss.efficiency == pytest.approx(
        (1 - 0.05 * loss.pin_loss_factor) * (1 - 0.04 * loss.output_loss_factor)
        * (1 - 0.002 * loss.bearing_loss_factor), rel=1e-15)
    assert "basic efficiency" in loss.text_report()
    assert loss.to_dict()["efficiency"] == loss.efficiency


@pytest.mark.parametrize("stage, words", [
    (PinRing(39, 64.0, 3.0, 1.7), "looped"),
    (PinRing(39, 64.0, 5.5, 1.3), "overlap"),
    (PinRing(39, 64.0, 4.8, 1.3), "undercut"),
    (PinRing(2, 64.0, 3.0, 1.3), "lobes"),
    (PinRing(39, 64.0, 3.0, -1.0), "eccentricity"),
])
def test_impossible_stages_are_refused(stage: PinRing, words: str) -> None:
    with pytest.raises(ModelError, match=words):
        cycloid_mesh_loss(stage, PinContact(0.05))


def test_bad_coefficients_and_mechanisms_are_refused() -> None:
    with pytest.raises(ModelError, match="coefficient"):
        cycloid_mesh_loss(RV, PinContact(1.5))
    with pytest.raises(ModelError, match="output mechanism"):
        cycloid_mesh_loss(RV, PinContact(0.05), OutputPins(8, 40.0, 0.05),
                          CrankBearing(0.002, 13.0, 36.0))
