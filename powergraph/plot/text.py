"""Plain text: every text the plots give matplotlib is drawn as written.

Model, component, port, mode and shift-element names come from files. matplotlib reads
a string with two unescaped ``$`` as mathtext (``"$x^2$"`` is drawn as x², and a name
such as ``"$\\frac{a$"`` ends the drawing with a parse error), and with ``text.usetex``
it hands every string to LaTeX. So every text a plot function creates — titles, axis
labels, legends, tick labels, annotations, node and arrow labels — is plain: created
with ``**PLAIN`` (``parse_math=False, usetex=False``), or, for texts matplotlib creates
itself (a legend's entries), made plain with :func:`plain` right after. The string stays
as given (``get_text()`` is the name, ``$`` included): nothing is escaped.

The plots have no mathtext of their own; matplotlib's tick formatters (``10^k`` on a log
axis) are left as they are.

Nothing here imports matplotlib.

Examples
--------
>>> import matplotlib.pyplot as plt                                  # doctest: +SKIP
>>> ax = plt.figure().add_subplot()                                  # doctest: +SKIP
>>> title = ax.set_title("$\\\\frac{a$", **PLAIN)                     # doctest: +SKIP
>>> title.get_text(), title.get_parse_math()                        # doctest: +SKIP
('$\\\\frac{a$', False)
>>> plain(ax.legend(handles, names))                                 # doctest: +SKIP
"""
from __future__ import annotations

from types import MappingProxyType
from typing import Any

#: Keywords of a matplotlib call that creates text (``ax.text``, ``set_title``,
#: ``set_xlabel``, ``annotate``, ``set_xticks(ticks, labels)``, ``bar_label``...): the text
#: is drawn as written, neither mathtext nor TeX.
PLAIN = MappingProxyType({"parse_math": False, "usetex": False})


def plain(*items: Any) -> Any:
    """Make texts already created plain: matplotlib ``Text`` artists, a ``Legend`` (its
    entries and title), or iterables of them. Returns the first item (so a legend can be
    made and made plain in one expression).

    >>> plain([]) == []
    True
    """
    for item in items:
        if item is None:
            continue
        if hasattr(item, "set_parse_math"):
            item.set_parse_math(PLAIN["parse_math"])
            item.set_usetex(PLAIN["usetex"])
        elif hasattr(item, "get_texts"):          # a Legend
            plain(*item.get_texts(), item.get_title())
        else:
            plain(*item)
    return items[0] if items else None
