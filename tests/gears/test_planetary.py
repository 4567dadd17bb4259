"""powergraph.gears.planetary: the conditions of a planetary set, against hand numbers.

(The synthesis filters its grids with the same functions: tests/analyses/test_synthesis.py
checks ``assembles`` against a brute-force fit on random stepped planets.)"""
from __future__ import annotations

import math

import numpy as np
import pytest

from powergraph.errors import ModelError
from powergraph.gears.planetary import (assembles, centre_distance, centre_tolerance,
                                        neighbours_clear, relative_turns, shift_sum,
                                        undercut_limit, working_centre_distance)


def one(value: int) -> np.ndarray:
    return np.array([value])


def test_centre_distance_in_half_modules() -> None:
    # sun 23 + planet 24 = 47, ring 72 - planet 24 = 48: not coaxial
    assert centre_distance(23, 24, False) == 47
    assert centre_distance(72, 24, True) == 48


def test_simple_planet_assembles_when_sun_plus_ring_over_n_is_whole() -> None:
    assert assembles([one(24), one(72)], [one(-24), one(24)], 3)[0]       # 96/3 = 32
    assert not assembles([one(24), one(72)], [one(-24), one(24)], 5)[0]   # 96/5 = 19.2
    assert assembles([one(24), one(72)], [one(-24), one(24)], 4)[0]       # 96/4 = 24


def test_stepped_planet_closed_form() -> None:
    # (z_s z_p2 + z_r z_p1)/(n gcd(z_p1, z_p2)): sun 18 on step 36, ring 72 on step 18:
    # (18·18 + 72·36)/(3·18) = 2916/54 = 54, whole; with 5 planets 2916/90 = 32.4, not.
    assert assembles([one(18), one(72)], [one(-36), one(18)], 3)[0]
    assert not assembles([one(18), one(72)], [one(-36), one(18)], 5)[0]


def test_relative_turns_through_planet_planet_meshes() -> None:
    # a (15) meshes b (20): z_a dθ_a = -z_b dθ_b, so b turns -15/20 of a; b meshes d (30):
    # d turns -(−15/20)·20/30 = 15·20/(20·30) of a.
    turns = relative_turns("a", [("a", "b", 15, 20), ("b", "d", 20, 30)])
    assert turns == {"a": (1, 1), "b": (-15, 20), "d": (300, 600)}


def test_neighbours_clear_in_modules() -> None:
    # sun 12, planet 30, ring 72, 4 planets: a = 21 modules, axes 2·21·sin 45° = 29.70 apart,
    # tip diameter 32 modules: they collide; 3 planets: 2·21·sin 60° = 36.37 > 32.
    assert not neighbours_clear(np.array(30), np.array(42), 4)
    assert neighbours_clear(np.array(30), np.array(42), 3)
    # a larger tip (h_a* + x = 1.5, tip 3 modules): 33 < 36.37 still clears with 3
    assert neighbours_clear(np.array(30), np.array(42), 3, tip=3.0)


def test_undercut_limit() -> None:
    # 2(1 - x)/sin²α: 17.10 at 20°, 11.97 with x = 0.3; 32.0 at 14.5°
    assert undercut_limit(20.0) == pytest.approx(2 / math.sin(math.radians(20)) ** 2)
    assert undercut_limit(20.0) == pytest.approx(17.097, abs=1e-3)
    assert undercut_limit(20.0, shift=0.3) == pytest.approx(0.7 * 17.097, abs=1e-3)
    assert undercut_limit(14.5) == pytest.approx(2 / math.sin(math.radians(14.5)) ** 2)


def test_working_centre_distance() -> None:
    # unshifted: m (z1 + z2)/2 and m (z2 - z1)/2
    assert working_centre_distance(20, 40, False, 2.0) == pytest.approx(60.0)
    assert working_centre_distance(15, 48, True, 1.0) == pytest.approx(16.5)
    # x1 + x2 = 0 (V-zero): the reference distance
    assert working_centre_distance(12, 36, False, 1.5, shift_1=0.3, shift_2=-0.3) == \
        pytest.approx(36.0)
    # shifted: inv α_w = inv α + 2 tan α (x1 + x2)/(z1 + z2), a_w = a cos α / cos α_w.
    # 20/40, x1 + x2 = 0.5: inv α_w = 0.0149044 + 0.7279404·0.5/60 = 0.0209706;
    # α_w = 22.3167° (tan α - α = 0.0209706), a_w = 60 cos 20°/cos 22.3167° = 60.9465 mm
    assert working_centre_distance(20, 40, False, 2.0, shift_1=0.25, shift_2=0.25) == \
        pytest.approx(60 * math.cos(math.radians(20)) / math.cos(math.radians(22.3167)),
                      rel=1e-5)


def test_shift_sum_inverts_the_working_centre_distance() -> None:
    # 20/40 at 60.9465 mm (the example above): cos α_w = 60 cos 20°/60.9465 = 0.925113,
    # α_w = 22.3167°, x1 + x2 = (0.0209706 − 0.0149044)·60/(2 tan 20°) = 0.5
    assert shift_sum(20, 40, False, 2.0, 60.9465) == pytest.approx(0.5, abs=1e-4)
    # an internal pair gives x2 − x1; helical and other pressure angles round-trip
    for args in ((15, 48, True, 1.0, 20.0, 0.0, 0.2, 0.874),
                 (17, 23, False, 3.0, 25.0, 15.0, -0.1, 0.45),
                 (23, 85, True, 2.5, 20.0, 30.0, 0.3, -0.2)):
        z1, z2, internal, m, alpha, beta, x1, x2 = args
        a_w = working_centre_distance(z1, z2, internal, m, alpha, beta, x1, x2)
        expected = x2 - x1 if internal else x1 + x2
        assert shift_sum(z1, z2, internal, m, a_w, alpha, beta) == pytest.approx(expected,
                                                                                 abs=1e-9)
    assert shift_sum(20, 40, False, 2.0, 60.0) == 0.0
    # inside the base circles' 60 cos 20° = 56.38 mm no working pressure angle exists
    with pytest.raises(ModelError, match="base circles' 56.3816 mm"):
        shift_sum(20, 40, False, 2.0, 56.0)


def test_centre_tolerance_is_a_thousandth_of_a_module() -> None:
    assert centre_tolerance(1.0) == pytest.approx(1e-3)          # 1 µm at module 1
    assert centre_tolerance(4.0) == pytest.approx(4e-3)
