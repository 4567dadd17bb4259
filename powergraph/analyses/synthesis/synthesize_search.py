"""The tooth-number search: closed-form speeds of every coaxial link, evaluated over grids.

For each graph and each choice of fixed link, the Willis rows are solved once with sympy
(:func:`powergraph.analyses.formula.equations.body_speeds`, the kinematic half of
:func:`~powergraph.analyses.formula.derive_formulas`) with the meshes' Willis ratios
``i_k`` as symbols, and lambdified: one numpy call gives the speed of every coaxial link
for a whole array of tooth numbers, hence the ratio of every (input, output) choice. The
grid of a layout (:mod:`~powergraph.analyses.synthesis.teeth`) already meets coaxiality,
the neighbour condition and single-cluster assembly; the hits within the tolerance are
then checked for the conditions that join several planets (assembly of a planet-planet
cluster, the triangle of a double planet).

Examples
--------
>>> from powergraph.analyses.synthesis.synthesize_classics import CLASSICS
>>> speeds = speed_functions(CLASSICS["2K-H"])
>>> fixed, others, fn = speeds[0]       # ring 0 fixed; others: sun 1, carrier 3
>>> others
(1, 3)
>>> [float(w) for w in fn(-2.0, 4.0)]   # i_sun/planet = -2 (40/20), i_planet/ring = 4 (80/20)
[1.0, 0.1111111111111111]
"""
from __future__ import annotations

import copy
import functools
from collections import Counter
from typing import Any, Callable

import numpy as np

from powergraph.analyses.synthesis.graph import TrainGraph
from powergraph.analyses.synthesis.teeth import Layout, layouts, structure
from powergraph.gears.planetary import assembles, planets_meet, relative_turns
from powergraph.kinematics.elements import element_stencil
from powergraph.records import record

#: Grid points evaluated at once (bounds the memory of a search).
SUB_CHUNK = 1 << 14


@record
class Hits:
    """Tooth sets of one arrangement (graph, layout, fixed, input, output) within the
    tolerance and feasible: ``flat`` indices into the layout's grid."""

    graph: int
    layout: int
    fixed: int
    input: int
    output: int
    flat: np.ndarray


@functools.lru_cache(maxsize=256)
def idle_links(graph: TrainGraph) -> frozenset[int]:
    """Links that mesh exactly one gear and carry nothing (hold no gear pair, no
    coupling). Unless such a link takes an external torque (fixed, input or output),
    its torque balance about its own axis leaves its one mesh force zero: the mesh
    passes no power at every tooth set, so the train with it is no working train (the
    ranking leaves such sets out, :mod:`~powergraph.analyses.synthesis.rank`).

    >>> from powergraph.analyses.synthesis.synthesize_classics import CLASSICS
    >>> sorted(idle_links(CLASSICS["2K-H"]))           # ring 0 and sun 1
    [0, 1]
    >>> sorted(idle_links(CLASSICS["Wolfrom 3K"]))     # sun 1, rings 0 and 2
    [0, 1, 2]
    """
    meshes = Counter(x for u, v, _ in graph.gear_pairs for x in (u, v))
    carriers = {c for *_, c in graph.gear_pairs}
    coupled = {x for pair in graph.couplings for x in pair}
    return frozenset(n for n in range(graph.links)
                     if meshes[n] == 1 and n not in carriers and n not in coupled)


def working(graph: TrainGraph, fixed: int, input: int, output: int) -> bool:
    """Whether every :func:`idle_links` link of ``graph`` takes an external torque in
    the arrangement (``fixed`` held, ``input`` driven, ``output`` loaded)."""
    return idle_links(graph) <= {fixed, input, output}


def workable(graph: TrainGraph) -> bool:
    """Whether some arrangement of ``graph`` is :func:`working`: only coaxial links are
    fixed, driven or loaded, so every idle link must be coaxial, and three at most.

    >>> from powergraph.analyses.synthesis.synthesize_classics import CLASSICS
    >>> workable(CLASSICS["Wolfrom 3K"])
    True
    >>> idle_planet = TrainGraph(5, ((0, 1, 0), (0, 3, 0), (3, 2, 1), (3, 4, 2)),
    ...                          ((1, 2, 3), (2, 0, 3), (1, 4, 3)))
    >>> workable(idle_planet)              # planet 4 meshes sun 1 only
    False
    """
    st = structure(graph)
    idle = idle_links(graph)
    return st is not None and idle <= set(st.coaxial) and len(idle) <= 3


