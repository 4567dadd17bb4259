"""One operating state of a train, built once and solved by every evaluator.

A :class:`TrainCase` is a model in an operating state: which mode (its clutches and brakes
engaged, the others open with their drag), which freewheels are left to decide at each
operating point, and whether the train is driven forward or back-driven (coasting: the
output drives, fed the power the forward solve takes in). Every evaluator — ``solve``,
``solve --mode``, ``--backdrive``, the gear table (forward and coasting), ``compare``, the
duty cycle's rows, the sweep and the map of a mode, ``formula --mode``, the tolerance
analysis — takes its operating state from :meth:`TrainCase.of` and its answer from
:meth:`TrainCase.point`, so two of them cannot decide the state differently.

Each answer carries its **verdict** (:data:`powergraph.statics.verdicts.VERDICTS`):
``ok``, ``self-locking`` (the declared input cannot drive the output; the efficiency is
0), ``locked`` (the train stays at rest), ``no power`` (the efficiency is undefined), or
why no state holds (``no consistent freewheel state (...)``). The verdict is a property
of the answer, not of the evaluator that asked.

Examples
--------
>>> from powergraph.model import load_model
>>> case = TrainCase.of(load_model("models/simpson_3speed.yaml"), "1")
>>> case.decides_freewheels, case.gear_model is None
(True, True)
>>> p = case.point()
>>> p.verdict, round(p.result.ratio, 6), dict(p.moded.freewheels)
('ok', 2.333333, {'F1': 'holding'})
>>> TrainCase.of(case.model, "1", backdrive=True).point().verdict[:33]
'no consistent freewheel state (F1'
>>> [s.kind for s in case.losses]
['mesh', 'mesh', 'mesh', 'mesh']
"""
from __future__ import annotations

import dataclasses
from dataclasses import field
from functools import cached_property
from typing import Any

from powergraph.errors import ModelError, UsageError
from powergraph.model.spec import Model
from powergraph.records import record
from powergraph.statics.verdicts import verdict_of

@record
class CasePoint:
    """The answer of a :class:`TrainCase` at one operating point.

    ``result`` is the power-flow result (None when no state is consistent: ``verdict``
    says why); ``moded`` the shift elements' states (a
    :class:`~powergraph.statics.modes.ModeResult`, None for a train without shift
    elements); ``verdict`` one of :data:`~powergraph.statics.verdicts.VERDICTS` or why
    there is no result.
    """

    case: "TrainCase" = field(repr=False, compare=False)
    result: Any
    moded: Any
    verdict: str

    @property
    def ok(self) -> bool:
        return self.result is not None

    @property
    def efficiency(self) -> float | None:
        return None if self.result is None else self.result.efficiency

    @property
    def report(self) -> Any:
        """What ``powergraph solve`` prints: the mode result when the train has shift
        elements, else the power-flow result."""
        return self.moded if self.moded is not None else self.result

    def required(self) -> "CasePoint":
        """This answer, or its verdict as a ModelError naming the mode when it has no
        result."""
        if self.result is None:
            what = "back-driven (coasting): " if self.case.backdrive else ""
            raise ModelError(what + self.verdict, self.case.path)
        return self


