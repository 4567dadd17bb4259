"""Speeds of every body from the given input speeds (docs/theory.md).

One linear row per mesh ``(w_a - w_c) - i (w_b - w_c) = s`` (``s`` = 0, or a slip used by
sensitivity analyses), one per coupling ``w_a - w_b = 0``, and ``w_frame = 0``.
DOF = bodies - rank (decided structurally, confirmed on the scaled system, see
:mod:`powergraph.linalg`). A rank defect or an inconsistency is a
KinematicsError that says what is wrong, never a NaN: given speeds that contradict each
other name the links whose rows cannot all hold, and what those rows require of them.
"""
from __future__ import annotations

from dataclasses import field
from types import MappingProxyType
from typing import Mapping

import numpy as np

from powergraph.errors import KinematicsError
from powergraph.kinematics.elements import Element, elements_of
from powergraph.kinematics.system import CONFLICT_RTOL, conflict, element_words, system_of
from powergraph.linalg import (
    SVD_RTOL,
    Triplets,
    equilibrated,
    matching,
    rank,
    solve_square,
    svd_rank,
)
from powergraph.model.spec import Model
from powergraph.records import record


@record
class Kinematics:
    """Speeds of a train. ``body_speeds`` in rad/s keyed by body id ("2/3").

    Examples
    --------
    >>> from powergraph.model import load_model
    >>> kin = solve_speeds(load_model("models/rv40e_wang2021.yaml"))     # doctest: +SKIP
    >>> round(kin.speed("4"), 5)                                # doctest: +SKIP
    1.29818
    """

    body_speeds: Mapping[str, float]
    body_of: Mapping[str, str] = field(repr=False)
    dof: int
    given: Mapping[str, float]
    input_component: str | None = None
    output_component: str | None = None

    def speed(self, component: str) -> float:
        """Absolute speed (rad/s) of a component (id as a string)."""
        return self.body_speeds[self.body_of[str(component)]]

    def relative(self, component: str, frame: str) -> float:
        """Speed of ``component`` seen from the body of component ``frame``."""
        return self.speed(component) - self.speed(frame)

    @property
    def ratio(self) -> float | None:
        """Input speed / output speed for a one-input, one-output train (else None)."""
        if self.input_component is None or self.output_component is None:
            return None
        out = self.speed(self.output_component)
        return self.speed(self.input_component) / out if out != 0 else float("inf")

    def to_dict(self) -> dict:
        return {"dof": self.dof, "ratio": self.ratio,
                "speeds": {c: self.body_speeds[b] for c, b in self.body_of.items()}}


def constraint_triplets(model: Model, elements: tuple[Element, ...] | None = None) -> Triplets:
    """The constraint rows as triplets: one row per element (its stencil, factor 1),
    then ``w_frame = 0``; columns: bodies in ``model.bodies`` order."""
    elements = elements_of(model) if elements is None else elements
    ids = [body.id for body in model.bodies]
    n_el = len(elements)
    rows, cols, values = system_of(ids, elements).willis_triplets(
        [el.ratio for el in elements])
    return Triplets.build(np.append(rows, n_el), np.append(cols, ids.index(model.frame_body)),
                          np.append(values, 1.0), (n_el + 1, len(ids)))


def constraint_matrix(model: Model, elements: tuple[Element, ...] | None = None) -> np.ndarray:
    """Rows: one per element (Willis/coupling), then ``w_frame = 0``; columns: bodies."""
    return constraint_triplets(model, elements).dense()


def degrees_of_freedom(model: Model) -> int:
    """Number of independent speeds the train needs (bodies - rank of the constraints)."""
    return len(model.bodies) - rank(constraint_triplets(model))


