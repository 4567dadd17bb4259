"""The linear algebra of the kinematics and the statics: sparse triplets, solved scaled.

A base-layer module (numpy; scipy.sparse only for large systems), so every layer uses it.

Both systems are built from :func:`powergraph.kinematics.elements.element_stencil` as
``(row, column, value)`` triplets (:class:`Triplets`). Small systems are solved with dense
numpy; from ``SPARSE_FROM`` unknowns on, with ``scipy.sparse`` (imported only then, so a
small solve never loads scipy). ``PATH`` forces one of the two ("dense" or "sparse"), for
tests that check both agree.

**Scaling.** A long train's unknowns span many decades (speeds of 20 planetary stages in
series differ by 5^20, torques of a chain at efficiency 1e-6 per mesh by 1e-6 per gear),
while each row only relates neighbours. :func:`solve_square` therefore solves, then
re-solves with every column scaled by the magnitude of its unknown and every row by its
largest scaled entry (equilibration) until those magnitudes settle, so each unknown comes
out accurate relative to itself; a small dense system whose unknowns lie within
``WELL_SCALED`` of each other is already accurate after the first (row-equilibrated) solve
and stops there.
Whether the system is regular is decided on that scaled system (its condition number,
estimated in linear time on the sparse path): diagonal scaling cannot hide a real
singularity, since entrywise relative round-off is the same in every scaling.

**Rank.** :func:`rank` takes the structural rank (a maximum matching of rows to columns,
an upper bound of the rank) and confirms it numerically on the matched square part, solved
scaled; only when that part is numerically singular (redundant loops with consistent
ratios) does it fall back to the singular values of the equilibrated dense matrix.

The scaled solve is written once (:func:`solve_square`, :func:`column_scales`); the two
paths differ only in how they store the matrix and factor it (``_Dense``, ``_Sparse``): a
dense array, solved by ``numpy.linalg.solve``, its condition number bounded from the
1-norm one (:func:`dense_condition`), or triplets, factored by
``scipy.sparse.linalg.splu``, the condition number estimated (Hager). Only numpy's public
API is used.
"""
from __future__ import annotations

from typing import Callable, NamedTuple

import numpy as np

#: A scaled system whose condition number reaches this is singular.
COND_LIMIT = 1e12
#: Scaled re-solves of a square system, at most.
MAX_PASSES = 12
#: The scales have settled when no unknown's magnitude changes by this factor.
SETTLED = 8.0
#: An unknown smaller than this fraction of its row's other terms is scaled like them.
ROUND_OFF = 1e-8
#: A dense system whose unknowns span at most this factor is solved once (rows equilibrated).
WELL_SCALED = 1e3

#: Systems with at least this many unknowns are solved with scipy.sparse.
SPARSE_FROM = 100
#: None: choose by size; "dense" or "sparse": force that path (tests).
PATH: str | None = None
#: Relative threshold of the singular values in the dense fallback.
SVD_RTOL = 1e-10


def use_sparse(n_unknown: int) -> bool:
    """Whether a system of ``n_unknown`` unknowns takes the sparse path.

    >>> use_sparse(10), use_sparse(10_000)
    (False, True)
    """
    if PATH is not None:
        return PATH == "sparse"
    return n_unknown >= SPARSE_FROM


