"""Each chunk: the specialised closed forms first, the general iteration for the rest.

The closed forms are tried in the order given (the caller keeps the one that took the
most variants so far first); each counts the variants it took in ``hits``.

The closed form of a direction pattern (:mod:`~powergraph.analyses.sweep.specialised`)
takes every variant it provably applies to; what is left goes through the general
vectorised iteration (:mod:`~powergraph.analyses.sweep.engine`), whose most common
settled pattern is returned so the caller can compile a closed form for it too.
"""
from __future__ import annotations

import dataclasses
from typing import Sequence

import numpy as np

from powergraph.analyses.sweep.engine import OK, Backend, Chunk, Views, solve_chunk
from powergraph.analyses.sweep.layout import Layout

#: A pattern is worth a closed form when the general path settled this many variants on it.
LEARN_AT_LEAST = 1024


def evaluate_chunk(layout: Layout, backend: Backend, chunk: Chunk, out: Views,
                   closed_forms: Sequence, moving: Sequence[int] | None) -> tuple | None:
    """Solve ``chunk`` into ``out``; return a pattern ``(ideal codes, settled codes)`` of
    the ``moving`` elements worth a closed form, or None (``moving`` None: never)."""
    rest = None
    with np.errstate(all="ignore"):
        for form in closed_forms:
            if rest is None:
                valid = form.evaluate(chunk, out)
                form.hits += _count(valid, chunk.n)
                if valid is True:
                    return None
                rest = np.arange(chunk.n) if valid is False else np.flatnonzero(~valid)
                continue
            part, views = sub_chunk(chunk, rest), empty_views(rest.size, layout.n_elements)
            valid = form.evaluate(part, views)
            form.hits += _count(valid, rest.size)
            if valid is False:
                continue
            taken = np.ones(rest.size, bool) if valid is True else valid
            scatter(views, out, rest[taken], taken)
            rest = rest[~taken]
            if rest.size == 0:
                return None
    if rest is None:
        if moving is None:
            solve_chunk(layout, backend, chunk, out)
            return None
        out = dataclasses.replace(out, ideal=np.empty_like(out.codes))
        solve_chunk(layout, backend, chunk, out)
        return dominant_pattern(out, moving)
    views = empty_views(rest.size, layout.n_elements)
    solve_chunk(layout, backend, sub_chunk(chunk, rest), views)
    scatter(views, out, rest, slice(None))
    return None if moving is None else dominant_pattern(views, moving)


def _count(valid, n: int) -> int:
    return n if valid is True else (0 if valid is False else int(np.count_nonzero(valid)))


def sub_chunk(chunk: Chunk, index: np.ndarray) -> Chunk:
    """The variants ``index`` of ``chunk``."""
    take = lambda values: [v if np.ndim(v) == 0 else v[index] for v in values]  # noqa: E731
    return Chunk(n=int(index.size), magnitudes=take(chunk.magnitudes),
                 efficiencies=take(chunk.efficiencies), speeds=take(chunk.speeds),
                 loads=take(chunk.loads))


FIELDS = ("ratio", "efficiency", "input_power", "output_power", "total_loss",
          "self_locking", "status", "passes")
DTYPES = {"self_locking": bool, "status": np.int8, "passes": np.int8}


def empty_views(n: int, n_el: int) -> Views:
    """Fresh result arrays for ``n`` variants."""
    return Views(**{name: np.empty(n, dtype=DTYPES.get(name, float)) for name in FIELDS},
                 losses=np.empty((n_el, n)), codes=np.empty((n_el, n), dtype=np.int8),
                 ideal=np.empty((n_el, n), dtype=np.int8))


def scatter(source: Views, target: Views, where: np.ndarray, pick) -> None:
    """``target[where] = source[pick]`` for every result array."""
    for name in FIELDS:
        getattr(target, name)[where] = getattr(source, name)[pick]
    target.losses[:, where] = source.losses[:, pick]
    target.codes[:, where] = source.codes[:, pick]


def dominant_pattern(out: Views, moving: Sequence[int]) -> tuple | None:
    """The most common ``(ideal codes, settled codes)`` of the moving elements among the
    solved variants, when at least :data:`LEARN_AT_LEAST` variants share it."""
    solved = out.status == OK
    if not moving or out.ideal is None or np.count_nonzero(solved) < LEARN_AT_LEAST:
        return None
    key = np.zeros(int(np.count_nonzero(solved)), dtype=np.int64)
    rows = [out.ideal[k] for k in moving] + [out.codes[k] for k in moving]
    for row in rows:
        key = key * 3 + (row[solved].astype(np.int64) + 1)
    values, counts = np.unique(key, return_counts=True)
    best = int(np.argmax(counts))
    if counts[best] < LEARN_AT_LEAST:
        return None
    code, digits = int(values[best]), []
    for _ in rows:
        code, digit = divmod(code, 3)
        digits.append(digit - 1)
    digits.reverse()
    return tuple(digits[:len(moving)]), tuple(digits[len(moving):])
