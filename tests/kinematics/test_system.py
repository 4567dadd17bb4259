"""The train system (powergraph.kinematics.system): where every evaluator's Willis rows
and torque balance come from. Expected values: Willis' relation and the torque balance of
a pair written out by hand, and the principle of virtual power (an ideal element's torques
do no work at the train's own speeds)."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from powergraph.kinematics import elements_of, solve_speeds
from powergraph.kinematics.system import TrainSystem, system_of
from powergraph.model import load_model

ROOT = Path(__file__).resolve().parents[2]


def test_a_pair_on_the_frame_by_hand() -> None:
    """Bodies 0 (frame), 1, 2; ratio i = -2: Willis' row is (w1 - w0) - i (w2 - w0) = 0,
    i.e. w1 + 2 w2 - 3 w0 = 0. With f = 0.5 gear a gets λ, gear b -i f λ = λ and the
    carrier (i f - 1) λ = -2 λ; the unknown torques on 2 and 0 have a 1 each."""
    system = TrainSystem(3, [[1, 2, 0]], [2, 0])
    assert system.willis(np.array([-2.0])).tolist() == [[-3.0, 1.0, 2.0]]
    assert system.balance(np.array([-2.0]), np.array([0.5])).tolist() == [
        [-2.0, 0.0, 1.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0]]


@pytest.mark.parametrize("name", ["rv40e_wang2021.yaml", "wolfrom_3k.yaml",
                                  "planetary_2kh_two_stages.yaml", "ravigneaux_first.yaml"])
def test_willis_rows_and_ideal_columns_vanish_at_the_trains_speeds(name: str) -> None:
    """Every Willis row is 0 at the solved speeds, and so is the power of every ideal
    static column (virtual power: an ideal element's torques do no work in any frame)."""
    model = load_model(ROOT / "models" / name)
    elements = elements_of(model)
    speeds = solve_speeds(model).body_speeds
    ids = [body.id for body in model.bodies]
    w = np.array([speeds[b] for b in ids])
    system = system_of(ids, elements)
    ratios = [e.ratio for e in elements]
    scale = np.max(np.abs(w)) * (1 + max(abs(r) for r in ratios))
    np.testing.assert_allclose(system.willis(ratios) @ w, 0.0, atol=1e-12 * scale)
    np.testing.assert_allclose(w @ system.balance(ratios), 0.0, atol=1e-12 * scale)


def test_a_stack_of_points_is_each_point() -> None:
    """Ratios and factors ``(E, P)`` give ``P`` matrices, each the one-point matrix."""
    system = TrainSystem(4, [[1, 2, 0], [2, 3, 0]], [3, 0])
    rng = np.random.default_rng(1)
    ratios, factors = rng.uniform(-4, 4, (2, 5)), rng.uniform(0.5, 2.0, (2, 5))
    stack = system.balance(ratios, factors)
    willis = system.willis(ratios)
    assert stack.shape == (5, 4, 4) and willis.shape == (5, 2, 4)
    for p in range(5):
        np.testing.assert_array_equal(stack[p], system.balance(ratios[:, p], factors[:, p]))
        np.testing.assert_array_equal(willis[p], system.willis(ratios[:, p]))
        for k in range(2):
            np.testing.assert_array_equal(
                stack[p][:, k], system.element_column(k, ratios[k, p], factors[k, p]))


def test_symbols_stay_exact() -> None:
    """Sympy ratios and factors give the stencil's exact coefficients."""
    i, f = sp.symbols("i f")
    rows, cols, values = TrainSystem(3, [[1, 2, 0]], [0]).balance_triplets(
        np.array([i], dtype=object), np.array([f], dtype=object))
    got = {(int(r), int(c)): sp.nsimplify(v) for r, c, v in zip(rows, cols, values)}
    assert got == {(1, 0): 1, (2, 0): -f * i, (0, 0): f * i - 1, (0, 1): 1}


def test_repeated_places_add_up() -> None:
    """An element whose gear a and carrier are one body (a degenerate model) puts the sum
    of both coefficients there, as the sparse triplets do."""
    system = TrainSystem(2, [[1, 0, 1]])
    assert system.willis(np.array([-2.0])).tolist() == [[2.0, -2.0]]
