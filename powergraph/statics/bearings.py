"""Bearing friction and no-load drag as losses (docs/losses.md).

A bearing ``between: [carried, carrying]`` with ``friction: {mu, bore}`` and/or ``drag``,
and a component with ``drag`` (against the frame), each apply a friction torque ``M`` to
their two bodies, opposing their relative rotation ``Δω = w_1 - w_2``: ``-M·sign(Δω)`` on
the first, ``+M·sign(Δω)`` on the second. Its loss is ``M·|Δω| >= 0``. Per instance,

    M_1 = mu · F · bore / 2  +  M0,     M0 = no_load_torque   or   a + b·|n_rel|  (rpm)

and ``M = instances · M_1`` with ``instances = max(count)`` of the two members (a
component's own ``count`` for its drag). At ``Δω = 0`` the torque is set-valued (static
friction); the model takes it as 0, which is also what a locked train at rest gets.

**The radial load F** (per instance) is not part of a torque-only model; powergraph takes
it from the tooth forces on the carried member: for every mesh in which a gear of the
carried member's rigid body takes part, the tangential tooth force ``|T_gear| / r_w`` (the
mesh's torque on that gear over its working pitch radius, shared by the mesh's ``count``
instances), summed as magnitudes. The scalar sum is exact for a planet of a simple 2K-H
set (the sun and the ring push it the same way, so its bearing carries twice the tooth
force) and for a gear on a shaft with one mesh; otherwise it is an upper bound of the
vector sum. Radial tooth-force components (``F_t·tan α``), weights, and the forces a
carrier receives from the gears it carries are not counted. A carried member without
gears in mesh has ``F = 0``: only its drag applies.

These torques are known once the speeds and the tooth forces are, so the torque balance
takes them as extra known torques on the right-hand side (:func:`with_extra_torques`);
since ``F`` depends on the balance, :func:`powergraph.statics.friction.solve_with_friction`
iterates both to a fixed point.

Examples
--------
A pair z 20/40 whose driven gear 2 has a seal drag of 0.5 N·m against the housing:

>>> import powergraph as pg
>>> from powergraph.model import model_from_dict
>>> m = model_from_dict({"name": "pair", "components": {0: {"role": "frame"},
...     1: {"teeth": 20}, 2: {"teeth": 40, "drag": {"no_load_torque": 0.5}}},
...     "links": [{"type": "mesh", "between": [1, 2]}],
...     "ports": [{"component": 1, "role": "input", "speed": 100, "power": 1000},
...               {"component": 2, "role": "output"}]})
>>> r = pg.solve(m)
>>> [(b.node, b.relative_speed, b.loss) for b in r.bearings]
[('drag 2', -50.0, 25.0)]
>>> round(r.efficiency, 12), r.total_loss
(0.975, 25.0)
"""
from __future__ import annotations

import numpy as np

import dataclasses
from types import MappingProxyType
from typing import Any, Mapping

from powergraph.kinematics.elements import gear_torque
from powergraph.model.spec import Model
from powergraph.records import record
from powergraph.statics.equilibrium import Loads, loads_of
from powergraph.statics.loss_sources import LossSource, torque_sources

#: Relative speeds below this fraction of the two bodies' speeds are zero.
SPEED_NOISE = 1e-12


@record
class BearingState:
    """One bearing (``kind="bearing"``) or body drag (``kind="drag"``) at the solution.

    ``between`` are the two members (component ids; the frame for a drag), ``bodies``
    their bodies; ``relative_speed`` is ``w_1 - w_2`` (rad/s); ``radial_load`` (N),
    ``friction_torque`` and ``drag_torque`` (N·m) are per instance; ``torque`` (N·m, >= 0)
    is the total of ``instances``; ``loss = torque · |relative_speed|`` (W).
    """

    kind: str
    link: int | None
    between: tuple[str, str]
    bodies: tuple[str, str]
    instances: int
    relative_speed: float
    radial_load: float
    friction_torque: float
    drag_torque: float
    torque: float
    loss: float
    node: str

    @property
    def torques(self) -> Mapping[str, float]:
        """The torque applied to each of the two bodies (N·m)."""
        on_first, on_second = body_torques(self.torque, self.relative_speed)
        return MappingProxyType({self.bodies[0]: on_first, self.bodies[1]: on_second})

    def to_dict(self, model: Model) -> dict[str, Any]:
        raw = model.raw_id
        return {"kind": self.kind, "link": self.link,
                "between": [raw(c) for c in self.between], "node": self.node,
                "instances": self.instances, "relative_speed": self.relative_speed,
                "radial_load": self.radial_load, "friction_torque": self.friction_torque,
                "drag_torque": self.drag_torque, "torque": self.torque, "loss": self.loss}


