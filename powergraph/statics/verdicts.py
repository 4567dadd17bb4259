"""The verdict of an answer: one word a designer reads before any number.

Every evaluator reports it for each operating point it solves (``solve``, each gear-table
row forward and coasting, each cycle row, each sweep variant), from the same function, so
two evaluators cannot call the same point differently.
"""
from __future__ import annotations

from typing import Any

#: The verdicts of a solved point (a point with no consistent freewheel state has no
#: result; its verdict says why).
VERDICTS = ("ok", "self-locking", "locked", "no power")
#: What each verdict but ``ok`` means, for the reports' legends.
MEANINGS = {"self-locking": "the declared input cannot drive the output (efficiency 0; "
                            "the output must be driven too)",
            "locked": "the train cannot move as asked and stays at rest (efficiency 0)",
            "no power": "no power passes through the train (the efficiency is undefined)"}


def verdict_of(result: Any) -> str:
    """The verdict of a solved operating point (a :class:`PowerFlowResult`): ``locked``,
    ``no power``, ``self-locking`` or ``ok``.

    >>> from powergraph.model import load_model
    >>> from powergraph.statics import solve
    >>> verdict_of(solve(load_model("models/rv40e.yaml")))
    'ok'
    """
    if result.lock is not None:
        return "locked"
    if result.efficiency_note is not None:
        return "no power"
    return "self-locking" if result.self_locking else "ok"


def combined(verdict: str, search: str) -> str:
    """A point's verdict with what its freewheel search says when that is not ``ok``
    (``2 consistent freewheel states; the first is reported``).

    >>> combined("ok", "ok"), combined("self-locking", "2 consistent states")
    ('ok', 'self-locking; 2 consistent states')
    """
    if search == "ok":
        return verdict
    return search if verdict == "ok" else f"{verdict}; {search}"
