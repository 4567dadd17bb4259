"""Every evaluator gives the single solve's answer: `solve`, the compiled sweep (a one-point
`sweep(model, {PATH: values})`, both backends), the efficiency grid and the closed-form
formulas, on every model file, on random trains that lock, cycle or have several
consistent direction patterns, and on chains near the thresholds of the direction rule.

Expected values: the single solve checked by ``assert_conservation`` (Willis, equilibrium,
power balance, mesh law), and for the chains the closed form ``η^(N-1)`` (each fixed-axis
mesh passes η of what its driver feeds it).
"""
from __future__ import annotations

import functools
from pathlib import Path

import numpy as np
import pytest

import powergraph as pg
from powergraph.analyses.efficiency_grid import at_point, solve_grid
from powergraph.analyses.sweep import STATUS, sweep
from powergraph.analyses.sweep.backends import applies
from powergraph.analyses.sweep.entry import compile_sweep
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
    if model.shift_elements:     # its modes: test_every_mode_every_evaluator
        assert "default-state" in {w.code for w in pg.solve(model).warnings}
        return
    single = pg.solve(model)
    assert_conservation(single)
    if model.buses:         # machines on buses: each variant the case's solve, at the boundary
        swept = one_point(model, "auto")
        assert swept.backend == "single solves"
        assert swept.efficiency.flat[0] == pytest.approx(single.efficiency, rel=1e-12)
        assert swept.total_loss.flat[0] == pytest.approx(single.total_loss, rel=1e-12)
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


# --- every mode of every bundled transmission, forward and coasting ----------------------
#
# One operating state, every evaluator: the case's own answer (``solve --mode M
# [--backdrive]``), the gear table's row, a duty-cycle row at the same point, a one-variant
# sweep in the mode and the closed form of ``formula --mode`` give the same efficiency and
# verdict. Coasting is the back-driven case (the output fed the power the forward solve
# takes in); the cycle row, the sweep and the formula reach the same physical point with
# the ports as declared: the input at its speed, giving out the power the back-driven
# solve delivers there (a negative input power).

TRANSMISSIONS = [p for p in MODELS if load_model(p).modes and not load_model(p).buses]
#: Multi-mode hybrids (modes and machines on buses): test_every_hybrid_mode.
HYBRIDS = [p for p in MODELS if load_model(p).modes and load_model(p).buses]


#: Modes whose closed forms take 5-60 s of sympy each (the factoring of the sign
#: conditions of six to eight lossy meshes); their formulas are left out of this test
#: (the 8-speed's 1st, 6th and reverse are checked, forward and coasting).
SLOW_FORMULAS = {("zf8hp_8speed", mode) for mode in ("2", "3", "4", "5", "7", "8")}


def _mode_cases():
    # the bundled transmissions as written, and the 8-speed with every mesh at 0.3, where
    # reverse self-locks and 6th gear is lossless (its efficiency exactly 1)
    trains = [(path, None) for path in TRANSMISSIONS] + [
        (path, 0.3) for path in TRANSMISSIONS if path.stem == "zf8hp_8speed"]
    for path, eta in trains:
        for mode in load_model(path).modes if eta is None else ("6", "R"):
            for backdrive in (False, True):
                yield pytest.param(path, eta, mode, backdrive,
                                   id=f"{path.stem}{'' if eta is None else f'@{eta}'}-{mode}-"
                                      f"{'coast' if backdrive else 'fwd'}")


def _at_input(model, speed: float, power: float):
    """``model`` with its input at ``speed`` (rad/s) giving ``power`` (W) into the train."""
    return model.with_port(model.inputs[0].index, speed=speed, power=power, torque=None)


def _same_point(model, point):
    """The model as declared at the physical point of ``point`` (forward or coasting)."""
    if not point.case.backdrive:
        return model
    back = point.result
    old_input = model.inputs[0].component
    speed = back.kinematics.speed(old_input)
    delivered = next(p.power for p in back.ports if p.component == old_input)
    return _at_input(model, speed, delivered)


def _cycle_row(model, mode: str, variant):
    import io

    from powergraph.analyses.cycle import cycle

    port = model.inputs[0]
    given = variant.inputs[0]
    text = (f"mode,{port.component}.speed [rad/s],{port.component}.power [W],duration [s]\n"
            f"{mode},{given.speed!r},{given.power!r},1\n")
    return cycle(model, io.StringIO(text), keep_going=True)


