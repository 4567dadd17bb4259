"""Strict YAML reading: duplicate keys, alias bombs and syntax errors become ModelErrors.

PyYAML silently keeps the last of two equal keys; in a model file that loses a component,
so this loader refuses them. Anchors and aliases are allowed, but the document they expand
to is bounded in size, so a "billion laughs" file fails fast instead of hanging.

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

from pathlib import Path

import yaml

from powergraph.errors import ModelError

#: Largest number of nodes a document may expand to once aliases are followed.
MAX_EXPANDED_NODES = 200_000


class _StrictLoader(yaml.SafeLoader):
    """SafeLoader that refuses duplicate mapping keys."""

    node_paths: dict = {}

    def construct_mapping(self, node, deep=False):  # noqa: D401 - PyYAML hook
        seen: dict = {}
        for key_node, _ in node.value:
            key = self.construct_object(key_node, deep=True)
            try:
                hash(key)
            except TypeError:
                raise ModelError(f"a mapping key must be a plain value "
                                 f"(line {key_node.start_mark.line + 1})",
                                 self.node_paths.get(id(node)) or None) from None
            if key in seen:
                raise ModelError(
                    f"duplicate key {key!r} (line {key_node.start_mark.line + 1}; "
                    f"first at line {seen[key] + 1})",
                    join_path(self.node_paths.get(id(node), ""), key))
            seen[key] = key_node.start_mark.line
        return super().construct_mapping(node, deep=deep)


def join_path(prefix: str, key) -> str:
    """Path of mapping key ``key`` inside the element at ``prefix``.

    >>> join_path("links[2]", "carrier"), join_path("", "name"), join_path("components", 7)
    ('links[2].carrier', 'name', 'components.7')
    """
    return f"{prefix}.{key}" if prefix else str(key)


def _record_paths(node, prefix: str, out: dict) -> None:
    """Map id(mapping node) -> its path in the document, for duplicate-key messages."""
    if id(node) in out:
        return
    if isinstance(node, yaml.MappingNode):
        out[id(node)] = prefix
        for key_node, value_node in node.value:
            key = key_node.value if isinstance(key_node, yaml.ScalarNode) else "?"
            _record_paths(value_node, join_path(prefix, key), out)
    elif isinstance(node, yaml.SequenceNode):
        for index, child in enumerate(node.value):
            _record_paths(child, f"{prefix}[{index}]", out)


def _expanded_size(node, memo: dict) -> int:
    """Number of nodes ``node`` stands for once every alias is expanded."""
    ident = id(node)
    if ident in memo:
        return memo[ident]
    memo[ident] = 1  # guards against recursive structures
    if isinstance(node, yaml.SequenceNode):
        size = 1 + sum(_expanded_size(child, memo) for child in node.value)
    elif isinstance(node, yaml.MappingNode):
        size = 1 + sum(_expanded_size(k, memo) + _expanded_size(v, memo) for k, v in node.value)
    else:
        size = 1
    size = min(size, MAX_EXPANDED_NODES + 1)
    memo[ident] = size
    return size


def load_yaml_text(text: str, source: str = "<model>"):
    """Parse YAML text strictly.

    Parameters
    ----------
    text : str
        The YAML document.
    source : str
        Name used in messages (usually the file name).

    Returns
    -------
    object
        The plain Python data (dicts, lists, scalars).

    Raises
    ------
    ModelError
        Syntax error (with line), duplicate key, several documents, or a document that
        expands past :data:`MAX_EXPANDED_NODES` nodes.
    """
    loader = _StrictLoader(text)
    try:
        node = loader.get_single_node()
        if node is None:
            raise ModelError(f"{source} is empty: a model needs name, components and links")
        if _expanded_size(node, {}) > MAX_EXPANDED_NODES:
            raise ModelError(f"{source} expands to more than {MAX_EXPANDED_NODES} nodes "
                             "through anchors and aliases; refusing it")
        loader.node_paths = {}
        _record_paths(node, "", loader.node_paths)
        return loader.construct_document(node)
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        where = f"line {mark.line + 1}, column {mark.column + 1}" if mark else "unknown place"
        problem = exc.problem or exc.context or "invalid YAML"
        raise ModelError(f"YAML syntax error at {where}: {problem}", source) from None
    except yaml.YAMLError as exc:
        raise ModelError(f"invalid YAML: {exc}", source) from None
    except RecursionError:
        raise ModelError("document nests too deeply", source) from None
    finally:
        loader.dispose()


def load_yaml_file(path: str | Path):
    """Read and strictly parse a YAML file (see :func:`load_yaml_text`)."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise ModelError(f"no such file: {path}") from None
    except IsADirectoryError:
        raise ModelError(f"{path} is a directory, not a model file") from None
    except UnicodeDecodeError as exc:
        raise ModelError(f"{path} is not UTF-8 text ({exc.reason})") from None
    except OSError as exc:
        raise ModelError(f"cannot read {path}: {exc.strerror}") from None
    return load_yaml_text(text, source=str(path))
