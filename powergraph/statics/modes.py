"""Solving a train in one of its modes (docs/modes.md).

:func:`solve_mode` resolves the mode (:func:`powergraph.model.modes.resolve`), checks that
it leaves the train with its designed degrees of freedom (one per port that gives a
speed), decides the freewheels by trying their states, solves, and reports each shift
element: the torque an engaged one carries (:mod:`powergraph.statics.shift_torques`), the
slip speed and drag loss of an open one.

Freewheels: a freewheel ``holds: positive`` allows ``w_a - w_b >= 0``. Engaged, it must
apply a torque ``>= 0`` to ``a``; overrunning, its slip ``w_a - w_b`` must be ``>= 0``
(``negative``: both signs reversed). Freewheels joining the same two bodies are one group
in parallel, decided once (:func:`powergraph.model.modes.freewheel_groups`). The consistent
combinations of group states are those of the exhaustive search, found by a pruned one
(:mod:`powergraph.statics.freewheels`: only combinations consistent in speed are solved);
at most ``MAX_FREEWHEELS`` groups. The one consistent combination is kept; none, or
several, is a verdict (``ModeResult.verdict``), not a number.

Examples
--------
>>> import powergraph as pg
>>> from powergraph.statics.modes import solve_mode
>>> m = pg.load_model("models/simpson_3speed.yaml")          # doctest: +SKIP
>>> r = solve_mode(m, "1")                                   # doctest: +SKIP
>>> round(r.result.ratio, 6), r.freewheels                   # doctest: +SKIP
(2.333333, {'F1': 'holding'})
"""
from __future__ import annotations

from dataclasses import field
from types import MappingProxyType
from typing import Any, Mapping

from powergraph.errors import Caveat, KinematicsError, ModelError
from powergraph.kinematics.speeds import degrees_of_freedom
from powergraph.model.mode_specs import at_mode_point
from powergraph.model.modes import engaged_in, freewheel_groups, mode_path, resolve
from powergraph.model.spec import Model
from powergraph.records import record
from powergraph.statics.bearings import relative_speed
from powergraph.statics.freewheels import ZERO, candidates, describe, settle
from powergraph.statics.shift_torques import component_torques, joint_torque
from powergraph.statics.verdicts import combined, verdict_of

#: At most this many freewheel groups (freewheels joining the same two bodies count once)
#: are left to decide in one mode; more is refused (the search may grow as 2**n).
MAX_FREEWHEELS = 10
#: At most this many reasons are listed in a "no consistent freewheel state" verdict.
MAX_NOTES = 12


@record
class ShiftState:
    """One shift element in a mode.

    ``state`` is ``engaged``, ``open``, ``holding`` / ``overrunning`` (freewheels) or
    ``idle`` (a freewheel whose members are already joined rigidly); ``torque`` (N·m) is
    what an engaged element applies to its first member (None when statically
    indeterminate), ``slip_speed`` (rad/s) is ``w_a - w_b`` (None when a member is idle:
    it turns at no speed the train sets), ``drag_loss`` (W) its drag.
    Freewheels holding together in parallel: ``parallel`` names them all (empty
    otherwise), ``torque`` is None (each one's share is indeterminate) and
    ``parallel_torque`` is their total on this element's first member.
    """

    name: str
    kind: str
    state: str
    torque: float | None
    slip_speed: float | None
    drag_loss: float
    parallel: tuple[str, ...] = ()
    parallel_torque: float | None = None

    @property
    def engaged(self) -> bool:
        return self.state in ("engaged", "holding")

    def to_dict(self) -> dict[str, Any]:
        return {"name": self.name, "kind": self.kind, "state": self.state,
                "engaged": self.engaged, "torque": self.torque,
                "slip_speed": self.slip_speed, "drag_loss": self.drag_loss,
                "parallel": list(self.parallel), "parallel_torque": self.parallel_torque}


