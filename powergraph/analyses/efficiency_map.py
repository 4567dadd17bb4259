"""Efficiency over output torque × input speed, as reducer catalogues draw it, on both
sides: driving (the output drives a load, torque > 0) and coasting (torque < 0: the load
drives the output, the train is back-driven, the second quadrant of a vehicle
transmission's loss map).

Every point is the single solve of the train at that input speed with that output torque
(:func:`~powergraph.analyses.efficiency_grid.at_point`; for a mode, the case's answer,
:class:`~powergraph.statics.case.TrainCase`), so its efficiency and verdict are the solve's:
power leaving the train over power entering it, which when coasting is the power leaving
at the (nominal) input over the power entering at the output; ``self-locking`` where none
comes out (the output cannot drive the train). With no load (torque 0) the efficiency is
undefined (NaN); the loss map still carries the drag there.

With constant basic efficiencies a train's efficiency does not depend on its load or speed
(the virtual-power statics are homogeneous), so each side of the map is flat: one solve per
side gives it. With bearing friction (``mu``, proportional to the tooth forces) and drags
(load-independent) but constant mesh efficiencies, the solution at one speed is affine in
the output torque as long as no element changes its driver and no tooth force loading a
bearing changes sign: two solves per speed and side, at the smallest and the largest
torque, give the row, and it is solved point by point when the two ends disagree (an
affine quantity with the same sign at both ends keeps it in between). Drag makes such maps
rise with torque. With load-dependent mesh friction (ISO/TR 14179-2) each point is its own
fixed point; the passes run on the whole grid at once, with arrays
(:mod:`powergraph.analyses.efficiency_grid`), and points the batch cannot take are solved
one by one.

Examples
--------
>>> import powergraph as pg
>>> m = efficiency_map(pg.load_model("models/rv40e_wang2021.yaml"), [-100.0, 100.0], [500.0, 1500.0])
>>> m.efficiency.round(4).tolist(), m.self_locking
([[0.0, 0.2874], [0.0, 0.2874]], ((500.0, -100.0), (1500.0, -100.0)))
"""
from __future__ import annotations

import dataclasses
from dataclasses import field
from typing import Any, Sequence

import numpy as np

from powergraph.analyses.efficiency_grid import at_point, solve_grid
from powergraph.analyses.efficiency_map_report import SIDE_NAMES, map_dict, map_text
from powergraph.errors import UsageError
from powergraph.kinematics import solve_speeds
from powergraph.model.spec import Model
from powergraph.records import record
from powergraph.statics import solve
from powergraph.statics.bearings import load_regime
from powergraph.statics.case import TrainCase
from powergraph.statics.friction import friction_meshes
from powergraph.statics.loss_sources import torque_sources
from powergraph.statics.ports import ROUND_OFF, flow_efficiency_of_roles
from powergraph.statics.verdicts import VERDICTS, verdict_of
from powergraph.units_si import RAD_S_PER_RPM
from powergraph.display import Displayed



