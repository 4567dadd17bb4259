"""Frozen records: how the package declares its model and result types.

``@record`` is ``@dataclass(frozen=True)`` with the same behaviour, made cheaper to
declare. The class is a dataclass (``dataclasses.fields``, ``replace`` and ``asdict`` work)
whose fields cannot be assigned or deleted after ``__init__`` (``FrozenInstanceError``),
compared and hashed by the values of its fields, with the repr ``Name(a=1, b=2)``.

Why not ``dataclass(frozen=True)`` itself: on Python 3.11 it compiles six methods per class
when the class is declared (``__init__``, ``__setattr__``, ``__delattr__``, ``__eq__``,
``__hash__``, ``__repr__``), about 0.1 ms each; ``powergraph solve`` declares 21 classes.
Only ``__init__`` has to be written for each class. ``record`` compiles that one alone
(assigning through ``object.__setattr__``, as the frozen ``__init__`` does) and gives every
class the same ``__setattr__``, ``__delattr__``, ``__eq__``, ``__hash__`` and ``__repr__``,
written once here. They follow the rules of the generated methods: assigning or deleting any
attribute of a record raises ``FrozenInstanceError`` (a plain subclass may still set
attributes that are not fields); fields with ``compare=False`` are neither compared nor
hashed (``hash`` overrides for hashing), fields with ``repr=False`` are not shown,
``__eq__`` compares only objects of the same class (else ``NotImplemented``), an ``__eq__``,
``__hash__`` or ``__repr__`` written in the class body is kept, and ``eq=False`` leaves
hashing by identity. ``__init__`` takes defaults and ``default_factory`` (a fresh value per
instance) and calls ``__post_init__``. A class that needs more of ``dataclass`` (a
dataclass base, ``InitVar``, keyword-only fields, its own ``__init__``, ``__setattr__`` or
``__delattr__``) is declared by ``dataclass(frozen=True)`` itself, with the shared
``__eq__``, ``__hash__`` and ``__repr__``.

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
import inspect
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
    if _plain(cls):
        undocumented = cls.__doc__ is None
        cls = dataclasses.dataclass(cls, init=False, eq=False, repr=False)
        fields = dataclasses.fields(cls)
        cls.__init__ = _frozen_init(cls, fields)
        cls.__setattr__, cls.__delattr__ = _frozen_setattr, _frozen_delattr
        # the standard library reads this flag when a dataclass inherits from the record
        cls.__dataclass_params__.frozen = True
        if undocumented:                      # dataclass's own docstring: the signature
            cls.__doc__ = cls.__name__ + str(inspect.signature(cls)).replace(" -> None", "")
    else:
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


def _plain(cls: type) -> bool:
    """Whether ``record``'s own ``__init__`` and frozen methods fit ``cls``: no dataclass
    base, no ``__init__``, ``__setattr__`` or ``__delattr__`` in its body, no ``InitVar``
    or keyword-only field, and no field named ``self``."""
    own = cls.__dict__
    if any("__dataclass_fields__" in base.__dict__ for base in cls.__mro__[1:]):
        return False
    if any(name in own for name in ("__init__", "__setattr__", "__delattr__")):
        return False
    annotations = own.get("__annotations__", {})
    if "self" in annotations or any(
            "InitVar" in str(kind) or "KW_ONLY" in str(kind) for kind in annotations.values()):
        return False
    return not any(isinstance(value, dataclasses.Field) and value.kw_only is True
                   for value in own.values())


def _frozen_init(cls: type, fields: tuple[dataclasses.Field, ...]) -> Callable:
    """The frozen ``__init__`` of ``cls``, compiled: each field set by
    ``object.__setattr__`` from its argument, its default or a fresh ``default_factory()``
    value; then ``__post_init__``. Raises TypeError where dataclass would (a field without
    a default after one with a default)."""
    names: dict[str, Any] = {"__record_set": object.__setattr__, "__record_factory": _FACTORY}
    parameters, lines, defaulted = [], [], False
    for f in fields:
        factory = f.default_factory is not dataclasses.MISSING
        default = f.default is not dataclasses.MISSING
        if factory:
            names[f"__record_make_{f.name}"] = f.default_factory
        if default:
            names[f"__record_default_{f.name}"] = f.default
        if f.init:
            if default:
                parameters.append(f"{f.name}=__record_default_{f.name}")
            elif factory:
                parameters.append(f"{f.name}=__record_factory")
            elif defaulted:
                raise TypeError(f"non-default argument {f.name!r} follows default argument")
            else:
                parameters.append(f.name)
            defaulted = defaulted or default or factory
            value = (f"__record_make_{f.name}() if {f.name} is __record_factory else {f.name}"
                     if factory else f.name)
        elif factory:
            value = f"__record_make_{f.name}()"
        elif default:
            value = f"__record_default_{f.name}"
        else:
            continue                          # init=False without a default: left unset
        lines.append(f" __record_set(self, {f.name!r}, {value})")
    if hasattr(cls, "__post_init__"):
        lines.append(" self.__post_init__()")
    source = f"def __init__(self, {', '.join(parameters)}):\n" + "\n".join(lines or [" pass"])
    exec(source, names)                       # noqa: S102  (our own text, as dataclass does)
    init = names["__init__"]
    init.__qualname__ = f"{cls.__qualname__}.__init__"
    init.__module__ = cls.__module__
    init.__annotations__ = {**{f.name: f.type for f in fields if f.init}, "return": None}
    return init


#: The default of a ``default_factory`` field's argument: "not given, call the factory".
_FACTORY = type("_Factory", (), {"__repr__": lambda self: "<factory>"})()


def _frozen_setattr(self: Any, name: str, value: Any) -> None:
    cls = type(self)
    if _READERS in cls.__dict__ or name in cls.__dataclass_fields__:
        raise dataclasses.FrozenInstanceError(f"cannot assign to field {name!r}")
    super(_record_of(cls), self).__setattr__(name, value)


def _frozen_delattr(self: Any, name: str) -> None:
    cls = type(self)
    if _READERS in cls.__dict__ or name in cls.__dataclass_fields__:
        raise dataclasses.FrozenInstanceError(f"cannot delete field {name!r}")
    super(_record_of(cls), self).__delattr__(name)


def _record_of(cls: type) -> type:
    """The record class a plain subclass ``cls`` inherits the frozen methods from."""
    return next(c for c in cls.__mro__ if c.__dict__.get("__setattr__") is _frozen_setattr)


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
