"""The rows of a duty cycle (:mod:`powergraph.analyses.cycle`): each row's powers, losses
and verdict, filled into :class:`~powergraph.analyses.cycle_columns.Columns` — at once from
the compiled sweep's arrays for a plain train (a row it does not solve is solved alone, for
its reason), or by one single solve per row (in the row's mode, the freewheels decided).
A train with machines on buses has its rows solved together by
:mod:`powergraph.analyses.cycle_hybrid` (10^5 THS-II rows in 2-3 s, where a single solve
takes 11-24 ms a row: docs/performance.md), which solves here, alone, the rows it
cannot."""
from __future__ import annotations

import math

import numpy as np

from powergraph.analyses.cycle_columns import CycleRow  # noqa: F401  (re-exported)
from powergraph.analyses.cycle_columns import OK, Columns, flow_names, port_label
from powergraph.analyses.cycle_points import Points
from powergraph.errors import ModelError, PowerGraphError, UsageError
from powergraph.model.mode_specs import at_mode_point, spec_of
from powergraph.model.spec import Model
from powergraph.statics.loss_sources import element_label, losses
from powergraph.statics.verdicts import verdict_codes, verdict_of

#: Errors of a numerical procedure (numpy's warnings are errors under the command line).
NUMERICAL = (FloatingPointError, OverflowError, RuntimeWarning)
#: The most rows per call of the compiled sweep (about 200 bytes of work per row).
SLICE = 1 << 18


class RowError(UsageError):
    """A row of the points that cannot be solved (without ``keep_going``)."""


def refused(points: Points, i: int, verdict: str) -> RowError:
    """The error for row ``i``, that cannot be solved (``verdict``: ``error: ...``)."""
    mode = points.mode(i)
    where = f"row {points.lines[i]}" + (f" (mode {mode!r})" if mode is not None else "")
    return RowError(f"{points.source}: {where}: cannot be solved: "
                    f"{verdict[7:]} (--keep-going, keep_going=True, leaves such rows "
                    "out of the totals)")


def sweepable(model: Model, points: Points) -> bool:
    """A plain train: no machines, no shift elements, no modes (the compiled sweep's)."""
    return not (model.buses or model.shift_elements or points.mode_codes is not None)


def sweep_rows(model: Model, points: Points, keep_going: bool) -> Columns:
    """The rows through the compiled sweep, straight from its arrays, :func:`slices` of
    rows at a time (compiled once: its work arrays are a slice's, not the cycle's); a row
    it does not solve (status other than ``ok`` or ``locked``, powers not finite) is solved
    alone, for its reason."""
    from powergraph.analyses.sweep import CompiledSweep

    base = cleared(model, points)
    paths = [path for path, _, _ in points.columns]
    evaluate = CompiledSweep(base, paths)
    columns, unsolved = Columns(len(points)), []
    for part in slices(len(points)):
        result = evaluate({path: v[part] for path, v in zip(paths, points.values)},
                          quiet=True)
        unsolved.append(_fill(columns, part, result, model))
    for i in np.concatenate(unsolved).tolist():
        single_row(base, points, i, keep_going, columns)
    return columns


