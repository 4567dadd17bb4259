"""The symbolic backend: the train's two linear systems solved once, by hand as it were.

Speeds: one Willis row per element over the bodies whose speed is not given,
``K(i) w = -K_known w_known`` (entries 1, ``-i_k``, ``i_k - 1``). Forces: the balance of
every body with no unknown external torque, ``M(g) λ = -T_given`` (entries 1, ``-g_k``,
``g_k - 1`` with ``g_k = i_k f_k``; the transpose pattern of the Willis rows). The ratio
arguments are magnitudes: ``i_k = s_k q_k`` with the sign ``s_k`` of a teeth-swept mesh
folded in at compile time (``q_k = z_b/z_a``). Both are
solved with sympy as adjugate / determinant — polynomials over one determinant, which
vanishes only where the system itself is singular — and compiled by ``lambdify`` with
common-subexpression elimination into numpy functions. The result is the closed form a
designer would derive for this train, but for any train.
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Callable, Sequence

import numpy as np

from powergraph.analyses.sweep.layout import Layout

if TYPE_CHECKING:  # pragma: no cover
    from powergraph.analyses.sweep.specialised import Specialised

#: Largest system solved symbolically; bigger ones use the numeric backend.
MAX_SYMBOLIC = 8
#: A determinant below this fraction of its terms' absolute sum counts as singular
#: (the single solver's rank tolerance is 1e-10 on singular values).
SINGULAR = 1e-12


def applies(layout: Layout) -> bool:
    """True when both reduced systems are square, small and statically determinate."""
    n_free, n_bal = len(layout.free_bodies), len(layout.balance_bodies)
    return (layout.determinate and n_free == layout.n_elements == n_bal
            and len(set(layout.unknown)) == len(layout.unknown)
            and 0 < layout.n_elements <= MAX_SYMBOLIC)


class SymbolicBackend:
    """Speeds and element forces of a train as compiled closed forms.

    Examples
    --------
    >>> from powergraph.model import load_model
    >>> from powergraph.analyses.sweep.layout import layout_of
    >>> backend = SymbolicBackend(layout_of(load_model("models/rv40e.yaml"), ()))  # doctest: +SKIP
    """

    name = "symbolic"

    def __init__(self, layout: Layout) -> None:
        import sympy as sp

        self.layout = layout
        n = layout.n_elements
        self.ratio_symbols = sp.symbols(f"i0:{n}")
        self.gain_symbols = sp.symbols(f"g0:{n}")
        self.speed_symbols = sp.symbols(f"w0:{len(layout.speed_ports)}")
        self.torque_symbols = sp.symbols(f"t0:{len(layout.loads)}")
        self._speeds = self._compile_speeds(sp)
        self._forces = self._compile_forces(sp)

    # --- compile ------------------------------------------------------------------------
    def _compile_speeds(self, sp) -> Callable:
        lay = self.layout
        free = {body: j for j, body in enumerate(lay.free_bodies)}
        known = {lay.frame: sp.Integer(0)}
        known.update({body: self.speed_symbols[j] for j, (body, _) in enumerate(lay.speed_ports)})
        matrix = sp.zeros(lay.n_elements, len(free))
        rhs = sp.zeros(lay.n_elements, 1)
        for k in range(lay.n_elements):
            i = sp.Integer(1) if lay.kinds[k] == "coupling" \
                else sp.Integer(int(lay.signs[k])) * self.ratio_symbols[k]
            for body, coef in ((lay.body_a[k], 1), (lay.body_b[k], -i), (lay.body_c[k], i - 1)):
                if body in free:
                    matrix[k, free[body]] += coef
                else:
                    rhs[k] -= coef * known[body]
        det, scale, values = _solve(sp, matrix, rhs)
        by_body = [known[j] if j in known else values[free[j]] for j in range(lay.n_bodies)]
        self.kinematics = (det, scale, by_body)
        return _lambdify(sp, [self.ratio_symbols, self.speed_symbols], [det, scale, *by_body])

    def _compile_forces(self, sp) -> Callable:
        lay = self.layout
        rows = {body: r for r, body in enumerate(lay.balance_bodies)}
        matrix = sp.zeros(len(rows), lay.n_elements)
        rhs = sp.zeros(len(rows), 1)
        for k in range(lay.n_elements):
            g = sp.Integer(int(lay.signs[k])) * self.gain_symbols[k]
            for body, coef in ((lay.body_a[k], 1), (lay.body_b[k], -g), (lay.body_c[k], g - 1)):
                if body in rows:
                    matrix[rows[body], k] += coef
        for j, load in enumerate(lay.loads):
            if load.body in rows:
                rhs[rows[load.body]] -= self.torque_symbols[j]
        det, scale, values = _solve(sp, matrix, rhs)
        self.balance = (det, scale, values)
        return _lambdify(sp, [self.gain_symbols, self.torque_symbols], [det, scale, *values])

    def specialise(self, moving: Sequence[int], codes: Sequence[int],
                   start: Sequence[int] | None = None) -> "Specialised":
        """The closed form of this train for one direction pattern (see
        :mod:`powergraph.analyses.sweep.specialised`)."""
        from powergraph.analyses.sweep.specialised import Specialised

        return Specialised(self, tuple(moving), tuple(codes),
                           None if start is None else tuple(start))

    # --- evaluate -----------------------------------------------------------------------
    def speeds(self, ratios: Sequence, given: Sequence) -> tuple[list, np.ndarray]:
        """Absolute speed of every body (rad/s), and where the Willis rows are regular."""
        det, scale, *values = self._speeds(list(ratios), list(given))
        return values, _regular(det, scale)

    def forces(self, gains: Sequence, torques: Sequence) -> tuple[list, np.ndarray]:
        """Force ``λ_k`` (torque on gear a) of every element for gains ``g = i f``, and
        where the balance is singular (loads not determined)."""
        det, scale, *values = self._forces(list(gains), list(torques))
        return values, _regular(det, scale)


def _regular(abs_det, threshold) -> np.ndarray:
    """``|det|`` not small against the determinant's terms taken in absolute value
    (False for NaN too)."""
    return abs_det > threshold


def _solve(sp, matrix, rhs) -> tuple:
    """``matrix^-1 rhs`` as polynomials over the determinant (fraction-free).

    Returns ``|det|``, its singularity threshold (:data:`SINGULAR` times the sum of the
    determinant's terms in absolute value) and the solution.
    """
    det = sp.expand(matrix.det(method="bareiss"))
    terms = sp.Add(*(sp.Abs(term) for term in sp.Add.make_args(det)))
    scale = sp.Mul(sp.Float(SINGULAR), terms, evaluate=False)
    adjugate = matrix.adjugate(method="bareiss")
    solution = [sp.cancel((adjugate[r, :] * rhs)[0, 0] / det) for r in range(matrix.rows)]
    return sp.Abs(det), scale, solution


def _lambdify(sp, args, expressions) -> Callable:
    """numpy function of ``args`` (call it under ``np.errstate(all="ignore")``)."""
    return sp.lambdify(args, list(expressions), modules="numpy", cse=True)
