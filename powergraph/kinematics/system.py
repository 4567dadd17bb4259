"""The train as linear systems: body rows, an element table and the unknown external
torques, from which every evaluator builds its Willis rows and its torque balance.

The coefficients are the element's stencil (:func:`~powergraph.kinematics.elements.
element_stencil`); where they go is fixed by the train's structure alone:

- **Willis rows** (one per element; columns: bodies): ``stencil(i) · (w_a, w_b, w_c) = 0``;
- **torque balance** (one row per body; columns: the element forces ``λ``, then the
  unknown external torques): element ``k``'s column is ``stencil(i_k, f_k)`` on its gear
  a, gear b and carrier, and each unknown torque has a 1 on its own body.

:class:`TrainSystem` places them, for one operating point (floats), many (arrays whose
last axis runs over the points) or symbols (numpy object arrays of sympy expressions):
as triplets (the single solve's sparse and small dense systems, the symbolic
derivation) or as dense stacks ``(points, rows, columns)`` (the batched evaluators: the
complementarity search, the efficiency grid, the sweep's numeric backend).

When given speeds cannot meet the Willis rows, :func:`conflict` finds an irreducible set
of rows that cannot all hold (a left null vector of the rows not orthogonal to their
right-hand side) and :func:`element_words` names their links, for the error message of
:func:`powergraph.kinematics.speeds.solve_speeds`.
"""
from __future__ import annotations

from typing import Mapping, Sequence

import numpy as np

from powergraph.kinematics.elements import ELEMENT_BODIES, Element, element_stencil
from powergraph.linalg import Triplets, matching, solve_square
from powergraph.model.spec import Model


class TrainSystem:
    """A train's structure as indices: ``places[k]`` holds the rows (bodies) of element
    ``k``'s gear a, gear b and carrier; ``unknown`` the rows of the bodies whose external
    torque the balance solves for (a column each, after the forces).

    Examples
    --------
    A pair on the frame (bodies 0 = frame, 1, 2; ratio -2), its output and frame
    torques unknown:

    >>> system = TrainSystem(3, [[1, 2, 0]], [2, 0])
    >>> system.willis(np.array([-2.0])).tolist()
    [[-3.0, 1.0, 2.0]]
    >>> system.balance(np.array([-2.0]), np.array([0.5])).tolist()
    [[-2.0, 0.0, 1.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0]]
    """

    __slots__ = ("n_bodies", "places", "unknown")

    def __init__(self, n_bodies: int, places, unknown=()) -> None:
        self.n_bodies = int(n_bodies)
        self.places = np.asarray(places, dtype=np.int64).reshape(-1, 3)
        self.unknown = np.asarray(unknown, dtype=np.int64).reshape(-1)

    @property
    def n_elements(self) -> int:
        return len(self.places)

    @property
    def n_columns(self) -> int:
        """Columns of the torque balance: the forces, then the unknown torques."""
        return self.n_elements + len(self.unknown)

    def willis_triplets(self, ratios) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(rows, columns, values)`` of the Willis rows (rows: elements; columns: bodies).

        ``ratios``: ``(E,)`` or ``(E, P)``, floats or sympy objects; ``values`` has the
        ratios' trailing shape after its first axis."""
        n_el = self.n_elements
        rows = np.tile(np.arange(n_el), 3)
        return rows, self.places.T.reshape(-1), _stacked(element_stencil(_array(ratios)))

    def balance_triplets(self, ratios, factors=1.0) -> tuple[np.ndarray, np.ndarray,
                                                                np.ndarray]:
        """``(rows, columns, values)`` of the torque balance (rows: bodies; columns: the
        element forces, then the unknown torques), for factors ``f`` per element (1: the
        ideal balance)."""
        n_el, n_unknown = self.n_elements, len(self.unknown)
        ratios = _array(ratios)
        stencil = _stacked(element_stencil(ratios, _array(factors)))
        ones = np.ones((n_unknown,) + stencil.shape[1:], dtype=stencil.dtype)
        k = np.arange(n_el)
        rows = np.concatenate([self.places.T.reshape(-1), self.unknown])
        cols = np.concatenate([k, k, k, n_el + np.arange(n_unknown)])
        return rows, cols, np.concatenate([stencil, ones])

    def willis(self, ratios) -> np.ndarray:
        """The Willis rows as a dense ``(E, B)`` matrix, or ``(P, E, B)`` for ``(E, P)``
        ratios."""
        return _dense(*self.willis_triplets(ratios), (self.n_elements, self.n_bodies))

    def balance(self, ratios, factors=1.0) -> np.ndarray:
        """The torque balance as a dense ``(B, E + U)`` matrix, or ``(P, B, E + U)``."""
        return _dense(*self.balance_triplets(ratios, factors),
                      (self.n_bodies, self.n_columns))

    def element_column(self, k: int, ratio, factor=1.0) -> np.ndarray:
        """Element ``k``'s torques on every body per unit force, ``(..., B)`` for a factor
        of any shape (its static column of the balance)."""
        factor = np.asarray(factor, dtype=float)
        out = np.zeros(factor.shape + (self.n_bodies,))
        for body, c in zip(self.places[k].tolist(), element_stencil(ratio, factor)):
            out[..., body] += c
        return out