class Triplets(NamedTuple):
    """A matrix as ``(row, column, value)`` triplets, duplicates summed, exact zeros
    dropped (so the structure is the structure of the physics).

    >>> t = Triplets.build([0, 0, 1], [0, 0, 1], [1.0, 2.0, 0.0], (2, 2))
    >>> t.dense()
    array([[3., 0.],
           [0., 0.]])
    """

    rows: np.ndarray
    cols: np.ndarray
    values: np.ndarray
    shape: tuple[int, int]

    @classmethod
    def build(cls, rows, cols, values, shape: tuple[int, int]) -> "Triplets":
        rows, cols = np.asarray(rows, dtype=np.int64), np.asarray(cols, dtype=np.int64)
        values = np.asarray(values, dtype=float)
        key = rows * max(shape[1], 1) + cols
        unique, inverse = unique_inverse(key)
        summed = np.bincount(inverse, weights=values, minlength=len(unique))
        keep = summed != 0.0
        unique = unique[keep]
        return cls(unique // max(shape[1], 1), unique % max(shape[1], 1), summed[keep],
                   (int(shape[0]), int(shape[1])))

    def dense(self) -> np.ndarray:
        out = np.zeros(self.shape)
        out[self.rows, self.cols] = self.values
        return out

    def csc(self):
        from scipy.sparse import csc_matrix

        return csc_matrix((self.values, (self.rows, self.cols)), shape=self.shape)

    def dot(self, x: np.ndarray) -> np.ndarray:
        """``A @ x`` in linear time."""
        return np.bincount(self.rows, weights=self.values * x[self.cols],
                           minlength=self.shape[0])

    def row_terms(self, x: np.ndarray) -> np.ndarray:
        """Per row, the largest ``|A_ij x_j|``: the size of the terms the row balances."""
        out = np.zeros(self.shape[0])
        np.maximum.at(out, self.rows, np.abs(self.values * x[self.cols]))
        return out

    def part(self, rows: np.ndarray, cols: np.ndarray) -> "Triplets":
        """The submatrix of the given rows and columns, renumbered in their order."""
        row_map = np.full(self.shape[0], -1)
        row_map[rows] = np.arange(len(rows))
        col_map = np.full(self.shape[1], -1)
        col_map[cols] = np.arange(len(cols))
        r, c = row_map[self.rows], col_map[self.cols]
        keep = (r >= 0) & (c >= 0)
        return Triplets(r[keep], c[keep], self.values[keep], (len(rows), len(cols)))

    def scaled(self, row_scale: np.ndarray, col_scale: np.ndarray) -> "Triplets":
        """``diag(1/row_scale) A diag(col_scale)``."""
        return Triplets(self.rows, self.cols,
                        self.values * col_scale[self.cols] / row_scale[self.rows], self.shape)


class Solved(NamedTuple):
    """A square system's solution and the condition number of its scaled system (on the
    dense path a bound of it on the same side of :data:`COND_LIMIT`, :func:`dense_condition`;
    on the sparse path an estimate); NaN and an infinite condition when the solve failed."""

    x: np.ndarray
    condition: float

    @property
    def regular(self) -> bool:
        return self.condition < COND_LIMIT     # (a failed solve: NaN, infinite condition)


def solve_square(t: Triplets, rhs: np.ndarray, guess: np.ndarray | None = None,
                 passes: int = 1) -> Solved:
    """Solve a square system, re-solved at least ``passes`` times scaled by its own
    solution, until the scales settle (each pass gains about 15 decades of relative
    accuracy on an unknown the previous scaling misjudged; at most ``MAX_PASSES``).

    ``guess`` (optional) is the expected magnitude of each unknown (0 where unknown): the
    first solve is then already scaled by it, which a system whose unknowns span hundreds
    of decades needs (unscaled elimination would absorb the small terms in the large ones).

    The first solve has its rows equilibrated too. A dense system whose unknowns come out
    within ``WELL_SCALED`` of each other (and that asks for one pass) stops there: partial
    pivoting on it is already as accurate as further scaled passes would be (pivoting does
    not depend on the columns' scales, and the rows' scales move by at most that factor);
    only the condition number of its scaled system is still taken.

    Examples
    --------
    >>> n = 30     # w_k - 5 w_(k+1) = 0 transposed: each unknown 5 times the one before
    >>> t = Triplets.build(list(range(n)) + list(range(1, n)),
    ...                    list(range(n)) + list(range(n - 1)), [1.0] * n + [-5.0] * (n - 1),
    ...                    (n, n))
    >>> s = solve_square(t, np.eye(n)[0])
    >>> s.regular, bool(abs(s.x[-1] / 5.0 ** (n - 1) - 1) < 1e-13)
    (True, True)
    """
    n = t.shape[0]
    if n == 0:
        return Solved(np.zeros(0), 1.0)
    system = _Sparse(t) if use_sparse(n) else _Dense(t)
    rhs = np.asarray(rhs, dtype=float)
    size = np.abs(rhs)
    d = np.ones(n) if guess is None else column_scales(system, np.abs(guess), size)
    x, condition = _scaled_solve(system, rhs, d)
    if x is None:
        return Solved(np.full(n, np.nan), np.inf)
    d = column_scales(system, x, size)
    if passes <= 1 and isinstance(system, _Dense) and d.max() <= WELL_SCALED * d.min():
        return Solved(x, dense_condition(system.equilibrated(d)[0]))
    for k in range(MAX_PASSES):
        x, condition = _scaled_solve(system, rhs, d)
        if x is None:
            return Solved(np.full(n, np.nan), np.inf)
        following = column_scales(system, x, size)
        if k + 1 >= passes and (np.abs(np.log(following / d)) < np.log(SETTLED)).all():
            break
        d = following
    return Solved(x, condition())


