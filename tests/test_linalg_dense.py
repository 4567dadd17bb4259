"""Small dense systems: the cheap condition bound decides regularity as the singular values
do, and the dense entry point gives the scaled solve's numbers.

Expected values: numpy's SVD (computed independently of the bound) and the closed form
x_k = 5^k of a ladder.
"""
from __future__ import annotations

import numpy as np
import pytest

from powergraph.linalg import Triplets, solve_square
from powergraph.linalg_dense import COND_LIMIT, dense_condition, solve_dense_square


def ladder(n: int, ratio: float) -> Triplets:
    """x_0 = 1 and x_k - ratio x_(k-1) = 0: x_k = ratio^k."""
    rows = list(range(n)) + list(range(1, n))
    cols = list(range(n)) + list(range(n - 1))
    return Triplets.build(rows, cols, [1.0] * n + [-ratio] * (n - 1), (n, n))


@pytest.mark.parametrize("eps", [1e-3, 1e-9, 1e-11, 1e-12, 1e-13, 1e-15, 1e-20, 0.0])
@pytest.mark.parametrize("n", [2, 8, 20])
def test_the_cheap_condition_is_on_the_same_side_of_the_limit_as_the_exact_one(
        eps: float, n: int) -> None:
    """diag(1, ..., 1, eps) rotated: its 2-norm condition number is 1/eps by its singular
    values, which numpy's SVD (np.linalg.cond) computes independently of the bound."""
    q, _ = np.linalg.qr(np.random.default_rng(n).normal(size=(n, n)))
    matrix = q @ np.diag([1.0] * (n - 1) + [eps]) @ q.T
    exact = np.linalg.cond(matrix)
    assert (dense_condition(matrix) < COND_LIMIT) == (exact < COND_LIMIT)


def test_the_small_dense_solve_is_the_scaled_solve() -> None:
    """The ladder x_k = 5^k through the dense entry point and through the triplets."""
    n = 25
    t = ladder(n, 5.0)
    dense = solve_dense_square(t.dense(), np.eye(n)[0])
    assert dense.regular
    assert np.allclose(dense.x / 5.0 ** np.arange(n), 1.0, rtol=1e-13, atol=0)
    assert np.array_equal(dense.x, solve_square(t, np.eye(n)[0]).x)


def test_an_exactly_singular_small_system_is_not_regular() -> None:
    solved = solve_dense_square(np.ones((3, 3)), np.ones(3))
    assert not solved.regular
