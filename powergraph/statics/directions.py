"""Power direction in each element's carrier frame, and the fixed-point iteration on it.

The basic efficiency of a mesh applies to the power it passes in its carrier's frame, in
the direction that power flows there (docs/theory.md). The direction depends on the
torques, which depend on the efficiencies: start ideal, read the directions, rebuild,
re-solve, until the directions stop changing. This is the fast path; when it cycles, the
complementarity search of :mod:`powergraph.statics.locking` decides (docs/locking.md).

"Nothing passes" is decided on each element's own scale, never against an absolute power
floor: an element passes nothing when its relative speed is zero on the scale of its own
bodies' speeds, or when its force is round-off on the scale of the torques acting on its
own bodies.
"""
from __future__ import annotations

from functools import lru_cache
from typing import Callable

import numpy as np

from powergraph.kinematics import Element, Kinematics, element_stencil
from powergraph.kinematics.elements import ELEMENT_BODIES, body_columns

#: A driver code per element: +1 gear a drives, -1 gear b drives, 0 no power passes.
Pattern = tuple[int, ...]

MAX_PASSES = 64
#: Relative speeds below this fraction of the element's own body speeds are zero.
SPEED_NOISE = 1e-12
#: Forces below this fraction of the torques acting on the element's own bodies are zero.
FORCE_NOISE = 1e-10

#: Maps factors (one per element) to element forces ``λ`` and their round-off scales.
ForceSolver = Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]]


def relative_speeds(elements: tuple[Element, ...], kin: Kinematics) -> np.ndarray:
    """``w_a - w_c`` of each element (speed of gear a in its carrier's frame).

    Exactly 0 where it is round-off on the scale of the element's own three speeds.

    >>> import powergraph as pg
    >>> from powergraph.kinematics import elements_of, solve_speeds
    >>> m = pg.load_model("models/bevel_differential.yaml")            # doctest: +SKIP
    >>> relative_speeds(elements_of(m), solve_speeds(m, {"case": 1, "L": 1}))  # doctest: +SKIP
    array([0., 0.])
    """
    speeds = kin.body_speeds
    w = body_columns(elements, speeds).astype(float).reshape(-1, 3)
    return relative_speed(w[:, 0], w[:, 1], w[:, 2])


def where(condition, x, y):
    """``np.where(condition, x, y)``: the one selection the per-value rules make. The
    sweep's kernels compile those rules on floats with this name bound to ``x if
    condition else y`` (numba's own ``np.where`` makes an array of a float).

    >>> where(np.array([True, False]), 0, np.array([1, 2])).tolist()
    [0, 2]
    """
    return np.where(condition, x, y)


def relative_speed(w_a, w_b, w_c):
    """``w_a - w_c`` (arrays of any one shape, 0-d for one value), exactly 0 where it is
    round-off on the scale of the three speeds (:data:`SPEED_NOISE`): the one rule for a
    relative speed that is zero, for one operating point or many.

    >>> relative_speed(np.array([1.0, 1.0]), np.array([2.0, 2.0]), np.array([0.5, 1.0 - 1e-16]))
    array([0.5, 0. ])
    """
    rel = w_a - w_c
    top = np.maximum(np.maximum(np.abs(w_a), np.abs(w_b)), np.abs(w_c))
    return where(np.abs(rel) <= SPEED_NOISE * top, 0.0, rel)


def force_scales(elements: tuple[Element, ...], forces: np.ndarray, factors: np.ndarray,
                 external: dict[str, float], frame_body: str) -> np.ndarray:
    """Per element, the largest sum of torque magnitudes on one of its own moving bodies
    (:func:`own_scales` of one operating point).

    The frame is left out (it collects every reaction of the train), unless the element
    touches nothing else. A force far below this scale is round-off: nothing passes.
    """
    bodies, outside, n_bodies, frame = _columns(tuple(map(ELEMENT_BODIES, elements)),
                                                tuple(external), frame_body)
    load = np.zeros(n_bodies)
    load[outside] = np.abs(np.fromiter(external.values(), dtype=float, count=len(external)))
    ratios = np.array([e.ratio for e in elements], dtype=float)
    return own_scales(bodies, ratios, np.asarray(forces, dtype=float),
                      np.asarray(factors, dtype=float), load, frame)


