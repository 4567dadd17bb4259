"""The basic efficiency of an involute gear pair from its geometry and a friction coefficient.

Ohlendorf's tooth loss factor ``H_V`` turns a mean coefficient of friction ``μ`` into the
pair's basic (carrier-held) efficiency, ``η = 1 − μ·H_V``. It is the sliding power along
the path of contact, with the load shared equally by two pairs in the double-contact zones,
averaged over one base pitch and divided by the transmitted power:

``H_V = π (u + 1) / (z1 u cos β_b) · (1 − ε_α + ε_1² + ε_2²)``

with ``u = z2/z1`` (negative for an internal pair), ``β_b`` the base helix angle, ``ε_1``
and ``ε_2`` the addendum contact ratios (the part of the path of contact on the tip side of
each gear, over the transverse base pitch) and ``ε_α = ε_1 + ε_2``. The closed form holds for
``1 <= ε_α < 2`` with ``ε_1, ε_2 < 1``; outside that range (internal pairs often have
``ε_2 >= 1``) the same load-shared sliding integral is evaluated exactly
(:func:`sliding_integral`). docs/losses.md derives both.

Conventions (DIN 3960, ISO 21771): module and lengths in mm, normal module ``m``, normal
pressure angle ``α_n``, helix angle ``β``; profile shift coefficients ``x1``, ``x2``; an
internal gear 2 has its tip inside the reference circle, ``r_a2 = r_2 − m (h_a* − x2)``.

Examples
--------
>>> loss = mesh_loss(MeshGeometry(20, 40), mu=0.05)
>>> round(loss.epsilon_alpha, 4), round(loss.loss_factor, 4), round(loss.efficiency, 5)
(1.6352, 0.1661, 0.9917)
"""
from __future__ import annotations

import math
from dataclasses import asdict
from functools import lru_cache
from typing import Any

import numpy as np

from powergraph.gears.involute import involute, inverse_involute
from powergraph.errors import ModelError
from powergraph.records import record


@record
class MeshGeometry:
    """The geometry of an involute pair that the loss factor needs.

    Parameters
    ----------
    teeth_1, teeth_2 : int
        Tooth numbers of the pinion (gear 1, external) and of gear 2.
    internal : bool
        Gear 2 is an internal gear (ring).
    module : float
        Normal module, mm (the loss factor does not depend on it; the speeds do).
    pressure_angle_deg, helix_angle_deg : float
        Normal pressure angle (default 20°) and helix angle (default 0°, spur).
    shift_1, shift_2 : float
        Profile shift coefficients (default 0).
    addendum : float
        Addendum coefficient ``h_a*`` (default 1).
    """

    teeth_1: int
    teeth_2: int
    internal: bool = False
    module: float = 1.0
    pressure_angle_deg: float = 20.0
    helix_angle_deg: float = 0.0
    shift_1: float = 0.0
    shift_2: float = 0.0
    addendum: float = 1.0


@record
class PathOfContact:
    """Transverse geometry of the pair: radii (mm), angles (rad) and the path of contact."""

    base_pitch: float
    working_pressure_angle: float
    base_helix_angle: float
    working_radius_1: float
    working_radius_2: float
    addendum_path_1: float   # from the pitch point to the end of contact on gear 1's tip side
    addendum_path_2: float   # from the pitch point to the start of contact on gear 2's tip side
    warnings: tuple[str, ...] = ()


