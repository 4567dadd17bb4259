"""Power direction in each element's carrier frame, and the fixed-point iteration on it.

The basic efficiency of a mesh applies to the power it passes in its carrier's frame, in
the direction that power flows there (DESIGN §3). The direction depends on the torques,
which depend on the efficiencies: start ideal, read the directions, rebuild, re-solve,
until the directions stop changing. A cycle with no self-consistent member is an error.
"""
from __future__ import annotations

from typing import Callable

import numpy as np

from powergraph.errors import SolveError
from powergraph.kinematics import Element, Kinematics

#: A driver code per element: +1 gear a drives, -1 gear b drives, 0 no power passes.
Pattern = tuple[int, ...]

MAX_PASSES = 64


def relative_speeds(elements: tuple[Element, ...], kin: Kinematics) -> np.ndarray:
    """``w_a - w_c`` of each element (speed of gear a in its carrier's frame)."""
    return np.array([kin.body_speeds[e.body_a] - kin.body_speeds[e.body_c] for e in elements])


def pattern_of(forces: np.ndarray, rel: np.ndarray, tolerance: float) -> Pattern:
    """Who drives each element: the sign of the power gear a feeds in, ``-λ (w_a - w_c)``."""
    power_a = -forces * rel
    return tuple(int(np.sign(p)) if abs(p) > tolerance else 0 for p in power_a)


def factors_of(pattern: Pattern, elements: tuple[Element, ...]) -> np.ndarray:
    """``f = η`` where gear a drives, ``1/η`` where gear b drives, 1 where nothing passes."""
    eta = np.array([e.efficiency for e in elements])
    code = np.array(pattern, dtype=float)
    return np.where(code > 0, eta, np.where(code < 0, 1.0 / eta, 1.0))


def settle(solve: Callable[[np.ndarray], np.ndarray], elements: tuple[Element, ...],
           rel: np.ndarray, tolerance: float) -> tuple[Pattern, int]:
    """Iterate ``pattern -> factors -> forces -> pattern`` to a self-consistent pattern.

    Parameters
    ----------
    solve : callable
        Maps factors (one per element) to element forces ``λ``.
    elements, rel, tolerance
        The elements, their relative speeds and the power below which nothing passes.

    Returns
    -------
    (pattern, passes)

    Raises
    ------
    SolveError
        When the iteration cycles and no pattern of the cycle is self-consistent.
    """
    pattern = pattern_of(solve(np.ones(len(elements))), rel, tolerance)
    history: list[Pattern] = [pattern]
    for passes in range(1, MAX_PASSES + 1):
        following = pattern_of(solve(factors_of(pattern, elements)), rel, tolerance)
        if following == pattern:
            return pattern, passes
        if following in history:
            cycle = history[history.index(following):]
            raise SolveError(
                "power directions did not settle: the iteration cycles between "
                + " and ".join(_describe(p) for p in cycle)
                + "; no consistent direction pattern exists at this operating point")
        history.append(following)
        pattern = following
    raise SolveError(f"power directions did not settle in {MAX_PASSES} passes")


def _describe(pattern: Pattern) -> str:
    return "[" + " ".join({1: "a", -1: "b", 0: "-"}[c] for c in pattern) + "]"
