"""Explicit YAML tags in a model file: each standard tag is read or refused in one line.

A model file holds plain data, so only the tags of plain data are read: ``!!str``,
``!!int``, ``!!float``, ``!!bool``, ``!!null``, ``!!timestamp`` (kept as text, as an
untagged date is), ``!!map`` on a mapping and ``!!seq`` on a list, and the merge key
``<<``. A value its tag cannot carry (``!!bool 'maybe'``, ``!!int 'abc'``, ``!!null 'x'``)
is refused, as are ``!!binary``, ``!!set``, ``!!omap``, ``!!pairs``, ``!!python/...`` and
local tags (``!foo``). :func:`tagged_scalar` raises :class:`TagProblem`; the loader adds
the line and key path.

Examples
--------
>>> import yaml
>>> tagged_scalar(TAG + "int", "0x10", yaml.SafeLoader(""))
16
>>> tagged_scalar(TAG + "bool", "maybe", yaml.SafeLoader(""))
Traceback (most recent call last):
...
powergraph.model.yaml_tags.TagProblem: !!bool 'maybe' is not a boolean (true or false)
"""
from __future__ import annotations

from typing import Any

import yaml

TAG = "tag:yaml.org,2002:"
MERGE = TAG + "merge"
STR = TAG + "str"
#: Longest number (in characters) read as a number: no model value needs more.
MAX_NUMBER_DIGITS = 1000


class _MergeKey:
    """The merge key ``<<`` (a plain ``<<`` in key position), unlike the text '<<'."""

    def __repr__(self) -> str:
        return "'<<'"

    def __str__(self) -> str:
        return "<<"


MERGE_KEY = _MergeKey()


class TagProblem(ValueError):
    """A tag that is unsupported or does not fit its value (the loader adds the place)."""


def short(tag: str) -> str:
    """``!!int`` for ``tag:yaml.org,2002:int``; other tags as written.

    >>> short(TAG + "python/tuple"), short("!foo")
    ('!!python/tuple', '!foo')
    """
    return "!!" + tag[len(TAG):] if tag.startswith(TAG) else tag


def check_collection_tag(tag: str | None, kind: str) -> None:
    """Refuse a tag on a mapping (``kind`` "map") or list ("seq") other than its own."""
    if tag in (None, "!", TAG + kind):
        return
    if tag in (TAG + "map", TAG + "seq", STR) or tag in _SCALARS:
        raise TagProblem(f"{short(tag)} does not fit a {_KIND_NAMES[kind]}")
    raise _unsupported(tag)


def tagged_scalar(tag: str, value: str, loader: Any) -> Any:
    """The value of scalar text ``value`` under ``tag`` (resolved or written).

    Raises
    ------
    TagProblem
        The tag is not one of plain data, or the text is not a value of that tag.
    """
    if tag == STR:
        return value
    if tag in _SCALARS:
        if len(value) > MAX_NUMBER_DIGITS:
            raise TagProblem(f"a number written with {len(value)} characters is out of range")
        what, check = _SCALARS[tag]
        node = yaml.ScalarNode(tag, value, None, None)
        try:
            if check is not None and not check(value):
                raise ValueError(value)
            return yaml.SafeLoader.yaml_constructors[tag](loader, node)
        except (ValueError, KeyError, IndexError, TypeError):
            raise TagProblem(f"{short(tag)} {_brief(value)} is not {what}") from None
    if tag == TAG + "timestamp":
        if not yaml.constructor.SafeConstructor.timestamp_regexp.fullmatch(value):
            raise TagProblem(f"!!timestamp {_brief(value)} is not a date or time")
        return value  # a date stays text, as an untagged one does
    if tag == MERGE:
        if value != "<<":
            raise TagProblem(f"!!merge {_brief(value)} is not the merge key <<")
        return MERGE_KEY
    if tag in (TAG + "map", TAG + "seq"):
        raise TagProblem(f"{short(tag)} does not fit a scalar")
    raise _unsupported(tag)


def _unsupported(tag: str) -> TagProblem:
    return TagProblem(f"unsupported YAML tag {short(tag)}: a model file holds plain data "
                      "(mappings, lists, text, numbers, booleans, null)")


def _brief(value: str, limit: int = 40) -> str:
    text = repr(value)
    return text if len(text) <= limit else f"{text[:limit - 4]}...'"


_NULLS = frozenset(("", "~", "null", "Null", "NULL"))
_KIND_NAMES = {"map": "mapping", "seq": "list"}
# Tag -> (what its values are, extra check before PyYAML's constructor or None).
_SCALARS = {TAG + "null": ("null (~, null or nothing)", _NULLS.__contains__),
            TAG + "bool": ("a boolean (true or false)", None),
            TAG + "int": ("an integer", None),
            TAG + "float": ("a number", None)}
