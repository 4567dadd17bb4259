"""Deciding a mode's freewheels without trying every combination (docs/modes.md).

A mode leaves groups of freewheels to decide (:func:`powergraph.model.modes.freewheel_groups`:
the freewheels joining the same two bodies are one element in parallel). Each group is
**joined** (a rigid joint between its bodies X and Y) or **open**. A combination is kept
when the train then has its designed DOF, every open group slips with a sign all its
members allow, and every joined group carries a torque some member can hold.

The first two conditions need only the speeds. With the base train's speeds written as
``w = N q`` (``N`` a basis of its null space, ``q`` its ``dof0`` free speeds), a joined
group is the row ``(N_X - N_Y) q = 0``. :func:`candidates` walks the combinations as a
tree, group by group (open before joined: the order of ``itertools.product``), and cuts a
branch as soon as every combination below it fails:

- the joined rows already have rank above ``dof0 - need`` (too few DOF whatever the rest
  do), or even all the rest joined cannot reach it (too many DOF);
- the joined rows have that rank: the speeds are fixed for the whole branch, so an open
  group that slips the wrong way, or a group yet undecided that slips the wrong way and
  cannot join without locking the train, condemns it.

Only the leaves left (combinations consistent in speed) are solved for torques, so the
kept combinations, their order and their number are those of the exhaustive search.

Examples
--------
>>> import powergraph as pg
>>> from powergraph.model.modes import freewheel_groups, resolve
>>> base = resolve(pg.load_model("models/simpson_3speed.yaml"), "1")   # doctest: +SKIP
>>> notes = []
>>> list(candidates(base, freewheel_groups(base), 1, notes)), notes     # doctest: +SKIP
([(True,)], ['F1 overrunning leaves 2 DOF'])
"""
from __future__ import annotations

import dataclasses
import itertools
from typing import Iterator, Sequence

import numpy as np

from powergraph.errors import Caveat
from powergraph.kinematics.speeds import constraint_matrix, degrees_of_freedom
from powergraph.model.modes import FreewheelGroup
from powergraph.model.spec import Model
from powergraph.statics.shift_torques import component_torques

#: Torques and slips below this fraction of the largest one are zero.
ZERO = 1e-9
#: Rank decisions: singular values below this fraction of the largest (at least 1) are 0.
RANK_RTOL = 1e-9


class Speeds:
    """The base train's speeds as ``w = N q``, and the rows of its freewheel groups."""

    def __init__(self, base: Model, groups: Sequence[FreewheelGroup], need: int) -> None:
        self.dof = degrees_of_freedom(base)
        column = {b.id: j for j, b in enumerate(base.bodies)}
        self.null = _null_space(constraint_matrix(base), self.dof)
        null = self.null if self.null is not None else np.zeros((len(column), self.dof))
        self.rows = np.array([null[column[g.bodies[0]]] - null[column[g.bodies[1]]]
                              for g in groups]).reshape(len(groups), self.dof)
        given = {p.component: p.speed for p in base.ports if p.speed is not None}
        if not given and need == 1 and base.inputs:
            given = {base.inputs[0].component: 1.0}      # as the kinematics solver does
        self.port_rows = np.array([null[column[base.body_of[c]]] for c in given]
                                  ).reshape(len(given), self.dof)
        self.port_speeds = np.array(list(given.values()), dtype=float)

    def rank(self, joined: Sequence[int]) -> int:
        """The rank of the joined groups' rows."""
        return _rank(self.rows[list(joined)])

    def slips(self, joined: Sequence[int]) -> np.ndarray | None:
        """``w_X - w_Y`` of every group once the joined ones are rigid (zero below
        ``ZERO`` of the largest speed), or None when the speeds are not fixed by the ports
        (the solver will say why)."""
        if self.null is None:
            return None
        matrix = np.vstack([self.rows[list(joined)], self.port_rows])
        rhs = np.concatenate([np.zeros(len(joined)), self.port_speeds])
        if _rank(matrix) < self.dof:
            return None
        q = np.linalg.lstsq(matrix, rhs, rcond=None)[0]
        scale = max(float(np.abs(self.null @ q).max(initial=0.0)), 1e-300)
        if np.abs(matrix @ q - rhs).max(initial=0.0) > ZERO * max(scale, 1.0):
            return None                                  # the ports' speeds contradict
        slips = self.rows @ q
        return np.where(np.abs(slips) <= ZERO * scale, 0.0, slips)


