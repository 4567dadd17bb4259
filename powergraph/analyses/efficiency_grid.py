"""Load-dependent efficiencies on a whole grid of operating points at once (docs/losses.md).

A load-dependent mesh law (ISO/TR 14179-2) or bearing friction makes every point of an
efficiency map its own fixed point: forces → coefficients and bearing torques →
efficiencies and torques → forces (:func:`powergraph.statics.friction.solve_with_friction`).
Here the same passes run on every point together, with arrays: for one direction pattern
(who drives each element, taken from a single solve at a reference point) the torque
balance of each point is a small square system placed by the train system
(:class:`powergraph.kinematics.system.TrainSystem`), and all of them are solved by one
batched ``numpy.linalg.solve``. Each point stops at the pass where the single solve would
stop (no efficiency changing by more than the tolerance, no bearing torque by more than the
tolerance times the largest torque of the train), so its values are the single solve's.

The points are batched by the sense of the input speed and the sign of the output torque
(driving, coasting — the output driving the train — and no load), each batch with its own
reference. After convergence each point is checked: the pattern its forces give must agree
with the assumed one, its port powers must have the reference's signs (so its verdict is
the reference's, :func:`powergraph.statics.verdicts.verdict_of`), and its balance must be
well conditioned. Points that fail, and points that do not converge, are solved one by one
with :func:`powergraph.statics.solve`; a point that does not converge there either is
reported, not dropped.

Examples
--------
>>> import powergraph as pg
>>> from powergraph.model.lubricant import fixed_temperature
>>> m = fixed_temperature(pg.load_model("models/rv40e.yaml"), 273.15 + 60)  # oil at 60 °C
>>> g = solve_grid(m, np.array([1815.0, 1815.0]), np.array([100.0, 412.0]))
>>> g.efficiency.round(4).tolist(), g.single_solves, g.unconverged.tolist()
([0.8264, 0.8702], 0, [False, False])
>>> g = solve_grid(m, np.array([1815.0, 1815.0]), np.array([-400.0, -5.0]))
>>> g.efficiency.round(4).tolist(), [VERDICTS[c] for c in g.verdicts]
([0.8547, 0.0], ['ok', 'self-locking'])
"""
from __future__ import annotations

from typing import Any

import numpy as np

from powergraph.errors import SolveError
from powergraph.kinematics import elements_of, solve_speeds
from powergraph.kinematics.elements import gear_torque
from powergraph.kinematics.system import system_of
from powergraph.model.spec import Model
from powergraph.records import record
from powergraph.statics import solve
from powergraph.statics.bearings import (body_torques, bearing_torque, relative_speed,
                                         tooth_force, torque_change)
from powergraph.statics.directions import (driver_codes, factors_for, own_scales,
                                           relative_speeds)
from powergraph.statics.equilibrium import loads_of
from powergraph.statics.loss_sources import torque_sources
from powergraph.statics.friction import MAX_PASSES, friction_meshes, mesh_friction
from powergraph.units_si import RAD_S_PER_RPM
from powergraph.statics.ports import flow_efficiency_of_roles
from powergraph.statics.verdicts import VERDICTS, verdict_of

#: The single solve's convergence test (the default of ``solve_with_friction``): no
#: efficiency changes by more than this, no bearing torque by more than this times the
#: largest torque of the train.
TOLERANCE = 1e-12
#: A balance whose condition number reaches this is solved one point at a time (as the
#: single solve then falls back to a least-squares solution).
MAX_CONDITION = 1e12


@record
class GridSolution:
    """Efficiency, input power (W, into the train at the input) and output power (W, taken
    out at the output: negative where the output drives) per point, and the verdict as a
    code into :data:`~powergraph.statics.verdicts.VERDICTS` (-1 where there is no answer);
    ``unconverged`` marks points whose passes did not converge (efficiency NaN);
    ``single_solves`` counts points solved one by one."""

    efficiency: np.ndarray
    input_power: np.ndarray
    unconverged: np.ndarray
    single_solves: int
    output_power: np.ndarray
    verdicts: np.ndarray


