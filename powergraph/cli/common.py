"""Helpers shared by the command modules: loading with overrides, JSON and file output."""
from __future__ import annotations

import argparse
import contextlib
import json
import math
import os
import sys
import tempfile
import warnings
from pathlib import Path
from typing import Any, Callable, Iterator

from powergraph.errors import UsageError
from powergraph.result import aligned_table  # noqa: F401  (used by the commands)


def print_json(data: Any) -> None:
    """Print one JSON object on stdout (NaN/inf become null: JSON has no such numbers)."""
    json.dump(_finite(data), sys.stdout, indent=2, allow_nan=False)
    sys.stdout.write("\n")


def _finite(data: Any) -> Any:
    if isinstance(data, float):
        return data if math.isfinite(data) else None
    if isinstance(data, dict):
        return {str(k): _finite(v) for k, v in data.items()}
    if isinstance(data, (list, tuple)):
        return [_finite(v) for v in data]
    return data


def efficiency_arg(text: str) -> float:
    """argparse type for a basic mesh efficiency in (0, 1]."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number: {text!r}") from None
    if not (0.0 < value <= 1.0):
        raise argparse.ArgumentTypeError(f"must be in (0, 1], got {text}")
    return value


def load(path: str, mesh_efficiency: float | None = None):
    """Load a model file, applying ``--mesh-efficiency`` if given."""
    from powergraph.model import load_model

    model = load_model(path)
    return model.with_mesh_efficiency(mesh_efficiency) if mesh_efficiency is not None else model


def add_strict(parser: argparse.ArgumentParser) -> None:
    """The ``--strict`` option: the model's caveats (``Model.warnings``) become errors."""
    parser.add_argument("--strict", action="store_true",
                        help="treat the model's warnings (docs/feasibility.md) as errors: "
                             "exit 2 with one line per warning")


def refuse_caveats(caveats: Any) -> int:
    """``--strict``: print each caveat as ``powergraph: error: PATH: MESSAGE`` on stderr;
    the exit status, 2 if there was any, else 0."""
    for caveat in caveats:
        print(f"powergraph: error: {caveat}", file=sys.stderr)
    return 2 if caveats else 0


def print_caveats(caveats: Any) -> None:
    """Each caveat as ``warning: PATH: MESSAGE`` on stdout."""
    for caveat in caveats:
        print(f"warning: {caveat}")


FIGURE_SUFFIXES = (".png", ".svg", ".pdf")


def check_figure_path(path: str, option: str = "-o") -> Path:
    """A figure path must end in .png, .svg or .pdf and its folder must exist."""
    target = Path(path)
    if target.suffix.lower() not in FIGURE_SUFFIXES:
        raise UsageError(f"{option} {path}: the suffix must be one of "
                         f"{', '.join(FIGURE_SUFFIXES)}")
    if not target.parent.exists():
        raise UsageError(f"{option} {path}: folder {str(target.parent)!r} does not exist")
    return target


def say_wrote(path: str | Path, detail: str = "", data_on_stdout: bool = False) -> None:
    """Tell the user a file was written: ``wrote PATH`` (and ``detail``) on stdout, or on
    stderr when stdout carries data (``--json``, a CSV) that the line would spoil.

    >>> say_wrote("flow.png", "(actual powers)")
    wrote flow.png (actual powers)
    """
    text = f"wrote {path}" + (f" {detail}" if detail else "")
    print(text, file=sys.stderr if data_on_stdout else sys.stdout)


def write_atomically(path: str | Path, write: Callable[[str], None]) -> None:
    """Call ``write(tmp_path)`` then rename onto ``path``: never a half-written file.

    The temporary file has the same suffix, so writers that pick a format by suffix
    (matplotlib's ``savefig``) still work.
    """
    target = Path(path)
    fd, tmp = tempfile.mkstemp(prefix=f".{target.stem}.", suffix=target.suffix,
                               dir=target.parent or ".")
    os.close(fd)
    try:
        write(tmp)
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)  # mkstemp makes 0600; a figure is an ordinary file
        os.replace(tmp, target)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


