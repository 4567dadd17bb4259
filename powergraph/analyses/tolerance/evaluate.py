"""The vectorised evaluator: toleranced values of many units -> their outputs.

Built once per model, then called on columns of sampled values (one array per PATH); no
Python loop runs over the units.

- **Lost motion** (arc-minutes at the output, worst case within a unit): the plays of the
  meshes add, each referred to the output through the kinematic sensitivity ``S_k`` of
  :func:`powergraph.analyses.backlash.analyse_backlash` (inputs held):
  ``Σ |S_k|·play_k``. A ``backlash:`` block's play is recomputed per unit by the same
  functions as the nominal analysis (Eqs. 1-3, 7 of Li et al. 2012), which are linear in M,
  runout and bearing clearance and take arrays.
- **Fluctuation** (% at the output, each cycloid stage alone, the largest): the exact
  :func:`powergraph.analyses.cycloid.train_fluctuation` is tabulated once on a grid of the
  profile error ``d`` over the distribution's support (plus the nominal ``d``, so the
  nominal is reproduced exactly) and interpolated linearly. The curve is close to linear
  (Csobán's design formula ``Δi = a·d + b·d·z1^−1.5`` is linear in ``d``); the table's own
  second differences bound the interpolation error (``h²/8·max|f''|``), reported as
  ``interpolation_error_bound``.
- **Efficiency**: the compiled sweep :func:`powergraph.analyses.sweep.compile_sweep` over
  the toleranced efficiencies (NaN where a unit's power directions do not settle).
"""
from __future__ import annotations

import dataclasses
import math
from typing import Mapping

import numpy as np

from powergraph.model.block_tolerances import Tolerances
from powergraph.errors import ModelError
from powergraph.records import record

#: Nodes of the fluctuation table over the support of the profile error.
TABLE_NODES = 6
OUTPUTS = ("lost_motion_arcmin", "fluctuation_percent", "efficiency")


class ToleranceEvaluator:
    """Outputs of many units from columns of their toleranced values.

    Parameters
    ----------
    model : Model
        A model with a ``tolerances:`` block (or give ``tolerances``).
    tolerances : Tolerances, optional
        Overrides the model's block.

    Examples
    --------
    >>> import numpy as np
    >>> from powergraph.model import loads_model
    >>> m = loads_model('''
    ... name: pair
    ... components: {0: {role: frame}, 1: {teeth: 20}, 2: {teeth: 60}}
    ... links: [{type: mesh, between: [1, 2], backlash_arcmin: 6.0}]
    ... ports: [{component: 1, role: input}, {component: 2, role: output}]
    ... tolerances: {links.0.backlash_arcmin: {distribution: uniform, min: 3, max: 9}}
    ... ''')
    >>> out = ToleranceEvaluator(m)({"links.0.backlash_arcmin": np.array([3.0, 9.0])})
    >>> np.round(out["lost_motion_arcmin"], 12).tolist()     # a third at the wheel
    [1.0, 3.0]
    """

    def __init__(self, model, tolerances: Tolerances | None = None) -> None:
        self.model = model
        self.tolerances = tolerances if tolerances is not None else model.tolerances
        if self.tolerances is None or not len(self.tolerances):
            raise ModelError("the model has no tolerances: block (PATH: distribution)",
                             "tolerances")
        self._by_value = {(t.target.kind, link, t.target.key): t.path
                          for t in self.tolerances.entries for link in t.target.links}
        self.backlash = _backlash_report(model)
        self.tables = self._fluctuation_tables()
        efficiency = [t.path for t in self.tolerances.entries if t.target.kind == "efficiency"]
        self._sweep = None
        if efficiency:
            from powergraph.analyses.sweep.compile import refuse_loss_blocks
            from powergraph.analyses.sweep.entry import compile_sweep

            refuse_loss_blocks(model, "the tolerance analysis's efficiency")
            self._sweep = compile_sweep(model, efficiency)

    @property
    def outputs(self) -> tuple[str, ...]:
        """The outputs this model has (lost motion with play data, fluctuation with a
        ``cycloid:`` block, efficiency when an efficiency is toleranced)."""
        present = (self.backlash is not None, bool(self.tables), self._sweep is not None)
        return tuple(name for name, ok in zip(OUTPUTS, present) if ok)

    def __call__(self, columns: Mapping[str, np.ndarray]) -> dict[str, np.ndarray]:
        """``{output: array}`` for units whose toleranced values are ``columns``."""
        size = len(next(iter(columns.values()))) if columns else 1
        out: dict[str, np.ndarray] = {}
        if self.backlash is not None:
            out["lost_motion_arcmin"] = self._lost_motion(columns, size)
        if self.tables:
            out["fluctuation_percent"] = self._fluctuation(columns, size)
        if self._sweep is not None:
            values = {p: columns[p] for p in self._sweep.paths}
            out["efficiency"] = np.asarray(self._sweep(values, quiet=True).efficiency)
        return out

    def _value(self, columns, kind: str, link: int, key, nominal):
        path = self._by_value.get((kind, link, key))
        return columns[path] if path is not None else nominal

    # -- lost motion -------------------------------------------------------------------
    def _lost_motion(self, columns, size: int) -> np.ndarray:
        total = np.zeros(size)
        for mesh in self.backlash.meshes:
            play = self._play(columns, mesh)
            total = total + abs(mesh.sensitivity) * play
        return total

    def _play(self, columns, mesh):
        if mesh.source == "backlash_arcmin":
            return self._value(columns, "backlash_arcmin", mesh.link, None, mesh.play_arcmin)
        from powergraph.analyses.backlash import lost_motion_arcmin
        from powergraph.analyses.backlash.pair import _backlash_terms

        link = self.model.links[mesh.link]
        block, pair = link.blocks["backlash"], mesh.pair
        get = lambda kind, key, nominal: self._value(columns, kind, mesh.link, key, nominal)
        used = {block.internal: get("measured_M", block.internal,
                                    min(block.measured_M[block.internal])),
                block.external: get("measured_M", block.external,
                                    max(block.measured_M[block.external]))}
        deviation = [used[g] - block.standard_M[g] for g in (block.internal, block.external)]
        runout = tuple(get("runout", g, block.runout.get(g, 0.0))
                       for g in (block.internal, block.external))
        bearings = tuple(get("bearing_clearance", k, u)
                         for k, u in enumerate(block.bearing_clearance))
        terms = _backlash_terms(*deviation, runout, bearings, math.radians(block.pressure_angle))
        j_t = terms["after" if pair.assembly == "compensated" else "before"]
        gear_a = link.between[0]
        return lost_motion_arcmin(j_t, pair.module, pair.teeth[gear_a])

    # -- fluctuation ---------------------------------------------------------------------
    def _fluctuation_tables(self) -> dict[int, "FluctuationTable"]:
        links = [link for link in self.model.meshes if "cycloid" in link.blocks]
        spread = {t.target.links[0]: t.distribution for t in self.tolerances.entries
                  if t.target.kind == "profile_error"}
        return {link.index: fluctuation_table(self.model, link.index, spread.get(link.index))
                for link in links}

    def _fluctuation(self, columns, size: int) -> np.ndarray:
        worst = np.zeros(size)
        for link, table in self.tables.items():
            d = self._value(columns, "profile_error", link, None, table.nominal_error)
            worst = np.maximum(worst, table(d))
        return worst