@lru_cache(maxsize=64)
def _columns(triples: tuple[tuple[str, str, str], ...], external: tuple[str, ...],
             frame_body: str) -> tuple[np.ndarray, np.ndarray, int, int]:
    """:func:`force_scales`' body columns: each element's three, the externally loaded
    bodies', how many bodies, the frame's (-1 if no element touches it). Kept for the last
    few structures (each solve of a train asks for the same one several times)."""
    index: dict[str, int] = {}
    for triple in triples:
        for b in triple:
            if b not in index:
                index[b] = len(index)
    bodies = np.array([[index[b] for b in triple] for triple in triples],
                      dtype=np.int64).reshape(-1, 3)
    outside = np.array([index.setdefault(b, len(index)) for b in external], dtype=np.int64)
    frame = index.get(frame_body, -1)
    bodies.flags.writeable = outside.flags.writeable = False
    return bodies, outside, len(index), frame


def own_scales(bodies: np.ndarray, ratios: np.ndarray, forces: np.ndarray,
               factors: np.ndarray, load: np.ndarray, frame: int) -> np.ndarray:
    """:func:`force_scales` on arrays, for one operating point or many at once.

    Parameters
    ----------
    bodies : (E, 3) int array
        Each element's gear a, gear b and carrier as body columns.
    ratios : (E,) array, or (E, P) with ``forces``
    forces, factors : (E,) or (E, P) arrays
        Element forces and factors (a column per operating point).
    load : (B,) or (B, P) array
        The magnitudes of the external torques on each body.
    frame : int
        The frame's body column (-1 if none).

    Each body's load is its external torque plus the element torques on it, added in
    element order for gear a, then gear b, then the carrier (one ``bincount``).

    Examples
    --------
    A pair on the frame (bodies 1, 2; frame 0) with ratio -2 and force 3: the torques on
    gear a and gear b are 3 and 6, so its scale is 6.

    >>> own_scales(np.array([[1, 2, 0]]), np.array([-2.0]), np.array([3.0]),
    ...            np.array([1.0]), np.zeros(3), 0).tolist()
    [6.0]
    """
    forces = np.asarray(forces, dtype=float)
    ratios = np.asarray(ratios, dtype=float)
    if ratios.ndim < forces.ndim:
        ratios = ratios[:, None]
    n_el, n_bodies = len(bodies), len(load)
    points = forces.size // n_el if n_el else 1
    load = np.asarray(load, dtype=float).reshape(n_bodies, -1)
    if load.shape[1] != points:
        load = np.broadcast_to(load, (n_bodies, points))
    index, on_frame = _own_places(np.asarray(bodies, dtype=np.int64).tobytes(), n_el, n_bodies,
                                  points, frame)
    weights = np.concatenate([load.ravel()] + [(c * forces).ravel()
                                               for c in element_stencil(ratios, factors)])
    np.abs(weights[load.size:], out=weights[load.size:])
    total = np.bincount(index, weights, minlength=n_bodies * points).reshape(n_bodies, points)
    own = np.where(on_frame, -np.inf, total[bodies]).max(axis=1)
    if not np.isfinite(own).all():
        own = np.where(np.isfinite(own), own, total.max(axis=0, initial=0.0))
    return own.reshape(forces.shape)


@lru_cache(maxsize=64)
def _own_places(bodies: bytes, n_el: int, n_bodies: int, points: int,
                frame: int) -> tuple[np.ndarray, np.ndarray]:
    """:func:`own_scales`' bins, body by point: the external loads', then each element's
    on its gear a, gear b and carrier in turn; and where an element's body is the frame."""
    places = np.frombuffer(bodies, dtype=np.int64).reshape(n_el, 3)
    index = np.concatenate([np.arange(n_bodies * points),
                            (places.T[:, :, None] * points + np.arange(points)).ravel()])
    on_frame = (places == frame)[:, :, None]
    index.flags.writeable = on_frame.flags.writeable = False
    return index, on_frame


