"""A duty cycle in modes (powergraph.analyses.cycle_modes): each mode's rows at once
through its gear's compiled sweep where the gear does not depend on the load, row by row
through the case where its freewheels do — and every row what the loop of single solves
(each row's own case) gives: the same powers, losses, verdicts and left-out rows."""
from __future__ import annotations

import io
from pathlib import Path

import numpy as np
import pytest

from powergraph.analyses.cycle import _single_rows, cycle
from powergraph.analyses.cycle_points import read_points
from powergraph.errors import UsageError
from powergraph.model import load_model

ROOT = Path(__file__).resolve().parents[2]


def _points(model, n: int, seed: int) -> str:
    """Random rows in every mode; a fifth of them back-driven (negative input power)."""
    rng = np.random.default_rng(seed)
    port = model.inputs[0].component
    lines = [f"mode,{port}.speed [rpm],{port}.power [kW],duration [s]"]
    modes = list(model.modes)
    for k in range(n):
        power = rng.uniform(1, 50) * (-1 if k % 5 == 4 else 1)
        lines.append(f"{modes[k % len(modes)]},{rng.uniform(500, 4000)!r},{power!r},1")
    return "\n".join(lines) + "\n"


@pytest.mark.parametrize("name", ["simpson_3speed.yaml", "ravigneaux_4speed.yaml",
                                  "zf8hp_8speed.yaml"])
def test_rows_in_modes_are_their_single_solves(name: str) -> None:
    model = load_model(ROOT / "models" / name)
    text = _points(model, 60, 7)
    batched = cycle(model, io.StringIO(text), keep_going=True)
    assert batched.method == "modes (sweep per gear)"
    single = _single_rows(model, read_points(io.StringIO(text), model))
    for a, b in zip(batched.rows, single.rows):
        assert a.verdict == b.verdict
        if b.failed:
            continue
        for field in ("power_in", "power_out", "loss"):
            assert getattr(a, field) == pytest.approx(getattr(b, field), rel=1e-9,
                                                      abs=1e-9 * b.power_in)
        assert a.efficiency == pytest.approx(b.efficiency, rel=1e-9)
    assert batched.energy_lost == pytest.approx(single.energy_lost, rel=1e-9)
    assert batched.left_out == single.left_out


def test_the_first_row_that_cannot_be_solved_is_the_error_in_file_order() -> None:
    """Rows of mode 2 are swept before mode 1's are solved one by one; the error still
    names the first row of the file that cannot be solved (first gear back-driven: F1
    overruns, no consistent state)."""
    model = load_model(ROOT / "models" / "simpson_3speed.yaml")
    text = ("mode,in.speed [rpm],in.power [kW],duration [s]\n"
            "2,2500,20,1\n1,2500,-20,1\n2,2500,0,1\n1,2500,20,1\n")
    with pytest.raises(UsageError, match=r"row 3 \(mode '1'\): cannot be solved: mode 1: "
                                         r"no consistent"):
        cycle(model, io.StringIO(text))
    kept = cycle(model, io.StringIO(text), keep_going=True)
    assert kept.left_out == [1]
    assert [r.verdict for r in kept.rows][2:] == ["no power", "ok"]