@record
class MeshLoss:
    """Contact ratios, Ohlendorf's loss factor and (with ``mu``) the basic efficiency."""

    geometry: MeshGeometry
    epsilon_alpha: float
    epsilon_1: float
    epsilon_2: float
    loss_factor: float
    mu: float | None = None
    warnings: tuple[str, ...] = ()

    @property
    def ohlendorf_loss_factor(self) -> float:
        """Ohlendorf's closed form ``π(u + 1)/(z1 u cos β_b)·(1 − ε_α + ε_1² + ε_2²)`` as
        published, whatever the contact ratios: equal to :attr:`loss_factor` within its
        domain (``ε_1, ε_2 < 1``, ``ε_α < 2``); outside it :attr:`loss_factor` is the exact
        load-shared integral and this the textbook value, kept for comparison."""
        e1, e2 = self.epsilon_1, self.epsilon_2
        return self._scale * (1 - (e1 + e2) + e1 ** 2 + e2 ** 2)

    @property
    def _scale(self) -> float:
        g = self.geometry
        u = (-1.0 if g.internal else 1.0) * g.teeth_2 / g.teeth_1
        beta_b = math.asin(math.sin(math.radians(g.helix_angle_deg))
                           * math.cos(math.radians(g.pressure_angle_deg)))
        return math.pi * (u + 1) / (g.teeth_1 * u * math.cos(beta_b))

    @property
    def efficiency(self) -> float | None:
        """``1 − μ·H_V``, or None when no friction coefficient was given."""
        return None if self.mu is None else 1.0 - self.mu * self.loss_factor

    def to_dict(self) -> dict[str, Any]:
        """JSON view: ``epsilon_alpha, epsilon_1, epsilon_2, loss_factor, efficiency``
        (and ``mu`` when given), plus the geometry."""
        out: dict[str, Any] = {"epsilon_alpha": self.epsilon_alpha, "epsilon_1": self.epsilon_1,
                               "epsilon_2": self.epsilon_2, "loss_factor": self.loss_factor,
                               "efficiency": self.efficiency,
                               "ohlendorf_loss_factor": self.ohlendorf_loss_factor}
        if self.mu is not None:
            out["mu"] = self.mu
        out["warnings"] = list(self.warnings)
        out["geometry"] = asdict(self.geometry)
        return out

    def text_report(self) -> str:
        g = self.geometry
        kind = "internal" if g.internal else "external"
        lines = [f"{kind} pair {g.teeth_1}/{g.teeth_2}, m {g.module:g} mm, "
                 f"α_n {g.pressure_angle_deg:g}°, β {g.helix_angle_deg:g}°, "
                 f"x {g.shift_1:g}/{g.shift_2:g}",
                 f"contact ratio ε_α        {self.epsilon_alpha:.4f}",
                 f"addendum ratios ε_1, ε_2 {self.epsilon_1:.4f}, {self.epsilon_2:.4f}",
                 f"loss factor H_V          {self.loss_factor:.5f}"]
        if abs(self.ohlendorf_loss_factor - self.loss_factor) > 1e-12 * self.loss_factor:
            lines.append(f"  Ohlendorf's closed form {self.ohlendorf_loss_factor:.5f} "
                         "(outside its domain: H_V above is the exact load-shared integral)")
        if self.mu is not None:
            lines += [f"friction coefficient μ   {self.mu:g}",
                      f"basic efficiency         {self.efficiency:.6f}"]
        lines += [f"warning: {w}" for w in self.warnings]
        return "\n".join(lines)

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """Nothing to draw: raises :class:`~powergraph.result.NothingToDrawError`."""
        from powergraph.result import nothing_to_draw

        raise nothing_to_draw(self, "print text_report() for the contact ratios and loss "
                                    "factor")


def path_of_contact(g: MeshGeometry, strict: bool = True) -> PathOfContact:
    """The transverse path of contact of an involute pair (DIN 3960 formulas).

    Kept for the last pairs asked for (a geometry is frozen; a friction solve asks for
    the same pair's path every pass).

    Raises ModelError when the pair cannot mesh (teeth, shifts or addenda out of range), and
    when a tip passes the other gear's interference point (an undercut flank) — unless
    ``strict`` is False, which computes the involute path all the same and lists the
    interference in ``warnings`` (a calculator's answer for a pair a model may not use).

    >>> p = path_of_contact(MeshGeometry(20, 40))
    >>> round(p.addendum_path_1, 4), round(p.addendum_path_2, 4)
    (2.298, 2.5293)
    """
    return _path_of_contact(g, strict)


