"""Contact ratios and Ohlendorf's loss factor of involute pairs.

Expected values come from the textbook contact-ratio formula written out below, and from an
independent brute-force simulation of the sliding friction power along the line of action
(the physical definition of the loss factor), not from the module's own output.
"""
from __future__ import annotations

import json
import math

import numpy as np
import pytest

from powergraph.gears.mesh_loss import MeshGeometry, mesh_loss, path_of_contact, sliding_integral
from powergraph.cli.main import main
from powergraph.errors import ModelError

ALPHA = math.radians(20.0)


def _simulated_loss_factor(z1: int, z2: int, internal: bool, e1: float, e2: float,
                           samples: int = 200_001) -> float:
    """Mean sliding friction power over one base pitch / (μ · transmitted power), spur.

    Pinion speed 1 rad/s, base pitch p_b; a pair at distance x (along the line of action,
    from the pitch point) slides at |ω1 − ω2|·|x| with ω2 = ∓ω1·z1/z2 (external: opposite
    sense); the n pairs in contact share the base force F equally. Power transmitted: F·r_b1.
    """
    m = 1.0
    rb1 = m * z1 / 2 * math.cos(ALPHA)
    p_b = math.pi * m * math.cos(ALPHA)
    omega_rel = 1.0 + z1 / z2 if not internal else 1.0 - z1 / z2
    s = (np.arange(samples) + 0.5) / samples            # travel, in base pitches
    loss = np.zeros_like(s)
    count = np.zeros_like(s)
    for k in range(-4, 5):
        x = s - k
        inside = (x >= -e2) & (x <= e1)
        loss += np.where(inside, np.abs(x) * p_b * omega_rel, 0.0)
        count += inside
    mean_loss = np.mean(loss / count)                   # per unit F and unit μ
    return mean_loss / rb1


def test_standard_external_spur_pair_by_hand() -> None:
    # z1 = 20, z2 = 40, m = 1, α = 20°, standard addendum: r = 10, 20; r_a = 11, 21.
    r1, r2, ra1, ra2 = 10.0, 20.0, 11.0, 21.0
    rb1, rb2 = r1 * math.cos(ALPHA), r2 * math.cos(ALPHA)
    p_b = math.pi * math.cos(ALPHA)
    g1 = math.sqrt(ra1**2 - rb1**2) - r1 * math.sin(ALPHA)   # pinion tip side of the path
    g2 = math.sqrt(ra2**2 - rb2**2) - r2 * math.sin(ALPHA)   # wheel tip side
    e1, e2 = g1 / p_b, g2 / p_b
    # Textbook contact ratio: (√(ra1²−rb1²) + √(ra2²−rb2²) − a sin α) / p_b, a = 30.
    eps = (math.sqrt(ra1**2 - rb1**2) + math.sqrt(ra2**2 - rb2**2) - 30 * math.sin(ALPHA)) / p_b
    u = 2.0
    h_v = math.pi * (u + 1) / (20 * u) * (1 - eps + e1**2 + e2**2)   # Ohlendorf, spur
    loss = mesh_loss(MeshGeometry(20, 40), mu=0.05)
    assert loss.epsilon_alpha == pytest.approx(eps, rel=1e-12)
    assert loss.epsilon_1 == pytest.approx(e1, rel=1e-12)
    assert loss.epsilon_2 == pytest.approx(e2, rel=1e-12)
    assert loss.loss_factor == pytest.approx(h_v, rel=1e-12)
    assert loss.efficiency == pytest.approx(1 - 0.05 * h_v, rel=1e-15)
    assert 1.63 < eps < 1.64 and 0.165 < h_v < 0.167     # the order of magnitude by hand


@pytest.mark.parametrize("z1, z2, internal", [(20, 40, False), (17, 23, False),
                                              (30, 80, True), (25, 60, True)])