def driver_codes(forces, rel, scales):
    """Who drives each element, of the shape of ``forces`` (0-d for one value): the sign
    of the power gear a feeds in, ``-λ (w_a - w_c)``; 0 where the relative speed is zero,
    the force is round-off on its own scale, or that power is NaN.

    >>> driver_codes(np.array([-1.0, 1e-13, 1.0]), np.array([2.0, 2.0, 2.0]), np.ones(3))
    array([ 1,  0, -1])
    """
    taken = forces * rel        # minus the power gear a feeds in
    nothing = (rel == 0.0) | (np.abs(forces) <= FORCE_NOISE * scales)
    return where(nothing, 0, where(taken < 0.0, 1, where(taken > 0.0, -1, 0)))


def pattern_of(forces: np.ndarray, rel: np.ndarray, scales: np.ndarray) -> Pattern:
    """Who drives each element (:func:`driver_codes`), as a pattern.

    >>> pattern_of(np.array([-1.0, 1e-13, 2.0]), np.array([2.0, 2.0, 0.0]), np.ones(3))
    (1, 0, 0)
    """
    return tuple(driver_codes(np.asarray(forces, dtype=float), np.asarray(rel, dtype=float),
                              np.asarray(scales, dtype=float)).tolist())


def read_codes(bodies: np.ndarray, ratios: np.ndarray, forces: np.ndarray,
               factors: np.ndarray, rel: np.ndarray, load: np.ndarray,
               frame: int) -> np.ndarray:
    """Who drives each element, for one operating point (``(E,)`` arrays) or many
    (``(E, P)``): :func:`driver_codes` on the scales of :func:`own_scales`. Every evaluator
    reads its directions here.

    >>> read_codes(np.array([[1, 2, 0]]), np.array([-2.0]), np.array([3.0]),
    ...            np.array([1.0]), np.array([-1.0]), np.zeros(3), 0).tolist()
    [1]
    """
    forces = np.asarray(forces, dtype=float)
    if forces.ndim == 2:
        # Every own scale is at most the bound of all torques (SCALE_BOUND): a force above
        # the noise of that bound is not round-off, whatever its own scale; only the points
        # with a force below it need their own scales.
        ratio = np.asarray(ratios, dtype=float)
        bound = SCALE_BOUND * (np.asarray(load, dtype=float).sum(axis=0) + element_load(
            ratio if ratio.ndim == 2 else ratio[:, None], factors, forces).sum(axis=0))
        unclear = np.flatnonzero(np.any(np.abs(forces) <= FORCE_NOISE * bound, axis=0))
        codes = driver_codes(forces, rel, np.zeros_like(forces))
        if unclear.size:
            pick = lambda a: np.asarray(a)[..., unclear] if np.ndim(a) == 2 else a  # noqa: E731
            scales = own_scales(bodies, pick(ratios), forces[:, unclear], pick(factors),
                                pick(load), frame)
            codes[:, unclear] = driver_codes(forces[:, unclear], pick(rel), scales)
        return codes
    scales = own_scales(bodies, ratios, forces, factors, load, frame)
    return driver_codes(forces, rel, scales)


#: Every own scale is at most the sum of all torque magnitudes on the train (external and
#: the elements' own, :func:`element_load`) times this factor: the margin covers the
#: rounding of sums of up to 10^6 terms in any order.
SCALE_BOUND = 1.0 + 1e-9


def element_load(ratio, factor, force):
    """The torque magnitudes an element puts on its gear a, gear b and carrier, summed
    (the terms :func:`own_scales` adds to those bodies' loads): arrays of any shapes that
    broadcast, or floats.

    An own scale is the load on one body, or the largest on any: at most
    ``SCALE_BOUND * (Σ |external torques| + Σ element_load)``. Read on that bound,
    :func:`driver_codes` only ever says "nothing passes" more often: **where it names a
    driver, or the relative speed is zero, its code is the own-scale rule's code** (the
    force test is the only place the scale enters, and it is monotonic in the scale).
    :func:`read_codes` uses this to take the own scales only of the points the bound does
    not decide; the sweep's numba kernels to read the directions of a variant in a few
    operations per element, leaving the variants it cannot decide to the own-scale rule.

    >>> element_load(-2.0, 1.0, 3.0)        # 3 on gear a, 6 on gear b, 9 on the carrier
    18.0
    """
    on_a, on_b, on_c = element_stencil(ratio, factor)
    return abs(on_a * force) + abs(on_b * force) + abs(on_c * force)


