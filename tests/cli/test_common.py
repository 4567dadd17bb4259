"""Shared command-line helpers: output paths checked before any work, one parser per kind
of number, one-line argument errors.

The expected behaviour is the command line's promise (README, docs/architecture.md): a bad
argument ends with exit status 2 and one line ``powergraph: error: OPTION...`` naming the
argument, never a traceback and never exit 1 ("numerical problem").
"""
from __future__ import annotations

import errno
import json
import io
import os
import warnings
import shutil
from contextlib import redirect_stderr, redirect_stdout
from pathlib import Path

import pytest

from powergraph.cli.common import (say_wrote, check_output_file, efficiency_option, number_option,
                                   whole_option, write_atomically)
from powergraph.cli.main import build_parser, main, parse_size
from powergraph.errors import PowerGraphError, UsageError

ROOT = Path(__file__).resolve().parents[2]
RV = str(ROOT / "models" / "rv40e.yaml")
GEARSET = str(ROOT / "models" / "gearsets" / "simpson.yaml")

#: Every option that writes: (argv before it, option, kind). A missing model file, or a bad
#: number after the output option, shows that the output is checked before anything else.
WRITERS = [
    (["draw", "{missing}"], "-o", "figure"),
    (["compare", "{missing}"], "-o", "figure"),
    (["backlash", "{missing}"], "--plot", "figure"),
    (["cycloid", "--module", "x", "--teeth", "9", "--error", "0.01"], "--plot", "figure"),
    (["volume", "{missing}"], "--plot", "figure"),
    (["sweep", "{missing}", "--set", "links.*.efficiency=0.9"], "-o", "file"),
    (["sweep", "{missing}", "--set", "links.*.efficiency=0.9"], "--plot", "figure"),
    (["tolerance", "{missing}"], "-o", "figure"),
    (["map", "{missing}", "--torque", "100", "--speed", "1000"], "-o", "figure"),
    (["map", "{missing}", "--torque", "100", "--speed", "1000"], "--loss-map", "file"),
    (["enumerate", "--links", "x"], "-o", "folder"),
    (["synthesize", "--ratio", "x"], "-o", "folder"),
    (["modes", "{missing}"], "-o", "figure"),
    (["lever", "{missing}"], "-o", "figure"),
    (["cycle", "{missing}", "--points", "p.csv"], "-o", "file"),
    (["cycle", "{missing}", "--points", "p.csv"], "--plot", "figure"),
    (["shifts", "{missing}", "--ratios", "2"], "-o", "model"),
    (["import", "{missing}"], "-o", "model"),
    (["import", "{missing}", "-o", "imported.yaml"], "--points", "file"),
    (["export", "{missing}", "--to", "rexs"], "-o", "rexs"),
]
NAMES = {"figure": "x.png", "file": "x.csv", "folder": "out", "model": "x.yaml",
         "rexs": "x.rexs"}


def run(*argv: str) -> tuple[int, str, str]:
    """``main(argv)`` in-process: (status, stdout, stderr); argparse exits count too."""
    out, err = io.StringIO(), io.StringIO()
    with redirect_stdout(out), redirect_stderr(err), warnings.catch_warnings():
        warnings.simplefilter("error")
        try:
            status = main(list(argv))
        except SystemExit as exc:
            status = exc.code
    return status, out.getvalue(), err.getvalue()


def assert_names_option(status: int, out: str, err: str, option: str) -> str:
    assert status == 2 and out == "", err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in err, err
    assert lines[0].startswith(f"powergraph: error: {option}"), lines[0]
    return lines[0]


def test_every_writing_option_is_in_the_table() -> None:
    # A new command or option that writes a file or folder must join WRITERS.
    listed = {(argv[0], option) for argv, option, _ in WRITERS}
    found = set()
    commands = next(a for a in build_parser()._actions if a.dest == "command")
    for name, parser in commands.choices.items():
        for action in parser._actions:
            metavar = str(action.metavar or "")
            if action.option_strings and ("FILE" in metavar or "DIR" in metavar):
                found.add((name, action.option_strings[0]))
    assert found == listed


