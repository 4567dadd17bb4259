"""``powergraph backlash MODEL [--json] [--output ID] [--plot FILE]``.

Reference values: Li et al. (2012), "Backlash control and compensation for internal meshing
involute spur gears", pairs 1 and 2, as printed and recomputed by hand from its equations
(tests/data/published_values.yaml, section ``li2012``).
"""
from __future__ import annotations

import json
from pathlib import Path

import pytest
import yaml

from powergraph.cli.main import main

ROOT = Path(__file__).resolve().parents[2]
LI2012 = str(ROOT / "models" / "backlash_li2012.yaml")
LI = yaml.safe_load((ROOT / "tests" / "data" / "published_values.yaml").read_text())["li2012"]
NO_BACKLASH = """
name: plain pair
components: {0: {role: frame}, 1: {teeth: 20}, 2: {teeth: 60}}
links: [{type: mesh, between: [1, 2]}]
ports: [{component: 1, role: input}, {component: 2, role: output}]
"""


def arcmin(text: str) -> float:
    """``6'57.1"`` -> arc minutes."""
    minutes, seconds = text.rstrip('"').split("'")
    return int(minutes) + float(seconds) / 60


def run(capsys, *argv: str) -> tuple[int, str, str]:
    status = main(["backlash", *argv])
    out, err = capsys.readouterr()
    return status, out, err


def test_json_keys_and_reference_values(capsys) -> None:
    status, out, err = run(capsys, LI2012, "--json")
    assert status == 0, err
    data = json.loads(out)
    assert set(data["output_lost_motion_arcmin"]) == {"worst_case", "rss"}
    first, second = data["meshes"]
    assert first["between"] == ["R1", "G1"]
    # a'' printed 2.572 / 2.565 (Eq. 15 as printed, within 0.01 mm), 2.522 / 2.514 with
    # tan α (within 0.001 mm); after compensation 2'3.5" and 2'23.5" (recomputed).
    for mesh, printed, standard, after, shift in zip(
            (first, second), LI["eccentric_offset_printed"], LI["eccentric_offset_standard"],
            LI["lost_motion_recomputed"]["after"], LI["equivalent_shift_recomputed"]):
        assert mesh["eccentric_offset"]["paper"] == pytest.approx(printed, abs=0.01)
        assert mesh["eccentric_offset"]["standard"] == pytest.approx(standard, abs=0.001)
        assert mesh["lost_motion_arcmin"]["after"] == pytest.approx(arcmin(after), abs=0.001)
        assert list(mesh["equivalent_shift"].values()) == pytest.approx(shift, abs=0.00005)
    assert set(first["lost_motion_arcmin"]) == {"thickness", "runout", "bearing", "before",
                                                "after"}


def test_human_report(capsys) -> None:
    status, out, _ = run(capsys, LI2012)
    assert status == 0
    # The recomputed lost motions, written as the paper writes angles: 6'57.1", 2'3.5"...
    recomputed = LI["lost_motion_recomputed"]
    for text in (*recomputed["before"], *recomputed["after"], "worst case", "RSS",
                 "eccentric offset a''"):
        assert text in out


def test_plot_writes_a_figure(capsys, tmp_path) -> None:
    target = tmp_path / "fig3.png"
    status, _, err = run(capsys, LI2012, "--plot", str(target))
    assert status == 0, err
    assert target.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize("argv,message", [
    (("--plot", "fig.txt"), "suffix"),
    (("--plot", "/no/such/folder/fig.png"), "does not exist"),
    (("--output", "Q"), "unknown component"),
])
def test_bad_arguments_exit_2(capsys, argv, message) -> None:
    status, out, err = run(capsys, LI2012, *argv)
    assert status == 2 and message in err and "Traceback" not in err and out == ""


def test_model_without_backlash_exits_2(capsys, tmp_path) -> None:
    model = tmp_path / "plain.yaml"
    model.write_text(NO_BACKLASH)
    status, _, err = run(capsys, str(model))
    assert status == 2 and "no mesh carries backlash" in err


def test_bad_block_exits_2_with_its_path(capsys, tmp_path) -> None:
    text = Path(LI2012).read_text().replace("pin_diameter: 1.732", "pin_diameter: -1.732", 1)
    model = tmp_path / "bad.yaml"
    model.write_text(text)
    status, _, err = run(capsys, str(model), "--json")
    assert status == 2 and "links[0].backlash.pin_diameter" in err


def test_help_lists_the_command(capsys) -> None:
    with pytest.raises(SystemExit):
        main(["backlash", "--help"])
    assert "--plot" in capsys.readouterr().out