@functools.lru_cache(maxsize=64)
def speed_expressions(graph: TrainGraph) -> tuple[tuple[int, tuple[int, ...], tuple, tuple], ...]:
    """Per fixed coaxial link: ``(fixed, others, symbols, expressions)``, the sympy speeds
    of ``others`` (the other coaxial links) over the speed of ``others[0]`` in the meshes'
    Willis ratios ``symbols`` (``i_0 .. i_G-1``): the one symbolic derivation of the
    search, lambdified by :func:`speed_functions` and :func:`ratio_functions`."""
    import sympy as sp

    from powergraph.errors import PowerGraphError
    from powergraph.kinematics import elements_of
    from powergraph.model import model_from_dict

    from powergraph.analyses.synthesis.teeth import structure

    st = structure(graph)
    if st is None:
        return ()
    symbols = tuple(sp.Symbol(f"i_{k}") for k in range(len(graph.gear_pairs)))
    out = []
    for fixed in st.coaxial:
        others = tuple(c for c in st.coaxial if c != fixed)
        if len(others) < 2:
            continue
        try:
            model = model_from_dict(_ratio_document(graph, fixed, others))
            elements = elements_of(model)
            willis = {el.link: symbols[el.link] if el.kind == "mesh" else sp.Integer(1)
                      for el in elements}
            speeds = _speeds(model, elements, willis, model.body_of[f"L{others[0]}"])
        except PowerGraphError:
            continue
        expressions = tuple(speeds[model.body_of[f"L{c}"]] for c in others)
        out.append((fixed, others, symbols, expressions))
    return tuple(out)


@functools.lru_cache(maxsize=64)
def ratio_functions(graph: TrainGraph) -> tuple[tuple[int, tuple[tuple[int, int], ...],
                                                      Callable, bool], ...]:
    """Per fixed link: ``(fixed, pairs, fn, linear)``; for the ``j``-th pair ``(a, b)`` of
    coaxial links, ``fn(i_0, ..., i_G-1)[2j: 2j + 2]`` gives polynomials ``N, D`` with
    ``w_a / w_b = N / D`` in lowest terms, from the one symbolic derivation
    (:func:`speed_expressions`); ``linear`` whether all are multilinear (the bounds of
    :mod:`~powergraph.analyses.synthesis.synthesize_bound` need it). The exact test takes
    its ratios from them too: the speeds over a reference link lose every digit where that
    link stands still (two links held by one fixed), and their quotient is round-off.

    Lowest terms matter: over a common denominator, a factor shared by both speeds (a
    planet block whose two meshes have equal ratios turns as one body) makes the ratio
    ``0/0`` on every box where that factor vanishes, and no bound could settle them.

    >>> from powergraph.analyses.synthesis.synthesize_classics import CLASSICS
    >>> fixed, pairs, fn, _ = ratio_functions(CLASSICS["2K-H"])[0]  # ring 0 fixed
    >>> pairs, [float(v) for v in fn(-2.0, 4.0)]    # sun 1 / carrier 3 = 1 - i0 i1 = 9
    (((1, 3),), [9.0, 1.0])
    """
    import sympy as sp

    out = []
    for fixed, others, symbols, expressions in speed_expressions(graph):
        pairs, polys = [], []
        for x in range(len(others)):
            for y in range(x + 1, len(others)):
                n, d = sp.fraction(sp.cancel(sp.together(expressions[x] / expressions[y])))
                pairs.append((others[x], others[y]))
                polys += [sp.expand(n), sp.expand(d)]
        linear = all(sp.Poly(p, *symbols).degree(s) <= 1 for p in polys for s in symbols)
        out.append((fixed, tuple(pairs), sp.lambdify(symbols, polys, "numpy"), linear))
    return tuple(out)


@functools.lru_cache(maxsize=64)
def speed_functions(graph: TrainGraph) -> tuple[tuple[int, tuple[int, ...], Callable], ...]:
    """Per fixed coaxial link: ``(fixed, others, fn)`` where ``fn(i_0, ..., i_G-1)`` gives
    the speeds of ``others`` (the other coaxial links) over the speed of ``others[0]``."""
    import sympy as sp

    return tuple((fixed, others, sp.lambdify(symbols, list(expressions), "numpy"))
                 for fixed, others, symbols, expressions in speed_expressions(graph))


def _speeds(model: Any, elements: Any, willis: dict, input_body: str) -> dict:
    """Every body's speed over the input's, from the train's symbolic Willis rows (the
    formula package's one symbolic derivation)."""
    from powergraph.analyses.formula.systems import solve_linear, train_systems
    from powergraph.errors import ModelError

    given = {model.frame_body: 0, input_body: 1}
    systems = train_systems([b.id for b in model.bodies], [el.bodies for el in elements],
                            [willis[el.link] for el in elements], [1] * len(elements),
                            given, {}, [])
    det = 0
    if systems.speed_matrix.is_square:
        det, solution = solve_linear(systems.speed_matrix, systems.speed_rhs)
    if det == 0:
        raise ModelError("the speeds are not fixed by one input")
    return {**dict(zip(systems.free, solution)), **given}


