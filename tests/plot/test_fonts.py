"""Names in other scripts: the font fallback list and the one notice (powergraph.plot.fonts).

No CJK or emoji font is needed: the tests make "no fallback font installed" explicit with
monkeypatch, and only check what holds with or without one.
"""
from __future__ import annotations

import warnings
from pathlib import Path

import matplotlib
import yaml

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from powergraph.model import model_from_dict  # noqa: E402
from powergraph.plot import fonts  # noqa: E402
from powergraph.plot.power_flow import plot_power_flow  # noqa: E402
from powergraph.testing import assert_conservation  # noqa: E402
from powergraph.testing_trains import with_ids  # noqa: E402

PLAIN = (Path(__file__).resolve().parents[2] / "models" / "planetary_2kh_sun_to_carrier.yaml")
SCRIPTS = {"sun": "太阳轮", "planet": "遊星歯車", "ring": "１２", "carrier": "🚀 carrier"}


def no_fallback(monkeypatch) -> None:
    """As on a machine with only the fonts matplotlib ships."""
    monkeypatch.setattr(fonts, "font_families", lambda: ("DejaVu Sans",))


def solve(new: dict[str, str]):
    """The plain 2K-H with components renamed (``new``: old id -> new id)."""
    import powergraph as pg

    text = PLAIN.read_text()
    data = with_ids(yaml.safe_load(text), new)
    result = pg.solve(model_from_dict(data))
    assert_conservation(result)
    return result


def test_families_are_installed_ones_dejavu_first() -> None:
    from matplotlib import font_manager

    installed = {f.name for f in font_manager.fontManager.ttflist}
    families = fonts.font_families()
    assert families[0] == "DejaVu Sans"
    assert set(families) <= installed
    assert list(families) == [f for f in fonts.FALLBACK_FAMILIES if f in families]


def test_undrawable_with_dejavu_only() -> None:
    names = ["2/3", "mesh 1-2", "Zahnrad ü", "Ω planet", "太阳轮", "１２", "🚀 carrier", "太阳轮"]
    assert fonts.undrawable(names, ("DejaVu Sans",)) == ["太阳轮", "１２", "🚀 carrier"]


def test_notice_names_the_names_and_the_package() -> None:
    text = fonts.glyph_notice(["太阳轮", "🚀"])
    assert "'太阳轮', '🚀'" in text and "fonts-noto-cjk" in text
    assert "fonts-noto-color-emoji" in text and "\n" not in text


def test_one_warning_of_our_own_and_none_from_matplotlib(monkeypatch) -> None:
    no_fallback(monkeypatch)
    result = solve(SCRIPTS)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        ax = plot_power_flow(result)          # measures every text with the renderer
    plt.close(ax.figure)
    ours = [w for w in caught if issubclass(w.category, fonts.GlyphWarning)]
    assert len(ours) == 1
    assert {"太阳轮", "遊星歯車", "🚀 carrier"} <= set(ours[0].message.names)
    assert "2/3" not in ours[0].message.names
    assert set(ax.powergraph_undrawable) == set(ours[0].message.names)
    assert not [w for w in caught if "Glyph" in str(w.message)]   # none per glyph


def test_plain_names_give_no_notice() -> None:
    result = solve({})
    with warnings.catch_warnings():
        warnings.simplefilter("error", fonts.GlyphWarning)
        ax = plot_power_flow(result)
    assert ax.powergraph_undrawable == ()
    plt.close(ax.figure)


def test_names_are_text_not_mathtext() -> None:
    # "$...$" in a name is drawn as written (it used to be parsed as mathtext, and
    # an invalid formula ended the drawing with a parse error)
    result = solve({"sun": "$\\frac{$", "planet": "$x^2$"})
    ax = plot_power_flow(result)
    ax.figure.canvas.draw()
    texts = {t.get_text() for t in ax.texts}
    assert "$\\frac{$" in texts and "$x^2$" in texts
    plt.close(ax.figure)
