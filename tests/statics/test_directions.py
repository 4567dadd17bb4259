"""The "nothing passes" rule's scales and codes, one function for one operating point or
many: ``own_scales`` of ``(E, P)`` arrays is ``own_scales`` of each point alone, bit for
bit, and each point's scales are the rule's definition (each body's external torque plus
the element torques on it; an element's largest over its own bodies but the frame);
``driver_codes`` of one value (0-d) is that of the arrays.

Expected values: the definition written out below with Python floats in own_scales'
order of addition, and a pair worked by hand.
"""
from __future__ import annotations

import numpy as np
from hypothesis import given, settings, strategies as st

from powergraph.kinematics import element_stencil
from powergraph.statics.directions import FORCE_NOISE, driver_codes, own_scales, pattern_of


def definition(bodies, ratios, forces, factors, load, frame) -> list[float]:
    """Each body's load: its external torque, then for gear a, gear b and the carrier in
    turn every element's torque magnitude on it; an element's scale is the largest load
    on its bodies other than the frame, or the largest of all when it has none."""
    load = list(load)
    for column in range(3):
        for triple, ratio, force, factor in zip(bodies, ratios, forces, factors):
            load[triple[column]] += abs(element_stencil(ratio, factor)[column] * force)
    own = [[load[b] for b in triple if b != frame] for triple in bodies]
    return [max(loads) if loads else max(load, default=0.0) for loads in own]


@settings(max_examples=300, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), n_bodies=st.integers(3, 8),
       n_elements=st.integers(1, 6), points=st.integers(1, 5))
def test_the_scales_of_many_points_are_each_points_definition(
        seed: int, n_bodies: int, n_elements: int, points: int) -> None:
    rng = np.random.default_rng(seed)
    bodies = np.array([rng.choice(n_bodies, 3, replace=False) for _ in range(n_elements)])
    ratios = rng.normal(size=(n_elements, points)) * 3
    forces = rng.normal(size=(n_elements, points)) * 10.0 ** rng.integers(
        -8, 8, (n_elements, points))
    factors = rng.uniform(0.5, 2.0, (n_elements, points))
    load = np.abs(rng.normal(size=(n_bodies, points))) * (rng.random((n_bodies, points)) < 0.5)
    frame = int(rng.integers(-1, n_bodies))
    many = own_scales(bodies, ratios, forces, factors, load, frame)
    for p in range(points):
        one = own_scales(bodies, ratios[:, p], forces[:, p], factors[:, p], load[:, p], frame)
        assert one.tolist() == many[:, p].tolist()
        assert one.tolist() == definition(bodies.tolist(), ratios[:, p].tolist(),
                                          forces[:, p].tolist(), factors[:, p].tolist(),
                                          load[:, p].tolist(), frame)


def test_an_element_on_the_frame_alone_takes_the_largest_load() -> None:
    """A coupling between the frame (0) and itself is no train; an element whose bodies are
    all the frame has no own moving body, so its scale is the largest load of all."""
    scales = own_scales(np.array([[1, 2, 0], [0, 0, 0]]), np.array([-2.0, 1.0]),
                        np.array([3.0, 0.0]), np.array([1.0, 1.0]), np.zeros(3), 0)
    # the pair (stencil 1, 2, -3 times 3): 3 on gear 1, 6 on gear 2, 9 on the frame; its own
    # scale leaves the frame out (6); the other element's is the largest load, the frame's
    assert scales.tolist() == [6.0, 9.0]


@settings(max_examples=300, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), n_elements=st.integers(1, 6))
def test_the_codes_of_one_value_are_the_arrays(seed: int, n_elements: int) -> None:
    """Forces at and around the noise of their scales, zero relative speeds: each value's
    code alone (0-d) is its code in the array, and the pattern lists them."""
    rng = np.random.default_rng(seed)
    scales = 10.0 ** rng.integers(-6, 6, n_elements)
    forces = rng.choice([-1.0, 1.0], n_elements) * scales * rng.choice(
        [FORCE_NOISE, FORCE_NOISE * (1 + 1e-15), 1e-3, 1.0, 0.0], n_elements)
    rel = rng.normal(size=n_elements) * (rng.random(n_elements) < 0.8)
    codes = driver_codes(forces, rel, scales)
    assert [int(driver_codes(f, w, s)) for f, w, s in zip(forces, rel, scales)] == \
        codes.tolist()
    assert pattern_of(forces, rel, scales) == tuple(codes.tolist())
    expected = [0 if w == 0.0 or abs(f) <= FORCE_NOISE * s else (1 if -f * w > 0 else -1)
                for f, w, s in zip(forces, rel, scales)]
    assert codes.tolist() == expected
