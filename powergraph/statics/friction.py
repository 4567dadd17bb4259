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
from dataclasses import dataclass
from functools import lru_cache
from typing import Any, Callable, Mapping

from powergraph.errors import SolveError
from powergraph.kinematics.elements import element_stencil
from powergraph.model.spec import Model

MAX_PASSES = 60


@dataclass(frozen=True)
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
        bearings = bearing_states(model, result) if model.has_bearing_losses else ()
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
    """Largest change of a body's bearing torque, relative to the largest torque acting."""
    moved = max((abs(new.get(b, 0.0) - old.get(b, 0.0)) for b in {*old, *new}), default=0.0)
    if not moved:
        return 0.0
    scale = max([abs(t) for t in result.external_torques.values()]
                + [abs(t) for t in new.values()])
    return moved / scale


def loss_block_places(model: Model) -> list[str]:
    """Where ``model`` has losses that are not a constant efficiency: a mesh's ``friction:``
    or ``pins:``, a bearing's ``friction:``/``drag:``, a component's ``drag:``, as YAML
    paths, in file order of links then components. Methods that read plain efficiencies
    refuse such a model rather than let these losses vanish.

    >>> from powergraph.model import load_model
    >>> loss_block_places(load_model("models/rv40e.yaml"))[:2]
    ['links[0].friction', 'links[1].pins']
    """
    places = [f"{link.path}.{'pins' if getattr(block, 'model', '') == 'cycloid' else key}"
              for link in model.links for key, block in link.blocks.items()
              if key in ("friction", "drag")]
    places += [f"components.{c.raw_id}.drag" for c in model.components.values()
               if c.drag is not None]
    return places


@lru_cache(maxsize=1024)
def _loss_factor(geometry: Any) -> float:
    from powergraph.gears.mesh_loss import mesh_loss  # only trains with friction

    return mesh_loss(geometry).loss_factor


@lru_cache(maxsize=1024)
def _constant(friction: Any) -> tuple[float, float]:
    return friction.efficiency()


def _state(model: Model, result: Any, friction: Any) -> MeshFrictionState:
    flow = result.element(friction.link)
    link = model.links[friction.link]
    if friction.model == "cycloid":      # pin ring: constant, force at the disc's pitch circle
        radius, h_v = friction.pitch_radius / 1000.0, friction.loss_factor
    else:
        from powergraph.gears.mesh_loss import path_of_contact  # only trains with friction

        radius = path_of_contact(friction.geometry).working_radius_1 / 1000.0   # m
        h_v = _loss_factor(friction.geometry)
    a, b = link.between
    on_a, on_b, _ = element_stencil(flow.ratio, flow.factor)
    torque_1 = (on_a if friction.gear_1 == a else on_b) * flow.force
    instances = max(model.components[a].count, model.components[b].count)
    speeds = result.kinematics.body_speeds
    relative = speeds[model.body_of[friction.gear_1]] - speeds[model.body_of[link.carrier]]
    force = abs(torque_1) / radius / instances
    pitch_speed = abs(relative) * radius
    if friction.load_dependent:
        mu, eta = friction.efficiency(force, pitch_speed)
    else:                                   # the same law, cached: it does not change
        mu, eta = _constant(friction)
    return MeshFrictionState(link=friction.link, model=friction.model, tangential_force=force,
                             pitch_speed=pitch_speed, mu=mu, loss_factor=h_v, efficiency=eta)