@record(repr=False)
class EfficiencyMap(Displayed):
    """Efficiency ``efficiency[i, j]`` at input speed ``speeds_rpm[i]`` and output torque
    ``torques[j]`` (N·m: > 0 the load the output drives, < 0 a load driving the output —
    coasting —, 0 no load, where the efficiency is NaN). ``input_power`` (W into the train
    at the input) and ``output_power`` (W taken out at the output, negative when coasting)
    per point; ``verdicts`` each point's verdict as a code into
    :data:`~powergraph.statics.verdicts.VERDICTS` (-1 where there is no answer).
    ``load_dependent`` is True when the efficiency varies over a side of the map
    (load-dependent mesh friction, bearing friction or drag). ``unconverged`` lists the
    ``(speed rpm, torque)`` points whose load-dependent passes did not converge (their
    efficiency is NaN); ``single_solves`` counts the points solved one at a time."""

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
    output_power: np.ndarray = field(default=None, repr=False)
    verdicts: np.ndarray = field(default=None, repr=False)

    @property
    def sides(self) -> np.ndarray:
        """Per torque: -1 coasting (torque < 0), 0 no load, 1 driving (keys of
        :data:`~powergraph.analyses.efficiency_map_report.SIDE_NAMES`)."""
        return np.sign(self.torques).astype(int)

    @property
    def self_locking(self) -> tuple[tuple[float, float], ...]:
        """The ``(speed rpm, torque)`` points under load whose verdict is
        ``self-locking``: no power comes out (efficiency 0); on the coasting side, the
        output cannot drive the train and the input must drive too."""
        return self.points_with("self-locking")

    def points_with(self, verdict: str) -> tuple[tuple[float, float], ...]:
        """The ``(speed rpm, torque)`` points under load (torque not 0) whose verdict is
        ``verdict``, rows by speed."""
        if self.verdicts is None:
            return ()
        hits = (self.verdicts == VERDICTS.index(verdict)) & (self.sides != 0)[None, :]
        return tuple((float(self.speeds_rpm[i]), float(self.torques[j]))
                     for i, j in zip(*np.nonzero(hits)))

    def _summary(self) -> str:
        finite = self.efficiency[np.isfinite(self.efficiency)]
        span = (f"efficiency {100 * finite.min():.4g}–{100 * finite.max():.4g} %"
                if finite.size else "efficiency undefined")
        return f"{self.name}: {len(self.speeds_rpm)} speeds × {len(self.torques)} torques, {span}"

    def _records(self) -> list[dict[str, Any]]:
        """One row per point: input speed (rpm), output torque (N·m), efficiency, side
        and verdict (None at no load, where the efficiency is undefined)."""
        return [{"speed_rpm": float(s), "torque_nm": float(t), "efficiency": float(e),
                 "side": SIDE_NAMES[int(np.sign(t))],
                 "verdict": _verdict_text(c) if t else None}
                for s, row, codes in zip(self.speeds_rpm, self.efficiency, self.verdicts)
                for t, e, c in zip(self.torques, row, codes)]

    def to_dict(self) -> dict[str, Any]:
        """JSON view (:func:`powergraph.analyses.efficiency_map_report.map_dict`)."""
        return map_dict(self)

    def text_report(self) -> str:
        """The table with its sides labelled and the notes
        (:func:`powergraph.analyses.efficiency_map_report.map_text`)."""
        return map_text(self)

    def loss_map(self) -> dict[str, np.ndarray]:
        """The map as a transmission loss map, the form VECTO reads: per point (rows by
        speed, then torque) the input speed (rpm), the input torque and the torque loss
        referred to the input (N·m). The input torque is the input power over the input
        speed, in the input's sense of rotation: negative when coasting (the input gives
        power out), as VECTO wants its drag side. The torque loss is the lost power over
        the input speed, ``(P_in − P_out)/ω_in = T_in − T_out·ω_out/ω_in``, never negative
        (round-off below zero is 0), on both sides and at no load (the drag); so VECTO's
        ``T_out = (T_in − T_loss)·i`` gives the output torque back. Points without an
        answer are left out (:attr:`unconverged`, :attr:`no_freewheel_state` name them).
        Also ``output_torque`` (N·m, as :attr:`torques`) per row.

        Examples
        --------
        A pair with ratio 2 and η 0.98: at 10 N·m out, 10/(2·0.98) N·m in, of which
        10/(2·0.98) − 5 are lost; coasting at −10 N·m, 10·0.98/2 N·m come out at the input
        (−4.9 N·m) and 5 − 4.9 are lost.

        >>> from powergraph.model import model_from_dict
        >>> pair = model_from_dict({"name": "pair", "components": {
        ...     0: {"role": "frame"}, 1: {"teeth": 20}, 2: {"teeth": 40}},
        ...     "links": [{"type": "mesh", "between": [1, 2], "efficiency": 0.98}],
        ...     "ports": [{"component": 1, "role": "input", "speed": 100.0},
        ...               {"component": 2, "role": "output"}]})
        >>> rows = efficiency_map(pair, [-10.0, 10.0], [1000.0]).loss_map()
        >>> rows["input_torque"].round(6).tolist(), rows["torque_loss"].round(6).tolist()
        ([-4.9, 5.102041], [0.1, 0.102041])
        """
        omega = np.abs(self.speeds_rpm * RAD_S_PER_RPM)[:, None]
        lost = self.input_power - self.output_power
        entering = np.maximum(self.input_power, 0.0) + np.maximum(-self.output_power, 0.0)
        lost = np.where((lost < 0.0) & (lost >= -ROUND_OFF * entering), 0.0, lost)
        input_torque, torque_loss = self.input_power / omega, lost / omega
        shape = self.efficiency.shape
        speed = np.broadcast_to(np.abs(self.speeds_rpm)[:, None], shape)
        output_torque = np.broadcast_to(self.torques[None, :], shape)
        kept = np.isfinite(input_torque) & np.isfinite(torque_loss)
        return {"speed_rpm": speed[kept], "input_torque": input_torque[kept],
                "torque_loss": torque_loss[kept], "output_torque": output_torque[kept]}

    def plot(self, ax: Any = None, **kwargs: Any):
        """Contours of the efficiency, coasting and driving sides apart, with the rated
        torque marked (delegates to
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
        Output torques, N·m: > 0 a load resisting the output's motion (driving), < 0 a
        load driving it (coasting: the train back-driven), 0 no load (efficiency NaN).
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
    active = case.base_model
    if len(active.inputs) != 1 or len(active.outputs) != 1:
        raise UsageError(f"an efficiency map needs one input and one output port; mode "
                         f"{mode!r} leaves {len(active.inputs)} input(s) and "
                         f"{len(active.outputs)} output(s) active (docs/modes.md)")
    if case.decides_freewheels or model.thermal is not None:
        emap = _case_map(case, torques, speeds, rated_torque)
    elif any(f.load_dependent for f in friction_meshes(case.gear_model).values()) or any(
            not getattr(s.friction, "affine", True) for s in torque_sources(case.gear_model)):
        emap = _dependent_map(case.gear_model, torques, speeds, rated_torque)
    else:
        emap = _plain_map(case.gear_model, torques, speeds, rated_torque)
    efficiency = emap.efficiency.copy()
    efficiency[:, torques == 0.0] = np.nan      # no load: nothing to compare the loss with
    return dataclasses.replace(emap, efficiency=efficiency)


def _plain_map(model: Model, torques: np.ndarray, speeds: np.ndarray,
               rated_torque: float | None) -> EfficiencyMap:
    """The map of constant mesh efficiencies: each side flat from one solve (scaled with
    the load and the speed), or, with bearings and drags, affine rows per side."""
    sense = np.sign(solve_speeds(model).ratio or 1.0)
    values, p_in, p_out = (np.empty((speeds.size, torques.size)) for _ in range(3))
    codes = np.empty(values.shape, dtype=np.int8)
    sources = bool(torque_sources(model))
    for side in _sides(torques):
        if sources:
            for i, speed in enumerate(speeds):
                (values[i, side], p_in[i, side], p_out[i, side],
                 codes[i, side]) = _affine_row(model, speed * RAD_S_PER_RPM, torques[side], sense)
            continue
        first = torques[side[0]]
        result = solve(_at(model, speeds[0] * RAD_S_PER_RPM, first, sense))
        scale = np.abs(speeds / speeds[0])[:, None] * (torques[side] / first if first else 1.0)
        values[:, side], codes[:, side] = _eta(result), VERDICTS.index(verdict_of(result))
        p_in[:, side], p_out[:, side] = result.input_power * scale, result.output_power * scale
    return EfficiencyMap(name=model.name, torques=torques, speeds_rpm=speeds,
                         efficiency=values, rated_torque=rated_torque,
                         load_dependent=sources, input_power=p_in, output_power=p_out,
                         verdicts=codes)


def _case_map(case: TrainCase, torques: np.ndarray, speeds: np.ndarray,
              rated_torque: float | None) -> EfficiencyMap:
    """The map of a mode whose freewheels depend on the load, or of a train whose oil
    temperature a heat balance sets at each point: every point the case's own answer (NaN
    where no freewheel state is consistent)."""
    sense = np.sign(case.point().required().result.ratio or 1.0)
    values, p_in, p_out = (np.full((speeds.size, torques.size), np.nan) for _ in range(3))
    codes = np.full(values.shape, -1, dtype=np.int8)
    for i, speed in enumerate(speeds):
        for j, torque in enumerate(torques):
            point = case.point(_at(case.model, speed * RAD_S_PER_RPM, torque, sense))
            if point.ok:
                values[i, j], codes[i, j] = _eta(point.result), VERDICTS.index(point.verdict)
                p_in[i, j], p_out[i, j] = point.result.input_power, point.result.output_power
    failed = codes < 0
    return EfficiencyMap(name=case.plain_model().name, torques=torques, speeds_rpm=speeds,
                         efficiency=values, rated_torque=rated_torque,
                         load_dependent=bool(torque_sources(case.model)), input_power=p_in,
                         output_power=p_out, verdicts=codes,
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
                         output_power=grid.output_power.reshape(shape),
                         verdicts=grid.verdicts.reshape(shape),
                         unconverged=tuple((float(speeds[i]), float(torques[j]))
                                           for i, j in zip(*np.nonzero(failed))),
                         single_solves=grid.single_solves)


def _affine_row(model: Model, speed: float, torques: np.ndarray,
                sense: float) -> tuple[np.ndarray, ...]:
    """Efficiency, input power, output power and verdict codes at one speed over
    ``torques`` (one side of the map) when the solution is affine in the load (constant
    mesh efficiencies, bearings and drags): from the two end points, or point by point
    when the ends differ in a driver, a bearing load's sign or their verdict."""
    low, high = float(np.min(torques)), float(np.max(torques))
    ends = [solve(_at(model, speed, t, sense)) for t in ((low, high) if high > low else (low,))]
    if len(ends) == 2 and all(r.lock is None for r in ends) and \
            verdict_of(ends[0]) == verdict_of(ends[1]) and \
            load_regime(model, ends[0]) == load_regime(model, ends[1]):
        share = (torques - low) / (high - low)
        p_in = ends[0].input_power + share * (ends[1].input_power - ends[0].input_power)
        p_out = ends[0].output_power + share * (ends[1].output_power - ends[0].output_power)
        return (flow_efficiency_of_roles(p_in, p_out), p_in, p_out,
                np.full(torques.shape, VERDICTS.index(verdict_of(ends[0]))))
    results = ends if len(ends) == 1 else [solve(_at(model, speed, t, sense)) for t in torques]
    return (np.array([_eta(r) for r in results]), np.array([r.input_power for r in results]),
            np.array([r.output_power for r in results]),
            np.array([VERDICTS.index(verdict_of(r)) for r in results]))


def _at(model: Model, speed: float, torque: float, sense: float) -> Model:
    """``model`` at input speed ``speed`` (rad/s) with output torque ``torque`` (N·m; < 0
    drives the output)."""
    return at_point(model, speed, torque, sense)


def _sides(torques: np.ndarray) -> list[np.ndarray]:
    """The indices of the coasting, no-load and driving torques (those present)."""
    groups = (np.flatnonzero(np.sign(torques) == s) for s in (-1, 0, 1))
    return [g for g in groups if g.size]


def _grid(values: Sequence[float], what: str) -> np.ndarray:
    array = np.asarray(values, dtype=float)
    if array.ndim != 1 or array.size == 0 or not np.all(np.isfinite(array)):
        raise UsageError(f"the {what} values must be a non-empty list of finite numbers")
    return array


def _eta(result) -> float:
    """The solve's efficiency (from the actual flows), NaN when no power passes."""
    return float("nan") if result.efficiency is None else result.efficiency


def _verdict_text(code: int) -> str | None:
    """The verdict of a code (None: no answer at that point)."""
    return VERDICTS[code] if code >= 0 else None
