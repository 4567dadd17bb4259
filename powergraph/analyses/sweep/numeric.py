"""The numeric backend: the single solver's matrices, batched over the variants.

For every variant the Willis rows over the bodies whose speed is not given, and the full
torque balance (element forces, unknown external torques), are built as ``(n, rows, cols)``
arrays by fancy indexing, and solved with batched ``numpy.linalg.solve`` — or, where a
system is not square or is singular, with the pseudo-inverse (the minimum-norm
least-squares solution the single solver takes) and a residual check. Slower than the
symbolic backend, but it takes any train.
"""
from __future__ import annotations

from typing import Sequence

import numpy as np

from powergraph.analyses.sweep.layout import Layout

#: Singular-value ratio below which a system is rank-deficient (as the single solver).
RANK_TOLERANCE = 1e-10


class NumericBackend:
    """Speeds and element forces by batched linear solves.

    Examples
    --------
    >>> from powergraph.model import load_model
    >>> from powergraph.analyses.sweep.layout import layout_of
    >>> backend = NumericBackend(layout_of(load_model("models/rv40e.yaml"), ()))  # doctest: +SKIP
    """

    name = "numeric"

    def __init__(self, layout: Layout) -> None:
        self.layout = layout
        self._free = {body: j for j, body in enumerate(layout.free_bodies)}

    def speeds(self, ratios: Sequence, given: Sequence) -> tuple[list, np.ndarray]:
        """Absolute speed of every body, and where the Willis rows fix them (regular)."""
        lay = self.layout
        n = _length(list(ratios) + list(given))
        known = {lay.frame: np.zeros(n)}
        for (body, _), value in zip(lay.speed_ports, given):
            known[body] = np.broadcast_to(np.asarray(value, float), n)
        matrix = np.zeros((n, lay.n_elements, len(self._free)))
        rhs = np.zeros((n, lay.n_elements))
        for k in range(lay.n_elements):
            i = lay.signs[k] * np.asarray(ratios[k], float)
            for body, coef in ((lay.body_a[k], 1.0), (lay.body_b[k], -i),
                               (lay.body_c[k], i - 1.0)):
                if body in self._free:
                    matrix[:, k, self._free[body]] += coef
                else:
                    rhs[:, k] -= coef * known[body]
        solution, bad = _solve(matrix, rhs, full_rank_needed=True)
        speeds = [known[j] if j in known else solution[:, self._free[j]]
                  for j in range(lay.n_bodies)]
        return _squeezed(speeds, bad, list(ratios) + list(given))

    def forces(self, gains: Sequence, torques: Sequence) -> tuple[list, np.ndarray]:
        """Element forces ``λ`` for gains ``g = i f``, and where the loads are fixed."""
        lay = self.layout
        n = _length(list(gains) + list(torques))
        n_el = lay.n_elements
        matrix = np.zeros((n, lay.n_bodies, n_el + len(lay.unknown)))
        for k in range(n_el):
            g = lay.signs[k] * np.asarray(gains[k], float)
            matrix[:, lay.body_a[k], k] += 1.0
            matrix[:, lay.body_b[k], k] -= g
            matrix[:, lay.body_c[k], k] += g - 1.0
        for j, body in enumerate(lay.unknown):
            matrix[:, body, n_el + j] = 1.0
        rhs = np.zeros((n, lay.n_bodies))
        for load, torque in zip(lay.loads, torques):
            rhs[:, load.body] -= torque
        solution, bad = _solve(matrix, rhs, full_rank_needed=lay.determinate)
        forces = [solution[:, k] for k in range(n_el)]
        return _squeezed(forces, bad, list(gains) + list(torques))


def _squeezed(values: list, bad: np.ndarray, inputs: list) -> tuple[list, np.ndarray]:
    """Scalars out when every input was a scalar (results broadcast like the symbolic
    backend's); the mask returned is ``regular`` (not bad)."""
    if any(np.ndim(v) for v in inputs):
        return values, ~bad
    return [float(v[0]) for v in values], not bad[0]


def _length(values: list) -> int:
    sizes = {np.size(v) for v in values if np.ndim(v)}
    return max(sizes) if sizes else 1


def _solve(matrix: np.ndarray, rhs: np.ndarray,
           full_rank_needed: bool) -> tuple[np.ndarray, np.ndarray]:
    """Batched solve; ``bad`` where inconsistent, or rank-deficient when a full rank is
    needed (speeds; loads of a statically determinate train)."""
    with np.errstate(all="ignore"):
        finite = np.all(np.isfinite(matrix), axis=(1, 2)) & np.all(np.isfinite(rhs), axis=1)
        clean = np.where(finite[:, None, None], matrix, 0.0)
        singular_values = np.linalg.svd(clean, compute_uv=False)
        top = np.maximum(singular_values[:, :1], 1.0)
        rank = np.sum(singular_values > RANK_TOLERANCE * top, axis=1)
        square = matrix.shape[1] == matrix.shape[2]
        full_rank = rank == matrix.shape[2]
        solution = np.full((matrix.shape[0], matrix.shape[2]), np.nan)
        exact = finite & full_rank if square else np.zeros_like(finite)
        if exact.any():
            solution[exact] = np.linalg.solve(clean[exact], rhs[exact][..., None])[..., 0]
        rest = finite & ~exact
        if rest.any():
            pinv = np.linalg.pinv(clean[rest], rcond=RANK_TOLERANCE)
            solution[rest] = (pinv @ rhs[rest][..., None])[..., 0]
        residual = np.einsum("nij,nj->ni", np.where(finite[:, None, None], matrix, 0.0),
                             np.nan_to_num(solution)) - rhs
        scale = np.maximum(1.0, np.max(np.abs(rhs), axis=1))
        inconsistent = np.max(np.abs(residual), axis=1) > 1e-8 * scale
        bad = ~finite | inconsistent | (full_rank_needed & ~full_rank)
    return solution, bad
