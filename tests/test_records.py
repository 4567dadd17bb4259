"""``powergraph.records.record`` behaves as ``dataclass(frozen=True)``: each class shape is
declared both ways and every behaviour is compared with the standard library's."""
from __future__ import annotations

import ast
import copy
import dataclasses
import inspect
import pickle
from dataclasses import dataclass, field
from pathlib import Path

import pytest

from powergraph.records import record

PACKAGE = Path(__file__).resolve().parents[1] / "powergraph"


def shapes(decorate):
    """The same class shapes declared with ``decorate`` (record or frozen dataclass)."""
    @decorate
    class Plain:
        name: str
        teeth: int = 20
        ratios: tuple = ()

    @decorate
    class Hidden:
        name: str
        model: object = field(default=None, repr=False, compare=False)
        cache: object = field(default=0, compare=True, hash=False)
        tag: object = field(default="t", compare=False, hash=True)

    @decorate
    class Written:
        value: float

        def __eq__(self, other):
            return isinstance(other, Written) and round(self.value) == round(other.value)

        def __repr__(self):
            return f"<{self.value}>"

    @decorate
    class Child(Plain):
        extra: float = 1.0

    @decorate
    class Empty:
        pass

    @decorate
    class Single:
        value: float

    @decorate
    class Made:
        """A record with factories, a field left out of ``__init__`` and a post-init."""
        name: str
        ratios: tuple = field(default_factory=tuple)
        count: int = field(default=0, init=False)
        stamps: list = field(default_factory=list, init=False, compare=False)

        def __post_init__(self):
            object.__setattr__(self, "count", len(self.ratios))

    @decorate
    class Bare:
        speed: float = 0.0

    return {"Plain": Plain, "Hidden": Hidden, "Written": Written, "Child": Child,
            "Empty": Empty, "Single": Single, "Made": Made, "Bare": Bare}


OURS = shapes(record)
THEIRS = shapes(dataclass(frozen=True))
ARGUMENTS = {"Plain": [("sun",), ("sun", 21), ("sun", 20, (1.5, 2))],
             "Hidden": [("a",), ("a", 1), ("a", None, 5), ("a", None, 0, "u")],
             "Written": [(1.2,), (0.9,), (2.0,)],
             "Child": [("sun",), ("sun", 20, (), 2.0)],
             "Empty": [()],
             "Single": [(1.0,), (2.0,)],
             "Made": [("a",), ("a", (1.0, 2.0)), ("b", (1.0,))],
             "Bare": [(), (2.0,)]}


def both(name):
    for args in ARGUMENTS[name]:
        yield OURS[name](*args), THEIRS[name](*args)


@pytest.mark.parametrize("name", sorted(ARGUMENTS))
def test_equality_hash_and_repr_match_the_standard_library(name) -> None:
    pairs = list(both(name))
    for ours_a, theirs_a in pairs:
        assert repr(ours_a) == repr(theirs_a)
        hashed = type(theirs_a).__hash__ is not None
        assert (type(ours_a).__hash__ is not None) == hashed
        if hashed:
            assert hash(ours_a) == hash(theirs_a)
        for ours_b, theirs_b in pairs:
            assert (ours_a == ours_b) == (theirs_a == theirs_b)
            assert (ours_a != ours_b) == (theirs_a != theirs_b)


@pytest.mark.parametrize("name", sorted(ARGUMENTS))
def test_fields_are_frozen_and_the_dataclass_tools_work(name) -> None:
    for ours, theirs in both(name):
        assert dataclasses.is_dataclass(ours)
        assert [f.name for f in dataclasses.fields(ours)] == \
               [f.name for f in dataclasses.fields(theirs)]
        assert dataclasses.asdict(ours) == dataclasses.asdict(theirs)
        assert dataclasses.replace(ours) == ours
        for attribute in [f.name for f in dataclasses.fields(ours)] + ["other"]:
            with pytest.raises(dataclasses.FrozenInstanceError):
                setattr(ours, attribute, 1)
        for attribute in [f.name for f in dataclasses.fields(ours)]:
            with pytest.raises(dataclasses.FrozenInstanceError):
                delattr(ours, attribute)
        assert copy.deepcopy(ours) == ours


