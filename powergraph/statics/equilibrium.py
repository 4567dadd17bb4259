"""Torque equilibrium of every body for a given set of mesh factors (docs/theory.md).

Element ``k`` applies ``λ_k`` to gear a, ``-i·f·λ_k`` to gear b and ``(i·f - 1)·λ_k`` to
its carrier (``f = 1`` ideal, ``η`` when a drives in the carrier's frame, ``1/η`` when b
drives). Each body's element torques plus its external torque sum to zero. Unknowns: every
``λ``, the external torques not given, and the frame's reaction.
"""
from __future__ import annotations

from functools import lru_cache
from typing import Mapping, NamedTuple

import numpy as np

from powergraph.errors import StaticsError
from powergraph.kinematics import Element, Kinematics, element_stencil
from powergraph.kinematics.elements import ELEMENT_BODIES
from powergraph.kinematics.system import TrainSystem, system_of
from powergraph.linalg import (
    COND_LIMIT,
    PLAIN_UP_TO,
    SVD_RTOL,
    Triplets,
    equilibrated,
    others,
    solve_dense_square,
    solve_plain,
    solve_square,
    use_sparse,
)
from powergraph.model.spec import Model


class Loads(NamedTuple):
    """External torques known before the solve: ``{body id: N·m}`` plus which are unknown."""

    given: dict[str, float]
    unknown: tuple[str, ...]  # bodies whose external torque is solved for (ports, frame)
    needed: int               # how many port loads the train takes: ports - DOF


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
        given[body] = port_torque(power, "power", port.role, speed)
    unknown = [model.body_of[p.component] for p in model.ports
               if model.body_of[p.component] not in given]
    return Loads(given=given, unknown=tuple(unknown) + (model.frame_body,),
                 needed=len(model.ports) - kin.dof)


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
    row = {body.id: r for r, body in enumerate(model.bodies)}
    n_el = len(elements)
    rhs = np.zeros(len(model.bodies))
    for body, torque in loads.given.items():
        rhs[row[body]] -= torque
    if guess is None and speeds is not None:
        guess = expected_sizes(elements, loads, speeds)
    solution, indeterminate = _solve_small(model, elements, loads, factors, rhs, guess), False
    if solution is None:
        system = equilibrium_triplets(model, elements, loads, factors)
        solution, indeterminate = _solve(system, rhs, n_el, loads, guess)
    external = dict(loads.given)
    external.update({body: float(solution[n_el + j]) for j, body in enumerate(loads.unknown)})
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


class _Layout(NamedTuple):
    """Where the torque balance's entries go, sorted by row then column (the order of
    :class:`Triplets`): what :func:`_solve_small` needs besides the factors."""

    order: np.ndarray        # entries (a, b, carrier of each element, then external) sorted
    rows: np.ndarray         # their rows and columns, in that order
    cols: np.ndarray
    unknown_rows: np.ndarray  # the row of each unknown external torque, in column order
    others: np.ndarray       # the other rows, which fix the forces
    # per element, for its gear a, gear b and carrier: (row among ``others``, or -1;
    # position among the unknown torques, or -1) — the plain-Python path's map
    places: tuple[tuple[tuple[int, int], ...], ...]
    system: TrainSystem      # the structure these come from


def _layout(model: Model, elements: tuple[Element, ...], loads: Loads) -> _Layout | None:
    """The layout of a small square balance whose unknown torques sit on distinct bodies
    and whose elements touch three distinct bodies (else None: the general path). It
    depends on which bodies each element touches only, so it is kept for the last few
    structures (a friction solve re-solves one structure with new efficiencies)."""
    if use_sparse(len(elements)):
        return None
    return _layout_of(tuple(body.id for body in model.bodies),
                      tuple(map(ELEMENT_BODIES, elements)), loads.unknown)


@lru_cache(maxsize=64)
def _layout_of(body_ids: tuple[str, ...], triples: tuple[tuple[str, str, str], ...],
               unknown: tuple[str, ...]) -> _Layout | None:
    row = {body: r for r, body in enumerate(body_ids)}
    n_el, n_ext = len(triples), len(unknown)
    system = TrainSystem(len(body_ids), [[row[b] for b in triple] for triple in triples],
                         [row[b] for b in unknown])
    unknown_rows = system.unknown
    rows, cols, _ = system.balance_triplets(np.ones(n_el))
    square = len(body_ids) == n_el + n_ext and not use_sparse(n_el)
    distinct = len(set((rows * (n_el + n_ext) + cols).tolist())) == len(rows)
    if not (square and distinct and len(set(unknown_rows.tolist())) == n_ext):
        return None
    order = np.lexsort((cols, rows))
    balance = others(len(body_ids), unknown_rows)
    row_of = {int(body): i for i, body in enumerate(balance)}
    unknown_of = {int(body): j for j, body in enumerate(unknown_rows)}
    places = tuple(tuple((row_of.get(body, -1), unknown_of.get(body, -1)) for body in triple)
                   for triple in system.places.tolist())
    return _Layout(order, rows[order], cols[order], unknown_rows, balance, places, system)


