"""The direction rule read on a bound of the own scales (as the sweep's numba kernels and
read_codes' screening of many points read it) agrees with the own-scale rule every
evaluator uses, checked with hypothesis on random structures and values: forces at and
below the round-off threshold, zero relative speeds, elements on the frame only, no frame
(-1). Where the bound names a driver (or the speed is zero) it must be the own-scale
rule's code. The per-value rules are the numpy functions on floats (0-d); the same
functions compiled by numba are checked against them at the end (skipped without numba)."""
from __future__ import annotations

import math

import numpy as np
import pytest

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from powergraph.kinematics import element_stencil  # noqa: E402
from powergraph.statics.directions import (FORCE_NOISE, SCALE_BOUND,  # noqa: E402
                                           driver_codes, element_load, read_codes,
                                           relative_speed)
from powergraph.statics.ports import (flow_efficiency_of_roles,  # noqa: E402
                                      flow_efficiency_point)

SETTINGS = settings(max_examples=300, deadline=None, derandomize=True,
                    suppress_health_check=[HealthCheck.too_slow])

finite = st.floats(-1e3, 1e3, allow_nan=False, allow_infinity=False)
#: A force: ordinary, zero, or near the round-off threshold of ordinary torques.
force = st.one_of(finite, st.just(0.0),
                  st.builds(lambda x, e: x * 10.0 ** -e, finite, st.sampled_from(
                      [9, 10, 11, 12, 13])))
#: A relative speed, often exactly zero.
speed = st.one_of(finite, st.just(0.0), st.just(-0.0))


@st.composite
def direction_problems(draw):
    """Bodies, ratios, forces, factors, relative speeds, loads (``(E, P)``) and frame."""
    n_bodies = draw(st.integers(2, 6))
    n_el = draw(st.integers(1, 4))
    points = draw(st.integers(1, 4))
    body = st.integers(0, n_bodies - 1)
    bodies = np.array(draw(st.lists(st.tuples(body, body, body), min_size=n_el,
                                    max_size=n_el)), dtype=np.int64)
    frame = draw(st.one_of(st.just(-1), body))
    grid = lambda strategy, rows: np.array(  # noqa: E731
        draw(st.lists(st.lists(strategy, min_size=points, max_size=points),
                      min_size=rows, max_size=rows)), dtype=float)
    ratios = grid(st.one_of(finite, st.just(1.0)), n_el)
    factors = grid(st.floats(0.05, 20.0), n_el)
    forces = grid(force, n_el)
    rel = grid(speed, n_el)
    load = grid(st.one_of(st.just(0.0), st.floats(0.0, 1e3)), n_bodies)
    return bodies, ratios, forces, factors, rel, load, frame


def bound_codes(bodies, ratios, forces, factors, rel, load, frame) -> np.ndarray:
    """The codes the sweep's kernels read: :func:`driver_codes` of each value on
    SCALE_BOUND times every torque magnitude on the train (the external ones and each
    element's own), summed in the kernels' order."""
    out = np.zeros(forces.shape, dtype=np.int8)
    for p in range(forces.shape[1]):
        total = 0.0 + sum(load[:, p].tolist())
        for k in range(forces.shape[0]):
            total += element_load(ratios[k, p], factors[k, p], forces[k, p])
        for k in range(forces.shape[0]):
            out[k, p] = driver_codes(forces[k, p], rel[k, p], SCALE_BOUND * total)
    return out


def exact_codes(bodies, ratios, forces, factors, rel, load, frame) -> np.ndarray:
    return np.stack([read_codes(bodies, ratios[:, p], forces[:, p], factors[:, p], rel[:, p],
                                load[:, p], frame) for p in range(forces.shape[1])], axis=1)


@SETTINGS
@given(direction_problems())
def test_a_code_read_on_the_bound_is_the_own_scale_code(problem) -> None:
    """Where the bound names a driver, or the relative speed is zero, its code is the
    single solver's; elsewhere the bound says 0 (undecided: the kernels leave the variant
    to numpy)."""
    bound, exact = bound_codes(*problem), exact_codes(*problem)
    rel = problem[4]
    decided = (bound != 0) | (rel == 0.0)
    assert bound[decided].tolist() == exact[decided].tolist()
    assert np.all(bound[~decided] == 0)


@SETTINGS
@given(direction_problems())
def test_the_bound_is_above_every_own_scale(problem) -> None:
    """SCALE_BOUND * (Σ external + Σ element_load) >= the largest load on any body, summed
    in own_scales' order: the inequality the decided codes rest on."""
    bodies, ratios, forces, factors, rel, load, frame = problem
    for p in range(forces.shape[1]):
        body_load = load[:, p].copy()
        for column in range(3):
            for k in range(forces.shape[0]):
                body_load[bodies[k, column]] += abs(
                    element_stencil(ratios[k, p], factors[k, p])[column] * forces[k, p])
        total = 0.0 + sum(load[:, p].tolist()) + sum(
            element_load(ratios[k, p], factors[k, p], forces[k, p])
            for k in range(forces.shape[0]))
        assert body_load.max() <= SCALE_BOUND * total


@SETTINGS
@given(finite, st.floats(1e-3, 1e3), st.sampled_from([math.inf, -math.inf, math.nan]))
def test_a_force_that_is_not_finite_makes_the_bound_not_finite(ratio, factor, bad) -> None:
    """The sweep's kernels test a force system's finiteness once, on its bound: an
    element's load is not finite when its force is not (whatever its ratio, even 0)."""
    assert not math.isfinite(element_load(ratio, factor, bad))
    assert not math.isfinite(SCALE_BOUND * (1.0 + element_load(ratio, factor, bad)))


