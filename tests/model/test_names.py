"""Names and ids are one line of text, and YAML 1.1's booleans are not names (issue 34:
a mode named ``"a\\nb"`` made two-line errors; ``off:`` silently became a mode ``False``)."""
from __future__ import annotations

from pathlib import Path

import pytest

from powergraph.cli.main import main
from powergraph.errors import ModelError
from powergraph.model import loads_model

SIMPSON = (Path(__file__).resolve().parents[2] / "models" / "simpson_3speed.yaml").read_text()
THS = (Path(__file__).resolve().parents[2] / "models" / "ths2_power_split.yaml").read_text()


def edited(text: str, old: str, new: str) -> str:
    assert old in text
    return text.replace(old, new, 1)


@pytest.mark.parametrize("text, path, words", [
    (edited(SIMPSON, '  "2": [C1, B1]', "  off: [C1, B1]"), "modes.False", "boolean false"),
    (edited(SIMPSON, '  "2": [C1, B1]', "  yes: [C1, B1]"), "modes.True", "boolean true"),
    (edited(SIMPSON, '  "2": [C1, B1]', "  ~: [C1, B1]"), "modes.None", "read as nothing"),
    (edited(SIMPSON, '  "2": [C1, B1]', '  "a\\nb": [C1, B1]'), "modes.a\\nb", "one line"),
    (edited(SIMPSON, "  in: {name: input shaft}", "  on: {name: input shaft}"),
     "components.True", "boolean true"),
    (edited(SIMPSON, "  in: {name: input shaft}", '  "i\\tn": {name: input shaft}'),
     "components.i\\tn", "one line"),
    (edited(SIMPSON, "  in: {name: input shaft}", '  in: {name: "input\\nshaft"}'),
     "components.in.name", "one line"),
    (edited(SIMPSON, "name: C1,", 'name: "C\\r1",'), "links[5].name", "one line"),
    (edited(SIMPSON, "name: Simpson 3-speed", "name: yes"), "name", "got True"),
    (edited(THS, "name: MG1,", 'name: "MG\\u20281",'), "ports[1].name", "one line"),
    (edited(THS, "  dc: {battery: 0 W}", "  no: {battery: 0 W}"), "buses.False",
     "boolean false"),
], ids=lambda v: v if isinstance(v, str) and len(v) < 40 else "")
def test_a_name_that_is_not_one_line_of_text_is_refused(text, path, words) -> None:
    with pytest.raises(ModelError) as info:
        loads_model(text)
    assert info.value.path == path and words in info.value.message
    assert "\n" not in str(info.value)


def test_numbers_are_names_as_written() -> None:
    model = loads_model(edited(SIMPSON, '  "2": [C1, B1]', "  2: [C1, B1]"))
    assert list(model.modes) == ["1", "2", "3", "R"]


def test_the_command_line_says_it_in_one_line(tmp_path, capsys) -> None:
    path = tmp_path / "m.yaml"
    path.write_text(edited(SIMPSON, '  "2": [C1, B1]', '  "a\\nb": [C1, B1]'))
    for argv in (["check", str(path)], ["solve", str(path), "--mode", "x"],
                 ["modes", str(path)]):
        assert main(argv) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and "one line of text" in err
