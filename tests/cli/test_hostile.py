"""Hostile input: every command ends with exit 0 or 2 and one line, never a traceback.

How long each command takes is the benchmark's to measure (benchmarks/hostile_inputs.py
reports every run over 5 s); tests never time things."""
from __future__ import annotations

import io
import json
import os
import random
import sys
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
sys.path[:0] = [str(ROOT / "benchmarks"), str(ROOT / "tests" / "cli")]
from hostile_mutations import CLASSES, mutate  # noqa: E402  (the benchmark's mutation classes)
from hostile_tables import TABLE_CLASSES  # noqa: E402  (its table, mode and machine classes)
from test_common import NOT_NUMBERS, NUMERIC_OPTIONS, WRITERS  # noqa: E402
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
    status, _, err = run("check", "/dev/zero")
    line = assert_one_error_line(status, err)
    assert "too large" in line or "NUL byte" in line  # by its size, or at its first byte


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
        status, _, err = run(command, str(path))
        if status != 0:
            assert_one_error_line(status, err, expected=status)
            assert status == 2, err


# --- arguments and output paths (benchmarks/hostile_inputs.py runs these on every file) ----
@pytest.mark.slow
@settings(max_examples=100, deadline=None, derandomize=True)
@given(case=st.sampled_from(NUMERIC_OPTIONS), value=st.sampled_from(NOT_NUMBERS),
       writer=st.sampled_from(WRITERS), bad=st.sampled_from(["missing", "folder"]))
def test_random_limit_values_and_bad_outputs_exit_2_at_once(case, value, writer, bad,
                                                            tmp_path_factory) -> None:
    tmp = tmp_path_factory.mktemp("args")
    argv, option = case
    status, out, err = run(*[a.replace("{v}", value).replace("{tmp}", str(tmp)) for a in argv])
    assert_one_error_line(status, err)
    argv, option, kind = writer
    path = str(tmp / "missing" / "x.png") if bad == "missing" else str(tmp)
    if bad == "folder" and kind == "folder":
        (tmp / "afile").write_text("x")
        path = str(tmp / "afile")
    status, out, err = run(*[a.format(missing=str(tmp / "m.yaml")) for a in argv], option, path)
    assert f"error: {option}: " in assert_one_error_line(status, err)


def _answer(path: Path) -> tuple[float, float]:
    from powergraph.model import load_model

    modes = load_model(path).modes         # a model with modes: its first gear
    status, out, err = run("solve", str(path), "--json",
                           *(["--mode", next(iter(modes))] if modes else []))
    assert status == 0, err
    data = json.loads(out)
    return data["efficiency"], data["circulating_power"]


@pytest.mark.parametrize("name", ["rv40e.yaml", "planetary_2kh_sun_to_carrier.yaml",
                                  "wolfrom_3k.yaml"])
def test_equivalent_units_give_the_same_answer(name, tmp_path) -> None:
    # 1000 rpm = 1000 * 2*pi/60 rad/s and 1 kW = 1000 W: the same train, the same answer.
    text = (ROOT / "models" / name).read_text()
    data, expect = mutate("equivalent-unit", text, random.Random(0))
    assert expect == "same" and data != text.encode()
    path = tmp_path / name
    path.write_bytes(data)
    assert _answer(path) == pytest.approx(_answer(ROOT / "models" / name), rel=1e-12, abs=1e-9)


#: Mutation classes of the benchmark: each ends in exit 0 or 2 with one line, never a
#: traceback, with the plain model's answer where the train is unchanged.
PASSING = sorted(CLASSES)


@pytest.mark.slow
@settings(max_examples=40, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow])
@given(kind=st.sampled_from(PASSING), model=st.sampled_from(MODELS),
       seed=st.integers(0, 2**32 - 1))
