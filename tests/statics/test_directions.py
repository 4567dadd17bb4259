"""The "nothing passes" rule's scales: the plain-Python form for a few elements equals the
numpy form (:func:`own_scales`), which the sweep and the grid use on many points.

Expected values: the numpy form on the same random trains, and a pair worked by hand.
"""
from __future__ import annotations

import numpy as np
from hypothesis import given, settings, strategies as st

from powergraph.statics.directions import own_scales, own_scales_plain


@settings(max_examples=300, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), n_bodies=st.integers(3, 8),
       n_elements=st.integers(1, 6))
def test_plain_scales_equal_the_numpy_scales(seed: int, n_bodies: int,
                                             n_elements: int) -> None:
    rng = np.random.default_rng(seed)
    bodies = np.array([rng.choice(n_bodies, 3, replace=False) for _ in range(n_elements)])
    ratios = rng.normal(size=n_elements) * 3
    forces = rng.normal(size=n_elements) * 10.0 ** rng.integers(-8, 8, n_elements)
    factors = rng.uniform(0.5, 2.0, n_elements)
    load = np.abs(rng.normal(size=n_bodies)) * (rng.random(n_bodies) < 0.5)
    frame = int(rng.integers(-1, n_bodies))
    expected = own_scales(bodies, ratios, forces, factors, load.copy(), frame)
    plain = own_scales_plain(bodies.tolist(), ratios.tolist(), forces.tolist(),
                             factors.tolist(), load.tolist(), frame)
    assert np.allclose(plain, expected, rtol=1e-14, atol=0)


def test_an_element_on_the_frame_alone_takes_the_largest_load() -> None:
    """A coupling between the frame (0) and itself is no train; an element whose bodies are
    all the frame has no own moving body, so its scale is the largest load of all."""
    scales = own_scales_plain([[1, 2, 0], [0, 0, 0]], [-2.0, 1.0], [3.0, 0.0], [1.0, 1.0],
                              [0.0, 0.0, 0.0], 0)
    # the pair (stencil 1, 2, -3 times 3): 3 on gear 1, 6 on gear 2, 9 on the frame; its own
    # scale leaves the frame out (6); the other element's is the largest load, the frame's
    assert scales == [6.0, 9.0]


@settings(max_examples=300, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), n_elements=st.integers(1, 6))
def test_plain_patterns_equal_the_numpy_driver_codes(seed: int, n_elements: int) -> None:
    """The single solve's pattern of a few elements (driver_code on floats) is
    driver_codes' (numpy), forces at and around the noise of their scales included."""
    from powergraph.statics.directions import FORCE_NOISE, driver_codes, pattern_of

    rng = np.random.default_rng(seed)
    scales = 10.0 ** rng.integers(-6, 6, n_elements)
    forces = rng.choice([-1.0, 1.0], n_elements) * scales * rng.choice(
        [FORCE_NOISE, FORCE_NOISE * (1 + 1e-15), 1e-3, 1.0, 0.0], n_elements)
    rel = rng.normal(size=n_elements) * (rng.random(n_elements) < 0.8)
    assert pattern_of(forces, rel, scales) == tuple(driver_codes(forces, rel, scales).tolist())
