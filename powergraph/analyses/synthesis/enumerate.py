"""Enumerate the non-isomorphic graphs of planetary gear trains (docs/synthesis.md).

:func:`enumerate_trains` lists every displacement graph (d-graph: the actual train, with
its common axes) of ``links`` links and ``dof`` degrees of freedom, and counts their
rotation graphs (r-graphs: which links mesh, carried by which link). The rules
(:mod:`~powergraph.analyses.synthesis.rules`): turning pairs form a spanning tree, each
gear pair has one carrier holding its two gears on two different axes, no sub-chain is
rigid. Isomorphism (:mod:`~powergraph.analyses.synthesis.canonical`) ignores link numbers
and axis labels, and treats coaxial links as one axis whatever their bearing arrangement.
For one degree of freedom this reproduces Yang & Ding (2019)'s counts.
"""
from __future__ import annotations

from typing import Any

from powergraph.analyses.synthesis.graph import TrainGraph
from powergraph.errors import UsageError
from powergraph.display import Displayed
from powergraph.records import record

#: Published counts ``{dof: {links: (r-graphs, d-graphs)}}``: Yang W. & Ding H., "The
#: complete set of one-degree-of-freedom planetary gear trains with up to nine links",
#: Journal of Mechanical Design 141(4), 2019 (abstract: 6 to 9 links).
PUBLISHED = {1: {6: (27, 81), 7: (152, 647), 8: (1070, 6360), 9: (8654, 71837)}}
#: Largest number of links :func:`enumerate_trains` accepts (9 links: slow, see docs).
MAX_LINKS = 9


@record(repr=False)
class EnumerationResult(Displayed):
    """The displacement graphs of one size, with the rotation graph each one has.

    Attributes
    ----------
    links, dof : the size asked for
    graphs : one :class:`TrainGraph` per displacement graph (non-isomorphic trains), those
        with the same rotation graph together
    rotation_index : for each graph, the number of its rotation graph (0, 1, ...)
    """

    links: int
    dof: int
    graphs: tuple[TrainGraph, ...]
    rotation_index: tuple[int, ...]

    def _summary(self) -> str:
        return (f"{self.links} links, {self.dof} DOF: {self.rotation_graphs} r-graphs, "
                f"{self.displacement_graphs} d-graphs")

    def _records(self) -> list[dict[str, Any]]:
        return [{"name": g.name, "r_graph": r,
                 "axes": " ".join("{" + ",".join(map(str, sorted(a))) + "}"
                                  for a in axes_of(g)),
                 "gears": " ".join(f"{u}-{v}/{c}" for u, v, c in g.gear_pairs)}
                for g, r in zip(self.graphs, self.rotation_index)]


    @property
    def rotation_graphs(self) -> int:
        """The number of non-isomorphic rotation graphs."""
        return len(set(self.rotation_index))

    @property
    def displacement_graphs(self) -> int:
        """The number of non-isomorphic displacement graphs (trains)."""
        return len(self.graphs)

    def find(self, train: TrainGraph) -> int | None:
        """The index of the graph isomorphic to ``train`` (as a d-graph), or None."""
        from powergraph.analyses.synthesis.canonical import same, wl_hash

        if train.links != self.links or train.dof != self.dof:
            return None
        target = d_graph(train)
        key = wl_hash(target)
        for i, graph in enumerate(self.graphs):
            other = d_graph(graph)
            if wl_hash(other) == key and same(target, other):
                return i
        return None

    def to_dict(self) -> dict[str, Any]:
        """``{links, dof, rotation_graphs, displacement_graphs, graphs: [...]}``; each graph
        ``{name, rotation_graph (numbered from 1, as in the name), axes, turning_pairs,
        gear_pairs}``."""
        return {"links": self.links, "dof": self.dof,
                "rotation_graphs": self.rotation_graphs,
                "displacement_graphs": self.displacement_graphs,
                "graphs": [{"name": g.name, "rotation_graph": r + 1,
                            "axes": [sorted(a) for a in axes_of(g)],
                            "turning_pairs": [list(t) for t in g.turning_pairs],
                            "gear_pairs": [list(p) for p in g.gear_pairs]}
                           for g, r in zip(self.graphs, self.rotation_index)]}

    def text_report(self) -> str:
        """Counts against the published ones, then each graph on one line."""
        published = PUBLISHED.get(self.dof, {}).get(self.links)
        lines = [f"{self.links}-link {self.dof}-DOF planetary gear trains",
                 f"rotation graphs (r-graphs)      {self.rotation_graphs}"
                 + (f"   (published: {published[0]})" if published else ""),
                 f"displacement graphs (d-graphs)  {self.displacement_graphs}"
                 + (f"   (published: {published[1]})" if published else "")]
        if published:
            lines.append("published: Yang & Ding (2019), J. Mech. Des. 141(4)")
        lines.append("")
        for g, r in zip(self.graphs, self.rotation_index):
            axes = " ".join("{" + ",".join(map(str, sorted(a))) + "}" for a in axes_of(g))
            gears = " ".join(f"{u}-{v}/{c}" for u, v, c in g.gear_pairs)
            lines.append(f"{g.name}: axes {axes}; gears (u-v/carrier) {gears}")
        return "\n".join(lines)

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """A sheet of the displacement graphs (:func:`powergraph.plot.synthesis.plot_graphs`)."""
        from powergraph.plot.synthesis import plot_graphs

        return plot_graphs(self.graphs, ax=ax, **kwargs)


