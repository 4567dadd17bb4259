"""Derive a train's closed-form ratio and efficiency by mirroring the numeric solver.

1. Numeric solve at the model's values (:func:`powergraph.statics.solve`): which gear
   drives each element in its carrier's frame (the direction pattern).
2. Symbolic Willis rows -> every body's speed relative to the input -> the ratio.
3. The same torque balance as :mod:`powergraph.statics.equilibrium`, with ``f = eta`` or
   ``1/eta`` from the pattern -> the output torque -> efficiency = output / input power.
4. The conditions: each driver keeps feeding power in its carrier's frame (> 0), and the
   denominators do not vanish.
"""
from __future__ import annotations

from types import MappingProxyType
from typing import Any, Mapping

import sympy as sp

from powergraph.analyses.formula.freewheels import freewheel_conditions
from powergraph.analyses.formula.readable import orient, readable, sign_factors
from powergraph.analyses.formula.result import Condition, Direction, FormulaResult
from powergraph.analyses.formula.symbols import SymbolTable, build_symbols
from powergraph.analyses.formula.systems import TrainSystems, solve_linear, train_systems
from powergraph.errors import MethodNotApplicableError
from powergraph.kinematics import Element, elements_of
from powergraph.model.spec import Model
from powergraph.statics import PowerFlowResult
from powergraph.statics.case import TrainCase
from powergraph.statics.directions import factor_of
from powergraph.statics.friction import loss_block_places


def derive_formulas(model: Model, relations: Mapping[str, Any] | None = None,
                    mode: str | None = None) -> FormulaResult:
    """Closed-form ratio and efficiency of a one-input, one-output, 1-DOF train.

    The efficiency is the one :func:`powergraph.solve` reports: power leaving over power
    entering. Where the model's input power is negative (the load back-drives the train)
    that is the reciprocal of declared output over declared input.

    Parameters
    ----------
    model : Model
        The train; its values fix the power-direction pattern the formulas are for.
    mode : str, optional
        The mode of a model with modes (required for one): the formulas are those of the
        train in that mode with its freewheels as ``solve --mode`` decides them at the
        model's values; each freewheel's sign condition is among the validity
        conditions.
    relations : mapping, optional
        ``{symbol name: expression}`` substituted before simplifying, e.g.
        ``{"z_4": "z_5 - 1"}`` (the one-tooth difference of a cycloid stage). Each must
        hold at the model's values.

    Returns
    -------
    FormulaResult

    Raises
    ------
    MethodNotApplicableError
        Machines on buses, not one input and one output, more than one DOF, no input
        power, load-dependent losses (a friction law, bearing friction or drag: the
        formulas would drop them), or a train whose equations have no unique solution in
        independent symbols.
    ModelError, SolveError
        From the numeric solve.

    Examples
    --------
    >>> from powergraph.model import load_model
    >>> f = derive_formulas(load_model("models/rv40e_wang2021.yaml"), {"z_4": "z_5 - 1"})  # doctest: +SKIP
    >>> f.ratio                                                                  # doctest: +SKIP
    1 + z_2*z_5/z_1
    """
    _check_ports(model)
    _check_constant_losses(model)
    point = TrainCase.of(model, mode).point().required()
    numeric, source = point.result, model
    model = numeric.model       # the train in its mode, freewheels decided
    _check_solved(numeric)
    elements = elements_of(model)
    table = build_symbols(model, elements, relations)
    values = {table.symbols[n]: v for n, v in table.values.items()}
    input_body = model.body_of[model.inputs[0].component]
    output_body = model.body_of[model.outputs[0].component]
    codes = {flow.link: _code(flow.driver, flow.a, flow.b) for flow in numeric.elements}
    factors = [_factor(codes[el.link], table.efficiency[el.link]) for el in elements]
    sign = 1 if numeric.input_power > 0 else -1  # powers keep the model's signs
    systems = train_systems(
        [body.id for body in model.bodies], [el.bodies for el in elements],
        [table.willis[el.link] for el in elements], factors,
        speeds={model.frame_body: 0, input_body: 1}, torques={input_body: sign},
        reacting=[output_body, model.frame_body])
    speeds = _speeds(systems, model.frame_body, input_body)
    w_out = speeds[output_body]
    if w_out == 0:
        raise MethodNotApplicableError("the output does not turn for independent tooth "
                                       "numbers: no ratio")
    forces = _solved(systems.force_matrix, systems.force_rhs, "torque balances")
    t_out = systems.reactions[output_body].xreplace(dict(zip(systems.forces, forces)))
    ratio = sp.cancel(1 / w_out)
    formal = -sign * t_out * w_out      # (-T_out w_out) / (T_in w_in), w_in = 1
    # leaving / entering, as solve; where the train self-locks solve says 0 and the
    # verdict says why: the closed form is then the formal efficiency (<= 0)
    efficiency = sp.cancel(formal if sign > 0 or numeric.self_locking else 1 / formal)
    conditions = _power_conditions(elements, codes, factors, forces, speeds, table, values)
    reactions = {body: expr.xreplace(dict(zip(systems.forces, forces)))
                 for body, expr in systems.reactions.items()}
    reactions[input_body] = sp.Integer(sign)
    input_sense = 1 if numeric.kinematics.speed(model.inputs[0].component) >= 0 else -1
    conditions += freewheel_conditions(source, point.moded, model, elements, factors, forces,
                                       speeds, reactions, sign, input_sense, table, values)
    conditions += [_denominator(ratio, "ratio", table, values),
                   _denominator(efficiency, "efficiency", table, values)]
    return FormulaResult(
        name=model.name, ratio=readable(ratio, values), efficiency=readable(efficiency, values),
        symbols=MappingProxyType(dict(table.symbols)), info=MappingProxyType(dict(table.info)),
        directions=_directions(elements, codes, factors, table), conditions=tuple(conditions),
        relations=MappingProxyType(dict(table.relations)),
        numeric=MappingProxyType({"ratio": numeric.ratio,
                                  "efficiency": numeric.efficiency}),
        model=model, verdict=point.verdict)


