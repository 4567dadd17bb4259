"""Fonts for names in any script: a fallback list, and one notice for what none can draw.

Component ids and names may be Chinese, Japanese, full-width digits or emoji. The
diagrams draw text with a list of families (matplotlib >= 3.6 falls back glyph by glyph):
DejaVu Sans first, then the first CJK and emoji fonts installed among
:data:`FALLBACK_FAMILIES` — only families matplotlib's font manager knows, so no
"font not found" noise. Characters that no font of the list has cannot be drawn (they
come out as empty boxes): instead of matplotlib's warning per glyph, the plot issues one
:class:`GlyphWarning` naming the names concerned and a font package to install; the
command line prints it as one line.

Nothing here imports matplotlib at import time.

Examples
--------
>>> font_families()[0]
'DejaVu Sans'
>>> undrawable(["2/3", "mesh 1-2"])
[]
"""
from __future__ import annotations

import contextlib
import functools
import unicodedata
import warnings
from typing import Iterable, Iterator, Sequence

#: Families tried in this order; only those installed are used.
FALLBACK_FAMILIES = ("DejaVu Sans", "Noto Sans CJK JP", "Noto Sans CJK SC", "Source Han Sans",
                     "Source Han Sans JP", "WenQuanYi Zen Hei", "Droid Sans Fallback",
                     "Noto Color Emoji", "Noto Emoji", "Symbola")
#: matplotlib's per-glyph warning ("Glyph 22826 (...) missing from font(s) DejaVu Sans.").
MATPLOTLIB_GLYPH_WARNING = r"Glyph .* missing from"


class GlyphWarning(UserWarning):
    """Some names have characters that no installed font can draw; ``names`` lists them."""

    def __init__(self, names: Sequence[str]) -> None:
        self.names = tuple(names)
        super().__init__(glyph_notice(self.names))


def glyph_notice(names: Sequence[str]) -> str:
    """The one-line notice for ``names``.

    >>> glyph_notice(["太阳轮"])  # doctest: +ELLIPSIS
    "no installed font can draw '太阳轮' (drawn as empty boxes): install ... fonts-noto-cjk..."
    """
    listed = ", ".join(repr(n) for n in names)
    emoji = any(_is_emoji(c) for n in names for c in n)
    package = "fonts-noto-cjk" + (" and fonts-noto-color-emoji" if emoji else "")
    return (f"no installed font can draw {listed} (drawn as empty boxes): install a font "
            f"with these characters (Debian: {package})")


def _is_emoji(char: str) -> bool:
    return ord(char) >= 0x1F000 or 0x2600 <= ord(char) <= 0x27BF


@functools.lru_cache(maxsize=None)
def font_families() -> tuple[str, ...]:
    """The families of :data:`FALLBACK_FAMILIES` that matplotlib has (DejaVu Sans, which
    matplotlib ships, always first)."""
    from matplotlib import font_manager

    installed = {font.name for font in font_manager.fontManager.ttflist}
    return ("DejaVu Sans",) + tuple(f for f in FALLBACK_FAMILIES[1:] if f in installed)


@functools.lru_cache(maxsize=None)
def _charmap(family: str) -> frozenset[int]:
    from matplotlib import font_manager
    from matplotlib.ft2font import FT2Font

    try:
        path = font_manager.findfont(font_manager.FontProperties(family=family),
                                     fallback_to_default=False)
        return frozenset(FT2Font(path).get_charmap())
    except (ValueError, RuntimeError, OSError):
        return frozenset()


def undrawable(texts: Iterable[str], families: Sequence[str] | None = None) -> list[str]:
    """The texts (once each, in order) with a character none of ``families`` (default
    :func:`font_families`) has; spaces and control characters do not count."""
    families = font_families() if families is None else families
    covered = frozenset().union(*(_charmap(f) for f in families))
    out: list[str] = []
    for text in texts:
        if text in out:
            continue
        if any(ord(c) not in covered for c in text
               if not c.isspace() and unicodedata.category(c)[0] != "C"):
            out.append(text)
    return out


@contextlib.contextmanager
def quiet_glyphs() -> Iterator[None]:
    """Silence matplotlib's per-glyph warnings (the names concerned get a
    :class:`GlyphWarning` of their own)."""
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message=MATPLOTLIB_GLYPH_WARNING)
        yield


@contextlib.contextmanager
def drawing_fonts() -> Iterator[None]:
    """Text created inside uses :func:`font_families`; matplotlib's glyph warnings are
    silenced (the figure's own ``rcParams`` are left as they were outside)."""
    import matplotlib

    with matplotlib.rc_context({"font.family": list(font_families())}), quiet_glyphs():
        yield


def warn_undrawable(texts: Iterable[str], stacklevel: int = 3) -> None:
    """Issue one :class:`GlyphWarning` if some of ``texts`` cannot be drawn."""
    names = undrawable(texts)
    if names:
        warnings.warn(GlyphWarning(names), stacklevel=stacklevel)