def enumerate_trains(links: int, dof: int = 1, fractionated: bool = False) -> EnumerationResult:
    """Every non-isomorphic planetary gear train graph of ``links`` links and ``dof`` DOF.

    Parameters
    ----------
    links : number of links (frame included), 3 to :data:`MAX_LINKS`
    dof : degrees of freedom, ``1 <= dof <= links - 2``; ``links - 1 - dof`` gear pairs
    fractionated : also keep fractionated trains (two trains sharing one link; only
        possible with two or more DOF)

    Returns
    -------
    EnumerationResult

    Examples
    --------
    Four links: the simple planetary, the ordinary three-gear train (same r-graph, other
    axes) and the train whose two planets nest:

    >>> result = enumerate_trains(4)
    >>> result.rotation_graphs, result.displacement_graphs
    (2, 3)
    """
    from powergraph.analyses.synthesis.canonical import (automorphisms, classify, images,
                                                         rotation_graph)
    from powergraph.analyses.synthesis.rules import axis_structures, gear_sets

    _check(links, dof)
    trains = []
    for axes in axis_structures(links):
        group, seen = automorphisms(links, axes), set()
        for gears in gear_sets(links, axes, dof, fractionated):
            if tuple(sorted(gears)) not in seen:      # a new orbit: keep it, mark its images
                seen.update(images(gears, group))
                trains.append((axes, gears))
    _, rotation = classify([g for _, g in trains], lambda g: rotation_graph(links, g))
    order = sorted(range(len(trains)), key=lambda i: (rotation[i], i))  # grouped by r-graph
    graphs = tuple(_train_graph(links, *trains[i], f"{links}-link d-graph {k + 1} "
                                f"(r-graph {rotation[i] + 1})") for k, i in enumerate(order))
    return EnumerationResult(links=links, dof=dof, graphs=graphs,
                             rotation_index=tuple(rotation[i] for i in order))


def _check(links: Any, dof: Any) -> None:
    for name, value in (("links", links), ("dof", dof)):
        if isinstance(value, bool) or not isinstance(value, int):
            raise UsageError(f"{name} must be an integer, got {value!r}")
    if not 3 <= links <= MAX_LINKS:
        raise UsageError(f"links must be between 3 and {MAX_LINKS}, got {links}")
    if not 1 <= dof <= links - 2:
        raise UsageError(f"dof must be between 1 and links - 2 = {links - 2}, got {dof}")


def axes_of(train: TrainGraph) -> list[frozenset[int]]:
    """The common axes of a train: the sets of links its turning pairs join, per label.

    Examples
    --------
    >>> g = TrainGraph(4, ((0, 1, 0), (0, 3, 0), (3, 2, 1)), ((1, 2, 3),))
    >>> axes_of(g)
    [frozenset({0, 1, 3}), frozenset({2, 3})]
    """
    import networkx as nx

    by_label: dict[int, nx.Graph] = {}
    for u, v, axis in train.turning_pairs:
        by_label.setdefault(axis, nx.Graph()).add_edge(u, v)
    return [frozenset(part) for label in sorted(by_label)
            for part in nx.connected_components(by_label[label])]


def d_graph(train: TrainGraph) -> Any:
    """The displacement graph of a :class:`TrainGraph` (for the matcher)."""
    from powergraph.analyses.synthesis.canonical import displacement_graph

    return displacement_graph(train.links, axes_of(train), train.gear_pairs)


def r_graph(train: TrainGraph) -> Any:
    """The rotation graph of a :class:`TrainGraph` (for the matcher)."""
    from powergraph.analyses.synthesis.canonical import rotation_graph

    return rotation_graph(train.links, train.gear_pairs)


def _train_graph(links: int, axes: tuple[frozenset[int], ...], gears: tuple, name: str
                 ) -> TrainGraph:
    """A TrainGraph with, on each axis, the bearings gear-to-carrier first (a spanning tree)."""
    turning = []
    for label, axis in enumerate(axes):
        root = {x: x for x in axis}

        def find(x: int) -> int:
            while root[x] != x:
                x = root[x]
            return x

        wanted = [(u, c) for u, v, c in gears for u in (u, v) if u in axis and c in axis]
        rest = [(min(axis), x) for x in sorted(axis)]
        for u, v in wanted + rest:
            if find(u) != find(v):
                root[find(u)] = find(v)
                turning.append((min(u, v), max(u, v), label))
    return TrainGraph(links=links, turning_pairs=tuple(turning), gear_pairs=tuple(gears),
                      name=name)
