"""Strict, bounded YAML reading: every problem becomes a one-line ModelError with its place.

- Size: a model file larger than :func:`max_model_bytes` (10 MB unless the environment
  variable ``POWERGRAPH_MAX_MODEL_BYTES`` or ``powergraph --max-model-size`` says otherwise)
  is refused before it is parsed; devices and pipes are read only up to that size.
- Text: invalid UTF-8, control characters (NUL, ``\\x01``...) and a byte-order mark after
  the start of the file are refused with their line and column.
- Structure: duplicate keys are refused (PyYAML silently keeps the last one, which loses a
  component); anchors and aliases are allowed, but the nodes they add by expansion are
  counted and bounded (:data:`MAX_ALIAS_EXPANSION`), so a "billion laughs" file fails at
  once while a large plain file does not; nesting is bounded (:data:`MAX_DEPTH`).
- Merge keys as in YAML 1.1: ``<<: *base`` (or a list, the earlier base winning) adds the
  keys the mapping does not write itself; a key written twice is still an error.
- Only plain data: strings, numbers, booleans, null, mappings and lists (a date stays text;
  other tags, and values their tag cannot carry, are refused: :mod:`.yaml_tags`).

The document is built directly from the parser's events with an explicit stack (libyaml's
C parser when PyYAML has it), so loading is linear in the file size and never recurses.

Examples
--------
>>> load_yaml_text("a: 1\\nb: [1, 2]\\n")
{'a': 1, 'b': [1, 2]}
>>> load_yaml_text("a: 1\\na: 2\\n")
Traceback (most recent call last):
...
powergraph.errors.ModelError: a: duplicate key 'a' (line 2; first at line 1)
"""
from __future__ import annotations

import gc
import re
from contextlib import contextmanager
from pathlib import Path
from typing import Any, Iterator

import yaml
from yaml import events as ev

from powergraph.errors import ModelError
from powergraph.model.input_files import KINDS, brief, max_bytes, place, read_bytes
from powergraph.model.input_files import size_limit  # noqa: F401  (the CLI sets it here)
from powergraph.model.yaml_tags import MAX_NUMBER_DIGITS, MERGE_KEY, TagProblem
from powergraph.model.yaml_tags import check_collection_tag, tagged_scalar

#: Most nodes that anchors and aliases may add to a document by expansion.
MAX_ALIAS_EXPANSION = 100_000
#: Deepest nesting of mappings and lists (a model needs about six levels).
MAX_DEPTH = 100
#: Default size limit of a model file, in bytes (the model kind of input file).
DEFAULT_MAX_MODEL_BYTES = KINDS["model"].default
ENV_MAX_MODEL_BYTES = KINDS["model"].variable

_Loader = getattr(yaml, "CSafeLoader", yaml.SafeLoader)


def max_model_bytes() -> int:
    """The size limit of model files in bytes (``--max-model-size``, then the environment
    variable ``POWERGRAPH_MAX_MODEL_BYTES``, then 10 MB).

    >>> max_model_bytes() > 0
    True
    """
    return max_bytes("model")


@contextmanager
def gc_paused() -> Iterator[None]:
    """Pause the cycle collector: reading or building a large model creates millions of
    acyclic objects, and collections over them would make the work quadratic."""
    enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if enabled:
            gc.enable()


def join_path(prefix: str, key: Any) -> str:
    """Path of mapping key ``key`` inside the element at ``prefix``.

    >>> join_path("links[2]", "carrier"), join_path("", "name"), join_path("components", 7)
    ('links[2].carrier', 'name', 'components.7')
    """
    return f"{prefix}.{key}" if prefix else str(key)


def _check_text(data: bytes, source: str) -> None:
    """Refuse invalid UTF-8, control characters and a byte-order mark after the start."""
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise ModelError(f"not UTF-8 text: invalid byte 0x{data[exc.start]:02x} at "
                         f"{place(data, exc.start)}", source) from None
    match = _BAD_CHARACTER.search(text)
    bad = match.start() if match else None
    if bad is not None:
        ch = text[bad]
        what = "byte-order mark" if ch == "\ufeff" else "control character"
        offset = len(text[:bad].encode("utf-8", errors="surrogatepass"))
        raise ModelError(f"{what} U+{ord(ch):04X} at {place(data, offset)} is not allowed "
                         "in a model file", source)


