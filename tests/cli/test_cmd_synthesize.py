"""``powergraph synthesize --ratio R ...``.

Expected values: the 2K-H's ratio with the ring fixed, sun in and carrier out,
``1 + z_r/z_s`` (Willis), checked on the teeth each row reports; single solves of the
written model files (with ``assert_conservation``).
"""
from __future__ import annotations

import json
import re

import pytest

import powergraph as pg
from powergraph.cli.main import main
from powergraph.model import load_model
from powergraph.testing import assert_conservation


def run(capsys, *argv: str) -> tuple[int, str, str]:
    status = main(["synthesize", *argv])
    out, err = capsys.readouterr()
    return status, out, err


@pytest.mark.slow
def test_table_lists_trains_within_the_tolerance(capsys) -> None:
    status, out, err = run(capsys, "--ratio", "5", "--max-links", "4", "--top", "4")
    assert status == 0, err
    lines = out.splitlines()
    assert lines[0].startswith("synthesis for ratio 5 : 1 ± 0.50%")
    header = next(line for line in lines if "train" in line)
    for column in ("ratio", "eff %", "back %", "circ/P", "Pv/P", "meshes"):
        assert column in header
    assert max(len(line) for line in lines) <= 100


def test_json_rows_carry_the_compare_fields(capsys) -> None:
    status, out, err = run(capsys, "--ratio", "5", "--max-links", "4", "--top", "3",
                           "--tolerance", "1%", "--json")
    assert status == 0, err
    data = json.loads(out)
    assert data["tolerance"] == pytest.approx(0.01) and 1 <= len(data["rows"]) <= 3
    for row in data["rows"]:
        for key in ("ratio", "efficiency", "backdrive_efficiency", "backdrive_self_locking",
                    "circulating_power", "max_virtual_power_ratio", "meshes", "teeth"):
            assert key in row
        assert abs(row["ratio"] / 5 - 1) <= 0.01 * (1 + 1e-12)   # 4.95 is on the edge
    simple = [r for r in data["rows"] if r["layout"] == "simple"
              and re.search(r"sun L\d in, carrier L\d out, ring L\d fixed", r["name"])]
    assert simple
    for row in simple:          # teeth: sun, planet twice, ring
        ring = row["teeth"][row["rings"][0]]
        values = sorted(row["teeth"].values())
        planet = next(z for z in values if values.count(z) == 2)
        (sun,) = [z for z in values if z not in (planet, ring)]
        assert ring == sun + 2 * planet                          # coaxial
        assert row["ratio"] == pytest.approx(1 + ring / sun)     # Willis, ring fixed


@pytest.mark.slow
def test_output_folder_gets_models_and_diagrams(capsys, tmp_path) -> None:
    target = tmp_path / "best"
    status, out, err = run(capsys, "--ratio", "-4", "--max-links", "4", "--top", "2",
                           "-o", str(target), "--json")
    assert status == 0, err
    rows = json.loads(out)["rows"]
    models = sorted(target.glob("*.yaml"))
    assert len(models) == len(rows) == len(sorted(target.glob("*.png")))
    for path, row in zip(models, rows):
        result = pg.solve(load_model(path))
        assert_conservation(result)
        assert result.ratio == pytest.approx(row["ratio"], rel=1e-9)
        assert result.efficiency == pytest.approx(row["efficiency"], rel=1e-9)


@pytest.mark.parametrize("argv, words", [
    (["--ratio", "x"], "--ratio x"),
    (["--ratio", "0"], "--ratio 0"),
    (["--ratio", "5", "--tolerance", "200%"], "--tolerance"),
    (["--ratio", "5", "--teeth", "12"], "--teeth"),
    (["--ratio", "5", "--teeth", "50:20"], "--teeth"),
    (["--ratio", "5", "--planets", "2.5"], "--planets"),
    (["--ratio", "5", "--mesh-efficiency", "1.2"], "--mesh-efficiency"),
    (["--ratio", "5", "--top", "0"], "--top"),
    (["--ratio", "5", "--workers", "0"], "--workers"),
    (["--ratio", "5", "--scheduler", "localhost:8786"], "dask://"),
    (["--ratio", "5", "-o", "/nonexistent/folder/x"], "-o"),
])
def test_bad_arguments_exit_2_with_one_line(capsys, argv, words) -> None:
    status, out, err = run(capsys, *argv)
    assert status == 2
    assert len(err.strip().splitlines()) == 1 and words in err
    assert "Traceback" not in err


