"""Torque equilibrium of every body for a given set of mesh factors (DESIGN §3).

Element ``k`` applies ``λ_k`` to gear a, ``-i·f·λ_k`` to gear b and ``(i·f - 1)·λ_k`` to
its carrier (``f = 1`` ideal, ``η`` when a drives in the carrier's frame, ``1/η`` when b
drives). Each body's element torques plus its external torque sum to zero. Unknowns: every
``λ``, the external torques not given, and the frame's reaction.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from powergraph.errors import StaticsError
from powergraph.kinematics import Element, Kinematics
from powergraph.model.spec import Model

_RTOL = 1e-10


@dataclass(frozen=True)
class Loads:
    """External torques known before the solve: ``{body id: N·m}`` plus which are unknown."""

    given: dict[str, float]
    unknown: tuple[str, ...]  # bodies whose external torque is solved for (ports, frame)
    needed: int               # how many port loads the train takes: ports - DOF


def loads_of(model: Model, kin: Kinematics) -> Loads:
    """External torques from the ports' power/torque (SPEC §1 sign conventions).

    An input's power is what it feeds in (``T = P/w``); an output's power is what it takes
    out (``T = -P/w``). With no power or torque anywhere, the first input feeds 1 W.
    """
    given: dict[str, float] = {}
    loaded = [p for p in model.ports if p.power is not None or p.torque is not None]
    if not loaded:
        first = model.inputs[0]
        loaded_values = [(first, 1.0, None)]
    else:
        loaded_values = [(p, p.power, p.torque) for p in loaded]
    for port, power, torque in loaded_values:
        body = model.body_of[port.component]
        if torque is not None:
            given[body] = torque
            continue
        speed = kin.speed(port.component)
        if abs(speed) < 1e-12:
            raise StaticsError("a power is given but the component does not turn "
                               "(speed 0), so its torque is unknown; give a torque instead",
                               f"{port.path}.power")
        given[body] = power / speed if port.role == "input" else -power / speed
    unknown = [model.body_of[p.component] for p in model.ports
               if model.body_of[p.component] not in given]
    return Loads(given=given, unknown=tuple(unknown) + (model.frame_body,),
                 needed=len(model.ports) - kin.dof)


@dataclass(frozen=True)
class Equilibrium:
    """Solution of the torque balance for one set of factors."""

    forces: np.ndarray           # λ per element
    external: dict[str, float]   # external torque per loaded body (given and solved)
    indeterminate: bool          # internal load sharing not fixed by statics (min-norm used)


def solve_equilibrium(model: Model, elements: tuple[Element, ...], loads: Loads,
                      factors: np.ndarray) -> Equilibrium:
    """Solve the torque balance for element factors ``factors`` (``f`` per element)."""
    row = {body.id: r for r, body in enumerate(model.bodies)}
    n_el, n_ext = len(elements), len(loads.unknown)
    matrix = np.zeros((len(model.bodies), n_el + n_ext))
    for k, (el, f) in enumerate(zip(elements, factors)):
        matrix[row[el.body_a], k] += 1.0
        matrix[row[el.body_b], k] -= el.ratio * f
        matrix[row[el.body_c], k] += el.ratio * f - 1.0
    for j, body in enumerate(loads.unknown):
        matrix[row[body], n_el + j] = 1.0
    rhs = np.zeros(len(model.bodies))
    for body, torque in loads.given.items():
        rhs[row[body]] -= torque
    solution, indeterminate = _solve(matrix, rhs, n_el, model, loads)
    external = dict(loads.given)
    external.update({body: float(solution[n_el + j]) for j, body in enumerate(loads.unknown)})
    return Equilibrium(forces=solution[:n_el], external=external, indeterminate=indeterminate)


def _solve(matrix: np.ndarray, rhs: np.ndarray, n_el: int, model: Model,
           loads: Loads) -> tuple[np.ndarray, bool]:
    if matrix.shape[0] == matrix.shape[1]:
        try:
            solution = np.linalg.solve(matrix, rhs)
            if np.all(np.isfinite(solution)) and np.linalg.cond(matrix) < 1e12:
                return solution, False
        except np.linalg.LinAlgError:
            pass
    _, s, vt = np.linalg.svd(matrix)
    rank = int(np.sum(s > _RTOL * max(1.0, s[0])))
    null = vt[rank:]
    if null.size and np.any(np.abs(null[:, n_el:]) > 1e-9):
        missing = max(1, loads.needed - len(loads.given))
        raise StaticsError(
            f"the loads are not determined: this train takes the power or torque of "
            f"{loads.needed} port(s), {len(loads.given)} given; give {missing} more", "ports")
    solution = np.linalg.lstsq(matrix, rhs, rcond=None)[0]
    residual = matrix @ solution - rhs
    if np.max(np.abs(residual)) > 1e-8 * max(1.0, float(np.max(np.abs(rhs)))):
        raise StaticsError(
            f"the given powers/torques contradict each other: this train takes the power or "
            f"torque of {loads.needed} port(s), {len(loads.given)} given", "ports")
    return solution, bool(null.size)
