"""Load-dependent losses: iterate forces → friction coefficients and bearing torques.

A mesh whose ``friction:`` block follows ISO/TR 14179-2 has a mean coefficient of friction
that depends on its tooth load and pitch-line speed, both in its carrier's frame, so its
basic efficiency depends on the solution. A bearing with ``friction: {mu, bore}`` has a
torque proportional to its radial load, taken from the tooth forces
(:mod:`powergraph.statics.bearings`), and bearing and body drags add torques that depend
on the speeds only. Starting ideal and without bearing torques, each pass solves the train
with the current efficiencies and bearing torques (as known torques in the balance), reads
every friction mesh's force and speed and every bearing's load, and updates both, until no
efficiency changes by more than ``tolerance`` and no bearing torque by more than
``tolerance`` times the largest torque of the train. The coefficient grows only as the load
to the power 0.2, and a bearing's torque is a small fraction of the torques that load it,
so the passes contract quickly (three to six). Meshes with a constant coefficient have a
constant efficiency; drags alone need one more pass.
"""
from __future__ import annotations

import dataclasses
from functools import lru_cache
from typing import Any, Callable, Mapping

import numpy as np

from powergraph.errors import ModelError, SolveError
from powergraph.kinematics.elements import gear_torque
from powergraph.model.spec import Model
from powergraph.records import record
from powergraph.statics.loss_sources import loss_sources

MAX_PASSES = 60


@record
class MeshFrictionState:
    """One friction mesh at the solution: its load, speed, coefficient and efficiency.

    ``tangential_force`` (N) and ``pitch_speed`` (m/s) are per mesh instance (the load of
    ``count`` parallel planets or discs is shared equally), in the carrier's frame.
    """

    link: int
    model: str
    tangential_force: float
    pitch_speed: float
    mu: float
    loss_factor: float
    efficiency: float

    def to_dict(self) -> dict[str, Any]:
        return {"link": self.link, "model": self.model, "tangential_force": self.tangential_force,
                "pitch_speed": self.pitch_speed, "mu": self.mu, "loss_factor": self.loss_factor,
                "efficiency": self.efficiency}


def friction_meshes(model: Model) -> dict[int, Any]:
    """``{link index: MeshFriction}`` of the meshes that carry a ``friction:`` block."""
    return {link.index: link.blocks["friction"] for link in model.links
            if link.type == "mesh" and "friction" in link.blocks}


def solve_with_friction(model: Model,
                        solve: Callable[[Mapping[int, float], Mapping[str, float]], Any],
                        tolerance: float = 1e-12, max_passes: int = MAX_PASSES) -> Any:
    """Solve ``model`` with its load-dependent mesh efficiencies and bearing torques made
    consistent.

    Parameters
    ----------
    model : Model
        The train (not changed).
    solve : callable
        The fixed-efficiency solver of ``model`` at its operating point:
        ``({friction mesh's link index: efficiency}, {body: bearing torque}) ->
        PowerFlowResult``; the train's structure and speeds do not change between passes,
        only these numbers.
    tolerance : float
        Largest change of any efficiency, and of any bearing torque relative to the largest
        torque of the train, between the last two passes.

    Returns
    -------
    PowerFlowResult
        Of ``model``, with ``friction`` (the meshes' states), ``bearings`` (the bearings'
        and drags' states, their losses in ``total_loss``) and ``friction_passes``.

    Raises
    ------
    SolveError
        When the efficiencies or bearing torques do not converge in ``max_passes``.
    """
    from powergraph.statics.bearings import bearing_states, torques_on_bodies, with_bearings

    frictions = friction_meshes(model)
    current = {k: (1.0 if f.load_dependent else f.efficiency()[1]) for k, f in frictions.items()}
    extra: dict[str, float] = {}
    passes = 0
    while True:
        passes += 1
        result = solve(current, extra)
        states = tuple(_state(model, result, frictions[k]) for k in sorted(frictions))
        bearings = bearing_states(model, result)
        torques = torques_on_bodies(bearings)
        change = max((abs(s.efficiency - current[s.link]) for s in states), default=0.0)
        moved = _torque_change(extra, torques, result)
        if change <= tolerance and moved <= tolerance:
            result = with_bearings(model, result, bearings, extra) if bearings else result
            return dataclasses.replace(result, model=model, friction=states,
                                       friction_passes=passes)
        if passes == max_passes:
            break
        current = {s.link: s.efficiency for s in states}
        extra = torques
    raise SolveError(f"the load-dependent mesh efficiencies and bearing torques did not "
                     f"converge in {max_passes} passes (last change {max(change, moved):.3g})")


def _torque_change(old: Mapping[str, float], new: Mapping[str, float], result: Any) -> float:
    """Largest change of a body's bearing torque, relative to the largest torque acting
    (:func:`powergraph.statics.bearings.torque_change`)."""
    if not old and not new:
        return 0.0
    from powergraph.statics.bearings import torque_change

    bodies = list({*old, *new})
    acting = list(result.external_torques.values())
    return float(torque_change(np.array([old.get(b, 0.0) for b in bodies]),
                               np.array([new.get(b, 0.0) for b in bodies]),
                               np.array(acting, dtype=float)))