def test_loss_factor_equals_simulated_sliding_power(z1: int, z2: int, internal: bool) -> None:
    loss = mesh_loss(MeshGeometry(z1, z2, internal=internal))
    simulated = _simulated_loss_factor(z1, z2, internal, loss.epsilon_1, loss.epsilon_2)
    assert loss.loss_factor == pytest.approx(simulated, rel=1e-4)


@pytest.mark.parametrize("e1, e2", [(0.7, 0.8), (0.45, 0.6), (0.99, 0.98), (0.2, 0.85)])
def test_closed_form_bracket_is_the_load_shared_sliding(e1: float, e2: float) -> None:
    # Piecewise by hand for 1 <= ε < 2: single contact in [e1 − 1, 1 − e2] carries the whole
    # load, double contact elsewhere half: 2·(((1−e1)² + (1−e2)²)/2 + (e1² + e2² −
    # (1−e1)² − (1−e2)²)/4) = 1 − ε + e1² + e2².
    by_hand = 2 * (((1 - e1)**2 + (1 - e2)**2) / 2
                   + (e1**2 + e2**2 - (1 - e1)**2 - (1 - e2)**2) / 4)
    assert sliding_integral(e1, e2) == pytest.approx(by_hand, rel=1e-12)


def test_high_contact_ratio_uses_the_exact_integral() -> None:
    # ε_2 >= 1: outside Ohlendorf's closed form; two or three pairs share the load.
    e1, e2 = 0.83, 1.11
    by_sampling = 2 * np.mean([
        sum(abs(s - k) for k in range(-3, 4) if -e2 <= s - k <= e1)
        / sum(1 for k in range(-3, 4) if -e2 <= s - k <= e1)
        for s in (np.arange(100_000) + 0.5) / 100_000])
    assert sliding_integral(e1, e2) == pytest.approx(by_sampling, rel=1e-6)


def test_module_does_not_change_the_loss_factor_and_helix_divides_by_cos_beta_b() -> None:
    base = mesh_loss(MeshGeometry(20, 40, module=1.0))
    assert mesh_loss(MeshGeometry(20, 40, module=4.5)).loss_factor == pytest.approx(
        base.loss_factor, rel=1e-12)
    helical = mesh_loss(MeshGeometry(20, 40, helix_angle_deg=15.0))
    beta_b = math.asin(math.sin(math.radians(15)) * math.cos(ALPHA))
    bracket = 1 - helical.epsilon_alpha + helical.epsilon_1**2 + helical.epsilon_2**2
    assert helical.loss_factor == pytest.approx(
        math.pi * 3 / (20 * 2 * math.cos(beta_b)) * bracket, rel=1e-12)


def test_positive_shift_moves_contact_into_recess() -> None:
    plain = mesh_loss(MeshGeometry(18, 50))
    shifted = mesh_loss(MeshGeometry(18, 50, shift_1=0.4, shift_2=-0.4))
    assert shifted.epsilon_1 > plain.epsilon_1 and shifted.epsilon_2 < plain.epsilon_2


@pytest.mark.parametrize("geometry, fragment", [
    (MeshGeometry(20, 60, internal=True), "interference"),
    (MeshGeometry(20, 40, addendum=0.3), "contact ratio"),
    (MeshGeometry(20, 15, internal=True), "more teeth"),
    (MeshGeometry(20, 40, module=float("nan")), "module"),
    # x1 = −2: r_a1 = 7.5 − 1 = 6.5 mm inside r_b1 = 7.5 cos 20° = 7.05 mm
    (MeshGeometry(15, 48, internal=True, shift_1=-2.0), "pinion's tip circle"),
])
def test_impossible_pairs_are_refused(geometry: MeshGeometry, fragment: str) -> None:
    with pytest.raises(ModelError, match=fragment):
        mesh_loss(geometry)


