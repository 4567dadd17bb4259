"""The basic (crank-frame) efficiency of a cycloid stage from Coulomb friction.

Three losses of a cycloid disc are proportional to the same quantity: the torque ``T`` the
disc passes times its speed relative to the crank, ``|T·(ω_d − ω_c)|`` — the power the
cycloid–pin mesh passes in the crank's frame, which is what a basic efficiency applies to
in the virtual-power method. Each gives a loss factor ``H`` (friction power over that
power, per unit friction coefficient) and an efficiency ``1 − μ·H``; the mesh's basic
efficiency is their product (the three act in series on the disc in the crank's frame):

1. **Pin contacts** (``H_pins``). The disc moves relative to the ring about the pitch point
   ``I`` at ``(ω_d − ω_c)/z_p``, so a fixed (sliding) pin whose contact lies at
   ``D_k − r_p`` from ``I`` slides at ``|ω_d − ω_c|·(D_k − r_p)/z_p``. A pin that rolls on
   the disc and turns in a seat (or on a bearing) of radius ``r_s`` slides there at that
   speed times ``r_s/r_p`` — the same speed when the seat has the pin's own radius, so
   rolling lowers the loss only through the seat's coefficient and radius. With the
   equal-load forces ``F_k = T·λ_k/Σλ_j²`` (:mod:`powergraph.gears.cycloid`),
   ``H_pins = Σ λ_k s_k / (z_p Σ λ_k²)``, ``s_k = (D_k − r_p)·r_s/r_p``, averaged over the
   crank angle. For many pins and sliding pins this tends to the closed form
   ``4 (R_p − r_p) / (π z_c z_p e)`` (:func:`sliding_pin_limit`).
2. **Output pins** (``H_out``, a W mechanism: ``n`` pins on the circle ``R_w`` in holes of
   radius pin + ``e``). Seen from the output the disc does not turn but circles at
   ``ω_c − ω_d`` on the radius ``e``: every hole slides along its pin at ``e·|ω_c − ω_d|``
   (times ``r_s/r`` for a rolling sleeve). All contact normals are parallel to the
   eccentricity; the loaded half carries ``F_j = T·|sin φ_j|/(R_w Σ sin² φ_j)``, so
   ``H_out = e·Σ|sin φ_j| / (R_w Σ sin² φ_j)`` → ``4e/(π R_w)`` for many pins.
3. **Eccentric (crank) bearing** (``H_b``): the disc turns on its eccentric at
   ``|ω_c − ω_d|`` and a rolling (or plain) bearing loses ``μ_b·F·r_b`` of torque (SKF's
   constant-coefficient model, ``r_b`` the bore radius). The load is what balances the
   disc: the resultant of the pin forces and of the output-pin forces (a central crank,
   ``crank_circle_radius = 0``), or, for ``N`` cranks on the radius ``R_c`` (an RV
   reducer, where the cranks are the output mechanism), the pin resultant shared equally
   plus the tangential forces ``T/(N R_c)`` that carry the torque;
   ``H_b = r_b Σ_i |F_i| / T``, averaged over the crank angle and the cranks' positions
   (it does not depend on ``N``).

Assumptions: rigid parts, no clearances or profile modifications (every pin of the driving
half touches), equal load sharing between discs, Coulomb friction with constant
coefficients, no churning or seal losses, the loss factor evaluated with the lossless
forces (first order in μ, as Ohlendorf's ``H_V`` for involute pairs). Every factor is
independent of the load, so the efficiency is a constant. docs/losses.md discusses them.

Lengths in mm.

Examples
--------
>>> stage = PinRing(lobes=39, circle_radius=64.0, pin_radius=3.0, eccentricity=1.3)
>>> loss = cycloid_mesh_loss(stage, PinContact(mu=0.05))
>>> round(loss.pin_loss_factor, 5), round(loss.efficiency, 6)
(0.0383, 0.998085)
"""
from __future__ import annotations

import math
from dataclasses import asdict
from typing import Any

import numpy as np

from powergraph.errors import ModelError
from powergraph.gears.cycloid import pin_forces, pin_phases, pitch_distance, stage_problem
from powergraph.records import record

#: Crank angles per pin pitch (and cranks' / output pins' positions per revolution) of the
#: averages: the midpoint rule is then exact to far below 1e-9 of the loss factors.
SAMPLES = 256


@record
class PinRing:
    """A cycloid disc of ``lobes`` (z_c) in a ring of ``z_c + 1`` pins (lengths in mm)."""

    lobes: int
    circle_radius: float
    pin_radius: float
    eccentricity: float

    @property
    def pins(self) -> int:
        return self.lobes + 1


@record
class PinContact:
    """Friction at the ring's pins: coefficient ``mu``; ``rolling`` pins turn in a seat (or
    on a bearing) of ``seat_radius`` (default: the pin radius), fixed pins slide on the disc."""

    mu: float
    rolling: bool = False
    seat_radius: float | None = None