def test_ordinary_trains_are_decided_on_the_bound() -> None:
    """Not a vacuous bound: a pair on the frame (bodies 1, 2) with 10 N*m on another body
    (3) names its driver from forces far below the 10 N*m; only a force under 1e-10 of
    all the train's torques is left undecided, though its own bodies carry nothing else."""
    args = lambda force: (np.array([[1, 2, 0]]), np.array([[-1.0]]),  # noqa: E731
                          np.array([[force]]), np.ones((1, 1)), np.array([[1.0]]),
                          np.array([[0.0], [0.0], [0.0], [10.0]]), 0)
    assert bound_codes(*args(1.0))[0, 0] == -1
    assert bound_codes(*args(-1e-6))[0, 0] == 1
    undecided = 5e-10   # its own scale is itself; 10 * 1e-10 = 1e-9 on the bound
    assert exact_codes(*args(undecided))[0, 0] == -1
    assert bound_codes(*args(undecided))[0, 0] == 0


@pytest.mark.parametrize("t", np.linspace(0.98, 1.02, 41))
def test_read_codes_at_the_round_off_threshold(t: float) -> None:
    """A pair on the frame with 1 N*m on gear a's body and a force of ``t`` times
    FORCE_NOISE: it passes nothing while the force is at most FORCE_NOISE times the
    largest torque on its bodies (1 + the force); read on the bound, never another
    code."""
    bodies = np.array([[1, 2, 0]])
    force = t * FORCE_NOISE
    expected = 0 if force <= FORCE_NOISE * (1.0 + force) else -1
    assert read_codes(bodies, np.array([-1.0]), np.array([force]), np.array([1.0]),
                      np.array([1.0]), np.array([0.0, 1.0, 0.0]), 0).tolist() == [expected]
    bound = bound_codes(bodies, np.array([[-1.0]]), np.array([[force]]), np.ones((1, 1)),
                        np.ones((1, 1)), np.array([[0.0], [1.0], [0.0]]), 0)[0, 0]
    assert bound in (0, expected)


def test_an_element_only_on_the_frame_takes_the_largest_load() -> None:
    """Every body of the element is the frame: its scale is the largest torque on any body
    (own_scales' rule), so a force of 1e-11 against a 1 N*m load elsewhere is round-off."""
    args = (np.array([[0, 0, 0], [1, 2, 0]]), np.array([[-1.0], [-1.0]]),
            np.array([[1e-11], [1.0]]), np.ones((2, 1)), np.array([[1.0], [1.0]]),
            np.array([[0.0], [1.0], [0.0]]), 0)
    assert exact_codes(*args)[:, 0].tolist() == [0, -1]
    assert bound_codes(*args)[:, 0].tolist() == [0, -1]


values = st.one_of(finite, st.just(0.0), st.just(1.0), st.just(math.nan),
                   st.just(math.inf), st.just(-math.inf), st.floats(-1e-300, 1e-300))


@SETTINGS
@given(values, values)
def test_flow_efficiency_point_is_flow_efficiency_of_roles(p_in, p_out) -> None:
    expected = float(flow_efficiency_of_roles(np.array([p_in]), np.array([p_out]))[0])
    got = flow_efficiency_point(p_in, p_out)
    assert got == expected or (math.isnan(got) and math.isnan(expected))


@pytest.mark.parametrize("above", [False, True])
def test_a_force_exactly_at_the_threshold_passes_nothing(above: bool) -> None:
    """Ratio 1 and factor 1 put no torque on the carrier (``i f - 1 = 0``); with gears a
    and b on the frame, the element's own scale is the 1 N*m on its carrier's body alone,
    so a force of exactly FORCE_NOISE is round-off and the next float up is not."""
    force = FORCE_NOISE if not above else np.nextafter(FORCE_NOISE, 1.0)
    expected = -1 if above else 0
    assert read_codes(np.array([[0, 0, 1]]), np.array([1.0]), np.array([force]),
                      np.array([1.0]), np.array([1.0]), np.array([0.0, 1.0]), 0
                      ).tolist() == [expected]
    assert driver_codes(force, 1.0, 1.0) == expected


@pytest.fixture(scope="module")
def compiled():
    """The sweep kernels' compiled rules (numba)."""
    pytest.importorskip("numba")
    from powergraph.analyses.sweep import kernel

    return kernel


@SETTINGS
@given(values, values, values, st.floats(-1e-15, 1e-15))
def test_the_compiled_relative_speed_is_numpys(compiled, w_a, w_b, w_c, nudge) -> None:
    """The kernels compile :func:`relative_speed` on floats, its selection a branch: the
    same number as numpy's, NaN and infinities included."""
    for c in (w_c, w_a * (1.0 + nudge) if math.isfinite(w_a) else w_c):
        with np.errstate(invalid="ignore"):     # inf - inf: NaN in both
            expected = float(relative_speed(np.array([w_a]), np.array([w_b]),
                                            np.array([c]))[0])
        got = compiled.jit_relative_speed(w_a, w_b, c)
        assert got == expected or (math.isnan(got) and math.isnan(expected))


@SETTINGS
@given(force, st.one_of(values, st.just(0.0)), st.one_of(values, st.floats(0.0, 1e3)))
def test_the_compiled_driver_codes_are_numpys(compiled, force, rel, scale) -> None:
    with np.errstate(invalid="ignore"):
        expected = int(driver_codes(np.array([force]), np.array([rel]), np.array([scale]))[0])
    assert compiled.jit_driver_codes(force, rel, scale) == expected
