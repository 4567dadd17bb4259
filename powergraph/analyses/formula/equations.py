"""The solver's two linear systems, with symbols instead of numbers (DESIGN §2-3).

Kinematics: one Willis row ``(w_a - w_c) - i (w_b - w_c) = 0`` per element, ``w_frame = 0``
and the input's speed set to 1 -- the speeds are then ratios to the input speed.

Statics: element ``k`` applies ``λ_k`` to gear a, ``-i·f·λ_k`` to gear b and
``(i·f - 1)·λ_k`` to its carrier (exactly :mod:`powergraph.statics.equilibrium`); each
body's element torques plus its external torque sum to zero. The input's torque is ``±1``
(the sign of the model's input power, so every power has the model's sign); the output's
torque and the frame's reaction are unknowns.
"""
from __future__ import annotations

from typing import Mapping, Sequence

import sympy as sp

from powergraph.errors import MethodNotApplicableError
from powergraph.kinematics import Element
from powergraph.model.spec import Model


def _solve(equations: list[sp.Expr], unknowns: list[sp.Symbol], what: str) -> list[sp.Expr]:
    """Unique solution of a linear system, each entry cancelled to one fraction."""
    solutions = sp.linsolve(equations, unknowns)
    if not solutions:
        raise MethodNotApplicableError(
            f"the {what} have no solution for independent tooth numbers: the train moves "
            "only because its values satisfy a relation; state it with a relation "
            "(--let NAME=EXPR)")
    (solution,) = solutions
    if any(s.free_symbols & set(unknowns) for s in solution):
        raise MethodNotApplicableError(
            f"the {what} do not determine a unique solution (e.g. load sharing between "
            "parallel paths that statics cannot fix); no closed form")
    return [sp.cancel(s) for s in solution]


def body_speeds(model: Model, elements: Sequence[Element], willis: Mapping[int, sp.Expr],
                input_body: str) -> dict[str, sp.Expr]:
    """Speed of every body divided by the input's speed.

    Examples
    --------
    >>> import sympy as sp
    >>> from powergraph.model import load_model
    >>> from powergraph.kinematics import elements_of
    >>> m = load_model("models/planetary_2kh_sun_to_ring.yaml")     # doctest: +SKIP
    >>> z = {c: sp.Symbol("z_" + c) for c in ("sun", "planet", "ring")}
    >>> willis = {0: -z["planet"] / z["sun"], 1: z["ring"] / z["planet"]}
    >>> body_speeds(m, elements_of(m), willis, "sun")["ring"]        # doctest: +SKIP
    -z_sun/z_ring
    """
    w = {body.id: sp.Symbol(f"w[{body.id}]") for body in model.bodies}
    known = {w[model.frame_body]: sp.Integer(0), w[input_body]: sp.Integer(1)}
    equations = []
    for el in elements:
        i = willis[el.link]
        row = (w[el.body_a] - w[el.body_c]) - i * (w[el.body_b] - w[el.body_c])
        equations.append(row.subs(known))
    unknowns = [s for s in w.values() if s not in known]
    solution = dict(zip(unknowns, _solve(equations, unknowns, "Willis equations")))
    solution.update(known)
    return {body: solution[symbol] for body, symbol in w.items()}


def torque_balance(model: Model, elements: Sequence[Element], willis: Mapping[int, sp.Expr],
                   factors: Sequence[sp.Expr], input_body: str, output_body: str,
                   input_torque: int) -> tuple[list[sp.Expr], sp.Expr]:
    """Element forces ``λ_k`` and the output's external torque, for the given factors.

    Examples
    --------
    A fixed-axis pair 20/40 with ``f = eta`` (gear 1 drives): per unit input torque the
    output's external torque is ``2·eta``; the output turns at ``-1/2``, so it takes out
    ``eta`` of the power.

    >>> import sympy as sp
    >>> from powergraph.model import model_from_dict
    >>> from powergraph.kinematics import elements_of
    >>> m = model_from_dict({"name": "pair", "components": {0: {"role": "frame"},
    ...     1: {"teeth": 20}, 2: {"teeth": 40}}, "links": [{"type": "mesh",
    ...     "between": [1, 2]}], "ports": [{"component": 1, "role": "input"},
    ...     {"component": 2, "role": "output"}]})
    >>> eta = sp.Symbol("eta_0")
    >>> torque_balance(m, elements_of(m), {0: sp.Integer(-2)}, [eta], "1", "2", 1)[1]
    2*eta_0
    """
    forces = [sp.Symbol(f"lambda[{el.link}]") for el in elements]
    t_out, t_frame = sp.Symbol("T[output]"), sp.Symbol("T[frame]")
    balance = {body.id: sp.Integer(0) for body in model.bodies}
    for lam, el, f in zip(forces, elements, factors):
        i = willis[el.link]
        balance[el.body_a] += lam
        balance[el.body_b] -= i * f * lam
        balance[el.body_c] += (i * f - 1) * lam
    balance[input_body] += input_torque
    balance[output_body] += t_out
    balance[model.frame_body] += t_frame
    unknowns = forces + [t_out, t_frame]
    solution = _solve(list(balance.values()), unknowns, "torque balances")
    return solution[:len(forces)], solution[len(forces)]