def _bad_output(case: str, kind: str, tmp_path: Path) -> tuple[str, str]:
    """(path, words of the message) of one bad output of this kind."""
    name = NAMES[kind]
    if case == "missing folder":
        return str(tmp_path / "missing" / "dir" / name), "folder"
    if case == "wrong kind":
        if kind == "folder":
            (tmp_path / "afile").write_text("x")
            return str(tmp_path / "afile"), "not a folder"
        (tmp_path / name).mkdir()
        return str(tmp_path / name), "is a folder"
    if case == "unwritable":
        return f"/proc/{name}", "cannot write"
    return str(tmp_path / "x.jpg"), "suffix"


@pytest.mark.parametrize("argv, option, kind, case", [
    pytest.param(argv, option, kind, case, id=f"{argv[0]} {option} {case}")
    for argv, option, kind in WRITERS
    for case in ["missing folder", "wrong kind", "unwritable"] + ["suffix"] * (kind == "figure")])
def test_bad_output_path_exits_2_before_any_work(argv, option, kind, case, tmp_path) -> None:
    # Once: `map -o missing/dir/x.png` and `sweep -o missing/x.csv` ended in a
    # FileNotFoundError traceback after the whole computation.
    if case == "unwritable" and not os.path.isdir("/proc/self"):
        pytest.skip("needs /proc, where no file can be created")
    path, words = _bad_output(case, kind, tmp_path)
    before = sorted(tmp_path.rglob("*"))
    full = [a.format(missing=str(tmp_path / "no-model.yaml")) for a in argv] + [option, path]
    line = assert_names_option(*run(*full), option=f"{option}:")
    assert words in line
    assert sorted(tmp_path.rglob("*")) == before   # nothing written, no temporary left


@pytest.mark.parametrize("argv, option", [
    pytest.param(argv, option, id=f"{argv[0]} {option}")
    for argv, option, kind in WRITERS if "{missing}" in argv and kind != "folder"])
def test_an_output_naming_the_model_file_is_refused(argv, option, tmp_path) -> None:
    # `sweep model.yaml -o model.yaml` once replaced the user's model with a CSV.
    model = tmp_path / "model.yaml"
    shutil.copy(ROOT / "models" / "rv40e.yaml", model)
    text = model.read_text()
    full = [a.format(missing=str(model)) for a in argv] + [option, str(model)]
    line = assert_names_option(*run(*full), option=f"{option}:")
    assert "overwrite the input" in line
    assert model.read_text() == text and sorted(tmp_path.iterdir()) == [model]


def test_a_cycle_output_naming_its_points_file_is_refused(tmp_path) -> None:
    points = tmp_path / "points.csv"
    points.write_text("x")
    line = assert_names_option(*run("cycle", str(ROOT / "models" / "rv40e.yaml"), "--points",
                                    str(points), "-o", str(points)), option="-o:")
    assert "overwrite the input" in line and points.read_text() == "x"


def test_output_file_name_too_long_for_the_folder(tmp_path) -> None:
    with pytest.raises(UsageError, match="longer than"):
        check_output_file(str(tmp_path / ("x" * 300 + ".png")), "-o", (".png",))
    assert check_output_file(str(tmp_path / ("x" * 240 + ".png")), "-o").suffix == ".png"


def test_a_failed_write_is_one_error_and_leaves_no_file(tmp_path) -> None:
    def full_disk(tmp: str) -> None:
        Path(tmp).write_text("half")
        raise OSError(errno.ENOSPC, "No space left on device")

    with pytest.raises(PowerGraphError, match="No space left"):
        write_atomically(tmp_path / "x.csv", full_disk)
    assert list(tmp_path.iterdir()) == []