def test_benchmark_mutation_classes_never_crash(kind, model, seed, tmp_path_factory) -> None:
    _registry()
    data, expect = mutate(kind, model.read_text(), random.Random(seed))
    path = tmp_path_factory.mktemp("hostile") / "m.yaml"
    path.write_bytes(data)
    for command in ("check", "solve"):
        status, _, err = run(command, str(path))
        if status != 0:
            assert_one_error_line(status, err)
        if expect == "same" and command == "solve":
            assert _answer(path) == pytest.approx(_answer(model), rel=1e-9, abs=1e-9)


# --- tables, modes and machines (benchmarks/hostile_tables.py, issue 34) -------------------
#: One case of each table class (class, model, seed), run through the commands that read
#: its hostile input (figures only where names are odd; of a model's modes, two solved one
#: by one); then the cases in which benchmarks/hostile_inputs.py found a problem, as its
#: report names them (``python benchmarks/hostile_inputs.py --make CLASS MODEL SEED``
#: writes one), run through every command.
TABLE_CASES = [
    ("points-units", "rv40e.yaml", 3), ("points-columns", "ths2_power_split.yaml", 3),
    ("points-cells", "zf8hp_8speed.yaml", 3), ("points-bytes", "wolfrom_3k.yaml", 3),
    ("points-files", "simpson_3speed.yaml", 3), ("points-same", "ths2_power_split.yaml", 3),
    ("points-same", "planetary_2kh_sun_to_ring.yaml", 4),
    ("map-values", "ths2_power_split.yaml", 3), ("map-grid", "ths2_power_split.yaml", 3),
    ("map-files", "ths2_power_split.yaml", 3), ("modes-names", "zf8hp_8speed.yaml", 3),
    ("modes-tables", "ravigneaux_4speed.yaml", 3),
    ("modes-elements", "lepelletier_6speed.yaml", 3), ("machines", "ths2_power_split.yaml", 3),
]
FOUND = [
    ("modes-names", "simpson_3speed.yaml", 1180064694),   # a mode "a\nb": a 2-line error
    ("modes-names", "ravigneaux_4speed.yaml", 1275040705),  # compare FILE:<300 chars>
    ("map-files", "ths2_power_split.yaml", 4003985375),   # map: "a\0b.csv"
]


def test_every_table_class_has_a_case() -> None:
    assert {kind for kind, _, _ in TABLE_CASES} == set(TABLE_CLASSES)


@pytest.mark.parametrize("kind, model, seed", TABLE_CASES + FOUND)
def test_table_classes_exit_0_or_2_with_one_line(kind, model, seed, tmp_path) -> None:
    from hostile_inputs import bundle_commands, cycle_answer, expand, same_cycle, write_bundle
    from hostile_tables import make_bundle

    _registry()
    rng = random.Random(seed)
    bundle = make_bundle(kind, (ROOT / "models" / model).read_text(), rng)
    commands = bundle_commands(bundle, rng)
    case, outputs = tmp_path / "case", tmp_path / "out"
    case.mkdir(), outputs.mkdir()
    write_bundle(bundle, case)
    figures = [c for c in commands if c[1][-1].endswith((".png", ".svg"))]
    if (kind, model, seed) not in FOUND:
        commands = [c for c in commands if c not in figures and not (
            c[0].startswith("solve --mode #") and c[0] not in ("solve --mode #0",
                                                               "solve --mode #1"))]
    answers = {}
    for label, argv in commands + (figures[:1] if bundle.figures else []):
        full = expand(argv, case, outputs, bundle.points)
        status, out, err = run(*full)
        assert status in (0, 2) and "Traceback" not in err, (kind, bundle.note, label, err)
        if status == 2:
            assert_one_error_line(status, err)
        answers[label] = cycle_answer(status, out) if label == "cycle --json" else None
    if bundle.expect == "same":                 # edits that keep the cycle keep its answer
        status, out, err = run(*expand(["cycle", "{m}", "--points", "{p}", "--json"], case,
                                       outputs, str(case / "plain.csv")))
        assert status == 0, err
        assert same_cycle(answers["cycle --json"], cycle_answer(status, out)), bundle.note
