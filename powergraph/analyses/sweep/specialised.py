"""The closed form of a train for one direction pattern, with the check that it applies.

A designer who derives a train's efficiency by hand fixes the direction of power in each
mesh first (DESIGN §3: who drives in the carrier's frame), then checks that the pattern
holds. This module does the same, for any train: for a pattern of driver codes of the
"moving" elements (those whose efficiency is not 1) it substitutes ``f = η`` or ``1/η``
into the symbolic solution, composes speeds, loads, forces, port powers and losses into
one expression graph, and compiles it (``lambdify`` with common-subexpression
elimination). Per variant it then checks what the single solver would find: speeds and
both force systems regular, and the pattern read from the ideal forces (``f = 1``) *and*
from the forces with the pattern's factors equal to the assumed one — the single solver
then settles on the first pass with exactly this pattern. Variants that fail the check
are left to the general iteration (:mod:`powergraph.analyses.sweep.engine`).
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from powergraph.analyses.sweep.dispatch import empty_views, scatter
from powergraph.analyses.sweep.engine import DIRECTION_TOLERANCE, OK, Chunk, Views

if TYPE_CHECKING:  # pragma: no cover
    from powergraph.analyses.sweep.symbolic import SymbolicBackend


class Specialised:
    """Ratio, powers and losses of every variant whose directions settle on ``codes``.

    Parameters
    ----------
    backend : SymbolicBackend
        The train's symbolic solution.
    moving : tuple of int
        Elements whose factor depends on the direction (efficiency not identically 1).
    codes : tuple of int
        Settled driver code of each moving element: +1 gear a drives, -1 gear b, 0 none.
    start : tuple of int, optional
        The codes read from the ideal forces, when they differ from ``codes``: the single
        solver then needs two passes (ideal -> ``start`` -> ``codes`` -> ``codes``), as a
        back-driven train typically does.
    """

    def __init__(self, backend: "SymbolicBackend", moving: tuple[int, ...],
                 codes: tuple[int, ...], start: tuple[int, ...] | None = None) -> None:
        import sympy as sp

        self.layout = backend.layout
        self.moving, self.codes = moving, codes
        self.start = codes if start is None else start
        self.passes = 1 if self.start == codes else 2
        self.hits = 0              # variants taken so far (the caller orders by it)
        lay = self.layout
        etas = sp.symbols(f"e0:{lay.n_elements}")
        loads = sp.symbols(f"p0:{len(lay.loads)}")
        q = backend.ratio_symbols
        det_k, scale_k, speeds = backend.kinematics
        torques = [_torque(load, value, speeds) for load, value in zip(lay.loads, loads)]
        rel = [speeds[a] - speeds[c] for a, c in zip(lay.body_a, lay.body_c)]
        factors = _factors(sp, lay.n_elements, moving, codes, etas)
        ideal = _balance(backend, [q[k] for k in range(lay.n_elements)], torques)
        final = _balance(backend, [q[k] * factors[k] for k in range(lay.n_elements)], torques)
        checks = [ideal, final]
        if self.passes == 2:
            first = _factors(sp, lay.n_elements, moving, self.start, etas)
            checks.insert(1, _balance(backend, [q[k] * first[k]
                                                for k in range(lay.n_elements)], torques))
        products = [f * r for f, r in zip(final[2], rel)]
        powers = _port_powers(lay, speeds, torques, final[2], q, factors)
        ratio = (speeds[lay.ratio_bodies[0]] / speeds[lay.ratio_bodies[1]]
                 if lay.ratio_bodies else sp.nan)
        outputs = [det_k, scale_k, *[x for c in checks for x in c[:2]],
                   *[c[2][k] * rel[k] for c in checks[:-1] for k in moving],
                   *products, *powers, ratio,
                   *[products[k] * (factors[k] - 1) for k in moving],
                   *[sp.Abs(t * speeds[load.body]) for load, t in zip(lay.loads, torques)]]
        self._function = sp.lambdify([q, etas, backend.speed_symbols, loads], outputs,
                                     modules="numpy", cse=True)

    def evaluate(self, chunk: Chunk, out: Views) -> np.ndarray | bool:
        """Write the variants the pattern holds for into ``out``; return where it holds."""
        n, n_el = chunk.n, self.layout.n_elements
        values = iter(self._function(chunk.magnitudes, chunk.efficiencies, chunk.speeds,
                                     chunk.loads))
        valid = next(values) > next(values)                 # speeds regular
        for _ in range(self.passes + 1):                    # every force system regular
            valid = valid & (next(values) > next(values))
        earlier = [[next(values) for _ in self.moving] for _ in range(self.passes)]
        products = [next(values) for _ in range(n_el)]
        input_power, output_power, ratio = next(values), next(values), next(values)
        losses = [next(values) for _ in self.moving]
        power = 0.0
        for term in values:
            power = np.maximum(power, term)
        tolerance = DIRECTION_TOLERANCE * np.maximum(power, 1e-300)
        valid = valid & np.isfinite(tolerance)
        expected = [self.start] + [self.codes] * (self.passes - 1)
        for read, codes in zip(earlier + [[products[k] for k in self.moving]],
                               expected + [self.codes]):
            for product, code in zip(read, codes):
                valid = valid & _holds(product, code, tolerance)
        valid = np.broadcast_to(valid, n)
        if not valid.any():
            return False
        if valid.all():
            self._write(out, input_power, output_power, ratio, products, losses, tolerance)
            return True
        views = empty_views(n, n_el)
        self._write(views, input_power, output_power, ratio, products, losses, tolerance)
        scatter(views, out, valid, valid)
        return valid

    def _write(self, out: Views, input_power, output_power, ratio, products: list,
               losses: list, tolerance) -> None:
        """Every result of the chunk into ``out``, in place."""
        out.input_power[:] = input_power
        out.output_power[:] = output_power
        out.ratio[:] = ratio
        np.divide(out.output_power, out.input_power, out=out.efficiency)
        if not np.all(input_power):
            out.efficiency[out.input_power == 0] = np.nan
        out.total_loss[:] = 0.0
        for loss in losses:
            out.total_loss += loss
        moving = dict(zip(self.moving, range(len(self.moving))))
        for k, product in enumerate(products):
            j = moving.get(k)
            if j is None:
                out.losses[k] = 0.0
                np.subtract(np.asarray(product < -tolerance).view(np.int8),
                            np.asarray(product > tolerance).view(np.int8), out=out.codes[k])
            else:
                out.losses[k] = losses[j]
                out.codes[k] = self.codes[j]
        out.status[:] = OK
        out.passes[:] = self.passes
        np.less_equal(out.efficiency, 0.0, out=out.self_locking)


def _factors(sp, n: int, moving, codes, etas) -> list:
    """``f = η`` (gear a drives), ``1/η`` (gear b), 1 (nothing, or an ideal element)."""
    factors = [sp.Integer(1)] * n
    for k, code in zip(moving, codes):
        factors[k] = etas[k] if code > 0 else (1 / etas[k] if code < 0 else sp.Integer(1))
    return factors


def _torque(load, value, speeds):
    """External torque of a loaded port, as the single solver (SPEC §1 signs)."""
    if load.kind == "torque":
        return value
    w = speeds[load.body]
    return value / w if load.role == "input" else -value / w


def _balance(backend: "SymbolicBackend", gains: list, torques: list) -> tuple:
    """Determinant, its scale and the element forces for these gains and torques."""
    det, scale, forces = backend.balance
    mapping = dict(zip(backend.gain_symbols, gains))
    mapping.update(zip(backend.torque_symbols, torques))
    return (det.xreplace(mapping), scale.xreplace(mapping),
            [f.xreplace(mapping) for f in forces])


def _port_powers(lay, speeds, torques, forces, q, factors) -> tuple:
    """Power fed in by the inputs and taken out by the outputs."""
    given = {load.body: t for load, t in zip(lay.loads, torques)}
    external = {}
    for body in set(lay.inputs + lay.outputs):
        if body in given:
            external[body] = given[body]
            continue
        total = 0
        for k in range(lay.n_elements):
            gain = int(lay.signs[k]) * q[k] * factors[k]
            on_a, on_b, on_c = (int(getattr(lay, f"body_{x}")[k] == body) for x in "abc")
            total += forces[k] * (on_a - gain * on_b + (gain - 1) * on_c)
        external[body] = -total
    return (sum(external[b] * speeds[b] for b in lay.inputs),
            -sum(external[b] * speeds[b] for b in lay.outputs))


def _holds(product, code: int, tolerance):
    """The driver code read from ``λ (w_a - w_c)`` is ``code``."""
    if code > 0:
        return product < -tolerance
    if code < 0:
        return product > tolerance
    return np.abs(product) <= tolerance