def solve_speeds(model: Model, speeds: Mapping[str, float] | None = None,
                 slips: Mapping[int, float] | None = None,
                 elements: tuple[Element, ...] | None = None) -> Kinematics:
    """Solve every body's speed.

    Parameters
    ----------
    model : Model
    speeds : mapping, optional
        ``{component id: rad/s}``; defaults to the ports' ``speed`` values, or the first
        input at 1 rad/s when no port gives one and the train has one DOF.
    slips : mapping, optional
        ``{link index: s}`` added to that mesh's Willis row (used for backlash and
        fluctuation sensitivities; 0 in a normal solve).
    elements : tuple of Element, optional
        ``elements_of(model)``, when the caller has it already.

    Returns
    -------
    Kinematics

    Raises
    ------
    KinematicsError
        Wrong number of speeds, speeds that do not fix the motion or contradict each other,
        or a train that cannot move.

    Examples
    --------
    >>> from powergraph.model import model_from_dict
    >>> m = model_from_dict({"name": "pair", "components": {0: {"role": "frame"},
    ...     1: {"teeth": 20}, 2: {"teeth": 50}},
    ...     "links": [{"type": "mesh", "between": [1, 2]}],
    ...     "ports": [{"component": 1, "role": "input", "speed": 10},
    ...               {"component": 2, "role": "output"}]})
    >>> kin = solve_speeds(m)
    >>> kin.speed("2"), kin.ratio
    (-4.0, -2.5)
    """
    elements = elements_of(model) if elements is None else elements
    # the speeds at the ports' own speeds depend on the model alone: solved once per model
    own = speeds is None and not slips and elements is model.derived.get("kinematics.elements")
    if own and "kinematics.own_speeds" in model.derived:
        return model.derived["kinematics.own_speeds"]
    rows, dof = _structure(model, elements)
    if dof == 0:
        raise KinematicsError("the train cannot move (0 degrees of freedom): its meshes and "
                              "couplings lock every body")
    given = _given_speeds(model, speeds, dof)
    rhs = np.zeros(len(elements))
    row_of = {el.link: r for r, el in enumerate(elements)}
    for index, value in (slips or {}).items():
        if index not in row_of:
            raise KinematicsError(f"links[{index}] is not a mesh or coupling: it has no slip")
        rhs[row_of[index]] = value
    solution = _solve_reduced(model, rows, rhs, given, elements)
    inputs, outputs = model.inputs, model.outputs
    ids = [b.id for b in model.bodies]
    kin = Kinematics(
        body_speeds=MappingProxyType(dict(zip(ids, solution.tolist()))),
        body_of=model.body_of, dof=dof, given=MappingProxyType(dict(given)),
        input_component=inputs[0].component if len(inputs) == 1 else None,
        output_component=outputs[0].component if len(outputs) == 1 else None)
    if own:
        model.derived["kinematics.own_speeds"] = kin
    return kin


def _structure(model: Model, elements: tuple[Element, ...]) -> tuple[Triplets, int]:
    """The element rows of the constraints (without ``w_frame = 0``) and the DOF: they
    depend on the model alone, so they are computed once per model (for its own
    elements; other elements are computed each time)."""
    cached = model.derived.get("kinematics.structure")
    if cached is not None and cached[0] is elements:
        return cached[1], cached[2]
    system = constraint_triplets(model, elements)
    dof = len(model.bodies) - rank(system)
    rows = system.part(np.arange(len(elements)), np.arange(len(model.bodies)))
    if elements is model.derived.get("kinematics.elements"):
        model.derived["kinematics.structure"] = (elements, rows, dof)
    return rows, dof


def _solve_reduced(model: Model, rows: Triplets, rhs: np.ndarray,
                   given: Mapping[str, float], elements: tuple[Element, ...]) -> np.ndarray:
    """Substitute the frame and the given speeds, then solve for the other bodies: the
    rows matched to the unknowns (structurally) solved scaled, every row checked."""
    column = {body.id: j for j, body in enumerate(model.bodies)}
    known: dict[int, float] = {column[model.frame_body]: 0.0}
    for component, value in given.items():
        j = column[model.body_of[component]]
        if j in known and abs(known[j] - value) > 1e-12 * max(1.0, abs(value)):
            what = "is fixed to the frame" if j == column[model.frame_body] else \
                "is on a body whose speed is already given"
            raise KinematicsError(f"a speed is given for {component!r}, which {what}")
        known[j] = value
    solution = np.zeros(len(model.bodies))
    solution[list(known)] = list(known.values())
    is_known = np.zeros(len(model.bodies), dtype=bool)
    is_known[list(known)] = True
    unknown = np.flatnonzero(~is_known)
    reduced, square = _reduced(model, rows, unknown)
    reduced_rhs = rhs - rows.dot(solution)
    determined = True
    if unknown.size:
        values, determined = _solve_unknown(reduced, reduced_rhs, square)
        solution[unknown] = values
    residual = rows.dot(solution) - rhs
    scale = max(1.0, float(np.max(np.abs(solution))))
    if residual.size and np.max(np.abs(residual)) > 1e-9 * scale:
        raise KinematicsError(contradiction_message(model, elements, rows, rhs, known,
                                                    given, reduced, square))
    if not determined:
        raise KinematicsError(_underdetermined_message(model, reduced, unknown, given),
                              missing="speed")
    return solution


def _reduced(model: Model, rows: Triplets, unknown: np.ndarray):
    """The constraint rows on the unknown speeds, and ``(matched rows, their column per
    row, the matched square part)``; cached per model and set of unknowns when ``rows``
    are the model's own (:func:`_structure`)."""
    cached = model.derived.get("kinematics.structure")
    key = ("kinematics.reduced", unknown.tobytes())
    own = cached is not None and cached[1] is rows
    if own and key in model.derived:
        return model.derived[key]
    reduced = rows.part(np.arange(rows.shape[0]), unknown)
    col_of = matching(reduced)
    matched = np.flatnonzero(col_of >= 0)
    out = reduced, (matched, col_of[matched], reduced.part(matched, col_of[matched]))
    if own:
        model.derived[key] = out
    return out


