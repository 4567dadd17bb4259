"""Frozen records: how the package declares its model and result types.

``@record`` is ``@dataclass(frozen=True)``; ``@record(eq=False)`` and ``@record(repr=False)``
pass ``eq`` and ``repr`` through. Records are not slotted: ``Model`` and several results
cache derived values with ``functools.cached_property``, which writes the instance's
``__dict__``.

Examples
--------
>>> @record
... class Pair:
...     name: str
...     teeth: int = 20
>>> Pair("sun") == Pair("sun", 20), Pair("sun")
(True, Pair(name='sun', teeth=20))
>>> hash(Pair("sun")) == hash(Pair("sun"))
True
"""
from __future__ import annotations

import dataclasses

__all__ = ["record"]


def record(cls: type | None = None, /, *, eq: bool = True, repr: bool = True):
    """``dataclasses.dataclass(cls, frozen=True, eq=eq, repr=repr)``.

    Examples
    --------
    >>> @record(repr=False)
    ... class Mesh:
    ...     efficiency: float
    >>> mesh = Mesh(0.98)
    >>> dataclasses.replace(mesh, efficiency=0.97).efficiency
    0.97
    >>> try:
    ...     mesh.efficiency = 0.5
    ... except dataclasses.FrozenInstanceError as error:
    ...     print(error)
    cannot assign to field 'efficiency'
    """
    return dataclasses.dataclass(cls, frozen=True, eq=eq, repr=repr)