def _solved(matrix: sp.Matrix, rhs: sp.Matrix, what: str) -> list[sp.Expr]:
    """The unique solution of one of the train's systems, or why there is none."""
    if matrix.rows > matrix.cols:
        raise MethodNotApplicableError(
            f"the {what} have no solution for independent tooth numbers: the train moves "
            "only because its values satisfy a relation; state it with a relation "
            "(--let NAME=EXPR)")
    det, solution = solve_linear(matrix, rhs) if matrix.is_square else (0, [])
    if det == 0:
        raise MethodNotApplicableError(
            f"the {what} do not determine a unique solution (e.g. load sharing between "
            "parallel paths that statics cannot fix); no closed form")
    return solution


def _speeds(systems: TrainSystems, frame: str, input_body: str) -> dict[str, sp.Expr]:
    """Every body's speed divided by the input's speed."""
    values = _solved(systems.speed_matrix, systems.speed_rhs, "Willis equations")
    speeds = dict(zip(systems.free, values))
    speeds.update({frame: sp.Integer(0), input_body: sp.Integer(1)})
    return speeds


def _directions(elements: tuple[Element, ...], codes: Mapping[int, int],
                factors: list[sp.Expr], table: SymbolTable) -> tuple[Direction, ...]:
    """The pattern: who drives each lossy element in its carrier's frame."""
    return tuple(Direction(el.link, el.kind, el.a, el.b, el.carrier,
                           _driver(codes[el.link], el), f)
                 for el, f in zip(elements, factors) if table.efficiency[el.link] != 1)


def _check_ports(model: Model) -> None:
    if model.buses:
        raise MethodNotApplicableError(
            "closed forms are derived for a mechanical train; this one has machines on "
            "buses (its efficiency: solve, the gear table, the sweep or a cycle; "
            "docs/hybrid.md)", "buses")
    if len(model.inputs) != 1 or len(model.outputs) != 1:
        raise MethodNotApplicableError(
            f"closed forms are derived for one input and one output; this train has "
            f"{len(model.inputs)} input(s) and {len(model.outputs)} output(s)", "ports")


def _check_constant_losses(model: Model) -> None:
    """Closed forms take constant efficiencies: a load-dependent loss (a friction law, a
    bearing's friction or drag) would silently vanish from them."""
    places = loss_block_places(model)
    if places:
        raise MethodNotApplicableError(
            "closed forms take constant mesh efficiencies; this loss depends on the load "
            "(evaluate the train with solve, the efficiency map or the sweep of a model "
            "with efficiencies)", places[0])


def _check_solved(numeric: PowerFlowResult) -> None:
    if numeric.dof != 1:
        raise MethodNotApplicableError(
            f"closed forms are derived for 1-DOF trains; this one has {numeric.dof} DOF")
    if numeric.input_power == 0:
        raise MethodNotApplicableError("no power enters at the input: no efficiency")


def _code(driver: str | None, a: str, b: str) -> int:
    return 1 if driver == a else (-1 if driver == b and driver is not None else 0)


def _driver(code: int, el: Element) -> str | None:
    return el.a if code > 0 else (el.b if code < 0 else None)


def _factor(code: int, eta: sp.Expr) -> sp.Expr:
    return sp.sympify(factor_of(code, eta))


def _power_conditions(elements: tuple[Element, ...], codes: Mapping[int, int],
                      factors: list[sp.Expr], forces: list[sp.Expr],
                      speeds: Mapping[str, sp.Expr], table: SymbolTable,
                      values: Mapping[sp.Symbol, float]) -> list[Condition]:
    """Each lossy element's driver keeps feeding power in its carrier's frame."""
    out = []
    for el, f, lam in zip(elements, factors, forces):
        if table.efficiency[el.link] == 1:
            continue
        code = codes[el.link]
        power_a = sp.cancel(-lam * (speeds[el.body_a] - speeds[el.body_c]))
        where = f"links[{el.link}] {el.kind} {el.a}-{el.b} (carrier {el.carrier})"
        if code == 0:
            if power_a == 0:
                continue
            quantity, relation = power_a, "="
            text = f"{where}: passes no power"
        else:
            quantity = power_a if code > 0 else sp.cancel(-power_a * f)
            relation = ">"
            text = f"{where}: {_driver(code, el)} keeps driving"
        sign, kept = sign_factors(quantity, table.positive, values, keep_even=relation == "=")
        out.append(Condition("power", text, orient(sp.factor(quantity), values), relation,
                             sign, tuple(kept), el.link))
    return out


def _denominator(expr: sp.Expr, what: str, table: SymbolTable,
                 values: Mapping[sp.Symbol, float]) -> Condition:
    denominator = sp.fraction(sp.cancel(expr))[1]
    sign, kept = sign_factors(denominator, table.positive, values, keep_even=True)
    return Condition("denominator", f"the {what}'s denominator ≠ 0",
                     orient(sp.factor(denominator), values), "!=", sign, tuple(kept))
