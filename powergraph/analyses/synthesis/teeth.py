"""Tooth layouts of a train graph and the geometric conditions on their tooth numbers.

A :class:`~powergraph.analyses.synthesis.graph.TrainGraph` says which links mesh; it does
not say which coaxial gear is a sun and which a ring, nor which planet gears are one gear.
A **layout** decides that, and leaves integer grids of tooth numbers that satisfy, by
construction or by a vectorised filter (docs/synthesis.md):

- **coaxiality** — every mesh of a planet link with a coaxial gear has the same centre
  distance (equal module on one carrier): ``z_sun + z_p = z_ring - z_p'`` in half-modules;
- **neighbour** — the tip circles (``z + 2`` modules) of adjacent planets clear:
  ``z + 2 < D sin(pi / n)`` with ``D`` the centre distance in half-modules;
- **assembly** — ``n`` identical planets fit at equal spacing (:func:`assembles`);

(the conditions themselves live in :mod:`powergraph.gears.planetary`, shared with the
model's feasibility caveats);
- internal pairs differ by at least :data:`MIN_INTERNAL_DIFFERENCE` teeth (involute rule
  of thumb against tip interference), except the one-tooth cycloid/pin pair of a K-H-V
  stage (a planet joined to a coaxial link by a coupling).

Examples
--------
>>> from powergraph.analyses.synthesis.synthesize_classics import CLASSICS
>>> [layout.name for layout in layouts(CLASSICS["2K-H"])]
['simple', 'simple', 'stepped', 'stepped', 'stepped', 'stepped']
"""
from __future__ import annotations

import functools
import itertools
from collections import Counter
from typing import Iterator, Mapping

import numpy as np

from powergraph.analyses.synthesis.graph import TrainGraph
# The conditions themselves (one copy, shared with the model's feasibility caveats):
from powergraph.gears.planetary import assembles, neighbours_clear  # noqa: F401
from powergraph.gears.planetary import centre_distance as planet_centre
from powergraph.records import record

#: Smallest tooth difference of an internal involute pair (ring - planet).
MIN_INTERNAL_DIFFERENCE = 10
#: Tooth difference of the K-H-V (cycloid) stage: one pin more than lobes.
KHV_DIFFERENCE = 1


@record
class Structure:
    """Which links turn about the main axis, what each planet turns on, each pair's kind.

    ``kinds[k]`` is ``"cp"`` (coaxial gear with a planet), ``"pp"`` (two planets on one
    carrier) or ``"khv"`` (a coupled planet meshing a ring); ``coaxial_side[k]`` the side
    of pair ``k`` on a coaxial link (None for ``pp``).
    """

    main_axis: int
    coaxial: tuple[int, ...]
    parent: Mapping[int, int]
    coupled: frozenset[int]
    kinds: tuple[str, ...]
    coaxial_side: tuple[int | None, ...]

    def planets(self) -> tuple[int, ...]:
        """The replicated planets: not coupled, turning on a coaxial link."""
        return tuple(sorted(p for p, c in self.parent.items()
                            if p not in self.coupled and c in self.coaxial))

    def phased(self, planet: int) -> bool:
        """Copies of ``planet`` must be identical in orientation: it carries a link."""
        return any(c == planet for c in self.parent.values())


def structure(graph: TrainGraph) -> Structure | None:
    """The :class:`Structure` of ``graph``, or None when a pair cannot be built (two
    coaxial links meshing, or a gear pair whose carrier does not hold its planet)."""
    count = Counter(a for _, _, a in graph.turning_pairs)
    main = min(count, key=lambda a: (-count[a], a))
    coaxial = sorted({x for u, v, a in graph.turning_pairs if a == main for x in (u, v)})
    parent: dict[int, int] = {}
    frontier = list(coaxial)
    while frontier:
        link = frontier.pop(0)
        for u, v, _ in graph.turning_pairs:
            for a, b in ((u, v), (v, u)):
                if a == link and b not in coaxial and b not in parent:
                    parent[b] = link
                    frontier.append(b)
    coupled = frozenset(x for pair in graph.couplings for x in pair if x not in coaxial)
    kinds, sides = [], []
    for u, v, c in graph.gear_pairs:
        cu, cv = u in coaxial, v in coaxial
        planet = v if cu else u
        if (cu and cv) or any(parent.get(x) != c for x in (u, v) if x not in coaxial):
            return None
        if not (cu or cv):
            kinds.append("pp")
            sides.append(None)
            continue
        kinds.append("khv" if planet in coupled else "cp")
        sides.append(0 if cu else 1)
    return Structure(main, tuple(coaxial), parent, coupled, tuple(kinds), tuple(sides))


