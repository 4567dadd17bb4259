"""Entry point of the ``powergraph`` console script.

Exit status (SPEC §2): 0 success, 2 invalid model or arguments, 1 anything else.
Users never see a traceback for a bad model or bad arguments.
"""
from __future__ import annotations

import argparse
import importlib
import sys

from powergraph.errors import ModelError, PowerGraphError, UsageError

#: Command modules, in the order ``--help`` lists them. Each has register() and run().
COMMANDS = ("solve", "check", "draw", "compare", "backlash", "cycloid", "volume", "sweep",
            "formula", "tolerance", "mesh", "map")


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="powergraph",
        description="Power flow, losses and efficiency of gear trains described as graphs.")
    from powergraph import __version__

    parser.add_argument("--version", action="version", version=f"powergraph {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True
    for name in COMMANDS:
        try:
            module = importlib.import_module(f"powergraph.cli.cmd_{name}")
        except ModuleNotFoundError as exc:
            if exc.name != f"powergraph.cli.cmd_{name}":
                raise
            continue  # command not built yet
        module.register(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Run the command line; returns (and exits with) the status code."""
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        status = args.handler(args)
    except (ModelError, UsageError) as exc:
        print(f"powergraph: error: {exc}", file=sys.stderr)
        status = 2
    except PowerGraphError as exc:
        print(f"powergraph: error: {exc}", file=sys.stderr)
        status = 1
    except KeyboardInterrupt:
        print("powergraph: interrupted", file=sys.stderr)
        status = 130
    except BrokenPipeError:
        status = 0
    if argv is None:
        sys.exit(status)
    return status


if __name__ == "__main__":
    main()
