"""Every evaluator gives the single solve's answer: `solve`, the compiled sweep (a one-point
`sweep(model, {PATH: values})`, both backends), the efficiency grid and the closed-form
formulas, on every model file, on random trains that lock, cycle or have several
consistent direction patterns, and on chains near the thresholds of the direction rule.

Expected values: the single solve checked by ``assert_conservation`` (Willis, equilibrium,
power balance, mesh law), and for the chains the closed form ``η^(N-1)`` (each fixed-axis
mesh passes η of what its driver feeds it).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import powergraph as pg
from powergraph.analyses.efficiency_grid import at_point, solve_grid
from powergraph.analyses.sweep import STATUS, sweep
from powergraph.analyses.sweep.backends import applies
from powergraph.analyses.sweep.compile import compile_sweep
from powergraph.errors import MethodNotApplicableError, ModelError, UsageError
from powergraph.kinematics import elements_of
from powergraph.model import load_model, loads_model
from powergraph.statics.friction import loss_block_places
from powergraph.testing import assert_conservation
from powergraph.testing_trains import gear_chain_text, random_train
from powergraph.units_si import RPM_PER_RAD_S

MODELS = sorted((Path(__file__).resolve().parents[1] / "models").glob("*.yaml"))
REL = 1e-11


def drivers(result) -> list[int]:
    return [0 if e.driver is None else (1 if e.driver == e.a else -1) for e in result.elements]


def one_point(model, backend: str):
    """The sweep of the model's own first efficiency (the model unchanged), one point."""
    element = next(e for e in elements_of(model) if e.kind == "mesh")
    return sweep(model, {f"links.{element.link}.efficiency": [element.efficiency]},
                 backend=backend, quiet=True)


def backends_of(model) -> list[str]:
    symbolic = applies(compile_sweep(model, [one_path(model)], backend="numeric").layout)
    return ["symbolic", "numeric"] if symbolic else ["numeric"]


def one_path(model) -> str:
    element = next(e for e in elements_of(model) if e.kind == "mesh")
    return f"links.{element.link}.efficiency"


def assert_sweep_is_the_solve(swept, single, rel: float = REL) -> None:
    """Variant 0 of ``swept`` is ``single``: values, drivers, status and verdict."""
    scale = abs(single.input_power) or 1.0
    assert STATUS[swept.status.flat[0]] == ("locked" if single.lock else "ok")
    assert swept.efficiency.flat[0] == pytest.approx(single.efficiency, rel=rel, abs=1e-300)
    if single.ratio is not None:
        assert swept.ratio.flat[0] == pytest.approx(single.ratio, rel=rel)
    assert swept.input_power.flat[0] == pytest.approx(single.input_power, rel=rel)
    assert swept.output_power.flat[0] == pytest.approx(single.output_power, rel=rel,
                                                       abs=rel * scale)
    assert swept.total_loss.flat[0] == pytest.approx(single.total_loss, rel=rel,
                                                     abs=rel * scale)
    for element in single.elements:
        assert swept.losses[element.link].flat[0] == pytest.approx(element.loss, rel=rel,
                                                                   abs=rel * scale)
    assert [int(swept.drivers[e.link].flat[0]) for e in single.elements] == drivers(single)
    assert bool(swept.self_locking.flat[0]) == single.self_locking


# --- every model file ---------------------------------------------------------------------

@pytest.mark.slow
@pytest.mark.parametrize("path", MODELS, ids=[p.name for p in MODELS])
def test_every_model_file(path: Path) -> None:
    model = load_model(path)
    single = pg.solve(model)
    assert_conservation(single)
    if model.buses:                         # machines on buses: the sweep refuses them
        with pytest.raises(UsageError, match="machines"):
            one_point(model, "auto")
        return
    if loss_block_places(model):            # load-dependent losses: the grid evaluates them
        with pytest.raises(ModelError):
            one_point(model, "auto")
    else:
        for backend in backends_of(model):
            assert_sweep_is_the_solve(one_point(model, backend), single)
    if single.dof == 1 and len(model.inputs) == 1 and len(model.outputs) == 1 \
            and single.lock is None and single.input_power:
        assert_grid_is_the_solve(model, single)
        if loss_block_places(model):        # the formulas refuse what they would drop
            with pytest.raises(MethodNotApplicableError, match="load"):
                from powergraph.analyses.formula import derive_formulas
                derive_formulas(model)
        else:
            assert_formula_is_the_solve(model, single)


