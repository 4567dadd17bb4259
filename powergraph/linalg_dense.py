"""Small dense square systems, solved scaled without numpy's per-call overhead.

The dense path of :func:`powergraph.linalg.solve_square` (which re-exports what is
here): a gear train's systems are small (the RV-40E's torque balance has 8 unknowns), so a
single solve's time is per-call overhead, not arithmetic. The LAPACK kernels behind
``np.linalg.solve`` and ``np.linalg.inv`` are called directly (the same calls, so the same
digits), and the regularity test uses a condition bound from one inverse
(:func:`dense_condition`), the singular values only when that bound is not decisive.

The smallest systems (up to :data:`PLAIN_UP_TO` unknowns: a reducer's are 3×3) take the
same steps on plain Python floats (:func:`solve_plain`): each numpy call costs a
microsecond or more whatever its size, and the first LAPACK call of a process another
millisecond or two. Gaussian elimination with partial pivoting is the algorithm of
LAPACK's ``getrf``/``getrs``, so the two paths agree to rounding.
"""
from __future__ import annotations

import math

from typing import NamedTuple

import numpy as np

#: A scaled system whose condition number reaches this is singular.
COND_LIMIT = 1e12
#: Scaled re-solves of a square system, at most.
MAX_PASSES = 12
#: The scales have settled when no unknown's magnitude changes by this factor.
SETTLED = 8.0
#: An unknown smaller than this fraction of its row's other terms is scaled like them.
ROUND_OFF = 1e-8
#: A small dense system whose unknowns span at most this factor is solved once, unscaled.
WELL_SCALED = 1e3
#: Systems of up to this many unknowns are solved in plain Python floats (:func:`solve_plain`).
PLAIN_UP_TO = 6

try:  # numpy's own kernels behind np.linalg.solve/inv, without their per-call checks
    from numpy.linalg import _umath_linalg as _kernels

    _SOLVE1, _INV = _kernels.solve1, _kernels.inv
except (ImportError, AttributeError):  # pragma: no cover - another numpy layout
    _SOLVE1 = _INV = None


def _solve_small(matrix: np.ndarray, rhs: np.ndarray) -> np.ndarray | None:
    """``np.linalg.solve(matrix, rhs)`` for a small float system (the same LAPACK call,
    so the same numbers), without its per-call overhead; None when it is exactly
    singular or the solution is not finite."""
    if _SOLVE1 is None:  # pragma: no cover
        try:
            x = np.linalg.solve(matrix, rhs)
        except np.linalg.LinAlgError:
            return None
    else:
        with np.errstate(all="ignore"):
            x = _SOLVE1(matrix, rhs)
    return x if np.isfinite(x).all() else None


def dense_condition(matrix: np.ndarray) -> float:
    """The 2-norm condition number of a small square matrix as far as
    :data:`COND_LIMIT` needs it: exact (``np.linalg.cond``) when it is near the limit,
    else a cheap bound from the 1-norm one (``κ1/n <= κ2 <= n·κ1``) on the same side.

    >>> dense_condition(np.eye(3)) < COND_LIMIT, dense_condition(np.ones((3, 3))) < COND_LIMIT
    (True, False)
    """
    n = len(matrix)
    if _INV is not None and n:
        with np.errstate(all="ignore"):
            inverse = _INV(matrix)
        if np.isfinite(inverse).all():
            k1 = float(np.abs(matrix).sum(axis=0).max() * np.abs(inverse).sum(axis=0).max())
            if n * k1 < COND_LIMIT:
                return n * k1
            if k1 > n * COND_LIMIT:
                return k1 / n
    return float(np.linalg.cond(matrix))



class Solved(NamedTuple):
    """A square system's solution and the condition number of its scaled system (for a
    small dense system, a bound of it on the same side of :data:`COND_LIMIT`:
    :func:`dense_condition`)."""

    x: np.ndarray
    condition: float

    @property
    def regular(self) -> bool:
        return bool(np.all(np.isfinite(self.x))) and self.condition < COND_LIMIT



def solve_dense_square(a: np.ndarray, rhs: np.ndarray, guess: np.ndarray | None = None,
                       passes: int = 1) -> Solved:
    """:func:`solve_square` of a small system given as a dense matrix (its dense path).

    >>> solve_dense_square(np.array([[2.0, 0.0], [0.0, 4.0]]), np.array([1.0, 1.0])).x
    array([0.5 , 0.25])
    """
    if len(rhs) == 0:
        return Solved(np.zeros(0), 1.0)
    return _dense_square(a, rhs, guess, passes)