@pytest.mark.parametrize("name", sorted(ARGUMENTS))
def test_init_signature_docstring_and_defaults_match_the_standard_library(name) -> None:
    assert str(inspect.signature(OURS[name])) == str(inspect.signature(THEIRS[name]))
    assert OURS[name].__doc__ == THEIRS[name].__doc__
    for ours, theirs in both(name):
        assert vars(ours) == vars(theirs)           # every field set, __post_init__ run


def test_factories_give_each_record_a_fresh_value() -> None:
    one, two = OURS["Made"]("a"), OURS["Made"]("a")
    assert one.stamps == [] and one.stamps is not two.stamps
    assert OURS["Made"]("a", (3.0,)).count == 1


def test_a_plain_subclass_may_set_other_attributes_but_not_fields() -> None:
    for classes in (OURS, THEIRS):
        class Plain(classes["Plain"]):
            pass

        sun = Plain("sun")
        sun.note = "ok"
        assert sun.note == "ok"
        del sun.note
        with pytest.raises(dataclasses.FrozenInstanceError):
            sun.teeth = 3
        with pytest.raises(dataclasses.FrozenInstanceError):
            del sun.name


def test_a_field_without_default_after_one_with_a_default_is_refused() -> None:
    for decorate in (record, dataclass(frozen=True)):
        with pytest.raises(TypeError, match="non-default argument 'b' follows default"):
            @decorate
            class Wrong:
                a: int = 1
                b: int


def test_a_frozen_dataclass_may_inherit_from_a_record() -> None:
    @dataclass(frozen=True)
    class Tagged(OURS["Plain"]):
        tag: str = "x"

    tagged = Tagged("sun", tag="y")
    assert (tagged.name, tagged.teeth, tagged.tag) == ("sun", 20, "y")
    with pytest.raises(dataclasses.FrozenInstanceError):
        tagged.tag = "z"


def test_package_records_survive_pickling() -> None:
    """Parallel sweeps send results between processes: pickling keeps value and class."""
    from powergraph.errors import Caveat
    from powergraph.model import load_model

    caveat = Caveat("hot", "links[0]")
    assert pickle.loads(pickle.dumps(caveat)) == caveat
    model = load_model(Path(__file__).resolve().parents[1] / "models" / "wolfrom_3k.yaml")
    component = next(iter(model.components.values()))
    back = pickle.loads(pickle.dumps(component))
    assert back == component and hash(back) == hash(component) and back is not component


def test_other_classes_are_not_equal_even_with_equal_fields() -> None:
    @record
    class Twin:
        name: str
        teeth: int = 20

    assert OURS["Plain"]("sun") != Twin("sun")
    assert OURS["Plain"]("sun").__eq__(Twin("sun")) is NotImplemented


def test_eq_false_keeps_identity_and_repr_false_keeps_the_inherited_repr() -> None:
    class Shown:
        def __repr__(self):
            return "<shown>"

    @record(eq=False, repr=False)
    class Result(Shown):
        value: float

    one, same = Result(1.0), Result(1.0)
    assert one != same and one == one and hash(one) != hash(same)
    assert repr(one) == "<shown>"


def test_a_record_holding_itself_shows_an_ellipsis() -> None:
    @record
    class Node:
        children: list

    node = Node([])
    node.children.append(node)
    assert repr(node).endswith("Node(children=[...])")


def test_the_package_declares_its_frozen_types_with_record() -> None:
    """One way to declare a frozen type: ``dataclass(frozen=True)`` compiles three methods
    per class that ``record`` shares (start-up, docs/architecture.md)."""
    offenders = []
    for path in PACKAGE.rglob("*.py"):
        if path.name == "records.py":
            continue
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.Call) and any(
                    k.arg == "frozen" for k in node.keywords) and "dataclass" in ast.unparse(
                    node.func):
                offenders.append(f"{path.relative_to(PACKAGE)}:{node.lineno}")
    assert offenders == []
