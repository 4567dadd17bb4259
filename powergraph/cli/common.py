"""Helpers shared by the command modules: loading with overrides, JSON and file output."""
from __future__ import annotations

import argparse
import contextlib
import json
import math
import os
import re
import sys
import tempfile
import warnings
from pathlib import Path
from typing import Any, Callable, Iterator, NoReturn

from powergraph.errors import PowerGraphError, UsageError
from powergraph.result import aligned_table  # noqa: F401  (used by the commands)


class CommandParser(argparse.ArgumentParser):
    """argparse's parser, but a mistake in the arguments is one line (no usage block):
    ``powergraph: error: argument --dpi: expected one argument (see powergraph draw -h)``,
    exit status 2, like every other bad argument."""

    def error(self, message: str) -> NoReturn:
        self.exit(2, f"powergraph: error: {message}{_dash_hint(message)} (see {self.prog} -h)\n")


def _dash_hint(message: str) -> str:
    """For an option left without its value, how to give a value that starts with ``-``
    (argparse takes ``--torque -400:400:9`` for two options, but reads
    ``--torque=-400:400:9``).

    >>> _dash_hint("argument -o/--output: expected one argument")
    '; a value that starts with - is written --output=VALUE'
    """
    found = re.fullmatch(r"argument (?:\S+/)?(\S+): expected one argument", message)
    return f"; a value that starts with - is written {found.group(1)}=VALUE" if found else ""


#: A list longer than this is printed one item a line (each item on one line).
LONG_LIST = 100


def print_json(data: Any) -> None:
    """Print one JSON object on stdout (NaN/inf become null: JSON has no such numbers).

    Indented by two spaces, but a list of more than :data:`LONG_LIST` items (a duty
    cycle's rows, a sweep's variants) is written one item a line, each by the standard
    library's compiled encoder: a 10^5-row cycle prints in seconds, not minutes.

    >>> print_json({"a": [1.5, float("nan")], "rows": [{"x": i} for i in range(101)]})
    ... # doctest: +ELLIPSIS
    {
      "a": [
        1.5,
        null
      ],
      "rows": [
        {"x": 0},
        ...
        {"x": 100}
      ]
    }
    """
    for piece in _json_pieces(data, ""):
        sys.stdout.write(piece)
    sys.stdout.write("\n")


def _json_pieces(data: Any, indent: str):
    """The text of ``data`` in pieces: :func:`json.dumps` with ``indent=2`` for what is
    small, a long list's items one a line."""
    if isinstance(data, dict) and _has_long_list(data):
        inner = indent + "  "
        yield "{"
        for i, (key, value) in enumerate(data.items()):
            yield ("," if i else "") + f"\n{inner}{json.dumps(str(key))}: "
            yield from _json_pieces(value, inner)
        yield f"\n{indent}}}" if data else "}"
    elif isinstance(data, (list, tuple)) and len(data) > LONG_LIST:
        yield "["
        for i, item in enumerate(data):
            yield ("," if i else "") + f"\n{indent}  {_compact(item)}"
        yield f"\n{indent}]"
    else:
        text = json.dumps(_finite(data), indent=2, allow_nan=False)
        yield text.replace("\n", "\n" + indent) if indent else text


def _has_long_list(data: Any) -> bool:
    if isinstance(data, dict):
        return any(_has_long_list(v) for v in data.values())
    return isinstance(data, (list, tuple)) and len(data) > LONG_LIST


def _compact(item: Any) -> str:
    """One item on one line (``{"x": 0}``), NaN and inf as null."""
    try:
        return json.dumps(item, allow_nan=False)
    except ValueError:                   # a NaN or an infinity somewhere inside
        return json.dumps(_finite(item), allow_nan=False)


def _finite(data: Any) -> Any:
    if isinstance(data, float):
        return data if math.isfinite(data) else None
    if isinstance(data, dict):
        return {str(k): _finite(v) for k, v in data.items()}
    if isinstance(data, (list, tuple)):
        return [_finite(v) for v in data]
    return data


def load(path: str, mesh_efficiency: str | None = None):
    """Load a model file, applying the text of ``--mesh-efficiency`` if given (checked
    first: a bad value fails before the file is read)."""
    from powergraph.model import load_model

    if mesh_efficiency is None:
        return load_model(path)
    efficiency = efficiency_option(mesh_efficiency)
    return load_model(path).with_mesh_efficiency(efficiency)


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
#: Characters of the target's name kept in the name of its temporary file.
_TEMP_STEM = 40