# --- numbers ------------------------------------------------------------------------------
#: Texts that are no usable number for any option: not finite, subnormal, not a number,
#: non-ASCII digits, Python expressions.
NOT_NUMBERS = ["nan", "inf", "-inf", "1e309", "1e-320", "5e-324", "", " ", "1e", "10**30",
               "9**9**9", "١٢", "9" * 400, "0x10"]


@pytest.mark.parametrize("text", NOT_NUMBERS)
def test_number_option_refuses_what_is_no_finite_normal_number(text) -> None:
    with pytest.raises(UsageError, match="^--x "):
        number_option(text, "--x")


@pytest.mark.parametrize("text, low, high, above, below, ok", [
    ("0", 0, 1, False, False, True), ("-0", 0, 1, True, False, False),
    ("1", 0, 1, False, True, False), ("1e308", None, None, False, False, True),
    ("-1e308", -1e9, None, False, False, False), ("2.2250738585072014e-308", 0, 1, True, False,
                                                  True)])
def test_number_option_bounds(text, low, high, above, below, ok) -> None:
    if ok:
        assert number_option(text, "--x", low, high, above=above, below=below) == float(text)
    else:
        with pytest.raises(UsageError, match="must be"):
            number_option(text, "--x", low, high, above=above, below=below)


@pytest.mark.parametrize("text, value", [("7", 7), ("-0", 0), ("1e3", 1000), (" 12 ", 12),
                                         ("9223372036854775807", 2**63 - 1)])
def test_whole_option_reads_digits_exactly(text, value) -> None:
    assert whole_option(text, "--n", -10, 2**63) == value


@pytest.mark.parametrize("text", ["1.5", "1e400", "9" * 5000, "-1", "١", "", "10**30"])
def test_whole_option_refuses(text) -> None:
    with pytest.raises(UsageError, match="^--n .*whole number from 0 to 100"):
        whole_option(text, "--n", 0, 100)


def test_efficiency_option_range() -> None:
    # Every mesh at 1e-320 made RV-40E's losses overflow: "numerical problem", exit 1.
    assert efficiency_option("1") == 1.0 and efficiency_option("1e-6") == 1e-6
    for text in ("0", "-0", "1e-7", "1e-320", "1.0000001"):
        with pytest.raises(UsageError, match="^--mesh-efficiency"):
            efficiency_option(text)


@pytest.mark.parametrize("text, size", [("20M", 20_000_000), ("1.5k", 1500), ("1", 1),
                                        ("1000000G", 10**15)])
def test_max_model_size(text, size) -> None:
    assert parse_size(text) == size


