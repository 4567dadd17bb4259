"""Shared fixtures: paths, model loading from text, and the conservation check."""
from __future__ import annotations

from pathlib import Path

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
