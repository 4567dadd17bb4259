"""``powergraph enumerate --links N [--dof D] [--json] [-o DIR]`` (docs/synthesis.md)."""
from __future__ import annotations

import json

import pytest

from powergraph.cli.main import main
from powergraph.model import load_model
from powergraph.statics import solve
from powergraph.testing import assert_conservation


def run(capsys, *argv: str) -> tuple[int, str, str]:
    status = main(["enumerate", *argv])
    out, err = capsys.readouterr()
    return status, out, err


def test_json_counts(capsys) -> None:
    """Four links by hand (tests/analyses/test_synthesis_enumerate.py): 2 r-graphs, 3 d-graphs."""
    status, out, err = run(capsys, "--links", "4", "--json")
    assert status == 0, err
    data = json.loads(out)
    assert (data["links"], data["dof"], data["rotation_graphs"],
            data["displacement_graphs"]) == (4, 1, 2, 3)
    assert len(data["graphs"]) == 3
    assert sorted({g["rotation_graph"] for g in data["graphs"]}) == [1, 2]
    assert all(len(g["gear_pairs"]) == 2 and len(g["turning_pairs"]) == 3
               for g in data["graphs"])


def test_text_report_quotes_the_published_six_link_counts(capsys) -> None:
    status, out, _ = run(capsys, "--links", "6")
    assert status == 0
    assert "(published: 27)" in out and "(published: 81)" in out


def test_output_folder_gets_models_that_solve_and_a_sheet(capsys, tmp_path) -> None:
    folder = tmp_path / "trains"
    status, out, err = run(capsys, "--links", "4", "-o", str(folder))
    assert status == 0, err
    assert out.splitlines()[-1] == f"wrote {folder} (3 model files and graphs.png)"
    files = sorted(folder.glob("dgraph_*.yaml"))
    assert len(files) == 3          # 4 links: 3 d-graphs (derived by hand in the analysis tests)
    assert (folder / "graphs.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    for path in files:
        model = load_model(path)
        assert "placeholder" in model.description
        assert model.name.startswith("4-link d-graph")
        assert all(c.name for c in model.components.values())      # every part named
        assert model.components[model.frame].name.endswith("(fixed)")
        result = solve(model)
        assert_conservation(result)
        assert 0 < result.efficiency <= 1


def test_two_dof_json(capsys) -> None:
    status, out, _ = run(capsys, "--links", "5", "--dof", "2", "--json")
    assert status == 0
    assert all(len(g["gear_pairs"]) == 2 for g in json.loads(out)["graphs"])


@pytest.mark.parametrize("argv", [[], ["--links", "x"], ["--links", "2"], ["--links", "11"],
                                  ["--links", "5", "--dof", "0"], ["--links", "5", "--dof", "4"],
                                  ["--links", "5", "--dof", "1.5"]])
def test_bad_arguments_exit_2_with_one_line(capsys, argv) -> None:
    status, out, err = run(capsys, *argv)
    assert status == 2 and out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("powergraph: error: ")


def test_output_path_that_is_a_file_or_has_no_parent(capsys, tmp_path) -> None:
    afile = tmp_path / "f"
    afile.write_text("x")
    for target in (afile, tmp_path / "missing" / "deeper"):
        status, _, err = run(capsys, "--links", "3", "-o", str(target))
        assert status == 2 and len(err.strip().splitlines()) == 1
