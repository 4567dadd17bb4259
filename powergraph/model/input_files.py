"""Every file a command reads, read in bounded time and memory.

Two kinds of input file have a size limit each (:data:`KINDS`): **model** files (YAML, 10 MB
unless ``POWERGRAPH_MAX_MODEL_BYTES`` or ``powergraph --max-model-size`` says otherwise) and
**tables** (a duty cycle's points CSV, a machine's efficiency map: 100 MB unless
``POWERGRAPH_MAX_TABLE_BYTES`` or ``powergraph --max-table-size`` says otherwise). A regular
file over its limit is refused by its size before a byte is read; a device or a pipe
(``/dev/zero``) is read only up to the limit, so no input can fill the memory.

Tables are UTF-8 text; a leading byte-order mark (what Excel's "CSV UTF-8" writes) is
skipped. Any other encoding (Latin-1, as Excel on Windows saves a plain "CSV") is one
error naming the file and the first byte that is not UTF-8, with its line and column.

Examples
--------
>>> decode_text(b"\\xef\\xbb\\xbfspeed [rpm]\\n", "points.csv")
'speed [rpm]\\n'
>>> decode_text(b"a,b\\nn\\xe9,1\\n", "points.csv")
Traceback (most recent call last):
...
powergraph.errors.UsageError: points.csv: not UTF-8 text: byte 0xe9 at byte 5 (line 2, \
column 2); save the file as UTF-8 (Excel: "CSV UTF-8")
"""
from __future__ import annotations

import os
import stat
from pathlib import Path
from typing import Any, NamedTuple

from powergraph.errors import ModelError, PowerGraphError, UsageError


class Kind(NamedTuple):
    """A kind of input file: its default size limit (bytes), the environment variable and
    command-line option that change it, and the error class its problems raise."""

    default: int
    variable: str
    option: str
    error: type[PowerGraphError]


#: The kinds of input file and their limits.
KINDS = {
    "model": Kind(10_000_000, "POWERGRAPH_MAX_MODEL_BYTES", "--max-model-size", ModelError),
    "table": Kind(100_000_000, "POWERGRAPH_MAX_TABLE_BYTES", "--max-table-size", UsageError),
}
_override: dict[str, list[int]] = {kind: [] for kind in KINDS}


def max_bytes(kind: str) -> int:
    """The size limit of one kind of input file, in bytes: the command-line option's, then
    the environment variable's, then the default.

    >>> max_bytes("table") > max_bytes("model") > 0
    True
    """
    if _override[kind]:
        return _override[kind][-1]
    spec = KINDS[kind]
    text = os.environ.get(spec.variable)
    if text is None:
        return spec.default
    try:
        value = int(text)
    except ValueError:
        raise spec.error(f"{spec.variable}={text!r} is not a whole number of bytes") from None
    if value < 1:
        raise spec.error(f"{spec.variable} must be at least 1, got {value}")
    return value


class size_limit:
    """Context manager setting the size limit of one kind of input file (the command
    line's ``--max-model-size`` and ``--max-table-size``); ``None`` leaves it as it is."""

    def __init__(self, limit: int | None, kind: str = "model") -> None:
        self.limit, self.kind = limit, kind

    def __enter__(self) -> None:
        if self.limit is not None:
            _override[self.kind].append(self.limit)

    def __exit__(self, *exc: object) -> None:
        if self.limit is not None:
            _override[self.kind].pop()


def brief(value: Any, limit: int = 60) -> str:
    """``repr(value)`` cut to ``limit`` characters, for messages about hostile values.

    >>> brief("x" * 100)[-20:]
    '... (102 characters)'
    >>> len(brief("x" * 100))
    76
    """
    try:
        text = repr(value)
    except ValueError:  # an integer too long for str()
        return f"an integer of {value.bit_length()} bits"
    return text if len(text) <= limit else f"{text[:limit - 4]}... ({len(text)} characters)"


