"""How a result shows itself in Python and Jupyter: a one-line ``repr``, a small HTML
table (``_repr_html_``) and ``to_dataframe()``.

A result class derives from :class:`Displayed` (and is declared with
``@record(repr=False)`` (:mod:`powergraph.records`) so the class keeps this ``repr``) and writes
two methods: ``_summary()``, one line of text, and ``_records()``, a list of dicts (one per
row, the same keys in each). pandas is optional: :func:`dataframe` imports it when asked
and says how to install it when it is missing.

Examples
--------
>>> class Table(Displayed):
...     def _summary(self): return "2 rows"
...     def _records(self): return [{"name": "a", "x": 1.0}, {"name": "b", "x": -0.0}]
>>> Table()
<Table 2 rows>
>>> print(Table()._repr_html_())  # doctest: +ELLIPSIS
<table>...<th>name</th><th>x</th>...<td>b</td><td>0</td>...</table>
"""
from __future__ import annotations

import html
from typing import Any, Mapping, Sequence

from powergraph.errors import UsageError
from powergraph.format import format_number

#: Rows shown in an HTML table before it is cut (with a line saying how many are left).
HTML_ROWS = 20


def dataframe(records: Sequence[Mapping[str, Any]] | Mapping[str, Any],
              index: str | None = None) -> Any:
    """A :class:`pandas.DataFrame` of ``records`` (one dict per row, or one mapping of
    columns), indexed by the column ``index`` when given.

    Raises
    ------
    UsageError
        pandas is not installed (it is optional: ``pip install pandas``).
    """
    try:
        import pandas as pd
    except ImportError:
        raise UsageError("to_dataframe() needs pandas, which powergraph does not require: "
                         "pip install pandas") from None
    if isinstance(records, Mapping):
        frame = pd.DataFrame(dict(records))
    else:
        frame = pd.DataFrame.from_records(list(records))
    return frame.set_index(index) if index is not None and len(frame) else frame


def html_table(records: Sequence[Mapping[str, Any]], caption: str = "",
               limit: int = HTML_ROWS) -> str:
    """A small HTML table of ``records``: numbers with four significant digits (never
    ``-0``), the first ``limit`` rows and a line counting the others."""
    columns = list(records[0]) if records else []
    head = "".join(f"<th>{html.escape(str(c))}</th>" for c in columns)
    body = []
    for record in records[:limit]:
        cells = "".join(f"<td>{html.escape(_cell(record.get(c)))}</td>" for c in columns)
        body.append(f"<tr>{cells}</tr>")
    if len(records) > limit:
        body.append(f'<tr><td colspan="{len(columns)}">… {len(records) - limit} more '
                    "rows (to_dataframe() has them all)</td></tr>")
    title = f"<caption>{html.escape(caption)}</caption>" if caption else ""
    return f"<table>{title}<thead><tr>{head}</tr></thead><tbody>{''.join(body)}</tbody></table>"


def _cell(value: Any) -> str:
    if isinstance(value, bool) or value is None:
        return "-" if value is None else ("yes" if value else "no")
    if isinstance(value, float):
        return format_number(value, 4)
    if hasattr(value, "dtype") and getattr(value, "ndim", 1) == 0:
        return _cell(value.item())
    return str(value)


class Displayed:
    """``repr``, ``_repr_html_`` and ``to_dataframe`` from ``_summary()`` and
    ``_records()`` (see the module)."""

    def _summary(self) -> str:  # pragma: no cover - every subclass writes its own
        raise NotImplementedError

    def _records(self) -> list[dict[str, Any]]:  # pragma: no cover
        raise NotImplementedError

    def __repr__(self) -> str:
        return f"<{type(self).__name__} {self._summary()}>"

    def _repr_html_(self) -> str:
        return html_table(self._records(), caption=f"{type(self).__name__}: {self._summary()}")

    def to_dataframe(self) -> Any:
        """The rows as a :class:`pandas.DataFrame` (pandas is optional; a
        :class:`~powergraph.errors.UsageError` says so when it is missing)."""
        return dataframe(self._records())