def _ratio_document(graph: TrainGraph, fixed: int, others: tuple[int, ...]) -> dict:
    """The graph's model with each mesh's Willis ratio given (generic values)."""
    teeth = {(k, s): 20 for k in range(len(graph.gear_pairs)) for s in (0, 1)}
    doc = copy.deepcopy(graph.to_model_dict(frame=fixed, inputs=(others[0],),
                                            outputs=(others[1],), teeth=teeth))
    for component in doc["components"].values():
        component.pop("teeth", None)
    meshes = [link for link in doc["links"] if link["type"] == "mesh"]
    for k, link in enumerate(meshes):
        link["ratio"] = -1.37 - 0.71 * k if k % 2 == 0 else 2.93 + 0.53 * k
    return doc


@functools.lru_cache(maxsize=64)
def graph_layouts(graph: TrainGraph, teeth: tuple[int, int], planets: int) -> tuple[Layout, ...]:
    """:func:`~powergraph.analyses.synthesis.teeth.layouts`, cached per process."""
    return tuple(layouts(graph, teeth, planets))


def willis_ratios(layout: Layout, teeth: dict[tuple[int, int], np.ndarray]) -> list[np.ndarray]:
    """``i_k = (w_a - w_c)/(w_b - w_c)``: ``-z_b/z_a`` external, ``+z_b/z_a`` internal."""
    internal = layout.internal
    return [(1.0 if k in internal else -1.0) * teeth[(k, 1)] / teeth[(k, 0)]
            for k in range(len(layout.graph.gear_pairs))]


def exact_hits(graph: TrainGraph, layout: Layout, flat: np.ndarray, ratio: float,
               tolerance: float) -> dict[tuple[int, int, int], np.ndarray]:
    """The grid points ``flat`` of ``layout`` that give ``ratio`` within ``tolerance`` and
    meet the joint conditions, per arrangement ``(fixed, input, output)``: the exact test
    every candidate passes, ``|w_in / w_out / ratio - 1| <= tolerance``."""
    found: dict[tuple[int, int, int], list[np.ndarray]] = {}
    for low in range(0, flat.size, SUB_CHUNK):
        part = flat[low:low + SUB_CHUNK]
        i = willis_ratios(layout, layout.teeth(part))
        for fixed, pairs, fn, _ in ratio_functions(graph):
            with np.errstate(divide="ignore", invalid="ignore"):
                p = [np.broadcast_to(np.asarray(v, dtype=float), part.shape)
                     for v in fn(*i)]
                for j, (u, v) in enumerate(pairs):
                    for a, b, top, bottom in ((u, v, p[2 * j], p[2 * j + 1]),
                                              (v, u, p[2 * j + 1], p[2 * j])):
                        if not working(graph, fixed, a, b):
                            continue
                        hit = np.abs(top / bottom / ratio - 1.0) <= tolerance
                        if hit.any():
                            hit[hit] = drivable(layout.graph, [x[hit] for x in i], fixed, a)
                        if hit.any():
                            found.setdefault((fixed, a, b), []).append(part[hit])
    out = {}
    for key, parts in found.items():
        hits = np.concatenate(parts)
        hits = hits[joint_conditions(layout, hits)]
        if hits.size:
            out[key] = hits
    return out


#: A speed system is taken as singular where its determinant is below this fraction of
#: Hadamard's bound (the product of its rows' norms): tooth numbers are whole, so a
#: singular system is singular exactly and its computed determinant is round-off.
SINGULAR = 1e-9


