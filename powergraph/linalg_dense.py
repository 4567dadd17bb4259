"""Small dense square systems, solved scaled without numpy's per-call overhead.

The dense path of :func:`powergraph.linalg.solve_square` (which re-exports what is
here): a gear train's systems are small (the RV-40E's torque balance has 8 unknowns), so a
single solve's time is per-call overhead, not arithmetic. The LAPACK kernels behind
``np.linalg.solve`` and ``np.linalg.inv`` are called directly (the same calls, so the same
digits), and the regularity test uses a condition bound from one inverse
(:func:`dense_condition`), the singular values only when that bound is not decisive.
"""
from __future__ import annotations

from dataclasses import dataclass

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



@dataclass(frozen=True)
class Solved:
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
    """:func:`solve_square` for a small dense matrix (the same steps, fewer calls)."""
    failed = Solved(np.full(len(rhs), np.nan), np.inf)
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


