"""Every text a figure shows is plain: names with ``$`` are drawn as written (issue 34).

matplotlib reads a string with two ``$`` as mathtext: ``$x^2$`` would be drawn as x²
and ``$\\frac{a$`` would stop the drawing with a parse error. Each figure the command line
writes is made here from models whose model, mode, component, port, machine and
shift-element names are such strings; the figure is caught as it is saved, and every
text showing a name must be that name as written (``get_text()``), neither mathtext nor
TeX. A figure that draws a name as mathtext fails, one whose name is invalid mathtext
fails at the save itself.
"""
from __future__ import annotations

import io
import re
from pathlib import Path

import pytest
import yaml
from matplotlib.figure import Figure
from matplotlib.text import Text

from powergraph.cli.main import main
from powergraph.plot.text import PLAIN, plain
from powergraph.testing_trains import with_ids

ROOT = Path(__file__).resolve().parents[2]
MODELS = ROOT / "models"
BAD = "$\\frac{a$"          # invalid mathtext: a parse error if read as mathtext
MATH = "$x^2$"             # valid mathtext: silently drawn as x² if read as mathtext
NAME = f"{BAD} {MATH}"     # the model names


@pytest.fixture
def saved(monkeypatch) -> list:
    """The figures the command saves (caught at ``Figure.savefig``, then saved)."""
    figures: list = []
    savefig = Figure.savefig

    def catch(self, *args, **kwargs):
        figures.append(self)
        return savefig(self, *args, **kwargs)

    monkeypatch.setattr(Figure, "savefig", catch)
    yield figures
    import matplotlib.pyplot as plt

    plt.close("all")


def write(tmp_path: Path, data: dict, stem: str = "hostile") -> str:
    path = tmp_path / f"{stem}.yaml"
    path.write_text(yaml.safe_dump(data, allow_unicode=True, sort_keys=False),
                    encoding="utf-8")
    return str(path)


def model(name: str) -> dict:
    """The data of ``models/NAME`` renamed :data:`NAME`."""
    return dict(yaml.safe_load((MODELS / name).read_text(encoding="utf-8")), name=NAME)


def simpson() -> dict:
    """Simpson 3-speed: mode "2" is ``$\\frac{a$``, clutch C1 ``$C_1$``, the sun ``s``
    ``$s$``, the input port ``$\\frac{in$``, the output port ``$x^2$ out``."""
    data = with_ids(model("simpson_3speed.yaml"), {"s": "$s$"})
    for link in data["links"]:
        if link.get("name") == "C1":
            link["name"] = "$C_1$"
    data["modes"] = {(BAD if m == "2" else m): ["$C_1$" if e == "C1" else e for e in on]
                     for m, on in data["modes"].items()}
    data["ports"][0]["name"] = "$\\frac{in$"
    data["ports"][1]["name"] = f"{MATH} out"
    return data


def ths2() -> dict:
    """THS-II: the engine port ``$\\frac{e$``, the wheels ``$w$heels``, MG1 ``$MG_1$``,
    the sun ``S`` ``$\\frac{S$``."""
    data = with_ids(model("ths2_power_split.yaml"), {"S": "$\\frac{S$"})
    names = {"engine": "$\\frac{e$", "wheels": "$w$heels", "MG1": "$MG_1$"}
    for port in data["ports"]:
        port["name"] = names.get(port["name"], port["name"])
    return data


def run(capsys, *argv: str) -> None:
    status = main(list(argv))
    err = capsys.readouterr().err
    assert status == 0, err
    assert "Traceback" not in err


def assert_plain(figures: list, *names: str) -> None:
    """Each name is shown by some text of the figures, as written and not parsed; no
    text with a ``$`` is parsed as mathtext or TeX."""
    assert figures, "no figure was saved"
    texts = [t for fig in figures for t in fig.findobj(Text)]
    for text in texts:
        if "$" in text.get_text():
            assert text.get_parse_math() is False, text.get_text()
            assert not text.get_usetex(), text.get_text()
            assert text._preprocess_math(text.get_text()) == (text.get_text(), False)
    for name in names:
        assert any(name in t.get_text() for t in texts), \
            (name, sorted({t.get_text() for t in texts if t.get_text()}))


# --- the figures of the command line ------------------------------------------------------
def test_draw_shows_port_machine_component_and_model_names(tmp_path, capsys, saved) -> None:
    run(capsys, "draw", write(tmp_path, ths2()), "-o", str(tmp_path / "d.png"))
    assert_plain(saved, NAME, "$\\frac{e$", "$w$heels", "$MG_1$", "$\\frac{S$")
    nodes = saved[0].axes[0].powergraph_nodes
    assert nodes["motor"][1].get_text() == "$\\frac{e$"          # the port, not "motor"
    assert nodes["generator"][1].get_text() == "$w$heels"        # ... nor "generator"


def test_draw_of_a_mode_shows_the_mode_name(tmp_path, capsys, saved) -> None:
    run(capsys, "draw", write(tmp_path, simpson()), "--mode", BAD,
        "-o", str(tmp_path / "d.svg"))
    assert_plain(saved, f"{NAME} [{BAD}]", "$\\frac{in$", f"{MATH} out")


def test_modes_gear_table_ticks_are_mode_names(tmp_path, capsys, saved) -> None:
    run(capsys, "modes", write(tmp_path, simpson()), "-o", str(tmp_path / "m.png"))
    assert_plain(saved, NAME)
    ax = saved[0].axes[0]
    ticks = [t for t in ax.get_xticklabels() if t.get_text()]
    assert [t.get_text() for t in ticks] == ["1", BAD, "3", "R"]
    assert ax.get_title().startswith(NAME)