def _solve_small(model: Model, elements: tuple[Element, ...], loads: Loads, factors,
                 rhs: np.ndarray, guess: np.ndarray | None) -> np.ndarray | None:
    """:func:`_solve_forces_first` for a small balance on a dense matrix built from the
    cached layout (the same numbers, without rebuilding the structure each time); None
    when the layout does not apply or the forces' part is not regular."""
    layout = _layout(model, elements, loads)
    if layout is None:
        return None
    n_el = len(elements)
    if n_el <= PLAIN_UP_TO:
        return _solve_plain(layout, elements, factors, rhs, guess)
    values = layout.system.balance_triplets([el.ratio for el in elements],
                                            factors)[2][layout.order]
    matrix = np.zeros((len(rhs), len(rhs)))
    matrix[layout.rows, layout.cols] = values
    matrix += 0.0   # no negative zeros, as Triplets drops them
    solved = solve_dense_square(matrix[layout.others][:, :n_el], rhs[layout.others],
                                None if guess is None else guess[:n_el])
    if not solved.regular:
        return None
    x = np.zeros(len(rhs))
    x[:n_el] = solved.x
    force = layout.cols < n_el
    element_torques = np.bincount(layout.rows[force],
                                  weights=values[force] * solved.x[layout.cols[force]],
                                  minlength=len(rhs))
    x[n_el:] = rhs[layout.unknown_rows] - element_torques[layout.unknown_rows]
    return x


def _solve_plain(layout: _Layout, elements: tuple[Element, ...], factors,
                 rhs: np.ndarray, guess: np.ndarray | None) -> np.ndarray | None:
    """:func:`_solve_small`'s steps on plain Python floats (a few elements: no numpy
    call costs more than the arithmetic): the forces from the rows of the bodies with no
    unknown torque, then each unknown torque from its own body's row."""
    n_el = len(elements)
    matrix = [[0.0] * n_el for _ in range(n_el)]
    torques = rhs[layout.unknown_rows].tolist()
    balance = rhs[layout.others].tolist()
    terms: list[list[tuple[int, float]]] = [[] for _ in torques]
    for k, (el, f, places) in enumerate(zip(elements, np.asarray(factors, dtype=float).tolist(),
                                            layout.places)):
        for (row, unknown), coefficient in zip(places, element_stencil(el.ratio, f)):
            if row >= 0:
                matrix[row][k] += coefficient
            else:
                terms[unknown].append((k, coefficient))
    forces, cond = solve_plain(matrix, balance, None if guess is None
                               else guess[:n_el].tolist())
    if forces is None or not cond < COND_LIMIT:
        return None
    for j, body_terms in enumerate(terms):
        total = 0.0
        for k, coefficient in body_terms:
            total += coefficient * forces[k]
        torques[j] -= total
    return np.array(forces + torques)


def _solve_forces_first(system: Triplets, rhs: np.ndarray, n_el: int,
                        guess: np.ndarray | None) -> np.ndarray | None:
    """A square balance with the unknown external torques eliminated first: each one
    appears in its own body's row only, so the other rows fix the forces (solved scaled)
    and its row then gives it. None when that part is not regular (or two unknown torques
    share a body)."""
    unknown_rows = system.rows[system.cols >= n_el]
    if len(set(unknown_rows.tolist())) != system.shape[1] - n_el:
        return None
    balance = others(system.shape[0], unknown_rows)
    forces_part = system.part(balance, np.arange(n_el))
    solved = solve_square(forces_part, rhs[balance], None if guess is None else guess[:n_el])
    if not solved.regular:
        return None
    x = np.zeros(system.shape[1])
    x[:n_el] = solved.x
    element_torques = system.part(np.arange(system.shape[0]), np.arange(n_el)).dot(solved.x)
    order = system.cols[system.cols >= n_el]
    x[order] = rhs[unknown_rows] - element_torques[unknown_rows]
    return x


def _solve(system: Triplets, rhs: np.ndarray, n_el: int, loads: Loads,
           guess: np.ndarray | None = None) -> tuple[np.ndarray, bool]:
    if system.shape[0] == system.shape[1]:
        x = _solve_forces_first(system, rhs, n_el, guess)
        if x is not None:
            return x, False
    matrix = system.dense()
    _, s, vt = np.linalg.svd(equilibrated(matrix))
    rank = int(np.sum(s > SVD_RTOL * max(1.0, s[0]))) if s.size else 0
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
