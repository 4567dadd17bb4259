"""The symbols of a train's closed forms and their values in the model.

Naming (part of the ``formula --json`` contract):

- ``z_<component id>``: the tooth number of a component that meshes;
- ``eta_<i>``: the basic efficiency of ``links[i]`` (every mesh; a coupling only when its
  efficiency is below 1 -- ideal couplings contribute nothing);
- ``i_<i>``: Willis' quotient ``(w_a - w_c)/(w_b - w_c)`` of ``links[i]`` when the model
  gives it as ``ratio:`` instead of tooth numbers.

Characters of a component id that cannot appear in a Python identifier become ``_``
(``4'`` -> ``z_4_``); a clash gets a numeric suffix.
"""
from __future__ import annotations

import re
from typing import Any, Mapping

import sympy as sp

from powergraph.errors import UsageError
from powergraph.kinematics import Element
from powergraph.model.spec import Model
from powergraph.records import record

TEETH, EFFICIENCY, RATIO = "teeth", "efficiency", "ratio"


@record
class SymbolInfo:
    """What one symbol stands for, and its value in the model."""

    name: str
    kind: str                     # "teeth", "efficiency" or "ratio"
    value: float
    component: str | None = None  # teeth
    link: int | None = None       # efficiency, ratio

    @property
    def path(self) -> str:
        """The model value it stands for, as a sweep PATH (``components.<id>.teeth``,
        ``links.<i>.efficiency``, ``links.<i>.ratio``)."""
        if self.kind == TEETH:
            return f"components.{self.component}.teeth"
        return f"links.{self.link}.{self.kind}"

    @property
    def positive(self) -> bool:
        """Teeth and efficiencies are positive; a given Willis quotient may be negative."""
        return self.kind in (TEETH, EFFICIENCY)

    def to_dict(self, model: Model) -> dict[str, Any]:
        out: dict[str, Any] = {"kind": self.kind, "value": self.value, "path": self.path}
        if self.component is not None:
            out["component"] = model.raw_id(self.component)
        if self.link is not None:
            out["link"] = self.link
        return out


@record
class SymbolTable:
    """Symbols, their meaning, and each element's symbolic Willis quotient and efficiency."""

    symbols: Mapping[str, sp.Symbol]
    info: Mapping[str, SymbolInfo]
    willis: Mapping[int, sp.Expr]      # by link index
    efficiency: Mapping[int, sp.Expr]  # by link index (1 for an ideal coupling)
    relations: Mapping[str, sp.Expr]   # substituted symbols -> expressions

    @property
    def values(self) -> dict[str, float]:
        """``{name: value in the model}`` of every free symbol."""
        return values_of(self.info)

    @property
    def positive(self) -> frozenset[sp.Symbol]:
        return frozenset(self.symbols[n] for n, i in self.info.items() if i.positive)


def values_of(info: Mapping[str, SymbolInfo]) -> dict[str, float]:
    """``{symbol name: value in the model}``."""
    return {name: i.value for name, i in info.items()}


def latex_names(symbols: Mapping[str, sp.Symbol],
                info: Mapping[str, SymbolInfo]) -> dict[sp.Symbol, str]:
    r"""LaTeX for each symbol: ``z_{sun}``, ``\eta_{0}``, ``i_{3}``.

    Parameters
    ----------
    symbols : mapping
        ``{name: sympy Symbol}``.
    info : mapping
        ``{name: SymbolInfo}`` (not read: the name says the kind).

    Returns
    -------
    dict
        ``{Symbol: LaTeX}``.

    Examples
    --------
    >>> z, eta = sp.Symbol("z_sun"), sp.Symbol("eta_0")
    >>> sorted(latex_names({"z_sun": z, "eta_0": eta}, {}).values())
    ['\\eta_{0}', 'z_{\\mathrm{sun}}']
    """
    out = {}
    for name, symbol in symbols.items():
        prefix, _, ident = name.partition("_")
        head = r"\eta" if prefix == "eta" else prefix
        ident = ident.replace("_", r"\_")
        out[symbol] = f"{head}_{{{ident}}}" if len(ident) <= 1 or ident.isdigit() \
            else f"{head}_{{\\mathrm{{{ident}}}}}"
    return out


def _identifier(text: str) -> str:
    return re.sub(r"\W", "_", text, flags=re.ASCII)


def _name(prefix: str, ident: str, taken: set[str]) -> str:
    base = f"{prefix}_{_identifier(ident)}"
    name, n = base, 2
    while name in taken:
        name, n = f"{base}_{n}", n + 1
    taken.add(name)
    return name