@record
class PlanetBlock:
    """The tooth variables of one replicated planet link: its steps and an anchor.

    ``steps[i]`` lists the pairs meshed by step ``i`` (one gear); the anchor is the
    coaxial gear of the first cp pair; ``internal`` the cp pairs whose coaxial gear is a
    ring. ``tuples`` (rows ``steps..., anchor``) are the values in range that satisfy
    coaxiality and the neighbour condition.
    """

    planet: int
    steps: tuple[tuple[int, ...], ...]
    cp_pairs: tuple[int, ...]
    internal: frozenset[int]
    tuples: np.ndarray

    def step_of(self, pair: int) -> int:
        return next(i for i, s in enumerate(self.steps) if pair in s)


@record
class Layout:
    """One way of giving a graph teeth: planet blocks, K-H-V rings, internal gears."""

    name: str
    graph: TrainGraph
    structure: Structure
    blocks: tuple[PlanetBlock, ...]
    khv_pairs: tuple[int, ...]
    teeth_range: tuple[int, int]
    planets: int

    @property
    def internal(self) -> dict[int, int]:
        """``{pair: side}`` of the internal gears (rings), as ``to_model_dict`` takes."""
        out = {k: self.structure.coaxial_side[k] for b in self.blocks for k in b.internal}
        out.update({k: self.structure.coaxial_side[k] for k in self.khv_pairs})
        return out

    @property
    def shape(self) -> tuple[int, ...]:
        lo, hi = self.teeth_range
        return tuple(len(b.tuples) for b in self.blocks) + (hi - lo,) * len(self.khv_pairs)

    @property
    def size(self) -> int:
        return int(np.prod(self.shape, dtype=np.int64))

    def teeth(self, flat: np.ndarray) -> dict[tuple[int, int], np.ndarray]:
        """Teeth ``{(pair, side): array}`` at the flat grid indices ``flat``."""
        index = np.unravel_index(flat, self.shape)
        values = {b.planet: b.tuples[rows] for b, rows in zip(self.blocks, index)}
        blocks = {b.planet: b for b in self.blocks}
        out: dict[tuple[int, int], np.ndarray] = {}
        for block in self.blocks:
            for k, (step, coax) in cp_teeth(block, values[block.planet]).items():
                side = self.structure.coaxial_side[k]
                out[(k, 1 - side)], out[(k, side)] = step, coax
        for k, (u, v, _) in enumerate(self.graph.gear_pairs):
            if self.structure.kinds[k] == "pp":
                for side, link in enumerate((u, v)):
                    out[(k, side)] = values[link][:, blocks[link].step_of(k)]
        lo = self.teeth_range[0]
        for k, rows in zip(self.khv_pairs, index[len(self.blocks):]):
            side = self.structure.coaxial_side[k]
            out[(k, side)] = rows.astype(np.int64) + lo + KHV_DIFFERENCE
            out[(k, 1 - side)] = out[(k, side)] - KHV_DIFFERENCE
        return out

    def centres(self, flat: np.ndarray) -> dict[int, np.ndarray]:
        """Centre distance (half-modules) of each planet link with a coaxial mesh."""
        index = np.unravel_index(flat, self.shape)
        return {b.planet: centre_distance(b, b.tuples[rows])
                for b, rows in zip(self.blocks, index) if b.cp_pairs}


