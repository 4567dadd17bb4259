"""The command line run in-process, for the command tests."""
from __future__ import annotations

import io
from contextlib import redirect_stderr, redirect_stdout

import pytest

from powergraph.cli.main import main


def run_main(*argv: str) -> tuple[int, str, str]:
    """``powergraph ARGV`` in-process: (exit status, stdout, stderr); argparse's exits
    count too."""
    out, err = io.StringIO(), io.StringIO()
    with redirect_stdout(out), redirect_stderr(err):
        try:
            status = main(list(argv))
        except SystemExit as exc:
            status = exc.code
    return status, out.getvalue(), err.getvalue()


@pytest.fixture
def cli():
    """:func:`run_main`: ``status, out, err = cli("solve", path)``."""
    return run_main