def test_cli_json(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["mesh", "20", "40", "--mu", "0.05", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert set(data) >= {"epsilon_alpha", "epsilon_1", "epsilon_2", "loss_factor",
                         "efficiency", "mu"}
    assert data["efficiency"] == pytest.approx(1 - 0.05 * data["loss_factor"], rel=1e-15)


def test_cli_refuses_an_impossible_pair_with_one_line(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["mesh", "20", "15", "--internal"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "more teeth" in err[0]


def _ohlendorf_by_hand(z1: int, z2: int, internal: bool) -> tuple[float, float, float]:
    """Standard spur pair (m 1, α 20°, addendum 1, no shift), by the textbook: the path
    of contact on each tip side over the base pitch, and Ohlendorf's closed form
    H_V = π (u + 1)/(z1 u) (1 − ε_α + ε_1² + ε_2²), u = ±z2/z1 (negative internal)."""
    r1, r2 = z1 / 2, z2 / 2
    rb1, rb2, p_b = r1 * math.cos(ALPHA), r2 * math.cos(ALPHA), math.pi * math.cos(ALPHA)
    e1 = (math.sqrt((r1 + 1) ** 2 - rb1 ** 2) - r1 * math.sin(ALPHA)) / p_b
    if internal:     # the ring's tip circle is inside its pitch circle
        e2 = (r2 * math.sin(ALPHA) - math.sqrt((r2 - 1) ** 2 - rb2 ** 2)) / p_b
    else:
        e2 = (math.sqrt((r2 + 1) ** 2 - rb2 ** 2) - r2 * math.sin(ALPHA)) / p_b
    u = -z2 / z1 if internal else z2 / z1
    return e1, e2, math.pi * (u + 1) / (z1 * u) * (1 - (e1 + e2) + e1 ** 2 + e2 ** 2)


@pytest.mark.parametrize("z1, z2, internal, h_v, eta", [
    (20, 40, False, 0.1661, 0.9917), (20, 60, True, 0.1077, 0.9946), (12, 36, False, 0.2318,
                                                                       None)])
def test_ohlendorf_values_of_standard_pairs(z1, z2, internal, h_v, eta, capsys) -> None:
    """The loss factors quoted for standard 20° spur pairs (20/40, 20/−60, 12/36; η at
    μ 0.05), within 1e-3, and the same quantities by hand. 20/−60 and 12/36 are past an
    interference point with standard teeth: `powergraph mesh` computes them with a warning
    (a model file refuses them). For 20/−60 ε_2 > 1, outside the closed form's domain:
    ``ohlendorf_loss_factor`` is the published closed form, ``loss_factor`` the exact
    load-shared integral (smaller: two pairs share the load over more of the path)."""
    e1, e2, by_hand = _ohlendorf_by_hand(z1, z2, internal)
    loss = mesh_loss(MeshGeometry(z1, z2, internal=internal), mu=0.05, strict=False)
    assert (loss.epsilon_1, loss.epsilon_2) == pytest.approx((e1, e2), rel=1e-12)
    assert loss.ohlendorf_loss_factor == pytest.approx(by_hand, rel=1e-12)
    assert loss.ohlendorf_loss_factor == pytest.approx(h_v, abs=1e-3)
    if eta is not None:
        assert 1 - 0.05 * loss.ohlendorf_loss_factor == pytest.approx(eta, abs=1e-4)
    if e2 < 1:
        assert loss.loss_factor == pytest.approx(by_hand, rel=1e-12)
    else:
        assert loss.loss_factor == pytest.approx(
            by_hand / (1 - (e1 + e2) + e1 ** 2 + e2 ** 2) * sliding_integral(e1, e2), rel=1e-12)
        assert loss.loss_factor < loss.ohlendorf_loss_factor
    assert bool(loss.warnings) == ((z1, z2) != (20, 40))
    args = ["mesh", str(z1), str(z2), "--mu", "0.05", "--json"] + (["--internal"] if internal
                                                                    else [])
    assert main(args) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["ohlendorf_loss_factor"] == pytest.approx(by_hand, rel=1e-12)
    assert len(data["warnings"]) == len(loss.warnings)


def test_iso14179_mean_friction_coefficient_by_hand() -> None:
    # m = 2, z = 20/40, α = 20°, spur, standard: radii of curvature at the pitch point
    # ρ = r·sin α, F_bt/b = F_t/cos α/b, v_Σ = 2·v_t·sin α; the standard's fit with
    # η_oil = 30 mPa·s, Ra = 0.5 µm, X_L = 1.
    from powergraph.gears.mesh_loss import iso14179_mu

    rho_1, rho_2 = 20 * math.sin(ALPHA), 40 * math.sin(ALPHA)     # 6.8404, 13.6808 mm
    rho_red = rho_1 * rho_2 / (rho_1 + rho_2)                      # 4.5603 mm
    load = 1000 / math.cos(ALPHA) / 20                             # 53.209 N/mm
    v_sum = 2 * 5 * math.sin(ALPHA)                                # 3.4202 m/s
    by_hand = 0.048 * (load / (v_sum * rho_red)) ** 0.2 * 30 ** -0.05 * 0.5 ** 0.25
    mu = iso14179_mu(1000.0, 20.0, 5.0, MeshGeometry(20, 40, module=2.0), 30.0, 0.5)
    assert mu == pytest.approx(by_hand, rel=1e-12)
    assert 0.0435 < mu < 0.0436
    # The fit's exponents: doubling the load raises μ by 2^0.2, doubling the speed lowers it.
    g = MeshGeometry(20, 40, module=2.0)
    assert iso14179_mu(2000.0, 20.0, 5.0, g, 30.0, 0.5) / mu == pytest.approx(2 ** 0.2)
    assert iso14179_mu(1000.0, 20.0, 10.0, g, 30.0, 0.5) / mu == pytest.approx(2 ** -0.2)
    # An internal pair has a larger reduced radius of curvature, hence a smaller μ.
    ring = MeshGeometry(20, 60, internal=True, module=2.0, addendum=0.8)
    assert iso14179_mu(1000.0, 20.0, 5.0, ring, 30.0, 0.5) < mu


def test_fzg_c40_pair_agrees_with_the_porto_groups_own_code() -> None:
    # The FZG type C40 test pair (z 16/24, m 4.5 mm, α 20°, x 0.1817/0.1715, b 40 mm) as
    # given in the public code of the Porto group whose FZG power-loss measurements are
    # discussed in docs/losses.md ("Against measurements"): cfernandesFEUP/Gear-Calculation,
    # GearC/gears.py, gear 'C40'. Their GEARpie report of the same pair (REPORT/C40.txt)
    # prints: working pitch radii 36.600 / 54.900 mm, base radii 33.829 / 50.743 mm, base
    # pitch 13.285 mm, T1T2 34.93 mm, AC 9.68 mm, AD 13.28 mm, AE 19.43 mm, ε_α 1.46, and
    # the loss factor H_V 0.1986 (Ohlendorf) / 0.1984 (Wimmer, numerical). An independent
    # implementation, not a measurement: it checks the geometry a comparison with their
    # measured torque losses would rest on.
    g = MeshGeometry(16, 24, module=4.5, shift_1=0.1817, shift_2=0.1715)
    path = path_of_contact(g)
    loss = mesh_loss(g)
    assert round(path.working_radius_1, 3) == 36.600
    assert round(path.working_radius_2, 3) == 54.900
    assert round(path.base_pitch, 3) == 13.285
    assert round(36.0 * math.cos(ALPHA), 3) == 33.829          # base radii, r·cos α
    assert round(54.0 * math.cos(ALPHA), 3) == 50.743
    t1t2 = (path.working_radius_1 + path.working_radius_2) * math.sin(path.working_pressure_angle)
    assert round(t1t2, 2) == 34.93
    assert round(path.addendum_path_2, 2) == 9.68                # A to the pitch point C
    assert round(loss.epsilon_alpha * path.base_pitch, 2) == 19.43   # AE
    assert round(loss.epsilon_alpha, 2) == 1.46
    assert round(loss.loss_factor, 4) == 0.1986
    assert loss.loss_factor == pytest.approx(0.1984, rel=2e-3)    # Wimmer's numerical H_VL
