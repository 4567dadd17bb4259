"""The structural rules of planetary gear trains, as the enumeration applies them.

A train of ``N`` links is first an **axis structure**: the links and their common axes.
Each axis holds the set of links that turn about it (two or more); an axis of ``k`` links
stands for ``k - 1`` turning pairs (which coaxial link is journalled on which does not
matter, see docs/synthesis.md), and the links and axes form a tree (the incidence graph:
a link joined to each axis it turns about). That is the turning-pair spanning tree of the
literature, with every group of coaxial links gathered in one axis vertex.

A **gear pair** ``(u, v, carrier)`` may join two links ``u`` and ``v`` when the tree path
between them is ``u - A - carrier - B - v``: ``u`` and the carrier share axis ``A``, the
carrier and ``v`` share another axis ``B`` (the transfer-vertex rule of Buchsbaum &
Freudenstein 1970); the carrier is therefore unique. A set of ``G = N - 1 - dof`` gear
pairs is kept when no sub-chain is rigid: every set ``S`` of ``n >= 2`` links joined by
their own axes (``n - 1`` turning pairs) holds at most ``n - 2`` of the gear pairs, i.e.
has planar mobility ``3(n - 1) - 2(n - 1) - g >= 1``. For more than one degree of freedom
a link must also do something (mesh, or carry a mesh: no free-turning link), and the train
must not be **fractionated**: no link whose removal splits the others into parts joined
neither by an axis nor by a gear pair (two trains sharing one link, each with its own
freedom; Tsai & Lin 1989). Both hold by themselves for one degree of freedom.
"""
from __future__ import annotations

from itertools import combinations
from typing import Iterator

Axes = tuple[frozenset[int], ...]
GearPair = tuple[int, int, int]


def axis_structures(links: int) -> list[Axes]:
    """Every axis structure of ``links`` links, one per isomorphism class.

    Built from the non-isomorphic trees on the links, each edge set split into connected
    groups (the coaxial turning pairs); duplicates are removed by their canonical tree
    code (:func:`~powergraph.analyses.synthesis.canonical.structure_code`).

    Examples
    --------
    Three links: one axis of three links, or two axes sharing a link.

    >>> sorted(sorted(map(len, axes)) for axes in axis_structures(3))
    [[2, 2], [3]]
    """
    import networkx as nx

    from powergraph.analyses.synthesis.canonical import structure_code

    found: dict[str, Axes] = {}
    for tree in nx.nonisomorphic_trees(links):
        for axes in _coaxial_groupings(sorted(tree.edges())):
            found.setdefault(structure_code(links, axes), axes)
    return list(found.values())


def _coaxial_groupings(edges: list[tuple[int, int]]) -> Iterator[Axes]:
    """Partitions of a tree's edges into groups that each form a connected subtree."""
    def grow(i: int, groups: list[list[tuple[int, int]]]) -> Iterator[Axes]:
        if i == len(edges):
            sets = [frozenset(v for e in g for v in e) for g in groups]
            if all(len(s) == len(g) + 1 for s, g in zip(sets, groups)):  # forest => tree
                yield tuple(sets)
            return
        for group in groups:
            group.append(edges[i])
            yield from grow(i + 1, groups)
            group.pop()
        groups.append([edges[i]])
        yield from grow(i + 1, groups)
        groups.pop()

    yield from grow(0, [])


def gear_candidates(links: int, axes: Axes) -> list[GearPair]:
    """The gear pairs the transfer-vertex rule allows on an axis structure.

    Examples
    --------
    A carrier 0 holding links 1 and 2 on two axes: they may mesh, carried by 0.

    >>> gear_candidates(3, (frozenset({0, 1}), frozenset({0, 2})))
    [(1, 2, 0)]
    """
    on = [[a for a, s in enumerate(axes) if link in s] for link in range(links)]
    pairs = []
    for u, v in combinations(range(links), 2):
        if set(on[u]) & set(on[v]):
            continue                                    # coaxial links cannot mesh
        for a in on[u]:
            for b in on[v]:
                common = (axes[a] & axes[b]) - {u, v}
                if common:
                    pairs.append((u, v, next(iter(common))))
    return pairs


