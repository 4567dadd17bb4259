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

from typing import Callable

import numpy as np

from powergraph.kinematics import Element, Kinematics, element_stencil

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
    out = np.empty(len(elements))
    for k, e in enumerate(elements):
        w_a, w_b, w_c = (kin.body_speeds[b] for b in e.bodies)
        rel = w_a - w_c
        out[k] = 0.0 if abs(rel) <= SPEED_NOISE * max(abs(w_a), abs(w_b), abs(w_c)) else rel
    return out


def force_scales(elements: tuple[Element, ...], forces: np.ndarray, factors: np.ndarray,
                 external: dict[str, float], frame_body: str) -> np.ndarray:
    """Per element, the largest sum of torque magnitudes on one of its own moving bodies.

    The frame is left out (it collects every reaction of the train), unless the element
    touches nothing else. A force far below this scale is round-off: nothing passes.
    """
    load: dict[str, float] = {b: abs(t) for b, t in external.items()}
    for e, force, f in zip(elements, forces, factors):
        for body, c in zip(e.bodies, element_stencil(e.ratio, f)):
            load[body] = load.get(body, 0.0) + abs(c * force)
    scales = np.empty(len(elements))
    for k, e in enumerate(elements):
        own = [load.get(b, 0.0) for b in e.bodies if b != frame_body]
        scales[k] = max(own) if own else max(load.values(), default=0.0)
    return scales


def pattern_of(forces: np.ndarray, rel: np.ndarray, scales: np.ndarray) -> Pattern:
    """Who drives each element: the sign of the power gear a feeds in, ``-λ (w_a - w_c)``;
    0 where the relative speed is zero or the force is round-off on its own scale."""
    return tuple(0 if r == 0.0 or abs(lam) <= FORCE_NOISE * s else int(np.sign(-lam * r))
                 for lam, r, s in zip(forces, rel, scales))


def factors_of(pattern: Pattern, elements: tuple[Element, ...]) -> np.ndarray:
    """``f = η`` where gear a drives, ``1/η`` where gear b drives, 1 where nothing passes."""
    eta = np.array([e.efficiency for e in elements])
    code = np.array(pattern, dtype=float)
    return np.where(code > 0, eta, np.where(code < 0, 1.0 / eta, 1.0))


def agrees(assumed: Pattern, found: Pattern) -> bool:
    """An assumed pattern is self-consistent when the forces it gives pass power the
    assumed way in every element (an element passing nothing agrees with any driver)."""
    return all(f == 0 or f == a for a, f in zip(assumed, found))


def settle(solve: ForceSolver, elements: tuple[Element, ...],
           rel: np.ndarray) -> tuple[Pattern | None, int, list[Pattern]]:
    """Iterate ``pattern -> factors -> forces -> pattern`` to a self-consistent pattern.

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
        if following == pattern:
            return pattern, passes, history
        if following in history:
            return None, passes, history
        history.append(following)
        pattern = following
    return None, MAX_PASSES, history


def describe(pattern: Pattern) -> str:
    """``[a b -]``: the driver of each element (a, b, or - when nothing passes)."""
    return "[" + " ".join({1: "a", -1: "b", 0: "-"}[c] for c in pattern) + "]"