def bearing_states(model: Model, result: Any) -> tuple[BearingState, ...]:
    """Every loss source of ``model`` (:func:`powergraph.statics.loss_sources.torque_sources`:
    its bearings with friction/drag, body drags, and any registered kind), evaluated at
    the speeds and tooth forces of ``result`` (a :class:`PowerFlowResult`).

    The torques are those of this result's forces: the solver iterates until they agree
    with the torques the balance was solved with.
    """
    return tuple(_state(model, result, source) for source in torque_sources(model))


def relative_speed(w_1: Any, w_2: Any) -> Any:
    """``w_1 - w_2``, zero where it is round-off on the scale of the two speeds (numbers or
    arrays of operating points).

    >>> relative_speed(3.0, 1.0), relative_speed(1.0, 1.0 + 1e-15)
    (2.0, 0.0)
    """
    rel = np.asarray(w_1, dtype=float) - w_2
    rel = np.where(np.abs(rel) <= SPEED_NOISE * np.maximum(np.abs(w_1), np.abs(w_2)), 0.0, rel)
    return float(rel) if rel.ndim == 0 else rel


def bearing_torque(count: int, friction: Any, drag: Any, load: Any, relative: Any) -> tuple:
    """The law of one bearing or drag: per instance its friction torque at the radial load
    and the relative speed (``μ·F·d/2``, or SKF's model) and its drag torque at the
    relative speed, and the total torque of
    ``count`` instances opposing the relative rotation (0 at rest). Numbers or arrays.

    Returns
    -------
    (friction torque, drag torque, total torque), N·m
    """
    m_friction = friction.torque(load, relative) if friction is not None else 0.0 * load
    m_drag = drag.torque(relative) if drag is not None else 0.0 * relative
    total = np.where(np.asarray(relative) != 0.0, count * (m_friction + m_drag), 0.0)
    return m_friction, m_drag, (float(total) if total.ndim == 0 else total)


def _state(model: Model, result: Any, source: LossSource) -> BearingState:
    bodies = (model.body_of[source.between[0]], model.body_of[source.between[1]])
    relative = relative_speed(*(result.kinematics.body_speeds[b] for b in bodies))
    load = sum(abs(tooth_force(*_mesh_force(result, mesh, gear), radius, count))
               for mesh, gear, radius, count in source.loaded_by)
    m_friction, m_drag, torque = bearing_torque(source.instances, source.friction,
                                                source.drag, load, relative)
    return BearingState(kind=source.kind, link=source.link, between=source.between,
                        bodies=bodies, instances=source.instances,
                        relative_speed=float(relative) + 0.0, radial_load=float(load),
                        friction_torque=float(m_friction), drag_torque=float(m_drag),
                        torque=float(torque), loss=float(torque * abs(relative)),
                        node=source.node)


def _mesh_force(result: Any, mesh: int, gear: str) -> tuple:
    """``(ratio, force, factor, on gear a)`` of ``gear`` in the mesh ``links[mesh]``."""
    flow = result.element(mesh)
    return flow.ratio, flow.force, flow.factor, gear == flow.a


def body_torques(torque: Any, relative: Any) -> tuple[Any, Any]:
    """A bearing's (or drag's) total torque ``torque`` (>= 0) as the torques on its two
    bodies, opposing their relative rotation ``w_1 - w_2`` (floats or arrays).

    >>> body_torques(2.0, -3.0)
    (2.0, -2.0)
    """
    sign = np.sign(relative) if np.ndim(relative) else (relative > 0) - (relative < 0)
    return -torque * sign + 0.0, torque * sign + 0.0


