"""Small dense linear systems solved many at once, scaled like the single solve.

:func:`solve_square_batch` is :func:`powergraph.linalg.solve_square`'s dense path over a
stack of systems (one per operating point or variant): each is re-solved with its columns
scaled by its own unknowns and its rows equilibrated until the scales settle, and its
regularity is decided on the scaled system, with the same constants. Base layer (numpy).
"""
from __future__ import annotations

import numpy as np

from powergraph.linalg import COND_LIMIT, MAX_PASSES, ROUND_OFF, SETTLED

__all__ = ["COND_LIMIT", "solve_square_batch"]


def solve_square_batch(a: np.ndarray, rhs: np.ndarray,
                       passes: int = 1) -> tuple[np.ndarray, np.ndarray]:
    """:func:`solve_square` over ``P`` small dense systems at once: ``a`` is ``(P, n, n)``,
    ``rhs`` ``(P, n)``. Each system is solved, then re-solved with its columns scaled by
    the magnitudes of its own unknowns and its rows equilibrated, until those magnitudes
    settle (the same scales as the single solve), so each unknown is accurate relative to
    itself. Returns the solutions (NaN rows where a system is exactly singular) and the
    condition numbers of the scaled systems (``COND_LIMIT`` or more: singular).

    Examples
    --------
    >>> n = 30     # the chain of solve_square's example, twice, the second scaled by 2
    >>> a = np.eye(n) - 5.0 * np.eye(n, k=-1)
    >>> x, cond = solve_square_batch(np.stack([a, 2 * a]), np.stack([np.eye(n)[0]] * 2))
    >>> bool(abs(x[0, -1] / 5.0 ** (n - 1) - 1) < 1e-13), float(x[1, 0]), bool(cond.max() < 1e3)
    (True, 0.5, True)
    """
    a, rhs = np.asarray(a, dtype=float), np.asarray(rhs, dtype=float)
    count, n = rhs.shape
    x = np.full((count, n), np.nan)
    condition = np.full(count, np.inf)
    if n == 0:
        return np.zeros((count, 0)), np.ones(count)
    magnitude, nonzero = np.abs(a), a != 0

    def scales(values: np.ndarray, idx: np.ndarray) -> np.ndarray:
        mag = magnitude[idx]
        terms = np.maximum((mag * np.abs(values)[:, None, :]).max(axis=2), np.abs(rhs[idx]))
        with np.errstate(divide="ignore", invalid="ignore"):
            implied = np.where(nonzero[idx] & (terms[:, :, None] > 0),
                               terms[:, :, None] / mag, np.inf).min(axis=1)
        d = np.abs(values)
        d = np.where((d < ROUND_OFF * implied) & np.isfinite(implied), implied, d)
        smallest = np.where(d > 0, d, np.inf).min(axis=1, keepdims=True)
        d = np.where(d > 0, d, smallest)
        return np.where(np.isfinite(d), d, 1.0)

    def scaled(d: np.ndarray, idx: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        m = a[idx] * d[:, None, :]
        r = np.abs(m).max(axis=2)
        r[r == 0] = 1.0
        m /= r[:, :, None]
        return d * _solve_each(m, rhs[idx] / r), m

    every = np.arange(count)
    first = _solve_each(a, rhs)
    active = np.all(np.isfinite(first), axis=1)
    d = np.ones((count, n))
    d[active] = scales(first[active], every[active])
    final = np.array(a)
    for k in range(MAX_PASSES):
        idx = np.flatnonzero(active)
        if idx.size == 0:
            break
        values, m = scaled(d[idx], idx)
        finite = np.all(np.isfinite(values), axis=1)
        x[idx], final[idx] = values, m
        following = np.ones_like(values)
        following[finite] = scales(values[finite], idx[finite])
        with np.errstate(divide="ignore", invalid="ignore"):
            settled = np.all(np.abs(np.log(following / d[idx])) < np.log(SETTLED), axis=1)
        d[idx] = following
        active[idx[~finite | (settled & (k + 1 >= passes))]] = False
    solved = np.all(np.isfinite(x), axis=1)
    if solved.any():
        condition[solved] = np.linalg.cond(final[solved])
    return x, condition


def _solve_each(a: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """Batched ``numpy.linalg.solve``; NaN rows for exactly singular systems."""
    try:
        return np.linalg.solve(a, rhs[..., None])[..., 0]
    except np.linalg.LinAlgError:
        out = np.full(rhs.shape, np.nan)
        for i in range(len(a)):
            try:
                out[i] = np.linalg.solve(a[i], rhs[i])
            except np.linalg.LinAlgError:
                pass
        return out


def structural_zeros(nonzero: np.ndarray, free_rows: np.ndarray) -> tuple[np.ndarray, ...]:
    """Unknowns that the structure of a system sets to exactly 0: a row with no right-hand
    side and a single unknown not yet known to be 0 (e.g. the balance of an unloaded gear
    that one element acts on: that element passes no force), repeated until none is left.
    Elimination would give them round-off instead of 0.

    Parameters
    ----------
    nonzero : (m, n) bool
        Where a coefficient may be nonzero (in any of the systems of a batch).
    free_rows : (m,) bool
        Rows whose right-hand side is 0 in every system.

    Returns
    -------
    (columns, rows)
        Boolean masks: the unknowns that are 0, and the rows that fix them (one each).

    >>> structural_zeros(np.array([[1, 1, 0], [1, 0, 0], [1, 1, 1]], bool),
    ...                  np.array([True, True, False]))
    (array([ True,  True, False]), array([ True,  True, False]))
    """
    m, n = nonzero.shape
    zero, used = np.zeros(n, dtype=bool), np.zeros(m, dtype=bool)
    changed = True
    while changed:
        changed = False
        for i in np.flatnonzero(free_rows & ~used):
            columns = np.flatnonzero(nonzero[i] & ~zero)
            if columns.size == 1:
                zero[columns[0]] = used[i] = changed = True
    return zero, used
