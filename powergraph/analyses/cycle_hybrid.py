"""The rows of a hybrid duty cycle — machines on electrical buses — solved together
(:mod:`powergraph.analyses.cycle`, docs/hybrid.md).

The single solve (:mod:`powergraph.statics.machines`) meets each balanced bus by Newton's
method on one machine torque ``τ`` per bus, each step a plain solve of the train with
``τ`` given. Here the same iteration (the same start, slopes by the same differences, the
same Broyden updates and test, :data:`~powergraph.statics.machines.MAX_STEPS`) runs over
every row at once: ``τ`` is a load column of the plain train, and each step evaluates
every row not yet settled through one call of the compiled sweep
(:mod:`powergraph.analyses.sweep`), which settles each row's power directions and losses.
The plain train's statics are linear in its loads for a direction pattern, so the ports'
torques and the elements' forces of a row are its loads times the answers of
:func:`~powergraph.statics.equilibrium.solve_equilibrium` to a unit load at each loaded
port, solved once per pattern met (:class:`~powergraph.analyses.cycle_train.PlainTrain`);
the machines' efficiencies and electrical powers are the single solve's functions on
arrays. A row the sweep does not solve, whose slopes are singular, that does not settle,
or whose values the single solve refuses, is solved alone, for its reason.

Examples
--------
>>> import io
>>> from powergraph.model import load_model
>>> from powergraph.analyses.cycle import cycle
>>> r = cycle(load_model("models/ths2_power_split.yaml"), io.StringIO(
...     "engine.speed [rpm],engine.power [kW],wheels.speed [rpm]\\n2000,30,400\\n"))
>>> r.method, round(float(r.efficiencies[0]), 6), bool(r.negative_split[0])
('sweep with bus balance', 0.902866, False)
"""
from __future__ import annotations

import itertools

import numpy as np

from powergraph.analyses.cycle_columns import Columns, flow_names
from powergraph.analyses.cycle_points import Points
from powergraph.analyses.cycle_hybrid_report import report
from powergraph.analyses.cycle_rows import cleared, single_row
from powergraph.analyses.cycle_train import Batch, PlainTrain, RowValues
from powergraph.analyses.sweep.compile import KERNEL_MIN_VARIANTS, refuse_loss_blocks
from powergraph.analyses.sweep.paths import value_allowed
from powergraph.errors import ModelError, UsageError
from powergraph.model.spec import Model
from powergraph.statics.machines import (MAX_STEPS, balance_scale, broyden_update,
                                         difference_steps, newton_step, settled)

#: ``CycleResult.method`` of a cycle solved here.
METHOD = "sweep with bus balance"
#: The most rows a call of the sweep takes: below the size at which it compiles numba
#: kernels (a second or more per direction pattern, once per process; measured slower
#: than numpy over a cycle of 10^5 rows).
BLOCK = KERNEL_MIN_VARIANTS - 1
#: A machine that turns slower than this (rad/s) is not a choice for a bus's unknown
#: torque (:func:`powergraph.statics.machines._choose_unknowns`).
STILL = 1e-12


def batchable(model: Model, points: Points) -> bool:
    """Machines on buses, no shift elements, no modes: the rows this module solves."""
    return bool(model.buses) and not model.shift_elements and points.mode_codes is None


def hybrid_rows(model: Model, points: Points, keep_going: bool) -> Columns:
    """Every row of ``points`` into columns, solved together where they can be (see the
    module docstring), the others alone in row order (without ``keep_going`` the first
    that cannot be solved is an error).

    Raises
    ------
    ModelError
        The train has losses the sweep does not take (friction laws, bearing losses), or
        its speeds are not linear in the given ones: the caller solves every row alone.
    RowError
        Without ``keep_going``, the first row that cannot be solved.
    """
    base = cleared(model, points)
    refuse_loss_blocks(base, "the hybrid cycle's sweep")
    columns, alone = Columns(len(points), flow_names(model)), []
    choices = _Choices(base, points)
    for start in range(0, len(points), BLOCK):
        rows = np.arange(start, min(len(points), start + BLOCK))
        alone.append(choices.solve(rows, columns))
    for i in np.unique(np.concatenate(alone)).tolist():
        single_row(base, points, i, keep_going, columns)
    return columns


