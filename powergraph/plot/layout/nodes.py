"""A read-only mapping keyed by flow-graph nodes (or arrows) that also answers to names.

The diagrams key their nodes by :class:`~powergraph.statics.flow.Node` (kind and name)
and their arrows by ``(source node, target node)``, so a body called ``motor`` never
meets the motor. For convenience a key may also be given by name — ``"2/3"`` for a node,
``("2/3", "mesh 4-5")`` for an arrow — when exactly one key has those names; a name two
keys share raises a ``KeyError`` that lists them.

Examples
--------
>>> from powergraph.statics.flow import Node
>>> kinds = NodeMap({Node("body", "motor"): "body", Node("motor", "motor"): "motor",
...                  Node("mesh", "mesh 1-2"): "mesh"})
>>> kinds["mesh 1-2"], kinds[Node("body", "motor")]
('mesh', 'body')
>>> "motor" in kinds          # two nodes are called motor: ask by Node
False
"""
from __future__ import annotations

from typing import Any, Iterator, Mapping

from powergraph.statics.flow import Node


def _names(key: Any) -> Any:
    """The names of a key: a node's name, or a tuple of them for an arrow."""
    if isinstance(key, Node):
        return key.name
    if isinstance(key, tuple) and all(isinstance(k, Node) for k in key):
        return tuple(k.name for k in key)
    return key


class NodeMap(Mapping):
    """A mapping keyed by nodes or arrows whose items can also be asked for by name."""

    def __init__(self, data: Mapping | None = None) -> None:
        self._data = dict(data or {})
        self._by_name: dict[Any, list] = {}
        for key in self._data:
            self._by_name.setdefault(_names(key), []).append(key)

    def __getitem__(self, key: Any) -> Any:
        try:
            return self._data[key]
        except (KeyError, TypeError):
            pass
        matches = self._by_name.get(key, []) if _hashable(key) else []
        if len(matches) == 1:
            return self._data[matches[0]]
        if matches:
            raise KeyError(f"{key!r} names several nodes: {sorted(matches)}; ask by Node")
        raise KeyError(key)

    def __iter__(self) -> Iterator:
        return iter(self._data)

    def __len__(self) -> int:
        return len(self._data)

    def __repr__(self) -> str:
        return f"NodeMap({self._data!r})"


def _hashable(key: Any) -> bool:
    try:
        hash(key)
    except TypeError:
        return False
    return True
