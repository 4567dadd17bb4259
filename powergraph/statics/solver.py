"""The virtual-power solver: torques, directions, losses, efficiency (docs/theory.md).

Directions come from the fixed-point iteration; when it cycles, the complementarity
search decides: the least-loss consistent solution, or the locking verdict with the train
at rest (docs/locking.md).
"""
from __future__ import annotations

import dataclasses
from types import MappingProxyType
from typing import Mapping

import numpy as np

from powergraph.kinematics import Element, Kinematics, element_stencil, elements_of, solve_speeds
from powergraph.model.modes import default_state
from powergraph.model.spec import Model
from powergraph.statics.loss_sources import torque_sources
from powergraph.model.validate import check_port_ranges
from powergraph.statics.directions import (
    factors_of,
    force_scales,
    pattern_of,
    relative_speeds,
    settle,
)
from powergraph.statics.equilibrium import (Equilibrium, Loads, loads_of, port_torques,
                                            solve_equilibrium)
from powergraph.statics.result import DirectionSearch, ElementFlow, Lock, PowerFlowResult


def solve(model: Model, speeds: Mapping[str, float] | None = None,
          extra_torques: Mapping[str, float] | None = None) -> PowerFlowResult:
    """Solve speeds, torques, power directions, losses and efficiency.

    Each mesh's basic efficiency is applied to the power it passes in its carrier's
    frame, in the direction that power flows there (Chen & Angeles' virtual power).

    Parameters
    ----------
    model : Model
        The validated train; it is not changed.
    speeds : mapping, optional
        ``{component id: rad/s}`` overriding the ports' speeds.
    extra_torques : mapping, optional
        ``{body: N·m}`` known bearing torques, set by the bearing iteration
        (:mod:`powergraph.statics.bearings`); the result's external torques then include
        them (the iteration takes them out).

    Returns
    -------
    PowerFlowResult

    Raises
    ------
    ModelError
        (KinematicsError, StaticsError) when speeds or loads are not determined.

    A train that cannot move as asked under its loads is not an error: the result has
    ``lock`` set, the train at rest and efficiency 0 (docs/locking.md).

    Examples
    --------
    >>> from powergraph.model import model_from_dict
    >>> pair = model_from_dict({"name": "pair", "defaults": {"mesh_efficiency": 0.98},
    ...     "components": {0: {"role": "frame"}, 1: {"teeth": 20}, 2: {"teeth": 40}},
    ...     "links": [{"type": "mesh", "between": [1, 2]}],
    ...     "ports": [{"component": 1, "role": "input", "speed": 100, "power": 1000},
    ...               {"component": 2, "role": "output"}]})
    >>> r = solve(pair)
    >>> round(r.efficiency, 12), round(r.ratio, 12), round(r.total_loss, 9)
    (0.98, -2.0, 20.0)
    """
    if model.modes and not model.resolved and model.point_of is None:
        # a loaded model in its default state, the first mode: at that mode's point too
        # (its inactive ports carrying nothing, the ports and buses it sets, idle members)
        model = default_state(model)
    if extra_torques is None:
        check_port_ranges(model, speeds)
    if model.thermal is not None and extra_torques is None:
        from powergraph.statics.thermal import solve_thermal

        return solve_thermal(model, speeds, solve)
    if model.buses and extra_torques is None:
        from powergraph.statics.machines import solve_machines

        return solve_machines(model, speeds, solve)
    elements = elements_of(model)
    if extra_torques is None and (model.has_load_dependent_losses or torque_sources(model)):
        from powergraph.statics.friction import solve_with_friction

        # the passes change efficiencies and bearing torques, never the motion: the speeds
        # are solved once for the operating point, the structure kept
        kin = solve_speeds(model, speeds, elements=elements)
        return solve_with_friction(model, lambda efficiencies, extra: _solve(
            model, kin, extra, with_efficiencies(elements, efficiencies)))
    return _solve(model, solve_speeds(model, speeds, elements=elements), extra_torques,
                  elements)


def with_efficiencies(elements: tuple[Element, ...],
                      efficiencies: Mapping[int, float]) -> tuple[Element, ...]:
    """The elements with these efficiencies (by link index) in place of their own."""
    return tuple(el._replace(efficiency=efficiencies[el.link])
                 if el.link in efficiencies else el for el in elements)


