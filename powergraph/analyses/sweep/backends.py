"""The train's two linear systems over arrays of variants, and its closed forms.

A backend solves, for arrays of variants, the **speeds** (Willis rows over the bodies
whose speed is not given) and the **forces** (the torque balances of the bodies with no
unknown external torque, for the elements' factors ``f``), returning with the forces the
external torques of the other bodies (the reactions). Every coefficient comes from
:func:`~powergraph.kinematics.elements.element_stencil`, placed by the train system
(:class:`~powergraph.kinematics.system.TrainSystem`). Ratio arguments are magnitudes:
``i_k = s_k q_k`` with the sign ``s_k`` of a teeth-swept mesh folded in (``q_k = z_b/z_a``).

- :class:`SymbolicBackend` builds both systems once with sympy
  (:func:`powergraph.analyses.formula.systems.train_systems`, the derivation
  ``powergraph formula`` uses), solves them as adjugate over determinant and compiles them
  with ``lambdify`` (common-subexpression elimination): the closed form a designer would
  derive, for any train. :meth:`SymbolicBackend.closed_form` composes the whole solve of
  one direction pattern into one compiled function (:class:`ClosedForm`).
- :class:`NumericBackend` builds ``(n, rows, cols)`` matrices and solves them batched and
  scaled like the single solve (:func:`powergraph.linalg_batch.solve_square_batch`) — or,
  where a system is not square, with the pseudo-inverse (the minimum-norm solution the
  single solver takes) and a residual check. Slower, but it takes any train.
"""
from __future__ import annotations

import functools
from typing import TYPE_CHECKING, Callable, Sequence

import numpy as np

from powergraph.kinematics.system import TrainSystem
from powergraph.linalg_batch import COND_LIMIT, solve_square_batch, structural_zeros
from powergraph.statics.directions import factor_of, factors_for
from powergraph.statics.equilibrium import port_torque

if TYPE_CHECKING:  # pragma: no cover
    from powergraph.analyses.sweep.layout import Layout
    from powergraph.analyses.sweep.evaluate import Chunk, Outputs

#: Largest system solved symbolically; bigger ones use the numeric backend.
MAX_SYMBOLIC = 8
#: A determinant below this fraction of its terms' absolute sum counts as singular
#: (the single solver's rank tolerance is 1e-10 on singular values).
SINGULAR = 1e-12
#: Singular-value ratio below which a system is rank-deficient (as the single solver).
RANK_TOLERANCE = 1e-10


def applies(layout: "Layout") -> bool:
    """True when both reduced systems are square, small and statically determinate."""
    return (layout.determinate and len(layout.free_bodies) == layout.n_elements
            == len(layout.balance_bodies) and len(set(layout.unknown)) == len(layout.unknown)
            and 0 < layout.n_elements <= MAX_SYMBOLIC)


@functools.lru_cache(maxsize=64)
def symbolic_backend(layout: "Layout") -> "SymbolicBackend":
    """The :class:`SymbolicBackend` of ``layout``, derived once per process: it depends on
    the layout alone (its symbols stand for every value a sweep varies), so sweeps of the
    same structure — the same train swept again, the modes of a cycle row after row, a
    model changed only in its numbers — share its derivation and its closed forms.

    >>> from powergraph.model import load_model
    >>> from powergraph.analyses.sweep import compile_sweep
    >>> one = compile_sweep(load_model("models/rv40e_wang2021.yaml"), ["links.1.efficiency"])
    >>> two = compile_sweep(load_model("models/rv40e_wang2021.yaml"), ["links.1.efficiency"])
    >>> one is two, one.backend is two.backend
    (False, True)
    """
    return SymbolicBackend(layout)


