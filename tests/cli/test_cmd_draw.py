"""``powergraph draw MODEL -o FILE [--frame ID] [--method M]``: files, exit codes, atomicity."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from powergraph.cli.main import main
from powergraph.testing_trains import with_ids

ROOT = Path(__file__).resolve().parents[2]
RV = str(ROOT / "models" / "rv40e_wang2021.yaml")
KHV = str(ROOT / "models" / "khv_involute.yaml")
MAGIC = {".png": b"\x89PNG\r\n\x1a\n", ".pdf": b"%PDF-"}


def draw(capsys, *argv: str) -> tuple[int, str, str]:
    status = main(["draw", *argv])
    out, err = capsys.readouterr()
    return status, out, err


@pytest.mark.parametrize("suffix", [".png", ".svg", ".pdf"])
def test_writes_each_format(tmp_path, capsys, suffix) -> None:
    target = tmp_path / f"rv{suffix}"
    status, out, err = draw(capsys, RV, "-o", str(target))
    assert status == 0, err
    data = target.read_bytes()
    if suffix == ".svg":
        assert b"<svg" in data[:1000]
    else:
        assert data.startswith(MAGIC[suffix])
    assert "actual powers (ground frame)" in out
    assert [p.name for p in tmp_path.iterdir()] == [target.name]     # no temporary left


def test_frame_draws_the_transformation_train(tmp_path, capsys) -> None:
    status, out, err = draw(capsys, RV, "-o", str(tmp_path / "f3.png"), "--frame", "3")
    assert status == 0, err
    assert "virtual powers seen from 2/3" in out
    status, out, err = draw(capsys, RV, "-o", str(tmp_path / "f0.png"), "--frame", "0")
    assert status == 0 and "actual powers" in out                    # a housing member


def test_unknown_frame_exits_2_without_a_file(tmp_path, capsys) -> None:
    target = tmp_path / "x.png"
    status, _, err = draw(capsys, RV, "-o", str(target), "--frame", "9")
    assert status == 2
    assert "--frame 9: unknown component '9'" in err and "Traceback" not in err
    assert not target.exists()


@pytest.mark.parametrize("argv, message", [
    (["-o", "{tmp}/x.txt"], "the suffix must be one of"),
    (["-o", "{tmp}/missing/x.png"], "does not exist"),
])
def test_bad_output_exits_2(tmp_path, capsys, argv, message) -> None:
    status, _, err = draw(capsys, RV, *[a.format(tmp=tmp_path) for a in argv])
    assert status == 2 and message in err
    assert list(tmp_path.iterdir()) == []


def test_invalid_model_exits_2(tmp_path, capsys) -> None:
    target = tmp_path / "x.png"
    status, _, err = draw(capsys, str(ROOT / "tests" / "data" / "malformed.yaml"),
                          "-o", str(target))
    assert status == 2 and err.startswith("powergraph: error:")
    assert not target.exists()


def test_output_is_required() -> None:
    result = subprocess.run([sys.executable, "-m", "powergraph.cli.main", "draw", RV],
                            capture_output=True, text=True, cwd=ROOT, timeout=60)
    assert result.returncode == 2 and "-o/--output" in result.stderr


def test_wang2021(tmp_path, capsys) -> None:
    pytest.importorskip("powergraph.methods.wang2021")
    target = tmp_path / "w.png"
    status, _, err = draw(capsys, RV, "-o", str(target), "--method", "wang2021")
    assert status == 0, err
    assert target.read_bytes().startswith(MAGIC[".png"])
    status, out, err = draw(capsys, RV, "-o", str(target), "--method", "wang2021",
                            "--frame", "3")
    assert status == 0 and "seen from 2/3" in out
    # a train the paper's method does not describe: exit 2, the reason, no file
    other = tmp_path / "k.png"
    status, _, err = draw(capsys, KHV, "-o", str(other), "--method", "wang2021")
    assert status == 2 and "wang2021" in err and not other.exists()


def test_mesh_efficiency_override(tmp_path, capsys) -> None:
    status, _, err = draw(capsys, RV, "-o", str(tmp_path / "e.png"),
                          "--mesh-efficiency", "0.998")
    assert status == 0, err
    status, _, err = draw(capsys, RV, "-o", str(tmp_path / "bad.png"), "--mesh-efficiency",
                          "1.5")
    assert status == 2 and err.startswith("powergraph: error: --mesh-efficiency 1.5: must be")
    assert not (tmp_path / "bad.png").exists()


def test_failing_writer_leaves_nothing(tmp_path, capsys, monkeypatch) -> None:
    """A writer that dies half-way leaves neither a file nor a temporary, and an
    existing file is left as it was."""
    from matplotlib.figure import Figure

    def half_then_fail(self, path, **kwargs):
        Path(path).write_bytes(b"\x89PNG half")
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(Figure, "savefig", half_then_fail)
    target = tmp_path / "rv.png"
    status, _, err = draw(capsys, RV, "-o", str(target))
    assert status == 1 and "cannot write" in err and "No space left" in err
    assert list(tmp_path.iterdir()) == []
    target.write_bytes(b"old picture")
    status, _, _ = draw(capsys, RV, "-o", str(target))
    assert status == 1
    assert target.read_bytes() == b"old picture"
    assert [p.name for p in tmp_path.iterdir()] == ["rv.png"]


def test_help_lists_draw(capsys) -> None:
    with pytest.raises(SystemExit):
        main(["--help"])
    assert "draw" in capsys.readouterr().out


# --- component ids that spell the tool's own names, and names in other scripts ----------
PLANETARY = ROOT / "models" / "planetary_2kh_sun_to_carrier.yaml"


def renamed_planetary(tmp_path, new: dict[str, str]) -> str:
    """The plain 2K-H (sun in, carrier out) with its ids replaced, written as YAML."""
    import yaml

    text = PLANETARY.read_text()
    data = with_ids(yaml.safe_load(text), new)
    path = tmp_path / "renamed.yaml"
    path.write_text(yaml.safe_dump(data, allow_unicode=True), encoding="utf-8")
    return str(path)


@pytest.mark.parametrize("new", [
    {"sun": "motor"}, {"carrier": "generator"},
    {"sun": "loss", "carrier": "motor", "ring": "generator", "planet": "mesh loss-motor"},
    {"frame": "F", "ring": "R", "carrier": "F/R"},
    {"sun": "$\\frac{$", "planet": "$x^2$"}], ids=["motor", "generator", "all", "slash", "math"])
def test_draws_whatever_the_ids(tmp_path, capsys, new) -> None:
    # these used to end in a traceback (a cycle through "motor", a refused "F/R", a
    # mathtext parse error)
    target = tmp_path / "d.png"
    status, out, err = draw(capsys, renamed_planetary(tmp_path, new), "-o", str(target))
    assert status == 0 and err == ""
    assert target.read_bytes().startswith(MAGIC[".png"])


CJK = {"sun": "太阳轮", "planet": "遊星歯車", "ring": "１２", "carrier": "🚀 carrier"}


def test_names_in_other_scripts_one_line_at_most(tmp_path) -> None:
    # a process of its own: what a user sees on stderr, with or without a CJK font
    target = tmp_path / "cjk.png"
    run = subprocess.run([sys.executable, "-m", "powergraph.cli.main", "draw",
                          renamed_planetary(tmp_path, CJK), "-o", str(target)],
                         capture_output=True, text=True, encoding="utf-8", timeout=120)
    assert run.returncode == 0, run.stderr
    assert len(run.stderr.splitlines()) <= 1 and "Glyph" not in run.stderr
    assert target.read_bytes().startswith(MAGIC[".png"])


def test_names_no_font_can_draw_are_named_once(tmp_path, capsys, monkeypatch) -> None:
    from powergraph.plot import fonts

    monkeypatch.setattr(fonts, "font_families", lambda: ("DejaVu Sans",))
    status, out, err = draw(capsys, renamed_planetary(tmp_path, CJK), "-o",
                            str(tmp_path / "cjk.png"))
    assert status == 0
    (line,) = err.splitlines()
    assert line.startswith("powergraph: warning: no installed font can draw")
    assert all(repr(name) in line for name in ("太阳轮", "遊星歯車", "🚀 carrier"))
    assert "fonts-noto-cjk" in line and "Glyph" not in line


def test_ports_are_labelled_by_their_names(tmp_path, capsys, monkeypatch) -> None:
    """Issue 34: the hybrid's output is "wheels" (not "generator" beside MG1), its input
    "engine"; nothing on the figure says motor or generator."""
    from matplotlib.figure import Figure
    from matplotlib.text import Text

    figures, savefig = [], Figure.savefig
    monkeypatch.setattr(Figure, "savefig",
                        lambda self, *a, **k: (figures.append(self), savefig(self, *a, **k)))
    status, _, err = draw(capsys, str(ROOT / "models" / "ths2_power_split.yaml"),
                          "-o", str(tmp_path / "ths2.png"))
    assert status == 0, err
    shown = {t.get_text() for t in figures[0].findobj(Text)}
    assert {"engine", "wheels", "MG1", "MG2"} <= shown
    assert not any(word in text for text in shown for word in ("motor", "generator"))