def drivable(graph: TrainGraph, ratios: list[np.ndarray], fixed: int, given: int
             ) -> np.ndarray:
    """Where the train, ``fixed`` held, can be driven at link ``given``: its Willis rows
    ``(w_u - w_c) - i_k (w_v - w_c) = 0`` (the kinematic rows of
    :func:`~powergraph.kinematics.elements.element_stencil`; ``w_u = w_v`` per coupling)
    fix every other link's speed from ``w_given``: their matrix over the other links is
    regular.

    The closed forms of :func:`speed_expressions` are simplified, so at a tooth set where
    the rows are singular they may still give a finite ratio (a removable singularity):
    for instance two meshes on one carrier that force the input to stand still. Such a
    set is no train of that ratio; every hit passes this test.

    >>> from powergraph.analyses.synthesis.synthesize_classics import CLASSICS
    >>> ratios = [np.array([-2.0, -2.0]), np.array([4.0, 4.0])]   # sun 1, ring 0, carrier 3
    >>> drivable(CLASSICS["2K-H"], ratios, 0, 1).tolist()
    [True, True]
    """
    unknown = [n for n in range(graph.links) if n not in (fixed, given)]
    column = {n: j for j, n in enumerate(unknown)}
    points = ratios[0].shape[0] if ratios else 0
    rows = len(graph.gear_pairs) + len(graph.couplings)
    if rows != len(unknown):
        return np.zeros(points, dtype=bool)
    # each row is an element's kinematic row; a coupling is an element of ratio 1 (its
    # carrier's coefficient is 0, so any link stands for it)
    elements = [(u, v, c, ratios[k]) for k, (u, v, c) in enumerate(graph.gear_pairs)]
    elements += [(u, v, u, 1.0) for u, v in graph.couplings]
    matrix = np.zeros((points, rows, len(unknown)))
    for r, (u, v, c, ratio) in enumerate(elements):
        for link, coefficient in zip((u, v, c), element_stencil(ratio)):
            if link in column:
                matrix[:, r, column[link]] += coefficient
    bound = np.prod(np.linalg.norm(matrix, axis=2), axis=1)
    return np.abs(np.linalg.det(matrix)) > SINGULAR * bound


def joint_conditions(layout: Layout, flat: np.ndarray) -> np.ndarray:
    """Conditions joining planets meshed with each other: the triangle of their axes
    (``|D_a - D_b| < z_a + z_b < D_a + D_b`` in half-modules) and the cluster's assembly."""
    st, graph = layout.structure, layout.graph
    pp = [k for k, kind in enumerate(st.kinds) if kind == "pp"]
    ok = np.ones(flat.shape, dtype=bool)
    if not pp:
        return ok
    z = layout.teeth(flat)
    centres = layout.centres(flat)
    for k in pp:
        u, v, _ = graph.gear_pairs[k]
        if u in centres and v in centres:
            ok &= planets_meet(centres[u], centres[v], z[(k, 0)], z[(k, 1)])
    for cluster in _clusters(layout):
        coax, coefficients = _cluster_meshes(layout, cluster, z)
        phased = any(st.phased(p) for p in cluster)
        ok &= assembles(coax, coefficients, layout.planets, phased)
    return ok


def _clusters(layout: Layout) -> list[list[int]]:
    """Planet links joined by planet-planet meshes (only those with such a mesh)."""
    st, graph = layout.structure, layout.graph
    joined: dict[int, set[int]] = {}
    for k, (u, v, _) in enumerate(graph.gear_pairs):
        if st.kinds[k] == "pp":
            joined.setdefault(u, set()).add(v)
            joined.setdefault(v, set()).add(u)
    clusters, seen = [], set()
    for p in sorted(joined):
        if p in seen:
            continue
        group, stack = [], [p]
        while stack:
            q = stack.pop()
            if q not in seen:
                seen.add(q)
                group.append(q)
                stack.extend(joined[q])
        clusters.append(sorted(group))
    return clusters


def _cluster_meshes(layout: Layout, cluster: list[int], z: dict) -> tuple[list, list]:
    """Coaxial teeth and integer coefficients ``a_j`` of a planet cluster (see
    :func:`~powergraph.gears.planetary.assembles`): each planet's turn is
    ``num/den`` times the first one's (:func:`~powergraph.gears.planetary.relative_turns`)."""
    st, graph = layout.structure, layout.graph
    ones = np.ones_like(z[next(iter(z))])
    pp = [(u, v, z[(k, 0)], z[(k, 1)]) for k, (u, v, _) in enumerate(graph.gear_pairs)
          if st.kinds[k] == "pp"]
    turns = relative_turns(cluster[0], pp)
    num = {p: n * ones for p, (n, _) in turns.items()}
    den = {p: d * ones for p, (_, d) in turns.items()}
    common = np.prod([den[p] for p in cluster], axis=0)
    coax, coefficients = [], []
    internal = layout.internal
    for k, (u, v, _) in enumerate(graph.gear_pairs):
        if st.kinds[k] != "cp":
            continue
        side = st.coaxial_side[k]
        planet = (u, v)[1 - side]
        if planet not in cluster:
            continue
        sign = 1 if k in internal else -1
        coax.append(z[(k, side)])
        coefficients.append(sign * z[(k, 1 - side)] * num[planet] * (common // den[planet]))
    return coax, coefficients