def subchains(links: int, axes: Axes) -> list[int]:
    """Bit masks of the sets of two or more links joined by their own axes.

    Examples
    --------
    >>> sorted(subchains(3, (frozenset({0, 1}), frozenset({0, 2}))))
    [3, 5, 7]
    """
    masks = [sum(1 << x for x in axis) for axis in axes]
    found = []
    for mask in range(1, 1 << links):
        n = mask.bit_count()
        if n >= 2 and sum(max(0, (mask & m).bit_count() - 1) for m in masks) == n - 1:
            found.append(mask)
    return found


def gear_sets(links: int, axes: Axes, dof: int = 1, fractionated: bool = False
              ) -> Iterator[tuple[GearPair, ...]]:
    """Every set of ``links - 1 - dof`` candidate gear pairs with no rigid sub-chain.

    ``fractionated=True`` keeps the fractionated trains of two or more DOF.
    Depth-first over the candidates, counting the gear pairs inside each sub-chain and
    cutting a branch as soon as one holds ``n - 1`` of them.

    Examples
    --------
    The simple planetary: sun 1 and ring 2 coaxial with carrier 0, planet 3 on 0.

    >>> list(gear_sets(4, (frozenset({0, 1, 2}), frozenset({0, 3}))))
    [((1, 3, 0), (2, 3, 0))]
    """
    wanted = links - 1 - dof
    candidates = gear_candidates(links, axes)
    if wanted < 0 or wanted > len(candidates):
        return
    chains = [m for m in subchains(links, axes) if m != (1 << links) - 1]
    room = [m.bit_count() - 2 for m in chains]
    inside = [[c for c, m in enumerate(chains) if (m >> u) & 1 and (m >> v) & 1]
              for u, v, _ in candidates]
    counts = [0] * len(chains)
    chosen: list[int] = []

    def extend(start: int) -> Iterator[tuple[GearPair, ...]]:
        if len(chosen) == wanted:
            gears = tuple(candidates[i] for i in chosen)
            if dof == 1 or (_all_links_work(links, axes, gears)
                            and (fractionated or not is_fractionated(links, axes, gears))):
                yield gears
            return
        for i in range(start, len(candidates) - (wanted - len(chosen)) + 1):
            if any(counts[c] >= room[c] for c in inside[i]):
                continue
            for c in inside[i]:
                counts[c] += 1
            chosen.append(i)
            yield from extend(i + 1)
            chosen.pop()
            for c in inside[i]:
                counts[c] -= 1

    yield from extend(0)


def _all_links_work(links: int, axes: Axes, gears: tuple[GearPair, ...]) -> bool:
    """No free-turning link: each link meshes or carries a mesh (automatic for 1 DOF)."""
    busy = {x for pair in gears for x in pair}
    return len(busy) == links


def is_fractionated(links: int, axes: Axes, gears: tuple[GearPair, ...]) -> bool:
    """Whether one link joins two parts that share neither an axis nor a gear pair.

    Examples
    --------
    Two gear pairs on a common carrier 0, one of them on a second carrier 1 turning on 0:

    >>> axes = (frozenset({0, 3}), frozenset({0, 4}), frozenset({0, 1}), frozenset({1, 2}))
    >>> is_fractionated(5, axes, ((0, 2, 1), (3, 4, 0)))
    True
    """
    for cut in range(links):
        rest = [n for n in range(links) if n != cut]
        part = {n: n for n in rest}

        def find(x: int) -> int:
            while part[x] != x:
                x = part[x]
            return x

        joins = [(u, v) for u, v, _ in gears]
        joins += [(x, y) for axis in axes for x in axis for y in axis]
        for x, y in joins:
            if cut not in (x, y):
                part[find(x)] = find(y)
        if len({find(n) for n in rest}) > 1:
            return True
    return False