@lru_cache(maxsize=256)
def _path_of_contact(g: MeshGeometry, strict: bool) -> PathOfContact:
    _check(g)
    alpha_n, beta = math.radians(g.pressure_angle_deg), math.radians(g.helix_angle_deg)
    alpha_t = math.atan(math.tan(alpha_n) / math.cos(beta))
    m_t = g.module / math.cos(beta)
    r1, r2 = m_t * g.teeth_1 / 2, m_t * g.teeth_2 / 2
    rb1, rb2 = r1 * math.cos(alpha_t), r2 * math.cos(alpha_t)
    sign = -1.0 if g.internal else 1.0          # z2 < 0 in DIN 3960's internal convention
    inv_w = involute(alpha_t) + 2 * math.tan(alpha_n) * (g.shift_1 + sign * g.shift_2) \
        / (g.teeth_1 + sign * g.teeth_2)
    alpha_w = inverse_involute(inv_w)
    ra1 = r1 + g.module * (g.addendum + g.shift_1)
    ra2 = r2 + sign * g.module * (g.addendum + sign * g.shift_2)
    rw1, rw2 = rb1 / math.cos(alpha_w), rb2 / math.cos(alpha_w)
    if ra1 <= rb1:
        raise ModelError(f"the pinion's tip circle (r {ra1:.4g} mm) lies inside its base "
                         f"circle (r {rb1:.4g} mm): it has no involute flank to mesh with")
    tip_1 = math.sqrt(ra1 ** 2 - rb1 ** 2) - rw1 * math.sin(alpha_w)
    if ra2 <= rb2:
        raise ModelError(f"gear 2's tip circle (r {ra2:.4g} mm) lies inside its base circle "
                         f"(r {rb2:.4g} mm): it has no involute flank to mesh with")
    tip_2 = sign * (math.sqrt(ra2 ** 2 - rb2 ** 2) - rw2 * math.sin(alpha_w))
    problems = _interference(tip_1, tip_2, rw1, rw2, alpha_w, g.internal)
    if problems and strict:
        raise ModelError(problems[0])
    beta_b = math.asin(math.sin(beta) * math.cos(alpha_n))
    return PathOfContact(base_pitch=math.pi * m_t * math.cos(alpha_t),
                         working_pressure_angle=alpha_w, base_helix_angle=beta_b,
                         working_radius_1=rw1, working_radius_2=rw2,
                         addendum_path_1=tip_1, addendum_path_2=tip_2,
                         warnings=tuple(problems))


def mesh_loss(g: MeshGeometry, mu: float | None = None, strict: bool = True) -> MeshLoss:
    """Contact ratios and Ohlendorf's loss factor of a pair; its basic efficiency if ``mu``.

    Parameters
    ----------
    g : MeshGeometry
    mu : float, optional
        Mean coefficient of friction in the mesh (0 <= μ < 1).
    strict : bool
        Refuse a pair with interference (default); False computes it with a warning.

    Returns
    -------
    MeshLoss

    Raises
    ------
    ModelError
        When the pair does not mesh properly (interference, contact ratio below 1), or
        ``mu`` is out of range.

    Examples
    --------
    >>> round(mesh_loss(MeshGeometry(30, 80, internal=True), mu=0.05).efficiency, 5)
    0.99683
    """
    if mu is not None and not (0.0 <= mu < 1.0):
        raise ModelError(f"the friction coefficient must be in [0, 1), got {mu!r}")
    path = path_of_contact(g, strict)
    e1, e2 = path.addendum_path_1 / path.base_pitch, path.addendum_path_2 / path.base_pitch
    if min(e1, e2) < 0 or e1 + e2 < 1.0:
        raise ModelError(f"the pair does not mesh continuously: contact ratio ε_α = "
                         f"{e1 + e2:.4f} (it must be >= 1; ε_1 = {e1:.4f}, ε_2 = {e2:.4f})")
    u = (-1.0 if g.internal else 1.0) * g.teeth_2 / g.teeth_1
    scale = math.pi * (u + 1) / (g.teeth_1 * u * math.cos(path.base_helix_angle))
    return MeshLoss(geometry=g, epsilon_alpha=e1 + e2, epsilon_1=e1, epsilon_2=e2,
                    loss_factor=scale * sliding_integral(e1, e2), mu=mu,
                    warnings=path.warnings)