def _solve(model: Model, kin: Kinematics, extra_torques: Mapping[str, float] | None,
           elements: tuple[Element, ...] | None = None) -> PowerFlowResult:
    """:func:`solve` at given speeds (constant efficiencies, known bearing torques)."""
    elements = elements_of(model) if elements is None else elements
    loads = loads_of(model, kin)
    if extra_torques:     # a pass of the bearing iteration (only trains with bearing losses)
        from powergraph.statics.bearings import with_extra_torques

        loads = with_extra_torques(loads, extra_torques)
    rel = relative_speeds(elements, kin)

    def forces(factors: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        eq = _equilibrium(model, elements, loads, factors, kin, last)
        scales = force_scales(elements, eq.forces, factors, eq.external, model.frame_body)
        last[:] = [eq, np.array(factors, dtype=float), scales]
        return eq.forces, scales

    # the previous solve, its factors and its force scales: its sizes hint the next solve
    last: list = []
    pattern, passes, visited = settle(forces, elements, rel)
    if pattern is not None:
        factors = factors_of(pattern, elements)
        return _assemble(model, kin, elements, loads, factors, rel, passes, last)
    from powergraph.statics.locking import decide

    decision = decide(model, elements, loads, rel, forces, visited)
    search = DirectionSearch(method=decision.method, solutions=decision.solutions,
                             complete=decision.complete)
    if decision.chosen is not None:
        return _assemble(model, kin, elements, loads, decision.chosen.factors, rel, passes,
                         search=search)
    lock = Lock(meshes=tuple(elements[k].link for k in decision.locking),
                reasons=decision.reasons, asked=kin)
    return _at_rest(model, kin, elements, loads, passes, search, lock)


def _equilibrium(model: Model, elements: tuple[Element, ...], loads: Loads,
                 factors: np.ndarray, kin: Kinematics,
                 last: list = ()) -> Equilibrium:
    """The torque balance, solved scaled so each force and torque is accurate relative to
    itself (a long chain's last torque, tiny efficiencies); the previous solve, when there
    is one (``[equilibrium, factors, scales]``), tells the size of each unknown, or is the
    answer when its factors are the same."""
    guess = None
    if last:
        previous, previous_factors, _ = last
        if np.array_equal(previous_factors, factors):
            return previous
        guess = np.concatenate([previous.forces, [previous.external[b] for b in loads.unknown]])
    return solve_equilibrium(model, elements, loads, factors, kin.body_speeds, guess)


def _assemble(model: Model, kin: Kinematics, elements: tuple[Element, ...], loads: Loads,
              factors: np.ndarray, rel: np.ndarray, passes: int,
              last: list = (), search: DirectionSearch | None = None
              ) -> PowerFlowResult:
    """The result for consistent factors: forces, each element's driver, losses."""
    eq = _equilibrium(model, elements, loads, factors, kin, last)
    if last and last[0] is eq:    # the last solve of the iteration: its scales are known
        scales = last[2]
    else:
        scales = force_scales(elements, eq.forces, factors, eq.external, model.frame_body)
    pattern = pattern_of(eq.forces, rel, scales)
    flows = _element_flows(elements, eq.forces, factors, pattern, kin)
    return _result(model, kin, flows, eq, loads, passes, search)


def _at_rest(model: Model, kin: Kinematics, elements: tuple[Element, ...], loads,
             passes: int, search: DirectionSearch, lock: Lock) -> PowerFlowResult:
    """A locked train at rest holding its loads. Every mesh sticks; the holding torques
    are set-valued (static friction), and the lossless equilibrium (every factor 1, inside
    each sticking mesh's ``[η, 1/η]``) is the member reported."""
    rest = dataclasses.replace(
        kin, body_speeds=MappingProxyType({b: 0.0 for b in kin.body_speeds}))
    factors = np.ones(len(elements))
    eq = solve_equilibrium(model, elements, loads, factors, kin.body_speeds)
    flows = tuple(dataclasses.replace(flow, carrier_frame_power=0.0, loss=0.0)
                  for flow in _element_flows(elements, eq.forces, factors,
                                             [0] * len(elements), rest))
    result = _result(model, rest, flows, eq, loads, passes, search)
    return dataclasses.replace(result, lock=lock)


def _element_flows(elements: tuple[Element, ...], forces: np.ndarray, factors: np.ndarray,
                   pattern, kin: Kinematics) -> tuple[ElementFlow, ...]:
    """Each element's torques (its stencil times its force), carrier-frame power, driver
    and loss."""
    speeds = kin.body_speeds
    out = []
    for el, force, factor, c in zip(elements, np.asarray(forces, dtype=float).tolist(),
                                    np.asarray(factors, dtype=float).tolist(),
                                    np.asarray(pattern, dtype=int).reshape(-1).tolist()):
        t_a, t_b, t_c = (coefficient * force for coefficient in element_stencil(el.ratio, factor))
        power = -force * (speeds[el.body_a] - speeds[el.body_c])   # fed in by gear a
        torques: dict[str, float] = {el.body_a: 0.0 + t_a}
        torques[el.body_b] = torques.get(el.body_b, 0.0) + t_b
        if el.kind == "mesh" or factor != 1.0:  # an ideal coupling does not touch the frame
            torques[el.body_c] = torques.get(el.body_c, 0.0) + t_c
        out.append(ElementFlow(
            link=el.link, kind=el.kind, a=el.a, b=el.b, carrier=el.carrier, ratio=el.ratio,
            efficiency=el.efficiency, force=force, factor=factor,
            torques=MappingProxyType(torques),
            driver=el.a if c > 0 else (el.b if c < 0 else None),
            # the power through the element in its carrier's frame, and its loss
            # -(T_a (w_a - w_c) + T_b (w_b - w_c)) >= 0
            carrier_frame_power=power if c > 0 else (-power * factor if c < 0 else 0.0),
            loss=power * (1.0 - factor)))
    return tuple(out)


def _result(model: Model, kin: Kinematics, flows: tuple[ElementFlow, ...], eq: Equilibrium,
            loads: Loads, passes: int, search: DirectionSearch | None = None
            ) -> PowerFlowResult:
    torques = port_torques(model, loads, eq.external)

    def fed(port) -> float:
        return torques[port.index] * kin.body_speeds[model.body_of[port.component]]

    input_power = sum(fed(p) for p in model.inputs)
    output_power = -sum(fed(p) for p in model.outputs)
    return PowerFlowResult(
        model=model, kinematics=kin, elements=flows,
        external_torques=MappingProxyType(dict(eq.external)), input_power=float(input_power),
        output_power=float(output_power) + 0.0, total_loss=float(sum(f.loss for f in flows)),
        passes=passes, load_sharing_assumed=eq.indeterminate, search=search,
        port_torques=torques)
