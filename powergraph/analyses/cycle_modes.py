"""The rows of a duty cycle in modes (a ``mode`` column): each mode's case, its rows at
once where it can be.

A mode whose freewheels do not depend on the load has one plain train for every row
(:attr:`powergraph.statics.case.TrainCase.gear_model`: its clutches and brakes as the mode
says): its rows go through that train's compiled sweep at once, as a plain train's cycle
does (:func:`~powergraph.analyses.cycle_rows.sweep_rows`). A mode whose freewheels are
decided at each load, a mode that leaves a port inactive, a train with machines, friction
laws or bearing losses, a row with an empty cell and any row the sweep does not solve go
row by row through the case
(:func:`~powergraph.analyses.cycle_rows.single_row`). Without ``keep_going`` the first row
in file order that cannot be solved is the error, whichever group it was in.

Examples
--------
>>> import io
>>> from powergraph.model import load_model
>>> m = load_model("models/simpson_3speed.yaml")
>>> pts = read_points(io.StringIO("mode,in.speed [rpm],in.power [kW],duration [s]\\n"
...                               "2,2500,20,1\\n3,2500,20,1\\n1,2500,20,1\\n"), m)
>>> rows = mode_rows(m, pts, keep_going=False)
>>> [round(e, 6) for e in rows.efficiencies.tolist()]
[0.993788, 1.0, 0.975394]
"""
from __future__ import annotations

import numpy as np

from powergraph.analyses.cycle_columns import FAILED, Columns, flow_names
from powergraph.analyses.cycle_points import Points, read_points  # noqa: F401 (doctest)
from powergraph.analyses.cycle_rows import (NUMERICAL, _fill, cleared, refused, row_base,
                                            single_row, slices)
from powergraph.errors import ModelError, UsageError
from powergraph.model.spec import Model
from powergraph.statics.case import TrainCase
from powergraph.statics.friction import loss_block_places

#: The method a cycle in modes reports.
METHOD = "modes (sweep per gear)"


def mode_rows(model: Model, points: Points, keep_going: bool) -> Columns:
    """Every row of ``points`` (with a ``mode`` column) in its mode's case."""
    swept, base = cleared(model, points), row_base(model, points)
    columns = Columns(len(points), flow_names(model))
    given = _complete(points)
    for code, mode in enumerate(points.mode_names):
        rows = np.flatnonzero(points.mode_codes == code)
        left = [rows[~given[rows]]]
        if given[rows].any():
            left.append(_swept(swept, mode, points, rows[given[rows]], columns))
        for i in np.sort(np.concatenate(left)).tolist():
            single_row(base, points, i, True, columns)
    failed = np.flatnonzero(columns.verdict_codes >= FAILED)
    if failed.size and not keep_going:
        first = int(failed[0])
        raise refused(points, first, columns.verdict_texts[columns.verdict_codes[first]])
    return columns


def _complete(points: Points) -> np.ndarray:
    """The rows that give every column's value (no empty cell): those a mode's compiled
    sweep may take; a row with an empty cell takes its mode's or the model's value,
    one by one (:func:`~powergraph.analyses.cycle_rows.row_model`)."""
    given = np.ones(len(points), dtype=bool)
    for values in (*points.values, *(v for _, v in points.batteries)):
        given &= ~np.isnan(values)
    return given


def _swept(base: Model, mode: str, points: Points, rows: np.ndarray,
           columns: Columns) -> np.ndarray:
    """The mode's rows through its plain train's compiled sweep; returns those left to
    solve one by one (all of them when the mode has no such train)."""
    from powergraph.analyses.sweep import CompiledSweep

    gear = TrainCase.of(base, mode).gear_model
    if gear is None or gear.buses or gear.inactive or loss_block_places(gear):
        return rows          # one by one: each row's own case (an inactive port refused)
    paths = [path for path, _, _ in points.columns]
    try:
        evaluate = CompiledSweep(gear, paths)
        left = []
        for part in slices(rows.size):
            picked = rows[part]
            result = evaluate({path: v[picked] for path, v in zip(paths, points.values)},
                              quiet=True)
            left.append(_fill(columns, picked, result, gear))
    except (UsageError, ModelError, *NUMERICAL):
        return rows          # a combination the compiled sweep does not take
    return np.concatenate(left)
