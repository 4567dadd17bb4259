"""Torque equilibrium of every body for a given set of mesh factors (docs/theory.md).

Element ``k`` applies ``λ_k`` to gear a, ``-i·f·λ_k`` to gear b and ``(i·f - 1)·λ_k`` to
its carrier (``f = 1`` ideal, ``η`` when a drives in the carrier's frame, ``1/η`` when b
drives). Each body's element torques plus its external torque sum to zero. Unknowns: every
``λ``, the external torques not given, and the frame's reaction.
"""
from __future__ import annotations

from functools import lru_cache
from types import MappingProxyType
from typing import Mapping, NamedTuple

import numpy as np

from powergraph.errors import StaticsError
from powergraph.kinematics import Element, Kinematics, element_stencil
from powergraph.kinematics.elements import ELEMENT_BODIES
from powergraph.kinematics.system import TrainSystem, system_of
from powergraph.linalg import (SVD_RTOL, Triplets, equilibrated, others, solve_square,
                               unique_inverse)
from powergraph.model.spec import Model


class Loads(NamedTuple):
    """External torques known before the solve: ``{body id: N·m}`` plus which are unknown."""

    given: dict[str, float]
    unknown: tuple[str, ...]  # bodies whose external torque is solved for (ports, frame)
    needed: int               # how many port loads the train takes: ports - DOF
    #: The given torque of each loaded port, by port index (a body with several ports
    #: that are all loaded has their sum in ``given``; one with an unloaded port is among
    #: the unknowns, and its loaded ports' torques are here only).
    ports: Mapping[int, float] = MappingProxyType({})


def port_torque(value, kind: str, role: str, speed):
    """The external torque of a loaded port: its ``torque``, or from its ``power`` what an
    input feeds in (``P/w``) or an output takes out (``-P/w``; docs/format.md). Floats,
    arrays of operating points or sympy expressions: the one place the convention is
    written.

    >>> port_torque(100.0, "power", "input", 10.0), port_torque(100.0, "power", "output", 10.0)
    (10.0, -10.0)
    """
    if kind == "torque":
        return value
    return value / speed if role == "input" else -value / speed


def loads_of(model: Model, kin: Kinematics) -> Loads:
    """External torques from the ports' power/torque (sign conventions of docs/format.md).

    An input's power is what it feeds in (``T = P/w``); an output's power is what it takes
    out (``T = -P/w``). With no power or torque anywhere, the first input feeds 1 W. An
    inactive port (docs/modes.md) carries nothing and is not counted. Several ports may
    share a rigid body when at most one of them has no load: the body's external torque
    is then that port's plus the others' (:func:`port_torques`).

    Raises
    ------
    StaticsError
        A power on a port that does not turn; two unloaded ports on one rigid body.
    """
    active = [p for p in model.ports if p.index not in model.inactive]
    loaded = [p for p in active if p.power is not None or p.torque is not None]
    if not loaded:
        if not model.inputs:
            raise StaticsError("no port has a load and no input is active: give the power "
                               "or torque of a port", "ports", missing="load")
        first = model.inputs[0]
        loaded_values = [(first, 1.0, None)]
    else:
        loaded_values = [(p, p.power, p.torque) for p in loaded]
    by_port: dict[int, float] = {}
    for port, power, torque in loaded_values:
        if torque is not None:
            by_port[port.index] = torque
            continue
        speed = kin.speed(port.component)
        if abs(speed) < 1e-12:
            raise StaticsError("a power is given but the component does not turn "
                               "(speed 0), so its torque is unknown; give a torque instead",
                               f"{port.path}.power")
        by_port[port.index] = port_torque(power, "power", port.role, speed)
    unknown: dict[str, int] = {}
    for port in active:
        if port.index in by_port:
            continue
        body = model.body_of[port.component]
        if body in unknown:
            raise StaticsError(
                f"{model.port_label(unknown[body])} and {model.port_label(port.index)} are "
                f"on one rigid body {body!r} and neither has a load: the torque balance "
                "gives only their sum; give the power or torque of one of them",
                f"{port.path}.component")
        unknown[body] = port.index
    given: dict[str, float] = {}
    for index, torque in by_port.items():
        body = model.body_of[model.ports[index].component]
        if body not in unknown:
            given[body] = given.get(body, 0.0) + torque
    return Loads(given=given, unknown=tuple(unknown) + (model.frame_body,),
                 needed=len(active) - kin.dof, ports=MappingProxyType(by_port))