def load_yaml_text(text: str | bytes, source: str = "<model>") -> Any:
    """Parse YAML text strictly into plain Python data.

    Parameters
    ----------
    text : str or bytes
        The YAML document (bytes must be UTF-8).
    source : str
        Name used in messages (usually the file name).

    Returns
    -------
    object
        Dicts, lists and scalars.

    Raises
    ------
    ModelError
        Bad characters, syntax error, duplicate key, several documents, unsupported tag,
        too deep nesting, or aliases that expand past :data:`MAX_ALIAS_EXPANSION` nodes,
        each with its line.
    """
    if isinstance(text, str):
        data = text.encode("utf-8", errors="surrogatepass")
    else:
        data = bytes(text)
    _check_text(data, source)
    loader = _Loader(data)
    try:
        with gc_paused():
            return _Builder(loader, source).document()
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        where = f"line {mark.line + 1}, column {mark.column + 1}" if mark else "unknown place"
        problem = exc.problem or exc.context or "invalid YAML"
        if "nesting depth" in problem:   # PyYAML >= 6.0.4 bounds the depth in its parser
            raise ModelError(f"the document nests more than {MAX_DEPTH} levels deep "
                             f"({where})", source) from None
        raise ModelError(f"YAML syntax error at {where}: {problem}", source) from None
    except yaml.YAMLError as exc:
        raise ModelError(f"invalid YAML: {' '.join(str(exc).split())}", source) from None
    finally:
        loader.dispose()