def candidates(base: Model, groups: Sequence[FreewheelGroup], need: int,
               notes: list[str]) -> Iterator[tuple[bool, ...]]:
    """The combinations (joined? per group) consistent in speed, in the order of
    ``itertools.product((False, True), repeat=len(groups))``; why each branch cut fails
    is appended to ``notes``."""
    speeds = Speeds(base, groups, need)
    target = speeds.dof - need
    n = len(groups)
    if speeds.null is None:      # no basis to reason on: every combination is solved
        return itertools.product((False, True), repeat=n)

    def visit(prefix: tuple[bool, ...]) -> Iterator[tuple[bool, ...]]:
        joined = [i for i, on in enumerate(prefix) if on]
        complete = len(prefix) == n
        rank = speeds.rank(joined)
        if rank > target:
            notes.append(_dof_note(groups, prefix, complete, speeds.dof - rank, "at most"))
            return
        top = rank if complete else speeds.rank(joined + list(range(len(prefix), n)))
        if top < target:
            notes.append(_dof_note(groups, prefix, complete, speeds.dof - top, "at least"))
            return
        if rank == target:
            bad = _wrong_slips(speeds, groups, prefix, joined, rank)
            if bad:
                notes.append(f"{_who(groups, prefix, complete)}: {'; '.join(bad)}")
                return
        if complete:
            yield prefix
            return
        yield from visit(prefix + (False,))
        yield from visit(prefix + (True,))

    return visit(())


def _wrong_slips(speeds: Speeds, groups, prefix, joined, rank) -> list[str]:
    """With the speeds fixed: the open groups slipping against every member's sense, and
    the undecided ones that do and cannot join (their row would raise the rank)."""
    slips = speeds.slips(joined)
    if slips is None:
        return []
    bad = []
    for i, group in enumerate(groups):
        if i in joined or all(s * slips[i] >= 0 for s in group.senses):
            continue
        if i < len(prefix):
            bad.append(overrun_note(group, slips[i]))
        elif speeds.rank(joined + [i]) > rank:
            bad.append(overrun_note(group, slips[i]) + ", and holding it would leave "
                       f"{speeds.dof - rank - 1} DOF")
    return bad


def overrun_note(group: FreewheelGroup, slip: float) -> str:
    """Why ``group`` cannot overrun at ``slip`` (``w_X - w_Y``), in the terms of its first
    member that forbids it."""
    k = next(k for k, s in enumerate(group.senses) if s * slip < 0)
    member = group.members[k]
    if len(group.members) == 1:
        who = "it overruns"
    elif len(set(group.senses)) == 1:
        who = "they overrun"
    else:
        who = f"{member.name} overruns"
    return (f"{group.label} overrunning would slip at {group.orients[k] * slip:.6g} rad/s "
            f"({who} {member.holds} only)")


