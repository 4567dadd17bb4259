"""Issue 34: a duty cycle's points CSV (``powergraph.analyses.cycle_points``) read in
bounded memory, its header checked whole before a row, every cell checked, each problem
one error naming the file, the column and the row (the file's line).

Expected values are closed forms: 1 rpm = π/30 rad/s, 1 Hz = 2π rad/s, 1 kW = 1000 W,
1 min = 60 s; row numbers are counted by hand in each test's text.
"""
from __future__ import annotations

import io
import math
import tracemalloc
from pathlib import Path

import numpy as np
import pytest

import powergraph as pg
from powergraph.analyses import cycle_points
from powergraph.analyses.cycle_points import as_dict, read_points
from powergraph.errors import UsageError
from powergraph.model.input_files import size_limit

MODELS = Path(__file__).resolve().parents[2] / "models"
PLANETARY = pg.load_model(MODELS / "planetary_2kh_carrier_to_ring.yaml")  # carrier, ring
SIMPSON = pg.load_model(MODELS / "simpson_3speed.yaml")                  # modes 1, 2, 3, R
RPM = math.pi / 30


def refused(text: str, model=PLANETARY) -> str:
    """The one-line message of reading ``text``."""
    with pytest.raises(UsageError) as info:
        read_points(io.StringIO(text), model, "points.csv")
    message = str(info.value)
    assert "\n" not in message and message.startswith("points.csv: ")
    return message


# --- 1. bounded, columnar reading ------------------------------------------------------

def test_issue34_values_are_the_header_unit_times_the_cells_in_si() -> None:
    points = read_points(io.StringIO(
        "carrier.speed [Hz],ring.torque [kN*m],duration [min]\n2,3,0.5\n-1,0,2\n"), PLANETARY)
    assert points.columns == (("ports.0.speed", 0, "speed"), ("ports.1.torque", 1, "torque"))
    assert points.values[0].tolist() == pytest.approx([4 * math.pi, -2 * math.pi])
    assert points.values[1].tolist() == [3000.0, 0.0]
    assert points.durations.tolist() == [30.0, 120.0]
    assert points.lines.tolist() == [2, 3]
    assert as_dict(points, 0) == pytest.approx({"ports.0.speed": 4 * math.pi,
                                               "ports.1.torque": 3000.0})


def test_issue34_rows_are_converted_across_chunks_with_their_lines(monkeypatch) -> None:
    monkeypatch.setattr(cycle_points, "CHUNK", 3)
    text = "carrier.speed [rpm],carrier.power [W]\n" + "".join(
        f"{k},{2 * k}\n" + ("\n" if k == 4 else "") for k in range(1, 9))
    points = read_points(io.StringIO(text), PLANETARY)
    assert points.values[0].tolist() == pytest.approx([k * RPM for k in range(1, 9)])
    assert points.values[1].tolist() == [2.0 * k for k in range(1, 9)]
    # rows 1-4 on lines 2-5, a blank line 6, rows 5-8 on lines 7-10
    assert points.lines.tolist() == [2, 3, 4, 5, 7, 8, 9, 10]
    bad = text.replace("7,14", "7,x")
    assert "row 9, column 'carrier.power [W]': not a number: 'x'" in refused(bad)


def test_issue34_the_lines_of_a_file_end_in_lf_crlf_or_cr_across_pieces() -> None:
    text = 'a,"b\nc"\r\nd\x0ce\n\nf\rg'
    assert list(cycle_points._lines(text, size=2)) == ['a,"b\n', 'c"\n', "d\x0ce\n", "\n",
                                                       "f\n", "g"]
    # no LF at all (an old Mac spreadsheet): pieces end after a CR
    assert list(cycle_points._lines("a\rb\rc\r", size=1)) == ["a\n", "b\n", "c\n"]


