"""Efficiency over output torque × input speed, as reducer catalogues draw it.

With constant basic efficiencies a train's efficiency does not depend on its load or speed
(the virtual-power statics are homogeneous), so the map is flat: one solve gives it. With
bearing friction (``mu``, proportional to the tooth forces) and drags (load-independent)
but constant mesh efficiencies, the solution at one speed is affine in the output torque as
long as no element changes its driver and no tooth force loading a bearing changes sign:
two solves per speed, at the smallest and the largest torque, give the whole row, and the
row is solved point by point when the two ends disagree (an affine quantity with the same
sign at both ends keeps it in between). Drag makes such maps rise with torque. With
load-dependent mesh friction (ISO/TR 14179-2) each point is its own fixed point; the passes
run on the whole grid at once, with arrays (:mod:`powergraph.analyses.efficiency_grid`),
and points the batch cannot take are solved one by one.

Examples
--------
>>> import powergraph as pg
>>> m = efficiency_map(pg.load_model("models/rv40e_wang2021.yaml"), [100.0, 400.0], [500.0, 1500.0])
>>> m.efficiency.shape
(2, 2)
"""
from __future__ import annotations

import math
from dataclasses import field
from typing import Any, Sequence

import numpy as np

from powergraph.analyses.efficiency_grid import at_point, solve_grid
from powergraph.errors import UsageError
from powergraph.kinematics import solve_speeds
from powergraph.model.spec import Model
from powergraph.records import record
from powergraph.statics import solve
from powergraph.statics.bearings import load_regime
from powergraph.statics.case import TrainCase
from powergraph.statics.friction import friction_meshes
from powergraph.statics.loss_sources import torque_sources
from powergraph.statics.ports import flow_efficiency_of_roles
from powergraph.units_si import RAD_S_PER_RPM
from powergraph.display import Displayed
from powergraph.format import aligned_table, format_fixed, format_number



@record(repr=False)
class EfficiencyMap(Displayed):
    """Efficiency ``efficiency[i, j]`` at input speed ``speeds_rpm[i]`` and output torque
    ``torques[j]`` (N·m, the load the output drives). ``load_dependent`` is True when it
    varies over the map (load-dependent mesh friction, bearing friction or drag).
    ``unconverged`` lists the ``(speed rpm, torque)`` points whose load-dependent passes
    did not converge (their efficiency is NaN); ``single_solves`` counts the points solved
    one at a time."""

    name: str
    torques: np.ndarray
    speeds_rpm: np.ndarray
    efficiency: np.ndarray
    rated_torque: float | None = None
    load_dependent: bool = False
    input_power: np.ndarray = field(default=None, repr=False)
    unconverged: tuple[tuple[float, float], ...] = ()
    single_solves: int = 0
    #: ``(speed rpm, torque)`` points of a mode where no freewheel state is consistent
    #: (their efficiency is NaN): the gear cannot carry that load.
    no_freewheel_state: tuple[tuple[float, float], ...] = ()

    def _summary(self) -> str:
        return (f"{self.name}: {len(self.speeds_rpm)} speeds × {len(self.torques)} torques, "
                f"efficiency {100 * np.nanmin(self.efficiency):.4g}–"
                f"{100 * np.nanmax(self.efficiency):.4g} %")

    def _records(self) -> list[dict[str, Any]]:
        """One row per point: input speed (rpm), output torque (N·m), efficiency."""
        return [{"speed_rpm": float(s), "torque_nm": float(t), "efficiency": float(e)}
                for s, row in zip(self.speeds_rpm, self.efficiency)
                for t, e in zip(self.torques, row)]

    def to_dict(self) -> dict[str, Any]:
        """JSON view: ``{name, torques, speeds_rpm, efficiency (rows by speed), rated_torque,
        load_dependent, unconverged, no_freewheel_state}`` (NaN efficiencies as null)."""
        values = [[None if math.isnan(e) else e for e in row] for row in self.efficiency.tolist()]
        return {"name": self.name, "torques": self.torques.tolist(),
                "speeds_rpm": self.speeds_rpm.tolist(), "efficiency": values,
                "rated_torque": self.rated_torque, "load_dependent": self.load_dependent,
                "unconverged": [list(p) for p in self.unconverged],
                "no_freewheel_state": [list(p) for p in self.no_freewheel_state]}

    def text_report(self) -> str:
        lines = [f"{self.name} — efficiency map (%)" + ("" if self.load_dependent else
                 ": constant mesh efficiencies and no drag, so it does not vary")]
        cells = [["speed rpm \\ torque N·m", *(format_number(t, 4) for t in self.torques)]]
        cells += [[format_number(speed, 5), *(format_fixed(100 * e, 3) for e in row)]
                  for speed, row in zip(self.speeds_rpm, self.efficiency)]
        lines += aligned_table(cells, set(range(len(cells[0]))), rules_after=())
        for points, what in ((self.unconverged, "did not converge"),
                             (self.no_freewheel_state, "have no consistent freewheel state")):
            if points:
                lines.append(f"{len(points)} point(s) {what} (nan): " +
                             ", ".join(f"{n:g} rpm {t:g} N·m" for n, t in points))
        return "\n".join(lines)

    def loss_map(self) -> dict[str, np.ndarray]:
        """The map as a transmission loss map, the form VECTO reads: per point (rows by
        speed, then torque) the input speed (rpm), the input torque and the torque loss
        referred to the input (N·m), both in the input's sense of rotation. The torque
        loss is the lost power over the input speed, ``T_in − T_out·ω_out/ω_in``. Points
        that did not converge are left out (:attr:`unconverged` names them).

        Examples
        --------
        A pair with ratio 2 and η 0.98: at 10 N·m out, 10/(2·0.98) N·m in, of which
        10/(2·0.98) − 5 are lost.

        >>> from powergraph.model import model_from_dict
        >>> pair = model_from_dict({"name": "pair", "components": {
        ...     0: {"role": "frame"}, 1: {"teeth": 20}, 2: {"teeth": 40}},
        ...     "links": [{"type": "mesh", "between": [1, 2], "efficiency": 0.98}],
        ...     "ports": [{"component": 1, "role": "input", "speed": 100.0},
        ...               {"component": 2, "role": "output"}]})
        >>> rows = efficiency_map(pair, [10.0], [1000.0]).loss_map()
        >>> round(float(rows["input_torque"][0]), 6), round(float(rows["torque_loss"][0]), 6)
        (5.102041, 0.102041)
        """
        omega = np.abs(self.speeds_rpm * RAD_S_PER_RPM)[:, None]
        input_torque = self.input_power / omega
        torque_loss = input_torque * (1.0 - self.efficiency)
        speed = np.broadcast_to(np.abs(self.speeds_rpm)[:, None], self.efficiency.shape)
        kept = np.isfinite(torque_loss)
        return {"speed_rpm": speed[kept], "input_torque": input_torque[kept],
                "torque_loss": torque_loss[kept]}

    def plot(self, ax: Any = None, **kwargs: Any):
        """Contours of the efficiency with the rated torque marked (delegates to
        :func:`powergraph.plot.efficiency_map.plot_efficiency_map`)."""
        from powergraph.plot.efficiency_map import plot_efficiency_map

        return plot_efficiency_map(self, ax=ax, **kwargs)


