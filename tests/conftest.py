"""Shared fixtures: paths, model loading from text, and the conservation check."""
from __future__ import annotations

import os
from pathlib import Path

# The library chooses no matplotlib backend; the test session draws off-screen.
os.environ.setdefault("MPLBACKEND", "Agg")

import pytest

import powergraph as pg
from powergraph.testing import assert_conservation

ROOT = Path(__file__).resolve().parents[1]
MODELS = ROOT / "models"


@pytest.fixture
def models_dir() -> Path:
    return MODELS


def solve_checked(model, **kwargs):
    """Solve and check every conservation law (used after every solve in the tests)."""
    result = pg.solve(model, **kwargs)
    assert_conservation(result)
    return result


@pytest.fixture
def solve_ok():
    return solve_checked