@record
class TrainCase:
    """A train in one operating state; see the module docstring.

    Build it with :meth:`of`. ``model`` is the model as loaded (never changed); ``mode``
    a key of its modes table (None for a train without); ``backdrive`` True for the
    train driven from its output at the forward input power.
    """

    model: Model = field(repr=False)
    mode: str | None
    backdrive: bool = False

    @classmethod
    def of(cls, model: Model, mode: str | None = None, backdrive: bool = False) -> "TrainCase":
        """The case of ``model`` in ``mode``, forward or back-driven.

        Raises
        ------
        UsageError
            A model with modes and no ``mode``, a mode the model does not have, a ``mode``
            for a model without modes, or ``backdrive`` for a train without exactly one
            input and one output port.
        """
        if mode is None and model.resolved and model.modes:
            mode = model.mode         # a model already resolved in one of its modes
        if mode is not None and not model.modes:
            raise UsageError(f"--mode {mode}: the model has no modes table")
        if model.modes and mode is None:
            raise UsageError("the model has modes " + ", ".join(model.modes)
                             + ": choose one with --mode NAME (or see them all with "
                               "`powergraph modes`)")
        if model.modes and mode not in model.modes:
            raise UsageError(f"--mode {mode}: unknown mode (the model's modes: "
                             + ", ".join(model.modes) + ")")
        if backdrive and model.modes and model.machines:
            raise UsageError("--backdrive: a hybrid with modes regenerates through its "
                             "machines, not its engine: give the mode a negative output "
                             "power instead (docs/modes.md)")
        if backdrive and (len(model.inputs) != 1 or len(model.outputs) != 1):
            raise UsageError("--backdrive needs a train with one input and one output "
                             f"port (this one has {len(model.inputs)} and "
                             f"{len(model.outputs)})")
        return cls(model=model, mode=mode, backdrive=backdrive)

    @property
    def path(self) -> str:
        """Where the case is in the file, for messages (``modes.R`` or ``links``)."""
        return f"modes.{self.mode}" if self.mode is not None else "links"

    @property
    def shifting(self) -> bool:
        """The train has modes or shift elements (answers carry their states)."""
        return bool(self.model.modes or self.model.shift_elements)

    @cached_property
    def decides_freewheels(self) -> bool:
        """Freewheels are left to decide at each operating point (their state depends on
        the load), so no plain train stands for the case at every point."""
        if not any(e.kind == "freewheel" for e in self.model.shift_elements):
            return False
        from powergraph.model.modes import freewheel_groups

        return bool(freewheel_groups(self.base_model))

    @cached_property
    def base_model(self) -> Model:
        """The train in the mode, clutches and brakes as the mode says, freewheels open."""
        if not self.shifting:
            return self.model
        from powergraph.model.modes import resolve

        engaged = None if self.mode is not None else tuple(
            e.name for e in self.model.shift_elements if e.engaged and e.kind != "freewheel")
        return resolve(self.model, self.mode, None, engaged)

    @property
    def gear_model(self) -> Model | None:
        """The plain train that stands for the case at every operating point (engaged
        elements rigid, open ones with their drag), forward; None when freewheels are
        left to decide per point (see :attr:`decides_freewheels`)."""
        if self.decides_freewheels:
            return None
        return self.base_model

    @property
    def losses(self) -> tuple:
        """Every loss source of the case (:func:`powergraph.statics.loss_sources.
        loss_sources` of the train in its mode: meshes, bearings, seals, drags, open
        clutches' drag, machines), the list every evaluator's losses are read from."""
        from powergraph.statics.loss_sources import loss_sources

        return loss_sources(self.base_model)

    def plain_model(self) -> Model:
        """The plain train of the case at its own operating point: :attr:`gear_model`,
        or the mode with its freewheels decided at the model's own load (for analyses of
        that one point: tolerances, the layout of a sweep)."""
        if not self.shifting:
            return self.model
        return self.gear_model or self.point().required().result.model

    def point(self, model: Model | None = None) -> CasePoint:
        """The answer at the case's operating point, or at ``model``: a variant of the
        case's model (other values, the same train), e.g. one row of a duty cycle. A mode
        that sets ports or buses (docs/modes.md) sets those the variant leaves as the
        model has them: the variant's own values come first, then the mode's, then the
        model's (:func:`powergraph.model.mode_specs.at_mode_point`).

        Raises
        ------
        PowerGraphError
            What the solve raises for a model that cannot be solved at all (wrong DOF,
            loads that do not determine the train...).
        """
        model = self.model if model is None else model
        forward = self._solve(model)
        if not self.backdrive or forward.result is None:
            return forward
        if forward.result.efficiency_note is not None:
            return CasePoint(self, None, forward.moded,
                             "no power passes forward, so none to feed back")
        from powergraph.kinematics.variants import backdriven

        driven = forward.result.model if self.shifting else model
        ports = backdriven(driven, forward.result.input_power).ports
        name = f"{model.name} (back-driven)"
        return self._solve(dataclasses.replace(model, ports=ports, name=name))

    def _solve(self, model: Model) -> CasePoint:
        if self.mode is not None and model is not self.model:
            # a variant's own values first, then the mode's, then the model's
            from powergraph.model.mode_specs import at_mode_point

            model = at_mode_point(model, self.mode, loaded=self.model)
        if not self.shifting:
            from powergraph.statics.solver import solve

            result = solve(model)
            return CasePoint(self, result, None, verdict_of(result))
        from powergraph.statics.modes import solve_mode

        moded = solve_mode(model, self.mode)
        return CasePoint(self, moded.result, moded, moded.verdict)