def _assert_same(efficiency, verdict, expected_efficiency, expected_verdict, who: str):
    assert verdict == expected_verdict, who
    if expected_efficiency is None:
        assert efficiency is None or np.isnan(efficiency), who
    else:
        assert efficiency == pytest.approx(expected_efficiency, rel=1e-9, abs=1e-12), who
        assert efficiency <= 1.0, who


@functools.lru_cache(maxsize=None)
def _gear_rows(path: Path, eta) -> dict:
    """The gear table's rows by mode: one table holds every mode forward and coasting, so
    it is made once (per process) for all the cases of a model, which only read it."""
    from powergraph.analyses.gear_table import gear_table

    model = load_model(path)
    if eta is not None:
        model = model.with_mesh_efficiency(eta)
    return {r.mode: r for r in gear_table(model).rows}


@pytest.mark.slow
@pytest.mark.parametrize("path, eta, mode, backdrive", list(_mode_cases()))
def test_every_mode_every_evaluator(path: Path, eta, mode: str, backdrive: bool) -> None:
    from powergraph.analyses.formula import derive_formulas
    from powergraph.statics.case import TrainCase

    model = load_model(path)
    if eta is not None:
        model = model.with_mesh_efficiency(eta)
    point = TrainCase.of(model, mode, backdrive).point()
    if point.result is None:       # e.g. first gear coasting through its freewheel
        row = _gear_rows(path, eta)[mode]
        assert (row.coast_verdict if backdrive else row.verdict) == point.verdict
        return
    assert_conservation(point.result)
    expected = (point.result.efficiency, point.verdict)
    assert point.result.efficiency is None or point.result.efficiency <= 1.0

    row = _gear_rows(path, eta)[mode]
    _assert_same(row.coast_efficiency if backdrive else row.efficiency,
                 row.coast_verdict if backdrive else row.verdict, *expected, "gear table")

    variant = _same_point(model, point)
    again = TrainCase.of(variant, mode).point()
    assert_conservation(again.result)
    _assert_same(again.result.efficiency, again.verdict, *expected, "the same point declared")

    cycled = _cycle_row(model, mode, variant)
    _assert_same(cycled.rows[0].efficiency, cycled.rows[0].verdict, *expected, "cycle row")

    given = variant.inputs[0]
    swept = sweep(model, {f"ports.{given.index}.power": [given.power]}, mode=mode, quiet=True)
    self_locking = bool(swept.self_locking.flat[0])
    swept_verdict = ("locked" if STATUS[swept.status.flat[0]] == "locked" else
                     "self-locking" if self_locking else "ok")
    _assert_same(float(swept.efficiency.flat[0]), swept_verdict, *expected, "sweep")

    if (path.stem, mode) in SLOW_FORMULAS:
        return
    formula = derive_formulas(variant, mode=mode)
    assert formula.verdict == expected[1]
    assert formula.numeric["efficiency"] == pytest.approx(expected[0], rel=1e-12)
    if expected[1] == "ok":
        assert formula.evaluate()["efficiency"] == pytest.approx(expected[0], rel=1e-9)
        kinds = {c.kind for c in formula.conditions}
        if point.moded.freewheels and any(s in ("holding", "overrunning")
                                          for s in point.moded.freewheels.values()):
            assert "freewheel" in kinds


def test_simpson_first_gear_coasting_is_refused_by_every_evaluator() -> None:
    """First gear drives through F1, which overruns when the output drives: coasting
    has no consistent state (docs/modes.md). ``solve --backdrive`` says so, the gear
    table says so, and a sweep or cycle row at a negative input power flags it too."""
    from powergraph.analyses.gear_table import gear_table
    from powergraph.statics.case import TrainCase

    model = load_model(MODELS[0].parent / "simpson_3speed.yaml")
    point = TrainCase.of(model, "1", backdrive=True).point()
    assert point.result is None and point.verdict.startswith("no consistent freewheel state")
    assert gear_table(model).rows[0].coast_verdict == point.verdict
    swept = sweep(model, {"ports.0.power": [-20e3, 20e3]}, mode="1", quiet=True)
    assert [STATUS[s] for s in swept.status] == ["no-freewheel-state", "ok"]
    assert np.isnan(swept.efficiency[0])
    forward = TrainCase.of(model, "1").point().result
    assert swept.efficiency[1] == pytest.approx(forward.efficiency, rel=1e-12)
    from powergraph.errors import UsageError

    with pytest.raises(UsageError, match="row 2: mode 1: no consistent freewheel state"):
        _cycle_row(model, "1", _at_input(model, 2500 * np.pi / 30, -20e3))


