"""Batched scaled solves: each system accurate relative to each of its own unknowns.

Expected values are closed forms: the chain ``x_0 = 1``, ``x_i = q x_(i-1)`` has
``x_i = q^i``; a singular system is refused by its condition number.
"""
from __future__ import annotations

import numpy as np

from powergraph.linalg import COND_LIMIT
from powergraph.linalg_batch import solve_square_batch


def chain(n: int, q: float) -> np.ndarray:
    """Rows ``x_0 = 1`` and ``x_i - q x_(i-1) = 0``."""
    return np.eye(n) - q * np.eye(n, k=-1)


def test_every_unknown_is_accurate_relative_to_itself() -> None:
    n, qs = 12, (1e-6, 1e-3, 5.0)
    a = np.stack([chain(n, q) for q in qs])
    x, condition = solve_square_batch(a, np.tile(np.eye(n)[0], (len(qs), 1)))
    for row, q in zip(x, qs):
        exact = q ** np.arange(n)
        assert np.max(np.abs(row / exact - 1)) < 1e-13
    assert np.all(condition < 1e3)


def test_singular_systems_are_refused_one_by_one() -> None:
    regular = chain(3, 2.0)
    singular = np.array([[1.0, 1.0, 0.0], [2.0, 2.0, 0.0], [0.0, 0.0, 1.0]])
    x, condition = solve_square_batch(np.stack([regular, singular]),
                                      np.array([[1.0, 0.0, 0.0], [1.0, 2.0, 1.0]]))
    assert x[0].tolist() == [1.0, 2.0, 4.0]
    assert not condition[1] < COND_LIMIT
