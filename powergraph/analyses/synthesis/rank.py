"""Figures of merit of the feasible tooth sets, vectorised, and their ranking.

Each arrangement (graph, layout, fixed, input, output) with hits is built once as a model
and compiled once with :func:`powergraph.analyses.sweep.compile_sweep`, forward and driven
from its output (:func:`powergraph.kinematics.backdriven`): one call per direction gives
the ratio, efficiency, self-locking flag and every mesh loss of all its tooth sets. A
mesh's loss is ``(1 - eta)`` times the power it passes in its carrier's frame (its
virtual power), so the largest virtual power over the input power is
``max(loss) / ((1 - eta) P_in)``.

Within an arrangement the best tooth set is the one with the highest efficiency, then
back-driven efficiency, then the smallest largest virtual power. Across arrangements
(:func:`rank_key`) rows are ordered by efficiency and back-driven efficiency (each to
0.1 percentage point), circulating power over input power (to 0.1 %; one ``solve`` of
each arrangement's best tooth set), meshes, and largest virtual power.
"""
from __future__ import annotations

import re
from dataclasses import asdict, field
from typing import Any, Mapping

import numpy as np

from powergraph.analyses.synthesis.naming import (arrangement_name, gear_names, link_names,
                                                  member_names, teeth_text)
from powergraph.analyses.synthesis.synthesize_search import Hits, graph_layouts
from powergraph.analyses.synthesis.teeth import Layout
from powergraph.records import record


@record
class SynthesisRow:
    """One arrangement at its best tooth set, with the ``compare`` table's figures.

    ``teeth`` maps gear ids (``g0a``: side a of gear pair 0) to tooth numbers and
    ``gear_names`` the same ids to readable names (``sun L1``, ``planet L2``, ``ring L0``);
    ``rings`` lists the internal gears; ``candidates`` counts the feasible tooth sets of
    the arrangement. Powers in W.
    """

    name: str
    graph: str
    layout: str
    fixed: int
    input: int
    output: int
    teeth: Mapping[str, int]
    rings: tuple[str, ...]
    ratio: float
    ratio_error: float
    efficiency: float
    self_locking: bool
    backdrive_efficiency: float | None
    backdrive_self_locking: bool | None
    circulating_power: float
    max_virtual_power_ratio: float | None
    meshes: int
    input_power: float
    candidates: int
    document: Mapping[str, Any]
    gear_names: Mapping[str, str] = field(default_factory=dict)
    members: Mapping[str, str] = field(default_factory=dict)

    def to_dict(self) -> dict[str, Any]:
        """Every field but the model document (see :meth:`model_document`)."""
        out = asdict(self)
        out.pop("document")
        out["teeth"] = dict(self.teeth)
        out["rings"] = list(self.rings)
        out["gear_names"] = dict(self.gear_names)
        out["members"] = dict(self.members)
        return out

    def drive_text(self) -> str:
        """``sun 1 in, carrier 2 out, ring 1+ring 2 fixed``: the members by role and set
        (:func:`~powergraph.analyses.synthesis.naming.member_names`)."""
        name = {n: self.members.get(f"L{n}", f"L{n}") for n in (self.input, self.output,
                                                                 self.fixed)}
        note = self.name.split("; ", 1)[1] if "; " in self.name else ""
        note = re.sub(r"L\d+", lambda m: self.members.get(m[0], m[0]), note)
        return (f"{name[self.input]} in, {name[self.output]} out, "
                f"{name[self.fixed]} fixed" + (f"; {note}" if note else ""))

    def member_teeth_text(self) -> str:
        """The tooth numbers by member: ``sun=12, planet=54, ring=120``."""
        names = {g: self.members.get(n.split(" ")[-1], n) for g, n in self.gear_names.items()}
        return teeth_text(self.teeth, names)

    def teeth_text(self) -> str:
        """``sun L1=12, planet L2=45, ring L0=102`` (gear ids where no name is known)."""
        return teeth_text(self.teeth, self.gear_names)

    def model_document(self) -> dict[str, Any]:
        """The powergraph model of this train (``model_from_dict`` takes it)."""
        import copy

        return copy.deepcopy(dict(self.document))