class SymbolicBackend:
    """Speeds, element forces and reactions of a train as compiled closed forms
    (:func:`symbolic_backend` keeps one per layout)."""

    name = "symbolic"

    def __init__(self, layout: "Layout") -> None:
        import sympy as sp

        from powergraph.analyses.formula.systems import train_systems

        self.layout = lay = layout
        n = lay.n_elements
        self.q, self.f = sp.symbols(f"q0:{n}"), sp.symbols(f"f0:{n}")
        self.w = sp.symbols(f"w0:{len(lay.speed_ports)}")
        self.t = sp.symbols(f"t0:{len(lay.loads)}")
        ratios = [sp.Integer(1) if lay.kinds[k] == "coupling"
                  else sp.Integer(int(lay.signs[k])) * self.q[k] for k in range(n)]
        known = {lay.frame: sp.Integer(0)}
        known.update({body: self.w[j] for j, (body, _) in enumerate(lay.speed_ports)})
        systems = train_systems(range(lay.n_bodies), lay.places, ratios, self.f, known,
                                {load.body: t for load, t in zip(lay.loads, self.t)},
                                lay.unknown)
        det, scale, values = _solve(sp, systems.speed_matrix, systems.speed_rhs)
        by_free = dict(zip(systems.free, values))
        self.kinematics = (det, scale, [known[j] if j in known else by_free[j]
                                        for j in range(lay.n_bodies)])
        det, scale, forces = _solve(sp, systems.force_matrix, systems.force_rhs)
        solved = dict(zip(systems.forces, forces))
        reactions = [systems.reactions[body].xreplace(solved) for body in lay.unknown]
        self.balance = (det, scale, forces + reactions)
        self._speeds = _lambdify(sp, [self.q, self.w], [*self.kinematics[:2],
                                                        *self.kinematics[2]])
        self._forces = _lambdify(sp, [self.q, self.f, self.t], [det, scale, *forces,
                                                                *reactions])

    def speeds(self, ratios: Sequence, given: Sequence) -> tuple[list, np.ndarray]:
        """Absolute speed of every body (rad/s), and where the Willis rows are regular."""
        det, scale, *values = self._speeds(list(ratios), list(given))
        return values, det > scale

    def forces(self, ratios: Sequence, factors: Sequence,
               torques: Sequence) -> tuple[list, np.ndarray]:
        """Force ``λ_k`` (torque on gear a) of every element, then the reaction of every
        body of ``layout.unknown``; and where the balance is regular (loads determined)."""
        det, scale, *values = self._forces(list(ratios), list(factors), list(torques))
        return values, det > scale

    def closed_form(self, moving: Sequence[int], codes: Sequence[int],
                    start: Sequence[int] | None = None) -> "ClosedForm":
        """The compiled closed form of this train for one direction pattern."""
        return ClosedForm(self, tuple(moving), tuple(codes),
                          None if start is None else tuple(start))


def _solve(sp, matrix, rhs) -> tuple:
    """``|det|``, its singularity threshold (:data:`SINGULAR` times the sum of the
    determinant's terms in absolute value) and the solution."""
    from powergraph.analyses.formula.systems import solve_linear

    det, solution = solve_linear(matrix, rhs)
    terms = sp.Add(*(sp.Abs(term) for term in sp.Add.make_args(det)))
    return sp.Abs(det), sp.Mul(sp.Float(SINGULAR), terms, evaluate=False), solution


def _lambdify(sp, args, expressions) -> Callable:
    """numpy function of ``args`` (call it under ``np.errstate(all="ignore")``)."""
    return sp.lambdify(args, list(expressions), modules="numpy", cse=True)


class ClosedForm:
    """The whole solve of one direction pattern as one compiled function, with the check
    that the pattern holds.

    A designer who derives a train's efficiency by hand fixes who drives each mesh in its
    carrier's frame first, then checks that this holds. Here, for the driver ``codes`` of
    the ``moving`` elements (efficiency not identically 1), ``f = η`` or ``1/η`` goes into
    the symbolic solution, and the speeds, the given torques and the forces are composed
    into one expression graph. Per variant :meth:`evaluate` checks what the single solver
    would find, with its own rule for the directions
    (:func:`~powergraph.analyses.sweep.evaluate.element_codes`): the speed and force
    systems regular, and the pattern read from the ideal forces (``f = 1``), then (two
    passes, ``start`` differing from ``codes``, as a back-driven train typically needs)
    from ``start``'s forces, and from the pattern's own forces. Variants that fail the
    check are left to the general iteration.
    """

    def __init__(self, backend: SymbolicBackend, moving: tuple[int, ...],
                 codes: tuple[int, ...], start: tuple[int, ...] | None = None) -> None:
        self.layout = backend.layout
        self.moving, self.codes = moving, codes
        self.start = codes if start is None else start
        self.passes = 1 if self.start == codes else 2
        self.hits = 0              # variants taken so far (the caller orders by it)
        #: The arguments (ratio magnitudes, efficiencies, given speeds, loads: symbols per
        #: element, speed and load) and the expressions the function computes, in order
        #: (read again by :mod:`~powergraph.analyses.sweep.kernel`).
        self._patterns, self.symbols, self.expressions, self._function = _composed(
            backend, moving, codes, self.start)

    @property
    def checked(self) -> tuple[tuple[tuple[int, ...], tuple[int, ...]], ...]:
        """``(factor pattern, codes expected)`` of each force system :meth:`evaluate` checks,
        in order: the ideal forces read ``start``, then (two passes) ``start``'s forces
        read ``codes``, and the pattern's own forces read ``codes``."""
        expected = [self.start] + [self.codes] * self.passes
        return tuple(zip(self._patterns, expected))

    def evaluate(self, chunk: "Chunk", out: "Outputs") -> np.ndarray | bool:
        """Write the variants the pattern holds for into ``out``; return where it holds."""
        from powergraph.analyses.sweep.evaluate import (element_codes, relative_speeds,
                                                        write_settled)

        lay, n = self.layout, chunk.n
        values = iter(self._function(chunk.magnitudes, chunk.efficiencies, chunk.speeds,
                                     chunk.loads))
        valid = next(values) > next(values)                 # speeds regular
        speeds = [next(values) for _ in range(lay.n_bodies)]
        torques = [next(values) for _ in lay.loads]
        for torque, load in zip(torques, lay.loads):
            valid = valid & np.isfinite(torque * speeds[load.body])
        rel = relative_speeds(lay, speeds)
        etas = [chunk.efficiencies[k] for k in self.moving]
        for pattern, codes in self.checked:
            valid = valid & (next(values) > next(values))    # the force system regular
            forces = [next(values) for _ in range(lay.n_elements + len(lay.unknown))]
            factors = [factors_for(c, e) for c, e in zip(pattern, etas)]
            read = element_codes(lay, chunk.magnitudes, torques, rel, forces,
                                 dict(zip(self.moving, factors)))
            for k, code in zip(self.moving, codes):
                valid = valid & (read[k] == code)
        valid = np.broadcast_to(valid, n)
        if not valid.any():
            return False
        target = out if valid.all() else type(out).empty(n, lay.n_elements)
        write_settled(lay, chunk, torques, rel, speeds, forces, factors, self.moving, target,
                      self.passes, read)
        if target is out:
            return True
        out.put(valid, target, valid)
        return valid