def build_symbols(model: Model, elements: tuple[Element, ...],
                  relations: Mapping[str, Any] | None = None) -> SymbolTable:
    """Symbols for ``model``'s teeth, efficiencies and given ratios; apply ``relations``.

    Parameters
    ----------
    model, elements
        The train and its elements (:func:`powergraph.kinematics.elements_of`).
    relations : mapping, optional
        ``{symbol name: expression}`` (string or sympy), e.g. ``{"z_4": "z_5 - 1"}`` for a
        one-tooth-difference cycloid stage. Each must hold at the model's values.

    Examples
    --------
    >>> from powergraph.model import load_model
    >>> from powergraph.kinematics import elements_of
    >>> m = load_model("models/rv40e_wang2021.yaml")                      # doctest: +SKIP
    >>> sorted(build_symbols(m, elements_of(m)).info)            # doctest: +SKIP
    ['eta_0', 'eta_1', 'z_1', 'z_2', 'z_4', 'z_5']
    """
    taken: set[str] = set()
    info: dict[str, SymbolInfo] = {}
    teeth: dict[str, sp.Symbol] = {}
    willis: dict[int, sp.Expr] = {}
    efficiency: dict[int, sp.Expr] = {}
    for el in elements:
        link = model.links[el.link]
        willis[el.link] = _willis(model, el, link.ratio, teeth, info, taken)
        if el.kind == "mesh" or el.efficiency < 1.0:
            name = _name("eta", str(el.link), taken)
            info[name] = SymbolInfo(name, EFFICIENCY, float(el.efficiency), link=el.link)
            efficiency[el.link] = sp.Symbol(name)
        else:
            efficiency[el.link] = sp.Integer(1)
    symbols = {name: sp.Symbol(name) for name in info}
    subs = parse_relations(relations or {}, symbols, info)
    if subs:
        willis = {k: sp.cancel(v.subs(subs)) for k, v in willis.items()}
        efficiency = {k: v.subs(subs) for k, v in efficiency.items()}
        info = {n: i for n, i in info.items() if symbols[n] not in subs}
        symbols = {n: s for n, s in symbols.items() if n in info}
    return SymbolTable(symbols=symbols, info=info, willis=willis, efficiency=efficiency,
                       relations={str(k): v for k, v in subs.items()})


def _willis(model: Model, el: Element, given: float | None, teeth: dict[str, sp.Symbol],
            info: dict[str, SymbolInfo], taken: set[str]) -> sp.Expr:
    if el.kind == "coupling":
        return sp.Integer(1)
    if given is not None:
        name = _name("i", str(el.link), taken)
        info[name] = SymbolInfo(name, RATIO, float(given), link=el.link)
        return sp.Symbol(name)
    for gear in (el.a, el.b):
        if gear not in teeth:
            name = _name("z", gear, taken)
            info[name] = SymbolInfo(name, TEETH, float(model.components[gear].teeth),
                                    component=gear)
            teeth[gear] = sp.Symbol(name)
    a, b = model.components[el.a], model.components[el.b]
    sign = 1 if (a.internal or b.internal) else -1
    return sign * teeth[el.b] / teeth[el.a]


def parse_relations(relations: Mapping[str, Any], symbols: Mapping[str, sp.Symbol],
                    info: Mapping[str, SymbolInfo]) -> dict[sp.Symbol, sp.Expr]:
    """Parse ``{name: expression}``; each must hold at the model's values.

    Raises
    ------
    UsageError
        An unknown symbol, an expression in unknown or substituted symbols, or a relation
        that the model's own values do not satisfy.
    """
    subs: dict[sp.Symbol, sp.Expr] = {}
    for name, text in relations.items():
        if name not in symbols:
            raise UsageError(f"relation {name} = {text}: unknown symbol {name!r} "
                             f"(symbols: {', '.join(sorted(symbols))})")
        try:
            expr = sp.sympify(text, locals=dict(symbols)) if isinstance(text, str) \
                else sp.sympify(text)
        except (sp.SympifyError, SyntaxError, TypeError) as exc:
            raise UsageError(f"relation {name} = {text}: cannot parse ({exc})") from None
        unknown = {str(s) for s in expr.free_symbols} - set(symbols)
        if unknown:
            raise UsageError(f"relation {name} = {text}: unknown symbol(s) "
                             f"{', '.join(sorted(unknown))}")
        subs[symbols[name]] = expr
    for target, expr in subs.items():
        if expr.free_symbols & set(subs):
            raise UsageError(f"relation {target} = {expr}: uses a substituted symbol")
        _check_holds(target, expr, symbols, info)
    return subs


def _check_holds(target: sp.Symbol, expr: sp.Expr, symbols: Mapping[str, sp.Symbol],
                 info: Mapping[str, SymbolInfo]) -> None:
    values = {symbols[n]: v for n, v in values_of(info).items()}
    lhs, rhs = info[str(target)].value, float(expr.subs(values))
    if abs(lhs - rhs) > 1e-12 * max(1.0, abs(lhs)):
        raise UsageError(f"relation {target} = {expr} does not hold at the model's values "
                         f"({target} = {lhs:g}, {expr} = {rhs:g})")
