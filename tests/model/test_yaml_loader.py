"""Strict, bounded YAML reading: bad characters, size, aliases, nesting, tags, duplicates."""
from __future__ import annotations

import os
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


@pytest.mark.skipif(not os.path.exists("/dev/zero"), reason="needs /dev/zero")
def test_an_endless_device_is_read_only_up_to_the_limit() -> None:
    with size_limit(1000):
        with pytest.raises(ModelError, match="too large"):
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