def solve_grid(model: Model, speeds_rpm: np.ndarray, torques: np.ndarray) -> GridSolution:
    """Solve ``model`` at input speeds ``speeds_rpm[p]`` (rpm) with output loads
    ``torques[p]`` (N·m; > 0 resisting the output's motion, < 0 driving it: coasting), all
    points at once.

    Parameters
    ----------
    model : Model
        A 1-DOF train with one input and one output port (their loads are replaced).
    speeds_rpm, torques : ndarray
        One value per point (same shape, 1-D).

    Returns
    -------
    GridSolution

    A train with a heat balance (``thermal:``) is solved point by point: each point
    settles its own oil temperature, as its single solve does.
    """
    from powergraph.analyses.sweep.layout import refuse_shared_ports

    refuse_shared_ports(model, "the efficiency grid")
    sense = float(np.sign(solve_speeds(model).ratio or 1.0))
    efficiency, power, taken = (np.full(speeds_rpm.shape, np.nan) for _ in range(3))
    verdicts = np.full(speeds_rpm.shape, -1, dtype=np.int8)
    pending = np.ones(speeds_rpm.shape, dtype=bool)
    # a heat balance settles each point's own oil temperature: single solves only
    for speed_sign in (1.0, -1.0) if model.thermal is None else ():
        for torque_sign in (1.0, -1.0, 0.0):
            group = np.flatnonzero((np.sign(speeds_rpm) == speed_sign)
                                   & (np.sign(torques) == torque_sign))
            done = _batch(model, speeds_rpm[group], torques[group], sense) \
                if group.size else None
            if done is not None:
                ok, eta, p_in, p_out, code = done
                points = group[ok]
                efficiency[points], power[points], taken[points] = eta[ok], p_in[ok], p_out[ok]
                verdicts[points] = code
                pending[points] = False
    unconverged = np.zeros(speeds_rpm.shape, dtype=bool)
    for p in np.flatnonzero(pending):
        try:
            result = solve(at_point(model, speeds_rpm[p] * RAD_S_PER_RPM, torques[p], sense))
        except SolveError:
            unconverged[p] = True
            continue
        efficiency[p], power[p], taken[p] = _eta(result), result.input_power, \
            result.output_power
        verdicts[p] = VERDICTS.index(verdict_of(result))
    return GridSolution(efficiency=efficiency, input_power=power, unconverged=unconverged,
                        single_solves=int(np.count_nonzero(pending)), output_power=taken,
                        verdicts=verdicts)


def at_point(model: Model, speed: float, torque: float, sense: float) -> Model:
    """``model`` at input speed ``speed`` (rad/s) with output load ``torque`` (N·m): the
    load opposes the output's motion when ``torque`` > 0 and drives it when < 0 (the
    train coasting, back-driven from its output)."""
    model = model.with_port(model.inputs[0].index, speed=speed, power=None, torque=None)
    # The load opposes the output's motion, whose sense is the input's over the ratio
    # (a negative load aids it).
    return model.with_port(model.outputs[0].index, speed=None, power=None,
                           torque=-float(torque) * float(np.sign(speed) * sense))


