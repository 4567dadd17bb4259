"""Strict, bounded YAML reading: bad characters, size, aliases, nesting, tags, duplicates."""
from __future__ import annotations

import contextlib
import os
import threading
from pathlib import Path

import pytest

from powergraph.errors import ModelError
from powergraph.model import yaml_loader
from powergraph.model.yaml_loader import (
    MAX_ALIAS_EXPANSION,
    load_yaml_file,
    load_yaml_text,
    size_limit,
)

ROOT = Path(__file__).resolve().parents[2]


def error_of(text) -> ModelError:
    with pytest.raises(ModelError) as info:
        load_yaml_text(text, source="m.yaml")
    return info.value


@pytest.mark.parametrize("text, where, what", [
    ("name: t\nx: a\x01b\n", "line 2, column 5", "control character U+0001"),
    ("name: t\n  \x00\n", "line 2, column 3", "control character U+0000"),
    ("name: t\nx: é\ufeff\n", "line 2, column 5", "byte-order mark"),
    ("name: t\r\nx: \x1b[31m\n", "line 2, column 4", "control character U+001B"),
    (b"name: t\nx: \xc3\x28\n", "line 2, column 4", "not UTF-8"),
    (b"name: \xff\n", "line 1, column 7", "not UTF-8"),
])
def test_bad_characters_are_refused_with_line_and_column(text, where, what) -> None:
    error = error_of(text)
    assert where in error.message and what in error.message
    assert error.path == "m.yaml" and "\n" not in str(error)


def test_a_byte_order_mark_at_the_start_is_allowed() -> None:
    assert load_yaml_text("\ufeffname: t\n") == {"name": "t"}
    assert load_yaml_text(b"\xef\xbb\xbfname: t\n") == {"name": "t"}


def test_alias_bomb_is_refused_by_counting_expansions() -> None:
    lines = ["a: &a [x, x, x, x, x, x, x, x, x, x]"]
    for prev, name in zip("abcdefgh", "bcdefghi"):
        lines.append(f"{name}: &{name} [{', '.join([f'*{prev}'] * 10)}]")
    assert "anchors and aliases" in error_of("\n".join(lines)).message


def test_a_large_plain_document_is_not_an_alias_bomb() -> None:
    # 3 x MAX_ALIAS_EXPANSION nodes, no alias: only expansions count, not size.
    n = MAX_ALIAS_EXPANSION
    text = "items:\n" + "".join(f"  - [{i}, {i}]\n" for i in range(n))
    data = load_yaml_text(text)
    assert len(data["items"]) == n and data["items"][-1] == [n - 1, n - 1]


def test_aliases_within_the_bound_are_shared_values() -> None:
    data = load_yaml_text("base: &b {efficiency: 0.9}\nlink: {<<: *b, type: mesh}\n"
                          "again: *b\n")
    assert data["link"] == {"efficiency": 0.9, "type": "mesh"}
    assert data["again"] == {"efficiency": 0.9}


@pytest.mark.parametrize("text, words", [
    ("a: *nowhere\n", "no anchor"),
    ("a: &x [1, *x]\n", "contains it"),
])
def test_bad_aliases(text, words) -> None:
    assert words in error_of(text).message


def test_deep_nesting_is_refused_without_recursion() -> None:
    depth = 200_000  # libyaml's composer would overflow the C stack here
    error = error_of("a: " + "[" * depth + "]" * depth)
    assert f"more than {yaml_loader.MAX_DEPTH} levels" in error.message


@pytest.mark.parametrize("text, words, path", [
    ("a: !!python/object:os.system x\n", "unsupported YAML tag", "a"),
    ("a: !!binary aGVsbG8=\n", "unsupported YAML tag", "a"),
    ("a: !custom {b: 1}\n", "unsupported YAML tag", "a"),
    ("a: 1\n---\nb: 2\n", "one YAML document", "m.yaml"),
    ("a: {b: 1, b: 2}\n", "duplicate key 'b' (line 1; first at line 1)", "a.b"),
    ("l:\n  - {x: 1}\n  - {y: 1,\n     y: 2}\n", "duplicate key 'y' (line 4; first at line 3)",
     "l[1].y"),
    ("? [1, 2]\n: x\n", "plain value", "m.yaml"),
    ("a: [1,\n", "YAML syntax error at line 2", "m.yaml"),
])
def test_structure_errors(text, words, path) -> None:
    error = error_of(text)
    assert words in error.message and error.path == path


def test_scalars_are_plain_data() -> None:
    data = load_yaml_text("a: 0x10\nb: 1_000\nc: 1.5e+3\nd: .inf\ne: ~\nf: yes\ng: 2024-01-02\n"
                          "h: '12'\ni: 012\nj: -7\n")
    assert data == {"a": 16, "b": 1000, "c": 1500.0, "d": float("inf"), "e": None,
                    "f": True, "g": "2024-01-02", "h": "12", "i": 10, "j": -7}