@functools.lru_cache(maxsize=256)
def _composed(backend: SymbolicBackend, moving: tuple[int, ...], codes: tuple[int, ...],
              start: tuple[int, ...]) -> tuple:
    """What a :class:`ClosedForm` computes — the patterns it checks, its arguments, its
    expressions and their compiled function — derived once per backend and pattern."""
    import sympy as sp

    lay = backend.layout
    n = lay.n_elements
    etas, loads = sp.symbols(f"e0:{n}"), sp.symbols(f"p0:{len(lay.loads)}")
    det_k, scale_k, speeds = backend.kinematics
    torques = [_torque(load, value, speeds) for load, value in zip(lay.loads, loads)]
    patterns = [(0,) * len(moving)] + ([start] if start != codes else []) + [codes]
    checks = [_balance(backend, _factors(sp, n, moving, pattern, etas), torques)
              for pattern in patterns]
    outputs = [det_k, scale_k, *speeds, *torques,
               *[x for c in checks for x in (c[0], c[1], *c[2])]]
    symbols = (tuple(backend.q), tuple(etas), tuple(backend.w), tuple(loads))
    return (tuple(patterns), symbols, tuple(outputs),
            _lambdify(sp, [backend.q, etas, backend.w, loads], outputs))


def _factors(sp, n: int, moving, codes, etas) -> list:
    """``f = η`` (gear a drives), ``1/η`` (gear b), 1 (nothing, or an ideal element)."""
    factors = [sp.Integer(1)] * n
    for k, code in zip(moving, codes):
        factors[k] = sp.sympify(factor_of(code, etas[k]))
    return factors


def _torque(load, value, speeds):
    """External torque of a loaded port, as the single solver
    (:func:`powergraph.statics.equilibrium.port_torque`)."""
    return port_torque(value, load.kind, load.role, speeds[load.body])


def _balance(backend: SymbolicBackend, factors: list, torques: list) -> tuple:
    """Determinant, its scale, and the forces and reactions for these factors and torques."""
    det, scale, forces = backend.balance
    mapping = dict(zip(backend.f, factors))
    mapping.update(zip(backend.t, torques))
    return (det.xreplace(mapping), scale.xreplace(mapping),
            [f.xreplace(mapping) for f in forces])


