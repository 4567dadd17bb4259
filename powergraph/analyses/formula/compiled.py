"""Closed forms compiled to numpy (``sympy.lambdify``) for fast, vectorised sweeps."""
from __future__ import annotations

from typing import Any, Callable, Mapping, Sequence

import numpy as np
import sympy as sp

from powergraph.errors import UsageError
from powergraph.records import record


@record
class CompiledFormula:
    """Ratio, efficiency and validity of one train as one numpy function.

    Call it with arrays (or scalars) by symbol name; names not given take the model's
    values; arrays broadcast against each other. Returns ``{"ratio", "efficiency",
    "valid"}``, arrays of the broadcast shape; ``valid`` is True where every condition
    of the formulas holds (the direction pattern they were derived for).

    ``names`` is the argument order of ``function``, the raw lambdified function
    ``function(*arrays) -> (ratio, efficiency, *condition quantities)``.

    Examples
    --------
    >>> import numpy as np
    >>> import sympy as sp
    >>> k, e = sp.symbols("z_r eta_0")
    >>> f = compile_formula({"z_r": k, "eta_0": e}, {"z_r": 3.0, "eta_0": 0.9}, -k, e,
    ...                     [(e, ">")])
    >>> out = f(z_r=np.array([3.0, 4.0]))
    >>> out["ratio"].tolist(), out["efficiency"].tolist(), out["valid"].tolist()
    ([-3.0, -4.0], [0.9, 0.9], [True, True])
    """

    names: tuple[str, ...]
    defaults: Mapping[str, float]
    function: Callable[..., Any]
    relations: tuple[str, ...]

    def __call__(self, **values: Any) -> dict[str, np.ndarray]:
        unknown = set(values) - set(self.names)
        if unknown:
            raise UsageError(f"unknown symbol(s) {', '.join(sorted(unknown))}; the formulas "
                             f"use {', '.join(self.names)}")
        args = [np.asarray(values.get(n, self.defaults[n]), dtype=float) for n in self.names]
        shape = np.broadcast_shapes(*(a.shape for a in args)) if args else ()
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio, efficiency, *quantities = self.function(*args)
            valid = np.ones(shape, dtype=bool)
            for quantity, relation in zip(quantities, self.relations):
                valid &= _holds(np.broadcast_to(np.asarray(quantity, float), shape), relation)
        return {"ratio": _shaped(ratio, shape), "efficiency": _shaped(efficiency, shape),
                "valid": valid}


def _shaped(value: Any, shape: tuple[int, ...]) -> np.ndarray:
    return np.array(np.broadcast_to(np.asarray(value, dtype=float), shape))


def _holds(quantity: np.ndarray, relation: str) -> np.ndarray:
    scale = 1e-12
    if relation == ">":
        return quantity > 0
    if relation == "!=":
        return np.abs(quantity) > 0
    return np.abs(quantity) <= scale


def compile_formula(symbols: Mapping[str, sp.Symbol], defaults: Mapping[str, float],
                    ratio: sp.Expr, efficiency: sp.Expr,
                    conditions: Sequence[tuple[sp.Expr, str]]) -> CompiledFormula:
    """Lambdify ratio, efficiency and the condition quantities into one numpy function."""
    names = tuple(symbols)
    expressions = [ratio, efficiency] + [expr for expr, _ in conditions]
    function = sp.lambdify([symbols[n] for n in names], expressions, modules="numpy",
                           cse=True)
    return CompiledFormula(names=names, defaults=dict(defaults), function=function,
                           relations=tuple(rel for _, rel in conditions))