def gear_teeth(layout: Layout, flat: np.ndarray) -> dict[str, np.ndarray]:
    """``{"g0a": teeth, ...}`` (component ids of ``TrainGraph.to_model_dict``)."""
    return {f"g{k}{'ab'[s]}": v for (k, s), v in sorted(layout.teeth(flat).items())}


def evaluate_hits(graph, hits: Hits, ratio: float, teeth_range: tuple[int, int],
                  planets: int, mesh_efficiency: float) -> SynthesisRow | None:
    """The best tooth set of one arrangement, its row (circulating power by one solve).

    Tooth sets with an idle mesh (no loss: a coaxial link that is neither fixed, input
    nor output turns freely, so the train is a smaller one with a passenger) and those the
    solver cannot settle are left out; None when none is left."""
    from powergraph.kinematics import backdriven
    from powergraph.model import model_from_dict
    from powergraph.statics import solve

    layout = graph_layouts(graph, teeth_range, planets)[hits.layout]
    teeth = gear_teeth(layout, hits.flat)
    doc = _document(layout, hits, {g: int(v[0]) for g, v in teeth.items()}, mesh_efficiency)
    model = model_from_dict(doc)
    paths = [f"components.{g}.teeth" for g in teeth]
    values = {f"components.{g}.teeth": v for g, v in teeth.items()}
    forward = _sweep(model, paths, values)
    eff = np.where(forward.converged, forward.efficiency, -np.inf)
    working = forward.converged & ~_idle(forward, mesh_efficiency, len(graph.gear_pairs))
    if not working.any():
        return None
    # the back-driven figures only break ties of the forward efficiency
    tied = np.flatnonzero(working & (eff == eff[working].max()))
    back = _sweep(backdriven(model), paths, {p: v[tied] for p, v in values.items()})
    back_eff = np.where(back.converged, back.efficiency, -np.inf)
    pv = _max_virtual_power(forward, mesh_efficiency)
    j = int(np.lexsort((np.nan_to_num(pv[tied], nan=np.inf), -back_eff))[0])
    best = int(tied[j])
    chosen = {g: int(v[best]) for g, v in teeth.items()}
    doc = _document(layout, hits, chosen, mesh_efficiency)
    single = solve(model_from_dict(doc))
    back_ok = bool(back.converged[j])
    return SynthesisRow(
        name=arrangement_name(layout, hits.fixed, hits.input, hits.output),
        graph=graph.name or f"{graph.links}-link", layout=layout.name, fixed=hits.fixed,
        input=hits.input, output=hits.output, teeth=chosen,
        rings=tuple(f"g{k}{'ab'[s]}" for k, s in sorted(layout.internal.items())),
        ratio=float(forward.ratio[best]), ratio_error=float(forward.ratio[best] / ratio - 1.0),
        efficiency=float(forward.efficiency[best]),
        self_locking=bool(forward.self_locking[best]),
        backdrive_efficiency=float(back.efficiency[j]) if back_ok else None,
        backdrive_self_locking=bool(back.self_locking[j]) if back_ok else None,
        circulating_power=float(single.circulating_power),
        max_virtual_power_ratio=None if np.isnan(pv[best]) else float(pv[best]),
        meshes=len(graph.gear_pairs), input_power=float(forward.input_power[best]),
        candidates=int(working.sum()), document=doc,
        gear_names=gear_names(layout), members=member_names(layout))


#: Tooth sets of one arrangement from which the compiled sweep takes its closed forms
#: (``backend="auto"``: about 0.3 s to derive and compile, then some 2·10⁶ sets a
#: second) rather than its batched linear solves (no set-up, some 3·10⁴ a second).
SYMBOLIC_FROM = 10_000