def test_issue34_crlf_and_cr_line_ends_read_as_lf() -> None:
    text = "carrier.speed [rpm],duration [s]\n1,2\n\n3,4\n"
    for ends in ("\r\n", "\r"):
        points = read_points(io.StringIO(text), PLANETARY)
        again = read_points(cycle_points._lines(text.replace("\n", ends)), PLANETARY)
        assert again.durations.tolist() == points.durations.tolist() == [2.0, 4.0]
        assert again.lines.tolist() == points.lines.tolist() == [2, 4]


def test_issue34_a_row_after_a_quoted_line_end_is_named_by_its_own_line() -> None:
    text = 'carrier.speed [rpm],carrier.power [W]\n1,"2\n"\n3,x\n'
    # row 1 takes lines 2-3 (a line end inside quotes; "2\n" is the number 2), row 2 is line 4
    assert "row 4, column 'carrier.power [W]': not a number: 'x'" in refused(text)


def test_issue34_rows_are_stored_in_tens_of_bytes_each() -> None:
    """Memory taken by reading 10^5 rows of four columns (the lines given, already in
    memory): the float arrays, 8 bytes per cell and per line number, built from one chunk
    of rows at a time (twice while the chunks are joined), and that chunk; a list of
    per-row lists kept to the end would take some 300 bytes per row more."""
    n = 100_000
    lines = ["carrier.speed [rpm],carrier.power [kW],ring.speed [rpm],duration [s]\n"]
    lines += [f"{1000 + k % 997}.5678,1.2345678,370.37037,0.5\n" for k in range(n)]
    tracemalloc.start()
    try:
        points = read_points(iter(lines), PLANETARY)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert len(points) == n and points.durations.sum() == n / 2
    chunk = cycle_points.CHUNK * 400      # a row as a list of 4 str, then flat and by column
    assert peak < 2 * 8 * 5 * n + chunk


# --- 2. the header ---------------------------------------------------------------------

@pytest.mark.parametrize("header,words", [
    ("carrier.speed [rmp]", "column 'carrier.speed [rmp]': unknown unit 'rmp' in 'rmp': a "
                            "speed is written in rad/s, "),
    ("carrier.speed [kW]", "column 'carrier.speed [kW]': 'kW' is not a speed: a speed is "
                           "written in rad/s, "),
    ("carrier.power [rpm]", "column 'carrier.power [rpm]': 'rpm' is not a power: a power is "
                            "written in W, kW"),
    ("carrier.power [mw]", "column 'carrier.power [mw]': cannot read 'mw' as a power: 'mw' "
                           "could be mW or MW"),
])
def test_issue34_a_bad_header_unit_is_a_unit_problem_listing_the_units(header, words) -> None:
    message = refused(f"{header}\n1\n")
    assert words in message and "not a number" not in message and "row" not in message


def test_issue34_a_header_unit_is_read_once_in_any_case() -> None:
    points = read_points(io.StringIO("carrier.speed [RPM],carrier.power [KW]\n30,2\n"),
                         PLANETARY)
    assert points.values[0][0] == pytest.approx(math.pi) and points.values[1][0] == 2000.0


@pytest.mark.parametrize("header,words", [
    ("carrier.speed [rpm],carrier.speed [rpm]",
     "column 'carrier.speed [rpm]': the same quantity as column 'carrier.speed [rpm]'"),
    ("carrier.speed [rpm],carrier.speed [rad/s]",
     "column 'carrier.speed [rad/s]': the same quantity as column 'carrier.speed [rpm]' "
     "(ports[0] speed)"),
    ("carrier.power [kW],carrier.torque [N*m]",
     "column 'carrier.torque [N*m]': conflicts with column 'carrier.power [kW]': a port's "
     "load is its power or its torque, not both"),
    ("carrier.speed,duration [s],duration [min]",
     "column 'duration [min]': the same quantity as column 'duration [s]'"),
    ("carrier.speed,time [s],duration [s]",
     "column 'duration [s]': conflicts with column 'time [s]'"),
    ("carrier.speed,duration [ms]", "column 'duration [ms]': 'ms' is not a unit of time"),
    ("carrier.speed,gearbox.speed", "column 'gearbox.speed': expected PORT.speed, PORT.power "
     "or PORT.torque with PORT one of carrier, ring, duration [s], time [s] or mode"),
    ("carrier.speed,mode", "column 'mode': the model '2K-H carrier -> ring gear, sun gear "
     "fixed' has no modes"),
    ("duration [s]", "no PORT.speed, PORT.power or PORT.torque column"),
])
def test_issue34_the_header_is_refused_before_any_row(header, words) -> None:
    # the row below the header is not even CSV of the right width: never reached
    assert words in refused(f"{header}\nnot,a,row,at,all\n")