def test_workers_and_scheduler_exclude_each_other(capsys) -> None:
    with pytest.raises(SystemExit) as exit_info:
        main(["synthesize", "--ratio", "5", "--workers", "2", "--scheduler", "dask://h:1"])
    assert exit_info.value.code == 2


def test_file_stems_are_cut_between_words() -> None:
    from powergraph.cli.cmd_synthesize import file_stem

    name = "Simpson / two 2K-H stages (6-link d-graph 7 (r-graph 3)) simple+simple: sun L1 in"
    stem = file_stem(name, limit=60)
    words = name.replace("/", " ").replace("-", " ").replace("(", " ").replace(")", " ")
    assert len(stem) <= 60 and set(stem.split("_")) <= set(words.replace(":", " ")
                                                            .replace("+", " ").split())
    assert stem == "Simpson_two_2K_H_stages_6_link_d_graph_7_r_graph_3_simple"


@pytest.mark.slow  # a synthesis over the 6-link graphs (about 30 s)
def test_no_two_rows_read_the_same(capsys, tmp_path) -> None:
    """Two d-graphs that differ only in which planets share a pin give the same gears and
    figures: the row names must still differ (the pin note), and each row its file."""
    status, out, err = run(capsys, "--ratio", "100", "--top", "8", "-o", str(tmp_path))
    assert status == 0, err
    lines = out.splitlines()
    assert max(len(line) for line in lines if not line.startswith("wrote ")) <= 100
    starts = [i for i, x in enumerate(lines) if re.match(r" ?\d+  ", x)]
    assert len(starts) == 8
    # the enumeration's graph number tells a reader nothing: drop it, rows must still differ
    label = re.compile(r"\d-link d-graph \d+")
    shown = [(label.sub("", lines[i][:48]),) + tuple(lines[i + 1:i + 3]) for i in starts]
    assert len(set(shown)) == len(shown)
    assert len(list(tmp_path.glob("*.yaml"))) == 8
    assert out.count("wrote ") == 8


def test_more_workers_than_cores_is_said(capsys, monkeypatch) -> None:
    import argparse
    import os

    from powergraph.cli.common import cluster_options

    monkeypatch.setattr(os, "cpu_count", lambda: 2)
    options = cluster_options(argparse.Namespace(workers="3", scheduler=None))
    assert options == {"workers": 3, "scheduler": None}
    err = capsys.readouterr().err
    assert err.startswith("warning: --workers 3") and "2 cores" in err and err.count("\n") == 1
    cluster_options(argparse.Namespace(workers="2", scheduler=None))
    assert capsys.readouterr().err == ""


@pytest.mark.slow
def test_graphs_with_an_idle_gear_are_named_not_searched(capsys) -> None:
    # by hand: the 3-link gear pair on the frame, the 4-link three gears in a row on the
    # frame (d-graph 2) and the 4-link gear on a crank (d-graph 3) each have a gear off the
    # main axis that meshes one gear only and carries nothing: never fixed, driven or
    # loaded, it passes no power; the 2K-H and the K-H-V are searched
    status, out, err = run(capsys, "--ratio", "5", "--max-links", "4", "--json")
    assert status == 0, err
    data = json.loads(out)
    assert data["idle"] == ["3-link d-graph 1 (r-graph 1)", "4-link d-graph 2 (r-graph 1)",
                            "4-link d-graph 3 (r-graph 2)"]
    assert data["skipped"] == [] and data["graphs"] == 5 and data["rows"]
    status, out, err = run(capsys, "--ratio", "5", "--max-links", "4")
    assert "3 graph(s) not searched" in out and max(map(len, out.splitlines())) <= 100
