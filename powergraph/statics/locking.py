"""When the fixed-point iteration cycles: every consistent direction pattern, the choice
among several, or the locking verdict (docs/locking.md).

A pattern found by :mod:`powergraph.statics.search` is confirmed with the project's own
torque balance (the same noise rule as the fast path). Several confirmed solutions: the
one of least total loss is taken (for the given loads it delivers the most power). None:
the train is LOCKED — it cannot move as asked under these loads — and each lossy mesh
whose friction alone is needed for that (with it lossless, the train moves) is named,
with the contradiction its two possible drivers meet.
"""
from __future__ import annotations

from typing import Callable

import numpy as np

from powergraph.kinematics import Element
from powergraph.model.spec import Model
from powergraph.records import record
from powergraph.statics.directions import Pattern, agrees, describe, factor_of, pattern_of
from powergraph.statics.equilibrium import Loads
from powergraph.statics.search import (
    EXHAUSTIVE_LIMIT,
    Statics,
    branch_and_bound,
    enumerate_patterns,
    statics_of,
)

#: Maps factors to element forces and their round-off scales.
ForceSolver = Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]]


@record
class Candidate:
    """A confirmed consistent solution: its pattern, factors and total loss (W)."""

    pattern: Pattern
    factors: np.ndarray
    loss: float


@record
class Decision:
    """What the search decided: the chosen solution (None when locked) and the facts."""

    chosen: Candidate | None
    solutions: int
    complete: bool
    method: str
    locking: tuple[int, ...] = ()      # element indices whose friction locks the train
    reasons: tuple[str, ...] = ()


def decide(model: Model, elements: tuple[Element, ...], loads: Loads, rel: np.ndarray,
           solve: ForceSolver, visited: list[Pattern]) -> Decision:
    """Find every consistent pattern (or the least-loss one) and decide.

    Parameters
    ----------
    model, elements, loads, rel
        The train, its elements, its loads and the elements' relative speeds.
    solve : callable
        Factors to (forces, scales), the project's torque balance.
    visited : list of Pattern
        Patterns the fixed-point iteration went through (for the locking reason).
    """
    st = statics_of(model, elements, loads, rel)
    found, complete, method = _solutions(st, solve)
    if found:
        found.sort(key=lambda c: c.loss)
        return Decision(chosen=found[0], solutions=len(found), complete=complete,
                        method=method)
    locking, reasons = _diagnose(model, st, loads, solve)
    if not reasons:
        locking = st.lossy
        links = ", ".join(f"links[{st.elements[k].link}]" for k in locking)
        reasons = (f"the friction of {links} together locks the train: no direction pattern "
                   "is consistent with the loads (the iteration went through "
                   + ", ".join(describe(p) for p in visited[:4])
                   + "), and no one of them made lossless frees it",)
    if not complete:
        reasons += ("the search stopped after its limit of linear programs without finding "
                    "a consistent pattern: the lock is likely but not proven",)
    return Decision(chosen=None, solutions=0, complete=complete, method=method,
                    locking=locking, reasons=reasons)


def _solutions(st: Statics, solve: ForceSolver,
               first: bool = False) -> tuple[list[Candidate], bool, str]:
    """Confirmed solutions, whether the search was complete, and the method used."""
    codes_list = enumerate_patterns(st) if len(st.lossy) <= EXHAUSTIVE_LIMIT else None
    if codes_list is not None:
        out: dict[Pattern, Candidate] = {}
        for codes in codes_list:
            cand = _confirm(st, solve, dict(zip(st.lossy, codes)), {})
            if cand is not None:
                out.setdefault(cand.pattern, cand)
                if first:
                    break
        return list(out.values()), True, "exhaustive"
    lp, complete = branch_and_bound(st, first=first)
    out = {}
    for s in lp:
        cand = _confirm(st, solve, s.codes, s.factors)
        if cand is not None:
            out.setdefault(cand.pattern, cand)
    return list(out.values()), complete, "branch and bound"


def _confirm(st: Statics, solve: ForceSolver, codes: dict[int, int],
             stick: dict[int, float]) -> Candidate | None:
    """The assumed drivers and stick factors, checked with the project's torque balance."""
    factors = np.ones(len(st.elements))
    for k, code in codes.items():
        factors[k] = factor_of(code, st.elements[k].efficiency)
    for k, f in stick.items():
        factors[k] = f
    forces, scales = solve(factors)
    found = pattern_of(forces, st.rel, scales)
    if not agrees(tuple(codes.values()), tuple(found[k] for k in codes)):
        return None
    loss = float(np.sum(-forces * st.rel * (1.0 - factors)))
    return Candidate(pattern=found, factors=factors, loss=loss)


def _diagnose(model: Model, st: Statics, loads: Loads,
              solve: ForceSolver) -> tuple[tuple[int, ...], tuple[str, ...]]:
    """Elements whose friction alone locks the train, each with its contradiction."""
    locking, reasons = [], []
    for k in st.lossy:
        freed = statics_of(model, st.elements, loads, st.rel, st.ideal | {k})

        def lossless_k(factors: np.ndarray, k=k) -> tuple[np.ndarray, np.ndarray]:
            factors = factors.copy()
            factors[k] = 1.0
            return solve(factors)

        moves, _, _ = _solutions(freed, lossless_k, first=True)
        if moves:
            locking.append(k)
            reasons.append(_contradiction(model, st, k, moves[0], solve))
    return tuple(locking), tuple(reasons)


def _contradiction(model: Model, st: Statics, k: int, moving: Candidate,
                   solve: ForceSolver) -> str:
    """What each driver of element ``k`` implies, the others as in ``moving``."""
    e, raw = st.elements[k], model.raw_id
    powers = []
    for f in (e.efficiency, 1.0 / e.efficiency):
        factors = moving.factors.copy()
        factors[k] = f
        forces, _ = solve(factors)
        powers.append(float(-forces[k] * st.rel[k]))
    a, b = raw(e.a), raw(e.b)
    name = f"links[{e.link}] ({e.kind} {a}-{b}, carrier {raw(e.carrier)}, η {e.efficiency:g})"
    if powers[0] < 0 < powers[1]:
        return (f"{name}: with {a} driving in the carrier's frame the loads make {a} take "
                f"power out ({powers[0]:.4g} W), with {b} driving they make {a} feed power in "
                f"({powers[1]:.4g} W); its friction would have to supply power, so it sticks")
    return f"{name}: its friction holds the train; lossless, the train moves as asked"
