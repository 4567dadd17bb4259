"""The freewheels' sign conditions of a closed form (``formula --mode``).

A mode's freewheels are decided at the model's values (``solve --mode``): each holds or
overruns. The closed forms stay valid only while each keeps its state, so each state is a
condition beside the power-flow ones, written with the same symbols:

- a holding freewheel (or group in parallel) keeps carrying a torque of the sense it
  holds: the torque found by cutting it (:func:`powergraph.statics.freewheels.cut_torque`,
  here on the symbolic torques of each component) times that sense is > 0;
- an overrunning one keeps slipping the way it may: its slip ``w_a - w_b`` (over the
  input speed, times the input speed's sign) times its sense is > 0.

Torques are per unit input torque and speeds per unit input speed, as in the rest of the
derivation, so the conditions hold for every load of the same sign.
"""
from __future__ import annotations

from collections import defaultdict
from types import SimpleNamespace
from typing import Any, Mapping, Sequence

import sympy as sp

from powergraph.analyses.formula.readable import orient, sign_factors
from powergraph.analyses.formula.result import Condition
from powergraph.kinematics import Element, element_stencil
from powergraph.model.spec import Model
from powergraph.statics.freewheels import cut_torque


def freewheel_conditions(source: Model, moded: Any, model: Model,
                         elements: Sequence[Element], factors: Sequence[sp.Expr],
                         forces: Sequence[sp.Expr], speeds: Mapping[str, sp.Expr],
                         reactions: Mapping[str, sp.Expr], sign: int, input_sense: float,
                         table: Any, values: Mapping[sp.Symbol, float]) -> list[Condition]:
    """The conditions that keep each freewheel of ``moded`` (a ModeResult, None for a train
    without shift elements) in the state the model's values give it.

    ``model`` is the train as solved (the mode, freewheels decided); ``reactions`` the
    external torque of each body (symbolic, ``sign`` on the input); ``input_sense`` the
    sign of the input's speed at the model's values.
    """
    if moded is None or not moded.freewheels:
        return []
    from powergraph.statics.case import TrainCase
    from powergraph.model.modes import freewheel_groups

    groups = freewheel_groups(TrainCase.of(source, moded.mode).base_model)
    torques = _component_torques(model, elements, factors, forces, table, reactions)
    out = []
    for group in groups:
        states = [moded.freewheels[name] for name in group.names]
        if "holding" in states:
            holder = states.index("holding")
            total = cut_torque(SimpleNamespace(model=model), group, torques)
            if total is None:
                continue        # statically indeterminate: no sign to keep
            quantity = sp.cancel(group.senses[holder] * total)
            text = f"{group.label} keeps holding (its torque keeps its sense)"
        else:
            a, b = group.members[0].between
            slip = speeds[model.body_of[a]] - speeds[model.body_of[b]]
            quantity = sp.cancel(group.senses[0] * int(input_sense) * slip)
            text = f"{group.label} keeps overrunning (its slip keeps its sense)"
        quantity = sp.nsimplify(quantity, rational=True)     # 1.0 -> 1 (exact stencils)
        sign_, kept = sign_factors(quantity, table.positive, values)
        out.append(Condition("freewheel", text, orient(sp.factor(quantity), values), ">",
                             sign_, tuple(kept), group.links[0]))
    return out


def _component_torques(model: Model, elements: Sequence[Element], factors: Sequence[sp.Expr],
                       forces: Sequence[sp.Expr], table: Any,
                       reactions: Mapping[str, sp.Expr]) -> dict[str, sp.Expr]:
    """Every torque on each component, symbolic: the elements' static columns times their
    forces, the ports' and the frame's external torques (as
    :func:`powergraph.statics.shift_torques.component_torques` on numbers)."""
    torques: dict[str, sp.Expr] = defaultdict(lambda: sp.Integer(0))
    for el, f, lam in zip(elements, factors, forces):
        for component, unit in zip((el.a, el.b, el.carrier),
                                   element_stencil(table.willis[el.link], f)):
            torques[component] += unit * lam
    for port in model.ports:
        torques[port.component] += reactions.get(model.body_of[port.component], 0)
    torques[model.frame] += reactions.get(model.frame_body, 0)
    return dict(torques)