def test_issue34_two_mode_columns_and_a_missing_one_are_refused() -> None:
    assert "column 'mode': a second mode column" in refused(
        "in.speed,mode,mode\n1,1,1\n", SIMPSON)
    assert "no mode column, but the model has modes 1, 2, 3, R" in refused(
        "in.speed [rpm]\n1\n", SIMPSON)


def test_issue34_a_port_is_named_by_its_name_or_its_component_alike() -> None:
    ths = pg.load_model(MODELS / "ths2_power_split.yaml")
    engine = next(p for p in ths.ports if p.name == "engine")
    text = f"engine.speed [rpm],{engine.component}.speed [rpm]\n1,1\n"
    assert "the same quantity as column 'engine.speed [rpm]'" in refused(text, ths)


def test_issue34_a_utf8_bom_is_accepted_and_latin1_refused_with_its_byte(tmp_path) -> None:
    good = tmp_path / "bom.csv"
    good.write_bytes(b"\xef\xbb\xbfcarrier.speed [rpm],carrier.power [kW]\n1000,1\n")
    assert read_points(good, PLANETARY).values[1].tolist() == [1000.0]
    bad = tmp_path / "latin1.csv"
    bad.write_bytes(b"carrier.speed [rpm],carrier.power [kW]\nn\xe9,1\n")
    with pytest.raises(UsageError, match=r"latin1.csv: not UTF-8 text: byte 0xe9 at byte 40 "
                                         r"\(line 2, column 2\)"):
        read_points(bad, PLANETARY)


def test_issue34_a_device_is_read_only_up_to_the_table_limit() -> None:
    # /dev/zero never ends: refused (too large, or not text) by the table reader
    with size_limit(4096, "table"), pytest.raises(UsageError, match="^/dev/zero"):
        read_points("/dev/zero", PLANETARY)


# --- 3. the rows -----------------------------------------------------------------------

@pytest.mark.parametrize("body,words", [
    ("1000,1,99\n", "row 2: 3 cells, but the header has 2 columns"),
    ("1000,1\n1000\n", "row 3: 1 cells, but the header has 2 columns"),
    ("1000,\n", "row 2, column 'carrier.power [kW]': empty cell"),
    ("1000,1\n1000 rpm,1\n", "row 3, column 'carrier.speed [rpm]': not a number: '1000 rpm'"),
    ("nan,1\n", "row 2, column 'carrier.speed [rpm]': not a finite number: 'nan'"),
    ("1000,-inf\n", "row 2, column 'carrier.power [kW]': not a finite number: '-inf'"),
    # 1e306 kW = 1e309 W, beyond the largest float (1.8e308)
    ("1000,1e306\n", "row 2, column 'carrier.power [kW]': '1e306' overflows once in W"),
    ('1000,"1\n', "row 2: not CSV"),
])
def test_issue34_each_bad_row_is_named_by_its_line(body, words) -> None:
    assert words in refused("carrier.speed [rpm],carrier.power [kW]\n" + body)


def test_issue34_a_huge_cell_or_column_name_is_cut_in_the_message() -> None:
    # 10^5 digits: not a finite number (1e99999); the message shows 60 characters of it
    message = refused("carrier.speed [rpm]\n" + "1" * 100_000 + "\n")
    assert "not a finite number: '1111" in message and "(100002 characters)" in message
    assert len(message) < 200
    message = refused("carrier.speed [rpm]," + "x" * 100_000 + "\n1,1\n")
    assert "(100002 characters)" in message and len(message) < 300