def check_output_file(path: str, option: str, suffixes: tuple[str, ...] = ()) -> Path:
    """Refuse, before any work, a file that the command could not write.

    The folder must exist and take a new file (the check creates and removes the very
    temporary file :func:`write_atomically` will use); the path must not be a folder;
    its suffix, if ``suffixes`` are given, one of them. Otherwise a
    :class:`~powergraph.errors.UsageError` naming ``option`` (exit 2).

    >>> check_output_file("out.csv", "-o").name
    'out.csv'
    >>> check_output_file("no/such/folder/out.csv", "-o")
    Traceback (most recent call last):
    ...
    powergraph.errors.UsageError: -o: folder 'no/such/folder' does not exist
    """
    if not path.strip() or "\x00" in path:
        raise UsageError(f"{option}: {path!r} is not a file name")
    target = Path(path)
    if suffixes and target.suffix.lower() not in suffixes:
        raise UsageError(f"{option}: the suffix must be one of {', '.join(suffixes)} "
                         f"(got {path!r})")
    if os.path.isdir(target) or path.endswith(("/", os.sep)) or target.name in ("", ".", ".."):
        raise UsageError(f"{option}: {path!r} is a folder, not a file")
    _check_folder(target.parent, option, target.name)
    return target


def writes_a_file(action: argparse.Action) -> bool:
    """Whether an option names a file or folder the command writes (its metavar says
    FILE or DIR: every writing option is named so)."""
    metavar = str(action.metavar or "")
    return bool(action.option_strings) and ("FILE" in metavar or "DIR" in metavar)


def refuse_overwriting_inputs(parser: argparse.ArgumentParser,
                              args: argparse.Namespace) -> None:
    """Refuse, before any work, an output that is one of the command's own input files
    (the model, a points table): writing it would destroy what was read.

    A :class:`~powergraph.errors.UsageError` naming the option (exit 2). A ``MODEL:MODE``
    argument counts as its file.
    """
    outputs, inputs = [], []
    for action in parser._actions:
        value = getattr(args, action.dest, None)
        strings = [v for v in (value if isinstance(value, list) else [value])
                   if isinstance(v, str)]
        if writes_a_file(action):
            outputs += [(action.option_strings[0], v) for v in strings]
        else:
            inputs += strings
    for option, path in outputs:
        for given in inputs:
            for candidate in {given, given.rpartition(":")[0]} - {""}:
                if _same_file(path, candidate):
                    raise UsageError(f"{option}: {path!r} is the input file {candidate!r}; "
                                     "writing it would overwrite the input")


def _same_file(path: str, other: str) -> bool:
    try:
        return os.path.isfile(path) and os.path.isfile(other) and os.path.samefile(path, other)
    except (OSError, ValueError):
        return False


def check_figure_path(path: str, option: str = "-o") -> Path:
    """:func:`check_output_file` for a figure: .png, .svg or .pdf."""
    return check_output_file(path, option, FIGURE_SUFFIXES)


def check_output_folder(path: str, option: str) -> Path:
    """A folder the command may write files into: an existing folder, or a new one
    whose parent folder exists (created by the writer, not here). Otherwise a
    :class:`~powergraph.errors.UsageError` naming ``option`` (exit 2).

    >>> check_output_folder(".", "-o").is_dir()
    True
    """
    if not path.strip() or "\x00" in path:
        raise UsageError(f"{option}: {path!r} is not a folder name")
    folder = Path(path)
    exists = os.path.lexists(folder)   # os.path never raises (a name too long...)
    if exists and not os.path.isdir(folder):
        raise UsageError(f"{option}: {path!r} exists and is not a folder")
    _check_folder(folder if exists else folder.parent, option, "x.yaml")
    return folder


def _check_folder(folder: Path, option: str, name: str) -> None:
    """``folder`` exists, is a folder and takes the temporary file of ``name``."""
    shown = str(folder)
    if not os.path.exists(folder):
        raise UsageError(f"{option}: folder {shown!r} does not exist")
    if not os.path.isdir(folder):
        raise UsageError(f"{option}: {shown!r} is not a folder")
    try:
        limit = os.pathconf(folder, "PC_NAME_MAX")
    except (OSError, ValueError, AttributeError):
        limit = 255
    if len(os.fsencode(name)) > limit:
        raise UsageError(f"{option}: the file name is longer than {limit} bytes")
    try:
        os.unlink(_temporary_file(folder / name))
    except OSError as exc:
        raise UsageError(f"{option}: cannot write in folder {shown!r}: "
                         f"{exc.strerror or exc}") from None