def cp_teeth(block: PlanetBlock, values: np.ndarray) -> dict[int, tuple[np.ndarray, np.ndarray]]:
    """Per cp pair of the block: (planet step teeth, coaxial gear teeth); the coaxial
    teeth follow from the common centre distance."""
    if not block.cp_pairs:
        return {}
    centre = centre_distance(block, values)
    out = {}
    for k in block.cp_pairs:
        step = values[:, block.step_of(k)]
        out[k] = (step, centre + step if k in block.internal else centre - step)
    return out


def centre_distance(block: PlanetBlock, values: np.ndarray) -> np.ndarray:
    """Planet centre distance in half-modules (``z_sun + z_planet``), per row."""
    step0 = values[:, block.step_of(block.cp_pairs[0])]
    return planet_centre(values[:, -1], step0, block.cp_pairs[0] in block.internal)


def _partitions(items: tuple[int, ...]) -> Iterator[list[list[int]]]:
    if not items:
        yield []
        return
    first, rest = items[0], items[1:]
    for part in _partitions(rest):
        for i in range(len(part)):
            yield part[:i] + [[first] + part[i]] + part[i + 1:]
        yield [[first]] + part


def _step_assignments(cp: tuple[int, ...]) -> Iterator[tuple[list[list[int]], frozenset[int]]]:
    """Planet steps (at most two) and ring choices: a step meshes at most one sun and
    one ring (two suns on one step would turn together)."""
    for part in _partitions(cp):
        if len(part) > 2 or any(len(s) > 2 for s in part):
            continue
        per_step = [[frozenset({s[0]}), frozenset({s[1]})] if len(s) == 2
                    else [frozenset(), frozenset(s)] for s in part]
        for rings in itertools.product(*per_step):
            yield sorted(part, key=min), frozenset().union(*rings)


def layouts(graph: TrainGraph, teeth: tuple[int, int] = (12, 120), planets: int = 3
            ) -> list[Layout]:
    """Every layout of ``graph``: planets simple (one gear) or stepped (two), each
    coaxial gear a sun or a ring, with the tuples of each planet block enumerated.

    Planet-planet meshes use the planet's first step. A graph whose structure cannot be
    built gives no layout.
    """
    st = structure(graph)
    if st is None:
        return []
    meshing = {x for u, v, _ in graph.gear_pairs for x in (u, v) if x not in st.coaxial}
    if not meshing <= set(st.planets()) | st.coupled:
        return []           # a planet on a planet (not coupled): not sized here
    per_planet = []
    for p in st.planets():
        cp = tuple(k for k, (u, v, _) in enumerate(graph.gear_pairs)
                   if st.kinds[k] == "cp" and p in (u, v))
        pp = tuple(k for k, (u, v, _) in enumerate(graph.gear_pairs)
                   if st.kinds[k] == "pp" and p in (u, v))
        choices = []
        for part, rings in _step_assignments(cp):
            steps = [tuple(s) for s in part] or [()]
            steps[0] = steps[0] + pp
            choices.append((p, tuple(steps), cp, rings))
        per_planet.append(choices)
    khv = tuple(k for k, kind in enumerate(st.kinds) if kind == "khv")
    out = []
    for combo in itertools.product(*per_planet):
        blocks = tuple(PlanetBlock(p, steps, cp, rings,
                                   block_rows(steps, cp, rings, teeth, planets,
                                              alone=not any(st.kinds[k] == "pp"
                                                            for k in steps[0]),
                                              phased=st.phased(p)))
                       for p, steps, cp, rings in combo)
        name = "+".join("stepped" if len(b.steps) > 1 else "simple" for b in blocks) or (
            "cycloid" if khv else "-")
        out.append(Layout(name, graph, st, blocks, khv, teeth, planets))
    return out