@pytest.mark.slow
def test_the_hybrid_through_every_evaluator_that_takes_it() -> None:
    """The THS-II power split (machines on a bus, 2 DOF, no modes): its case's answer,
    the same point as a duty-cycle row (solved with the other rows, the bus balance's
    iteration batched) and as a sweep's variant (its case's solve) give the same
    efficiency and verdict; the evaluators that do not take it say so in one line (the
    formulas: 1-DOF trains; the gear table: no modes)."""
    import io

    from powergraph.analyses.cycle import cycle
    from powergraph.analyses.formula import derive_formulas
    from powergraph.analyses.gear_table import gear_table
    from powergraph.statics.case import TrainCase

    model = load_model(MODELS[0].parent / "ths2_power_split.yaml")
    point = TrainCase.of(model).point()
    assert_conservation(point.result)
    columns = [(p.name or p.component, p) for p in model.ports if p.speed is not None
               or p.power is not None or p.torque is not None]
    header, cells = [], []
    for name, port in columns:
        for kind in ("speed", "power", "torque"):
            value = getattr(port, kind)
            if value is not None:
                unit = {"speed": "rad/s", "power": "W", "torque": "N*m"}[kind]
                header.append(f"{name}.{kind} [{unit}]")
                cells.append(repr(value))
    text = ",".join(header + ["duration [s]"]) + "\n" + (",".join(cells + ["1"]) + "\n") * 3
    rows = cycle(model, io.StringIO(text))
    assert rows.method == "sweep with bus balance"
    for row in rows.rows:
        assert row.verdict == point.verdict
        assert row.efficiency == pytest.approx(point.result.efficiency, rel=1e-9)
    swept = sweep(model, {"ports.0.speed": [model.ports[0].speed]}, quiet=True)
    assert STATUS[swept.status.flat[0]] == "ok" and not swept.self_locking.flat[0]
    assert swept.efficiency.flat[0] == pytest.approx(point.result.efficiency, rel=1e-12)
    with pytest.raises(MethodNotApplicableError):
        derive_formulas(model)
    with pytest.raises(ModelError, match="no modes table"):
        gear_table(model)


@pytest.mark.parametrize("path, mode", [(p, m) for p in HYBRIDS for m in load_model(p).modes],
                         ids=lambda v: getattr(v, "stem", v))
def test_every_hybrid_mode(path: Path, mode: str) -> None:
    """A multi-mode hybrid's mode (docs/modes.md): its case's answer is the gear table's
    row, a duty-cycle row's and a one-variant sweep's at the same point (the sweep solves
    each variant by its case: machines on buses)."""
    import io

    from powergraph.analyses.cycle import cycle
    from powergraph.analyses.gear_table import gear_table
    from powergraph.statics.case import TrainCase

    model = load_model(path)
    point = TrainCase.of(model, mode).point()
    assert_conservation(point.result)
    row = {r.mode: r for r in gear_table(model).rows}[mode]
    _assert_same(row.efficiency, row.verdict, point.result.efficiency, point.verdict,
                 "gear table")
    assert [m.to_dict() for m in row.machines] == [m.to_dict() for m in point.result.machines]
    speeds = [(p.name or p.component, p.speed) for p in point.result.model.ports
              if p.speed is not None]
    header = ",".join(f"{name}.speed [rad/s]" for name, _ in speeds)
    cells = ",".join(repr(w) for _, w in speeds)
    rows = cycle(model, io.StringIO(f"mode,{header},duration [s]\n{mode},{cells},1\n"))
    _assert_same(rows.rows[0].efficiency, rows.rows[0].verdict, point.result.efficiency,
                 point.verdict, "cycle row")
    output = point.result.model.outputs[0]
    swept = sweep(model, {f"ports.{output.index}.speed": [output.speed]}, mode=mode,
                  quiet=True)
    swept_verdict = "self-locking" if swept.self_locking.flat[0] else STATUS[
        swept.status.flat[0]]
    _assert_same(float(swept.efficiency.flat[0]), swept_verdict, point.result.efficiency,
                 point.verdict, "sweep")
    assert swept.total_loss.flat[0] == pytest.approx(point.result.total_loss, rel=1e-9)
    from powergraph.analyses.formula import derive_formulas

    with pytest.raises(MethodNotApplicableError, match="machines on buses"):
        derive_formulas(model, mode=mode)      # closed forms: mechanical trains only
