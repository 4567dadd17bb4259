"""A train's kinematic and static systems with symbols instead of numbers: the one
symbolic derivation shared by :func:`~powergraph.analyses.formula.derive_formulas` and the
compiled sweep's symbolic backend (:mod:`powergraph.analyses.sweep.backends`).

Every coefficient comes from :func:`powergraph.kinematics.elements.element_stencil`:

- **speeds**: one Willis row per element, ``stencil(i) · (w_a, w_b, w_c) = 0``, over the
  bodies whose speed is not given (the given ones move to the right-hand side);
- **forces**: element ``k`` applies ``stencil(i_k, f_k) · λ_k`` to (gear a, gear b,
  carrier); each body's element torques plus its external torque sum to zero. The
  balances of the bodies without an unknown external torque fix the forces ``λ``; the
  others give those bodies' external torques (the *reactions*).

The factors ``f_k`` are those of one direction pattern (``η``, ``1/η`` or 1), or symbols
to be replaced later. Systems are solved as adjugate over determinant (fraction-free; the
determinant vanishes only where the system itself is singular). The method is described
in docs/theory.md.
"""
from __future__ import annotations

from typing import Any, Hashable, Mapping, Sequence

import numpy as np
import sympy as sp

from powergraph.kinematics.elements import element_stencil
from powergraph.kinematics.system import TrainSystem
from powergraph.records import record


@record
class TrainSystems:
    """The two linear systems of a train, ``matrix · unknowns = rhs``.

    ``free`` are the bodies whose speeds the speed system solves for (its columns);
    ``balanced`` the bodies whose balances are the force system's rows (its columns are
    the elements' forces ``forces``). ``reactions`` gives the external torque of every
    other body as an expression in ``forces``.
    """

    speed_matrix: sp.Matrix
    speed_rhs: sp.Matrix
    free: tuple[Hashable, ...]
    force_matrix: sp.Matrix
    force_rhs: sp.Matrix
    balanced: tuple[Hashable, ...]
    forces: tuple[sp.Symbol, ...]
    reactions: Mapping[Hashable, sp.Expr]


def train_systems(bodies: Sequence[Hashable], elements: Sequence[tuple[Hashable, ...]],
                  ratios: Sequence[Any], factors: Sequence[Any],
                  speeds: Mapping[Hashable, Any], torques: Mapping[Hashable, Any],
                  reacting: Sequence[Hashable]) -> TrainSystems:
    """Build a train's symbolic speed and force systems for one direction pattern.

    Parameters
    ----------
    bodies : sequence
        Every body (ids or indices).
    elements : sequence of (body of gear a, body of gear b, body of the carrier)
    ratios, factors : sequences
        Willis' quotient ``i_k`` and factor ``f_k`` of each element (sympy or numbers).
    speeds : mapping body -> expression
        The given speeds (the frame's 0 included).
    torques : mapping body -> expression
        The given external torques.
    reacting : sequence of bodies
        Bodies whose external torque is unknown (their balance gives it).

    Examples
    --------
    A fixed-axis pair 20/40 (``i = -2``) whose gear 1 drives (``f = eta``), input torque 1:
    the output's reaction is ``2·eta``.

    >>> eta = sp.Symbol("eta")
    >>> s = train_systems(["0", "1", "2"], [("1", "2", "0")], [-2], [eta],
    ...                   {"0": 0, "1": 1}, {"1": 1}, ["2", "0"])
    >>> det, (w2,) = solve_linear(s.speed_matrix, s.speed_rhs)
    >>> w2
    -1/2
    >>> det, (force,) = solve_linear(s.force_matrix, s.force_rhs)
    >>> s.reactions["2"].subs(s.forces[0], force)
    2*eta
    """
    free = tuple(b for b in bodies if b not in speeds)
    balanced = tuple(b for b in bodies if b not in set(reacting))
    column, row = {b: j for j, b in enumerate(free)}, {b: r for r, b in enumerate(balanced)}
    speed_matrix, speed_rhs = sp.zeros(len(elements), len(free)), sp.zeros(len(elements), 1)
    force_matrix, force_rhs = sp.zeros(len(balanced), len(elements)), sp.zeros(len(balanced), 1)
    forces = sp.symbols(f"lambda0:{len(elements)}")
    on_body: dict[Hashable, sp.Expr] = {b: sp.Integer(0) for b in bodies}
    index = {b: j for j, b in enumerate(bodies)}
    system = TrainSystem(len(bodies), [[index[b] for b in places] for places in elements])
    ratios = [sp.sympify(r) for r in ratios]
    for k, j, coef in zip(*system.willis_triplets(_symbols(ratios))):
        body, coef = bodies[j], _exact(coef)
        if body in column:
            speed_matrix[k, column[body]] += coef
        else:
            speed_rhs[k] -= coef * speeds[body]
    for j, k, coef in zip(*system.balance_triplets(_symbols(ratios),
                                                    _symbols([sp.sympify(f) for f in factors]))):
        body, coef = bodies[j], _exact(coef)
        on_body[body] += coef * forces[k]
        if body in row:
            force_matrix[row[body], k] += coef
    for body, torque in torques.items():
        if body in row:
            force_rhs[row[body]] -= torque
    reactions = {b: -(on_body[b] + torques.get(b, 0)) for b in bodies if b not in row}
    return TrainSystems(speed_matrix, speed_rhs, free, force_matrix, force_rhs, balanced,
                        tuple(forces), reactions)


