"""Helpers shared by the commands (powergraph/cli/common.py): the ``wrote FILE`` line."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from powergraph.cli.common import say_wrote
from powergraph.cli.main import main

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