class _Dense:
    """A small system as a dense matrix: :func:`solve_square`'s operations on it."""

    def __init__(self, t: Triplets) -> None:
        self.a = t.dense()
        self.magnitude = np.abs(self.a)
        self.largest = self.magnitude.max(axis=0)       # per column

    def row_terms(self, d: np.ndarray) -> np.ndarray:
        """Per row, the largest ``|A_ij| d_j`` (``d >= 0``)."""
        return (self.magnitude * d).max(axis=1)

    def implied(self, terms: np.ndarray) -> np.ndarray:
        """Per column, the smallest over its rows of ``terms_i / |A_ij|`` (rows with a
        coefficient there and terms > 0; inf where none)."""
        reciprocal = np.divide(1.0, self.magnitude, out=np.full(self.a.shape, np.inf),
                               where=self.magnitude > 0)
        return (np.where(terms > 0, terms, np.inf)[:, None] * reciprocal).min(axis=0)

    def equilibrated(self, d: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``diag(1/r) A diag(d)`` with ``r`` each row's largest ``|A_ij| d_j`` (1 for an
        empty row), and ``r``."""
        m = self.a * d
        r = np.abs(m).max(axis=1)
        if not r.all():
            r[r == 0] = 1.0
        m /= r[:, None]
        return m, r

    def factor_solve(self, m: np.ndarray,
                     rhs: np.ndarray) -> tuple[np.ndarray | None, Callable[[], float]]:
        try:
            x = np.linalg.solve(m, rhs)
        except np.linalg.LinAlgError:
            return None, _infinite
        return x, lambda: dense_condition(m)


class _Sparse:
    """A large system as triplets: :func:`solve_square`'s operations on it."""

    def __init__(self, t: Triplets) -> None:
        self.t = t
        self.magnitude = np.abs(t.values)
        self.largest = np.zeros(t.shape[1])              # per column
        np.maximum.at(self.largest, t.cols, self.magnitude)

    def row_terms(self, d: np.ndarray) -> np.ndarray:
        return self.t.row_terms(d)

    def implied(self, terms: np.ndarray) -> np.ndarray:
        t = self.t
        out = np.full(t.shape[1], np.inf)
        np.minimum.at(out, t.cols, np.where(terms > 0, terms, np.inf)[t.rows] / self.magnitude)
        return out

    def equilibrated(self, d: np.ndarray) -> tuple[Triplets, np.ndarray]:
        r = self.t.row_terms(d)
        if not r.all():
            r[r == 0] = 1.0
        return self.t.scaled(r, d), r

    def factor_solve(self, m: Triplets,
                     rhs: np.ndarray) -> tuple[np.ndarray | None, Callable[[], float]]:
        from scipy.sparse.linalg import splu

        try:
            lu = splu(m.csc())
        except RuntimeError:  # exactly singular
            return None, _infinite

        def condition() -> float:
            norm = float(np.bincount(m.cols, weights=np.abs(m.values),
                                     minlength=m.shape[1]).max())
            return norm * _inverse_norm1(lu.solve, lambda b: lu.solve(b, trans="T"),
                                         m.shape[0])

        return lu.solve(rhs), condition