def _sweep(model, paths: list[str], values: dict[str, np.ndarray]):
    """The compiled sweep of ``model`` over ``values`` (one call, backend by size)."""
    from powergraph.analyses.sweep import compile_sweep

    size = len(next(iter(values.values())))
    backend = "auto" if size >= SYMBOLIC_FROM else "numeric"
    return compile_sweep(model, paths, backend=backend)(values, quiet=True)


def _document(layout: Layout, hits: Hits, teeth: Mapping[str, int], mesh_efficiency: float
              ) -> dict[str, Any]:
    pairs = {(int(g[1:-1]), "ab".index(g[-1])): z for g, z in teeth.items()}
    name = arrangement_name(layout, hits.fixed, hits.input, hits.output)
    names = {f"L{n}": text for n, text in link_names(layout, hits.fixed).items()}
    names.update(gear_names(layout))
    planets = set(layout.structure.planets())      # replicated: `planets` identical copies
    counts = {f"L{p}": layout.planets for p in planets}
    counts.update({f"g{k}{'ab'[side]}": layout.planets
                   for k, pair in enumerate(layout.graph.gear_pairs)
                   for side, link in enumerate(pair[:2]) if link in planets})
    return layout.graph.to_model_dict(frame=hits.fixed, inputs=(hits.input,),
                                      outputs=(hits.output,), teeth=pairs,
                                      internal=layout.internal,
                                      mesh_efficiency=mesh_efficiency, name=name,
                                      names=names, counts=counts)


def _idle(result, mesh_efficiency: float, meshes: int) -> np.ndarray:
    """Some mesh (links ``0 .. meshes-1``; couplings are ideal) passes no power, detected
    from its loss (ideal meshes cannot tell)."""
    if mesh_efficiency >= 1.0 or meshes == 0:
        return np.zeros(result.shape, dtype=bool)
    smallest = np.min(np.stack([np.abs(np.asarray(result.losses[k])) for k in range(meshes)]),
                      axis=0)
    return ~(smallest > 1e-9 * np.abs(result.input_power))


def _max_virtual_power(result, mesh_efficiency: float) -> np.ndarray:
    """Largest mesh virtual power over input power (NaN when the meshes are ideal, and
    for a set that takes no input power: one the ranking leaves out as idle)."""
    if mesh_efficiency >= 1.0 or not result.losses:
        return np.full(result.shape, np.nan)
    largest = np.max(np.stack([np.asarray(v) for v in result.losses.values()]), axis=0)
    power = np.asarray(result.input_power, dtype=float)
    return np.divide(largest / (1.0 - mesh_efficiency), power,
                     out=np.full(largest.shape, np.nan), where=power != 0.0)


def rank_key(row: SynthesisRow) -> tuple:
    """Sort key: efficiency, back-driven efficiency (to 0.1 pp, higher first), circulating
    power over input (to 0.1 %), meshes, largest virtual power and ratio error (to 9
    decimals), then name and teeth (a total order)."""
    back = row.backdrive_efficiency if row.backdrive_efficiency is not None else -np.inf
    circulating = row.circulating_power / row.input_power if row.input_power else 0.0
    pv = row.max_virtual_power_ratio
    # the figures to 9 decimals: equal trains (mirror images) computed along different
    # paths differ in the last bits, and their name should decide, not round-off
    return (-round(row.efficiency, 3), -round(back, 3), round(circulating, 3), row.meshes,
            round(pv, 9) if pv is not None else np.inf, round(abs(row.ratio_error), 9),
            row.name, tuple(sorted(row.teeth.items())))


def signature(row: SynthesisRow) -> tuple:
    """Rows equal in graph, figures and tooth multiset describe one train (an arrangement
    and its mirror image, e.g. the sun/ring labels of a symmetric graph swapped)."""
    return (row.graph, round(row.ratio, 9), round(row.efficiency, 9),
            tuple(sorted(row.teeth.values())), row.meshes)