def efficiency_map(model: Model, torques: Sequence[float], speeds_rpm: Sequence[float],
                   rated_torque: float | None = None, mode: str | None = None) -> EfficiencyMap:
    """Solve ``model`` over output torque × input speed.

    Parameters
    ----------
    model : Model
        A 1-DOF train with one input and one output port (its own loads are replaced).
    torques : sequence of float
        Output load torques, N·m (> 0: the load resists the output's motion).
    speeds_rpm : sequence of float
        Input speeds, rpm (non-zero).
    rated_torque : float, optional
        Drawn as a line on the map.
    mode : str, optional
        The mode of a model with modes. A mode whose freewheels are decided at each
        operating point is solved point by point as its case
        (:class:`~powergraph.statics.case.TrainCase`), as ``solve --mode`` would; so is
        a train with a heat balance (``thermal:``), each point at its own oil temperature.

    Returns
    -------
    EfficiencyMap
    """
    torques, speeds = _grid(torques, "torque"), _grid(speeds_rpm, "speed")
    if len(model.inputs) != 1 or len(model.outputs) != 1:
        raise UsageError("an efficiency map needs one input and one output port")
    if np.any(speeds == 0.0):
        raise UsageError("input speeds must be non-zero")
    case = TrainCase.of(model, mode)
    if case.decides_freewheels or model.thermal is not None:
        return _case_map(case, torques, speeds, rated_torque)
    model = case.gear_model
    dependent = any(f.load_dependent for f in friction_meshes(model).values())
    sense = np.sign(solve_speeds(model).ratio or 1.0)
    if dependent:
        return _dependent_map(model, torques, speeds, rated_torque)
    values = np.empty((speeds.size, torques.size))
    power = np.empty_like(values)
    for i, speed in enumerate(speeds):
        if torque_sources(model):
            values[i], power[i] = _affine_row(model, speed * RAD_S_PER_RPM, torques, sense)
            continue
        for j, torque in enumerate(torques):
            if i or j:
                values[i, j] = values[0, 0]
                power[i, j] = power[0, 0] * (speed / speeds[0]) * (torque / torques[0])
                continue
            result = solve(_at(model, speed * RAD_S_PER_RPM, torque, sense))
            values[i, j], power[i, j] = _eta(result), result.input_power
    return EfficiencyMap(name=model.name, torques=torques, speeds_rpm=speeds,
                         efficiency=values, rated_torque=rated_torque,
                         load_dependent=bool(torque_sources(model)), input_power=power)


