"""Readable and LaTeX reports of a :class:`FormulaResult` (``powergraph formula``).

Works on the result it is given (its formulas, ``evaluate()``, ``latex()``, ``values``):
it never imports :mod:`powergraph.analyses.formula.result`, whose ``text_report()``
imports this module (the annotations name the type as text).
"""
from __future__ import annotations

from powergraph.analyses.formula.readable import display
from powergraph.analyses.formula.symbols import EFFICIENCY, RATIO, TEETH, latex_names


def _meaning(result: FormulaResult, name: str) -> str:
    info, model = result.info[name], result.model
    if info.kind == TEETH:
        return f"teeth of {model.components[info.component].label}"
    link = model.links[info.link]
    between = "-".join(str(model.raw_id(c)) for c in link.between)
    if info.kind == EFFICIENCY:
        return f"basic efficiency of links[{info.link}] ({link.type} {between})"
    assert info.kind == RATIO
    return f"Willis ratio of links[{info.link}] ({link.type} {between})"


def _directions(result: FormulaResult) -> list[str]:
    raw = result.model.raw_id
    lines = []
    for d in result.directions:
        driver = raw(d.driver) if d.driver is not None else "nothing (no power)"
        lines.append(f"  links[{d.link}] {d.kind} {raw(d.a)}-{raw(d.b)} (carrier "
                     f"{raw(d.carrier)}): {driver} drives, f = {d.factor}")
    return lines


def _verdict(result: FormulaResult) -> list[str]:
    """A line for a verdict other than ``ok``: what the numbers above mean then."""
    if result.verdict == "ok":
        return []
    if result.verdict == "self-locking":
        return ["SELF-LOCKING at the model's values: the input cannot drive the output, so "
                "solve's efficiency is 0; eta above is the formal efficiency (declared "
                "output / declared input)"]
    return [f"verdict: {result.verdict}"]


def _conditions(result: FormulaResult) -> list[str]:
    """The conditions that depend on the values, each freewheel's state (always named: the
    formulas are those of that state), then a count of the others."""
    shown = [(c.text(), c.description) for c in result.conditions
             if not c.always or c.kind == "freewheel"]
    width = min(48, max((len(text) for text, _ in shown), default=0))
    lines = [f"  {text:<{width}}  ({what})" for text, what in shown]
    always = len(result.conditions) - len(shown)
    if always:
        lines.append(f"  {'always':<{width}}  ({'the other ' if shown else ''}{always} "
                     "condition(s), for any positive teeth and efficiencies)")
    return lines


def suggested_relations(result: FormulaResult) -> dict[str, str]:
    """``{z_external: "z_internal - 1"}`` for each internal pair one tooth apart (cycloid
    and RV stages), when no relation was given and both tooth numbers are symbols."""
    if result.relations:
        return {}
    teeth = {i.component: name for name, i in result.info.items() if i.kind == TEETH}
    out = {}
    for link in result.model.meshes:
        a, b = (result.model.components[c] for c in link.between)
        if link.ratio is None and a.internal != b.internal and abs(a.teeth - b.teeth) == 1:
            outer, inner = (a, b) if a.internal else (b, a)
            if outer.id in teeth and inner.id in teeth:
                sign = "-" if outer.teeth > inner.teeth else "+"
                out[teeth[inner.id]] = f"{teeth[outer.id]}{sign}1"
    return out


def text_report(result: FormulaResult) -> str:
    """Ratio, efficiency, symbols, direction pattern and validity conditions as text.

    Examples
    --------
    >>> from powergraph.model import load_model
    >>> from powergraph.analyses.formula import derive_formulas
    >>> print(text_report(derive_formulas(load_model("models/rv40e_wang2021.yaml"))))  # doctest: +SKIP
    RV-40E — closed-form ratio and efficiency
    ...
    """
    at = result.evaluate()
    lines = [f"{result.name} — closed-form ratio and efficiency (virtual-power method)", "",
             f"ratio       i   = {display(result.ratio)}",
             f"efficiency  eta = {display(result.efficiency)}", "",
             f"at the model's values: i = {at['ratio']:.12g}, eta = {at['efficiency']:.12g}"
             f" (numeric solve: {result.numeric['ratio']:.12g}, "
             f"{result.numeric['efficiency']:.12g})", *_verdict(result), "", "symbols"]
    for name, value in result.values.items():
        lines.append(f"  {name:<12} = {value:<10g} {_meaning(result, name)}")
    for name, expr in result.relations.items():
        lines.append(f"  {name:<12} = {expr}  (relation given)")
    lines += ["", "power-flow directions (carrier frames, at the model's values)"]
    lines += _directions(result) or ["  (no lossy element)"]
    lines += ["", "valid while (the signs that must not change)"]
    lines += _conditions(result)
    hints = suggested_relations(result)
    if hints:
        lines += ["", "hint: one-tooth-difference pair(s); for the textbook form use "
                  + " ".join(f"--let {name}={expr}" for name, expr in hints.items())]
    return "\n".join(lines)


def latex_report(result: FormulaResult) -> str:
    """The formulas and conditions as LaTeX lines, ready to paste into a paper."""
    latex = result.latex()
    names = latex_names(result.symbols, result.info)
    lines = [f"% {result.name}: closed forms (powergraph formula)",
             f"i = {latex['ratio']}", rf"\eta = {latex['efficiency']}",
             "% valid while:"]
    for c in result.conditions:
        if not c.always:
            lines.append(f"{c.latex(names)}  % {c.description}")
    return "\n".join(lines)
