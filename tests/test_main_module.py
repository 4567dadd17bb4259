"""``python -m powergraph`` runs the command line (powergraph/__main__.py)."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.slow  # a fresh interpreter
def test_python_m_powergraph_runs_the_command_line() -> None:
    done = subprocess.run([sys.executable, "-m", "powergraph", "check", "models/rv40e.yaml"],
                          cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert "ok" in done.stdout and "RV-40E" in done.stdout


@pytest.mark.slow  # a fresh interpreter
def test_python_m_powergraph_exits_2_on_a_bad_model() -> None:
    done = subprocess.run([sys.executable, "-m", "powergraph", "check", "no/such/file.yaml"],
                          cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert done.returncode == 2
    assert done.stderr.startswith("powergraph: error:") and "Traceback" not in done.stderr