#: A small synthesis (a second): values that are taken run it.
SMALL = ["--max-links", "4", "--teeth", "12:40"]
#: (argv with {v} for the value, option named in the message). Values of NOT_NUMBERS
#: fail for every one of them.
NUMERIC_OPTIONS = [
    (["--max-model-size={v}", "check", RV], "--max-model-size"),
    (["solve", RV, "--mesh-efficiency={v}"], "--mesh-efficiency"),
    (["draw", RV, "-o", "{tmp}/x.png", "--dpi={v}"], "--dpi"),
    (["compare", RV, "--mesh-efficiency={v}"], "--mesh-efficiency"),
    (["cycloid", "--module={v}", "--teeth", "9", "--error", "0.01"], "--module"),
    (["cycloid", "--module", "1", "--teeth={v}", "--error", "0.01"], "--teeth"),
    (["cycloid", "--module", "1", "--teeth", "9", "--error={v}"], "--error"),
    (["cycloid", "--module", "1", "--teeth", "9", "--error", "0", "--shift={v}"], "--shift"),
    (["cycloid", "--module", "1", "--teeth", "9", "--error", "0", "--rc={v}"], "--rc"),
    (["sweep", RV, "--set", "links.*.efficiency=0.9", "--mesh-efficiency={v}"],
     "--mesh-efficiency"),
    (["sweep", RV, "--set", "links.*.efficiency=0.9", "--workers={v}"], "--workers"),
    (["tolerance", RV, "--samples={v}"], "--samples"),
    (["tolerance", RV, "--seed={v}"], "--seed"),
    (["tolerance", RV, "--sobol-samples={v}"], "--sobol-samples"),
    (["mesh", "--", "{v}", "40"], "Z1"),
    (["mesh", "--", "20", "{v}"], "Z2"),
    (["mesh", "20", "40", "--module={v}"], "--module"),
    (["mesh", "20", "40", "--pressure-angle={v}"], "--pressure-angle"),
    (["mesh", "20", "40", "--helix={v}"], "--helix"),
    (["mesh", "20", "40", "--shift", "{v}", "0"], "--shift X1"),
    (["mesh", "20", "40", "--addendum={v}"], "--addendum"),
    (["mesh", "20", "40", "--mu={v}"], "--mu"),
    (["map", RV, "--torque={v}", "--speed", "1000"], "--torque"),
    (["map", RV, "--torque", "100:200:{v}", "--speed", "1000"], "--torque"),
    (["map", RV, "--torque", "100", "--speed={v}:1000:3"], "--speed"),
    (["map", RV, "--torque", "100", "--speed", "1000", "--rated={v}"], "--rated"),
    (["enumerate", "--links={v}"], "--links"),
    (["enumerate", "--links", "5", "--dof={v}"], "--dof"),
    (["synthesize", "--ratio={v}", *SMALL], "--ratio"),
    (["synthesize", "--ratio", "5", "--tolerance={v}", *SMALL], "--tolerance"),
    (["synthesize", "--ratio", "5", "--max-links={v}", "--teeth", "12:40"], "--max-links"),
    (["synthesize", "--ratio", "5", "--planets={v}", *SMALL], "--planets"),
    (["synthesize", "--ratio", "5", "--mesh-efficiency={v}", *SMALL], "--mesh-efficiency"),
    (["synthesize", "--ratio", "5", "--top={v}", *SMALL], "--top"),
    (["synthesize", "--ratio", "5", "--max-grid={v}", *SMALL], "--max-grid"),
    (["shifts", GEARSET, "--ratios={v}"], "--ratios"),
    (["shifts", GEARSET, "--ratios", "2.5,{v}"], "--ratios"),
    (["shifts", GEARSET, "--ratios", "2.5", "--tolerance={v}"], "--tolerance"),
    (["shifts", GEARSET, "--ratios", "2.5", "--top={v}"], "--top"),
]
QUICK_VALUES = ["-inf", "5e-324", "١٢"]


def _numeric_cases(values):
    return [pytest.param(argv, option, v, id=f"{argv[0]} {option} {v[:8]!r}")
            for argv, option in NUMERIC_OPTIONS for v in values]


@pytest.mark.parametrize("argv, option, value", _numeric_cases(QUICK_VALUES))
def test_numeric_option_refuses_values_at_the_float_limits(argv, option, value,
                                                           tmp_path) -> None:
    _assert_refused(argv, option, value, tmp_path)


@pytest.mark.slow
@pytest.mark.parametrize("argv, option, value", _numeric_cases(
    [v for v in NOT_NUMBERS if v not in QUICK_VALUES]))
def test_numeric_option_refuses_every_non_number(argv, option, value, tmp_path) -> None:
    _assert_refused(argv, option, value, tmp_path)


def _assert_refused(argv, option, value, tmp_path) -> None:
    full = [a.replace("{v}", value).replace("{tmp}", str(tmp_path)) for a in argv]
    if option == "--shift X1" and value.startswith("-"):
        option = "argument --shift:"   # argparse reads "-inf" as an option: one line too
    assert_names_option(*run(*full), option=f"{option} ")


