"""The one interface every analysis result offers: ``to_dict``, ``text_report``, ``plot``.

Every result powergraph returns — a power-flow solve, Wang (2021)'s method and the
comparison of methods, backlash, cycloid fluctuation, volume, sweeps, closed-form
formulas, the comparison of trains — is a frozen dataclass with

- ``to_dict()``: plain JSON data (``json.dumps`` works on it);
- ``text_report()``: the readable report the command line prints;
- ``plot(ax=None, **kwargs)``: draws the result's obvious picture and returns the axes.
  It imports its drawing function from :mod:`powergraph.plot` inside the method (the one
  lazy import that crosses the layers, see :mod:`powergraph.plot`); a result with no
  picture raises :class:`NothingToDrawError`.

This module sits in the base layer with :mod:`powergraph.errors` and imports nothing
heavy, so any layer may use it.

Examples
--------
>>> import powergraph as pg
>>> result = pg.solve(pg.load_model("models/rv40e_wang2021.yaml"))     # doctest: +SKIP
>>> isinstance(result, Result)                                # doctest: +SKIP
True
>>> aligned_table([["a", "n"], ["bb", "1"]], {1})
['a   n', '--  -', 'bb  1']
"""
from __future__ import annotations

from typing import Any, Protocol, runtime_checkable

from powergraph.errors import PowerGraphError
from powergraph.format import aligned_table, display_width, pad  # noqa: F401  (re-exported)


@runtime_checkable
class Result(Protocol):
    """What every analysis result offers (checked with ``isinstance(obj, Result)``)."""

    def to_dict(self) -> dict[str, Any]:
        """Plain JSON data (dicts, lists, str, float, int, bool, None)."""

    def text_report(self) -> str:
        """The readable report (what the command line prints)."""

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """Draw on ``ax`` (a new figure when None) and return the axes."""


class NothingToDrawError(PowerGraphError, TypeError):
    """``plot()`` of a result that has no picture (e.g. closed-form formulas)."""


def nothing_to_draw(result: object, instead: str) -> NothingToDrawError:
    """The error a result without a picture raises from ``plot()``.

    Examples
    --------
    >>> str(nothing_to_draw(3, "print text_report()"))
    'int has nothing to draw; print text_report()'
    """
    return NothingToDrawError(f"{type(result).__name__} has nothing to draw; {instead}")