def block_rows(steps, cp, rings, teeth: tuple[int, int], planets: int, alone: bool,
               phased: bool) -> np.ndarray:
    """:func:`_tuples` of a planet block, its gear pairs renamed ``0, 1, ...`` (its cp
    pairs in order, then its planet-planet pairs): the rows depend on which pair is on
    which step and which is a ring, not on the pairs' numbers in the graph, so blocks of
    one shape in different graphs share one cached grid.

    >>> a = block_rows(((3,), (5,)), (3, 5), frozenset({5}), (12, 40), 3, True, False)
    >>> b = block_rows(((0,), (1,)), (0, 1), frozenset({1}), (12, 40), 3, True, False)
    >>> a is b
    True
    """
    local = {k: i for i, k in enumerate(cp)}
    for k in steps[0] if steps else ():
        local.setdefault(k, len(local))
    return _tuples(tuple(tuple(local[k] for k in step) for step in steps),
                   tuple(local[k] for k in cp), frozenset(local[k] for k in rings),
                   teeth, planets, alone, phased)


@functools.lru_cache(maxsize=256)
def _tuples(steps, cp, rings, teeth: tuple[int, int], planets: int, alone: bool,
            phased: bool) -> np.ndarray:
    """Rows (steps..., anchor) in range meeting coaxiality and the neighbour condition,
    and assembly when the planet forms a cluster ``alone`` (no planet-planet mesh)."""
    lo, hi = teeth
    values = _candidate_rows(steps, cp, rings, teeth, planets)
    if not cp:
        return values
    block = PlanetBlock(0, steps, cp, rings, values)
    centre = centre_distance(block, values)
    ok = centre > 0
    for k in cp:
        step = values[:, block.step_of(k)]
        coax = centre + step if k in rings else centre - step
        ok &= (coax >= lo) & (coax <= hi)
        if k in rings:
            ok &= coax - step >= MIN_INTERNAL_DIFFERENCE
    for i in range(len(steps)):
        ok &= neighbours_clear(values[:, i], centre, planets)
    values = values[ok]
    if alone:
        block = PlanetBlock(0, steps, cp, rings, values)
        pairs = cp_teeth(block, values)
        coax = [pairs[k][1] for k in cp]
        coefficients = [pairs[k][0] if k in rings else -pairs[k][0] for k in cp]
        values = values[assembles(coax, coefficients, planets, phased)]
    values.setflags(write=False)
    return values


def _candidate_rows(steps, cp, rings, teeth: tuple[int, int], planets: int) -> np.ndarray:
    """Rows (steps..., anchor): the anchor and its step over the whole range, every other
    step only over the interval its meshes' centre distance allows (a superset of the
    feasible rows, filtered exactly afterwards)."""
    lo, hi = teeth
    axes = np.arange(lo, hi + 1, dtype=np.int64)
    if not cp:
        grids = np.meshgrid(*([axes] * len(steps)), indexing="ij")
        return np.stack([g.ravel() for g in grids], axis=1)
    first = next(i for i, step in enumerate(steps) if cp[0] in step)
    a, z = np.meshgrid(axes, axes, indexing="ij")
    anchor, step0 = a.ravel(), z.ravel()
    centre = planet_centre(anchor, step0, cp[0] in rings)
    columns = {first: step0}
    keep = centre > 0
    anchor, centre, columns[first] = anchor[keep], centre[keep], step0[keep]
    reach = np.sin(np.pi / planets) if planets >= 2 else np.inf
    for i, step in enumerate(steps):
        if i == first:
            continue
        low = np.full(centre.shape, lo)
        high = np.minimum(hi, np.ceil(centre * reach).astype(np.int64) - 2) if planets >= 2 \
            else np.full(centre.shape, hi)
        for k in step:
            if k in cp and k in rings:       # ring = centre + step
                low, high = np.maximum(low, lo - centre), np.minimum(high, hi - centre)
            elif k in cp:                    # sun = centre - step
                low, high = np.maximum(low, centre - hi), np.minimum(high, centre - lo)
        count = np.clip(high - low + 1, 0, None)
        rows = np.repeat(np.arange(centre.size), count)
        offsets = np.arange(rows.size) - np.repeat(np.cumsum(count) - count, count)
        new = low[rows] + offsets
        anchor, centre = anchor[rows], centre[rows]
        columns = {j: c[rows] for j, c in columns.items()}
        columns[i] = new
    return np.stack([columns[i] for i in range(len(steps))] + [anchor], axis=1)
