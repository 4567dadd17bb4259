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


# --- the plain-Python path: the same steps on lists --------------------------------------
# Expected values: the numpy path of the same function (LAPACK's getrf/getrs, which use
# the same partial pivoting), forced by PLAIN_UP_TO = 0, and the ladder's closed form.

from hypothesis import given, settings, strategies as st  # noqa: E402

import powergraph.linalg_dense as linalg_dense  # noqa: E402
from powergraph.linalg_dense import factor, solve_plain, substitute  # noqa: E402


def numpy_path(a: np.ndarray, rhs: np.ndarray, guess=None, passes: int = 1):
    """The dense path with the plain one switched off."""
    saved = linalg_dense.PLAIN_UP_TO
    linalg_dense.PLAIN_UP_TO = 0
    try:
        return linalg_dense._dense_square(a, rhs, guess, passes)
    finally:
        linalg_dense.PLAIN_UP_TO = saved


@settings(max_examples=300, deadline=None)
@given(n=st.integers(1, 6), seed=st.integers(0, 2**32 - 1),
       spread=st.integers(0, 12), zeros=st.floats(0.0, 0.6))
def test_the_plain_path_gives_the_numpy_paths_solution_and_verdict(
        n: int, seed: int, spread: int, zeros: float) -> None:
    """Random systems with entries over ``spread`` decades and some exact zeros: the same
    regularity verdict, and where regular the same solution to rounding."""
    rng = np.random.default_rng(seed)
    a = rng.normal(size=(n, n)) * 10.0 ** rng.integers(-spread, spread + 1, size=(n, n))
    a[rng.random((n, n)) < zeros] = 0.0
    rhs = rng.normal(size=n)
    expected = numpy_path(a, rhs)
    x, cond = solve_plain(a.tolist(), rhs.tolist())
    regular = x is not None and cond < COND_LIMIT
    if abs(np.log10(max(expected.condition, 1.0)) - 12) > 0.5:   # not at the limit itself
        assert regular == expected.regular
    if regular and expected.regular:
        assert np.allclose(x, expected.x, rtol=1e-9 * expected.condition, atol=0)
        assert np.allclose(a @ np.array(x), rhs,
                           atol=1e-9 * np.max(np.abs(a) * np.abs(np.array(x))) + 1e-300)


@pytest.mark.parametrize("n", [2, 4, 6])
def test_the_plain_path_scales_a_ladder_as_the_numpy_path(n: int) -> None:
    """x_k = 1e-40^k: unknowns spanning 200 decades, each accurate relative to itself."""
    t = ladder(n, 1e-40)
    x, cond = solve_plain(t.dense().tolist(), np.eye(n)[0].tolist(), passes=2)
    assert cond < COND_LIMIT
    assert np.allclose(x, [1e-40 ** k for k in range(n)], rtol=1e-13, atol=0)


def test_a_singular_system_has_no_plain_solution() -> None:
    assert factor([[1.0, 2.0], [2.0, 4.0]]) is None or \
        solve_plain([[1.0, 2.0], [2.0, 4.0]], [1.0, 2.0])[1] >= COND_LIMIT
    assert solve_plain([[0.0, 0.0], [0.0, 1.0]], [1.0, 1.0])[0] is None


def test_factor_and_substitute_solve_with_row_exchanges() -> None:
    """[[0, 2], [4, 1]] x = [2, 9]: x = (2, 1) by hand (the first pivot needs a swap)."""
    assert substitute(*factor([[0.0, 2.0], [4.0, 1.0]]), [2.0, 9.0]) == [2.0, 1.0]