def test_size_limit_refuses_large_files_before_reading(tmp_path, monkeypatch) -> None:
    path = tmp_path / "m.yaml"
    path.write_text("name: t\n" + "# padding\n" * 100)
    with size_limit(100):
        with pytest.raises(ModelError, match="too large .*the limit is 100 bytes"):
            load_yaml_file(path)
    monkeypatch.setenv("POWERGRAPH_MAX_MODEL_BYTES", "50")
    with pytest.raises(ModelError, match="the limit is 50 bytes"):
        load_yaml_file(path)
    monkeypatch.setenv("POWERGRAPH_MAX_MODEL_BYTES", "many")
    with pytest.raises(ModelError, match="POWERGRAPH_MAX_MODEL_BYTES"):
        load_yaml_file(path)
    monkeypatch.delenv("POWERGRAPH_MAX_MODEL_BYTES")
    assert load_yaml_file(path) == {"name": "t"}


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="needs named pipes")
def test_an_endless_pipe_is_read_only_up_to_the_limit(tmp_path) -> None:
    fifo = tmp_path / "endless"
    os.mkfifo(fifo)

    def write_forever() -> None:
        with contextlib.suppress(BrokenPipeError), open(fifo, "wb") as pipe:
            while True:
                pipe.write(b"# text without end\n" * 1000)

    writer = threading.Thread(target=write_forever, daemon=True)
    writer.start()
    with size_limit(100_000):
        with pytest.raises(ModelError, match="too large .*more than that; the limit is "
                                             "100000 bytes"):
            load_yaml_file(fifo)
    writer.join(timeout=10)
    assert not writer.is_alive()


@pytest.mark.skipif(not os.path.exists("/dev/zero"), reason="needs /dev/zero")
def test_dev_zero_stops_at_its_first_byte() -> None:
    with pytest.raises(ModelError, match=r"NUL byte .* at byte 0 .*not a text file"):
        load_yaml_file("/dev/zero")


def test_missing_file_and_directory(tmp_path) -> None:
    with pytest.raises(ModelError, match="no such file"):
        load_yaml_file(tmp_path / "none.yaml")
    with pytest.raises(ModelError, match="is a directory"):
        load_yaml_file(tmp_path)


def test_the_library_loads_the_same_as_pyyaml() -> None:
    import yaml

    for path in sorted((ROOT / "models").glob("*.yaml")):
        assert load_yaml_file(path) == yaml.safe_load(path.read_text()), path.name


# --- merge keys (YAML 1.1): explicit keys override merged ones, an earlier base in a list of
# bases wins over a later one, a base that merges is merged with its own merges done. The
# expected mappings are written from these rules (PyYAML's own reading differs between
# releases: 6.0.4 merges the third case's base before its override).

MERGES = [
    ("g: &g {teeth: 20, internal: false}\np: {<<: *g, teeth: 30}\n",
     {"g": {"teeth": 20, "internal": False}, "p": {"teeth": 30, "internal": False}}),
    ("g: &g {teeth: 20}\np: {teeth: 30, <<: *g}\n", {"g": {"teeth": 20}, "p": {"teeth": 30}}),
    ("a: &a {x: 1, y: 1}\nb: &b {x: 2, z: 2}\nc: {<<: [*a, *b], w: 0}\n",
     {"a": {"x": 1, "y": 1}, "b": {"x": 2, "z": 2}, "c": {"x": 1, "y": 1, "z": 2, "w": 0}}),
    ("a: &a {x: 1, y: 1}\nb: &b {<<: *a, x: 2, z: 2}\nc: {<<: *b, y: 3}\n",
     {"a": {"x": 1, "y": 1}, "b": {"x": 2, "y": 1, "z": 2}, "c": {"x": 2, "y": 3, "z": 2}}),
    ("c: {<<: {x: 1}, y: 2}\n", {"c": {"x": 1, "y": 2}}),
    ("a: &a {x: 1}\nb: &b {y: 2}\nc:\n  <<: [*a, *b]\n  x: 3\n",
     {"a": {"x": 1}, "b": {"y": 2}, "c": {"x": 3, "y": 2}}),
]


@pytest.mark.parametrize("text, expected", MERGES)
def test_merge_keys_read_as_yaml_defines_them(text, expected) -> None:
    assert load_yaml_text(text) == expected


def test_explicit_keys_override_merged_ones_and_the_earlier_base_wins() -> None:
    data = load_yaml_text("a: &a {x: 1, y: 1}\nb: &b {x: 2, z: 2}\n"
                          "c: {<<: [*a, *b], y: 5}\n")
    assert data["c"] == {"x": 1, "y": 5, "z": 2}


