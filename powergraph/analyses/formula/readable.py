"""Forms a person would write: short rational expressions with their sums turned positive,
and sign conditions with the manifestly positive factors taken out.

Only ``cancel``/``factor`` are used (never ``simplify``): the expressions are rational
functions of the teeth and efficiencies, and these are fast and exact on them.
"""
from __future__ import annotations

from typing import Iterable, Mapping

import sympy as sp
from sympy.printing.latex import LatexPrinter
from sympy.printing.str import StrPrinter

Values = Mapping[sp.Symbol, float]


def _cost(expr: sp.Expr) -> tuple[int, int, int]:
    text = display(expr)
    return sp.count_ops(expr), text.count("-"), len(text)


def _value(expr: sp.Expr, values: Values) -> float:
    try:
        return float(expr.xreplace({s: sp.Float(v) for s, v in values.items()}))
    except TypeError:  # a symbol without a value: leave the factor as it is
        return 0.0


def orient(expr: sp.Expr, values: Values) -> sp.Expr:
    """The same expression with each sum factor turned positive at ``values``.

    ``1 - z2*z5/(z1*(z4 - z5))`` reads better as ``1 + z2*z5/(z1*(z5 - z4))`` when
    ``z5 > z4``: the sign moves to the front.

    Examples
    --------
    >>> import sympy as sp
    >>> z4, z5 = sp.symbols("z_4 z_5")
    >>> orient(2 / (z4 - z5), {z4: 39, z5: 40})
    -2/(-z_4 + z_5)
    """
    sign, factors = 1, []
    for factor in sp.Mul.make_args(expr):
        base, exponent = factor.as_base_exp()
        if base.is_Add and _value(base, values) < 0:
            base = -base
            if exponent.is_integer and exponent % 2:
                sign = -sign
        factors.append(base ** exponent)
    return sign * sp.Mul(*factors)


def readable(expr: sp.Expr, values: Values | None = None) -> sp.Expr:
    """The shortest of a few equivalent forms of a rational expression.

    Candidates: the cancelled and the factored fraction, and ``±1 +`` a factored remainder
    (the ``1 + z2·z5/z1`` of planetary ratios); sums are turned positive at ``values``.

    Examples
    --------
    >>> import sympy as sp
    >>> z1, z2, z5 = sp.symbols("z_1 z_2 z_5")
    >>> display(readable((z1 + z2 * z5) / z1))
    '1 + z_2*z_5/z_1'
    >>> readable((z1 + 2 * z2) / (z1 + z2))
    z_2/(z_1 + z_2) + 1
    >>> readable((z1 + 3 * z2) / (2 * z1 + z2))
    (z_1 + 3*z_2)/(2*z_1 + z_2)
    """
    values = values or {}
    expr = sp.cancel(sp.sympify(expr))
    candidates = [expr, orient(sp.factor(expr), values)]
    for unit in (1, -1):
        rest = orient(sp.factor(sp.cancel(expr - unit)), values)
        if rest != 0:
            candidates.append(unit + rest)
    return min(candidates, key=_cost)


def _term_order(term: sp.Expr) -> tuple[bool, bool]:
    """Positive terms first, a positive constant leading them, a negative one last."""
    negative = term.could_extract_minus_sign()
    return negative, bool(term.is_Number) == negative


class _TextPrinter(StrPrinter):
    """sympy's text printer, with the positive terms of a sum first (``z_5 - 1``)."""

    def _as_ordered_terms(self, expr, order=None):
        return sorted(super()._as_ordered_terms(expr, order=order), key=_term_order)


class _LatexPrinter(LatexPrinter):
    """sympy's LaTeX printer, with the positive terms of a sum first."""

    def _as_ordered_terms(self, expr, order=None):
        return sorted(super()._as_ordered_terms(expr, order=order), key=_term_order)


def display(expr: sp.Expr, latex: bool = False, **settings) -> str:
    """Text (or LaTeX) with the positive terms of each sum first: ``1 - z_r/z_s``,
    ``z_5 - 1`` (sympy would print ``-z_r/z_s + 1``, ``-1 + z_5``). The text parses back
    with ``sympy.sympify`` to the same expression.

    Examples
    --------
    >>> import sympy as sp
    >>> display(1 - sp.Symbol("z_r") / sp.Symbol("z_s"))
    '1 - z_r/z_s'
    >>> display(sp.Symbol("z_5") - 1, latex=True)
    'z_{5} - 1'
    """
    printer = _LatexPrinter(settings) if latex else _TextPrinter(settings)
    return printer.doprint(expr)


def _polynomial_sign(poly: sp.Expr, positive: frozenset[sp.Symbol]) -> int:
    """+1 / -1 when every term has that sign for positive ``positive`` symbols, else 0."""
    if not poly.free_symbols <= positive:
        return 0
    coefficients = sp.Poly(poly, *sorted(poly.free_symbols, key=str)).coeffs() \
        if poly.free_symbols else [poly]
    if all(c > 0 for c in coefficients):
        return 1
    if all(c < 0 for c in coefficients):
        return -1
    return 0


def sign_factors(expr: sp.Expr, positive: Iterable[sp.Symbol], values: Values | None = None,
                 keep_even: bool = False) -> tuple[int, list[sp.Expr]]:
    """``expr``'s sign as ``sign · Π factors``, dropping factors of known sign.

    A factor whose terms all have one sign when every symbol in ``positive`` is positive
    (``z_s + eta_0*z_r``, ``z_1``) leaves only its sign, and so does a factor to an even
    power unless ``keep_even`` (for "≠ 0" conditions, where it matters). The factors
    returned are those whose sign depends on the values, each turned positive at
    ``values`` when given. ``sign`` is ±1, or 0 when ``expr`` is identically 0.

    Examples
    --------
    >>> import sympy as sp
    >>> z4, z5, e = sp.symbols("z_4 z_5 eta_1")
    >>> sign_factors(-e * (z5 - z4) / (z5 + z4), [z4, z5, e])
    (1, [z_4 - z_5])
    >>> sign_factors(-e * (z5 - z4) / (z5 + z4), [z4, z5, e], {z4: 39, z5: 40})
    (-1, [-z_4 + z_5])
    """
    positive = frozenset(positive)
    expr = sp.cancel(sp.sympify(expr))
    if expr == 0:
        return 0, []
    sign, kept = 1, []
    for part in sp.fraction(expr):
        coefficient, factors = sp.factor_list(part)
        sign *= 1 if coefficient > 0 else -1
        for factor, power in factors:
            known = _polynomial_sign(factor, positive)
            if known:
                sign *= known ** power
            elif power % 2 or keep_even:
                if values and _value(factor, values) < 0:
                    factor, sign = -factor, sign * (-1) ** power
                kept.append(factor)
    return int(sign), kept