@record
class OutputPins:
    """A W output mechanism: ``count`` pins on ``circle_radius`` in holes of radius pin +
    e. ``rolling`` sleeves of outer ``radius`` turn on a seat of ``seat_radius``."""

    count: int
    circle_radius: float
    mu: float
    rolling: bool = False
    radius: float | None = None
    seat_radius: float | None = None


@record
class CrankBearing:
    """The disc's bearing on its eccentric: coefficient ``mu`` referred to the bore radius
    ``radius``; ``crank_circle_radius`` 0 for one central crank, else the radius of the
    circle of the (equally loaded) cranks."""

    mu: float
    radius: float
    crank_circle_radius: float = 0.0


@record
class CycloidLoss:
    """Loss factors and efficiencies of a cycloid stage (per unit crank-frame power)."""

    stage: PinRing
    pins: PinContact
    output: OutputPins | None
    bearing: CrankBearing | None
    pin_loss_factor: float
    output_loss_factor: float
    bearing_loss_factor: float

    @property
    def pin_efficiency(self) -> float:
        return 1.0 - self.pins.mu * self.pin_loss_factor

    @property
    def output_efficiency(self) -> float:
        return 1.0 if self.output is None else 1.0 - self.output.mu * self.output_loss_factor

    @property
    def bearing_efficiency(self) -> float:
        return 1.0 if self.bearing is None else 1.0 - self.bearing.mu * self.bearing_loss_factor

    @property
    def efficiency(self) -> float:
        """The mesh's basic efficiency: the product of the three."""
        return self.pin_efficiency * self.output_efficiency * self.bearing_efficiency

    def to_dict(self) -> dict[str, Any]:
        return {"stage": asdict(self.stage), "pins": asdict(self.pins),
                "output_pins": None if self.output is None else asdict(self.output),
                "crank_bearing": None if self.bearing is None else asdict(self.bearing),
                "pin_loss_factor": self.pin_loss_factor,
                "output_loss_factor": self.output_loss_factor,
                "bearing_loss_factor": self.bearing_loss_factor,
                "pin_efficiency": self.pin_efficiency,
                "output_efficiency": self.output_efficiency,
                "bearing_efficiency": self.bearing_efficiency, "efficiency": self.efficiency}

    def text_report(self) -> str:
        s = self.stage
        lines = [f"cycloid stage {s.lobes}/{s.pins}, R_p {s.circle_radius:g} mm, r_p "
                 f"{s.pin_radius:g} mm, e {s.eccentricity:g} mm",
                 f"pins          μ {self.pins.mu:<8g} H {self.pin_loss_factor:.5f}  "
                 f"η {self.pin_efficiency:.6f}"]
        if self.output is not None:
            lines.append(f"output pins   μ {self.output.mu:<8g} H "
                         f"{self.output_loss_factor:.5f}  η {self.output_efficiency:.6f}")
        if self.bearing is not None:
            lines.append(f"crank bearing μ {self.bearing.mu:<8g} H "
                         f"{self.bearing_loss_factor:.5f}  η {self.bearing_efficiency:.6f}")
        lines.append(f"basic efficiency (crank frame) {self.efficiency:.6f}")
        return "\n".join(lines)

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """Nothing to draw: raises :class:`~powergraph.result.NothingToDrawError`."""
        from powergraph.result import nothing_to_draw

        raise nothing_to_draw(self, "print text_report() for the loss factors")


def cycloid_mesh_loss(stage: PinRing, pins: PinContact, output: OutputPins | None = None,
                      bearing: CrankBearing | None = None) -> CycloidLoss:
    """Loss factors and basic efficiency of a cycloid–pin mesh with its output mechanism
    and eccentric bearing.

    Parameters
    ----------
    stage : PinRing
    pins : PinContact
        Friction at the ring's pins.
    output : OutputPins, optional
        A W output mechanism (pins in holes of the disc).
    bearing : CrankBearing, optional
        The disc's bearing on its eccentric.

    Returns
    -------
    CycloidLoss

    Raises
    ------
    ModelError
        For an impossible stage or coefficient (the message says which).

    Examples
    --------
    >>> stage = PinRing(39, 64.0, 3.0, 1.3)
    >>> loss = cycloid_mesh_loss(stage, PinContact(0.0), bearing=CrankBearing(0.0, 13.0, 36.0))
    >>> loss.efficiency
    1.0
    """
    _check(stage, pins, output, bearing)
    out = 0.0 if output is None else output_loss_factor(stage.eccentricity, output)
    bear = 0.0 if bearing is None else bearing_loss_factor(stage, bearing, output)
    return CycloidLoss(stage=stage, pins=pins, output=output, bearing=bearing,
                       pin_loss_factor=pin_loss_factor(stage, pins), output_loss_factor=out,
                       bearing_loss_factor=bear)