def slices(n: int) -> list[slice]:
    """The rows evaluated by each call of the compiled sweep: slices of equal size, of
    :data:`SLICE` rows or fewer (``2 * KERNEL_MIN_VARIANTS`` if that is more). A cycle
    of at least ``KERNEL_MIN_VARIANTS`` rows is evaluated in slices at least that long,
    so that the sweep takes its numba kernels as for the whole cycle at once."""
    from powergraph.analyses.sweep.compile import KERNEL_MIN_VARIANTS

    size = max(SLICE, 2 * KERNEL_MIN_VARIANTS)
    count = max(1, -(-n // size))
    bounds = [n * k // count for k in range(count + 1)]
    return [slice(a, b) for a, b in zip(bounds, bounds[1:])]


def _fill(columns: Columns, part: slice, result, model: Model) -> np.ndarray:
    """Rows ``part`` from the sweep's ``result`` over them; returns the indices of the
    rows it did not solve."""
    from powergraph.analyses.sweep import STATUS

    p_in, p_out = np.asarray(result.input_power, float), -np.asarray(result.output_power, float)
    total = np.asarray(result.total_loss, float)
    status = np.asarray(result.status)
    locked = status == STATUS.index("locked")
    solved = ((status == STATUS.index("ok")) | locked) & np.isfinite(p_in) \
        & np.isfinite(p_out) & np.isfinite(total)
    p_in, p_out = _finite(p_in), _finite(p_out)
    entering = np.maximum(p_in, 0.0) + np.maximum(p_out, 0.0)
    leaving = np.maximum(-p_in, 0.0) + np.maximum(-p_out, 0.0)
    verdicts = verdict_codes(locked, np.asarray(result.self_locking, bool),
                             (entering == 0) & (leaving == 0))
    efficiency = np.asarray(result.efficiency, dtype=float)
    columns.fill(part, solved, entering, leaving, _finite(total),
                 np.where(np.isfinite(efficiency), efficiency, np.nan), verdicts,
                 {element_label(model, k): _finite(v) for k, v in result.losses.items()})
    rows = np.arange(len(columns.power_in))[part]
    columns.warn("role-reversed", rows[_reversed_roles(p_in, p_out) & solved & (verdicts == OK)])
    return rows[~solved]


def _reversed_roles(p_in: np.ndarray, p_out: np.ndarray) -> np.ndarray:
    """Rows whose inputs give power out or whose outputs take power in (powers into the
    train), beyond round-off: the single solve's ``role-reversed`` warning, read from the
    sums over the input and the output ports (the ports themselves for a train with one
    of each)."""
    from powergraph.statics.ports import WARN_FRACTION

    entering = np.maximum(p_in, 0.0) + np.maximum(p_out, 0.0)
    return (p_in < -WARN_FRACTION * entering) | (p_out > WARN_FRACTION * entering)


def _finite(values) -> np.ndarray:
    """``values`` as floats with NaN (a variant not solved) as 0 and no -0."""
    array = np.asarray(values, dtype=float)
    return np.where(np.isfinite(array), array, 0.0) + 0.0


def cleared(model: Model, points: Points) -> Model:
    """The model with the loads of the ports the points load cleared (a port takes
    power or torque, not both), and the batteries the points give balanced: at NaN, a
    place each row fills with its own value (so that a batched evaluator that read the
    model's value instead would fail loudly)."""
    for _, index, kind in points.columns:
        if kind in ("power", "torque"):
            model = model.with_port(index, power=None, torque=None)
    for bus, _ in points.batteries:
        model = model.with_bus(bus, battery=math.nan)
    return model


def row_base(model: Model, points: Points) -> Model:
    """The model every row of ``points`` starts from (:func:`row_model`): :func:`cleared`,
    and in a cycle in modes the speeds of the points' speed columns cleared too (each
    column gives its quantity in every row, or leaves it to the row's mode)."""
    base = cleared(model, points)
    if points.mode_codes is None:
        return base
    for _, index, kind in points.columns:
        if kind == "speed":
            base = base.with_port(index, speed=None)
    return base


def row_model(base: Model, points: Points, i: int) -> Model:
    """Row ``i``'s model: ``base`` (:func:`row_base`) with the row's values.

    In a cycle in modes an empty cell (NaN) is *not given in this row*: the row's mode
    gives the value if it sets one (its ports and buses), else the row has none (a load
    or speed the mode's other values fix, or a free battery). ``base`` is put at the
    mode's point (:func:`~powergraph.model.mode_specs.at_mode_point`: its inactive ports
    carrying nothing) and the row's cells set on it; a value for a port the mode leaves
    inactive is refused. A load replaces the port's load of either kind.
    """
    mode = points.mode(i)
    variant = base if mode is None else at_mode_point(base, mode)
    for (_, index, kind), values in zip(points.columns, points.values):
        value = float(values[i])
        if math.isnan(value):
            continue
        if index in variant.inactive:
            raise ModelError(f"{port_label(base.ports[index])} is inactive in mode {mode!r}: "
                             f"it takes no {kind} (leave the cell empty in its rows)",
                             f"modes.{mode}.inactive")
        load = {} if kind == "speed" else {"power": None, "torque": None}
        variant = variant.with_port(index, **{**load, kind: value})
    for bus, values in points.batteries:
        battery = float(values[i])
        if math.isnan(battery):     # not given in this row: the mode's, else free
            battery = variant.buses[bus].battery
            battery = None if battery is None or math.isnan(battery) else battery
        variant = variant.with_bus(bus, battery=battery)
    return variant


def unset(variant: Model, points: Points, i: int, missing_kind: str) -> list[str]:
    """The quantities of row ``i``'s empty cells of ``missing_kind`` (``speed`` or
    ``load``: a power or torque, or a battery's power) that its mode does not give
    (``wheels.power``): what a row that cannot be solved for want of them lacks."""
    missing = []
    for (_, index, kind), values in zip(points.columns, points.values):
        port = variant.ports[index]
        if kind != "speed" and missing_kind == "load":
            lacking = port.power is None and port.torque is None
        else:
            lacking = kind == missing_kind == "speed" and port.speed is None
        if math.isnan(values[i]) and index not in variant.inactive and lacking:
            missing.append(f"{port_label(port)}.{kind}")
    if missing_kind == "load":
        spec = spec_of(variant, points.mode(i))
        missing += [f"{bus}.battery" for bus, values in points.batteries
                    if math.isnan(values[i]) and variant.buses[bus].battery is None
                    and (spec is None or bus not in spec.buses)]
    return list(dict.fromkeys(missing))


def single_rows(model: Model, points: Points, keep_going: bool = True) -> Columns:
    """One single solve per row, into preallocated columns; without ``keep_going`` the
    first row that cannot be solved is an error."""
    base = row_base(model, points)
    columns = Columns(len(points), flow_names(model))
    for i in range(len(points)):
        single_row(base, points, i, keep_going, columns)
    return columns


def single_row(base: Model, points: Points, i: int, keep_going: bool,
                columns: Columns) -> None:
    """Row ``i`` by the single solve (``base``: :func:`row_base`), into ``columns``."""
    from powergraph.statics.machine_report import (boundary_powers, electrical_share,
                                                   negative_split)

    variant = None
    try:
        variant = row_model(base, points, i)
        result = _solve(variant, points.mode(i))
        crossing = boundary_powers(result)
        power_in = sum(p for p in crossing if p > 0) + 0.0
        power_out = -sum(p for p in crossing if p < 0) + 0.0
        if not all(map(math.isfinite, (power_in, power_out, result.total_loss))):
            raise FloatingPointError("the powers are not finite")
    except (PowerGraphError, *NUMERICAL) as error:
        reason = " ".join(str(error).split())
        verdict = "error: " + (reason if isinstance(error, PowerGraphError)
                               else f"numerical problem ({reason})")
        kind = getattr(error, "missing", None)
        missing = [] if variant is None or kind is None else unset(variant, points, i, kind)
        if missing:
            verdict += (f" (not given in this row nor by mode {points.mode(i)!r}: "
                        f"{', '.join(missing)})")
        columns.fail(i, verdict)
        if not keep_going:
            raise refused(points, i, verdict)
        return
    verdict = verdict_of(result)
    columns.set(i, power_in, power_out, result.total_loss, result.efficiency, verdict,
                solve_losses(result),
                electrical_share=electrical_share(result) if result.machines else None,
                negative_split=negative_split(result) if result.machines else None,
                warnings=_own_warnings(result))
    if result.machines:
        columns.put_flows(i, *flows(result))


def flows(result) -> tuple[dict, dict, dict]:
    """The flows of one single solve with machines, as the cycle's columns hold them
    (:class:`~powergraph.analyses.cycle_columns.FlowNames`): each other port's power
    (fed in at an input, taken out at an output), each machine's quantities, each bus's
    battery power."""
    model = result.model
    label = port_label
    ports = {}
    for port in model.ports:
        if not port.is_machine:
            power = result.ports[port.index].power
            ports[label(port)] = (-power if port.role == "output" else power) + 0.0
    machines = {label(port): {"speed": math.nan if port.index in model.inactive else m.speed,
                              "torque": m.torque, "power": m.power,
                              "electrical_power": m.electrical_power}
                for port, m in zip(model.machines, result.machines)}
    return ports, machines, {name: b.battery_power for name, b in result.buses.items()}


def _solve(model: Model, mode: str | None):
    """The single solve of one row: the row's case (its mode, the freewheels decided at
    the row's load: :class:`~powergraph.statics.case.TrainCase`)."""
    from powergraph.statics.case import TrainCase

    point = TrainCase.of(model, mode).point()
    if point.result is None:
        raise ModelError(f"mode {mode}: {point.verdict}" if mode else point.verdict)
    return point.result


def _own_warnings(result) -> tuple[str, ...]:
    """The codes of a row's warnings that the model file does not have by itself."""
    own = result.warnings[len(result.model.warnings):]   # the model's come first
    return tuple(dict.fromkeys(w.code for w in own))


def solve_losses(result) -> dict[str, float]:
    """``{loss source: W}`` of one solve (every loss source of its model, by label:
    :mod:`powergraph.statics.loss_sources`)."""
    return {source.label: loss for source, loss in losses(result)}