@pytest.mark.parametrize("argv, option", [
    (["--max-model-size", "1" + "0" * 30, "check", RV], "--max-model-size"),
    (["--max-model-size", "1e308", "check", RV], "--max-model-size"),
    (["solve", RV, "--mesh-efficiency", "1e-320"], "--mesh-efficiency"),
    (["cycloid", "--module", "1", "--teeth", "9", "--error", "1e-30"], "--error"),
    (["cycloid", "--module", "1", "--teeth", "9", "--error", "0", "--shift", "1e-30"],
     "--shift"),
    (["map", RV, "--torque", "1e308", "--speed", "1000"], "--torque"),
    (["map", RV, "--torque", "100", "--speed", "1e308"], "--speed"),
    (["mesh", "1" + "0" * 30, "40"], "Z1"),
    (["synthesize", "--ratio", "1e-300", *SMALL], "--ratio"),
    (["tolerance", RV, "--samples", "1e308"], "--samples"),
])
def test_values_that_once_ended_in_exit_1_or_a_traceback(argv, option) -> None:
    # Each of these once ended with "numerical problem" (exit 1) or a numpy traceback.
    assert_names_option(*run(*argv), option=f"{option} ")


def test_argparse_mistakes_are_one_line() -> None:
    status, out, err = run("map", RV, "--torque", "-inf", "--speed", "1000")
    assert status == 2 and out == "" and err.count("\n") == 1
    assert err.startswith("powergraph: error: argument --torque: expected one argument")


RV40E = str(Path(__file__).resolve().parents[2] / "models" / "rv40e.yaml")


def test_say_wrote_goes_to_stdout_or_to_stderr_beside_data(capsys) -> None:
    say_wrote("a.png", "(actual powers)")
    say_wrote("b.csv", data_on_stdout=True)
    out, err = capsys.readouterr()
    assert out == "wrote a.png (actual powers)\n" and err == "wrote b.csv\n"


@pytest.mark.slow  # a solve and a figure
def test_json_on_stdout_stays_json_when_a_file_is_written(capsys, tmp_path) -> None:
    target = tmp_path / "v.png"
    assert main(["volume", RV40E, "--json", "--plot", str(target)]) == 0
    out, err = capsys.readouterr()
    json.loads(out)
    assert err.strip() == f"wrote {target}"


def test_the_programs_help_lists_every_command_and_a_commands_help_its_own(capsys) -> None:
    """A command line registers only the command it names; the program's help, asked
    for before any command, still lists them all."""
    from powergraph.cli.main import COMMANDS

    with pytest.raises(SystemExit):
        main(["--help", "solve"])
    listed = capsys.readouterr().out
    assert all(name in listed for name in COMMANDS)
    with pytest.raises(SystemExit):
        main(["solve", "--help"])
    assert "usage: powergraph solve" in capsys.readouterr().out


def test_print_json_writes_long_lists_one_item_a_line(capsys) -> None:
    """A duty cycle's --json of 10^5 rows took minutes through the indented pure-Python
    encoder: lists longer than LONG_LIST are now written one item a line. The text is
    the same JSON, NaN and infinities as null, small parts indented as before."""
    import json
    import math

    from powergraph.cli.common import LONG_LIST, print_json

    n = LONG_LIST + 1
    rows = [{"row": i, "efficiency": math.nan if i == 3 else 0.5, "losses": {"a": 1.0}}
            for i in range(n)]
    data = {"name": "t", "rows": rows, "nested": {"values": list(range(n)), "empty": {}},
            "short": [1.0, math.inf], "none": {}}
    print_json(data)
    text = capsys.readouterr().out
    expected = {"name": "t", "rows": [dict(r, efficiency=None if r["row"] == 3 else 0.5)
                                      for r in rows],
                "nested": {"values": list(range(n)), "empty": {}}, "short": [1.0, None],
                "none": {}}
    assert json.loads(text) == expected
    lines = text.splitlines()
    assert '    {"row": 3, "efficiency": null, "losses": {"a": 1.0}},' in lines
    assert len(lines) < 3 * n + 20            # one line a row, not one a value
    print_json({"a": [1, 2]})                 # small: indented as json.dumps(indent=2)
    assert capsys.readouterr().out == json.dumps({"a": [1, 2]}, indent=2) + "\n"