def _batch(model: Model, speeds_rpm: np.ndarray, torques: np.ndarray,
           sense: float) -> tuple[np.ndarray, ...] | None:
    """``(settled, efficiency, input power, output power, verdict code)`` of points whose
    input speeds share a sign and whose output torques do, or None when the train's
    balance is not a square system with one consistent pattern at a reference point (the
    first, middle or last that converges; then every point is solved alone). A settled
    point's verdict is the reference's: it has its pattern and its port powers' signs."""
    reference = None
    for p in dict.fromkeys((0, speeds_rpm.size // 2, speeds_rpm.size - 1)):
        try:
            reference = solve(at_point(model, speeds_rpm[p] * RAD_S_PER_RPM, torques[p], sense))
            break
        except SolveError:
            continue
    if reference is None or reference.lock is not None or reference.search is not None:
        return None
    grid = _Grid.build(model, speeds_rpm, torques, sense, reference)
    if grid is None:
        return None
    done = grid.iterate(TOLERANCE, MAX_PASSES)
    return None if done is None else (*done, VERDICTS.index(verdict_of(reference)))


@record
class _Grid:
    """The arrays of one batch: ``P`` points, bodies ``B`` (rows), elements then unknown
    external torques (columns)."""

    model: Model
    elements: tuple
    codes: np.ndarray          # the assumed driver code per element (+1 a, -1 b, 0)
    row: dict
    unknown: tuple
    out_row: int
    given: np.ndarray          # (P,) the output's load torque
    speeds: np.ndarray         # (P, B) body speeds, rad/s
    rel: np.ndarray            # (P, E) w_a - w_c, round-off set to 0
    frictions: dict
    bearings: list
    signs: tuple               # the reference's signs of the input and output powers

    @classmethod
    def build(cls, model: Model, speeds_rpm: np.ndarray, torques: np.ndarray, sense: float,
              reference: Any) -> "_Grid | None":
        elements = elements_of(model)
        row = {body.id: r for r, body in enumerate(model.bodies)}
        values, inverse = np.unique(speeds_rpm, return_inverse=True)
        kins = [solve_speeds(at_point(model, v * RAD_S_PER_RPM, torques[0], sense)) for v in values]
        loads = loads_of(at_point(model, values[0] * RAD_S_PER_RPM, torques[0], sense), kins[0])
        out_body = model.body_of[model.outputs[0].component]
        if set(loads.given) != {out_body} or \
                len(model.bodies) != len(elements) + len(loads.unknown):
            return None
        codes = np.array([1 if f.driver is not None and f.driver == f.a else
                          -1 if f.driver is not None else 0 for f in reference.elements])
        speeds = np.array([[k.body_speeds[b.id] for b in model.bodies] for k in kins])[inverse]
        rel = np.array([relative_speeds(elements, k) for k in kins])[inverse]
        given = -torques * np.sign(speeds_rpm) * sense
        return cls(model, elements, codes, row, loads.unknown, row[out_body], given, speeds,
                   rel, friction_meshes(model), _bearing_specs(model, row, elements),
                   (np.sign(reference.input_power), np.sign(reference.output_power)))

    def factors(self, eta: np.ndarray) -> np.ndarray:
        """``(P, E)`` element factors: η where gear a drives, 1/η where b drives, else 1."""
        return factors_for(self.codes, eta)

    def balance(self, factors: np.ndarray, extra: np.ndarray) -> tuple[np.ndarray, ...]:
        """The stacked torque balances ``(P, B, B)``, their right-hand sides and solutions."""
        system = system_of(list(self.row), self.elements, self.unknown)
        matrix = system.balance([[el.ratio] for el in self.elements], factors.T)
        rhs = -extra.copy()
        rhs[:, self.out_row] -= self.given
        return matrix, rhs, np.linalg.solve(matrix, rhs[..., None])[..., 0]

    def iterate(self, tolerance: float, max_passes: int) -> tuple[np.ndarray, ...] | None:
        """The passes of ``solve_with_friction`` on every point: start ideal without
        bearing torques; solve; update the efficiencies and bearing torques; a point
        settles at the first pass whose updates are within ``tolerance`` and keeps that
        pass's values. Returns ``(accepted, efficiency, input power, output power)``, or
        None when a balance is singular (then every point is solved alone)."""
        n_points, n_el = self.rel.shape
        eta = np.tile([el.efficiency for el in self.elements], (n_points, 1))
        for k, f in self.frictions.items():
            column = self._column(k)
            eta[:, column] = 1.0 if f.load_dependent else f.efficiency()[1]
        extra = np.zeros((n_points, len(self.row)))
        settled = np.zeros(n_points, dtype=bool)
        broken = np.zeros(n_points, dtype=bool)        # a coefficient left [0, 1): alone
        out = np.full((4, n_points), np.nan)   # efficiency, input and output power, agrees
        for _ in range(max_passes):
            factors = self.factors(eta)
            try:
                matrix, rhs, x = self.balance(factors, extra)
            except np.linalg.LinAlgError:
                return None
            new_eta, valid = self._efficiencies(eta, factors, x)
            broken |= ~valid & ~settled
            new_extra = self._bearing_torques(factors, x)
            change = np.max(np.abs(new_eta - eta), axis=1, initial=0.0)
            moved = self._moved(extra, new_extra, rhs, x)
            now = ~settled & ~broken & (change <= tolerance) & (moved <= tolerance)
            if np.any(now):
                out[:, now] = self._outputs(matrix[now], rhs[now], x[now], factors[now],
                                            now)
                settled |= now
            if (settled | broken).all():
                break
            eta, extra = new_eta, new_extra
        ok = settled & (out[3] > 0)
        return ok, out[0], out[1], out[2]

    def _column(self, link: int) -> int:
        return next(k for k, el in enumerate(self.elements) if el.link == link)

    def _efficiencies(self, eta: np.ndarray, factors: np.ndarray,
                      x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The friction meshes' efficiencies at the forces and speeds of ``x``
        (:func:`powergraph.statics.friction.mesh_friction`, the single solve's law), and
        where every coefficient is in [0, 1) (elsewhere the single solve refuses it)."""
        new = eta.copy()
        valid = np.ones(x.shape[0], dtype=bool)
        for link, friction in self.frictions.items():
            if not friction.load_dependent:
                continue
            k = self._column(link)
            el = self.elements[k]
            torque_1 = gear_torque(el.ratio, x[:, k], factors[:, k], friction.gear_1 == el.a)
            gear = self.row[self.model.body_of[friction.gear_1]]
            relative = self.speeds[:, gear] - self.speeds[:, self.row[el.body_c]]
            instances = max(self.model.components[c].count for c in (el.a, el.b))
            _, _, mu, new[:, k] = mesh_friction(friction, torque_1, relative, instances)
            valid &= (mu >= 0.0) & (mu < 1.0)
        return new, valid

    def _bearing_torques(self, factors: np.ndarray, x: np.ndarray) -> np.ndarray:
        """``(P, B)`` the bearings' and drags' torques on the bodies (as
        :func:`powergraph.statics.bearings.bearing_states`: the same tooth forces, law
        and sense)."""
        torques = np.zeros((x.shape[0], len(self.row)))
        for spec in self.bearings:
            rel = relative_speed(self.speeds[:, spec["rows"][0]], self.speeds[:, spec["rows"][1]])
            load = np.zeros(x.shape[0])
            for k, on_a_side, radius, count in spec["meshes"]:
                load += np.abs(tooth_force(self.elements[k].ratio, x[:, k], factors[:, k],
                                           on_a_side, radius, count))
            total = bearing_torque(spec["count"], spec["friction"], spec["drag"], load, rel)[2]
            on_first, on_second = body_torques(total, rel)
            torques[:, spec["rows"][0]] += on_first
            torques[:, spec["rows"][1]] += on_second
        return torques

    def _moved(self, extra: np.ndarray, new: np.ndarray, rhs: np.ndarray,
               x: np.ndarray) -> np.ndarray:
        """The bearing iteration's convergence test on every point
        (:func:`powergraph.statics.bearings.torque_change`): the torques acting are the
        given ones with the bearings' and the solved external torques."""
        free = np.ones(len(self.row), dtype=bool)
        free[[self.row[b] for b in self.unknown]] = False
        acting = np.concatenate([-rhs[:, free], x[:, len(self.elements):]], axis=1)
        return torque_change(extra, new, acting)

    def _outputs(self, matrix: np.ndarray, rhs: np.ndarray, x: np.ndarray,
                 factors: np.ndarray, mask: np.ndarray) -> np.ndarray:
        """Efficiency, input power, output power and whether the point is accepted (its
        forces agree with the assumed pattern, its port powers have the reference's signs
        and its balance is well conditioned)."""
        n_el = len(self.elements)
        speeds = self.speeds[mask]
        w_in = speeds[:, self.row[self.model.body_of[self.model.inputs[0].component]]]
        t_in = x[:, n_el + self.unknown.index(
            self.model.body_of[self.model.inputs[0].component])]
        p_in = t_in * w_in
        p_out = -self.given[mask] * speeds[:, self.out_row]
        found = self._pattern(matrix, rhs, x, factors, mask)
        agrees = np.all((found == 0) | (found == self.codes), axis=1)
        agrees &= (np.sign(p_in) == self.signs[0]) & (np.sign(p_out) == self.signs[1])
        agrees &= np.linalg.cond(matrix) < MAX_CONDITION
        return np.array([flow_efficiency_of_roles(p_in, p_out), p_in, p_out,
                         agrees.astype(float)])

    def _pattern(self, matrix: np.ndarray, rhs: np.ndarray, x: np.ndarray,
                 factors: np.ndarray, mask: np.ndarray) -> np.ndarray:
        """Who drives each element at ``x`` (as :func:`powergraph.statics.directions.
        pattern_of`, with :func:`~powergraph.statics.directions.force_scales`)."""
        n_el = len(self.elements)
        external = -rhs.copy()
        for j, body in enumerate(self.unknown):
            external[:, self.row[body]] = x[:, n_el + j]
        bodies = np.array([[self.row[b] for b in el.bodies] for el in self.elements],
                          dtype=np.int64).reshape(-1, 3)
        ratios = np.array([el.ratio for el in self.elements], dtype=float)
        scales = own_scales(bodies, ratios, x[:, :n_el].T, factors.T, np.abs(external).T,
                            self.row[self.model.frame_body]).T
        return driver_codes(x[:, :n_el], self.rel[mask], scales)


def _bearing_specs(model: Model, row: dict, elements: tuple) -> list[dict]:
    """What :func:`powergraph.statics.bearings.bearing_states` reads, per loss source
    (:func:`powergraph.statics.loss_sources.torque_sources`): the two bodies' rows, the
    instances, the laws and the meshes loading it (as element columns)."""
    column = {el.link: k for k, el in enumerate(elements)}
    return [{"rows": tuple(row[model.body_of[c]] for c in source.between),
             "count": source.instances, "friction": source.friction, "drag": source.drag,
             "meshes": [(column[mesh], gear == elements[column[mesh]].a, radius, count)
                        for mesh, gear, radius, count in source.loaded_by]}
            for source in torque_sources(model)]


def _eta(result) -> float:
    """The solve's efficiency (from the actual flows), NaN when no power passes."""
    return float("nan") if result.efficiency is None else result.efficiency
