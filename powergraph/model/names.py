"""Names and ids in a model file: one line of text each.

A name (the model's, a component's, a port's, a link's or shift element's, a mode's, a
bus's) and a component id appear in reports, in error messages, in a duty cycle's column
headers and on figures, so each is one line of text: no line break nor other control
character. YAML 1.1 reads some bare words as other things — ``off``, ``on``, ``yes``,
``no`` (and ``true``, ``false``) as booleans, ``~`` and ``null`` as nothing — so a mode
written ``off:`` would silently be called ``False``; such a name is refused with a hint to
quote it. A number is a name as written (``1`` is ``"1"``).

Examples
--------
>>> name_text(2, "modes.2"), name_text("MG1", "ports[1].name")
('2', 'MG1')
>>> name_text(False, "modes.False", "mode name")
Traceback (most recent call last):
...
powergraph.errors.ModelError: modes.False: a mode name read as the boolean false: YAML 1.1 \
reads off, on, yes, no, true and false unquoted as booleans; quote the name ('off')
>>> name_text("a\\nb", "modes.a", "mode name")
Traceback (most recent call last):
...
powergraph.errors.ModelError: modes.a: a mode name is one line of text: 'a\\nb' holds a \
line break or another control character
"""
from __future__ import annotations

import re
from typing import Any

from powergraph.errors import ModelError
from powergraph.model.input_files import brief

#: Characters a name may not hold: C0 and C1 controls (line breaks and tabs among them)
#: and the Unicode line and paragraph separators.
_NOT_IN_A_NAME = re.compile("[\x00-\x1f\x7f-\x9f\u2028\u2029]")


def name_text(value: Any, path: str, what: str = "name") -> str:
    """``value`` (a name or id as the YAML gave it) as text, or a :class:`ModelError` at
    ``path`` when it is a boolean, nothing, or more than one line of text."""
    path = _NOT_IN_A_NAME.sub(lambda m: repr(m.group())[1:-1], path)   # one line too
    if isinstance(value, bool):
        raise ModelError(f"a {what} read as the boolean {str(value).lower()}: YAML 1.1 reads "
                         "off, on, yes, no, true and false unquoted as booleans; quote the "
                         "name ('off')", path)
    if value is None:
        raise ModelError(f"a {what} read as nothing: YAML reads ~ and null unquoted as no "
                         "value; quote the name ('~')", path)
    text = str(value)
    if _NOT_IN_A_NAME.search(text):
        raise ModelError(f"a {what} is one line of text: {brief(text)} holds a line break or "
                         "another control character", path)
    return text


def optional_name(value: Any, path: str, what: str = "name") -> str | None:
    """:func:`name_text` of a name that may be left out (None stays None)."""
    return None if value is None else name_text(value, path, what)