def test_issue34_the_first_problem_by_row_is_reported_whatever_its_column() -> None:
    # row 3 has a bad power, row 2 (earlier) a bad speed: row 2 is named
    text = "carrier.speed [rpm],carrier.power [kW]\n1,1\nx,1\n2,y\n"
    assert "row 3, column 'carrier.speed [rpm]'" in refused(text)


def test_issue34_an_overflow_after_the_unit_scale_names_row_and_column() -> None:
    # 1e308 Hz is 2π·1e308 rad/s > 1.8e308; 1e308 rpm = 1.05e307 rad/s is a number, but
    # beyond the 1e6 rad/s a port's speed may be in a model file
    assert "row 2, column 'carrier.speed [Hz]': '1e308' overflows once in rad/s" in refused(
        "carrier.speed [Hz]\n1e308\n")
    assert ("row 2, column 'carrier.speed [rpm]': '1e308' is out of range: a port's speed is "
            "at most 1e+06 rad/s") in refused("carrier.speed [rpm]\n1e308\n")
    points = read_points(io.StringIO("carrier.speed [rad/s]\n-1e6\n"), PLANETARY)
    assert points.values[0][0] == -1e6


def test_issue34_blank_lines_are_skipped() -> None:
    points = read_points(io.StringIO("\ncarrier.speed [rpm],duration [s]\n\n1,2\n,\n  \n3,4\n\n"),
                         PLANETARY)
    assert points.durations.tolist() == [2.0, 4.0] and points.lines.tolist() == [4, 7]


@pytest.mark.parametrize("body,words", [
    ("1,-1\n", "row 2, column 'duration [s]': a duration must be >= 0, got -1 s"),
    ("1,1e308\n1,1e308\n", "column 'duration [s]': the durations add up to more than the "
                           "largest float"),
])
def test_issue34_durations_are_finite_and_not_negative(body, words) -> None:
    assert words in refused("carrier.speed [rpm],duration [s]\n" + body)


@pytest.mark.parametrize("body,words", [
    ("1,0\n1,2\n1,2\n", "row 4, column 'time [min]': the time does not increase"),
    ("1,0\n1,1e308\n", "row 3, column 'time [min]': '1e308' overflows once in s"),
    ("1,0\n", "column 'time [min]': sample times need two rows at least"),
])
def test_issue34_times_increase_and_their_steps_are_finite(body, words) -> None:
    assert words in refused("carrier.speed [rpm],time [min]\n" + body)


def test_issue34_a_time_step_that_overflows_is_named() -> None:
    text = "carrier.speed [rpm],time [s]\n1,-1e308\n1,1e308\n"
    assert "row 3, column 'time [s]': the step from the row before overflows" in refused(text)


def test_issue34_time_steps_give_the_durations() -> None:
    points = read_points(io.StringIO("carrier.speed,time [min]\n1,0\n1,0.5\n1,2\n"),
                         PLANETARY)
    assert points.durations.tolist() == [30.0, 90.0, 90.0]
    assert points.duration_column == "time [min]"


# --- 4. modes --------------------------------------------------------------------------

def test_issue34_an_unknown_mode_is_named_by_row_and_column() -> None:
    text = "in.speed [rpm],in.power [kW],mode\n2500,20,1\n2500,20,2\n2000,10,9\n"
    message = refused(text, SIMPSON)
    assert message == ("points.csv: row 4, column 'mode': unknown mode '9' (the model's "
                       "modes: 1, 2, 3, R)")
    assert "row 2, column 'mode': empty cell" in refused(text.replace("20,1", "20,"), SIMPSON)


def test_issue34_modes_are_stored_as_codes_into_their_names() -> None:
    points = read_points(io.StringIO("in.speed,mode\n1,2\n1, R\n1,2\n"), SIMPSON)
    assert points.mode_names == ("2", "R")
    assert points.mode_codes.tolist() == [0, 1, 0] and points.mode_codes.itemsize <= 4
    assert points.modes == ("2", "R", "2") and points.mode(1) == "R"
    assert np.all(points.durations == 1.0)