def _temporary_file(target: Path) -> str:
    """A new empty file beside ``target``, of the same suffix (closed; the caller owns it)."""
    fd, tmp = tempfile.mkstemp(prefix=f".{target.stem[:_TEMP_STEM]}.", suffix=target.suffix,
                               dir=target.parent)
    os.close(fd)
    return tmp


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
    (matplotlib's ``savefig``) still work. A file system error (disk full, folder gone)
    is a :class:`~powergraph.errors.PowerGraphError` naming the file (exit 1).
    """
    target = Path(path)
    try:
        tmp = _temporary_file(target)
    except OSError as exc:
        raise PowerGraphError(f"cannot write {str(target)!r}: {exc.strerror or exc}") from None
    try:
        write(tmp)
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)  # mkstemp makes 0600; a figure is an ordinary file
        os.replace(tmp, target)
    except OSError as exc:
        _remove(tmp)
        raise PowerGraphError(f"cannot write {str(target)!r}: {exc.strerror or exc}") from None
    except BaseException:
        _remove(tmp)
        raise


def write_text_atomically(path: str | Path, text: str) -> None:
    """Write ``text`` (UTF-8, ``\\n`` line ends) to ``path`` by :func:`write_atomically`."""
    def write(tmp: str) -> None:
        with open(tmp, "w", encoding="utf-8", newline="\n") as handle:
            handle.write(text)

    write_atomically(path, write)


def _remove(path: str) -> None:
    if os.path.exists(path):
        os.unlink(path)

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
    cores = os.cpu_count() or 1
    if workers is not None and workers > cores:
        print(f"warning: --workers {workers} on a machine with {cores} cores: the workers "
              f"share them, no faster than {cores}", file=sys.stderr)
    if args.scheduler:
        from powergraph.analyses.parallel import scheduler_address

        scheduler_address(args.scheduler)   # a bad address fails before any work
    return {"workers": workers, "scheduler": args.scheduler}


def add_oil_temperature(parser: argparse.ArgumentParser, span: bool = False) -> None:
    """``--oil-temperature T``: the oil at T degC, the model's heat balance set aside."""
    parser.add_argument("--oil-temperature", metavar="A:B:N" if span else "T",
                        help="the oil temperature, degC (the model's lubricant: block; its "
                             "heat balance set aside)" + ("; A:B:N for one map per "
                                                           "temperature" if span else ""))


def oil_temperature(text: str, option: str = "--oil-temperature") -> float:
    """The kelvin of a ``--oil-temperature`` in degC (-60 to 300)."""
    return number_option(text, option, -60.0, 300.0) + 273.15


def number_option(text: str, option: str, low: float | None = None,
                  high: float | None = None, *, above: bool = False,
                  below: bool = False) -> float:
    """The finite number given to ``option``, from ``low`` to ``high`` (above ``low`` with
    ``above=True``, below ``high`` with ``below=True``); otherwise a :class:`~powergraph.errors.UsageError` naming the option
    (exit 2). ASCII decimal text only (``2.5``, ``-1e3``), and no subnormal number (0 <
    \\|x\\| < 2.2e-308): nothing the commands compute with is that small, and dividing by
    one overflows.

    >>> number_option("2.5", "--ratio")
    2.5
    >>> number_option("1e-320", "--error")
    Traceback (most recent call last):
    ...
    powergraph.errors.UsageError: --error 1e-320: too close to zero (a subnormal number)
    """
    shown = _shown(text)
    try:
        if not text.isascii():
            raise ValueError(text)
        value = float(text)
    except ValueError:
        raise UsageError(f"{option} {shown}: not a number") from None
    if not math.isfinite(value):
        raise UsageError(f"{option} {shown}: must be finite")
    if value != 0 and abs(value) < sys.float_info.min:
        raise UsageError(f"{option} {shown}: too close to zero (a subnormal number)")
    too_low = low is not None and (value <= low if above else value < low)
    too_high = high is not None and (value >= high if below else value > high)
    if too_low or too_high:
        raise UsageError(f"{option} {shown}: must be {_range(low, high, above, below)}")
    return value


def whole_option(text: str, option: str, low: int, high: int) -> int:
    """A whole number from ``low`` to ``high`` given to ``option`` (exit 2 otherwise):
    digits (read exactly, however large) or a number such as ``1e6``.

    >>> whole_option("4", "--workers", 1, 1024), whole_option("1e3", "--top", 1, 1000)
    (4, 1000)
    """
    digits = text.strip()
    if re.fullmatch(r"[+-]?[0-9]{1,40}", digits):
        value: float = int(digits)
    else:
        try:
            value = number_option(text, option)
        except UsageError:
            value = math.nan
    if not float(value).is_integer() or not low <= value <= high:
        raise UsageError(f"{option} {_shown(text)}: must be a whole number from {low} to {high}")
    return int(value)


#: Range of a basic mesh efficiency given on the command line: below 1e-6 the losses
#: of a train of a few meshes leave the floating-point range.
EFFICIENCY_RANGE = (1e-6, 1.0)


def efficiency_option(text: str, option: str = "--mesh-efficiency") -> float:
    """A basic mesh efficiency from 1e-6 to 1 given to ``option`` (exit 2 otherwise).

    >>> efficiency_option("0.98")
    0.98
    """
    return number_option(text, option, *EFFICIENCY_RANGE)


def _range(low: float | None, high: float | None, above: bool, below: bool) -> str:
    bounds = ([f"{'above' if above else 'at least'} {low:g}"] if low is not None else []) + \
             ([f"{'below' if below else 'at most'} {high:g}"] if high is not None else [])
    return " and ".join(bounds)


def _shown(text: str, limit: int = 40) -> str:
    """``text`` as typed if short and plain, else its ``repr`` cut to ``limit`` characters."""
    if text and text.isprintable() and text.strip() == text and len(text) <= limit:
        return text
    return repr(text) if len(text) <= limit else repr(text[:limit]) + "..."
