"""Frozen records: how the package declares its model and result types.

``@record`` is ``@dataclass(frozen=True)`` with the same behaviour, made cheaper to
declare. The class is a dataclass (``dataclasses.fields``, ``replace`` and ``asdict`` work)
whose fields cannot be assigned or deleted after ``__init__`` (``FrozenInstanceError``),
compared and hashed by the values of its fields, with the repr ``Name(a=1, b=2)``.

Why not ``dataclass(frozen=True)`` itself: on Python 3.11 it compiles six methods per class
when the class is declared (``__init__``, ``__setattr__``, ``__delattr__``, ``__eq__``,
``__hash__``, ``__repr__``); ``powergraph solve`` declares 22 classes, and their methods
took 15 ms of its start-up. Only the first three depend on the class (the frozen
``__init__``); ``record`` asks ``dataclass`` for those and gives every class the same
``__eq__``, ``__hash__`` and ``__repr__``, written once here. They follow the rules of the
generated methods: fields with ``compare=False`` are neither compared nor hashed (``hash``
overrides for hashing), fields with ``repr=False`` are not shown, ``__eq__`` compares only
objects of the same class (else ``NotImplemented``), an ``__eq__``, ``__hash__`` or
``__repr__`` written in the class body is kept, and ``eq=False`` leaves hashing by identity.

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
import reprlib
from operator import attrgetter
from typing import Any, Callable, TypeVar

__all__ = ["record"]

T = TypeVar("T", bound=type)

#: The attribute holding a record class's (compared, hashed, shown) field readers.
_READERS = "_record_readers"


def record(cls: T | None = None, /, *, eq: bool = True, repr: bool = True):  # noqa: A002
    """Declare ``cls`` a frozen dataclass (see the module docstring).

    Parameters
    ----------
    cls
        The class, when used as ``@record``; omitted with ``@record(eq=..., repr=...)``.
    eq
        Compare and hash by field values (``dataclass``'s ``eq``); False keeps identity.
    repr
        Give the class the field repr; False keeps an inherited or written ``__repr__``.

    Examples
    --------
    >>> import dataclasses
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
    def wrap(cls: T) -> T:
        return _declare(cls, eq, repr)

    return wrap if cls is None else wrap(cls)


def _declare(cls: T, eq: bool, shown: bool) -> T:
    own = cls.__dict__
    # dataclass's rule: a __hash__ written in the body is kept; the None Python puts there
    # for a class that writes __eq__ alone is not one
    explicit_hash = "__hash__" in own and not (own["__hash__"] is None and "__eq__" in own)
    cls = dataclasses.dataclass(cls, frozen=True, eq=False, repr=False)
    fields = dataclasses.fields(cls)
    setattr(cls, _READERS, (
        _reader([f.name for f in fields if f.compare]),
        _reader([f.name for f in fields if (f.compare if f.hash is None else f.hash)]),
        tuple(f.name for f in fields if f.repr)))
    if eq and "__eq__" not in own:
        cls.__eq__ = _equal
    if eq and not explicit_hash:
        cls.__hash__ = _hash
    if shown and "__repr__" not in own:
        cls.__repr__ = _repr
    return cls


def _reader(names: list[str]) -> Callable[[Any], tuple]:
    """A function from an object to the tuple of its ``names`` attributes."""
    if not names:
        return lambda obj: ()
    if len(names) == 1:
        one = attrgetter(names[0])
        return lambda obj: (one(obj),)
    return attrgetter(*names)


def _equal(self: Any, other: Any) -> Any:
    if other.__class__ is self.__class__:
        compared = getattr(self.__class__, _READERS)[0]
        return compared(self) == compared(other)
    return NotImplemented


def _hash(self: Any) -> int:
    return hash(getattr(self.__class__, _READERS)[1](self))


@reprlib.recursive_repr()
def _repr(self: Any) -> str:
    names = getattr(self.__class__, _READERS)[2]
    body = ", ".join(f"{name}={getattr(self, name)!r}" for name in names)
    return f"{self.__class__.__qualname__}({body})"