def pin_loss_factor(stage: PinRing, pins: PinContact) -> float:
    """``H_pins``: friction power at the pins over ``μ·|T (ω_d − ω_c)|``, crank-angle mean.

    >>> round(pin_loss_factor(PinRing(39, 64.0, 3.0, 1.3), PinContact(0.05)), 5)
    0.0383
    """
    theta = _midpoints(2.0 * np.pi / stage.pins)
    forces, _ = pin_forces(stage.lobes, stage.circle_radius, stage.eccentricity, theta)
    phase = pin_phases(stage.lobes, theta)
    reach = pitch_distance(stage.lobes, stage.circle_radius, stage.eccentricity, phase) \
        - stage.pin_radius
    scale = (pins.seat_radius or stage.pin_radius) / stage.pin_radius if pins.rolling else 1.0
    return float((forces * reach).sum(axis=-1).mean() * scale / stage.pins)


def output_loss_factor(eccentricity: float, output: OutputPins) -> float:
    """``H_out = e·Σ|sin φ_j| / (R_w Σ sin² φ_j)`` over the loaded half, mean over the pins'
    positions; times ``seat_radius/radius`` for rolling sleeves.

    >>> round(output_loss_factor(1.0, OutputPins(1000, 40.0, 0.05)) * 40 * math.pi / 4, 6)
    1.0
    """
    phi = _midpoints(2.0 * np.pi)[:, None] + 2.0 * np.pi * np.arange(output.count) \
        / output.count
    loaded = np.maximum(-np.sin(phi), 0.0)
    ratio = loaded.sum(axis=1) / (loaded ** 2).sum(axis=1)
    scale = output.seat_radius / output.radius if output.rolling else 1.0
    return float(eccentricity * ratio.mean() / output.circle_radius * scale)


def bearing_loss_factor(stage: PinRing, bearing: CrankBearing,
                        output: OutputPins | None = None) -> float:
    """``H_b = r_b Σ_i |F_i| / T``: the eccentric bearings' loads per unit disc torque.

    >>> h = bearing_loss_factor(PinRing(39, 64.0, 3.0, 1.3), CrankBearing(0.002, 13.0, 36.0))
    >>> round(h, 4)
    0.4167
    """
    theta = _midpoints(2.0 * np.pi / stage.pins)
    _, resultant = pin_forces(stage.lobes, stage.circle_radius, stage.eccentricity, theta)
    turn = np.exp(1j * _midpoints(2.0 * np.pi))
    if bearing.crank_circle_radius > 0:
        # N cranks: each takes R/N and a tangential T/(N R_c) at a position that turns past
        # the eccentricity; Σ|F_i| = mean over that angle of |R + e^{iβ}/R_c|.
        total = np.abs(resultant[:, None] + turn[None, :] / bearing.crank_circle_radius)
    elif output is None:
        total = np.abs(resultant)[:, None]
    else:
        # Output pins push the disc along −x (the eccentricity), Σ F_j per unit torque.
        phi = np.angle(turn)[:, None] + 2.0 * np.pi * np.arange(output.count) / output.count
        loaded = np.maximum(-np.sin(phi), 0.0)
        push = loaded.sum(axis=1) / (loaded ** 2).sum(axis=1) / output.circle_radius
        total = np.abs(resultant[:, None] - push[None, :])
    return float(bearing.radius * total.mean())


def sliding_pin_limit(stage: PinRing) -> float:
    """The many-pins limit of ``H_pins`` for sliding pins: ``4 (R_p − r_p)/(π z_c z_p e)``.

    >>> round(sliding_pin_limit(PinRing(39, 64.0, 3.0, 1.3)), 5)
    0.0383
    """
    return 4.0 * (stage.circle_radius - stage.pin_radius) \
        / (math.pi * stage.lobes * stage.pins * stage.eccentricity)


def _midpoints(span: float, samples: int = SAMPLES) -> np.ndarray:
    return (np.arange(samples) + 0.5) * span / samples


def _check(stage: PinRing, pins: PinContact, output: OutputPins | None,
           bearing: CrankBearing | None) -> None:
    problem = stage_problem(stage.lobes, stage.circle_radius, stage.pin_radius,
                            stage.eccentricity)
    if problem:
        raise ModelError(problem)
    for name, mu in (("pins", pins.mu), ("output pins", output and output.mu),
                     ("crank bearing", bearing and bearing.mu)):
        if mu is not None and not (math.isfinite(mu) and 0.0 <= mu < 1.0):
            raise ModelError(f"the {name}' friction coefficient must be in [0, 1), got {mu!r}")
    if pins.rolling and pins.seat_radius is not None and not pins.seat_radius > 0:
        raise ModelError(f"the pins' seat radius must be > 0, got {pins.seat_radius!r}")
    if output is not None:
        if output.count < 2 or not output.circle_radius > 0:
            raise ModelError("the output mechanism needs at least 2 pins on a circle of "
                             "radius > 0")
        if output.rolling and not (output.radius and output.seat_radius
                                   and 0 < output.seat_radius <= output.radius):
            raise ModelError("rolling output pins need radius and seat_radius, 0 < "
                             "seat_radius <= radius")
        if bearing is not None and bearing.crank_circle_radius > 0:
            raise ModelError("output pins and cranks on a circle both carry the disc's torque: "
                             "give one output mechanism")
    if bearing is not None and not (bearing.radius > 0 and bearing.crank_circle_radius >= 0):
        raise ModelError("the crank bearing needs a radius > 0 and a crank circle radius >= 0")