@record
class ModeResult:
    """A train solved in one mode: the power-flow result (None when no freewheel state is
    consistent, see ``verdict``), its shift elements and caveats."""

    model: Model = field(repr=False, compare=False)
    mode: str
    engaged: tuple[str, ...]
    result: Any
    elements: tuple[ShiftState, ...]
    freewheels: Mapping[str, str]
    verdict: str
    warnings: tuple = ()

    def element(self, name: str) -> ShiftState:
        return {e.name: e for e in self.elements}[name]

    @property
    def inactive(self) -> tuple[str, ...]:
        """The ports the mode leaves inactive, by name (or ``component ID``)."""
        spec = self.model.mode_specs.get(self.mode) if self.mode is not None else None
        ports = self.model.ports
        return tuple(ports[i].name or f"component {self.model.raw_id(ports[i].component)}"
                     for i in (spec.inactive if spec is not None else ()))

    @property
    def idle(self) -> tuple[str, ...]:
        """The components the mode leaves idle (their ids as text), in file order."""
        if self.result is None:
            return ()
        model = self.result.model
        return tuple(str(model.raw_id(c)) for c in model.components if c in model.idle)

    def to_dict(self) -> dict[str, Any]:
        data = self.result.to_dict() if self.result is not None else {"name": self.model.name}
        inactive = self.result.model.inactive if self.result is not None else frozenset()
        for port, flow in zip(data.get("ports", ()), self.model.ports):
            port["active"] = flow.index not in inactive
        data.update({"mode": self.mode, "engaged": list(self.engaged),
                     "inactive": list(self.inactive), "idle": list(self.idle),
                     "shift_elements": [e.to_dict() for e in self.elements],
                     "freewheels": dict(self.freewheels), "verdict": self.verdict})
        data["warnings"] = list(data.get("warnings", [])) + [str(w) for w in self.warnings]
        return data

    def text_report(self) -> str:
        from powergraph.statics.mode_report import mode_report

        return mode_report(self)

    def plot(self, ax: Any = None, **kwargs: Any):
        if self.result is None:
            from powergraph.errors import NothingToDrawError

            raise NothingToDrawError(f"mode {self.mode}: {self.verdict}")
        return self.result.plot(ax=ax, **kwargs)


def designed_dof(model: Model) -> int:
    """The degrees of freedom the train is designed for: one per active port giving a
    speed (ports on one rigid body count once).

    >>> from powergraph.model import load_model
    >>> designed_dof(load_model("models/simpson_3speed.yaml"))
    1
    """
    return max(1, len({model.body_of[p.component] for p in model.ports
                       if p.speed is not None and p.index not in model.inactive}))


def solve_mode(model: Model, mode: str | None, solve: Any = None) -> ModeResult:
    """Solve ``model`` in ``mode``.

    Parameters
    ----------
    model : Model
        A model with a ``modes`` table.
    mode : str or None
        A key of ``model.modes``; None for a model without modes: its clutches and brakes
        as their ``engaged`` says, its freewheels decided.
    solve : callable, optional
        The solver (default :func:`powergraph.statics.solve`).

    Returns
    -------
    ModeResult

    Raises
    ------
    ModelError
        ``modes.NAME: ...`` for a mode that leaves the wrong DOF, locks the train, joins
        what cannot be joined, whose engaged elements' torques are indeterminate, or that
        leaves more than ``MAX_FREEWHEELS`` freewheel groups to decide.
    """
    if solve is None:
        from powergraph.statics.solver import solve
    engaged = engaged_in(model, mode) if mode is not None else tuple(
        e.name for e in model.shift_elements if e.engaged and e.kind != "freewheel")
    fixed = None if mode is not None else engaged
    path = mode_path(mode) if mode is not None else "links"
    model = at_mode_point(model, mode)
    base = resolve(model, mode, None, fixed)
    need = designed_dof(base)
    groups = freewheel_groups(base)
    if not groups:
        _check_dof(degrees_of_freedom(base), need, engaged, path,
                   lambda: _releasing(model, engaged, need))
        result = solve(base)
        return _finish(model, mode, engaged, result, _states(model, base, result, {}), "ok",
                       path)
    if len(groups) > MAX_FREEWHEELS:
        raise ModelError(f"{len(groups)} freewheels (or groups of freewheels joining the same "
                         f"two members) to decide, more than the limit of {MAX_FREEWHEELS}",
                         path)
    first, count, notes = None, 0, []
    for choice in candidates(base, groups, need, notes):
        trial = _trial(model, mode, fixed, groups, choice, need, solve, path)
        if isinstance(trial, str):
            notes.append(trial)
        else:
            first, count = first or trial, count + 1
    if first is None:
        return ModeResult(model=model, mode=mode, engaged=engaged, result=None, elements=(),
                          freewheels=MappingProxyType({}),
                          verdict="no consistent freewheel state (" + _listing(notes) + ")")
    result, states, caveats = first
    verdict = "ok" if count == 1 else (
        f"{count} consistent freewheel states; the first is reported")
    return _finish(model, mode, engaged, result, states, verdict, path, caveats)