def loss_block_places(model: Model) -> list[str]:
    """Where ``model`` has losses that are not a constant efficiency: a mesh's ``friction:``
    or ``pins:``, a bearing's ``friction:``/``drag:``, a seal, a component's ``drag:``, a
    heat balance (``thermal``), as YAML paths, in file order of links then components. Methods that read plain efficiencies
    refuse such a model rather than let these losses vanish.

    >>> from powergraph.model import load_model
    >>> loss_block_places(load_model("models/rv40e.yaml"))[:2]
    ['links[0].friction', 'links[1].pins']
    """
    found = []
    for source in loss_sources(model):
        where = len(model.links) if source.link is None else source.link
        if source.applied == "element":
            if source.friction is not None:
                found.append((where, f"{source.path}.{_block_name(source.friction)}"))
        elif source.applied == "machine":
            continue
        elif source.kind == "bearing":
            found += [(where, f"{source.path}.{getattr(law, 'block', key)}") for key, law in
                      (("friction", source.friction), ("drag", source.drag)) if law is not None]
        else:
            found.append((where, source.path))
    if model.thermal is not None:          # the oil temperature: a heat balance per point
        found.append((len(model.links) + 1, "thermal"))
    return [path for _, path in sorted(found, key=lambda item: item[0])]


def _block_name(block: Any) -> str:
    """A mesh's friction block as written: ``pins`` for a cycloid stage's."""
    return "pins" if getattr(block, "model", "") == "cycloid" else "friction"


@lru_cache(maxsize=1024)
def _loss_factor(geometry: Any) -> float:
    from powergraph.gears.mesh_loss import mesh_loss  # only trains with friction

    return mesh_loss(geometry).loss_factor


@lru_cache(maxsize=1024)
def _constant(friction: Any) -> tuple[float, float]:
    return friction.efficiency()


def mesh_friction(friction: Any, torque_1: Any, relative: Any,
                  instances: int) -> tuple[Any, Any, Any, Any]:
    """The state of a friction mesh at the torque on its gear 1 (N·m, all instances) and
    gear 1's speed relative to the carrier (rad/s): ``(tangential force per instance (N),
    pitch-line speed (m/s), μ, η)``, ``η = 1 - μ·H_V``. Floats, or arrays of operating
    points (the efficiency grid's): the one place the law is applied.

    A float coefficient out of [0, 1) is refused (ModelError); with arrays the caller
    checks it (a point that leaves the law's range is solved alone).
    """
    radius, h_v = _radius_and_loss_factor(friction)
    force = abs(torque_1) / radius / instances
    pitch_speed = abs(relative) * radius
    if not friction.load_dependent:        # the same law, cached: it does not change
        mu, eta = _constant(friction)
        return force, pitch_speed, mu, eta
    from powergraph.gears.mesh_loss import iso14179_mu  # only trains with friction

    mu = iso14179_mu(force, friction.face_width, pitch_speed, friction.geometry,
                     friction.viscosity, friction.roughness, friction.lubricant_factor)
    if np.ndim(mu) == 0 and not 0.0 <= mu < 1.0:
        raise ModelError(f"the friction coefficient must be in [0, 1), got {mu!r}")
    return force, pitch_speed, mu, 1.0 - mu * h_v


@lru_cache(maxsize=1024)
def _radius_and_loss_factor(friction: Any) -> tuple[float, float]:
    """Working pitch radius of gear 1 (m) and the loss factor H_V of a friction mesh
    (a cycloid stage's pin ring: the disc's pitch circle and its own factor)."""
    if friction.model == "cycloid":
        return friction.pitch_radius / 1000.0, friction.loss_factor
    from powergraph.gears.mesh_loss import path_of_contact  # only trains with friction

    return path_of_contact(friction.geometry).working_radius_1 / 1000.0, \
        _loss_factor(friction.geometry)


def _state(model: Model, result: Any, friction: Any) -> MeshFrictionState:
    flow = result.element(friction.link)
    link = model.links[friction.link]
    a, b = link.between
    torque_1 = gear_torque(flow.ratio, flow.force, flow.factor, friction.gear_1 == a)
    speeds = result.kinematics.body_speeds
    relative = speeds[model.body_of[friction.gear_1]] - speeds[model.body_of[link.carrier]]
    force, pitch_speed, mu, eta = mesh_friction(
        friction, torque_1, relative, max(model.components[a].count, model.components[b].count))
    h_v = _radius_and_loss_factor(friction)[1]
    return MeshFrictionState(link=friction.link, model=friction.model, tangential_force=force,
                             pitch_speed=pitch_speed, mu=mu, loss_factor=h_v, efficiency=eta)