def factor_of(code: int, efficiency):
    """The factor of one element: ``η`` where gear a drives (code +1), ``1/η`` where gear
    b drives (-1), 1 where nothing passes (0). ``efficiency`` may be a float or a sympy
    expression; for arrays use :func:`factors_for`.

    >>> factor_of(1, 0.5), factor_of(-1, 0.5), factor_of(0, 0.5)
    (0.5, 2.0, 1)
    """
    return efficiency if code > 0 else (1 / efficiency if code < 0 else 1)


def factors_for(codes, efficiencies) -> np.ndarray:
    """:func:`factor_of` over arrays (any shapes that broadcast).

    >>> factors_for(np.array([1, -1, 0]), 0.5).tolist()
    [0.5, 2.0, 1.0]
    """
    codes = np.asarray(codes)
    with np.errstate(divide="ignore"):
        inverse = 1.0 / np.asarray(efficiencies, dtype=float)
    return np.where(codes > 0, efficiencies, np.where(codes < 0, inverse, 1.0))


def factors_of(pattern: Pattern, elements: tuple[Element, ...]) -> np.ndarray:
    """``f = η`` where gear a drives, ``1/η`` where gear b drives, 1 where nothing passes
    (:func:`factor_of` per element)."""
    return np.array([float(factor_of(code, e.efficiency))
                     for code, e in zip(pattern, elements)], dtype=float).reshape(len(elements))


def agreeing(assumed, found) -> np.ndarray:
    """:func:`agrees` over arrays: per operating point (the last axis of ``(E, P)`` codes),
    whether ``found`` agrees with ``assumed`` in every element.

    >>> agreeing(np.array([[1, 1], [-1, -1]]), np.array([[1, 0], [1, -1]])).tolist()
    [False, True]
    """
    assumed, found = np.asarray(assumed), np.asarray(found)
    return np.all((found == 0) | (found == assumed), axis=0)


def agrees(assumed: Pattern, found: Pattern) -> bool:
    """An assumed pattern is self-consistent when the forces it gives pass power the
    assumed way in every element (an element passing nothing agrees with any driver)."""
    return all(f == 0 or f == a for a, f in zip(assumed, found))


def settle(solve: ForceSolver, elements: tuple[Element, ...],
           rel: np.ndarray) -> tuple[Pattern | None, int, list[Pattern]]:
    """Iterate ``pattern -> factors -> forces -> pattern`` to a self-consistent pattern:
    one whose forces pass power the assumed way in every element (:func:`agrees`; an
    element found passing nothing, e.g. past the point where a very long lossy chain's
    power underflows, agrees with its assumed driver).

    Parameters
    ----------
    solve : callable
        Maps factors (one per element) to element forces ``λ`` and their scales
        (:func:`force_scales`).
    elements, rel
        The elements and their relative speeds.

    Returns
    -------
    (pattern, passes, visited)
        ``pattern`` is None when the iteration cycles or does not settle in
        ``MAX_PASSES``; ``visited`` lists the patterns it went through.

    Examples
    --------
    >>> import numpy as np
    >>> from powergraph.kinematics import Element
    >>> pair = (Element(0, "mesh", "1", "2", "0", "1", "2", "0", -2.0, 0.9),)
    >>> settle(lambda f: (np.array([-1.0]), np.array([1.0])), pair, np.array([1.0]))
    ((1,), 1, [(1,)])
    """
    forces, scales = solve(np.ones(len(elements)))
    pattern = pattern_of(forces, rel, scales)
    history: list[Pattern] = [pattern]
    for passes in range(1, MAX_PASSES + 1):
        forces, scales = solve(factors_of(pattern, elements))
        following = pattern_of(forces, rel, scales)
        if agrees(pattern, following):
            return pattern, passes, history
        if following in history:
            return None, passes, history
        history.append(following)
        pattern = following
    return None, MAX_PASSES, history


def describe(pattern: Pattern) -> str:
    """``[a b -]``: the driver of each element (a, b, or - when nothing passes)."""
    return "[" + " ".join({1: "a", -1: "b", 0: "-"}[c] for c in pattern) + "]"
