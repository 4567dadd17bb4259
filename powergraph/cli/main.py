"""Entry point of the ``powergraph`` console script.

Exit status: 0 success, 2 invalid model or arguments, 1 anything else. Users never see a
traceback for a bad model or bad arguments, nor a numpy warning: a floating-point problem
during a command (overflow, invalid value) ends it with one clear line instead.
"""
from __future__ import annotations

import argparse
import importlib
import sys
import warnings

from powergraph.cli.common import CommandParser, number_option
from powergraph.errors import ModelError, PowerGraphError, UsageError

#: Command modules, in the order ``--help`` lists them. Each has register() and run().
COMMANDS = ("solve", "check", "draw", "compare", "backlash", "cycloid", "volume", "sweep",
            "formula", "schema", "tolerance", "mesh", "map", "enumerate", "synthesize",
            "modes", "lever", "shifts", "cycle", "import", "export")
_SIZE_SUFFIXES = {"": 1, "k": 10**3, "m": 10**6, "g": 10**9}
#: Largest --max-model-size: a file of a petabyte is no model.
_SIZE_LIMIT = 10**15


def parse_size(text: str, option: str = "--max-model-size") -> int:
    """--max-model-size, --max-table-size: bytes, optionally with k, M or G (powers of
    1000).

    >>> parse_size("20M"), parse_size("1.5k")
    (20000000, 1500)
    """
    number, suffix = (text[:-1], text[-1].lower()) if text[-1:].isalpha() else (text, "")
    if suffix not in _SIZE_SUFFIXES:
        raise UsageError(f"{option} {text}: not a size in bytes (e.g. 20M)")
    scale = _SIZE_SUFFIXES[suffix]
    value = number_option(number, option, 1 / scale, _SIZE_LIMIT / scale)
    return max(1, int(value * scale))


def build_parser(argv: list[str] | None = None) -> argparse.ArgumentParser:
    """The command-line parser. Given the arguments, only the command they name is
    registered (each command module imports what it needs, so ``powergraph solve`` does
    not load the other sixteen); without them, or when they name none, every command is
    (``--help`` lists them all)."""
    parser = CommandParser(
        prog="powergraph",
        description="Power flow, losses and efficiency of gear trains described as graphs.")
    from powergraph import __version__

    parser.add_argument("--version", action="version", version=f"powergraph {__version__}")
    parser.add_argument("--max-model-size", metavar="BYTES",
                        help="refuse model files larger than this (default 10M, or the "
                             "environment variable POWERGRAPH_MAX_MODEL_BYTES)")
    parser.add_argument("--max-table-size", metavar="BYTES",
                        help="refuse table files (points CSV, efficiency maps) larger than "
                             "this (default 100M, or the environment variable "
                             "POWERGRAPH_MAX_TABLE_BYTES)")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True
    named = command_named(argv)
    for name in COMMANDS if named is None else (named,):
        try:
            module = importlib.import_module(f"powergraph.cli.cmd_{name}")
        except ModuleNotFoundError as exc:
            if exc.name != f"powergraph.cli.cmd_{name}":
                raise
            continue  # command not built yet
        module.register(sub)
    return parser


def command_named(argv: list[str] | None) -> str | None:
    """The command ``argv`` names (its first word that is not an option or the value of
    ``--max-model-size``), or None (also when the program's own help is asked for first,
    which lists every command).

    >>> command_named(["--max-model-size", "2M", "solve", "m.yaml"]), command_named(["-h"])
    ('solve', None)
    >>> command_named(["--help", "solve"]), command_named(["solve", "--help"])
    (None, 'solve')
    """
    words = iter(argv or ())
    for word in words:
        if word in ("--max-model-size", "--max-table-size"):
            next(words, None)
        elif word in ("-h", "--help"):
            return None
        elif not word.startswith("-"):
            return word if word in COMMANDS else None
    return None


def main(argv: list[str] | None = None) -> int:
    """Run the command line; returns (and exits with) the status code."""
    parser = build_parser(sys.argv[1:] if argv is None else argv)
    args = parser.parse_args(argv)
    try:
        status = _run(parser, args)
    except (ModelError, UsageError) as exc:
        print(f"powergraph: error: {exc}", file=sys.stderr)
        status = 2
    except PowerGraphError as exc:
        print(f"powergraph: error: {exc}", file=sys.stderr)
        status = 1
    except (FloatingPointError, RuntimeWarning, OverflowError) as exc:
        print(f"powergraph: error: numerical problem ({exc}); the model's numbers are out of "
              "the range this computation can handle", file=sys.stderr)
        status = 1
    except MemoryError:
        print("powergraph: error: out of memory: the model or the requested output is too "
              "large", file=sys.stderr)
        status = 1
    except KeyboardInterrupt:
        print("powergraph: interrupted", file=sys.stderr)
        status = 130
    except BrokenPipeError:
        status = 0
    if argv is None:
        sys.exit(status)
    return status


def _run(parser: argparse.ArgumentParser, args: argparse.Namespace) -> int:
    """Run the command with the model size limit set and numpy warnings turned into errors,
    once no output would overwrite one of its inputs."""
    from powergraph.cli.common import glyph_notices, refuse_overwriting_inputs
    from powergraph.model.input_files import size_limit

    commands = next(a for a in parser._actions if a.dest == "command")
    refuse_overwriting_inputs(commands.choices[args.command], args)
    models, tables = ((None if text is None else parse_size(text, option))
                      for text, option in ((args.max_model_size, "--max-model-size"),
                                           (args.max_table_size, "--max-table-size")))
    with size_limit(models, "model"), size_limit(tables, "table"), \
            warnings.catch_warnings(), glyph_notices():
        warnings.simplefilter("error", RuntimeWarning)
        return args.handler(args)


if __name__ == "__main__":
    main()