def _dense_square(a: np.ndarray, rhs: np.ndarray, guess: np.ndarray | None,
                  passes: int) -> Solved:
    """:func:`solve_square` for a small dense matrix (the same steps, fewer calls; plain
    Python floats up to :data:`PLAIN_UP_TO` unknowns)."""
    failed = Solved(np.full(len(rhs), np.nan), np.inf)
    if len(rhs) <= PLAIN_UP_TO:
        x, cond = solve_plain(a.tolist(), rhs.tolist(),
                              None if guess is None else guess.tolist(), passes)
        return failed if x is None else Solved(np.array(x), cond)
    nonzero = a != 0
    magnitude = np.abs(a)
    rhs_size = np.abs(rhs)

    def scales(x: np.ndarray) -> np.ndarray:
        d = np.abs(x)
        terms = np.maximum((magnitude * d).max(axis=1), rhs_size)[:, None]
        implied = np.divide(terms, magnitude, out=np.full(a.shape, np.inf),
                            where=nonzero & (terms > 0)).min(axis=0)
        small = d < ROUND_OFF * implied
        if small.any():
            d = np.where(small & np.isfinite(implied), implied, d)
        positive = d > 0
        if positive.all():
            return d
        if not positive.any():
            return np.ones_like(d)
        return np.where(positive, d, d[positive].min())

    def scaled(d: np.ndarray):
        m = a * d
        r = np.abs(m).max(axis=1)
        r[r == 0] = 1.0
        m /= r[:, None]
        y = _solve_small(m, rhs / r)
        return (None if y is None else d * y), m

    x = _solve_small(a, rhs) if guess is None else scaled(scales(np.abs(guess)))[0]
    if x is None or not np.all(np.isfinite(x)):
        return failed
    d = scales(x)
    if passes <= 1 and d.max() <= WELL_SCALED * d.min():
        # Unknowns within three decades: partial pivoting (on the system as given or scaled
        # by the guess) already solved it as accurately as further scaled passes would;
        # only its condition is still needed.
        r = np.abs(a * d).max(axis=1)
        r[r == 0] = 1.0
        return Solved(x, dense_condition(a * d / r[:, None]))
    for k in range(MAX_PASSES):
        x, m = scaled(d)
        if x is None or not np.all(np.isfinite(x)):
            return failed
        following = scales(x)
        if k + 1 >= passes and np.all(np.abs(np.log(following / d)) < np.log(SETTLED)):
            break
        d = following
    return Solved(x, dense_condition(m))


_LOG_SETTLED = math.log(SETTLED)

Matrix = list[list[float]]


def factor(matrix: Matrix) -> tuple[Matrix, list[int]] | None:
    """LU factors of a square matrix with partial pivoting (``L`` below the diagonal, unit
    diagonal implied; ``U`` on and above), and the row order; None when a pivot is exactly
    zero or not finite.

    >>> lu, order = factor([[0.0, 2.0], [4.0, 1.0]])
    >>> lu, order
    ([[4.0, 1.0], [0.0, 2.0]], [1, 0])
    """
    lu = [row[:] for row in matrix]
    n = len(lu)
    order = list(range(n))
    for k in range(n):
        p, top = k, abs(lu[k][k])
        for i in range(k + 1, n):
            size = abs(lu[i][k])
            if size > top:
                p, top = i, size
        if not 0.0 < top < math.inf:
            return None
        if p != k:
            lu[k], lu[p] = lu[p], lu[k]
            order[k], order[p] = order[p], order[k]
        pivot_row = lu[k]
        pivot = pivot_row[k]
        for i in range(k + 1, n):
            row = lu[i]
            f = row[k] / pivot
            row[k] = f
            if f != 0.0:
                for j in range(k + 1, n):
                    row[j] -= f * pivot_row[j]
    return lu, order


def substitute(lu: Matrix, order: list[int], rhs: list[float]) -> list[float]:
    """Solve ``A x = rhs`` from :func:`factor`'s output.

    >>> substitute(*factor([[2.0, 0.0], [0.0, 4.0]]), [1.0, 1.0])
    [0.5, 0.25]
    """
    n = len(lu)
    y = [rhs[p] for p in order]
    for i in range(n):
        row, s = lu[i], y[i]
        for j in range(i):
            s -= row[j] * y[j]
        y[i] = s
    for i in range(n - 1, -1, -1):
        row, s = lu[i], y[i]
        for j in range(i + 1, n):
            s -= row[j] * y[j]
        y[i] = s / row[i]
    return y


def _solve(matrix: Matrix, rhs: list[float]) -> tuple[list[float] | None, tuple | None]:
    """The solution (None if singular or not finite) and the factors."""
    factors = factor(matrix)
    if factors is None:
        return None, None
    x = substitute(*factors, rhs)
    return (x if all(math.isfinite(v) for v in x) else None), factors