def port_torques(model: Model, loads: Loads, external: Mapping[str, float]
                 ) -> tuple[float, ...]:
    """The external torque of each port (by its place in ``model.ports``, N·m): a
    loaded port's own, an unloaded one's its body's external torque less the other ports'
    on that body, an inactive port's 0.

    >>> from powergraph.model import model_from_dict
    >>> m = model_from_dict({"name": "p1", "components": {0: {"role": "frame"},
    ...     "e": {}, "a": {"teeth": 20}, "w": {"teeth": 40}},
    ...     "links": [{"type": "fixed", "between": ["e", "a"]},
    ...               {"type": "mesh", "between": ["a", "w"]}],
    ...     "ports": [{"component": "e", "role": "input", "speed": 10, "torque": 3},
    ...               {"component": "a", "role": "input", "torque": 2},
    ...               {"component": "w", "role": "output"}]})
    >>> port_torques(m, Loads({"e/a": 5.0}, ("w", "0"), 1, {0: 3.0, 1: 2.0}),
    ...              {"e/a": 5.0, "w": -10.0, "0": 5.0})
    (3.0, 2.0, -10.0)
    """
    others: dict[str, float] = {}
    for index, torque in loads.ports.items():
        body = model.body_of[model.ports[index].component]
        others[body] = others.get(body, 0.0) + torque
    out = []
    for port in model.ports:
        if port.index in loads.ports:
            out.append(float(loads.ports[port.index]))
        elif port.index in model.inactive:
            out.append(0.0)
        else:
            body = model.body_of[port.component]
            out.append(float(external.get(body, 0.0)) - others.get(body, 0.0) + 0.0)
    return tuple(out)


class Equilibrium(NamedTuple):
    """Solution of the torque balance for one set of factors."""

    forces: np.ndarray           # λ per element
    external: dict[str, float]   # external torque per loaded body (given and solved)
    indeterminate: bool          # internal load sharing not fixed by statics (min-norm used)


def equilibrium_triplets(model: Model, elements: tuple[Element, ...], loads: Loads,
                         factors) -> Triplets:
    """The torque balance: rows = bodies, columns = element forces then unknown external
    torques. Each element's column is its stencil with its factor."""
    system = system_of([body.id for body in model.bodies], elements, loads.unknown)
    triplets = system.balance_triplets([el.ratio for el in elements], factors)
    return Triplets.build(*triplets, (system.n_bodies, system.n_columns))


def solve_equilibrium(model: Model, elements: tuple[Element, ...], loads: Loads,
                      factors: np.ndarray, speeds: Mapping[str, float] | None = None,
                      guess: np.ndarray | None = None) -> Equilibrium:
    """Solve the torque balance for element factors ``factors`` (``f`` per element).

    ``speeds`` (body speeds, optional) give the expected size of each unknown before the
    solve: a force passes about the train's power at its relative speed, an external
    torque about that power at its body's speed (:func:`expected_sizes`). ``guess``, the
    forces then the unknown external torques of a previous solve, is a better hint still.

    A square balance is solved scaled (each force and torque accurate relative to itself,
    :func:`powergraph.linalg.solve_square`) and is determined when its scaled
    system is regular; otherwise the singular values of the equilibrated balance decide
    between indeterminate load sharing (minimum-norm forces), undetermined loads and
    contradictory loads.
    """
    structure = _structure_of(tuple(body.id for body in model.bodies),
                              tuple(map(ELEMENT_BODIES, elements)), loads.unknown)
    n_el = len(elements)
    rhs = np.zeros(len(model.bodies))
    for body, torque in loads.given.items():
        rhs[structure.row[body]] -= torque
    if guess is None and speeds is not None:
        guess = expected_sizes(elements, loads, speeds)
    solution, indeterminate = None, False
    if structure.forces_first:
        solution = _solve_forces_first(structure, [el.ratio for el in elements], factors, rhs,
                                       guess)
    if solution is None:
        system = equilibrium_triplets(model, elements, loads, factors)
        solution, indeterminate = _solve(system, rhs, n_el, loads)
    external = dict(loads.given)
    external.update(zip(loads.unknown, solution[n_el:].tolist()))
    return Equilibrium(forces=solution[:n_el], external=external, indeterminate=indeterminate)


def expected_sizes(elements: tuple[Element, ...], loads: Loads,
                   speeds: Mapping[str, float]) -> np.ndarray:
    """Expected magnitude of each unknown (forces, then unknown external torques): the
    train's power over the relative speed of the element or the speed of the body; 0
    where that speed is 0 (the solve then takes the size the neighbours give)."""
    power = max((abs(t * speeds[b]) for b, t in loads.given.items()), default=0.0) or 1.0
    rel = [abs(speeds[el.body_a] - speeds[el.body_c]) for el in elements]
    rel += [abs(speeds[b]) for b in loads.unknown]
    return np.array([power / w if w > 0 else 0.0 for w in rel], dtype=float)


class _Structure(NamedTuple):
    """Where the torque balance's entries go, for a structure (which bodies each element
    touches, whose torques are unknown): it does not depend on the ratios or factors, so
    it is kept for the last few structures (a solve re-solves one structure with new
    factors; a friction solve with new efficiencies too).

    The balance's cells (row, element) with an element entry, sorted by row then column
    (the order of :class:`Triplets`), and for each element entry (its stencil on gear a,
    gear b and carrier, as :meth:`TrainSystem.balance_triplets` lists them) its cell
    (duplicates, an element touching a body twice, are summed there); the cells on the
    rows with no unknown torque, which fix the forces, renumbered among those rows; the
    cells on each unknown torque's row."""

    row: Mapping[str, int]    # each body's row
    system: TrainSystem
    forces_first: bool        # square, and each unknown torque alone on its body
    cell: np.ndarray          # the cell of each element entry (gear a's, b's, carriers')
    force_cells: np.ndarray   # the cells on the other rows, their row among those, column
    force_rows: np.ndarray
    force_cols: np.ndarray
    balance_rows: np.ndarray  # the rows with no unknown torque
    torque_cells: np.ndarray  # the cells on the unknown torques' rows, the torque, column
    torque_of: np.ndarray
    torque_cols: np.ndarray
    unknown_rows: np.ndarray  # the row of each unknown torque


