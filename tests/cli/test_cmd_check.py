"""`powergraph check` prints the model's warnings and exits 0; `check --strict` and
`solve --strict` refuse a model with warnings (exit 2, one error line per warning)."""
from __future__ import annotations

import json
from pathlib import Path

import yaml

from powergraph.cli.main import main

ROOT = Path(__file__).resolve().parents[2]
SOUND = str(ROOT / "models" / "planetary_2kh_sun_to_carrier.yaml")


def broken(tmp_path: Path) -> str:
    """The bundled 2K-H (sun 24, planet 24, ring 72, 3 planets) with a 23-tooth sun and 5
    planets: 23 + 2·24 = 71 ≠ 72 (coaxiality), but (23 + 72)/5 = 19 is whole (it
    assembles): one caveat, coaxiality."""
    doc = yaml.safe_load(Path(SOUND).read_text())
    doc["components"]["sun"]["teeth"] = 23
    doc["components"]["planet"]["count"] = 5
    path = tmp_path / "broken.yaml"
    path.write_text(yaml.safe_dump(doc))
    return str(path)


def test_check_prints_each_warning_after_the_ok_line_and_exits_0(tmp_path, capsys) -> None:
    model = broken(tmp_path)
    assert main(["check", model]) == 0
    out, err = capsys.readouterr()
    lines = out.splitlines()
    assert lines[0].startswith(f"{model}: ok") and err == ""
    assert lines[1:] == ["warning: links[0..1]: sun 23 + 2 × planet 24 = 71 ≠ ring 72: the "
                         "planets cannot share the axis of sun and ring (one module, no "
                         "profile shift; if the set is profile-shifted, give each of these "
                         "meshes a geometry with its shifts or its centre_distance)"]


def test_check_strict_refuses_with_one_line_per_warning(tmp_path, capsys) -> None:
    doc = yaml.safe_load(Path(SOUND).read_text())
    doc["components"]["planet"]["count"] = 5          # (24 + 72)/5 = 19.2
    doc["components"]["ring"]["teeth"] = 73            # 24 + 48 = 72 ≠ 73
    path = tmp_path / "two.yaml"
    path.write_text(yaml.safe_dump(doc))
    assert main(["check", "--strict", str(path)]) == 2
    out, err = capsys.readouterr()
    assert out == ""
    lines = err.splitlines()
    assert len(lines) == 2 and all(line.startswith("powergraph: error: ") for line in lines)
    assert lines[0].startswith("powergraph: error: links[0..1]: sun 24 + 2 × planet 24 = 72 "
                               "≠ ring 73")
    assert lines[1].startswith("powergraph: error: components.planet.count: (24 + 73)/5 = "
                               "19.4 is not whole")


def test_a_sound_model_passes_check_strict_silently(capsys) -> None:
    assert main(["check", "--strict", SOUND]) == 0
    out, err = capsys.readouterr()
    assert err == "" and len(out.splitlines()) == 1 and "warning" not in out


def test_solve_strict_refuses_before_solving(tmp_path, capsys) -> None:
    model = broken(tmp_path)
    assert main(["solve", "--strict", "--json", model]) == 2
    out, err = capsys.readouterr()
    assert out == "" and err.startswith("powergraph: error: links[0..1]: sun 23")
    assert main(["solve", "--json", model]) == 0        # without --strict: solved
    assert json.loads(capsys.readouterr().out)["dof"] == 1
    assert main(["solve", "--strict", "--json", SOUND]) == 0
    assert json.loads(capsys.readouterr().out)["dof"] == 1


def profile_shifted(tmp_path: Path, sun_shift: float) -> str:
    """The bundled 2K-H with sun 22, planet 24, ring 71 at module 2 mm: 46 and 47 mm as
    standard gears; the sun pair's shifts [x_s, 0.2] and the ring pair's [0.2, 0.2] put
    both at 47 mm for x_s + 0.2 = (inv α_w − inv 20°)·46/(2 tan 20°) = 0.53824 with
    cos α_w = 46 cos 20°/47 (x_s = 0.338 as drawn); x_s = 0.3 puts the sun pair at 46.9331 mm."""
    doc = yaml.safe_load(Path(SOUND).read_text())
    doc["components"]["sun"]["teeth"] = 22
    doc["components"]["ring"]["teeth"] = 71
    doc["links"][0]["geometry"] = {"module": 2, "shifts": [sun_shift, 0.2]}
    doc["links"][1]["geometry"] = {"module": 2, "shifts": [0.2, 0.2]}
    path = tmp_path / f"shifted_{sun_shift}.yaml"
    path.write_text(yaml.safe_dump(doc))
    return str(path)


def test_check_strict_takes_a_set_its_shifts_make_coaxial(tmp_path, capsys) -> None:
    model = profile_shifted(tmp_path, 0.338)
    assert main(["check", "--strict", model]) == 0
    out, err = capsys.readouterr()
    assert err == "" and len(out.splitlines()) == 1 and out.startswith(f"{model}: ok")
    assert main(["check", "--strict", profile_shifted(tmp_path, 0.3)]) == 2
    out, err = capsys.readouterr()
    assert out == "" and err.splitlines() == [
        "powergraph: error: links[0..1]: the working centre distances of planet planet's "
        "meshes differ: links[0] 46.9331 mm (shifts 0.3, 0.2); links[1] 47.0000 mm (shifts "
        "0.2, 0.2); 66.9 µm apart, more than 0.001 module = 2 µm: the planets cannot share "
        "the axis of the central gears"]
