"""What :func:`derive_formulas` returns: the closed forms, the direction pattern they hold
for, the conditions that keep that pattern, and fast numeric evaluation."""
from __future__ import annotations

from dataclasses import field
from functools import cached_property
from typing import Any, Mapping

import sympy as sp

from powergraph.analyses.formula.compiled import CompiledFormula, compile_formula
from powergraph.analyses.formula.readable import display
from powergraph.analyses.formula.symbols import SymbolInfo, latex_names, values_of
from powergraph.model.spec import Model
from powergraph.records import record

_FLIP = {">": "<", "<": ">", "!=": "!=", "=": "="}
_LATEX_RELATION = {">": ">", "<": "<", "!=": r"\neq", "=": "="}


@record
class Direction:
    """Who drives one lossy element in its carrier's frame, at the model's values."""

    link: int
    kind: str
    a: str
    b: str
    carrier: str
    driver: str | None
    factor: sp.Expr   # f = eta (a drives), 1/eta (b drives), 1 (no power)

    def to_dict(self, model: Model) -> dict[str, Any]:
        raw = model.raw_id
        return {"link": self.link, "kind": self.kind, "between": [raw(self.a), raw(self.b)],
                "carrier": raw(self.carrier),
                "driver": raw(self.driver) if self.driver is not None else None,
                "factor": str(self.factor)}


@record
class Condition:
    """``expression relation 0`` must hold for the formulas to stay valid.

    ``sign · Π factors`` has the sign of ``expression`` whenever teeth and efficiencies are
    positive; ``factors`` are the parts whose sign depends on the values.
    """

    kind: str                 # "power" (a driver keeps driving), "denominator" or
                              # "freewheel" (a freewheel keeps its state)
    description: str
    expression: sp.Expr
    relation: str             # ">", "!=" or "="
    sign: int
    factors: tuple[sp.Expr, ...]
    link: int | None = None

    @property
    def always(self) -> bool:
        """True when it holds for every positive teeth and efficiencies."""
        # a plain bool (the sign may come from sympy, whose comparisons give BooleanTrue)
        return bool(not self.factors and (self.relation == "!=" or
                                          (self.relation == ">" and int(self.sign) > 0)))

    @property
    def reduced(self) -> tuple[sp.Expr, str]:
        """``(expression, relation)`` with the factors of known sign taken out."""
        relation = self.relation if self.sign > 0 else _FLIP[self.relation]
        return sp.Mul(*self.factors), relation

    def text(self) -> str:
        if self.always:
            return "always (positive teeth and efficiencies)"
        expr, relation = self.reduced
        return f"{display(expr)} {relation} 0"

    def latex(self, names: Mapping[sp.Symbol, str]) -> str:
        if self.always:
            return r"\text{always}"
        expr, relation = self.reduced
        return f"{display(expr, latex=True, symbol_names=names)} {_LATEX_RELATION[relation]} 0"

    def to_dict(self, names: Mapping[sp.Symbol, str]) -> dict[str, Any]:
        return {"kind": self.kind, "link": self.link, "description": self.description,
                "expression": display(self.expression), "relation": self.relation,
                "condition": self.text(), "always": self.always,
                "latex": self.latex(names)}