@pytest.mark.parametrize("text, words, path", [
    ("g: &g {t: 1}\np: {<<: *g, t: 2, t: 3}\n", "duplicate key 't'", "p.t"),
    ("g: &g {t: 1}\np: {<<: *g, <<: *g}\n", "duplicate key '<<'", "p.<<"),
    ("p: {<<: 5}\n", "'<<' must merge a mapping", "p.<<"),
])
def test_merge_errors(text, words, path) -> None:
    error = error_of(text)
    assert words in error.message and error.path == path


def test_a_plain_double_angle_outside_key_position_is_text() -> None:
    assert load_yaml_text("a: [<<, {v: <<}]\n") == {"a": ["<<", {"v": "<<"}]}


def test_merges_do_not_escape_the_alias_bound() -> None:
    lines = ["a: &a {" + ", ".join(f"k{i}: {i}" for i in range(10)) + "}"]
    for prev, name in zip("abcdefgh", "bcdefghi"):
        lines.append(f"{name}: &{name} {{<<: [{', '.join([f'*{prev}'] * 10)}]}}")
    assert "anchors and aliases" in error_of("\n".join(lines)).message


# --- explicit tags: read correctly, or refused in one line naming the place ------------

TAG_VALUES = [("!!bool 'false'", False), ("!!bool yes", True), ("!!int '40'", 40),
              ("!!int 0x28", 40), ("!!int 1_000", 1000), ("!!float '0.5'", 0.5),
              ("!!float 1", 1.0), ("!!null ''", None), ("!!null ~", None), ("!!str 12", "12"),
              ("!!timestamp 2001-12-14", "2001-12-14"), ("!!seq [1]", [1]),
              ("!!map {b: 1}", {"b": 1}), ("! 12", 12)]


@pytest.mark.parametrize("tagged, value", TAG_VALUES)
def test_standard_tags_construct_their_values(tagged, value) -> None:
    assert load_yaml_text(f"a: {tagged}\n") == {"a": value}


BAD_TAGS = [("!!bool 'maybe'", "!!bool 'maybe' is not a boolean"),
            ("!!bool ''", "is not a boolean"),
            ("!!int 'abc'", "!!int 'abc' is not an integer"),
            ("!!int '-'", "is not an integer"), ("!!int 0x", "is not an integer"),
            ("!!int '1.5'", "is not an integer"),
            ("!!float ''", "!!float '' is not a number"), ("!!float '.'", "is not a number"),
            ("!!null 'x'", "is not null"),
            ("!!timestamp 'soon'", "is not a date or time"),
            ("!!binary aGVsbG8=", "unsupported YAML tag !!binary"),
            ("!!set {x, y}", "unsupported YAML tag !!set"),
            ("!!omap [{x: 1}]", "unsupported YAML tag !!omap"),
            ("!!pairs [{x: 1}]", "unsupported YAML tag !!pairs"),
            ("!!python/object:os.system x", "unsupported YAML tag !!python/object:os.system"),
            ("!!python/tuple [1]", "unsupported YAML tag !!python/tuple"),
            ("!foo x", "unsupported YAML tag !foo"), ("!foo {b: 1}", "unsupported YAML tag"),
            ("!!map x", "!!map does not fit a scalar"),
            ("!!seq {b: 1}", "!!seq does not fit a mapping"),
            ("!!str [1]", "!!str does not fit a list"),
            ("!!merge x", "is not the merge key")]


@pytest.mark.parametrize("tagged, words", BAD_TAGS)
def test_impossible_or_unsupported_tags_are_refused_with_line_and_path(tagged, words) -> None:
    error = error_of(f"name: t\nx:\n  a: {tagged}\n")
    assert words in error.message and "(line 3)" in error.message, error.message
    assert error.path == "x.a" and "\n" not in str(error)


TRAIN = """name: pair
components:
  0: {role: frame}
  1: {teeth: 20}
  2: {teeth: 40, internal: TAGGED}
links: [{type: mesh, between: [1, 2]}]
ports: [{component: 1, role: input, speed: 10 rad/s}, {component: 2, role: output}]
"""


@pytest.mark.parametrize("tagged, words", [BAD_TAGS[0], BAD_TAGS[2], BAD_TAGS[6],
                                           BAD_TAGS[8], BAD_TAGS[10], BAD_TAGS[16]])
def test_the_cli_reports_a_bad_tag_on_one_line(tagged, words, tmp_path, capsys) -> None:
    from powergraph.cli.main import main

    path = tmp_path / "m.yaml"
    path.write_text(TRAIN.replace("TAGGED", tagged))
    status = main(["solve", str(path)])
    out, err = capsys.readouterr()
    assert status == 2 and out == ""
    assert err.count("\n") == 1 and "Traceback" not in err
    assert err.startswith("powergraph: error: components.2.internal: ") and words in err
    assert "(line 5)" in err