def test_lever_shows_mode_component_and_shift_element_names(tmp_path, capsys,
                                                            saved) -> None:
    run(capsys, "lever", write(tmp_path, simpson()), "--mode", BAD,
        "-o", str(tmp_path / "l.png"))
    assert_plain(saved, f"{NAME} [{BAD}]", "$s$ [", "$C_1$")


def test_cycle_plot_title_is_the_model_name(tmp_path, capsys, saved) -> None:
    points = tmp_path / "points.csv"            # the first points of the urban cycle
    lines = (MODELS / "cycles" / "urban_synthetic.csv").read_text().splitlines()
    points.write_text("\n".join(lines[:5]) + "\n")
    run(capsys, "cycle", write(tmp_path, model("ths2_power_split.yaml")),
        "--points", str(points), "--plot", str(tmp_path / "c.png"))
    assert_plain(saved, f"{NAME}: duty cycle")


def test_compare_ticks_are_model_names(tmp_path, capsys, saved) -> None:
    first = write(tmp_path, model("planetary_2kh_sun_to_carrier.yaml"))
    run(capsys, "compare", first, str(MODELS / "rv40e_wang2021.yaml"),
        "-o", str(tmp_path / "c.png"))
    assert_plain(saved, NAME)


def test_sweep_and_map_titles_are_the_model_name(tmp_path, capsys, saved) -> None:
    path = write(tmp_path, model("planetary_2kh_sun_to_carrier.yaml"))
    run(capsys, "sweep", path, "--set", "links.0.efficiency=0.9:1:3", "--quiet",
        "-o", str(tmp_path / "s.csv"), "--plot", str(tmp_path / "s.png"))
    run(capsys, "map", path, "--torque", "10:100:3", "--speed", "100:1000:2",
        "--rated", "50", "-o", str(tmp_path / "m.png"))
    assert_plain(saved[:1], NAME)
    assert_plain(saved[1:], f"{NAME}: efficiency map")


@pytest.mark.slow
def test_tolerance_titles_are_the_model_name(tmp_path, capsys, saved) -> None:
    run(capsys, "tolerance", write(tmp_path, model("rv40e_tolerances.yaml")),
        "--samples", "200", "--sobol-samples", "64", "--seed", "1",
        "-o", str(tmp_path / "t.png"))
    assert_plain(saved, NAME)


@pytest.mark.slow
def test_backlash_and_volume_show_component_names(tmp_path, capsys, saved) -> None:
    text = (MODELS / "backlash_li2012.yaml").read_text(encoding="utf-8")
    path = tmp_path / "b.yaml"      # R1 renamed everywhere, its backlash block too
    path.write_text(re.sub(r"\bR1\b", '"$R_1$"', text), encoding="utf-8")
    run(capsys, "backlash", str(path), "--plot", str(tmp_path / "b.png"))
    data = model("rv40e.yaml")
    data["components"][1]["name"] = BAD
    run(capsys, "volume", write(tmp_path, data, "v"), "--plot", str(tmp_path / "v.png"))
    assert_plain(saved[:1], "$R_1$")
    assert_plain(saved[1:], f"{BAD} (component 1)")


# --- the library's own figures ----------------------------------------------------------
def test_wang2021_figure_caption_has_the_model_name(tmp_path) -> None:
    import matplotlib.pyplot as plt

    from powergraph.methods.figures import mesh_efficiency_curves
    from powergraph.model import model_from_dict
    from powergraph.plot.wang2021 import add_caption, plot_figure

    data = mesh_efficiency_curves(model_from_dict(model("rv40e_wang2021.yaml")))
    ax = plot_figure(data)
    add_caption(ax.figure, data.caption)
    ax.figure.savefig(tmp_path / "w.png")
    assert_plain([ax.figure], NAME)
    plt.close(ax.figure)


def test_plain_makes_legends_and_texts_plain_and_keeps_the_string() -> None:
    fig = Figure()
    ax = fig.add_subplot()
    ax.plot([0, 1], label=BAD)
    legend = ax.legend(title=MATH)
    title = ax.set_title(MATH)
    assert title.get_parse_math() is True           # matplotlib's default: mathtext
    assert plain(legend, [title]) is legend
    assert [t.get_text() for t in legend.get_texts()] == [BAD]
    assert all(not t.get_parse_math() for t in [*legend.get_texts(), legend.get_title()])
    assert title.get_text() == MATH and not title.get_parse_math()
    assert dict(PLAIN) == {"parse_math": False, "usetex": False}
    fig.savefig(io.BytesIO(), format="png")          # and it draws


def test_log_axis_ticks_keep_matplotlib_mathtext(tmp_path) -> None:
    """The plots' own texts are plain; matplotlib's 10^k tick labels stay mathtext."""
    import numpy as np

    from powergraph.plot.cycloid import plot_fit_comparison

    class Study:                    # what plot_fit_comparison reads, nothing computed
        profile_error = np.array([0.01, 0.1])
        teeth = np.array([20, 40])
        max_deviation_percent = np.array([0.01, 1.0])
        max_deviation_percent_2deg = np.array([0.012, 1.1])
        paper_a = None
        module = 2.0

        def fitted(self, d, z):
            return 10 * d

    ax = plot_fit_comparison(Study(), ax=Figure().add_subplot())
    ax.figure.savefig(tmp_path / "f.png")
    ticks = [t for t in ax.get_xticklabels() if t.get_text()]
    assert ticks and all(t.get_parse_math() and "$" in t.get_text() for t in ticks)
    assert not ax.title.get_parse_math()