@record
class FormulaResult:
    """Closed-form ratio and efficiency of one train.

    ``ratio`` (input speed / output speed) and ``efficiency`` (output / input power) are
    sympy expressions in ``symbols`` (``z_<id>``, ``eta_<i>``, ``i_<i>``; see
    :mod:`powergraph.analyses.formula.symbols`). They hold for the power-direction
    pattern ``directions`` found at the model's values, as long as every ``conditions``
    entry holds.

    Examples
    --------
    >>> from powergraph.model import load_model
    >>> from powergraph.analyses.formula import derive_formulas
    >>> f = derive_formulas(load_model("models/planetary_2kh_sun_to_ring.yaml"))  # doctest: +SKIP
    >>> f.ratio, f.efficiency                                                 # doctest: +SKIP
    (-z_ring/z_sun, eta_0*eta_1)
    """

    name: str
    ratio: sp.Expr
    efficiency: sp.Expr
    symbols: Mapping[str, sp.Symbol]
    info: Mapping[str, SymbolInfo]
    directions: tuple[Direction, ...]
    conditions: tuple[Condition, ...]
    relations: Mapping[str, sp.Expr]
    numeric: Mapping[str, float]      # ratio and efficiency of the numeric solve
    model: Model = field(repr=False, compare=False)
    #: The verdict of the numeric solve at the model's values (``ok``, ``self-locking``...;
    #: :mod:`powergraph.statics.verdicts`). Self-locking: ``solve``'s efficiency is 0 and
    #: the closed form is the formal efficiency, declared output over declared input (<= 0).
    verdict: str = "ok"

    @property
    def values(self) -> dict[str, float]:
        """``{symbol name: value in the model}``."""
        return values_of(self.info)

    @property
    def paths(self) -> dict[str, str]:
        """``{model PATH: symbol name}``, e.g. ``{"components.1.teeth": "z_1"}`` (the PATHs
        of ``powergraph sweep``)."""
        return {i.path: name for name, i in self.info.items()}

    @cached_property
    def _compiled(self) -> CompiledFormula:
        return self.lambdify()

    def lambdify(self) -> CompiledFormula:
        """A fast numpy function of the symbols (see :class:`CompiledFormula`).

        Examples
        --------
        >>> import numpy as np
        >>> from powergraph.model import load_model
        >>> from powergraph.analyses.formula import derive_formulas
        >>> f = derive_formulas(load_model("models/khv_involute.yaml")).lambdify() # doctest: +SKIP
        >>> f(eta_0=np.array([0.99, 0.98]))["efficiency"].round(4)                 # doctest: +SKIP
        array([0.9167, 0.8448])
        """
        return compile_formula(self.symbols, self.values, self.ratio, self.efficiency,
                               [(c.expression, c.relation) for c in self.conditions])

    def evaluate(self, **values: float) -> dict[str, float]:
        """Ratio and efficiency at the model's values, with ``values`` (by name) changed."""
        out = self._compiled(**values)
        return {"ratio": float(out["ratio"]), "efficiency": float(out["efficiency"])}

    def holds(self, **values: float) -> bool:
        """Whether every condition holds at the model's values with ``values`` changed."""
        return bool(self._compiled(**values)["valid"])

    def latex(self) -> dict[str, Any]:
        """LaTeX of the ratio, the efficiency and the conditions."""
        names = latex_names(self.symbols, self.info)
        return {"ratio": display(self.ratio, latex=True, symbol_names=names),
                "efficiency": display(self.efficiency, latex=True, symbol_names=names),
                "conditions": [c.latex(names) for c in self.conditions]}

    def text_report(self) -> str:
        """The readable report ``powergraph formula`` prints."""
        from powergraph.analyses.formula.report import text_report

        return text_report(self)

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """Nothing to draw: raises :class:`~powergraph.result.NothingToDrawError`."""
        from powergraph.result import nothing_to_draw

        raise nothing_to_draw(self, "evaluate the formulas (lambdify) and plot the values")

    def to_dict(self) -> dict[str, Any]:
        """The ``powergraph formula --json`` object."""
        names = latex_names(self.symbols, self.info)
        latex = self.latex()
        at_values = self.evaluate()
        return {
            "name": self.name,
            "ratio": display(self.ratio),
            "efficiency": display(self.efficiency),
            "latex": {"ratio": latex["ratio"], "efficiency": latex["efficiency"]},
            "directions": [d.to_dict(self.model) for d in self.directions],
            "conditions": [c.to_dict(names) for c in self.conditions],
            "symbols": {n: i.to_dict(self.model) for n, i in self.info.items()},
            "relations": {n: str(e) for n, e in self.relations.items()},
            "at_model_values": {**at_values, "valid": self.holds()},
            "numeric": dict(self.numeric),
            "verdict": self.verdict,
        }