def system_of(bodies: Sequence[str], elements: Sequence[Element],
              unknown: Sequence[str] = ()) -> TrainSystem:
    """The :class:`TrainSystem` of ``elements`` over the body ids ``bodies`` (rows in that
    order), with the external torques of the bodies ``unknown`` solved for.

    >>> e = Element(0, "mesh", "1", "2", "0", "1", "2", "0", -2.0, 0.9)
    >>> system_of(["0", "1", "2"], [e], ["2", "0"]).places.tolist()
    [[1, 2, 0]]
    """
    row: Mapping[str, int] = {body: r for r, body in enumerate(bodies)}
    places = [[row[b] for b in ELEMENT_BODIES(e)] for e in elements]
    return TrainSystem(len(row), places, [row[b] for b in unknown])


def _array(values) -> np.ndarray:
    """Numbers as a float array; sympy expressions as an object array (kept exact)."""
    array = np.asarray(values)
    return array if array.dtype == object else array.astype(float)


def _stacked(stencil: tuple) -> np.ndarray:
    """The three coefficient arrays of a stencil one after the other (gear a's constant
    broadcast to the others' shape)."""
    on_a, on_b, on_c = stencil
    on_a = np.broadcast_to(np.asarray(on_a, dtype=np.asarray(on_b).dtype), np.shape(on_b))
    return np.concatenate([on_a, on_b, on_c])


def _dense(rows: np.ndarray, cols: np.ndarray, values: np.ndarray,
           shape: tuple[int, int]) -> np.ndarray:
    """Triplets (values ``(N,)`` or ``(N, P)``) as a dense matrix, or a stack of ``P``;
    repeated places add up."""
    out = np.zeros(values.shape[1:] + shape, dtype=values.dtype)
    for r, c, v in zip(rows.tolist(), cols.tolist(), values):
        out[..., r, c] += v
    return out


# --- rows that cannot all hold -----------------------------------------------------------
#: A row (or port) whose share of a conflict is below this fraction of the largest is none.
CONFLICT_RTOL = 1e-9
#: Without regular matched rows, systems up to this many rows are diagnosed densely.
DENSE_DIAGNOSIS_UP_TO = 400


def conflict(reduced: Triplets, b: np.ndarray, square: tuple) -> np.ndarray | None:
    """Weights ``y`` of the rows of ``reduced · x = b`` with ``y · reduced = 0`` and
    ``y · b ≠ 0``: the rows with a weight cannot all hold, whatever the unknowns (zero
    weights are exact zeros). None when no such weights are found.

    With the matched rows (``square``: :func:`matched_square`) regular, a violated unmatched
    row ``r`` minus its expansion in the matched rows, which is unique: no row of it can
    be dropped (an irreducible conflict), in the time of one sparse factorisation. Else
    (redundant loops) the part of ``b`` outside the range of ``reduced`` (least squares),
    cut down to an irreducible set row by row: small systems only.

    Examples
    --------
    >>> t = Triplets.build([0, 1], [0, 0], [1.0, 1.0], (2, 1))   # x = 1 and x = 3
    >>> conflict(t, np.array([1.0, 3.0]), matched_square(t)).tolist()
    [-1.0, 1.0]
    """
    matched, columns, part = square
    x = np.zeros(reduced.shape[1])
    solved = solve_square(part, b[matched]) if matched.size else None
    if solved is None or solved.regular:
        if solved is not None:
            x[columns] = solved.x
        residual = reduced.dot(x) - b
        terms = np.maximum(reduced.row_terms(x), np.abs(b))
        off = np.abs(residual) / np.where(terms > 0, terms, 1.0)
        off[matched] = 0.0
        r = int(np.argmax(off)) if off.size else 0
        if off.size and off[r] > CONFLICT_RTOL:
            y = np.zeros(reduced.shape[0])
            y[r] = 1.0
            if matched.size:
                a_r = reduced.part(np.array([r]), columns).dense()[0]
                z = solve_square(Triplets(part.cols, part.rows, part.values, part.shape), a_r)
                if not z.regular:
                    return _dense_conflict(reduced, b)
                y[matched] = -z.x
            return _significant(reduced, y, r)
    return _dense_conflict(reduced, b)


