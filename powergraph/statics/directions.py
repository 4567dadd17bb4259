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

import math
from functools import lru_cache
from typing import Callable

import numpy as np

from powergraph.kinematics import Element, Kinematics, element_stencil
from powergraph.kinematics.elements import ELEMENT_BODIES, body_columns
from powergraph.linalg import PLAIN_UP_TO

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


def relative_speed(w_a, w_b, w_c):
    """``w_a - w_c`` (arrays of any one shape, or floats), exactly 0 where it is round-off
    on the scale of the three speeds (:data:`SPEED_NOISE`): the one rule for a relative
    speed that is zero, for one operating point or many.

    >>> relative_speed(np.array([1.0, 1.0]), np.array([2.0, 2.0]), np.array([0.5, 1.0 - 1e-16]))
    array([0.5, 0. ])
    """
    w_a, w_b, w_c = np.asarray(w_a, float), np.asarray(w_b, float), np.asarray(w_c, float)
    rel = w_a - w_c
    top = np.maximum(np.maximum(np.abs(w_a), np.abs(w_b)), np.abs(w_c))
    return np.where(np.abs(rel) <= SPEED_NOISE * top, 0.0, rel)


def relative_speed_point(w_a: float, w_b: float, w_c: float) -> float:
    """:func:`relative_speed` of one element at one point, on floats: plain Python that a
    compiler of scalar loops (the sweep's numba kernels) takes as it is; the same
    operations in the same order, so the same number.

    >>> relative_speed_point(1.0, 2.0, 0.5), relative_speed_point(1.0, 2.0, 1.0 - 1e-16)
    (0.5, 0.0)
    """
    rel = w_a - w_c
    top = nan_max(nan_max(abs(w_a), abs(w_b)), abs(w_c))
    return 0.0 if abs(rel) <= SPEED_NOISE * top else rel


def nan_max(a: float, b: float) -> float:
    """``np.maximum`` on two floats (NaN when either is NaN), in plain Python.

    >>> nan_max(1.0, 2.0), nan_max(float("nan"), 2.0), nan_max(2.0, float("nan"))
    (2.0, nan, nan)
    """
    return a if (a >= b or a != a) else b


def force_scales(elements: tuple[Element, ...], forces: np.ndarray, factors: np.ndarray,
                 external: dict[str, float], frame_body: str) -> np.ndarray:
    """Per element, the largest sum of torque magnitudes on one of its own moving bodies.

    The frame is left out (it collects every reaction of the train), unless the element
    touches nothing else. A force far below this scale is round-off: nothing passes.
    """
    bodies, outside, n_bodies, frame = _columns(tuple(map(ELEMENT_BODIES, elements)),
                                                tuple(external), frame_body)
    if len(elements) <= PLAIN_UP_TO:
        return np.array(own_scales_plain(bodies.tolist(), [e.ratio for e in elements],
                                         np.asarray(forces, dtype=float).tolist(),
                                         np.asarray(factors, dtype=float).tolist(),
                                         _external_load(n_bodies, outside, external), frame))
    load = np.zeros(n_bodies)
    np.add.at(load, outside, np.abs(np.array(list(external.values()), dtype=float)))
    ratios = np.array([e.ratio for e in elements], dtype=float)
    return own_scales(bodies, ratios, forces, np.asarray(factors, dtype=float), load, frame)


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


def _external_load(n_bodies: int, outside: np.ndarray, external: dict) -> list[float]:
    load = [0.0] * n_bodies
    for body, torque in zip(outside.tolist(), external.values()):
        load[body] += abs(torque)
    return load