def assert_grid_is_the_solve(model, single) -> None:
    """The efficiency grid at the single solve's operating point (input speed, output
    torque) gives the single solve of that point."""
    w_in = single.kinematics.body_speeds[model.body_of[model.inputs[0].component]]
    out = model.body_of[model.outputs[0].component]
    torque = abs(single.external_torques.get(out, 0.0))
    if w_in == 0 or torque == 0:
        return
    sense = float(np.sign(single.ratio or 1.0))
    grid = solve_grid(model, np.array([w_in * RPM_PER_RAD_S]), np.array([torque]))
    point = pg.solve(at_point(model, w_in, torque, sense))
    assert_conservation(point)
    assert grid.efficiency[0] == pytest.approx(point.efficiency, rel=1e-9)
    assert grid.input_power[0] == pytest.approx(point.input_power, rel=1e-9)


def assert_formula_is_the_solve(model, single) -> None:
    from powergraph.analyses.formula import derive_formulas

    try:
        formula = derive_formulas(model)
    except MethodNotApplicableError:
        return
    values = formula.evaluate()
    assert values["efficiency"] == pytest.approx(single.efficiency, rel=1e-10)
    assert values["ratio"] == pytest.approx(single.ratio, rel=1e-10)
    assert formula.holds()


# --- random trains: locking, cycling, several solutions -----------------------------------

SEEDS = range(60)


@pytest.mark.slow
@pytest.mark.parametrize("seed", SEEDS)
def test_random_trains_lossy_and_back_driven(seed: int) -> None:
    """Very lossy back-driven trains cycle, lock or have several consistent patterns: the
    sweep hands those to the single solver's search, so its status and verdict are the
    single solve's."""
    train = random_train(seed, stages=(1, 3), dof=1, drive="back-driven", eta=(0.05, 0.6))
    single = pg.solve(train.model)
    assert_conservation(single)
    assert_sweep_is_the_solve(one_point(train.model, "numeric"), single)


@pytest.mark.slow
def test_the_random_trains_do_lock_and_search() -> None:
    """The seeds above contain locked trains and searched (cycling) ones."""
    locked = searched = 0
    for seed in SEEDS[:30]:
        train = random_train(seed, stages=(1, 3), dof=1, drive="back-driven",
                             eta=(0.05, 0.6))
        single = pg.solve(train.model)
        locked += single.lock is not None
        searched += single.search is not None
    assert locked > 0 and searched > 0


@pytest.mark.slow
@pytest.mark.parametrize("seed", [2, 12])
def test_a_cycling_random_train_with_both_backends(seed: int) -> None:
    """Two of the trains above whose directions cycle (the single solver searches)."""
    train = random_train(seed, stages=(1, 3), dof=1, drive="back-driven", eta=(0.05, 0.6))
    single = pg.solve(train.model)
    assert_conservation(single)
    assert single.search is not None
    for backend in backends_of(train.model):
        assert_sweep_is_the_solve(one_point(train.model, backend), single)


# --- chains at the thresholds of the direction rule -------------------------------------

def chain(n: int, eta: float):
    """``n`` gears on fixed axes in a row, each mesh of efficiency ``eta``."""
    return loads_model(gear_chain_text(n)).with_mesh_efficiency(eta)


@pytest.mark.parametrize("n, eta", [(4, 1e-6), pytest.param(6, 1e-3, marks=pytest.mark.slow),
                                    pytest.param(8, 1e-6, marks=pytest.mark.slow)])
def test_small_chains_at_tiny_efficiencies(n: int, eta: float) -> None:
    """Every mesh passes η of its driver's power, however small: η^(N-1) from every
    evaluator (the sweep once answered 1e-12 for 1e-18: it called a tiny power nothing)."""
    model = chain(n, eta)
    single = pg.solve(model)
    assert_conservation(single)
    assert single.efficiency == pytest.approx(eta ** (n - 1), rel=1e-12)
    for backend in ("symbolic", "numeric"):
        swept = sweep(model, {"links.*.efficiency": [eta]}, backend=backend, quiet=True)
        assert_sweep_is_the_solve(swept, single, rel=1e-12)
        assert swept.efficiency[0] == pytest.approx(eta ** (n - 1), rel=1e-12)


@pytest.mark.slow
@pytest.mark.parametrize("n, eta", [(20, 1e-2), (301, 0.9), (40, 1e-6)])
def test_long_chains(n: int, eta: float) -> None:
    """Long chains (up to 300 meshes) through the numeric backend's scaled batched solves."""
    model = chain(n, eta)
    single = pg.solve(model)
    assert_conservation(single)
    expected = eta ** (n - 1)
    assert single.efficiency == pytest.approx(expected, rel=1e-9)
    swept = sweep(model, {"links.*.efficiency": [eta]}, backend="numeric", quiet=True)
    assert_sweep_is_the_solve(swept, single, rel=1e-9)
