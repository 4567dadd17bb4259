"""The verdict of an answer: one word a designer reads before any number.

Every evaluator reports it for each operating point it solves (``solve``, each gear-table
row forward and coasting, each cycle row, each sweep variant), from the same function, so
two evaluators cannot call the same point differently.
"""
from __future__ import annotations

from typing import Any

import numpy as np

#: The verdicts of a solved point, by code (a point with no consistent freewheel state
#: has no result; its verdict says why).
VERDICTS = ("ok", "locked", "self-locking", "no power")
#: What each verdict but ``ok`` means, for the reports' legends.
MEANINGS = {"self-locking": "the declared input cannot drive the output (efficiency 0; "
                            "the output must be driven too)",
            "locked": "the train cannot move as asked and stays at rest (efficiency 0)",
            "no power": "no power passes through the train (the efficiency is undefined)"}


def verdict_codes(locked: Any, self_locking: Any, no_power: Any) -> np.ndarray:
    """The rule, on one point or arrays of them: codes into :data:`VERDICTS` — ``locked``
    first, then ``no power`` (no port passes power), then ``self-locking``, else ``ok``.

    >>> verdict_codes([True, False, False, False], [True, False, True, False],
    ...               [False, True, False, False]).tolist()
    [1, 3, 2, 0]
    """
    return np.where(locked, 1, np.where(no_power, 3, np.where(self_locking, 2, 0)))


def verdict_of(result: Any) -> str:
    """The verdict of a solved operating point (a :class:`PowerFlowResult`).

    >>> from powergraph.model import load_model
    >>> from powergraph.statics import solve
    >>> verdict_of(solve(load_model("models/rv40e.yaml")))
    'ok'
    """
    return VERDICTS[int(verdict_codes(result.lock is not None, result.self_locking,
                                      result.efficiency_note is not None))]


def combined(verdict: str, search: str) -> str:
    """A point's verdict with what its freewheel search says when that is not ``ok``
    (``2 consistent freewheel states; the first is reported``).

    >>> combined("ok", "ok"), combined("self-locking", "2 consistent states")
    ('ok', 'self-locking; 2 consistent states')
    """
    if search == "ok":
        return verdict
    return search if verdict == "ok" else f"{verdict}; {search}"