@lru_cache(maxsize=64)
def _structure_of(body_ids: tuple[str, ...], triples: tuple[tuple[str, str, str], ...],
                  unknown: tuple[str, ...]) -> _Structure:
    row = {body: r for r, body in enumerate(body_ids)}
    n_el, n_bodies = len(triples), len(body_ids)
    system = TrainSystem(n_bodies, [[row[b] for b in triple] for triple in triples],
                         [row[b] for b in unknown])
    rows, cols, _ = system.balance_triplets(np.ones(n_el))
    entries = slice(0, 3 * n_el)        # then the unknown torques' ones
    cells, cell = unique_inverse(rows[entries] * n_el + cols[entries])
    cell_rows, cell_cols = cells // max(n_el, 1), cells % max(n_el, 1)
    unknown_rows = system.unknown
    forces_first = (n_bodies == n_el + len(unknown)
                    and len(set(unknown_rows.tolist())) == len(unknown))
    balance_rows = others(n_bodies, unknown_rows)
    renumber = np.full(n_bodies, -1)
    renumber[balance_rows] = np.arange(len(balance_rows))
    torque_index = np.full(n_bodies, -1)
    torque_index[unknown_rows] = np.arange(len(unknown_rows))
    force_cells = np.flatnonzero(renumber[cell_rows] >= 0)
    torque_cells = np.flatnonzero(torque_index[cell_rows] >= 0)
    structure = _Structure(MappingProxyType(row), system, forces_first, cell, force_cells,
                           renumber[cell_rows[force_cells]], cell_cols[force_cells],
                           balance_rows, torque_cells, torque_index[cell_rows[torque_cells]],
                           cell_cols[torque_cells], unknown_rows)
    for array in structure[3:]:
        array.flags.writeable = False
    return structure


def _solve_forces_first(structure: _Structure, ratios, factors, rhs: np.ndarray,
                        guess: np.ndarray | None) -> np.ndarray | None:
    """A square balance with the unknown external torques eliminated first: each one
    appears in its own body's row only, so the other rows fix the forces (solved scaled)
    and its row then gives it. None when that part is not regular."""
    s = structure
    n_el = s.system.n_elements
    on_a, on_b, on_c = element_stencil(np.asarray(ratios, dtype=float), factors)
    values = np.concatenate([np.full(n_el, on_a), on_b, on_c])
    summed = np.bincount(s.cell, weights=values, minlength=len(s.force_cols) + len(s.torque_cols))
    part = summed[s.force_cells]
    rows, cols = s.force_rows, s.force_cols
    if not part.all():      # no exact zeros, as Triplets.build drops them
        kept = part != 0.0
        rows, cols, part = rows[kept], cols[kept], part[kept]
    forces_part = Triplets(rows, cols, part, (len(s.balance_rows), n_el))
    solved = solve_square(forces_part, rhs[s.balance_rows],
                          None if guess is None else guess[:n_el])
    if not solved.regular:
        return None
    element_torques = np.bincount(s.torque_of, weights=summed[s.torque_cells]
                                  * solved.x[s.torque_cols], minlength=len(s.unknown_rows))
    return np.concatenate([solved.x, rhs[s.unknown_rows] - element_torques])


def _solve(system: Triplets, rhs: np.ndarray, n_el: int,
           loads: Loads) -> tuple[np.ndarray, bool]:
    """A balance the forces-first solve does not determine: by the singular values of the
    equilibrated balance, indeterminate load sharing (minimum-norm forces), or an error
    naming undetermined or contradictory loads."""
    matrix = system.dense()
    _, s, vt = np.linalg.svd(equilibrated(matrix))
    rank = int(np.sum(s > SVD_RTOL * max(1.0, s[0]))) if s.size else 0
    null = vt[rank:]
    if null.size and np.any(np.abs(null[:, n_el:]) > 1e-9):
        missing = max(1, loads.needed - len(loads.given))
        raise StaticsError(
            f"the loads are not determined: this train takes the power or torque of "
            f"{loads.needed} port(s), {len(loads.given)} given; give {missing} more", "ports",
            missing="load")
    solution = np.linalg.lstsq(matrix, rhs, rcond=None)[0]
    residual = matrix @ solution - rhs
    if np.max(np.abs(residual)) > 1e-8 * max(1.0, float(np.max(np.abs(rhs)))):
        raise StaticsError(
            f"the given powers/torques contradict each other: this train takes the power or "
            f"torque of {loads.needed} port(s), {len(loads.given)} given", "ports")
    return solution, bool(null.size)