class _Choices:
    """The machines whose torques are a row's unknowns, one per balanced bus, as the
    single solve chooses them (:func:`~powergraph.statics.machines._choose_unknowns`):
    of the combinations of each bus's free machines that turn, taken by falling speed,
    the first with which the train is determined; a :class:`PlainTrain` per combination."""

    def __init__(self, base: Model, points: Points) -> None:
        self.values = RowValues(base, points)
        balanced = [bus for bus in base.buses.values() if bus.battery is not None]
        given = self.values.given
        self.free = [[p.index for p in base.machines if p.bus == bus.name
                      and not given(p.index, "power") and not given(p.index, "torque")]
                     for bus in balanced]
        self.trains: dict[tuple[int, ...], PlainTrain | None] = {}

    def train(self, unknowns: tuple[int, ...]) -> PlainTrain | None:
        """The plain train with these unknowns (None: not determined with them)."""
        if unknowns not in self.trains:
            try:
                self.trains[unknowns] = PlainTrain(self.values, unknowns)
            except (UsageError, ModelError):
                self.trains[unknowns] = None
        return self.trains[unknowns]

    def solve(self, rows: np.ndarray, columns: Columns) -> np.ndarray:
        """Rows ``rows`` into ``columns``; returns those to be solved alone."""
        speeds = self.values.speeds(rows)
        turning = {i: np.abs(speeds[:, self.values.body(i)])
                   for free in self.free for i in free}
        combos = list(itertools.product(*self.free))
        keys = np.zeros((len(rows), len(combos)))
        for k, combo in enumerate(combos):
            for free, chosen in zip(self.free, combo):   # the rank of ``chosen``, by speed
                w = turning[chosen]
                rank = sum(((turning[i] > w) | ((turning[i] == w) & (n < free.index(chosen))))
                           & (turning[i] > STILL) for n, i in enumerate(free))
                keys[:, k] = keys[:, k] * len(free) + np.where(w > STILL, rank, np.inf)
        alone = []
        while len(rows):
            hopeless = ~np.isfinite(np.min(keys, axis=1, initial=np.inf))
            if hopeless.any():               # no choice turns: alone, for its error
                alone.append(rows[hopeless])
                rows, speeds, keys = rows[~hopeless], speeds[~hopeless], keys[~hopeless]
                continue
            best = np.argmin(keys, axis=1)
            train = self.train(combos[best[0]])
            if train is None:                # not determined with it: the next choice
                keys[:, best[0]] = np.inf
                continue
            mine = best == best[0]
            alone.append(_newton(train, train.prepare(rows[mine], speeds[mine]), columns))
            rows, speeds, keys = rows[~mine], speeds[~mine], keys[~mine]
        return np.concatenate(alone) if alone else np.zeros(0, np.int64)


def _newton(train: PlainTrain, batch: Batch, columns: Columns) -> np.ndarray:
    """:func:`~powergraph.statics.machines._newton` over the rows of ``batch`` at once:
    the settled rows into ``columns``; returns the rows to be solved alone."""
    alone = [batch.rows[~batch.ok]]
    batch = batch.take(batch.ok)
    unknowns = [train.values.body(i) for i in train.unknowns]
    x = np.zeros((len(batch.rows), len(unknowns)))
    state = train.evaluate(batch, x)
    alone.append(batch.rows[~state.ok])
    keep = state.ok
    batch, state, x = batch.take(keep), state.take(keep), x[keep]
    scale = balance_scale(state.powers, train.balanced, state.batteries)
    r, jac = state.residual, None
    for _ in range(MAX_STEPS):
        done = settled(r, scale)
        if done.any():
            alone.append(report(train, state.take(done), batch.rows[done], columns))
        batch, x, r, scale = batch.take(~done), x[~done], r[~done], scale[~done]
        jac = None if jac is None else jac[~done]
        if not len(batch.rows):
            break
        if jac is None:
            steps = difference_steps(x, scale, batch.speeds[:, unknowns])
            jac, ok = np.empty(x.shape + x.shape[1:]), np.ones(len(x), bool)
            for j in range(x.shape[1]):
                shifted = x.copy()
                shifted[:, j] += steps[:, j]
                slope = _evaluate(train, batch, shifted, ok)
                with np.errstate(all="ignore"):
                    jac[:, :, j] = (slope.residual - r) / steps[:, j:j + 1]
            alone.append(batch.rows[~ok])
            batch, x, r, scale, jac = batch.take(ok), x[ok], r[ok], scale[ok], jac[ok]
        dx, ok = _steps(jac, r)
        x = x + dx
        state = _evaluate(train, batch, x, ok)
        alone.append(batch.rows[~ok])
        with np.errstate(all="ignore"):
            jac = broyden_update(jac, dx, state.residual - r)
        batch, x, jac, scale = batch.take(ok), x[ok], jac[ok], scale[ok]
        state = state.take(ok)
        r = state.residual
    alone.append(batch.rows)                      # not settled in MAX_STEPS
    return np.concatenate(alone)


def _evaluate(train: PlainTrain, batch: Batch, x: np.ndarray, ok: np.ndarray):
    """The plain train at ``x`` over the rows of ``batch``; ``ok`` (changed in place)
    keeps the rows solved, whose torques are ones a model takes (the single solve's
    plain solve refuses others: that row is solved alone, for its error)."""
    ok &= np.all(value_allowed("torque", x), axis=1)
    safe = np.where(ok[:, None], x, 0.0)
    state = train.evaluate(batch, safe)
    ok &= state.ok
    return state


def _steps(jac: np.ndarray, r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Newton's step of each row and where it is one (its slopes not singular)."""
    ok = np.all(np.isfinite(jac), axis=(1, 2)) & np.all(np.isfinite(r), axis=1)
    dx = np.zeros_like(r)
    try:
        dx[ok] = newton_step(jac[ok], r[ok])
    except np.linalg.LinAlgError:
        for i in np.flatnonzero(ok).tolist():
            try:
                dx[i] = newton_step(jac[i], r[i])
            except np.linalg.LinAlgError:
                ok[i] = False
    return dx, ok & np.all(np.isfinite(dx), axis=1)