def settle(groups: Sequence[FreewheelGroup], choice: Sequence[bool], result, states: dict,
           scale: float, path: str) -> tuple[list[str], list[Caveat]]:
    """Give each group's members their states in the solved ``result`` (``states``, from
    :func:`powergraph.statics.modes.solve_mode`, updated in place) and say what is wrong.

    A joined group carries the torque ``T`` found by cutting all its members at once (on
    its X side; None when another rigid path joins X and Y). The members whose sense holds
    ``T`` hold (at ``T == 0``, those of the first member's sense); the others overrun at
    zero slip. One holding member carries ``T``; several carry it together, each one's
    share statically indeterminate (``torque`` None, ``parallel_torque`` their total, a
    caveat ``indeterminate``).

    Returns
    -------
    bad : list of str
        Why the combination is inconsistent (empty when it is consistent).
    caveats : list of Caveat
    """
    torques = component_torques(result)
    bad, caveats = [], []
    for group, joined in zip(groups, choice):
        first = states[group.members[0].name]
        if not joined:
            slip = group.orients[0] * first.slip_speed
            if any(s * slip < 0 for s in group.senses):
                bad.append(overrun_note(group, slip))
            continue
        total = cut_torque(result, group, torques)
        if total is not None and abs(total) <= ZERO * scale:
            total = 0.0      # round-off: the sign of a zero torque decides nothing
        sense = None if total is None else (
            group.senses[0] if total == 0 else (1 if total > 0 else -1))
        holders = [k for k, s in enumerate(group.senses) if sense is None or s == sense]
        if not holders:
            they = "it holds" if len(group.members) == 1 else "they hold"
            bad.append(f"{group.label} holding would carry "
                       f"{group.orients[0] * total:.6g} N·m ({they} "
                       f"{group.members[0].holds} only)")
            continue
        names = tuple(group.names[k] for k in holders) if len(holders) > 1 else ()
        for k, member in enumerate(group.members):
            own = None if total is None else group.orients[k] * total
            states[member.name] = dataclasses.replace(
                states[member.name], state="holding" if k in holders else "overrunning",
                torque=own if k in holders and not names else None,
                parallel=names if k in holders else (),
                parallel_torque=own if k in holders and names else None)
        if names:
            k = holders[0]
            together = ("also indeterminate: another rigid path joins the same members"
                        if total is None else
                        f"together {group.orients[k] * total:.6g} N·m on "
                        f"{group.members[k].between[0]}")
            caveats.append(Caveat(f"{', '.join(names)} hold together in parallel: the torque "
                                  f"each carries is statically indeterminate ({together})",
                                  path, "indeterminate"))
    return bad, caveats


def cut_torque(result, group: FreewheelGroup, torques: dict[str, float]) -> float | None:
    """The torque the joined ``group`` applies to its X side, by cutting every member:
    minus the sum of every torque on the components still rigidly attached to the first
    member's ``between[0]``; None when they still reach its ``between[1]``."""
    a, b = group.members[0].between
    cut = set(group.links)
    neighbours: dict[str, list[str]] = {}
    for link in result.model.links:
        if link.type == "fixed" and link.index not in cut:
            x, y = link.between
            neighbours.setdefault(x, []).append(y)
            neighbours.setdefault(y, []).append(x)
    side, todo = {a}, [a]
    while todo:
        for other in neighbours.get(todo.pop(), ()):
            if other not in side:
                side.add(other)
                todo.append(other)
    if b in side:
        return None
    return -sum(torques.get(c, 0.0) for c in side)


def describe(groups: Sequence[FreewheelGroup], prefix: Sequence[bool]) -> str:
    """``F1 holding, F2+F3 overrunning``."""
    return ", ".join(f"{g.label} {'holding' if on else 'overrunning'}"
                     for g, on in zip(groups, prefix))


def _who(groups, prefix, complete: bool) -> str:
    if complete:
        return describe(groups, prefix)
    if not prefix:
        return "every freewheel state"
    return describe(groups, prefix) + " (the others in any state)"


def _dof_note(groups, prefix, complete: bool, dof: int, bound: str) -> str:
    if complete:
        return f"{describe(groups, prefix)} leaves {dof} DOF"
    return f"{_who(groups, prefix, complete)} leaves {bound} {dof} DOF"


def _rank(matrix: np.ndarray) -> int:
    if matrix.size == 0:
        return 0
    s = np.linalg.svd(matrix, compute_uv=False)
    return int(np.sum(s > RANK_RTOL * max(1.0, s[0])))


def _null_space(matrix: np.ndarray, dof: int) -> np.ndarray | None:
    """An orthonormal basis (columns) of the null space of the constraint matrix, with
    ``dof`` columns, or None when the singular values disagree with ``dof`` (no pruning
    then: every combination is solved, as the exhaustive search does)."""
    rows = np.abs(matrix).max(axis=1, initial=0.0)
    scaled = matrix / np.where(rows > 0, rows, 1.0)[:, None]
    if dof == 0:
        return np.zeros((matrix.shape[1], 0))
    _, _, vt = np.linalg.svd(scaled)
    null = vt[vt.shape[0] - dof:].T
    if np.abs(scaled @ null).max(initial=0.0) > 1e-8:
        return None
    return null