def _scaled_solve(system: _Dense | _Sparse, rhs: np.ndarray,
                  d: np.ndarray) -> tuple[np.ndarray | None, Callable[[], float]]:
    """Solve with the columns scaled by ``d`` and each row by its largest entry; None when
    the factorisation finds it exactly singular or the solution is not finite."""
    m, r = system.equilibrated(d)
    y, condition = system.factor_solve(m, rhs / r)
    if y is None or not np.isfinite(y).all():
        return None, _infinite
    return d * y, condition


def column_scales(system: _Dense | _Sparse, x: np.ndarray, size: np.ndarray) -> np.ndarray:
    """The magnitude of each unknown, or, where it is round-off (below ``ROUND_OFF`` of the
    other terms in each of its rows, the right-hand side's ``size`` included) or zero, the
    magnitude its rows give it."""
    d = np.abs(x)
    terms = np.maximum(system.row_terms(d), size)
    # Every implied magnitude is at most (largest row terms) / (the column's largest
    # coefficient): unknowns above ROUND_OFF of that bound are neither round-off nor zero.
    low = (d * system.largest).min()
    if low > 0 and low >= ROUND_OFF * terms.max():
        return d
    implied = system.implied(terms)
    small = d < ROUND_OFF * implied
    if small.any():
        d = np.where(small & np.isfinite(implied), implied, d)
    if d.min() > 0:
        return d
    positive = d > 0
    if not positive.any():
        return np.ones_like(d)
    return np.where(positive, d, d[positive].min())


def dense_condition(matrix: np.ndarray) -> float:
    """The 2-norm condition number of a square matrix as far as :data:`COND_LIMIT` needs
    it: from the 1-norm one (one inverse) when that decides (``κ1/n <= κ2 <= n·κ1``),
    else exact (the singular values).

    >>> dense_condition(np.eye(3)) < COND_LIMIT, dense_condition(np.ones((3, 3))) < COND_LIMIT
    (True, False)
    """
    n = len(matrix)
    try:
        inverse = np.linalg.inv(matrix)
    except np.linalg.LinAlgError:
        return np.inf
    k1 = float(np.abs(matrix).sum(axis=0).max() * np.abs(inverse).sum(axis=0).max())
    if n * k1 < COND_LIMIT:
        return n * k1
    if k1 > n * COND_LIMIT:
        return k1 / n
    return float(np.linalg.cond(matrix))


def _infinite() -> float:
    return np.inf


def _inverse_norm1(solve, solve_transposed, n: int) -> float:
    """Estimate of ``||A^-1||_1`` from a few solves (Hager 1984, "Condition estimates";
    Higham 1988, "FORTRAN codes for estimating the one-norm", with his extra vector)."""
    x = np.full(n, 1.0 / n)
    estimate = 0.0
    for _ in range(5):
        y = solve(x)
        value = float(np.abs(y).sum())
        if not np.isfinite(value):
            return np.inf
        if value <= estimate:
            break
        estimate = value
        z = solve_transposed(np.where(y >= 0, 1.0, -1.0))
        j = int(np.argmax(np.abs(z)))
        if abs(z[j]) <= z @ x:
            break
        x = np.zeros(n)
        x[j] = 1.0
    alternating = (-1.0) ** np.arange(n) * (1.0 + np.arange(n) / max(n - 1, 1))
    extra = 2.0 * float(np.abs(solve(alternating)).sum()) / (3.0 * n)
    return max(estimate, extra)


def matching(t: Triplets) -> np.ndarray:
    """A maximum matching of rows to columns: the matched column of each row, -1 if none.

    >>> t = Triplets.build([0, 0, 1], [0, 1, 0], [1.0, 1.0, 1.0], (2, 2))
    >>> matching(t).tolist()
    [1, 0]
    """
    if use_sparse(t.shape[1]):
        from scipy.sparse.csgraph import maximum_bipartite_matching

        return np.asarray(maximum_bipartite_matching(t.csc().tocsr(), perm_type="column"))
    return _augmenting_paths(t)