def sliding_integral(e1: float, e2: float) -> float:
    """The load-weighted sliding over one base pitch, in base pitches: Ohlendorf's bracket.

    Within ``1 <= ε_α < 2`` and ``ε_1, ε_2 < 1`` it is ``1 − ε_α + ε_1² + ε_2²``. Outside
    it (high-contact-ratio and internal pairs often have ``ε_2 >= 1``) the same quantity,
    ``2·(1/p_b²)·∫ Σ_k |x_k| / n`` over one base pitch of travel — the ``n`` pairs in contact
    at ``x_k`` (from the pitch point) sharing the load equally — is integrated exactly,
    piece by piece.

    >>> round(sliding_integral(0.7, 0.8), 12) == round(1 - 1.5 + 0.49 + 0.64, 12)
    True
    """
    if e1 < 1 and e2 < 1 and 1 <= e1 + e2 < 2:
        return 1 - (e1 + e2) + e1 ** 2 + e2 ** 2
    # Pair k sits at x = s - k (base pitches), s in [0, 1); in contact while -e2 <= x <= e1.
    ks = range(-int(math.ceil(e1)) - 1, int(math.ceil(e2)) + 2)
    cuts = {0.0, 1.0}
    for k in ks:
        cuts.update(c for c in (k - e2, k + e1, float(k)) if 0.0 < c < 1.0)
    edges = sorted(cuts)
    total = 0.0
    for lo, hi in zip(edges, edges[1:]):
        mid = 0.5 * (lo + hi)
        active = [k for k in ks if -e2 <= mid - k <= e1]
        # Σ|s - k| is linear on the piece (no sign change inside it): midpoint rule is exact.
        total += (hi - lo) * sum(abs(mid - k) for k in active) / len(active)
    return 2.0 * total


def _interference(tip_1: float, tip_2: float, rw1: float, rw2: float, alpha_w: float,
                  internal: bool) -> list[str]:
    """Each tip must meet the line of action before the other gear's tangent point: the
    ways it does not."""
    problems = []
    if tip_2 > rw1 * math.sin(alpha_w) * (1 + 1e-12):
        problems.append("gear 2's tip passes the pinion's interference point (the pinion's "
                        "flank would be undercut): shift the pinion or shorten gear 2's tip")
    if not internal and tip_1 > rw2 * math.sin(alpha_w) * (1 + 1e-12):
        problems.append("the pinion's tip passes gear 2's interference point: shift gear 2 "
                        "or shorten the pinion's tip")
    return problems


def _check(g: MeshGeometry) -> None:
    for name in ("teeth_1", "teeth_2"):
        value = getattr(g, name)
        if not isinstance(value, int) or isinstance(value, bool) or value < 3:
            raise ModelError(f"{name} must be an integer >= 3, got {value!r}")
    if g.internal and g.teeth_2 <= g.teeth_1:
        raise ModelError("an internal gear needs more teeth than its pinion "
                         f"({g.teeth_2} <= {g.teeth_1})")
    checks = (("module", g.module, 0.0, 1e4, "0 < {} <= 1e4"),
              ("pressure_angle_deg", g.pressure_angle_deg, 0.0, 45.0, "0 < {} <= 45"),
              ("helix_angle_deg", g.helix_angle_deg, -60.0, 60.0, "-60 <= {} <= 60"),
              ("addendum", g.addendum, 0.0, 2.0, "0 < {} <= 2"),
              ("shift_1", g.shift_1, -2.0, 2.0, "-2 <= {} <= 2"),
              ("shift_2", g.shift_2, -2.0, 2.0, "-2 <= {} <= 2"))
    for name, value, low, high, rule in checks:
        ok = math.isfinite(value) and low <= value <= high and not (low == 0.0 and value == 0)
        if not ok:
            raise ModelError(f"{name} must satisfy {rule.format(name)}, got {value!r}")


