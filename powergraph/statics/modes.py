"""Solving a train in one of its modes (docs/modes.md).

:func:`solve_mode` resolves the mode (:func:`powergraph.model.modes.resolve`), checks that
it leaves the train with its designed degrees of freedom (one per port that gives a
speed), decides the freewheels by trying their states, solves, and reports each shift
element: the torque an engaged one carries (:mod:`powergraph.statics.shift_torques`), the
slip speed and drag loss of an open one.

Freewheels: a freewheel ``holds: positive`` allows ``w_a - w_b >= 0``. Engaged, it must
apply a torque ``>= 0`` to ``a``; overrunning, its slip ``w_a - w_b`` must be ``>= 0``
(``negative``: both signs reversed). Every combination of states is tried; the one
consistent combination is kept. None, or several, is a verdict (``ModeResult.verdict``),
not a number.

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

import itertools
from dataclasses import field
from types import MappingProxyType
from typing import Any, Mapping

from powergraph.errors import Caveat, KinematicsError, ModelError
from powergraph.kinematics.speeds import degrees_of_freedom
from powergraph.model.modes import engaged_in, mode_path, resolve
from powergraph.model.spec import Model
from powergraph.records import record
from powergraph.statics.bearings import relative_speed
from powergraph.statics.shift_torques import component_torques, joint_torque

#: Torques and slips below this fraction of the input's are zero.
ZERO = 1e-9
#: At most this many freewheels are decided by trying every combination of states.
MAX_FREEWHEELS = 10


@record
class ShiftState:
    """One shift element in a mode.

    ``state`` is ``engaged``, ``open``, ``holding`` / ``overrunning`` (freewheels) or
    ``idle`` (a freewheel whose members are already joined rigidly); ``torque`` (N·m) is
    what an engaged element applies to its first member (None when statically
    indeterminate), ``slip_speed`` (rad/s) is ``w_a - w_b``, ``drag_loss`` (W) its drag.
    """

    name: str
    kind: str
    state: str
    torque: float | None
    slip_speed: float
    drag_loss: float

    @property
    def engaged(self) -> bool:
        return self.state in ("engaged", "holding")

    def to_dict(self) -> dict[str, Any]:
        return {"name": self.name, "kind": self.kind, "state": self.state,
                "engaged": self.engaged, "torque": self.torque,
                "slip_speed": self.slip_speed, "drag_loss": self.drag_loss}


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

    def to_dict(self) -> dict[str, Any]:
        data = self.result.to_dict() if self.result is not None else {"name": self.model.name}
        data.update({"mode": self.mode, "engaged": list(self.engaged),
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
    """The degrees of freedom the train is designed for: one per port giving a speed."""
    return max(1, sum(p.speed is not None for p in model.ports))


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
        what cannot be joined, or whose engaged elements' torques are indeterminate.
    """
    if solve is None:
        from powergraph.statics.solver import solve
    engaged = engaged_in(model, mode) if mode is not None else tuple(
        e.name for e in model.shift_elements if e.engaged and e.kind != "freewheel")
    fixed = None if mode is not None else engaged
    path = mode_path(mode) if mode is not None else "links"
    need = designed_dof(model)
    trials, notes = [], []
    free = _deciding_freewheels(model, mode, fixed)
    for states in itertools.product((False, True), repeat=len(free)):
        choice = dict(zip((f.name for f in free), states))
        try:
            derived = resolve(model, mode, choice, fixed)
        except ModelError as error:
            if not any(choice.values()):
                raise
            notes.append(f"{_describe(choice)}: {error.message}")
            continue
        dof = degrees_of_freedom(derived)
        if free and dof != need:
            notes.append(f"{_describe(choice)} leaves {dof} DOF")
            continue
        _check_dof(dof, need, engaged, path, lambda: _releasing(model, engaged, need))
        result = solve(derived)
        states_ = _states(model, derived, result, choice)
        bad = [_inconsistency(model.shift_element(n), s) for n, s in states_.items()
               if n in choice]
        bad = [b for b in bad if b]
        if bad:
            notes.append(f"{_describe(choice)}: {'; '.join(bad)}")
            continue
        trials.append((choice, result, states_))
    if not trials:
        return ModeResult(model=model, mode=mode, engaged=engaged, result=None, elements=(),
                          freewheels=MappingProxyType({}),
                          verdict="no consistent freewheel state (" + "; ".join(notes) + ")")
    choice, result, states = trials[0]
    verdict = "ok" if len(trials) == 1 else (
        f"{len(trials)} consistent freewheel states; the first is reported")
    return _finish(model, mode, engaged, result, states, verdict, path)


def _finish(model, mode, engaged, result, states, verdict, path) -> ModeResult:
    warnings = []
    for name, state in states.items():
        if state.state == "engaged" and state.torque is None:
            raise ModelError(f"{name}'s torque is statically indeterminate: another engaged "
                             "element joins the same members", path)
        if state.state == "engaged" and abs(state.torque) <= ZERO * _scale(result):
            warnings.append(Caveat(f"{name} is engaged but carries no torque", path,
                                   "redundant"))
    freewheels = {n: s.state for n, s in states.items()
                  if model.shift_element(n).kind == "freewheel"}
    return ModeResult(model=model, mode=mode, engaged=engaged, result=result,
                      elements=tuple(states.values()),
                      freewheels=MappingProxyType(freewheels), verdict=verdict,
                      warnings=tuple(warnings))


def _deciding_freewheels(model: Model, mode: str | None, fixed) -> list:
    """Freewheels whose members the mode's clutches and brakes do not already join."""
    base = resolve(model, mode, None, fixed)
    return [e for e in model.shift_elements if e.kind == "freewheel"
            and base.body_of[e.between[0]] != base.body_of[e.between[1]]]


def _check_dof(dof: int, need: int, engaged: tuple[str, ...], path: str,
               releasing: Any = None) -> None:
    listing = ", ".join(engaged) or "nothing"
    if dof > need:
        more = dof - need
        raise KinematicsError(f"engages {listing}: leaves {dof} DOF, the train needs {more} "
                              f"more engaged element{'s' if more > 1 else ''}", path)
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
        slip = 0.0 if abs(slip) <= ZERO * scale else slip
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
                                          float(slip), float(loss))
    return states


def _inconsistency(element, state: ShiftState) -> str | None:
    sign = 1.0 if element.holds == "positive" else -1.0
    if state.state == "holding" and state.torque is not None and sign * state.torque < 0:
        return (f"{element.name} holding would carry {state.torque:.6g} N·m (it holds "
                f"{element.holds} only)")
    if state.state == "overrunning" and sign * state.slip_speed < 0:
        return (f"{element.name} overrunning would slip at {state.slip_speed:.6g} rad/s "
                f"(it overruns {element.holds} only)")
    return None


def _describe(choice: Mapping[str, bool]) -> str:
    return ", ".join(f"{n} {'holding' if on else 'overrunning'}" for n, on in choice.items())


def _scale(result) -> float:
    return max([abs(t) for t in result.external_torques.values()] + [1e-300])


def _speed_scale(result) -> float:
    return max([abs(w) for w in result.kinematics.body_speeds.values()] + [1e-300])