@record
class FluctuationTable:
    """The train's fluctuation (%) of one cycloid mesh against its profile error (mm)."""

    link: int
    errors: np.ndarray
    values: np.ndarray
    nominal_error: float

    def __call__(self, d) -> np.ndarray:
        return np.interp(d, self.errors, self.values)

    @property
    def error_bound(self) -> float:
        """Estimated largest error of the linear interpolation: ``h²/8·max|f''|`` with
        ``f''`` from the table's second divided differences (0 for fewer than 3 nodes)."""
        x, y = self.errors, self.values
        if len(x) < 3:
            return 0.0
        h = np.diff(x)
        slopes = np.diff(y) / h
        curvature = np.abs(np.diff(slopes)) / ((h[:-1] + h[1:]) / 2.0)
        return float(np.max(curvature) * np.max(h) ** 2 / 8.0)


def fluctuation_table(model, link_index: int, distribution=None,
                      nodes: int = TABLE_NODES) -> FluctuationTable:
    """Tabulate :func:`train_fluctuation` of ``links[link_index]`` over the profile error.

    The grid spans the distribution's support with ``nodes`` evenly spaced values and
    includes the nominal error; without a distribution only the nominal is computed.
    """
    from powergraph.analyses.cycloid import train_fluctuation

    link = model.links[link_index]
    block = link.blocks["cycloid"]
    grid = {block.profile_error}
    if distribution is not None and distribution.high > distribution.low:
        grid.update(np.linspace(distribution.low, distribution.high, nodes).tolist())
    errors = np.array(sorted(grid))
    values = np.empty_like(errors)
    for i, d in enumerate(errors):
        blocks = dict(link.blocks)
        blocks["cycloid"] = dataclasses.replace(block, profile_error=float(d))
        stages = train_fluctuation(model.with_link(link_index, blocks=blocks)).stages
        values[i] = next(s.max_deviation_percent for s in stages if s.link == link_index)
    errors.setflags(write=False)
    values.setflags(write=False)
    return FluctuationTable(link_index, errors, values, block.profile_error)


def _backlash_report(model):
    """The nominal :class:`BacklashReport`, or None when no mesh carries play data."""
    if not any("backlash" in link.blocks or "backlash_arcmin" in link.blocks
               for link in model.meshes):
        return None
    from powergraph.analyses.backlash import analyse_backlash

    return analyse_backlash(model)
