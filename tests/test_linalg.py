"""The linear systems: triplets, structural rank, scaled solves, dense and sparse alike.

Expected values are closed forms (geometric sequences, a matrix with a dependent row, a
well-conditioned system rescaled over many decades, whose unscaled solution numpy's
``solve`` gives) and numpy's SVD for condition numbers (computed independently of the
bound the dense path uses).
"""
from __future__ import annotations

import numpy as np
import pytest

from powergraph import linalg
from hypothesis import given, settings, strategies as st

from powergraph.linalg import (COND_LIMIT, Triplets, dense_condition, matching, rank,
                               solve_square)


@pytest.fixture(params=["dense", "sparse"])
def path(request, monkeypatch):
    monkeypatch.setattr(linalg, "PATH", request.param)
    return request.param


def ladder(n: int, ratio: float) -> Triplets:
    """x_0 = 1 and x_k - ratio x_(k-1) = 0: x_k = ratio^k (rows k, columns k and k-1)."""
    rows = list(range(n)) + list(range(1, n))
    cols = list(range(n)) + list(range(n - 1))
    return Triplets.build(rows, cols, [1.0] * n + [-ratio] * (n - 1), (n, n))


def test_triplets_sum_duplicates_and_drop_exact_zeros() -> None:
    t = Triplets.build([0, 0, 1, 1], [0, 0, 1, 1], [2.0, 3.0, 1.5, -1.5], (2, 2))
    assert t.dense().tolist() == [[5.0, 0.0], [0.0, 0.0]]
    assert len(t.values) == 1          # the cancelled entry is not part of the structure


@pytest.mark.parametrize("ratio", [5.0, 0.2, 1e-6])
def test_a_ladder_spanning_hundreds_of_decades_is_solved_relative_to_each_unknown(
        ratio: float, path) -> None:
    """ratio^k for k up to 49: 5^49 ≈ 1.8e34, 1e-6^49 = 1e-294."""
    n = 50
    solved = solve_square(ladder(n, ratio), np.eye(n)[0])
    assert solved.regular
    expected = ratio ** np.arange(n)
    assert np.allclose(solved.x, expected, rtol=1e-12, atol=0)


def test_a_singular_system_is_not_regular_whatever_its_scaling(path) -> None:
    """Row 2 = row 0 + row 1 of a 3x3 system whose entries span 1e-8..1e8."""
    a = np.array([[1e8, 2.0, 0.0], [0.0, 3.0, 1e-8], [1e8, 5.0, 1e-8]])
    rows, cols = np.nonzero(a)
    t = Triplets.build(rows, cols, a[rows, cols], a.shape)
    assert not solve_square(t, np.array([1.0, 1.0, 2.0])).regular


def test_an_exactly_singular_small_system_is_not_regular(path) -> None:
    ones = Triplets.build(*np.nonzero(np.ones((3, 3))), np.ones(9), (3, 3))
    assert not solve_square(ones, np.ones(3)).regular
    zero_column = Triplets.build([0, 1], [1, 1], [1.0, 1.0], (2, 2))
    assert not solve_square(zero_column, np.ones(2)).regular


def test_the_dense_and_sparse_paths_give_the_ladders_numbers(monkeypatch) -> None:
    """x_k = 5^k, k < 25, through both factorisations: the same scaled steps."""
    n = 25
    solved = {}
    for which in ("dense", "sparse"):
        monkeypatch.setattr(linalg, "PATH", which)
        solved[which] = solve_square(ladder(n, 5.0), np.eye(n)[0])
        assert solved[which].regular
    assert np.allclose(solved["dense"].x / 5.0 ** np.arange(n), 1.0, rtol=1e-13, atol=0)
    assert np.allclose(solved["dense"].x, solved["sparse"].x, rtol=1e-13, atol=0)


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


@settings(max_examples=200, deadline=None)
@given(n=st.integers(1, 8), seed=st.integers(0, 2**32 - 1), spread=st.integers(0, 24),
       zeros=st.floats(0.0, 0.5))
def test_each_unknown_is_accurate_relative_to_itself_over_many_decades(
        n: int, seed: int, spread: int, zeros: float) -> None:
    """A well-conditioned system ``a x = b`` (the identity plus off-diagonal entries of
    1e-12..0.3, some exactly zero; numpy's solve gets it to rounding) with its rows and
    columns rescaled by up to ``10^±spread``: ``diag(r) a diag(1/c)`` has the solution
    ``c x``, whose unknowns span up to 2·spread decades. The scaled solve finds it regular
    and every unknown to a relative 1e-10. (Unscaled elimination does not: the row scales
    make it pivot on the tiny entries; it misses that accuracy on more than half of such
    systems with spread 24.)"""
    rng = np.random.default_rng(seed)
    off = rng.normal(size=(n, n)) * 10.0 ** rng.uniform(-12, 0, (n, n))
    off[rng.random((n, n)) < zeros] = 0.0
    np.fill_diagonal(off, 0.0)
    a = np.eye(n) + 0.3 * off
    if np.linalg.cond(a) > 1e3:
        return
    x = np.linalg.solve(a, a @ (rng.choice([-1.0, 1.0], n) * rng.uniform(0.5, 2.0, n)))
    b = a @ x
    x = np.linalg.solve(a, b)          # the solution of the rounded right-hand side
    r = 10.0 ** rng.integers(-spread, spread + 1, n)
    c = 10.0 ** rng.integers(-spread, spread + 1, n)
    scaled = a * r[:, None] / c[None, :]
    rows, cols = np.nonzero(scaled)
    solved = solve_square(Triplets.build(rows, cols, scaled[rows, cols], (n, n)), b * r)
    assert solved.regular
    assert np.allclose(solved.x / (c * x), 1.0, rtol=1e-10, atol=0)


def test_matching_and_rank_see_a_dependent_row(path) -> None:
    """Three rows over three columns, structurally full, numerically of rank 2 (the
    third row is the sum of the first two): the structural rank is confirmed or not on
    the scaled matched part."""
    a = np.array([[1.0, -4.0, 0.0], [0.0, 1.0, -4.0], [1.0, -3.0, -4.0]])
    rows, cols = np.nonzero(a)
    t = Triplets.build(rows, cols, a[rows, cols], a.shape)
    assert (matching(t) >= 0).sum() == 3
    assert rank(t) == 2
    assert rank(ladder(40, 5.0)) == 40


def test_matching_finds_an_augmenting_path() -> None:
    """Row 0 touches columns 0 and 1, row 1 only column 0: a maximum matching must give
    column 0 to row 1."""
    t = Triplets.build([0, 0, 1], [0, 1, 0], [1.0, 1.0, 1.0], (2, 2))
    assert matching(t).tolist() == [1, 0]



# --- set operations without numpy.ma: numpy's own functions are the expected values ----

from powergraph.linalg import others, unique_inverse  # noqa: E402


@given(st.lists(st.integers(-50, 50), max_size=60))
def test_unique_inverse_is_numpys(keys: list[int]) -> None:
    key = np.array(keys, dtype=np.int64)
    values, inverse = unique_inverse(key)
    expected_values, expected_inverse = np.unique(key, return_inverse=True)
    assert values.tolist() == expected_values.tolist()
    assert inverse.tolist() == expected_inverse.ravel().tolist()


@given(st.integers(0, 40), st.data())
def test_others_is_setdiff1d(n: int, data) -> None:
    taken = data.draw(st.lists(st.integers(0, max(n - 1, 0)), max_size=n)) if n else []
    assert others(n, taken).tolist() == np.setdiff1d(np.arange(n), taken).tolist()