def _augmenting_paths(t: Triplets) -> np.ndarray:
    """A greedy matching completed by Kuhn's augmenting paths (small systems)."""
    adjacency: list[list[int]] = [[] for _ in range(t.shape[0])]
    for r, c in zip(t.rows.tolist(), t.cols.tolist()):
        adjacency[r].append(c)
    row_of = [-1] * t.shape[1]
    degree = np.bincount(t.cols, minlength=t.shape[1]).tolist()
    unmatched = []
    for row in sorted(range(t.shape[0]), key=lambda r: len(adjacency[r])):
        # greedy first: the free column with the fewest entries
        free = [c for c in adjacency[row] if row_of[c] < 0]
        if free:
            row_of[min(free, key=degree.__getitem__)] = row
        else:
            unmatched.append(row)
    for start in unmatched:
        seen: set[int] = set()
        # iterative depth-first search for an augmenting path from row ``start``
        stack = [(start, iter(adjacency[start]))]
        path: list[tuple[int, int]] = []
        while stack:
            row, cols = stack[-1]
            col = next((c for c in cols if c not in seen), None)
            if col is None:
                stack.pop()
                if path:
                    path.pop()
                continue
            seen.add(col)
            path.append((row, col))
            if row_of[col] < 0:
                for r, c in path:
                    row_of[c] = r
                break
            stack.append((row_of[col], iter(adjacency[row_of[col]])))
    col_of = np.full(t.shape[0], -1)
    for c, r in enumerate(row_of):
        if r >= 0:
            col_of[r] = c
    return col_of


def rank(t: Triplets) -> int:
    """Rank: structural, confirmed on the scaled matched part; else by singular values.

    >>> rank(Triplets.build([0, 1, 2], [0, 1, 1], [1.0, 2.0, 4.0], (3, 2)))
    2
    """
    col_of = matching(t)
    rows = np.flatnonzero(col_of >= 0)
    if rows.size == 0:
        return 0
    cols = col_of[rows]
    free = others(t.shape[1], cols)
    ones = np.zeros(t.shape[1])
    ones[free] = 1.0
    rhs = -t.dot(ones)[rows]
    square = t.part(rows, cols)
    if not np.any(rhs):
        rhs = square.row_terms(np.ones(len(cols)))
    if solve_square(square, rhs).regular:
        return int(rows.size)
    return svd_rank(t)


def unique_inverse(key: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``np.unique(key, return_inverse=True)`` of a 1-D integer array, by one sort
    (``np.unique`` imports ``numpy.ma`` on its first call: 10 ms of every start-up).

    >>> [a.tolist() for a in unique_inverse(np.array([5, 2, 5, 7]))]
    [[2, 5, 7], [1, 0, 1, 2]]
    """
    key = np.asarray(key).ravel()
    order = np.argsort(key)
    ordered = key[order]
    first = np.ones(ordered.size, dtype=bool)
    first[1:] = ordered[1:] != ordered[:-1]
    inverse = np.empty(key.size, dtype=np.int64)
    inverse[order] = np.cumsum(first) - 1
    return ordered[first], inverse


def others(n: int, taken) -> np.ndarray:
    """The indices ``0..n-1`` not in ``taken``, in order (``np.setdiff1d(np.arange(n),
    taken)`` without its sorting and set machinery).

    >>> others(5, [3, 0]).tolist()
    [1, 2, 4]
    """
    free = np.ones(n, dtype=bool)
    free[np.asarray(taken, dtype=np.int64)] = False
    return np.flatnonzero(free)


def svd_rank(t: Triplets) -> int:
    """Numerical rank of the row- and column-equilibrated matrix (dense)."""
    s = np.linalg.svd(equilibrated(t.dense()), compute_uv=False)
    return int(np.sum(s > SVD_RTOL * max(1.0, s[0]))) if s.size else 0


def equilibrated(matrix: np.ndarray) -> np.ndarray:
    """Rows, then columns, divided by their largest magnitude (zero ones left alone)."""
    rows = np.abs(matrix).max(axis=1, initial=0.0)
    matrix = matrix / np.where(rows > 0, rows, 1.0)[:, None]
    cols = np.abs(matrix).max(axis=0, initial=0.0)
    return matrix / np.where(cols > 0, cols, 1.0)