def own_scales_plain(bodies: list, ratios: list, forces: list, factors: list,
                     load: list, frame: int) -> list[float]:
    """:func:`own_scales` of one operating point on plain Python floats (a few elements:
    no numpy call costs more than the arithmetic). ``load`` is changed: each element's
    torque magnitudes are added to its bodies'.

    >>> own_scales_plain([[1, 2, 0]], [-2.0], [3.0], [1.0], [0.0, 0.0, 0.0], 0)
    [6.0]
    """
    for (a, b, c), ratio, force, factor in zip(bodies, ratios, forces, factors):
        on_a, on_b, on_c = element_stencil(ratio, factor)
        load[a] += abs(on_a * force)
        load[b] += abs(on_b * force)
        load[c] += abs(on_c * force)
    top = max(load, default=0.0)
    scales = []
    for triple in bodies:
        own = -math.inf
        for body in triple:
            if body != frame and load[body] > own:
                own = load[body]
        scales.append(own if own > -math.inf else top)
    return scales


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

    Examples
    --------
    A pair on the frame (bodies 1, 2; frame 0) with ratio -2 and force 3: the torques on
    gear a and gear b are 3 and 6, so its scale is 6.

    >>> own_scales(np.array([[1, 2, 0]]), np.array([-2.0]), np.array([3.0]),
    ...            np.array([1.0]), np.zeros(3), 0).tolist()
    [6.0]
    """
    load = np.array(load, dtype=float)
    ratios = np.asarray(ratios, dtype=float)
    if ratios.ndim < forces.ndim:
        ratios = ratios[:, None]
    stencil = element_stencil(ratios, factors)
    if forces.ndim == 1:
        for column, c in enumerate(stencil):
            np.add.at(load, bodies[:, column], np.abs(c * forces))
        own = np.where(bodies == frame, -np.inf, load[bodies]).max(axis=1, initial=-np.inf)
    else:   # many points: a row operation per (element, body) beats np.add.at
        for column, c in enumerate(stencil):
            terms = np.abs(c * forces)
            for k, body in enumerate(bodies[:, column].tolist()):
                load[body] += terms[k]
        own = np.full(forces.shape, -np.inf)
        for k, triple in enumerate(bodies.tolist()):
            for body in triple:
                if body != frame:
                    np.maximum(own[k], load[body], out=own[k])
    return np.where(np.isfinite(own), own, load.max(axis=0, initial=0.0))


def driver_codes(forces: np.ndarray, rel: np.ndarray, scales: np.ndarray) -> np.ndarray:
    """Who drives each element, as an array of the shape of ``forces``: the sign of the
    power gear a feeds in, ``-λ (w_a - w_c)``; 0 where the relative speed is zero or the
    force is round-off on its own scale.

    >>> driver_codes(np.array([-1.0, 1e-13]), np.array([2.0, 2.0]), np.array([1.0, 1.0]))
    array([1, 0])
    """
    forces, rel = np.asarray(forces), np.asarray(rel)
    code = np.sign(-forces * rel).astype(int)
    code[(rel == 0.0) | (np.abs(forces) <= FORCE_NOISE * np.asarray(scales))] = 0
    return code


def pattern_of(forces: np.ndarray, rel: np.ndarray, scales: np.ndarray) -> Pattern:
    """Who drives each element (:func:`driver_codes`), as a pattern.

    >>> pattern_of(np.array([-1.0, 1e-13, 2.0]), np.array([2.0, 2.0, 0.0]), np.ones(3))
    (1, 0, 0)
    """
    if len(forces) > PLAIN_UP_TO:
        return tuple(driver_codes(forces, rel, scales).tolist())
    return tuple(driver_code(force, speed, scale)     # on plain floats (a few elements)
                 for force, speed, scale in zip(np.asarray(forces, dtype=float).tolist(),
                                                np.asarray(rel, dtype=float).tolist(),
                                                np.asarray(scales, dtype=float).tolist()))


def driver_code(force: float, rel: float, scale: float) -> int:
    """:func:`driver_codes` of one element at one point, on floats: plain Python that the
    single solve runs as it is and the sweep's numba kernels compile. 0 also where
    ``-λ (w_a - w_c)`` is NaN (which :func:`driver_codes` leaves undefined).

    >>> driver_code(-1.0, 2.0, 1.0), driver_code(1e-13, 2.0, 1.0), driver_code(1.0, 2.0, 1.0)
    (1, 0, -1)
    """
    power = -force * rel
    if rel == 0.0 or abs(force) <= FORCE_NOISE * scale:
        return 0
    return 1 if power > 0.0 else (-1 if power < 0.0 else 0)


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
        # Every own scale is at most the sum of all torques: a force above the noise of
        # that sum is not round-off, whatever its own scale; only the points with a force
        # below it need their own scales.
        ratio = np.asarray(ratios, dtype=float)
        total = np.asarray(load, dtype=float).sum(axis=0)
        for c in element_stencil(ratio if ratio.ndim == 2 else ratio[:, None], factors):
            total = total + np.abs(c * forces).sum(axis=0)
        unclear = np.flatnonzero(np.any(np.abs(forces) <= FORCE_NOISE * total, axis=0))
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


def element_load(ratio: float, factor: float, force: float) -> float:
    """The torque magnitudes an element puts on its gear a, gear b and carrier, summed
    (the terms :func:`own_scales` adds to those bodies' loads), for one point on floats.

    An own scale is the load on one body, or the largest on any: at most
    ``SCALE_BOUND * (Σ |external torques| + Σ element_load)``. Read on that bound,
    :func:`driver_code` only ever says "nothing passes" more often: **where it names a
    driver, or the relative speed is zero, its code is the own-scale rule's code** (the
    force test is the only place the scale enters, and it is monotonic in the scale). The
    sweep's numba kernels use this to read the directions of a variant in a few operations
    per element, and leave the variants it cannot decide to the own-scale rule.

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