def _case_map(case: TrainCase, torques: np.ndarray, speeds: np.ndarray,
              rated_torque: float | None) -> EfficiencyMap:
    """The map of a mode whose freewheels depend on the load, or of a train whose oil
    temperature a heat balance sets at each point: every point the case's own answer (NaN
    where no freewheel state is consistent)."""
    sense = np.sign(case.point().required().result.ratio or 1.0)
    values = np.full((speeds.size, torques.size), np.nan)
    power = np.full_like(values, np.nan)
    for i, speed in enumerate(speeds):
        for j, torque in enumerate(torques):
            point = case.point(_at(case.model, speed * RAD_S_PER_RPM, torque, sense))
            if point.ok:
                values[i, j], power[i, j] = _eta(point.result), point.result.input_power
    failed = np.isnan(power)
    return EfficiencyMap(name=case.plain_model().name, torques=torques, speeds_rpm=speeds,
                         efficiency=values, rated_torque=rated_torque,
                         load_dependent=bool(torque_sources(case.model)), input_power=power,
                         no_freewheel_state=tuple((float(speeds[i]), float(torques[j]))
                                                  for i, j in zip(*np.nonzero(failed))),
                         single_solves=int(values.size))


def _dependent_map(model: Model, torques: np.ndarray, speeds: np.ndarray,
                   rated_torque: float | None) -> EfficiencyMap:
    """The map of a load-dependent mesh law, every point a fixed point, all at once."""
    speed_grid, torque_grid = np.meshgrid(speeds, torques, indexing="ij")
    grid = solve_grid(model, speed_grid.ravel(), torque_grid.ravel())
    shape = speed_grid.shape
    failed = grid.unconverged.reshape(shape)
    return EfficiencyMap(name=model.name, torques=torques, speeds_rpm=speeds,
                         efficiency=grid.efficiency.reshape(shape), rated_torque=rated_torque,
                         load_dependent=True, input_power=grid.input_power.reshape(shape),
                         unconverged=tuple((float(speeds[i]), float(torques[j]))
                                           for i, j in zip(*np.nonzero(failed))),
                         single_solves=grid.single_solves)


def _affine_row(model: Model, speed: float, torques: np.ndarray,
                sense: float) -> tuple[np.ndarray, np.ndarray]:
    """Efficiency and input power at one speed over ``torques`` when the solution is affine
    in the load (constant mesh efficiencies, bearings and drags): from the two end points,
    or point by point when the ends differ in a driver or a bearing load's sign."""
    low, high = float(np.min(torques)), float(np.max(torques))
    ends = [solve(_at(model, speed, t, sense)) for t in ((low, high) if high > low else (low,))]
    if len(ends) == 2 and all(r.lock is None for r in ends) and \
            load_regime(model, ends[0]) == load_regime(model, ends[1]):
        share = (torques - low) / (high - low)
        p_in = ends[0].input_power + share * (ends[1].input_power - ends[0].input_power)
        p_out = ends[0].output_power + share * (ends[1].output_power - ends[0].output_power)
        return flow_efficiency_of_roles(p_in, p_out), p_in
    results = ends if len(ends) == 1 else [solve(_at(model, speed, t, sense)) for t in torques]
    return (np.array([_eta(r) for r in results]),
            np.array([r.input_power for r in results]))


def _at(model: Model, speed: float, torque: float, sense: float) -> Model:
    """``model`` at input speed ``speed`` (rad/s) with output load ``torque`` (N·m)."""
    return at_point(model, speed, torque, sense)


def _grid(values: Sequence[float], what: str) -> np.ndarray:
    array = np.asarray(values, dtype=float)
    if array.ndim != 1 or array.size == 0 or not np.all(np.isfinite(array)):
        raise UsageError(f"the {what} values must be a non-empty list of finite numbers")
    if what == "torque" and np.any(array <= 0):
        raise UsageError("output torques must be > 0 (the load the output drives)")
    return array


def _eta(result) -> float:
    """The solve's efficiency (from the actual flows), NaN when no power passes."""
    return float("nan") if result.efficiency is None else result.efficiency