def matched_square(t: Triplets) -> tuple[np.ndarray, np.ndarray, Triplets]:
    """``(matched rows, their columns, that square part)`` of ``t``: a maximum matching of
    rows to columns (:func:`powergraph.linalg.matching`)."""
    col_of = matching(t)
    matched = np.flatnonzero(col_of >= 0)
    return matched, col_of[matched], t.part(matched, col_of[matched])


def _significant(reduced: Triplets, y: np.ndarray, r: int) -> np.ndarray:
    """``y`` without the weights that are round-off: the rows reached from row ``r``
    through the unknowns they share, a row entering through an unknown only when its
    term ``y_i a_ij`` there is not round-off beside the largest (each unknown's terms
    cancel, so a genuine row is never small beside them; a scale-free test, so a train
    whose speeds span many decades keeps its small rows)."""
    term = np.abs(y[reduced.rows] * reduced.values)
    largest = np.zeros(reduced.shape[1])
    np.maximum.at(largest, reduced.cols, term)
    strong = term > CONFLICT_RTOL * largest[reduced.cols]
    by_row: list[list[int]] = [[] for _ in range(reduced.shape[0])]
    by_col: list[list[int]] = [[] for _ in range(reduced.shape[1])]
    for row, col, keep in zip(reduced.rows.tolist(), reduced.cols.tolist(), strong.tolist()):
        by_row[row].append(col)
        if keep:
            by_col[col].append(row)
    reached, seen, queue = {r}, set(), [r]
    while queue:
        for col in by_row[queue.pop()]:
            if col not in seen:
                seen.add(col)
                fresh = [row for row in by_col[col] if row not in reached]
                reached.update(fresh)
                queue.extend(fresh)
    out = np.zeros_like(y)
    out[list(reached)] = y[list(reached)]
    return out


def _dense_conflict(reduced: Triplets, b: np.ndarray) -> np.ndarray | None:
    """:func:`conflict` by least squares, for a system of a few hundred rows at most."""
    if reduced.shape[0] > DENSE_DIAGNOSIS_UP_TO:
        return None
    matrix = reduced.dense()

    def residual(keep: list[int]) -> np.ndarray:
        part = matrix[keep]
        x = np.linalg.lstsq(part, b[keep], rcond=None)[0]
        terms = np.maximum(np.abs(part * x).max(axis=1, initial=0.0), np.abs(b[keep]))
        out = b[keep] - part @ x
        return np.where(np.abs(out) > CONFLICT_RTOL * np.where(terms > 0, terms, 1.0),
                        out, 0.0)

    keep = [int(k) for k in np.flatnonzero(residual(list(range(matrix.shape[0]))))]
    if not keep:
        return None
    for k in list(keep):                   # drop every row the conflict does without
        trial = [i for i in keep if i != k]
        if trial and np.any(residual(trial)):
            keep = trial
    y = np.zeros(matrix.shape[0])
    y[keep] = residual(keep)
    return y


def element_words(model: Model, element: Element) -> str:
    """``links[3] (mesh s-p, carrier c)``, with the link's name when it has one."""
    link = model.links[element.link]
    a, b = (model.raw_id(x) for x in link.between)
    named = f"{link.name}, " if link.name else ""
    if element.kind != "mesh":
        return f"{link.path} ({named}{element.kind} {a}-{b})"
    where = "fixed axes" if link.carrier == model.frame else \
        f"carrier {model.raw_id(link.carrier)}"
    return f"{link.path} ({named}mesh {a}-{b}, {where})"
