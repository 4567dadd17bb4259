"""Sweeps in parts, here or on a Dask cluster: the same results as one plain sweep."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from powergraph.analyses.sweep import sweep
from powergraph.analyses.sweep.compile import CHUNK_SIZE
from powergraph.analyses.sweep.distributed import sweep_on_cluster
from powergraph.errors import UsageError
from powergraph.model import load_model

MODELS = Path(__file__).resolve().parents[2] / "models"
FIELDS = ("ratio", "efficiency", "input_power", "output_power", "total_loss",
          "self_locking", "converged", "status", "passes")


def rv_grid() -> dict[str, np.ndarray]:
    """40,000 RV variants over both meshes' efficiencies (three parts of one chunk each)."""
    first, second = np.meshgrid(np.linspace(0.9, 1.0, 200), np.linspace(0.5, 1.0, 200),
                                indexing="ij")
    return {"links.0.efficiency": first, "links.1.efficiency": second}


def assert_same(a, b, rel: float = 0.0) -> None:
    for name in FIELDS:
        x, y = getattr(a, name), getattr(b, name)
        assert x.shape == y.shape, name
        if rel == 0.0 or x.dtype.kind in "bi":
            assert np.array_equal(x, y, equal_nan=x.dtype.kind == "f"), name
        else:
            np.testing.assert_allclose(x, y, rtol=rel, atol=0, equal_nan=True, err_msg=name)
    for link in a.losses:
        assert np.array_equal(a.drivers[link], b.drivers[link])
        np.testing.assert_allclose(a.losses[link], b.losses[link], rtol=rel, atol=1e-12,
                                   equal_nan=True)


def test_in_parts_here_is_the_plain_sweep_exactly() -> None:
    model, grid = load_model(MODELS / "rv40e_wang2021.yaml"), rv_grid()
    plain = sweep(model, grid, quiet=True)
    parts = sweep_on_cluster(model, grid, part_size=CHUNK_SIZE)
    assert_same(parts, plain)
    assert plain.status_counts() == {"ok": plain.size}
    assert parts.parameters["links.1.efficiency"].shape == (200, 200)


def test_part_size_must_be_whole_chunks() -> None:
    with pytest.raises(UsageError, match="multiple"):
        sweep_on_cluster(load_model(MODELS / "rv40e_wang2021.yaml"), rv_grid(), part_size=1000)


@pytest.mark.slow  # starts a local cluster of two worker processes
def test_two_local_workers_give_the_single_process_result() -> None:
    """Numeric backend: identical to the last bit. Symbolic (closed forms learned per
    worker): a variant may take the closed form on one worker and the iteration on the
    other, equal to rounding; statuses and drivers identical."""
    model, grid = load_model(MODELS / "rv40e_wang2021.yaml"), rv_grid()
    numeric = sweep(model, grid, backend="numeric", quiet=True)
    assert_same(sweep_on_cluster(model, grid, backend="numeric", part_size=CHUNK_SIZE,
                                 workers=2), numeric)
    symbolic = sweep(model, grid, quiet=True)
    assert_same(sweep_on_cluster(model, grid, part_size=CHUNK_SIZE, workers=2), symbolic,
                rel=1e-12)