def _solve_unknown(reduced: Triplets, rhs: np.ndarray,
                   square: tuple[np.ndarray, np.ndarray, Triplets]) -> tuple[np.ndarray, bool]:
    """The unknown speeds and whether they are determined: the rows matched to them
    (``square``: the rows, their columns, that part) solved scaled when they are regular
    (the usual case; unknowns left unmatched are 0 and undetermined, and since the
    matched rows then span all the rows, the others hold iff the speeds are consistent);
    else dense least squares and the rank of the equilibrated matrix."""
    rows, columns, part = square
    solved = solve_square(part, rhs[rows])
    if solved.regular:
        values = np.zeros(reduced.shape[1])
        values[columns] = solved.x
        return values, rows.size == reduced.shape[1]
    matrix = reduced.dense()
    values = np.linalg.lstsq(matrix, rhs, rcond=None)[0]
    return values, svd_rank(reduced) == reduced.shape[1]


def _given_speeds(model: Model, speeds: Mapping[str, float] | None, dof: int) -> dict:
    if speeds is not None:
        given = {str(k): float(v) for k, v in speeds.items()}
        for component in given:
            if component not in model.components:
                raise KinematicsError(f"speed given for unknown component {component!r}")
    else:
        given = _port_speeds(model)
        if not given and dof == 1:
            if not model.inputs:
                raise KinematicsError("no port gives a speed and no input is active: give "
                                      "the speed of a port", "ports", missing="speed")
            given = {model.inputs[0].component: 1.0}
    if len(given) != dof:
        plural = "s" if dof != 1 else ""
        raise KinematicsError(
            f"train has {dof} degree{plural} of freedom but {len(given)} speed"
            f"{'s were' if len(given) != 1 else ' was'} given"
            + ("" if len(given) > dof else " (give a speed on more ports)"),
            missing=None if len(given) > dof else "speed")
    return given


#: Two ports on one rigid body give the same speed when they agree to this (relative).
SAME_SPEED_RTOL = 1e-9


def _port_speeds(model: Model) -> dict[str, float]:
    """The ports' own speeds, one per rigid body: ports on one body (an engine and a
    machine on one shaft) must give the same speed."""
    given: dict[str, float] = {}
    first: dict[str, object] = {}
    for port in model.ports:
        if port.speed is None:
            continue
        body = model.body_of[port.component]
        if body not in first:
            first[body] = port
            given[port.component] = port.speed
            continue
        other = first[body]
        if abs(port.speed - other.speed) > SAME_SPEED_RTOL * max(abs(port.speed),
                                                                 abs(other.speed)):
            raise KinematicsError(
                f"{model.port_label(other.index)} gives {other.speed:.6g} rad/s and "
                f"{model.port_label(port.index)} {port.speed:.6g} rad/s, but they are on one rigid "
                f"body {body!r}: give the speed once, or speeds that agree",
                f"{port.path}.speed")
    return given


def _underdetermined_message(model: Model, reduced: Triplets, unknown: np.ndarray,
                             given: Mapping) -> str:
    _, s, vt = np.linalg.svd(equilibrated(reduced.dense()))
    null = vt[int(np.sum(s > SVD_RTOL * max(1.0, s[0]))):] if s.size else vt
    free = [model.bodies[j].id for k, j in enumerate(unknown) if np.any(np.abs(null[:, k]) > 1e-9)]
    return ("the given speeds (" + ", ".join(given) + ") do not fix the motion; "
            "bodies still free to turn: " + ", ".join(free))


# --- given speeds the rows cannot meet: which rows, which ports -----------------------------
#: At most this many links are named in a conflict (then how many there are in all).
NAMED_LINKS = 8
#: Model warnings (docs/feasibility.md) that mean a link's row is not the train's.
WRONG_ROWS = ("ring-without-carrier", "planet-carrier", "ring-not-internal")