def stencil(ratio: Any, factor: Any = 1) -> tuple[sp.Expr, sp.Expr, sp.Expr]:
    """:func:`~powergraph.kinematics.elements.element_stencil` on sympy values, exact: the
    stencil's constants are floats (``1.0``), taken here as the integers they are.

    Examples
    --------
    >>> stencil(sp.Symbol("i"), sp.Symbol("f"))
    (1, -f*i, f*i - 1)
    """
    return tuple(_exact(c) for c in element_stencil(sp.sympify(ratio), sp.sympify(factor)))


def _exact(coefficient) -> sp.Expr:
    """A stencil coefficient with its integer-valued floats (``1.0``) as integers."""
    c = sp.sympify(coefficient)
    return c.xreplace({f: sp.Integer(int(f)) for f in c.atoms(sp.Float)
                       if float(f).is_integer()})


def _symbols(values: list) -> np.ndarray:
    """Sympy values as an object array (:class:`TrainSystem` keeps them exact)."""
    array = np.empty(len(values), dtype=object)
    array[:] = values
    return array


def solve_linear(matrix: sp.Matrix, rhs: sp.Matrix) -> tuple[sp.Expr, list[sp.Expr]]:
    """``matrix⁻¹ · rhs``, each entry cancelled (Cramer's rule, by fraction-free
    elimination).

    Returns the expanded determinant and the solution; the caller decides what a
    vanishing determinant means. ``matrix`` must be square.

    Examples
    --------
    >>> a = sp.Symbol("a")
    >>> solve_linear(sp.Matrix([[a, 1], [0, 2]]), sp.Matrix([1, 4]))
    (2*a, [-1/a, 2])
    """
    # Fraction-free elimination over the polynomial ring of the symbols (sympy's
    # DomainMatrix), for the determinant and the solution: the same as the adjugate,
    # without its n² cofactors (an eight-speed's balance: 0.15 s instead of 15 s), and
    # without the simplification of every product that Matrix.det's Bareiss runs (the
    # eight-speed's determinant: 7 s).
    from sympy.polys.matrices import DomainMatrix

    a, b = DomainMatrix.from_Matrix(matrix).unify(DomainMatrix.from_Matrix(rhs))
    det = sp.expand(a.domain.to_sympy(a.det()))
    if det == 0:
        return det, []
    numerators, denominator = a.solve_den(b)
    den = a.domain.to_sympy(denominator)
    return det, [sp.cancel(x / den) for x in numerators.to_Matrix()]