def read_bytes(path: str | Path, kind: str, what: str) -> bytes:
    """The bytes of an input file of ``kind``, refusing one over its size limit.

    ``what`` names the file in messages (``a model file``, ``the points``). A missing file,
    a folder, an unreadable file or one over the limit is one error of the kind's class
    (:class:`ModelError` for models, :class:`UsageError` for tables).
    """
    spec, limit = KINDS[kind], max_bytes(kind)
    path = os.fspath(path)      # as written: Path() would drop a trailing slash
    if "\0" in path:
        raise spec.error(f"{brief(path)} is not a file name (it holds a NUL character)")
    try:
        with open(path, "rb") as handle:
            info = os.fstat(handle.fileno())
            if stat.S_ISDIR(info.st_mode):
                raise IsADirectoryError
            if stat.S_ISREG(info.st_mode) and info.st_size > limit:
                raise spec.error(_too_large(path, what, info.st_size, limit, spec))
            data = _read_text_bytes(handle, limit, spec.error, path)
    except FileNotFoundError:
        raise spec.error(f"no such file: {path}") from None
    except IsADirectoryError:
        raise spec.error(f"{path} is a directory, not {what}") from None
    except OSError as exc:
        raise spec.error(f"cannot read {path}: {exc.strerror or exc}") from None
    if len(data) > limit:
        raise spec.error(_too_large(path, what, None, limit, spec))
    return data


#: Bytes read at a time: a small file costs no buffer of the whole limit.
CHUNK = 1 << 20


def _read_text_bytes(handle, limit: int, error: type[PowerGraphError], source: str) -> bytes:
    """At most ``limit + 1`` bytes of ``handle``, read in chunks; a NUL byte ends the
    reading at once with an error (no input file is binary: ``/dev/zero`` stops in its
    first chunk)."""
    chunks, size = [], 0
    while size <= limit:
        chunk = handle.read(min(CHUNK, limit + 1 - size))
        if not chunk:
            break
        nul = chunk.find(b"\0")
        if nul >= 0:
            offset = size + nul
            raise error(f"{source}: a NUL byte (U+0000) at byte {offset} "
                        f"({place(b''.join(chunks) + chunk, offset)}): not a text file")
        chunks.append(chunk)
        size += len(chunk)
    return b"".join(chunks)


def _too_large(path: str, what: str, size: int | None, limit: int, spec: Kind) -> str:
    found = f"{size} bytes" if size is not None else "more than that"
    return (f"{path} is too large for {what} ({found}; the limit is {limit} bytes: raise it "
            f"with {spec.option} or {spec.variable})")


def place(data: bytes, offset: int) -> str:
    """``line L, column C`` of byte ``offset`` of ``data`` (columns in characters).

    >>> place(b"ab\\ncd", 4)
    'line 2, column 2'
    """
    start = data.rfind(b"\n", 0, offset) + 1
    column = len(data[start:offset].decode("utf-8", errors="replace")) + 1
    line = data.count(b"\n", 0, offset) + 1
    return f"line {line}, column {column}"


def decode_text(data: bytes, source: str) -> str:
    """``data`` as UTF-8 text, a leading byte-order mark skipped; otherwise a
    :class:`UsageError` naming ``source`` and the first byte that is not UTF-8."""
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        start = exc.start + (3 if data.startswith(b"\xef\xbb\xbf") else 0)
        raise UsageError(f"{source}: not UTF-8 text: byte 0x{data[start]:02x} at byte "
                         f"{start} ({place(data, start)}); save the file as UTF-8 (Excel: "
                         '"CSV UTF-8")') from None


def read_table_text(path: str | Path, what: str) -> str:
    """The text of a table file (a points CSV, an efficiency map), bounded and decoded as
    :func:`decode_text` says."""
    return decode_text(read_bytes(path, "table", what), str(path))


#: The file names read as REXS gear units (docs/exchange.md) wherever a model is taken.
REXS_SUFFIXES = (".rexs", ".rexsj")


def is_rexs_path(path: str | Path) -> bool:
    """True for a ``.rexs`` or ``.rexsj`` file name.

    >>> is_rexs_path("unit.REXS"), is_rexs_path("unit.yaml")
    (True, False)
    """
    return Path(path).suffix.lower() in REXS_SUFFIXES