def contradiction_message(model: Model, elements: tuple[Element, ...], rows: Triplets,
                          rhs: np.ndarray, known: Mapping[int, float],
                          given: Mapping[str, float], reduced: Triplets,
                          square: tuple) -> str:
    """Why the given speeds (``known``: body column -> rad/s, the frame's 0 included) and
    the element ``rows`` (slips ``rhs``; ``reduced``, ``square``: the rows on the unknown
    speeds and their matched part, :func:`_reduced`) cannot all hold: the links of a
    conflicting set of rows (:func:`conflict`), what together they require of the given
    speeds, and the model's warnings that explain a wrong row (a ring without carrier...).

    Called only once a solve has failed (its cost is one more sparse factorisation).

    Examples
    --------
    >>> from powergraph.model import model_from_dict
    >>> m = model_from_dict({"name": "p", "components": {0: {"role": "frame"},
    ...     1: {"teeth": 20}, 2: {"teeth": 40}, 3: {}},
    ...     "links": [{"type": "mesh", "between": [1, 2]}],
    ...     "ports": [{"component": 1, "role": "input", "speed": 10},
    ...               {"component": 2, "role": "output", "speed": 3},
    ...               {"component": 3, "role": "output"}]})
    >>> try:
    ...     solve_speeds(m)
    ... except KinematicsError as err:
    ...     print(err)  # doctest: +NORMALIZE_WHITESPACE
    the given speeds contradict each other: links[0] (mesh 1-2, fixed axes) requires
    w_1 = -2·w_2 (= -6 rad/s), but ports[0] gives w_1 = 10 rad/s and ports[1] gives
    w_2 = 3 rad/s
    """
    fixed = np.zeros(len(model.bodies))
    fixed[list(known)] = list(known.values())
    y = conflict(reduced, rhs - rows.dot(fixed), square)
    head = "the given speeds contradict each other: "
    if y is None or not y.any():
        return head + ", ".join(f"{model.raw_id(c)} = {v:g} rad/s"
                                for c, v in given.items()) + " cannot all hold"
    support = np.flatnonzero(y)
    links = [model.links[elements[k].link] for k in support]
    named = [element_words(model, elements[k]) for k in support[:NAMED_LINKS]]
    if support.size > NAMED_LINKS:
        named[-1] = f"… ({support.size} links in all)"
    lead = "together " if support.size > 1 else ""
    want = _requirement(model, rows, rhs, y, known, given, lead)
    if want is None:
        slips = ", ".join(f"{link.path} {rhs[k]:.6g} rad/s"
                          for k, link in zip(support, links) if rhs[k])
        want = f"{lead}cannot take the slips given ({slips})"
    text = head + _and(named) + " " + want
    near = {link.path for link in links} | {f"components.{model.raw_id(x)}"
                                            for link in links for x in link.between}
    notes = [str(c) for c in model.warnings if c.code in WRONG_ROWS
             and (c.path or "").split(".carrier")[0] in near]
    return text + "".join(f" — warning: {note}" for note in notes[:2])


def _requirement(model: Model, rows: Triplets, rhs: np.ndarray, y: np.ndarray,
                 known: Mapping[int, float], given: Mapping[str, float],
                 lead: str) -> str | None:
    """What the rows weighted by ``y`` require of the given speeds (``Σ g_k w_k = y·s``
    over the given bodies, ``g = y · rows``, ``s`` the slips), and what the ports give;
    None when no given speed takes part (the slips alone conflict)."""
    n, terms = len(model.bodies), rows.values * y[rows.rows]
    g = np.bincount(rows.cols, weights=terms, minlength=n)
    mass = np.bincount(rows.cols, weights=np.abs(terms), minlength=n)
    index = {body.id: j for j, body in enumerate(model.bodies)}
    involved = [(c, index[model.body_of[c]]) for c in given]
    involved = [(c, j) for c, j in involved if abs(g[j]) > CONFLICT_RTOL * mass[j]]
    if not involved:
        return None
    slip, s = float(y @ rhs), "" if lead else "s"
    port = {p.component: p.path for p in reversed(model.ports)      # the ports' own speeds
            if p.speed is not None and p.speed == given.get(p.component)}
    (first, j0), rest = involved[0], involved[1:]
    required = (slip - sum(g[j] * known[j] for _, j in rest)) / g[j0]
    terms = [f"{-g[j] / g[j0]:.6g}·w_{model.raw_id(c)}" for c, j in rest]
    if slip:
        terms.append(f"{slip / g[j0]:.6g} rad/s")
    want = f"{lead}require{s} w_{model.raw_id(first)} = "
    if terms:
        want += " + ".join(terms).replace("+ -", "- ") + f" (= {required:.6g} rad/s)"
    else:
        want += f"{required + 0.0:.6g} rad/s"
    gives = [f"{port[c]} gives w_{model.raw_id(c)} = {given[c]:.6g} rad/s" if c in port
             else f"w_{model.raw_id(c)} = {given[c]:.6g} rad/s is given" for c, _ in involved]
    return f"{want}, but {_and(gives)}"


def _and(items: list[str]) -> str:
    return items[0] if len(items) == 1 else ", ".join(items[:-1]) + " and " + items[-1]