def _trial(model, mode, fixed, groups, choice, need, solve, path):
    """The combination ``choice`` (joined? per group) solved: ``(result, states,
    caveats)``, or why it is inconsistent (a string)."""
    on = {m.name: joined for g, joined in zip(groups, choice) for m in g.members}
    try:
        derived = resolve(model, mode, on, fixed)
    except ModelError as error:
        return f"{describe(groups, choice)}: {error.message}"
    dof = degrees_of_freedom(derived)
    if dof != need:
        return f"{describe(groups, choice)} leaves {dof} DOF"
    try:
        result = solve(derived)
    except ModelError as error:     # e.g. loads that this state leaves undetermined
        return f"{describe(groups, choice)}: {error.message}"
    states = _states(model, derived, result, on)
    bad, caveats = settle(groups, choice, result, states, _scale(result), path)
    if bad:
        return f"{describe(groups, choice)}: {'; '.join(bad)}"
    return result, states, caveats


def _listing(notes: list[str]) -> str:
    if len(notes) <= MAX_NOTES:
        return "; ".join(notes)
    return "; ".join(notes[:MAX_NOTES]) + f"; and {len(notes) - MAX_NOTES} more"


def _finish(model, mode, engaged, result, states, verdict, path, caveats=()) -> ModeResult:
    warnings = list(caveats)
    loaded = _scale(result) > 1e-300     # with no load anywhere, no element carries any
    for name, state in states.items():
        if state.state == "engaged" and state.torque is None:
            raise ModelError(f"{name}'s torque is statically indeterminate: another engaged "
                             "element joins the same members", path)
        if loaded and state.state == "engaged" and abs(state.torque) <= ZERO * _scale(result):
            warnings.append(Caveat(f"{name} is engaged but carries no torque", path,
                                   "redundant"))
    freewheels = {n: s.state for n, s in states.items()
                  if model.shift_element(n).kind == "freewheel"}
    return ModeResult(model=model, mode=mode, engaged=engaged, result=result,
                      elements=tuple(states.values()),
                      freewheels=MappingProxyType(freewheels),
                      verdict=combined(verdict_of(result), verdict),
                      warnings=tuple(warnings))


def _check_dof(dof: int, need: int, engaged: tuple[str, ...], path: str,
               releasing: Any = None) -> None:
    listing = ", ".join(engaged) or "nothing"
    if dof > need:
        more = dof - need
        raise KinematicsError(f"engages {listing}: leaves {dof} DOF, the train needs {more} "
                              f"more engaged element{'s' if more > 1 else ''} (or a given "
                              f"speed on {more} more port{'s' if more > 1 else ''})", path,
                              missing="speed")
    if dof < need:
        free = releasing() if releasing is not None else ()
        hint = (f"; without {' or '.join(free)} it would have {need}" if free else "")
        raise KinematicsError(f"engages {listing}: these lock the train ({dof} DOF, it "
                              f"needs {need}){hint}", path)


def _releasing(model: Model, engaged: tuple[str, ...], need: int) -> list[str]:
    """The engaged elements whose release alone gives the train its designed DOF."""
    out = []
    for name in engaged:
        try:
            derived = resolve(model, None, None, [n for n in engaged if n != name])
        except ModelError:
            continue
        if degrees_of_freedom(derived) == need:
            out.append(name)
    return out


def _states(model: Model, derived: Model, result, choice: Mapping[str, bool]) -> dict:
    torques = component_torques(result)
    drag = {b.link: b for b in result.bearings if b.link is not None}
    speeds = result.kinematics
    scale = _speed_scale(result)
    states = {}
    for element in model.shift_elements:
        link = derived.links[element.index]
        slip = relative_speed(speeds.speed(element.between[0]),
                              speeds.speed(element.between[1]))
        slip = 0.0 if abs(slip) <= ZERO * scale else float(slip)
        if derived.idle & set(element.between) and link.type != "fixed":
            slip = None      # an idle member turns at no speed the train sets
        if link.type == "fixed":
            state = "holding" if element.kind == "freewheel" else "engaged"
            torque = joint_torque(result, element.index, torques)
            if torque is not None and abs(torque) <= ZERO * _scale(result):
                torque = 0.0        # round-off: the sign of a zero torque decides nothing
        else:
            state = "open" if element.kind != "freewheel" else (
                "idle" if element.name not in choice else "overrunning")
            torque = None
        loss = drag[element.index].loss if element.index in drag else 0.0
        states[element.name] = ShiftState(element.name, element.kind, state, torque,
                                          slip, float(loss))
    return states


def _scale(result) -> float:
    return max([abs(t) for t in result.external_torques.values()] + [1e-300])


def _speed_scale(result) -> float:
    return max([abs(w) for w in result.kinematics.body_speeds.values()] + [1e-300])