# --- figures: the command line writes files with matplotlib's object-oriented API -------
def new_figure(figsize: tuple[float, float] = (6.4, 4.8)):
    """A :class:`matplotlib.figure.Figure` not registered with pyplot.

    The command line only writes files, so it needs no interactive backend and chooses
    none: ``Figure.savefig`` picks the writer from the file's suffix.
    """
    import matplotlib
    from matplotlib.figure import Figure

    from powergraph.plot.fonts import font_families

    # the command line is the application: its figures draw names in any script
    matplotlib.rcParams["font.family"] = list(font_families())
    return Figure(figsize=figsize)


def new_axes(figsize: tuple[float, float] = (6.4, 4.8), projection: str | None = None):
    """One axes on a :func:`new_figure`."""
    return new_figure(figsize).add_subplot(projection=projection)


def save_figure(figure, target: str | Path, **savefig: Any) -> None:
    """Write ``figure`` to ``target`` atomically (``savefig`` keywords passed on).

    matplotlib's warnings per missing glyph are silenced; the lines of text that cannot
    be drawn give one :class:`~powergraph.plot.fonts.GlyphWarning` instead (unless the
    plot already checked its names: a power-flow diagram), which :func:`glyph_notices`
    prints as one line.
    """
    from matplotlib.text import Text

    from powergraph.plot.fonts import quiet_glyphs, warn_undrawable

    if not any(hasattr(ax, "powergraph_undrawable") for ax in figure.axes):
        warn_undrawable([line for text in figure.findobj(Text)
                         for line in text.get_text().splitlines()])
    with quiet_glyphs():
        write_atomically(target, lambda tmp: figure.savefig(tmp, **savefig))


@contextlib.contextmanager
def glyph_notices() -> Iterator[None]:
    """Collect the :class:`~powergraph.plot.fonts.GlyphWarning` of a command and print
    them, merged, as one line on stderr at its end; other warnings pass through."""
    names: list[str] = []
    shown = warnings.showwarning

    def show(message, category, *args, **kwargs):
        if getattr(category, "__name__", "") == "GlyphWarning" and hasattr(message, "names"):
            names.extend(n for n in message.names if n not in names)
        else:
            shown(message, category, *args, **kwargs)

    with warnings.catch_warnings():
        warnings.showwarning = show
        warnings.filterwarnings("always", message="no installed font can draw")
        try:
            yield
        finally:
            if names:
                from powergraph.plot.fonts import glyph_notice

                print(f"powergraph: warning: {glyph_notice(names)}", file=sys.stderr)


def add_cluster_arguments(parser: Any) -> None:
    """``--workers N | --scheduler dask://ADDRESS`` (docs/synthesis.md, docs/sweep.md)."""
    where = parser.add_mutually_exclusive_group()
    where.add_argument("--workers", metavar="N",
                       help="run on a local Dask cluster of N worker processes")
    where.add_argument("--scheduler", metavar="dask://ADDRESS",
                       help="run on the Dask cluster of this scheduler")


def cluster_options(args: Any) -> dict[str, Any]:
    """``{"workers": N or None, "scheduler": address or None}`` from the parsed options;
    a bad number or address is a :class:`~powergraph.errors.UsageError` (exit 2)."""
    workers = None if args.workers is None else whole_option(args.workers, "--workers", 1, 1024)
    if args.scheduler:
        from powergraph.analyses.parallel import scheduler_address

        scheduler_address(args.scheduler)   # a bad address fails before any work
    return {"workers": workers, "scheduler": args.scheduler}


def number_option(text: str, option: str) -> float:
    """A finite number given to ``option``; otherwise a
    :class:`~powergraph.errors.UsageError` naming the option (exit 2).

    >>> number_option("2.5", "--ratio")
    2.5
    """
    try:
        value = float(text)
    except ValueError:
        raise UsageError(f"{option} {text}: not a number") from None
    if not math.isfinite(value):
        raise UsageError(f"{option} {text}: must be finite")
    return value


def whole_option(text: str, option: str, low: int, high: int) -> int:
    """A whole number from ``low`` to ``high`` given to ``option`` (exit 2 otherwise).

    >>> whole_option("4", "--workers", 1, 1024)
    4
    """
    value = number_option(text, option)
    if not value.is_integer() or not low <= value <= high:
        raise UsageError(f"{option} {text}: must be a whole number from {low} to {high}")
    return int(value)
