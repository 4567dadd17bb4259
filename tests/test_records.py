"""``powergraph.records.record`` declares frozen dataclasses: equal and hashed by their
compared fields, shown by their field repr, immutable, with defaults, factories and
``__post_init__``; ``eq=False`` and ``repr=False`` keep identity and an inherited repr."""
from __future__ import annotations

import ast
import copy
import dataclasses
import pickle
from dataclasses import field
from functools import cached_property
from pathlib import Path

import pytest

from powergraph.records import record

PACKAGE = Path(__file__).resolve().parents[1] / "powergraph"


@record
class Plain:
    name: str
    teeth: int = 20
    ratios: tuple = ()


@record
class Hidden:
    name: str
    model: object = field(default=None, repr=False, compare=False)
    cache: object = field(default=0, compare=True, hash=False)


@record
class Written:
    value: float

    def __eq__(self, other):
        return isinstance(other, Written) and round(self.value) == round(other.value)

    def __hash__(self):
        return hash(round(self.value))

    def __repr__(self):
        return f"<{self.value}>"


@record
class Made:
    """A record with factories, a field left out of ``__init__`` and a post-init."""
    name: str
    ratios: tuple = field(default_factory=tuple)
    count: int = field(default=0, init=False)
    stamps: list = field(default_factory=list, init=False, compare=False)

    def __post_init__(self):
        object.__setattr__(self, "count", len(self.ratios))


def test_records_are_frozen_dataclasses() -> None:
    assert dataclasses.is_dataclass(Plain) and Plain.__dataclass_params__.frozen
    assert not hasattr(Plain, "__slots__")        # cached_property needs the __dict__


def test_equality_hash_and_repr_follow_the_compared_and_shown_fields() -> None:
    assert Plain("sun") == Plain("sun", 20, ()) and Plain("sun") != Plain("sun", 21)
    assert hash(Plain("sun")) == hash(Plain("sun", 20))
    assert repr(Plain("sun")) == "Plain(name='sun', teeth=20, ratios=())"
    assert Hidden("a", model=1) == Hidden("a", model=2)
    assert Hidden("a", cache=1) != Hidden("a", cache=2)
    assert hash(Hidden("a", cache=1)) == hash(Hidden("a", cache=2))
    assert repr(Hidden("a", model=1)) == "Hidden(name='a', cache=0)"


def test_an_eq_hash_or_repr_written_in_the_body_is_kept() -> None:
    assert Written(1.2) == Written(0.9) and hash(Written(1.2)) == hash(Written(0.9))
    assert repr(Written(1.2)) == "<1.2>"


def test_fields_are_frozen_and_the_dataclass_tools_work() -> None:
    sun = Plain("sun", 21, (1.5, 2))
    for attribute in ("name", "teeth", "ratios", "other"):
        with pytest.raises(dataclasses.FrozenInstanceError):
            setattr(sun, attribute, 1)
    with pytest.raises(dataclasses.FrozenInstanceError):
        del sun.name
    assert dataclasses.asdict(sun) == {"name": "sun", "teeth": 21, "ratios": (1.5, 2)}
    assert dataclasses.replace(sun, teeth=22) == Plain("sun", 22, (1.5, 2))
    assert copy.deepcopy(sun) == sun


def test_defaults_factories_and_post_init() -> None:
    one, two = Made("a"), Made("a")
    assert one.ratios == () and one.count == 0 and one.stamps == []
    assert one.stamps is not two.stamps
    assert Made("a", (3.0,)).count == 1
    assert Made("a") == Made("a", ())


def test_a_cached_property_is_not_part_of_the_value() -> None:
    """As ``Model.derived``: computed once, ignored by ``==``, absent from a replace."""
    @record
    class Cached:
        value: float

        @cached_property
        def store(self) -> dict:
            return {}

    one = Cached(1.0)
    one.store["x"] = 1
    assert one.store == {"x": 1} and one == Cached(1.0)
    assert dataclasses.replace(one).store == {}


def test_a_plain_subclass_may_set_other_attributes_but_not_fields() -> None:
    class Sub(Plain):
        pass

    sun = Sub("sun")
    sun.note = "ok"
    assert sun.note == "ok"
    del sun.note
    with pytest.raises(dataclasses.FrozenInstanceError):
        sun.teeth = 3


def test_a_record_may_inherit_from_a_record() -> None:
    @record
    class Tagged(Plain):
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
        ratios: tuple = ()

    assert Plain("sun") != Twin("sun")
    assert Plain("sun").__eq__(Twin("sun")) is NotImplemented


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
    with pytest.raises(dataclasses.FrozenInstanceError):
        one.value = 2.0


def test_a_record_holding_itself_shows_an_ellipsis() -> None:
    @record
    class Node:
        children: list

    node = Node([])
    node.children.append(node)
    assert repr(node).endswith("Node(children=[...])")


def test_the_package_declares_its_frozen_types_with_record() -> None:
    """One way to declare a frozen type, so that they all change together."""
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
