"""Every output the README shows comes from the command printed beside it.

A ``text`` block of the README is either introduced by a sentence naming a command in
backticks and "prints" (the block is an excerpt of that command's output: each of its
lines, other than the ``...`` elisions, must be a line of the real output), or starts with
``$ powergraph ...`` (the whole output follows). The JSON excerpt's numbers are checked
against the JSON the command prints.
"""
from __future__ import annotations

import json
import re
import shlex
from pathlib import Path

import pytest

from powergraph.cli.main import main

ROOT = Path(__file__).resolve().parents[1]
README = (ROOT / "README.md").read_text()
BLOCK = re.compile(r"```text\n(.*?)```", re.S)
INTRO = re.compile(r"`(powergraph [^`]+)` prints[^\n]*\n(?:[^\n]+\n)*?\n```text\n(.*?)```", re.S)


def _blocks() -> list[tuple[str, str]]:
    """(command, block) for every README block that shows a command's output."""
    found = [(command, block) for command, block in INTRO.findall(README)]
    for block in BLOCK.findall(README):
        first, _, rest = block.partition("\n")
        if first.startswith("$ powergraph "):
            found.append((first[2:], rest))
    return found


def _run(command: str, capsys, monkeypatch) -> str:
    monkeypatch.chdir(ROOT)
    argv = shlex.split(command)[1:]
    capsys.readouterr()
    assert main(argv) == 0
    return capsys.readouterr().out


def test_the_readme_shows_command_outputs() -> None:
    commands = [command for command, _ in _blocks()]
    assert any("--json" in c for c in commands) and any(c.startswith("powergraph compare")
                                                          for c in commands)


@pytest.mark.slow  # each block runs its command
@pytest.mark.parametrize("command, block", _blocks(), ids=lambda v: v[:60])
def test_readme_output_is_the_commands_own(command: str, block: str, capsys,
                                           monkeypatch) -> None:
    out = _run(command, capsys, monkeypatch)
    if "--json" in command:
        data = json.loads(out)
        shown = dict(re.findall(r'"(\w+)": (-?[\d.]+(?:e-?\d+)?|true|false)\b', block))
        flat = dict(data)
        for port in data.get("ports", []):   # the excerpt's per-port keys
            flat.update({k: v for k, v in port.items() if k not in flat})
        for key in ("name", "method"):
            assert f'"{key}": "{data[key]}"' in block
        for key, text in shown.items():
            if key in ("efficiency", "formal_efficiency", "input_power", "output_power",
                       "total_loss", "ratio", "dof"):
                assert float(data[key]) == pytest.approx(float(text), rel=1e-9), key
        return
    lines = {line.rstrip() for line in out.splitlines()}
    for line in block.splitlines():
        if line.strip() in ("", "...") or "..." in line:
            continue
        assert line.rstrip() in lines, f"{line!r} is not in the output of {command}"


def test_the_readme_opens_with_the_two_set_up_lines_under_its_title() -> None:
    # The two lines a new user runs first, and the two lines .ci/run runs.
    lines = README.splitlines()
    assert lines[:6] == ["# powergraph", "", "```",
                         "pip install -e . && powergraph solve models/rv40e.yaml",
                         'pip install -e ".[test]" && pytest', "```"]
    ci = (ROOT / ".ci" / "run").read_text()
    assert "pip install --quiet -e . && powergraph solve models/rv40e.yaml" in ci
    assert "pip install --quiet -e \".[test]\" && pytest" in ci
