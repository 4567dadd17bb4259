"""Issue 34: ``powergraph cycle MODEL --points FILE.csv [--keep-going]`` — every bad points
file of the audit is one line ``powergraph: error: FILE: ...`` and exit status 2, never a
traceback, a dropped cell or a total of nan; ``--keep-going`` leaves the rows that cannot
be solved out of the totals and says so.

Expected energies: 1 kW for 2 s is 2 kJ in; the planetary's efficiency is the closed form
(k + 1)·η0/(k·η0 + 1) with k = 3 and η0 = 0.98 · 0.99 (the model file's description).
"""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from powergraph.cli.main import main

MODELS = Path(__file__).resolve().parents[2] / "models"
PLANETARY = str(MODELS / "planetary_2kh_carrier_to_ring.yaml")   # ports carrier, ring
SIMPSON = str(MODELS / "simpson_3speed.yaml")
THS = str(MODELS / "ths2_power_split.yaml")
ETA0 = 0.98 * 0.99
EFFICIENCY = 4 * ETA0 / (3 * ETA0 + 1)


def run(capsys, tmp_path, content: bytes | str, *options: str,
        model: str = PLANETARY) -> tuple[int, str, str]:
    points = tmp_path / "points.csv"
    if isinstance(content, str):
        content = content.encode()
    points.write_bytes(content)
    status = main(["cycle", model, "--points", str(points), *options])
    out, err = capsys.readouterr()
    return status, out, err


def one_error(status: int, err: str, tmp_path) -> str:
    """The message of a one-line error with exit status 2, naming the points file."""
    assert status == 2
    assert len(err.splitlines()) == 1 and "Traceback" not in err
    assert err.startswith(f"powergraph: error: {tmp_path / 'points.csv'}")
    return err.strip()


HEADER = "carrier.speed [rpm],carrier.power [kW]"


@pytest.mark.parametrize("content,words", [
    (f"{HEADER}\n1000,1,99\n", "row 2: 3 cells, but the header has 2 columns"),
    ("carrier.speed [rmp],carrier.power [kW]\n1000,1\n",
     "column 'carrier.speed [rmp]': unknown unit 'rmp' in 'rmp': a speed is written in"),
    ("carrier.speed [kW],carrier.power [kW]\n1000,1\n",
     "column 'carrier.speed [kW]': 'kW' is not a speed: a speed is written in"),
    (b"carrier.speed [rpm],carrier.power [kW]\nn\xe9,1\n",
     "not UTF-8 text: byte 0xe9 at byte 40 (line 2, column 2)"),
    (b"carrier.sp\xe9ed [rpm]\n1\n", "not UTF-8 text: byte 0xe9 at byte 10 (line 1, column 11)"),
    (f"{HEADER},carrier.torque [N*m]\n1000,1,2\n", "column 'carrier.torque [N*m]': conflicts "
     "with column 'carrier.power [kW]'"),
    (f"{HEADER},carrier.speed [rpm]\n1000,1,1000\n", "column 'carrier.speed [rpm]': the same "
     "quantity as column 'carrier.speed [rpm]'"),
    (f"{HEADER},duration [s],duration [s]\n1000,1,1,1\n", "column 'duration [s]': the same "
     "quantity as column 'duration [s]'"),
    (f"{HEADER},time [s],duration [s]\n1000,1,1,1\n", "column 'duration [s]': conflicts with "
     "column 'time [s]'"),
    (f"{HEADER},mode,mode\n1000,1,1,1\n", "column 'mode': the model '2K-H carrier -> ring "
     "gear, sun gear fixed' has no modes"),
    ("carrier.speed [Hz],carrier.power [kW]\n1e308,1\n",
     "row 2, column 'carrier.speed [Hz]': '1e308' overflows once in rad/s"),
    (f"{HEADER}\n1000,1e306\n", "row 2, column 'carrier.power [kW]': '1e306' overflows once in W"),
    (f"{HEADER},duration [s]\n1000,1,1e308\n1000,1,1e308\n",
     "column 'duration [s]': the durations add up to more than the largest float"),
    # 1e9 kW = 1e12 W, the most a port takes, for 1e297 s: 1e309 J > 1.8e308
    (f"{HEADER},duration [s]\n1000,1e9,1e297\n",
     "column 'duration [s]': the energies over the cycle overflow"),
    (f"{HEADER}\n1000,1\n0,1\n", "row 3: cannot be solved: ports[0].power: a power is given "
     "but the component does not turn (speed 0)"),
])
def test_issue34_every_audit_reproducer_is_one_error_line_exit_2(capsys, tmp_path, content,
                                                                  words) -> None:
    status, out, err = run(capsys, tmp_path, content)
    assert words in one_error(status, err, tmp_path) and out == ""


def test_issue34_two_mode_columns_and_an_unknown_mode_name_the_column(capsys, tmp_path) -> None:
    status, _, err = run(capsys, tmp_path, "in.speed [rpm],in.power [kW],mode,mode\n1,1,1,1\n",
                         model=SIMPSON)
    assert "column 'mode': a second mode column" in one_error(status, err, tmp_path)
    csv = "in.speed [rpm],in.power [kW],mode\n2500,20,1\n2500,20,2\n2000,10,9\n"
    status, _, err = run(capsys, tmp_path, csv, model=SIMPSON)
    assert one_error(status, err, tmp_path).endswith(
        "points.csv: row 4, column 'mode': unknown mode '9' (the model's modes: 1, 2, 3, R)")


def test_issue34_a_utf8_bom_file_works(capsys, tmp_path) -> None:
    status, out, err = run(capsys, tmp_path, b"\xef\xbb\xbf" + f"{HEADER},duration [s]\n"
                           "1000,1,2\n".encode(), "--json")
    assert status == 0, err
    data = json.loads(out)
    assert data["energy_in"] == pytest.approx(2000.0, rel=1e-12)
    assert data["efficiency"] == pytest.approx(EFFICIENCY, rel=1e-12)


def test_issue34_dev_zero_stops_at_the_table_limit(capsys) -> None:
    status = main(["--max-table-size", "64k", "cycle", PLANETARY, "--points", "/dev/zero"])
    err = capsys.readouterr().err
    # refused by the table reader (too large, or not text), not read to the end
    assert status == 2 and len(err.splitlines()) == 1
    assert err.startswith("powergraph: error: /dev/zero") and "Traceback" not in err


def test_issue34_keep_going_counts_the_rows_left_out(capsys, tmp_path) -> None:
    content = f"{HEADER},duration [s]\n1000,1,2\n0,1,3\n"
    status, out, err = run(capsys, tmp_path, content, "--keep-going")
    assert status == 0, err
    assert "left out            1 row(s), 3 s (cannot be solved; file lines 3)" in out
    assert "time                2 s" in out and "energy in           2 kJ" in out
    status, out, err = run(capsys, tmp_path, content, "--keep-going", "--json")
    data = json.loads(out)
    assert data["left_out"] == {"rows": 1, "time": 3.0} and data["time"] == 2.0
    assert data["energy_out"] == pytest.approx(2000.0 * EFFICIENCY, rel=1e-12)


def test_issue34_no_row_solved_is_an_error_with_or_without_keep_going(capsys, tmp_path) -> None:
    content = "MG2.speed [rpm],engine.power [kW],wheels.speed [rpm]\n1000,10,400\n"
    for options in ((), ("--keep-going",)):
        status, out, err = run(capsys, tmp_path, content, *options, model=THS)
        message = one_error(status, err, tmp_path)
        assert "train has 2 degrees of freedom but 3 speeds were given" in message
        assert ("no row could be solved" in message) == bool(options) and out == ""