class _Builder:
    """Plain data from parser events, with an explicit stack (no recursion)."""

    def __init__(self, loader: Any, source: str) -> None:
        self.loader, self.source = loader, source
        self.anchors: dict[str, tuple[Any, int]] = {}
        self.open_anchors: set[str] = set()
        self.expansion = 0
        self.plain: dict[str, Any] = {}  # plain scalar text -> its value

    def document(self) -> Any:
        get = self.loader.get_event
        get()  # StreamStart
        start = get()
        if isinstance(start, ev.StreamEndEvent):
            raise ModelError(f"{self.source} is empty: a model needs name, components, links "
                             "and ports")
        root = self._node(get)
        if root is MERGE_KEY:
            root = "<<"
        get()  # DocumentEnd
        extra = get()
        if not isinstance(extra, ev.StreamEndEvent):
            raise ModelError(f"line {extra.start_mark.line + 1}: a model file holds one YAML "
                             "document, found a second one", self.source)
        return root

    def _error(self, message: str, event: Any, path: str = "") -> ModelError:
        return ModelError(f"{message} (line {event.start_mark.line + 1})",
                          path or self.source)

    def _node(self, get) -> Any:
        # Frame: [container, path, anchor, size, pending key, key line, seen keys, is_map,
        #         merged keys (a dict, once the mapping has a merge key) or None]
        stack: list[list] = []
        scalar, add = self._scalar, self._add
        while True:
            event = get()
            kind = type(event)
            if kind is ev.ScalarEvent:
                value, size = scalar(event, stack), 1
                if event.anchor is not None:
                    self.anchors[event.anchor] = (value, 1)
            elif kind is ev.MappingEndEvent or kind is ev.SequenceEndEvent:
                frame = stack.pop()
                value, size = frame[0], frame[3]
                if frame[8] is not None:  # explicit keys override the merged ones
                    value = {**frame[8], **value}
                if frame[2] is not None:
                    self.anchors[frame[2]] = (value, size)
                    self.open_anchors.discard(frame[2])
            elif kind is ev.MappingStartEvent or kind is ev.SequenceStartEvent:
                if len(stack) >= MAX_DEPTH:
                    raise self._error(f"the document nests more than {MAX_DEPTH} levels deep",
                                      event)
                is_map = kind is ev.MappingStartEvent
                if event.tag is not None:
                    try:
                        check_collection_tag(event.tag, "map" if is_map else "seq")
                    except TagProblem as exc:
                        raise self._error(str(exc), event, self._child_path(stack)) from None
                path = self._child_path(stack)
                if event.anchor is not None:
                    self.open_anchors.add(event.anchor)
                stack.append([{} if is_map else [], path, event.anchor, 1, _NO_KEY, 0, {},
                              is_map, None])
                continue
            elif kind is ev.AliasEvent:
                value, size = self._alias(event)
            else:  # pragma: no cover - the parser guarantees the order of events
                raise self._error("unexpected YAML event", event)
            if not stack:
                return value
            add(stack[-1], value, size, event)

    def _child_path(self, stack: list[list]) -> str:
        if not stack:
            return ""
        parent = stack[-1]
        if parent[7]:
            return parent[1] if parent[4] is _NO_KEY else join_path(parent[1], parent[4])
        return f"{parent[1]}[{len(parent[0])}]"

    def _add(self, frame: list, value: Any, size: int, event: Any) -> None:
        frame[3] += size
        if value is MERGE_KEY and not (frame[7] and frame[4] is _NO_KEY):
            value = "<<"  # a plain << anywhere but in key position is text
        if not frame[7]:
            frame[0].append(value)
            return
        if frame[4] is _NO_KEY:
            try:
                hash(value)
            except TypeError:
                raise self._error("a mapping key must be a plain value", event,
                                  frame[1]) from None
            line = event.start_mark.line
            if value in frame[6]:
                raise ModelError(f"duplicate key {brief(value)} (line {line + 1}; first at line "
                                 f"{frame[6][value] + 1})", join_path(frame[1], value))
            frame[6][value] = line
            frame[4] = value
            return
        key, frame[4] = frame[4], _NO_KEY
        if key is MERGE_KEY:
            self._merge(frame, value, event)
        else:
            frame[0][key] = value

    def _merge(self, frame: list, value: Any, event: Any) -> None:
        """YAML merge key ``<<: *base`` (or a list of bases, the earlier winning): the
        bases' keys go aside and the mapping's own keys override them when it closes."""
        bases = value if isinstance(value, list) else [value]
        if not all(isinstance(b, dict) for b in bases):
            raise self._error("'<<' must merge a mapping or a list of mappings", event,
                              join_path(frame[1], "<<"))
        merged: dict = {}
        for base in reversed(bases):
            merged.update(base)
        frame[8] = merged

    def _alias(self, event: Any) -> tuple[Any, int]:
        name = event.anchor
        if name in self.open_anchors:
            raise self._error(f"alias *{name} refers to a node that contains it", event)
        if name not in self.anchors:
            raise self._error(f"alias *{name} has no anchor &{name} before it", event)
        value, size = self.anchors[name]
        self.expansion += size
        if self.expansion > MAX_ALIAS_EXPANSION:
            raise ModelError(f"{self.source} expands to more than {MAX_ALIAS_EXPANSION} extra "
                             "nodes through anchors and aliases; refusing it")
        return value, size

    def _scalar(self, event: Any, stack: list[list]) -> Any:
        value, tag = event.value, event.tag
        if tag is None or tag == "!":
            if not event.implicit[0]:
                return value  # quoted: a string
            known = self.plain.get(value, _NO_KEY)  # plain scalars repeat: resolve once
            if known is not _NO_KEY:
                return known
            if value.isdigit() and (value[0] != "0" or value == "0") and value.isascii() \
                    and len(value) <= MAX_NUMBER_DIGITS:
                result: Any = int(value)  # the common case, without the resolver's regexes
            else:
                tag = self.loader.resolve(yaml.ScalarNode, value, (True, False))
                result = self._typed(tag, event, stack)
            self.plain[value] = result
            return result
        return self._typed(tag, event, stack)

    def _typed(self, tag: str, event: Any, stack: list[list]) -> Any:
        """The value of a scalar with tag ``tag`` (plain data only)."""
        try:
            return tagged_scalar(tag, event.value, self.loader)
        except TagProblem as exc:
            raise self._error(str(exc), event, self._child_path(stack)) from None


_NO_KEY = object()
#: Characters a model file may not contain (C0/C1 controls but tab and line breaks,
#: non-characters, lone surrogates, and a byte-order mark anywhere but at the start).
_BAD_CHARACTER = re.compile("[\x00-\x08\x0b\x0c\x0e-\x1f\x7f-\x84\x86-\x9f"
                            "\ufffe\uffff\ud800-\udfff]|(?!\\A)\ufeff")


def read_model_bytes(path: str | Path) -> bytes:
    """The bytes of a model file, refusing files over :func:`max_model_bytes`.

    Regular files are checked by their size before reading; devices and pipes are read
    only up to the limit (``powergraph check /dev/zero`` stops at once).
    """
    return read_bytes(path, "model", "a model file")


def load_yaml_file(path: str | Path) -> Any:
    """Read and strictly parse a YAML file (see :func:`load_yaml_text`)."""
    return load_yaml_text(read_model_bytes(path), source=str(path))
