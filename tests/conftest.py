"""Shared fixtures: paths, model loading from text, and the conservation check."""
from __future__ import annotations

import os
import shutil
import tempfile
from pathlib import Path

# The library chooses no matplotlib backend; the test session draws off-screen.
os.environ.setdefault("MPLBACKEND", "Agg")

import pytest

import powergraph as pg
from powergraph.testing import assert_conservation

ROOT = Path(__file__).resolve().parents[1]
MODELS = ROOT / "models"
SLOW_TESTS = Path(__file__).resolve().parent / "slow_tests.txt"


def pytest_configure(config) -> None:
    """The sweep's compiled kernels go to the test session's own folder — pytest's cache
    (kept between runs), or a temporary folder without it — never to the user's kernel
    cache, unless POWERGRAPH_CACHE_DIR chooses one."""
    if "POWERGRAPH_CACHE_DIR" in os.environ:
        return
    cache = getattr(config, "cache", None)
    if cache is not None:
        directory = cache.mkdir("powergraph-kernels")
    else:
        directory = Path(tempfile.mkdtemp(prefix="powergraph-kernels-"))
        config.add_cleanup(lambda: shutil.rmtree(directory, ignore_errors=True))
    os.environ["POWERGRAPH_CACHE_DIR"] = str(directory)


def pytest_collection_modifyitems(config, items) -> None:
    """Mark `slow` the tests listed in tests/slow_tests.txt (measured, about 0.12 s or more),
    beside those marked in their modules."""
    listed = {line.strip() for line in SLOW_TESTS.read_text(encoding="utf-8").splitlines()
              if line.strip() and not line.startswith("#")}
    for item in items:
        if item.nodeid in listed:
            item.add_marker(pytest.mark.slow)


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
