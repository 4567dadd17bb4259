"""Load-dependent mesh losses: iterate forces → friction coefficients → efficiencies.

A mesh whose ``friction:`` block follows ISO/TR 14179-2 has a mean coefficient of friction
that depends on its tooth load and pitch-line speed, both in its carrier's frame, so its
basic efficiency depends on the solution. Starting ideal, each pass solves the train with
the current efficiencies, reads every such mesh's tangential force and speed, and updates
its efficiency, until no efficiency changes by more than ``tolerance``. The coefficient
grows only as the load to the power 0.2, so the passes contract quickly (three to six).
Meshes with a constant coefficient have a constant efficiency and need no pass.
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from types import MappingProxyType
from typing import Any, Callable, Mapping

from powergraph.errors import SolveError
from powergraph.gears.mesh_loss import mesh_loss, path_of_contact
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


def solve_with_friction(model: Model, solve: Callable[[Model], Any], tolerance: float = 1e-12,
                        max_passes: int = MAX_PASSES) -> Any:
    """Solve ``model`` with its load-dependent mesh efficiencies made consistent.

    Parameters
    ----------
    model : Model
        The train; its friction meshes' ``efficiency`` is replaced pass by pass in copies.
    solve : callable
        The fixed-efficiency solver (``Model -> PowerFlowResult``).
    tolerance : float
        Largest change of any efficiency between the last two passes.

    Returns
    -------
    PowerFlowResult
        Of ``model``, with ``friction`` (the meshes' states) and ``friction_passes``.

    Raises
    ------
    SolveError
        When the efficiencies do not converge in ``max_passes``.
    """
    frictions = friction_meshes(model)
    current = {k: (1.0 if f.load_dependent else f.efficiency()[1]) for k, f in frictions.items()}
    passes = 0
    while True:
        passes += 1
        result = solve(_fixed(model, current))
        states = tuple(_state(model, result, frictions[k]) for k in sorted(frictions))
        change = max((abs(s.efficiency - current[s.link]) for s in states), default=0.0)
        if change <= tolerance or not any(f.load_dependent for f in frictions.values()):
            return dataclasses.replace(result, model=model, friction=states,
                                       friction_passes=passes)
        if passes == max_passes:
            break
        current = {s.link: s.efficiency for s in states}
    raise SolveError(f"the load-dependent mesh efficiencies did not converge in {max_passes} "
                     f"passes (last change {change:.3g})")


def needs_friction(model: Model) -> bool:
    """True when a mesh of ``model`` carries a ``friction:`` block."""
    return any("friction" in link.blocks for link in model.links)


def _fixed(model: Model, efficiencies: Mapping[int, float]) -> Model:
    """A copy whose friction meshes have the given efficiencies and no friction block."""
    for link, eta in efficiencies.items():
        blocks = {k: v for k, v in model.links[link].blocks.items() if k != "friction"}
        model = model.with_link(link, efficiency=eta, blocks=MappingProxyType(blocks))
    return model


def _state(model: Model, result: Any, friction: Any) -> MeshFrictionState:
    flow = result.element(friction.link)
    link = model.links[friction.link]
    if friction.model == "cycloid":      # pin ring: constant, force at the disc's pitch circle
        radius, h_v = friction.pitch_radius / 1000.0, friction.loss_factor
    else:
        radius = path_of_contact(friction.geometry).working_radius_1 / 1000.0   # m
        h_v = mesh_loss(friction.geometry).loss_factor
    a, b = link.between
    on_a, on_b, _ = element_stencil(flow.ratio, flow.factor)
    torque_1 = (on_a if friction.gear_1 == a else on_b) * flow.force
    instances = max(model.components[a].count, model.components[b].count)
    speeds = result.kinematics.body_speeds
    relative = speeds[model.body_of[friction.gear_1]] - speeds[model.body_of[link.carrier]]
    force = abs(torque_1) / radius / instances
    pitch_speed = abs(relative) * radius
    mu, eta = friction.efficiency(force, pitch_speed)
    return MeshFrictionState(link=friction.link, model=friction.model, tangential_force=force,
                             pitch_speed=pitch_speed, mu=mu, loss_factor=h_v, efficiency=eta)
