"""Every input file read in bounded memory (issue 34, item 1): a size limit per kind of
file, devices read only up to it, tables decoded as utf-8-sig with the first bad byte named."""
from __future__ import annotations

import os
import tracemalloc

import pytest

from powergraph.cli.main import main
from powergraph.errors import ModelError, UsageError
from powergraph.model.input_files import (CHUNK, KINDS, decode_text, max_bytes, read_bytes,
                                          read_table_text, size_limit)

ZERO = "/dev/zero"


def test_a_table_over_its_limit_is_refused_by_its_size(tmp_path) -> None:
    path = tmp_path / "points.csv"
    path.write_text("a\n" + "1\n" * 100)
    with size_limit(50, "table"):
        with pytest.raises(UsageError, match=r"too large for the points \(202 bytes; the "
                                             r"limit is 50 bytes: raise it with "
                                             r"--max-table-size"):
            read_bytes(path, "table", "the points")
    assert read_table_text(path, "the points").startswith("a\n1\n")


def test_the_two_kinds_have_their_own_limits_and_errors(tmp_path) -> None:
    path = tmp_path / "m.yaml"
    path.write_text("x" * 20)
    with size_limit(10, "model"):
        assert max_bytes("table") == KINDS["table"].default
        with pytest.raises(ModelError):
            read_bytes(path, "model", "a model file")
        assert read_bytes(path, "table", "a table") == b"x" * 20


def test_the_environment_variable_sets_the_table_limit(monkeypatch) -> None:
    monkeypatch.setenv("POWERGRAPH_MAX_TABLE_BYTES", "123")
    assert max_bytes("table") == 123
    monkeypatch.setenv("POWERGRAPH_MAX_TABLE_BYTES", "lots")
    with pytest.raises(UsageError, match="not a whole number of bytes"):
        max_bytes("table")


@pytest.mark.skipif(not os.path.exists(ZERO), reason="needs /dev/zero")
def test_dev_zero_stops_in_its_first_chunk() -> None:
    tracemalloc.start()
    try:
        with pytest.raises(UsageError, match=r"NUL byte \(U\+0000\) at byte 0 "
                                             r"\(line 1, column 1\): not a text file"):
            read_table_text(ZERO, "the points")
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 4 * CHUNK      # not the 100 MB limit


def test_a_small_file_costs_no_buffer_of_the_whole_limit(tmp_path) -> None:
    path = tmp_path / "small.csv"
    path.write_text("a,b\n1,2\n")
    tracemalloc.start()
    try:
        read_table_text(path, "the points")
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 4 * CHUNK < KINDS["table"].default


def test_a_byte_order_mark_is_skipped() -> None:
    assert decode_text(b"\xef\xbb\xbfa,b\n", "p.csv") == "a,b\n"


@pytest.mark.parametrize("data, byte, where", [
    (b"a,b\nn\xe9,1\n", 5, "line 2, column 2"),             # Latin-1 é
    (b"\xef\xbb\xbfa\n\x96\n", 5, "line 2, column 1"),        # cp1252 dash after a BOM
])
def test_latin1_is_refused_naming_the_byte_and_its_place(data, byte, where) -> None:
    with pytest.raises(UsageError) as info:
        decode_text(data, "p.csv")
    message = str(info.value)
    assert message.startswith("p.csv: not UTF-8 text: ")
    assert f"byte 0x{data[byte]:02x} at byte {byte} ({where})" in message


def test_a_folder_and_a_missing_file_are_one_line_errors(tmp_path) -> None:
    with pytest.raises(UsageError, match="is a directory, not the points"):
        read_bytes(tmp_path, "table", "the points")
    with pytest.raises(UsageError, match="no such file"):
        read_bytes(tmp_path / "nope.csv", "table", "the points")


def test_max_table_size_on_the_command_line(tmp_path, capsys) -> None:
    points = tmp_path / "points.csv"
    points.write_text("carrier.speed [rpm],carrier.power [kW]\n" + "1000,1\n" * 50)
    model = os.path.join(os.path.dirname(__file__), "..", "..", "models",
                         "planetary_2kh_carrier_to_ring.yaml")
    status = main(["--max-table-size", "100", "cycle", model, "--points", str(points)])
    err = capsys.readouterr().err.strip()
    assert status == 2 and len(err.splitlines()) == 1
    assert "too large for the points" in err and "--max-table-size" in err
    assert main(["--max-table-size", "ten", "cycle", model, "--points", str(points)]) == 2