def tooth_force(ratio: Any, force: Any, factor: Any, on_gear_a: bool, radius: float,
                instances: int) -> Any:
    """Signed tangential tooth force (N, per mesh instance) of a mesh on one of its gears:
    the mesh's torque on the gear over its working pitch radius (m). Floats or arrays.

    >>> tooth_force(-2.0, 10.0, 1.0, True, 0.05, 2)
    100.0
    """
    return gear_torque(ratio, force, factor, on_gear_a) / radius / instances


def torque_change(old: Any, new: Any, acting: Any) -> Any:
    """The convergence test of the bearing iteration: the largest change of a bearing
    torque between two passes (``old``, ``new``: torques per body, the last axis),
    relative to the largest torque acting (``acting``: the given and solved external
    torques, with the new bearing torques). One pass or an array of operating points.

    >>> float(torque_change(np.array([1.0, 0.0]), np.array([1.5, 0.0]), np.array([10.0])))
    0.05
    """
    moved = np.max(np.abs(new - old), axis=-1, initial=0.0)
    scale = np.maximum(np.max(np.abs(acting), axis=-1, initial=0.0),
                       np.max(np.abs(new), axis=-1, initial=0.0))
    return np.where(moved > 0.0, moved / np.where(scale > 0.0, scale, 1.0), 0.0)


def torques_on_bodies(states: tuple[BearingState, ...]) -> dict[str, float]:
    """The bearings' torques summed per body (N·m), zero entries left out.

    >>> s = BearingState("drag", None, ("6", "0"), ("6/7", "0"), 1, -2.0, 0.0, 0.0, 0.5,
    ...                  0.5, 1.0, "drag 6")
    >>> torques_on_bodies((s,))
    {'6/7': 0.5, '0': -0.5}
    """
    out: dict[str, float] = {}
    for state in states:
        for body, torque in state.torques.items():
            if torque:
                out[body] = out.get(body, 0.0) + torque
    return out


def load_regime(model: Model, result: Any) -> tuple:
    """What must not change for the solution to stay affine in the loads: each element's
    driver and the sign of every tooth force that loads a bearing."""
    signs = tuple((f > 0) - (f < 0) for source in torque_sources(model)
                  for mesh, gear, radius, count in source.loaded_by
                  for f in [tooth_force(*_mesh_force(result, mesh, gear), radius, count)])
    return tuple(e.driver for e in result.elements), signs


def with_extra_torques(loads: Loads, extra: Mapping[str, float]) -> Loads:
    """``loads`` with the known bearing torques added to the given torques, so that the
    torque balance carries them on its right-hand side (the unknowns stay the same)."""
    given = dict(loads.given)
    for body, torque in extra.items():
        given[body] = given.get(body, 0.0) + torque
    return loads._replace(given=given)


def with_bearings(model: Model, result: Any, states: tuple[BearingState, ...],
                  extra: Mapping[str, float]) -> Any:
    """The result of a balance solved with ``extra`` bearing torques among its loads: the
    true external torques (without ``extra``), the input and output powers from them, the
    bearing states, and the total loss including theirs."""
    external = dict(result.external_torques)
    if extra:
        kin = result.kinematics if result.lock is None else result.lock.asked
        true = loads_of(model, kin)
        for body in extra:
            if body in true.unknown:
                continue
            if body in true.given:
                external[body] = true.given[body]
            else:
                external.pop(body, None)
    speeds = result.kinematics.body_speeds

    def fed(port) -> float:
        return result.port_torque(port.index) * speeds[model.body_of[port.component]]

    input_power = sum(fed(p) for p in model.inputs)
    output_power = -sum(fed(p) for p in model.outputs)
    return dataclasses.replace(
        result, external_torques=MappingProxyType(external), input_power=float(input_power),
        output_power=float(output_power) + 0.0, bearings=states,
        total_loss=float(sum(e.loss for e in result.elements) + sum(s.loss for s in states)))
