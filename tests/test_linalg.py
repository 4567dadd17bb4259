"""The linear systems: triplets, structural rank, scaled solves, dense and sparse alike.

Expected values are closed forms: geometric sequences, a matrix with a dependent row.
"""
from __future__ import annotations

import numpy as np
import pytest

from powergraph import linalg
from powergraph.linalg import Triplets, matching, rank, solve_square


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

from hypothesis import given, strategies as st  # noqa: E402

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
