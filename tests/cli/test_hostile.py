"""Hostile input: every command ends with exit 0 or 2 and one line, never a traceback."""
from __future__ import annotations

import io
import os
import time
import warnings
from contextlib import redirect_stderr, redirect_stdout
from pathlib import Path

import pytest
import yaml
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from powergraph.cli.main import main
from powergraph.model.units import _registry

ROOT = Path(__file__).resolve().parents[2]
MODELS = sorted((ROOT / "models").glob("*.yaml"))
UNSOLVABLE = {c["id"]: c for c in yaml.safe_load((ROOT / "tests" / "data" /
                                                  "unsolvable.yaml").read_text())}


def run(*argv: str) -> tuple[int, str, str]:
    """``main(argv)`` in-process: (status, stdout, stderr); argparse exits count too."""
    out, err = io.StringIO(), io.StringIO()
    with redirect_stdout(out), redirect_stderr(err), warnings.catch_warnings():
        warnings.simplefilter("error")  # a warning reaching the user is a failure
        try:
            status = main(list(argv))
        except SystemExit as exc:  # argparse errors
            status = exc.code
    return status, out.getvalue(), err.getvalue()


def assert_one_error_line(status: int, err: str, expected: int = 2) -> str:
    assert status == expected, err
    assert "Traceback" not in err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("powergraph: error: "), err
    return lines[0]


@pytest.mark.parametrize("case", ["contradictory-loads", "loads-missing"])
def test_check_runs_the_load_analysis(case: str, tmp_path) -> None:
    path = tmp_path / "m.yaml"
    path.write_text(UNSOLVABLE[case]["text"])
    status, out, err = run("check", str(path))
    assert out == ""
    line = assert_one_error_line(status, err)
    assert "ports: " in line and UNSOLVABLE[case]["match"] in line


def test_check_reports_the_loads_it_takes() -> None:
    # RV-40E: 2 ports, 1 DOF -> it takes the power or torque of 2 - 1 = 1 port (1 given).
    status, out, _ = run("check", str(ROOT / "models" / "rv40e_wang2021.yaml"))
    assert status == 0 and "1 DOF, loads of 1 of 1 port(s) given" in out


@pytest.mark.parametrize("text, place", [
    ("name: t\nx: \x01\n", "line 2, column 4"),
    ("name: t\x00\n", "line 1, column 8"),
    ("name: a\ufeffb\n", "line 1, column 8"),
])
def test_bad_characters_exit_2_naming_the_place(text: str, place: str, tmp_path) -> None:
    path = tmp_path / "m.yaml"
    path.write_text(text)
    for command in ("check", "solve", "volume", "backlash", "draw"):
        argv = [command, str(path)] + (["-o", str(tmp_path / "x.png")]
                                       if command == "draw" else [])
        status, _, err = run(*argv)
        assert place in assert_one_error_line(status, err)


@pytest.mark.skipif(not os.path.exists("/dev/zero"), reason="needs /dev/zero")
def test_check_dev_zero_is_refused_at_once() -> None:
    start = time.perf_counter()
    status, _, err = run("check", "/dev/zero")
    assert "too large" in assert_one_error_line(status, err)
    assert time.perf_counter() - start < 5.0  # generous: it reads at most 10 MB


def test_max_model_size_option(tmp_path) -> None:
    rv = str(ROOT / "models" / "rv40e_wang2021.yaml")
    status, _, err = run("--max-model-size", "1k", "check", rv)
    assert "the limit is 1000 bytes" in assert_one_error_line(status, err)
    assert run("--max-model-size", "1M", "check", rv)[0] == 0
    assert run("--max-model-size", "lots", "check", rv)[0] == 2


@pytest.mark.parametrize("dpi", ["100000", "0", "5", "nan"])
def test_draw_dpi_out_of_range_exits_2(dpi: str, tmp_path) -> None:
    status, _, err = run("draw", str(ROOT / "models" / "rv40e_wang2021.yaml"), "-o",
                         str(tmp_path / "x.png"), "--dpi", dpi)
    assert status == 2 and "--dpi" in err and not (tmp_path / "x.png").exists()


@pytest.mark.parametrize("port, place", [
    ("{component: 1, role: input, speed: 1e-308, power: 1e308}", "ports[0].power"),
    ("{component: 1, role: input, speed: .inf}", "ports[0].speed"),
    ("{component: 1, role: input, speed: .nan}", "ports[0].speed"),
    ("{component: 1, role: input, speed: 1e400 rpm}", "ports[0].speed"),
    ("{component: 1, role: input, torque: -1e300}", "ports[0].torque"),
])
def test_non_finite_or_huge_numbers_exit_2(port: str, place: str, tmp_path) -> None:
    path = tmp_path / "m.yaml"
    path.write_text("name: t\ncomponents: {0: {role: frame}, 1: {teeth: 20}, 2: {teeth: 40}}\n"
                    "links: [{type: mesh, between: [1, 2]}]\n"
                    f"ports: [{port}, {{component: 2, role: output}}]\n")
    status, _, err = run("solve", str(path), "--json")
    assert f"{place}: " in assert_one_error_line(status, err)


def _mutations(text: str, data: st.DataObject) -> str:
    """One random hostile edit of a model file's text."""
    kind = data.draw(st.sampled_from(["bytes", "line", "value", "insert"]))
    lines = text.splitlines(keepends=True)
    if kind == "bytes":
        raw = bytearray(text.encode())
        for _ in range(data.draw(st.integers(1, 4))):
            raw[data.draw(st.integers(0, len(raw) - 1))] = data.draw(st.integers(0, 255))
        return raw.decode("utf-8", errors="surrogateescape")
    index = data.draw(st.integers(0, len(lines) - 1))
    if kind == "line":
        return "".join(lines[:index] + (lines[index:index + 1] * 2 if data.draw(st.booleans())
                                        else []) + lines[index + 1:])
    junk = data.draw(st.sampled_from(["1e308", ".nan", "-.inf", "0", "-1", "9" * 40, "[]",
                                      "{}", "~", "true", "'x'", "*a", "&a [1]", "1e-308",
                                      "\x01", "\ufeff", "[[[[[[", "!!binary x"]))
    if kind == "value" and ": " in lines[index]:
        head = lines[index].split(": ", 1)[0]
        return "".join(lines[:index] + [f"{head}: {junk}\n"] + lines[index + 1:])
    return "".join(lines[:index] + [junk + "\n"] + lines[index:])


@settings(max_examples=60, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_random_mutations_of_library_models_never_crash(data, tmp_path_factory) -> None:
    _registry()  # pint's one-time start-up is not a per-file cost
    model = data.draw(st.sampled_from(MODELS))
    text = _mutations(model.read_text(), data)
    path = tmp_path_factory.mktemp("hostile") / "m.yaml"
    path.write_bytes(text.encode("utf-8", errors="surrogateescape"))
    for command in ("check", "solve"):
        start = time.perf_counter()
        status, _, err = run(command, str(path))
        assert time.perf_counter() - start < 1.0, (command, text)
        if status != 0:
            assert_one_error_line(status, err, expected=status)
            assert status == 2, err
