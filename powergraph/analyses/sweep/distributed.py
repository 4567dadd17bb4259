"""Sweeps beyond one process: the variants cut into parts, each evaluated by a worker.

The flat variants are cut into parts of ``part_size`` (a multiple of the evaluator's chunk
size, so memory stays bounded on every worker), the parts are mapped with
:func:`powergraph.analyses.parallel.map_chunks` (in this process, on a local cluster of
``workers`` processes, or on the Dask cluster at ``scheduler``), and the results are joined
in the order of the variants. Each worker compiles the model once and keeps it for the
parts it is given.

Run in this process, the parts go through one compiled evaluator in order, exactly as a
plain :func:`~powergraph.analyses.sweep.sweep` does, so the results are identical. On
several workers, the numeric backend gives identical results too; with the symbolic
backend each worker learns the closed forms of the direction patterns it meets, so a
variant may go through a closed form on one worker and through the iteration on another:
the two agree to rounding (about 1e-15 relative), statuses and drivers exactly.
"""
from __future__ import annotations

from types import MappingProxyType
from typing import Any, Callable, Mapping
from uuid import uuid4

import numpy as np

from powergraph.analyses.parallel import map_chunks
from powergraph.analyses.sweep.compile import CHUNK_SIZE
from powergraph.analyses.sweep.entry import compile_sweep
from powergraph.analyses.sweep.paths import (broadcast_values, flat_values, parse_paths,
                                             shaped_views)
from powergraph.analyses.sweep.result import SweepResult
from powergraph.errors import UsageError
from powergraph.model.spec import Model

#: Variants of one part (16 chunks of the evaluator).
PART_SIZE = 16 * CHUNK_SIZE

_COMPILED: dict[str, Any] = {}


def sweep_on_cluster(model: Model, values: Mapping[str, Any], *, backend: str = "auto",
                     part_size: int = PART_SIZE, scheduler: str | None = None,
                     workers: int | None = None, mode: str | None = None) -> SweepResult:
    """:func:`~powergraph.analyses.sweep.sweep`, with the variants evaluated in parts on a
    Dask cluster (``scheduler="dask://HOST:PORT"``), on ``workers`` local worker processes,
    or here when neither is given.

    Examples
    --------
    >>> import numpy as np
    >>> from powergraph.model import load_model
    >>> r = sweep_on_cluster(load_model("models/planetary_2kh_sun_to_carrier.yaml"),
    ...                      {"components.ring.teeth": np.array([48, 72, 96])}, part_size=2)
    Traceback (most recent call last):
    ...
    powergraph.errors.UsageError: part_size must be a whole multiple of 16384 variants
    >>> r = sweep_on_cluster(load_model("models/planetary_2kh_sun_to_carrier.yaml"),
    ...                      {"components.ring.teeth": np.array([48, 72, 96])})
    >>> np.round(r.ratio, 12).tolist()
    [3.0, 4.0, 5.0]
    """
    if part_size < CHUNK_SIZE or part_size % CHUNK_SIZE:
        raise UsageError(f"part_size must be a whole multiple of {CHUNK_SIZE} variants")
    arrays, shape = broadcast_values(parse_paths(model, list(values)), values)
    n = int(np.prod(shape, dtype=np.int64))
    flat = flat_values(arrays, shape, keep_scalars=False)
    key = uuid4().hex
    parts = [(key, model, mode, tuple(flat), backend,
              {path: v[start:start + part_size] for path, v in flat.items()})
             for start in range(0, max(n, 1), part_size)]
    try:
        results = map_chunks(_evaluate_part, parts, scheduler=scheduler, workers=workers)
    finally:
        _COMPILED.pop(key, None)    # run here: keep no compiled model after the sweep
    return _joined(model.name, arrays, shape, results)


def _evaluate_part(part: tuple) -> SweepResult:
    """One part on a worker: the model compiled once per sweep (``key``) and kept."""
    key, model, mode, paths, backend, values = part
    if key not in _COMPILED:
        _COMPILED.clear()
        _COMPILED[key] = compile_sweep(model, paths, backend, mode)
    return _COMPILED[key](values, quiet=True)


def _joined(name: str, arrays: Mapping[str, np.ndarray], shape: tuple[int, ...],
            parts: list[SweepResult]) -> SweepResult:
    """One result of the broadcast ``shape`` from the parts' flat results, in order."""
    def joined(get: Callable[[SweepResult], np.ndarray]) -> np.ndarray:
        return np.concatenate([np.ravel(get(p)) for p in parts]).reshape(shape)

    links = tuple(parts[0].losses)
    return SweepResult(
        name=name,
        parameters=shaped_views(arrays, shape),
        ratio=joined(lambda p: p.ratio), efficiency=joined(lambda p: p.efficiency),
        input_power=joined(lambda p: p.input_power),
        output_power=joined(lambda p: p.output_power),
        total_loss=joined(lambda p: p.total_loss),
        losses=MappingProxyType({k: joined(lambda p, k=k: p.losses[k]) for k in links}),
        drivers=MappingProxyType({k: joined(lambda p, k=k: p.drivers[k]) for k in links}),
        self_locking=joined(lambda p: p.self_locking), converged=joined(lambda p: p.converged),
        status=joined(lambda p: p.status), passes=joined(lambda p: p.passes),
        backend=parts[0].backend)