def condition(a: Matrix, factors: tuple | None, scaled_by: tuple | None = None,
              factored_by: tuple | None = None) -> float:
    """:func:`dense_condition` of ``m = diag(1/r) a diag(d)`` (``scaled_by = (d, r)``;
    ``a`` itself when None) from the LU factors of another scaling of ``a``,
    ``diag(1/r0) a diag(d0)`` (``factored_by = (d0, r0)``; ``a`` when None), since
    ``m⁻¹ = diag(d0/d) (its inverse) diag(r/r0)``: no second factorization. The 1-norm
    condition number ``κ1`` gives ``κ1/n <= κ2 <= n·κ1``; the exact ``κ2`` (numpy) only
    when that bound straddles :data:`COND_LIMIT`.

    >>> condition([[1.0, 0.0], [0.0, 1.0]], factor([[1.0, 0.0], [0.0, 1.0]]))
    2.0
    >>> a = [[1.0, 0.0], [0.0, 1e-9]]    # diag(1, 1e-9) scaled by d = (1, 1e9): the identity
    >>> condition(a, factor(a), ([1.0, 1e9], [1.0, 1.0]))
    2.0
    """
    n = len(a)
    if factors is None:
        return math.inf
    d, r = scaled_by if scaled_by is not None else ([1.0] * n, [1.0] * n)
    d0, r0 = factored_by if factored_by is not None else ([1.0] * n, [1.0] * n)
    norm = 0.0
    for j in range(n):
        total = 0.0
        for row, size in zip(a, r):
            total += abs(row[j]) / size
        total *= d[j]
        if total > norm:
            norm = total
    inverse_norm = 0.0
    rescale = [u / v for u, v in zip(d0, d)]
    for j in range(n):
        unit = [0.0] * n
        unit[j] = 1.0
        total = 0.0
        for v, w in zip(substitute(*factors, unit), rescale):
            total += abs(v) * w
        total *= r[j] / r0[j]
        if total > inverse_norm:
            inverse_norm = total
    k1 = norm * inverse_norm
    if not math.isfinite(k1):
        return math.inf
    if n * k1 < COND_LIMIT:
        return n * k1
    if k1 > n * COND_LIMIT:
        return k1 / n
    return float(np.linalg.cond(np.array([[v * s / size for v, s in zip(row, d)]
                                          for row, size in zip(a, r)])))


def solve_plain(a: Matrix, rhs: list[float], guess: list[float] | None = None,
                passes: int = 1) -> tuple[list[float] | None, float]:
    """The dense path of :func:`powergraph.linalg.solve_square` on lists: the solution
    (None when it fails) and the condition number of the scaled system (a bound on the
    same side of :data:`COND_LIMIT`).

    Examples
    --------
    >>> x, cond = solve_plain([[2.0, 0.0], [0.0, 4.0]], [1.0, 1.0])
    >>> x, cond < COND_LIMIT
    ([0.5, 0.25], True)
    """
    n = len(rhs)
    magnitude = [[abs(v) for v in row] for row in a]
    rhs_size = [abs(v) for v in rhs]
    # per column, the rows where it has a coefficient, and its magnitude there
    entries = [[(i, row[j]) for i, row in enumerate(magnitude) if row[j] != 0.0]
               for j in range(n)]

    def scales(x: list[float]) -> list[float]:
        d = [abs(v) for v in x]
        terms = []
        for row, size in zip(magnitude, rhs_size):
            for m, s in zip(row, d):
                if m * s > size:
                    size = m * s
            terms.append(size)
        low = math.inf
        for j, column in enumerate(entries):
            implied = math.inf
            for i, m in column:
                if terms[i] > 0.0 and terms[i] < implied * m:
                    implied = terms[i] / m
            if d[j] < ROUND_OFF * implied < math.inf:
                d[j] = implied
            if 0.0 < d[j] < low:
                low = d[j]
        if low == math.inf:
            return [1.0] * n
        return [s if s > 0.0 else low for s in d]

    def row_sizes(d: list[float]) -> list[float]:
        """Each row's largest term with the columns scaled by ``d`` (1 for a zero row)."""
        sizes = []
        for row in magnitude:
            size = 0.0
            for m, s in zip(row, d):
                if m * s > size:
                    size = m * s
            sizes.append(size or 1.0)
        return sizes

    def scaled(d: list[float]) -> tuple[list[float] | None, list[float], tuple | None]:
        """Solve with the columns scaled by ``d``, each row by its largest entry."""
        r = row_sizes(d)
        m = [[v * s / size for v, s in zip(row, d)] for row, size in zip(a, r)]
        y, factors = _solve(m, [v / size for v, size in zip(rhs, r)])
        return (None if y is None else [s * v for s, v in zip(d, y)]), r, factors

    if guess is None:
        x, factors = _solve(a, rhs)
        factored_by = None
    else:
        d0 = scales(guess)
        x, r0, factors = scaled(d0)
        factored_by = (d0, r0)
    if x is None:
        return None, math.inf
    d = scales(x)
    if passes <= 1 and max(d) <= WELL_SCALED * min(d):
        return x, condition(a, factors, (d, row_sizes(d)), factored_by)
    for k in range(MAX_PASSES):
        used = d
        x, r, factors = scaled(used)
        if x is None:
            return None, math.inf
        d = scales(x)
        if k + 1 >= passes and all(abs(math.log(f / s)) < _LOG_SETTLED
                                   for f, s in zip(d, used)):
            break
    return x, condition(a, factors, (used, r), (used, r))