class NumericBackend:
    """Speeds, element forces and reactions by batched linear solves."""

    name = "numeric"

    def __init__(self, layout: "Layout") -> None:
        self.layout = layout
        self._free = {body: j for j, body in enumerate(layout.free_bodies)}
        self.system = TrainSystem(layout.n_bodies, layout.places, layout.unknown)

    def speeds(self, ratios: Sequence, given: Sequence) -> tuple[list, np.ndarray]:
        """Absolute speed of every body, and where the Willis rows fix them (regular)."""
        lay = self.layout
        n = _length(list(ratios) + list(given))
        known = {lay.frame: np.zeros(n)}
        for (body, _), value in zip(lay.speed_ports, given):
            known[body] = np.broadcast_to(np.asarray(value, float), n)
        rows = self.system.willis(self._signed(ratios, n))           # (n, E, B)
        matrix = rows[:, :, list(self._free)]
        rhs = np.zeros((n, lay.n_elements))
        for body, speed in known.items():
            rhs -= rows[:, :, body] * speed[:, None]
        solution, bad = _batched_solve(matrix, rhs, full_rank_needed=True)
        speeds = [known[j] if j in known else solution[:, self._free[j]]
                  for j in range(lay.n_bodies)]
        return _squeezed(speeds, bad, list(ratios) + list(given))

    def forces(self, ratios: Sequence, factors: Sequence,
               torques: Sequence) -> tuple[list, np.ndarray]:
        """Element forces ``λ``, then the reactions of ``layout.unknown``; and where the
        loads are fixed."""
        lay = self.layout
        n = _length(list(ratios) + list(factors) + list(torques))
        n_el = lay.n_elements
        matrix = self.system.balance(self._signed(ratios, n),
                                     [np.broadcast_to(np.asarray(f, float), n)
                                      for f in factors])
        rhs = np.zeros((n, lay.n_bodies))
        for load, torque in zip(lay.loads, torques):
            rhs[:, load.body] -= torque
        solution, bad = _batched_solve(matrix, rhs, full_rank_needed=lay.determinate)
        forces = solution[:, :n_el]
        on_body = np.einsum("nbk,nk->nb", matrix[:, :, :n_el], forces)
        reactions = [rhs[:, body] - on_body[:, body] for body in lay.unknown]
        return _squeezed(list(forces.T) + reactions, bad,
                         list(ratios) + list(factors) + list(torques))

    def _signed(self, ratios: Sequence, n: int) -> np.ndarray:
        """``(E, n)`` Willis ratios from the backend's ratio magnitudes."""
        return np.array([np.broadcast_to(sign * np.asarray(r, float), n)
                         for sign, r in zip(self.layout.signs, ratios)]).reshape(-1, n)


def _squeezed(values: list, bad: np.ndarray, inputs: list) -> tuple[list, np.ndarray]:
    """Scalars out when every input was a scalar (results broadcast like the symbolic
    backend's); the mask returned is ``regular`` (not bad)."""
    if any(np.ndim(v) for v in inputs):
        return values, ~bad
    return [float(v[0]) for v in values], not bad[0]


def _length(values: list) -> int:
    sizes = {np.size(v) for v in values if np.ndim(v)}
    return max(sizes) if sizes else 1


def _batched_solve(matrix: np.ndarray, rhs: np.ndarray,
                   full_rank_needed: bool) -> tuple[np.ndarray, np.ndarray]:
    """Batched solve; ``bad`` where inconsistent, or rank-deficient when a full rank is
    needed (speeds; loads of a statically determinate train).

    Square systems first set the unknowns their structure makes exactly 0
    (:func:`~powergraph.linalg_batch.structural_zeros`: an idle gear's force), then are
    solved scaled, each by its own unknowns, and judged regular on the scaled system
    (:func:`powergraph.linalg_batch.solve_square_batch`, the single solve's procedure and
    limits); the others (load sharing not fixed by statics) take the minimum-norm
    solution, with a residual check.
    """
    with np.errstate(all="ignore"):
        finite = np.all(np.isfinite(matrix), axis=(1, 2)) & np.all(np.isfinite(rhs), axis=1)
        clean = np.where(finite[:, None, None], matrix, 0.0)
        solution = np.full((matrix.shape[0], matrix.shape[2]), np.nan)
        regular = np.zeros(matrix.shape[0], dtype=bool)
        if matrix.shape[1] == matrix.shape[2] and finite.any():
            zero, used = structural_zeros(np.any(clean[finite] != 0, axis=0),
                                          np.all(rhs[finite] == 0, axis=0))
            keep_rows, keep_cols = np.flatnonzero(~used), np.flatnonzero(~zero)
            x, condition = solve_square_batch(clean[finite][:, keep_rows][:, :, keep_cols],
                                              rhs[finite][:, keep_rows])
            part = np.zeros((x.shape[0], matrix.shape[2]))
            part[:, keep_cols] = x
            solution[finite] = part
            regular[finite] = (condition < COND_LIMIT) & np.all(np.isfinite(x), axis=1)
        rest = finite & ~regular
        if rest.any() and not (full_rank_needed and matrix.shape[1] == matrix.shape[2]):
            singular_values = np.linalg.svd(clean[rest], compute_uv=False)
            top = np.maximum(singular_values[:, :1], 1.0)
            full_rank = np.sum(singular_values > RANK_TOLERANCE * top, axis=1) == \
                matrix.shape[2]
            pinv = np.linalg.pinv(clean[rest], rcond=RANK_TOLERANCE)
            solution[rest] = (pinv @ rhs[rest][..., None])[..., 0]
            residual = np.einsum("nij,nj->ni", clean[rest], solution[rest]) - rhs[rest]
            scale = np.maximum(1.0, np.max(np.abs(rhs[rest]), axis=1))
            consistent = np.max(np.abs(residual), axis=1) <= 1e-8 * scale
            regular[rest] = consistent & (full_rank | (not full_rank_needed))
    return solution, ~regular