#: Sum velocities below this (m/s) are taken at it: the fitted law diverges at rest
#: (an assumption of this project, documented in docs/losses.md).
MIN_SUM_VELOCITY = 0.1


def iso14179_mu(tangential_force: float, face_width: float, pitch_speed: float,
                geometry: MeshGeometry, viscosity: float, roughness: float,
                lubricant_factor: float = 1.0) -> float:
    """Mean coefficient of friction of a mesh by ISO/TR 14179-2 (Schlenk's fit).

    ``μ = 0.048 · (F_bt/b / (v_Σc·ρ_redc))^0.2 · η_oil^−0.05 · Ra^0.25 · X_L``, with
    ``F_bt`` the transverse load on the base circle (N), ``b`` the face width (mm),
    ``v_Σc = 2 v_t sin α_wt`` the sum of the flanks' velocities at the pitch point (m/s),
    ``ρ_redc`` the reduced transverse radius of curvature at the pitch point (mm),
    ``η_oil`` the oil's dynamic viscosity (mPa·s) and ``Ra`` the mean roughness (µm).

    Parameters
    ----------
    tangential_force : float or array
        Tangential force at the working pitch circle, N (its magnitude is used); with
        arrays of forces and/or speeds, an array of coefficients is returned.
    face_width : float
        Face width b, mm.
    pitch_speed : float
        Pitch-line velocity ``v_t`` in the carrier's frame, m/s (magnitude).
    geometry : MeshGeometry
    viscosity : float
        Dynamic viscosity of the oil at its working temperature, mPa·s.
    roughness : float
        Arithmetic mean roughness of the flanks, µm.
    lubricant_factor : float
        ``X_L``: 1.0 for mineral oil (the standard's table gives others).

    Examples
    --------
    >>> g = MeshGeometry(20, 40, module=2.0)
    >>> round(iso14179_mu(1000.0, 20.0, 5.0, g, viscosity=30.0, roughness=0.5), 4)
    0.0435
    >>> iso14179_mu(np.array([0.0, 1000.0]), 20.0, 5.0, g, viscosity=30.0,
    ...             roughness=0.5).round(4).tolist()
    [0.0, 0.0435]
    """
    for name, value in (("face_width", face_width), ("viscosity", viscosity),
                        ("roughness", roughness), ("lubricant_factor", lubricant_factor)):
        if not (math.isfinite(value) and value > 0):
            raise ModelError(f"{name} must be a finite number > 0, got {value!r}")
    path = path_of_contact(geometry)
    alpha_w = path.working_pressure_angle
    rho_1 = path.working_radius_1 * math.sin(alpha_w)
    rho_2 = path.working_radius_2 * math.sin(alpha_w) * (-1.0 if geometry.internal else 1.0)
    rho_red = rho_1 * rho_2 / (rho_1 + rho_2) / math.cos(path.base_helix_angle)
    if np.ndim(tangential_force) or np.ndim(pitch_speed):     # arrays: one μ per point
        load = np.abs(tangential_force) / math.cos(alpha_w) / face_width
        v_sum = np.maximum(2.0 * np.abs(pitch_speed) * math.sin(alpha_w), MIN_SUM_VELOCITY)
        return np.where(load == 0.0, 0.0, _schlenk(load, v_sum, rho_red, viscosity, roughness,
                                                   lubricant_factor))
    load = abs(tangential_force) / math.cos(alpha_w) / face_width
    v_sum = max(2.0 * abs(pitch_speed) * math.sin(alpha_w), MIN_SUM_VELOCITY)
    if load == 0.0:
        return 0.0
    return _schlenk(load, v_sum, rho_red, viscosity, roughness, lubricant_factor)


def _schlenk(load, v_sum, rho_red, viscosity, roughness, lubricant_factor):
    """ISO/TR 14179-2's fit for the mean coefficient (floats or arrays)."""
    return 0.048 * (load / (v_sum * rho_red)) ** 0.2 * viscosity ** -0.05 \
        * roughness ** 0.25 * lubricant_factor
